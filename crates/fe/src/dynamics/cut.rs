//! Where the line is cut for two threads (issue 48): the cut itself ([`Split`]), what one thread
//! steps ([`Scope`]: the whole line, or one part and the other part's node next to it) and where
//! a thread that steps one part meets the other ([`Lane`]). The Workspace holds all three; the
//! [`super::Pair`] (`pair.rs`) makes and drives them; neither file imports the other's types but
//! through this one.

use std::ops::Range;

use crate::assembly::Part;
use crate::partner::Seat;
use crate::wave_sampling::{KinematicsGrid, Sample};

use super::*;

/// The line cut in two parts where the band's two ends meet ([`Assembler::split_at_node`]): the
/// first owns the nodes `0..=k`, the second the others. The residual's squared norm is the sum of
/// the two parts' in that order, whether one thread steps the line or two (issue 48), so that
/// both give the same bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Split {
    /// The first part's last node.
    pub k: usize,
    /// The first of the free runs that belong to the second part (the runs are cut at its first
    /// dof).
    pub runs: usize,
}

/// What one thread steps: the whole line, or one of its two parts ([`Split`]) and the other
/// part's node next to it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Scope {
    /// The elements it computes and the nodes it owns.
    pub part: Part,
    /// The free runs of its own nodes (the residual's equations it takes).
    pub own_runs: Range<usize>,
    /// The free runs of its own nodes and of the halo (where it updates the iterate).
    pub reach_runs: Range<usize>,
    /// The dofs of its own nodes and of the halo (where it predicts).
    pub reach_dofs: Range<usize>,
    /// Its own equations.
    pub own_eqs: Range<usize>,
}

impl Scope {
    /// The whole line, `runs` free runs.
    pub fn whole(line: &LineModel, runs: usize) -> Self {
        Self {
            part: Part::whole(line),
            own_runs: 0..runs,
            reach_runs: 0..runs,
            reach_dofs: 0..3 * line.nodes(),
            own_eqs: 0..line.n_eq,
        }
    }

    /// Side `side` (0: the first part) of the line cut at `split`.
    pub(super) fn side(
        line: &LineModel,
        split: Split,
        runs: &[(usize, usize, usize)],
        side: usize,
    ) -> Self {
        let (k, n) = (split.k, line.nodes());
        let [first, second] = Part::halves(line, k);
        // The second part's first run starts at its first equation (the runs are cut there).
        let p = runs[split.runs].1;
        let below = |g: usize| runs.partition_point(|r| r.0 < g);
        if side == 0 {
            Self {
                part: first,
                own_runs: 0..split.runs,
                reach_runs: 0..below(3 * (k + 2)),
                reach_dofs: 0..3 * (k + 2),
                own_eqs: 0..p,
            }
        } else {
            Self {
                part: second,
                own_runs: split.runs..runs.len(),
                reach_runs: below(3 * k)..runs.len(),
                reach_dofs: 3 * k..3 * n,
                own_eqs: p..line.n_eq,
            }
        }
    }

    /// Its own nodes, and their dofs.
    pub fn own(&self) -> (Range<usize>, Range<usize>) {
        let nodes = self.part.nodes.clone();
        let dofs = 3 * nodes.start..3 * nodes.end;
        (nodes, dofs)
    }
}

/// Where a thread that steps one part meets the other.
#[derive(Debug)]
pub(super) struct Lane {
    /// 0: the first part; 1: the second.
    pub side: usize,
    pub(super) seat: Seat,
    /// The equations whose corrections it sends after a solve (side 1: those of the first
    /// part's halo node, `k + 1`), and those it receives (side 0: the same).
    pub(super) send: Range<usize>,
    pub(super) receive: Range<usize>,
    /// The first part's nodes whose wave samples the second thread takes and hands to the first
    /// (empty without sampled waves).
    pub lent: Range<usize>,
    /// The lent samples as numbers, seven a sample ([`Lane::lend_samples`]).
    pub(super) mail: Vec<f64>,
}

/// The numbers a sample is sent as: whether there is one (1 or 0), then its velocity,
/// acceleration and jerk.
pub(super) const SAMPLE_NUMBERS: usize = 7;

impl Lane {
    /// The meeting before the threads take new wave samples, where the first thread hands the
    /// second the committed State (`u`, `v`, `a`) of the `lent` nodes, which only the first
    /// commits: the second keeps it in its mail ([`Lane::lent_state`]) while it samples them. So
    /// it samples from the State of the sub-step that needs the samples, also after a cut.
    /// Nothing without lent nodes. Allocates nothing.
    pub(super) fn lend_state(&mut self, state: &DynState) {
        let dofs = 3 * self.lent.start..3 * self.lent.end;
        let len = dofs.len();
        if len == 0 {
            return;
        }
        if self.side == 1 {
            self.seat.exchange(&[], &mut self.mail[..3 * len]);
            return;
        }
        for (to, from) in self
            .mail
            .chunks_exact_mut(len)
            .zip([&state.u, &state.v, &state.a])
        {
            to.copy_from_slice(&from[dofs.clone()]);
        }
        self.seat.exchange(&self.mail[..3 * len], &mut []);
    }

    /// On the second thread after [`Lane::lend_state`], at a dof `j` of a lent node: its
    /// committed `(u, v, a)`. `None` at any other dof. (Not on the first thread: its mail holds
    /// other numbers.)
    #[inline]
    pub(super) fn lent_state(&self, j: usize) -> Option<(f64, f64, f64)> {
        let first = 3 * self.lent.start;
        let len = 3 * self.lent.len();
        let k = j.checked_sub(first).filter(|&k| k < len)?;
        Some((self.mail[k], self.mail[len + k], self.mail[2 * len + k]))
    }

    /// The meeting where the second thread hands the first the samples it took at the `lent`
    /// nodes (both grid times), after both have sampled: the first writes them into `grid`.
    /// Nothing without lent nodes. Allocates nothing.
    pub(super) fn lend_samples(&mut self, grid: &mut KinematicsGrid) {
        let lent = self.lent.clone();
        if lent.is_empty() {
            return;
        }
        if self.side == 1 {
            let numbers = grid.samples.iter().flat_map(|s| &s[lent.clone()]);
            for (to, s) in self.mail.chunks_exact_mut(SAMPLE_NUMBERS).zip(numbers) {
                let Some(s) = s else {
                    to.fill(0.0);
                    continue;
                };
                to[0] = 1.0;
                to[1..3].copy_from_slice(&s.v);
                to[3..5].copy_from_slice(&s.a);
                to[5..7].copy_from_slice(&s.j);
            }
            self.seat.exchange(&self.mail, &mut []);
            return;
        }
        self.seat.exchange(&[], &mut self.mail);
        let samples = grid.samples.iter_mut().flat_map(|s| &mut s[lent.clone()]);
        for (from, s) in self.mail.chunks_exact(SAMPLE_NUMBERS).zip(samples) {
            *s = (from[0] == 1.0).then(|| Sample {
                v: [from[1], from[2]],
                a: [from[3], from[4]],
                j: [from[5], from[6]],
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::partner::seats;

    /// The lent samples reach the first thread as the second took them, a node out of the water
    /// (no sample) included, at both grid times, and no other node's sample changes.
    #[test]
    fn lent_samples_arrive_as_they_were_taken() {
        let (first, second) = seats(2 * SAMPLE_NUMBERS * 3);
        let lane = |side, seat| Lane {
            side,
            seat,
            send: 0..0,
            receive: 0..0,
            lent: 2..5,
            mail: vec![0.0; 2 * SAMPLE_NUMBERS * 3],
        };
        let sample = |i: usize, t: usize| {
            let x = (10 * i + t) as f64;
            Some(Sample {
                v: [x, x + 0.1],
                a: [x + 0.2, x + 0.3],
                j: [x + 0.4, x + 0.5],
            })
        };
        let mut taken = KinematicsGrid {
            index: 7,
            samples: [
                (0..6).map(|i| sample(i, 0)).collect(),
                (0..6).map(|i| sample(i, 1)).collect(),
            ],
        };
        taken.samples[1][3] = None;
        let mut got = KinematicsGrid {
            index: 7,
            samples: [vec![None; 6], vec![sample(9, 9); 6]],
        };
        std::thread::scope(|s| {
            let mut l1 = lane(1, second);
            let sent = &mut taken;
            s.spawn(move || l1.lend_samples(sent));
            lane(0, first).lend_samples(&mut got);
        });
        for t in 0..2 {
            for i in 0..6 {
                let want = match (i, t) {
                    (2..5, _) => taken.samples[t][i],
                    (_, 0) => None,
                    _ => sample(9, 9),
                };
                assert_eq!(got.samples[t][i], want, "node {i}, time {t}");
            }
        }
    }
}
