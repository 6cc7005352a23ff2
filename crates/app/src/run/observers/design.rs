//! The strength check as an observer of a run (`[design_check]`): at every step from its start, the
//! utilisation of the chosen code's criterion at every node ([`crate::checks::design`]), keeping per node
//! the largest, when it occurred and which term dominated; and the least effective tension at every
//! node with its time, against the Euler load of the node's elements
//! (`π²EI/L_e²`, the smaller of its adjacent elements'): a node whose tension falls below minus that load is reported (when and where) as
//! compression that may buckle the pipe between nodes.
//!
//! The functional load effects are the statics' (read when the run starts, fresh or restarted);
//! the environmental ones are each step's increment over them.

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::checks::design::{euler_load, DesignSpec, Evaluator, Term};
use crate::error::AppError;
use crate::run::observe::{Control, Observer, RunContext, StepView};
use crate::scene::riser::DynamicSpec;
use catena_fe::statics::LineResults;

/// A node whose effective tension fell below minus its Euler load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Compression {
    /// Node index.
    pub node: usize,
    /// Arc length from the top, m.
    pub arc: f64,
    /// The least effective tension, N (negative).
    pub least_tension: f64,
    /// When it occurred, s.
    pub time: f64,
    /// The smaller Euler load of the node's adjacent elements, N.
    pub euler_load: f64,
}

/// The design check observer.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignCheck {
    /// The check.
    pub spec: DesignSpec,
    /// The evaluator (built when the run starts, from its statics).
    pub evaluator: Option<Evaluator>,
    /// Each node's largest utilisation since the start.
    pub max: Vec<f64>,
    /// When each node's largest utilisation occurred, s.
    pub time_of_max: Vec<f64>,
    /// Which term dominated then.
    pub term_of_max: Vec<Term>,
    /// Each node's least effective tension since the start, N.
    pub least_tension: Vec<f64>,
    /// When it occurred, s.
    pub time_of_least: Vec<f64>,
    /// Each node's Euler load (the smaller of its adjacent elements'), N.
    pub euler: Vec<f64>,
    /// Each node's arc length, m.
    pub arc: Vec<f64>,
    /// First and last time checked, s.
    pub span: (Option<f64>, f64),
}

#[derive(Serialize, Deserialize)]
struct Saved {
    max: Vec<f64>,
    time_of_max: Vec<f64>,
    term_of_max: Vec<Term>,
    least_tension: Vec<f64>,
    time_of_least: Vec<f64>,
    first: Option<f64>,
    last: f64,
}

impl DesignCheck {
    /// The observer for a line with these element lengths and bending stiffnesses (`(L0, EI)`
    /// per element) and node arc lengths.
    pub fn new(spec: DesignSpec, elements: &[(f64, f64)], arc: &[f64]) -> Self {
        let n = arc.len();
        let euler = (0..n)
            .map(|i| {
                let adjacent = [i.checked_sub(1), (i < elements.len()).then_some(i)];
                adjacent
                    .into_iter()
                    .flatten()
                    .map(|e| euler_load(elements[e].1, elements[e].0))
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        Self {
            spec,
            evaluator: None,
            max: vec![0.0; n],
            time_of_max: vec![0.0; n],
            term_of_max: vec![Term::None; n],
            least_tension: vec![f64::MAX; n],
            time_of_least: vec![0.0; n],
            euler,
            arc: arc.to_vec(),
            span: (None, 0.0),
        }
    }

    /// The node with the largest utilisation: `(node, utilisation)`.
    pub fn worst(&self) -> Option<(usize, f64)> {
        self.max
            .iter()
            .copied()
            .enumerate()
            .filter(|&(i, _)| self.term_of_max[i] != Term::None)
            .fold(None, |w: Option<(usize, f64)>, (i, u)| match w {
                Some((_, b)) if b >= u => w,
                _ => Some((i, u)),
            })
    }

    /// Every node in compression beyond its Euler load.
    pub fn compression(&self) -> Vec<Compression> {
        (0..self.arc.len())
            .filter(|&i| self.least_tension[i] < -self.euler[i])
            .map(|i| Compression {
                node: i,
                arc: self.arc[i],
                least_tension: self.least_tension[i],
                time: self.time_of_least[i],
                euler_load: self.euler[i],
            })
            .collect()
    }

    fn take(&mut self, s: &StepView<'_>) {
        if s.t < self.spec.start - 1e-9 {
            return;
        }
        let Some(ev) = &self.evaluator else { return };
        self.span.0.get_or_insert(s.t);
        self.span.1 = s.t;
        let r = s.results;
        for i in 0..self.max.len() {
            let u = ev.at(i, r.tension[i], r.moment[i], r.z[i]);
            if u.value > self.max[i] {
                self.max[i] = u.value;
                self.time_of_max[i] = s.t;
                self.term_of_max[i] = u.term;
            }
            if r.tension[i] < self.least_tension[i] {
                self.least_tension[i] = r.tension[i];
                self.time_of_least[i] = s.t;
            }
        }
    }
}

/// The evaluator of a run's check: each node's section (a line of sections' own, else the
/// scene's), the statics' moments and tensions as the functional part. `None` when the run has
/// no check or no section (the scene refuses a check without one).
pub fn evaluator_of(ctx: &RunContext<'_>) -> Option<Evaluator> {
    evaluator_for(ctx.spec, &ctx.statics.results)
}

/// [`evaluator_of`] from a dynamic specification and the statics' results (`n` nodes).
pub fn evaluator_for(spec: &DynamicSpec, statics: &LineResults) -> Option<Evaluator> {
    let check = spec.design_check?;
    let n = statics.moment.len();
    let sections: Vec<_> = if spec.node_sections.is_empty() {
        vec![spec.section?; n]
    } else {
        spec.node_sections.clone()
    };
    Some(Evaluator::new(
        check,
        sections.into_iter(),
        &statics.moment,
        &statics.tension,
    ))
}

impl Observer for DesignCheck {
    fn name(&self) -> &'static str {
        "design_check"
    }
    fn start(
        &mut self,
        ctx: &RunContext<'_>,
        first: &StepView<'_>,
        restarted: bool,
    ) -> Result<(), AppError> {
        self.evaluator = evaluator_of(ctx);
        if !restarted {
            self.take(first);
        }
        Ok(())
    }
    fn step(&mut self, _: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        self.take(s);
        Ok(Control::Continue)
    }
    fn save(&mut self) -> Result<Value, AppError> {
        Ok(serde_json::to_value(Saved {
            max: self.max.clone(),
            time_of_max: self.time_of_max.clone(),
            term_of_max: self.term_of_max.clone(),
            least_tension: self.least_tension.clone(),
            time_of_least: self.time_of_least.clone(),
            first: self.span.0,
            last: self.span.1,
        })
        .unwrap_or(Value::Null))
    }
    fn restore(&mut self, v: &Value) -> Result<(), String> {
        let s: Saved =
            serde_json::from_value(v.clone()).map_err(|e| format!("design_check: {e}"))?;
        if s.max.len() != self.max.len() {
            return Err("design_check: the saved state does not fit the scene's nodes".into());
        }
        self.max = s.max;
        self.time_of_max = s.time_of_max;
        self.term_of_max = s.term_of_max;
        self.least_tension = s.least_tension;
        self.time_of_least = s.time_of_least;
        self.span = (s.first, s.last);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checks::design::Code;
    use crate::checks::fatigue::stress::PipeSection;
    use catena_fe::dynamics::DynState;
    use catena_fe::statics::LineResults;

    /// Compression: three nodes on two elements of 2 m and 0.5 m (EI 1 MN·m²): each node's Euler
    /// load is the smaller of its adjacent elements', π²·1e6/4 = 2.467 MN at the first two nodes,
    /// π²·1e6/0.25 = 39.48 MN at the last. The least tension and its time are kept per node, and only the node
    /// pushed beyond its own Euler load is reported, with when. The largest utilisation keeps its
    /// time and term.
    #[test]
    fn compression_beyond_the_element_euler_load_is_reported_when_and_where() {
        let spec = DesignSpec {
            code: Code::DnvStF201,
            smys: 448e6,
            smts: 531e6,
            internal_pressure: 0.0,
            corrosion_allowance: 0.0,
            start: 1.0,
            gamma_sc: 1.14,
            gamma_m: 1.15,
            gamma_f: 1.1,
            gamma_e: 1.3,
            alpha_u: 0.96,
            alpha_fab: 1.0,
            ovality: 0.005,
            youngs_modulus: 207e9,
            poisson: 0.3,
            design_factor: 0.8,
            gamma_c: 1.0,
            gamma_eps: 2.5,
            alpha_h: 0.92,
        };
        let mut d = DesignCheck::new(spec, &[(2.0, 1e6), (0.5, 1e6)], &[0.0, 2.0, 2.5]);
        let pi2 = std::f64::consts::PI.powi(2);
        assert!((d.euler[0] - pi2 * 1e6 / 4.0).abs() < 1e-6);
        assert!(d.euler[1] == d.euler[0] && (d.euler[2] - pi2 * 1e6 / 0.25).abs() < 1e-6);
        let section = PipeSection {
            od: 0.2286,
            wall: 0.0254,
            contents_density: 0.0,
            internal_pressure: 0.0,
            water_density: 1025.0,
            gravity: 9.80665,
            water_depth: 100.0,
        };
        d.evaluator = Some(Evaluator::new(
            spec,
            std::iter::repeat_n(section, 3),
            &[0.0; 3],
            &[1e5; 3],
        ));
        let state = DynState::default();
        let mut results = LineResults {
            tension: vec![1e5; 3],
            moment: vec![0.0; 3],
            z: vec![50.0; 3],
            ..LineResults::default()
        };
        // t = 0 is before the start: not counted however large.
        for (t, te0, m2) in [
            (0.0, -9e6, -4e5),
            (1.0, -3e6, -1e5),
            (2.0, -1e6, -2e5),
            (3.0, 1e5, 0.0),
        ] {
            results.tension[0] = te0;
            results.moment[2] = m2;
            let view = StepView {
                t,
                step: t as u64,
                state: &state,
                results: &results,
                info: Default::default(),
                record: false,
                envelope: true,
            };
            d.take(&view);
        }
        assert_eq!(d.least_tension[0], -3e6);
        assert_eq!(d.time_of_least[0], 1.0);
        let c = d.compression();
        assert_eq!(c.len(), 1, "{c:?}");
        assert_eq!((c[0].node, c[0].time, c[0].arc), (0, 1.0, 0.0));
        assert_eq!(d.time_of_max[2], 2.0);
        assert_eq!(d.term_of_max[2], Term::Bending);
        assert_eq!(d.span, (Some(1.0), 3.0));
    }
}
