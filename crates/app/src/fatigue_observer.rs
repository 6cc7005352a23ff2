//! Fatigue as an observer of a run: at every step from `start`, the stresses at the top and bottom of
//! each chosen fibre at every node go into a streaming rainflow counter, and every counted cycle's
//! Miner damage is added at once (`n/N(SCF·t_corr·Δσ)`); at the end the residue counts as half
//! cycles. No second pass over the output, and nothing of the history is kept.

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::error::AppError;
use crate::fatigue::rainflow::{Cycle, Rainflow};
use crate::fatigue::sn::SnCurve;
use crate::fatigue::stress::Fibre;
use crate::fatigue::FatigueSpec;
use crate::observe::{Control, Observer, RunContext, StepView, Stop};

/// The fatigue observer: damage per node, fibre and side (top, bottom).
#[derive(Debug, Clone, PartialEq)]
pub struct Fatigue {
    /// The specification.
    pub spec: FatigueSpec,
    /// The factor on every stress range of the specification's own section and curve: SCF ×
    /// thickness correction (a line of sections has one per node, `node_factor`).
    pub factor: f64,
    /// Each node's factor on its stress ranges (its type's SCF × its wall's thickness correction).
    pub node_factor: Vec<f64>,
    /// Each node's S-N curve.
    pub node_curve: Vec<SnCurve>,
    counters: Vec<Rainflow>,
    /// Miner damage, indexed `(node·fibres + fibre)·2 + side` (side 0 top, 1 bottom).
    pub damage: Vec<f64>,
    /// First and last time counted, s.
    pub span: (Option<f64>, f64),
    n: usize,
}

#[derive(Serialize, Deserialize)]
struct Saved {
    counters: Vec<Rainflow>,
    damage: Vec<f64>,
    first: Option<f64>,
    last: f64,
}

impl Fatigue {
    /// The observer for `n` nodes (each with the specification's section and curve, or, for a line
    /// of sections, its own: [`FatigueSpec::nodes`]).
    pub fn new(spec: FatigueSpec, n: usize) -> Self {
        let factor = spec.scf * spec.curve.thickness_factor(spec.section.wall);
        let m = n * spec.fibres.len() * 2;
        let node = |i: usize| {
            spec.nodes
                .get(i)
                .copied()
                .unwrap_or((spec.section, spec.curve, spec.scf))
        };
        let node_factor = (0..n)
            .map(|i| {
                let (sec, curve, scf) = node(i);
                scf * curve.thickness_factor(sec.wall)
            })
            .collect();
        let node_curve = (0..n).map(|i| node(i).1).collect();
        Self {
            spec,
            factor,
            node_factor,
            node_curve,
            counters: vec![Rainflow::new(); m],
            damage: vec![0.0; m],
            span: (None, 0.0),
            n,
        }
    }

    fn take(&mut self, s: &StepView<'_>) {
        if s.t < self.spec.start - 1e-9 {
            return;
        }
        self.span.0.get_or_insert(s.t);
        self.span.1 = s.t;
        // Compiled for one section (its section, curve and factor constants of the loop, whose
        // areas the compiler takes out of it) and for a line of sections (each node's own).
        if self.spec.nodes.is_empty() {
            self.count::<false>(s);
        } else {
            self.count::<true>(s);
        }
    }

    /// Counts one step's stresses at every node (`PER_NODE`: each node's section, curve and factor).
    #[inline(always)]
    fn count<const PER_NODE: bool>(&mut self, s: &StepView<'_>) {
        let r = s.results;
        let nf = self.spec.fibres.len();
        for i in 0..self.n {
            let (sec, curve, factor) = if PER_NODE {
                (
                    &self.spec.nodes[i].0,
                    self.node_curve[i],
                    self.node_factor[i],
                )
            } else {
                (&self.spec.section, self.spec.curve, self.factor)
            };
            for (k, f) in self.spec.fibres.iter().enumerate() {
                let (top, bottom) = sec.fibre_stresses(*f, r.tension[i], r.moment[i], r.z[i]);
                for (side, sigma) in [(0, top), (1, bottom)] {
                    let j = (i * nf + k) * 2 + side;
                    let d = &mut self.damage[j];
                    self.counters[j].push(sigma * 1e-6, &mut |c: Cycle| {
                        *d += c.count / curve.cycles(factor * c.range);
                    });
                }
            }
        }
    }

    /// The damage per node for a fibre, the larger of its top and bottom.
    pub fn damage_of(&self, fibre: Fibre) -> Option<Vec<f64>> {
        let k = self.spec.fibres.iter().position(|f| *f == fibre)?;
        let nf = self.spec.fibres.len();
        Some(
            (0..self.n)
                .map(|i| {
                    let j = (i * nf + k) * 2;
                    self.damage[j].max(self.damage[j + 1])
                })
                .collect(),
        )
    }

    /// The seconds counted (from the first counted step to the last).
    pub fn counted_seconds(&self) -> f64 {
        self.span.0.map_or(0.0, |a| self.span.1 - a)
    }
}

impl Observer for Fatigue {
    fn name(&self) -> &'static str {
        "fatigue"
    }
    fn step(&mut self, _: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        self.take(s);
        Ok(Control::Continue)
    }
    fn finish(&mut self, _: &RunContext<'_>, _: Option<&Stop>) -> Result<(), AppError> {
        let per_node = 2 * self.spec.fibres.len();
        for (j, (c, d)) in self
            .counters
            .iter_mut()
            .zip(self.damage.iter_mut())
            .enumerate()
        {
            let (curve, factor) = (
                self.node_curve[j / per_node],
                self.node_factor[j / per_node],
            );
            std::mem::take(c).finish(&mut |cy: Cycle| {
                *d += cy.count / curve.cycles(factor * cy.range);
            });
        }
        Ok(())
    }
    fn save(&mut self) -> Result<Value, AppError> {
        Ok(serde_json::to_value(Saved {
            counters: self.counters.clone(),
            damage: self.damage.clone(),
            first: self.span.0,
            last: self.span.1,
        })
        .unwrap_or(Value::Null))
    }
    fn restore(&mut self, v: &Value) -> Result<(), String> {
        let s: Saved = serde_json::from_value(v.clone()).map_err(|e| format!("fatigue: {e}"))?;
        if s.counters.len() != self.counters.len() || s.damage.len() != self.damage.len() {
            return Err(
                "fatigue: the saved counters do not fit the scene's nodes and fibres".into(),
            );
        }
        self.counters = s.counters;
        self.damage = s.damage;
        self.span = (s.first, s.last);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fatigue::stress::PipeSection;
    use catena_fe::dynamics::DynState;
    use catena_fe::statics::LineResults;

    /// The thickness correction reaches the damage: a 50 mm wall (twice the reference 25 mm) on
    /// curve E in free corrosion (one slope, m = 3, log ā = 11.533, k = 0.20), 1000 cycles of
    /// ±100 kN·m at the outer fibre of a 0.5 m pipe. By hand: Δσ = 2·M·r/I, the factor
    /// 2^0.2 = 1.148698, D = 1000·(factor·Δσ)³/10^11.533, to 1e-9. Without the correction the
    /// damage is 2^0.6 = 1.516 times smaller.
    #[test]
    fn the_thickness_correction_reaches_the_damage_along_the_line() {
        let section = PipeSection {
            od: 0.5,
            wall: 0.05,
            contents_density: 0.0,
            internal_pressure: 0.0,
            water_density: 1025.0,
            gravity: 9.80665,
            water_depth: 100.0,
        };
        let spec = FatigueSpec {
            curve: SnCurve::dnv("dnv-e-free-corrosion").expect("curve"),
            curve_name: "dnv-e-free-corrosion".into(),
            scf: 1.0,
            fibres: vec![Fibre::Outer],
            design_factor: None,
            start: 0.0,
            section,
            nodes: Vec::new(),
        };
        let mut f = Fatigue::new(spec, 1);
        let state = DynState::default();
        let mut results = LineResults {
            tension: vec![1e5],
            moment: vec![0.0],
            z: vec![-50.0],
            ..LineResults::default()
        };
        let cycles = 1000;
        for k in 0..=2 * cycles {
            results.moment[0] = if k % 2 == 0 { 1e5 } else { -1e5 };
            let view = StepView {
                t: k as f64,
                step: k as u64,
                state: &state,
                results: &results,
                info: Default::default(),
                record: false,
                envelope: true,
            };
            f.take(&view);
        }
        // The residue as `finish` counts it (half cycles).
        let (curve, factor) = (f.node_curve[0], f.node_factor[0]);
        for (c, d) in f.counters.iter_mut().zip(f.damage.iter_mut()) {
            std::mem::take(c).finish(&mut |cy: Cycle| {
                *d += cy.count / curve.cycles(factor * cy.range);
            });
        }
        let (r, i) = (0.25, section.inertia());
        let range = 2.0 * 1e5 * r / i * 1e-6; // MPa
        let factor = 2f64.powf(0.2);
        let want = cycles as f64 * (factor * range).powi(3) / 10f64.powf(11.533);
        let got = f.damage_of(Fibre::Outer).expect("outer")[0];
        println!("range {range:.3} MPa, damage {got:.6e} (by hand {want:.6e})");
        assert!((f.factor - factor).abs() < 1e-12, "{}", f.factor);
        assert!((got / want - 1.0).abs() < 1e-9, "{got} against {want}");
    }
}
