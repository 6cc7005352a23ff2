//! The envelopes lent to the waits of the pair that steps the line ([`crate::run::lend`]): split at
//! a node into two halves, each with its nodes' range graphs, `1/EI` and sections, and handed each
//! step's moment, tension, penetration, seabed force and height at its nodes; each thread of the
//! pair takes its half of the step before into the range graphs while it waits. Each node's least,
//! greatest and summed values take the same numbers in the same order, through the same kernels
//! ([`take_range`], [`wall_stresses`]): the same range graphs to the bit.

use std::ops::Range as Nodes;

use super::{take_range, Envelopes, Range};
use crate::checks::fatigue::stress::{Fibre, PipeSection};
use crate::run::lend::{Halves, Piece};
use std::sync::Arc;

/// Scratch space: not part of the envelopes' value (any two are equal).
#[derive(Debug, Clone)]
pub(super) struct Scratch<T>(pub(super) T);

impl<T> PartialEq for Scratch<T> {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// The envelopes' halves lent to a pair's waits (`observe/lent.rs`), if they are: how the work is
/// done, not part of the envelopes' value (any two are equal).
#[derive(Debug, Clone, Default)]
pub(super) struct Lending(pub(super) Option<Arc<Halves<Half>>>);

impl PartialEq for Lending {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// Nodes whose curvature and wall stresses are computed at a time (on the stack).
const BLOCK: usize = 16;

/// A half of the envelopes (see the module docs).
#[derive(Debug)]
pub(super) struct Half {
    /// In [`Envelopes::ranges_mut`]'s order: moment, tension, curvature, penetration, seabed
    /// force, then wall tension and the two fibre stresses where the section is known.
    ranges: Vec<Range>,
    inv_ei: Vec<f64>,
    section: Option<PipeSection>,
    /// A line of sections: each node's (empty: `section` at every node).
    node_sections: Vec<PipeSection>,
}

impl Range {
    /// The range at the nodes `at..`, this one keeping the nodes before.
    fn split_off(&mut self, at: usize) -> Range {
        Range {
            min: self.min.split_off(at),
            max: self.max.split_off(at),
            sum: self.sum.split_off(at),
        }
    }

    /// `second` appended (the nodes after this one's).
    fn append(&mut self, mut second: Range) {
        self.min.append(&mut second.min);
        self.max.append(&mut second.max);
        self.sum.append(&mut second.sum);
    }

    /// Takes one step's values `v` at the nodes `nodes` ([`take_range`]).
    fn take_at(&mut self, nodes: Nodes<usize>, v: &[f64]) {
        let (min, max, sum) = (
            &mut self.min[nodes.clone()],
            &mut self.max[nodes.clone()],
            &mut self.sum[nodes],
        );
        take_range(min, max, sum, v);
    }
}

impl Envelopes {
    /// The two halves, of the nodes `..at` and `at..`; the envelopes keep none of their nodes
    /// until [`Envelopes::join`].
    pub(super) fn split(&mut self, at: usize) -> [Half; 2] {
        let (section, sections) = (self.section, &mut self.node_sections);
        let second_sections = if sections.is_empty() {
            Vec::new()
        } else {
            sections.split_off(at)
        };
        let mut first = Vec::new();
        let mut second = Vec::new();
        for r in self.ranges_mut() {
            second.push(r.split_off(at));
            first.push(std::mem::replace(r, Range::new(0)));
        }
        let mut inv_ei = std::mem::take(&mut self.inv_ei);
        let second_inv_ei = inv_ei.split_off(at);
        [
            Half {
                ranges: first,
                inv_ei,
                section,
                node_sections: std::mem::take(&mut self.node_sections),
            },
            Half {
                ranges: second,
                inv_ei: second_inv_ei,
                section,
                node_sections: second_sections,
            },
        ]
    }

    /// The halves of [`Envelopes::split`] back, whole.
    pub(super) fn join(&mut self, [a, b]: [Half; 2]) {
        for ((r, ra), rb) in self.ranges_mut().into_iter().zip(a.ranges).zip(b.ranges) {
            *r = ra;
            r.append(rb);
        }
        self.inv_ei = [a.inv_ei, b.inv_ei].concat();
        self.node_sections = [a.node_sections, b.node_sections].concat();
    }
}

impl Piece for Half {
    fn nodes(&self) -> usize {
        self.inv_ei.len()
    }

    /// `step`: the moment, tension, penetration, seabed force and (with the section) height at
    /// the half's nodes.
    fn take(&mut self, step: &[&[f64]], nodes: Nodes<usize>) {
        let at = |k: usize| &step[k][nodes.clone()];
        let (m, t) = (at(0), at(1));
        let r = &mut self.ranges;
        r[0].take_at(nodes.clone(), m);
        r[1].take_at(nodes.clone(), t);
        r[3].take_at(nodes.clone(), at(2));
        r[4].take_at(nodes.clone(), at(3));
        let outer = Fibre::Outer;
        // The height only with the section (then handed).
        let z = step.get(4).map_or(&[][..], |z| &z[nodes.clone()]);
        for start in nodes.clone().step_by(BLOCK) {
            let block = start..(start + BLOCK).min(nodes.end);
            let len = block.len();
            let local = |i: usize| i - nodes.start;
            let mut k = [0.0; BLOCK];
            for (j, i) in block.clone().enumerate() {
                k[j] = m[local(i)] * self.inv_ei[i];
            }
            r[2].take_at(block.clone(), &k[..len]);
            let Some(sec) = &self.section else {
                continue;
            };
            let (mut w, mut top, mut bottom) = ([0.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK]);
            for (j, i) in block.clone().enumerate() {
                let sec = self.node_sections.get(i).unwrap_or(sec);
                let (te, zi) = (t[local(i)], z[local(i)]);
                w[j] = te + sec.wall_minus_effective(zi);
                (top[j], bottom[j]) = sec.fibre_stresses(outer, te, m[local(i)], zi);
            }
            r[5].take_at(block.clone(), &w[..len]);
            r[6].take_at(block.clone(), &top[..len]);
            r[7].take_at(block, &bottom[..len]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::observe::Observer;
    use catena_fe::assembly::LineResults;

    fn section(wall: f64) -> PipeSection {
        PipeSection {
            od: 0.5,
            wall,
            contents_density: 800.0,
            internal_pressure: 1e6,
            water_density: 1025.0,
            gravity: 9.80665,
            water_depth: 100.0,
        }
    }

    /// The envelopes lent to a pair's waits take every step to the same bits as at once, whoever
    /// takes each piece: two threads doing the two halves' chores while the steps are handed over
    /// (racing the observer), none at all (each step taken when the next is handed over), and
    /// saved halfway and restored into a third. 37 nodes of two sections (each node's own, the
    /// wall stresses too), `EI` varying along the line; 1000 steps of pseudo-random moment,
    /// tension, penetration, seabed force and height. Every range graph's least, greatest and
    /// summed values equal to the bit, and the samples.
    #[test]
    fn lent_envelopes_take_the_same_bits() {
        let n = 37;
        let ei: Vec<f64> = (0..n - 1).map(|e| 1e7 * (1.0 + 0.1 * e as f64)).collect();
        let sections: Vec<PipeSection> = (0..n)
            .map(|i| section(if i % 3 == 0 { 0.025 } else { 0.04 }))
            .collect();
        let new = || Envelopes::with_sections(&ei, Some(section(0.025)), sections.clone());
        let mut here = new();
        let (mut chored, mut alone, mut restored) = (
            new().lend_to_pair(),
            new().lend_to_pair(),
            new().lend_to_pair(),
        );
        assert!(here.chores().is_none(), "only lent envelopes leave chores");
        let chores = chored.chores().expect("chores");
        let mut r = LineResults {
            moment: vec![0.0; n],
            tension: vec![0.0; n],
            penetration: vec![0.0; n],
            seabed_force: vec![0.0; n],
            z: vec![0.0; n],
            ..LineResults::default()
        };
        let mut next = crate::run::lend::xorshift(0x9e37_79b9_7f4a_7c15u64);
        let pieces = crate::run::lend::racing_chores(&chores, || {
            for k in 0..1000 {
                for i in 0..n {
                    r.moment[i] = 1e5 * next();
                    r.tension[i] = 2e5 + 1e5 * next();
                    r.penetration[i] = 0.1 * next();
                    r.seabed_force[i] = 1e3 * next();
                    r.z[i] = 50.0 + 10.0 * next();
                }
                for e in [&mut here, &mut chored, &mut alone] {
                    e.take_step(&r);
                }
                if k == 300 {
                    let saved = alone.save().expect("saved");
                    restored.restore(&saved).expect("restored");
                } else if k > 300 {
                    restored.take_step(&r);
                }
                if k % 7 == 0 {
                    std::thread::sleep(std::time::Duration::from_micros(50));
                }
            }
        });
        assert!(pieces > 100, "the chores were not done");
        let bits = |e: &mut Envelopes| -> Vec<Vec<u64>> {
            e.drain();
            e.ranges()
                .iter()
                .flat_map(|(_, r)| [&r.min, &r.max, &r.sum])
                .map(|v| v.iter().map(|x| x.to_bits()).collect())
                .collect()
        };
        let want = bits(&mut here);
        assert_eq!(want.len(), 24, "eight range graphs");
        assert!(want.iter().all(|v| v.len() == n));
        for (what, e) in [
            ("in the chores", &mut chored),
            ("no chores done", &mut alone),
            ("saved, restored and taken on", &mut restored),
        ] {
            assert_eq!(bits(e), want, "{what}");
            assert_eq!(e.samples, here.samples, "{what}");
        }
    }
}
