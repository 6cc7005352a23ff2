//! Observers of a dynamic run: every output is one. The run hands each converged step to every
//! observer ([`Observer::step`]); observers never touch the State. The built-in ones live here:
//! [`Envelopes`] (per-node extremes from `envelope_start`, every step), [`Gauges`] (moment and tension
//! at arc lengths: histories at the output interval, extremes every step), [`TopHistory`] (top
//! position and tension: histories at the output interval, extremes every step) and [`Checkpointer`]
//! (writes a [`Checkpoint`] every N steps). The HDF5 recorder and the progress bar are observers in
//! the crates above this one; fatigue will be one more.
//!
//! An observer that keeps state across steps saves it into checkpoints ([`Observer::save`]) and
//! takes it back on restart ([`Observer::restore`]), so a restarted run's outputs cover the whole run.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use catena_fe::assembly::LineResults;
use catena_fe::dynamics::{DynState, DynamicModel, StepInfo};
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::error::AppError;
use crate::run::checkpoint::Checkpoint;
use crate::run::lend::Halves;
use crate::run::statics::StaticRun;
use crate::scene::riser::{DynamicSpec, Gauge};

/// What every observer may read about the run.
#[derive(Debug, Clone, Copy)]
pub struct RunContext<'a> {
    /// The statics the run started from (scene, results).
    pub statics: &'a StaticRun,
    /// The dynamic Model (in an `Arc`: a run's second stepping thread reads it too).
    pub model: &'a Arc<DynamicModel>,
    /// The dynamic specification (duration, Δt, output interval, envelope start, placed gauges).
    pub spec: &'a DynamicSpec,
}

/// One converged step (or the initial state, step 0).
#[derive(Debug, Clone, Copy)]
pub struct StepView<'a> {
    /// Time, s.
    pub t: f64,
    /// Time steps of `dynamic.time_step` completed.
    pub step: u64,
    /// The committed State.
    pub state: &'a DynState,
    /// The nodal results of that State.
    pub results: &'a LineResults,
    /// What the step took (zero for the initial state).
    pub info: StepInfo,
    /// An output record is due at this step (every `output_interval`).
    pub record: bool,
    /// The step lies in the envelope window (`t ≥ envelope_start`).
    pub envelope: bool,
}

/// How a run ended (or stops).
#[derive(Debug, Clone, PartialEq)]
pub enum Stop {
    /// A step did not converge (when, where and how much: see the error).
    Failed(catena_fe::dynamics::StepError),
    /// An observer asked the run to stop (e.g. SIGINT or SIGTERM), with its reason.
    Interrupted(String),
    /// The run was asked to stop after a number of steps (`stop_after`).
    StoppedAfter(u64),
    /// A converged step gave a value that is not a finite number (see
    /// [`catena_fe::assembly::first_non_finite`]); it was not handed to any observer, so nothing
    /// non-finite is written.
    NonFinite {
        /// The time of the step, s.
        t: f64,
        /// The quantity (`tension`, `moment`, `velocity`, …).
        field: &'static str,
        /// The node.
        node: usize,
        /// The node's arc length from the top, m.
        arc: f64,
    },
}

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stop::Failed(e) => write!(f, "{e}"),
            Stop::Interrupted(r) => write!(f, "interrupted: {r}"),
            Stop::StoppedAfter(k) => write!(f, "stopped as asked after step {k}"),
            Stop::NonFinite {
                t,
                field,
                node,
                arc,
            } => write!(
                f,
                "the step to t = {t:.6} s gave a {field} that is not a finite number at node {node} \
                 (arc {arc:.3} m); the run stopped at the step before it (check the inputs that \
                 drive {field}: loads, motions, material and seabed numbers)"
            ),
        }
    }
}

/// What an observer tells the run after a step.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Control {
    /// Go on.
    Continue,
    /// Stop after this step (everything up to it is kept), for this reason.
    Stop(String),
}

/// An observer of converged steps.
pub trait Observer {
    /// Its name (the key of its state in checkpoints).
    fn name(&self) -> &'static str;

    /// Called once before the first step: with the initial state (step 0) on a fresh run, or with the
    /// restored state on a restart (`restarted`; its state was restored just before). By default the
    /// initial state of a fresh run is observed like a step, and a restart observes nothing (the
    /// restored state was observed before the checkpoint).
    fn start(
        &mut self,
        ctx: &RunContext<'_>,
        first: &StepView<'_>,
        restarted: bool,
    ) -> Result<(), AppError> {
        if !restarted {
            self.step(ctx, first)?;
        }
        Ok(())
    }

    /// Called after every converged step.
    fn step(&mut self, ctx: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError>;

    /// Called once at the end, however the run ended (`stop` is `None` when it completed).
    fn finish(&mut self, ctx: &RunContext<'_>, stop: Option<&Stop>) -> Result<(), AppError> {
        let _ = (ctx, stop);
        Ok(())
    }

    /// Makes its state durable (e.g. flushes buffered records) and returns it for a checkpoint
    /// (`Null` when it keeps none).
    fn save(&mut self) -> Result<Value, AppError> {
        Ok(Value::Null)
    }

    /// Takes back the state it saved.
    fn restore(&mut self, v: &Value) -> Result<(), String> {
        let _ = v;
        Ok(())
    }

    /// Whether it wants a checkpoint after this step.
    fn wants_checkpoint(&self, step: u64) -> bool {
        let _ = step;
        false
    }

    /// Receives the checkpoint it asked for.
    fn checkpoint(&mut self, cp: &Checkpoint) -> Result<(), AppError> {
        let _ = cp;
        Ok(())
    }

    /// The threads of its own that it keeps busy while the run steps (the HDF5 writer's: 1). The
    /// run counts them against [`crate::run::RunOptions::threads`] before it steps the line on
    /// two threads: two threads in lockstep that share their cores with a third wait for each
    /// other whenever it runs.
    fn busy_threads(&self) -> usize {
        0
    }

    /// Work this observer leaves for the line's two stepping threads to do while they wait for
    /// each other, if any ([`catena_fe::partner::Chores`]: the fatigue counting and the envelopes
    /// of the step before, when a pair may step the line; [`crate::run::lend`]). The run hands
    /// every observer's to the Workspace, done in turn
    /// ([`catena_fe::dynamics::DynWorkspace::set_chores`]); an observer that leaves chores must
    /// also do whatever of them is left when it is handed the next step.
    fn chores(&self) -> Option<catena_fe::partner::SharedChores> {
        None
    }
}

/// Non-finite values (the ±∞ of empty extremes) as JSON nulls and back.
fn enc(v: &[f64]) -> Vec<Option<f64>> {
    v.iter().map(|x| x.is_finite().then_some(*x)).collect()
}

fn dec(v: &[Option<f64>], empty: f64) -> Vec<f64> {
    v.iter().map(|x| x.unwrap_or(empty)).collect()
}

fn decode<T: for<'de> Deserialize<'de>>(v: &Value, what: &str) -> Result<T, String> {
    serde_json::from_value(v.clone()).map_err(|e| format!("{what}: {e}"))
}

/// `(least, greatest)` of a series (`(∞, −∞)` when it is empty).
pub fn extremes(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(*x), hi.max(*x))
        })
}

/// One quantity's range graph along the line: per node, the least and greatest value and the sum
/// (for the mean) over the steps of the envelope window.
#[derive(Debug, Clone, PartialEq)]
pub struct Range {
    /// Least value per node.
    pub min: Vec<f64>,
    /// Greatest value per node.
    pub max: Vec<f64>,
    /// Sum over the steps taken, per node (`mean = sum / samples`).
    pub sum: Vec<f64>,
}

#[derive(Serialize, Deserialize)]
struct RangeSaved {
    min: Vec<Option<f64>>,
    max: Vec<Option<f64>>,
    sum: Vec<f64>,
}

impl Range {
    /// An empty range for `n` nodes.
    pub fn new(n: usize) -> Self {
        Self {
            min: vec![f64::INFINITY; n],
            max: vec![f64::NEG_INFINITY; n],
            sum: vec![0.0; n],
        }
    }

    /// Takes one step's values, one per node ([`take_range`]).
    fn take(&mut self, v: &[f64]) {
        take_range(&mut self.min, &mut self.max, &mut self.sum, v);
    }

    /// `max − min` per node.
    pub fn range(&self) -> Vec<f64> {
        self.max.iter().zip(&self.min).map(|(a, b)| a - b).collect()
    }

    /// The mean over `samples` steps per node (NaN when there were none).
    pub fn mean(&self, samples: u64) -> Vec<f64> {
        let k = if samples > 0 {
            1.0 / samples as f64
        } else {
            f64::NAN
        };
        self.sum.iter().map(|s| s * k).collect()
    }

    fn save(&self) -> RangeSaved {
        RangeSaved {
            min: enc(&self.min),
            max: enc(&self.max),
            sum: self.sum.clone(),
        }
    }

    fn restore(&mut self, s: RangeSaved, name: &str) -> Result<(), String> {
        let n = self.min.len();
        for (what, len) in [
            ("min", s.min.len()),
            ("max", s.max.len()),
            ("sum", s.sum.len()),
        ] {
            if len != n {
                return Err(format!(
                    "envelopes.{name}.{what} has {len} entries, expected {n}"
                ));
            }
        }
        self.min = dec(&s.min, f64::INFINITY);
        self.max = dec(&s.max, f64::NEG_INFINITY);
        self.sum = s.sum;
        Ok(())
    }
}

/// The quantities with a range graph: `(name, units, what)`. The name is the HDF5 group under
/// `/ranges` and the Python key; the last three need the pipe's section (`line.wall` and
/// `line.contents_density`, or `[fatigue]`).
pub const RANGE_QUANTITIES: [(&str, &str, &str); 8] = [
    (
        "bending_moment",
        "N*m",
        "bending moment, negative in a sag bend",
    ),
    ("effective_tension", "N", "effective tension"),
    ("curvature", "1/m", "curvature M/EI, negative in a sag bend"),
    (
        "penetration",
        "m",
        "penetration of the invert below the mudline, positive down",
    ),
    (
        "seabed_force",
        "N/m",
        "seabed force per unit length (resistance, buoyancy and damping), positive up",
    ),
    (
        "wall_tension",
        "N",
        "wall tension T_w = T_e + p_i A_i - p_o A_o",
    ),
    (
        "stress_top",
        "Pa",
        "axial stress at the outer fibre on the upper side, T_w/A - M r/I (no SCF)",
    ),
    (
        "stress_bottom",
        "Pa",
        "axial stress at the outer fibre on the lower side, T_w/A + M r/I (no SCF)",
    ),
];

/// Per-node range graphs (least, greatest, mean) over the envelope window, from every step: bending
/// moment, effective tension, curvature, penetration and seabed force; with the pipe's section also
/// wall tension and the outer fibre's stresses (top and bottom of the section).
#[derive(Debug, Clone, PartialEq)]
pub struct Envelopes {
    /// Bending moment, N·m (negative = sag).
    pub moment: Range,
    /// Effective tension, N.
    pub tension: Range,
    /// Curvature `M/EI`, 1/m (negative = sag).
    pub curvature: Range,
    /// Penetration of the invert, m (positive down; negative: clear of the seabed).
    pub penetration: Range,
    /// Seabed force per unit length, N/m.
    pub seabed_force: Range,
    /// With the section: wall tension (N) and the outer fibre's axial stress at the top and the
    /// bottom of the section (Pa, no SCF), in that order.
    pub wall: Option<[Range; 3]>,
    /// Steps taken into the envelopes.
    pub samples: u64,
    /// The touchdown point's least and greatest arc length, m (`catena_fe::statics::touchdown_arc`;
    /// infinite while no step has a touchdown point).
    pub touchdown: (f64, f64),
    /// `1/EI` per node (the mean of the adjacent elements' EI).
    inv_ei: Vec<f64>,
    /// Scratch for the curvature, one value per node (allocated once).
    scratch: Scratch<Vec<f64>>,
    /// Scratch for wall tension and the two fibre stresses (empty without a section).
    section_scratch: Scratch<[Vec<f64>; 3]>,
    section: Option<crate::checks::fatigue::stress::PipeSection>,
    /// A line of sections: each node's (empty: `section` at every node).
    node_sections: Vec<crate::checks::fatigue::stress::PipeSection>,
    /// The halves lent to the waits of the pair that steps the line ([`Envelopes::lend_to_pair`]).
    lending: Lending,
}

mod lent;
use lent::{Lending, Scratch};

#[derive(Serialize, Deserialize)]
struct EnvelopesSaved {
    #[serde(default)]
    touchdown: Option<(f64, f64)>,
    ranges: Vec<RangeSaved>,
    samples: u64,
}

impl Envelopes {
    /// Empty envelopes for a line of elements with bending stiffnesses `ei` (N·m², one per element:
    /// the nodes are one more), with the pipe's section if it is known.
    pub fn new(ei: &[f64], section: Option<crate::checks::fatigue::stress::PipeSection>) -> Self {
        Self::with_sections(ei, section, Vec::new())
    }

    /// [`Envelopes::new`] for a line of sections: each node's section in `node_sections` (empty:
    /// `section` at every node).
    pub fn with_sections(
        ei: &[f64],
        section: Option<crate::checks::fatigue::stress::PipeSection>,
        node_sections: Vec<crate::checks::fatigue::stress::PipeSection>,
    ) -> Self {
        let n = ei.len() + 1;
        let inv_ei = (0..n)
            .map(|i| {
                let (a, b) = (ei.get(i.wrapping_sub(1)), ei.get(i));
                let mean = match (a, b) {
                    (Some(a), Some(b)) => 0.5 * (a + b),
                    (Some(a), None) | (None, Some(a)) => *a,
                    (None, None) => f64::NAN,
                };
                1.0 / mean
            })
            .collect();
        Self {
            moment: Range::new(n),
            tension: Range::new(n),
            curvature: Range::new(n),
            penetration: Range::new(n),
            seabed_force: Range::new(n),
            wall: section.map(|_| [Range::new(n), Range::new(n), Range::new(n)]),
            samples: 0,
            touchdown: (f64::INFINITY, f64::NEG_INFINITY),
            inv_ei,
            scratch: Scratch(vec![0.0; n]),
            section_scratch: Scratch(std::array::from_fn(|_| {
                vec![0.0; if section.is_some() { n } else { 0 }]
            })),
            section,
            node_sections,
            lending: Lending::default(),
        }
    }

    /// Makes the envelopes take each step in the waits of the pair that may step the line, each
    /// thread half the nodes ([`crate::run::lend`]): [`Observer::chores`].
    pub fn lend_to_pair(mut self) -> Self {
        let n = self.inv_ei.len();
        self.lending = Lending(Some(Arc::new(Halves::new(n / 2))));
        self
    }

    /// Takes a step into the range graphs: at once, or handed to the halves lent to the pair's
    /// waits.
    fn take_step(&mut self, r: &LineResults) {
        let Some(l) = self.lending.0.clone() else {
            self.update(r);
            return;
        };
        if !l.lent() {
            let halves = self.split(l.at());
            l.lend(halves);
        }
        let step = [&r.moment, &r.tension, &r.penetration, &r.seabed_force, &r.z];
        // The height only for the wall stresses.
        let k = if self.wall.is_some() { 5 } else { 4 };
        l.hand(&step.map(|v| v.as_slice())[..k]);
        self.samples += 1;
    }

    /// Takes the halves back from the pair's waits, each step's rest taken first.
    fn drain(&mut self) {
        if let Some(h) = self.lending.0.as_ref().and_then(|l| l.take_back()) {
            self.join(h);
        }
    }

    /// Every range graph with its name (as in [`RANGE_QUANTITIES`]); the section's three only when
    /// the section is known.
    pub fn ranges(&self) -> Vec<(&'static str, &Range)> {
        let mut v = vec![
            (RANGE_QUANTITIES[0].0, &self.moment),
            (RANGE_QUANTITIES[1].0, &self.tension),
            (RANGE_QUANTITIES[2].0, &self.curvature),
            (RANGE_QUANTITIES[3].0, &self.penetration),
            (RANGE_QUANTITIES[4].0, &self.seabed_force),
        ];
        if let Some(w) = &self.wall {
            for (k, r) in w.iter().enumerate() {
                v.push((RANGE_QUANTITIES[5 + k].0, r));
            }
        }
        v
    }

    fn ranges_mut(&mut self) -> Vec<&mut Range> {
        let mut v = vec![
            &mut self.moment,
            &mut self.tension,
            &mut self.curvature,
            &mut self.penetration,
            &mut self.seabed_force,
        ];
        if let Some(w) = &mut self.wall {
            v.extend(w.iter_mut());
        }
        v
    }

    fn update(&mut self, s: &LineResults) {
        self.moment.take(&s.moment);
        self.tension.take(&s.tension);
        self.penetration.take(&s.penetration);
        self.seabed_force.take(&s.seabed_force);
        let k = &mut self.scratch.0;
        for ((k, m), c) in k.iter_mut().zip(&s.moment).zip(&self.inv_ei) {
            *k = m * c;
        }
        self.curvature.take(k);
        if let (Some(sec), Some([wt, top, bottom])) = (&self.section, &mut self.wall) {
            let [w, t, b] = &mut self.section_scratch.0;
            // One section (a constant of the loop) or each node's own.
            if self.node_sections.is_empty() {
                wall_stresses_one(s, sec, [w, t, b]);
            } else {
                let per_node = &self.node_sections;
                wall_stresses(s, |i| &per_node[i], [w, t, b]);
            }
            wt.take(w);
            top.take(t);
            bottom.take(b);
        }
        self.samples += 1;
    }
}

/// Takes one step's values into a range graph's least, greatest and summed values, one per node: a
/// loop per array, which the compiler vectorises, compiled also for AVX2 and AVX-512 and chosen at
/// run time (each node's own minimum, maximum and sum: the same values to the bit on every
/// processor).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn take_range(min: &mut [f64], max: &mut [f64], sum: &mut [f64], v: &[f64]) {
    for (m, x) in min.iter_mut().zip(v) {
        *m = m.min(*x);
    }
    for (m, x) in max.iter_mut().zip(v) {
        *m = m.max(*x);
    }
    for (m, x) in sum.iter_mut().zip(v) {
        *m += *x;
    }
}

/// [`wall_stresses`] with one section for every node, compiled as [`take_range`] is.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn wall_stresses_one(
    s: &LineResults,
    sec: &crate::checks::fatigue::stress::PipeSection,
    out: [&mut Vec<f64>; 3],
) {
    wall_stresses(s, |_| sec, out);
}

/// Each node's wall tension and outer-fibre stresses (top, bottom) into `w`, `t`, `b`, with node
/// `i`'s section `section(i)`.
#[inline(always)]
fn wall_stresses<'s>(
    s: &LineResults,
    section: impl Fn(usize) -> &'s crate::checks::fatigue::stress::PipeSection,
    [w, t, b]: [&mut Vec<f64>; 3],
) {
    let outer = crate::checks::fatigue::stress::Fibre::Outer;
    for i in 0..s.moment.len() {
        let sec = section(i);
        let (te, z) = (s.tension[i], s.z[i]);
        w[i] = te + sec.wall_minus_effective(z);
        (t[i], b[i]) = sec.fibre_stresses(outer, te, s.moment[i], z);
    }
}

impl Observer for Envelopes {
    fn name(&self) -> &'static str {
        "envelopes"
    }
    fn step(&mut self, ctx: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        if s.envelope {
            self.take_step(s.results);
            if let Some(a) =
                catena_fe::statics::touchdown_arc(&ctx.model.line.arc, &s.results.penetration)
            {
                self.touchdown = (self.touchdown.0.min(a), self.touchdown.1.max(a));
            }
        }
        Ok(Control::Continue)
    }
    fn finish(&mut self, _: &RunContext<'_>, _: Option<&Stop>) -> Result<(), AppError> {
        self.drain();
        Ok(())
    }
    fn chores(&self) -> Option<catena_fe::partner::SharedChores> {
        let l = Arc::clone(self.lending.0.as_ref()?);
        Some(catena_fe::partner::SharedChores(l))
    }
    fn save(&mut self) -> Result<Value, AppError> {
        self.drain();
        Ok(serde_json::to_value(EnvelopesSaved {
            touchdown: self.touchdown.0.is_finite().then_some(self.touchdown),
            ranges: self.ranges().iter().map(|(_, r)| r.save()).collect(),
            samples: self.samples,
        })
        .unwrap_or(Value::Null))
    }
    fn restore(&mut self, v: &Value) -> Result<(), String> {
        self.drain();
        let s: EnvelopesSaved = decode(v, "envelopes")?;
        let names: Vec<&str> = self.ranges().iter().map(|(n, _)| *n).collect();
        if s.ranges.len() != names.len() {
            return Err(format!(
                "envelopes: {} range graphs saved, this scene has {}",
                s.ranges.len(),
                names.len()
            ));
        }
        for ((r, saved), name) in self.ranges_mut().into_iter().zip(s.ranges).zip(names) {
            r.restore(saved, name)?;
        }
        self.samples = s.samples;
        self.touchdown = s.touchdown.unwrap_or((f64::INFINITY, f64::NEG_INFINITY));
        Ok(())
    }
}

/// Linear interpolation of nodal values at an arc length.
pub fn at_arc(arc: &[f64], v: &[f64], s: f64) -> f64 {
    let i = arc.partition_point(|a| *a < s).clamp(1, arc.len() - 1);
    let f = ((s - arc[i - 1]) / (arc[i] - arc[i - 1])).clamp(0.0, 1.0);
    v[i - 1] + f * (v[i] - v[i - 1])
}

/// One gauge's record.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct GaugeTrace {
    /// Bending moment at each record, N·m.
    pub moment: Vec<f64>,
    /// Effective tension at each record, N.
    pub tension: Vec<f64>,
    /// Least and greatest moment over every step of the run, N·m.
    pub moment_extremes: (Option<f64>, Option<f64>),
    /// Least and greatest moment over the steps where the top rose, then where it fell, N·m.
    pub by_direction: [(Option<f64>, Option<f64>); 2],
}

fn widen(e: &mut (Option<f64>, Option<f64>), v: f64) {
    e.0 = Some(e.0.map_or(v, |a| a.min(v)));
    e.1 = Some(e.1.map_or(v, |a| a.max(v)));
}

/// Gauges: moment and tension at fixed arc lengths, recorded at the output interval; extremes over
/// every step, overall and split by the direction the top moves (pull-up: rising; lay-down:
/// falling).
#[derive(Debug, Clone, PartialEq)]
pub struct Gauges {
    /// The gauges (arc lengths placed).
    pub gauges: Vec<Gauge>,
    /// One trace per gauge.
    pub traces: Vec<GaugeTrace>,
    /// The values of the last step, `(moment, tension)` per gauge.
    pub current: Vec<(f64, f64)>,
    last_top_z: Option<f64>,
}

impl Gauges {
    /// Gauges at the placed arc lengths.
    pub fn new(gauges: &[Gauge]) -> Self {
        Self {
            gauges: gauges.to_vec(),
            traces: vec![GaugeTrace::default(); gauges.len()],
            current: vec![(0.0, 0.0); gauges.len()],
            last_top_z: None,
        }
    }

    fn take(&mut self, arc: &[f64], s: &StepView<'_>) {
        let r = s.results;
        let dz = self.last_top_z.map(|z| r.z[0] - z);
        for (k, g) in self.gauges.iter().enumerate() {
            let m = at_arc(arc, &r.moment, g.arc);
            let t = at_arc(arc, &r.tension, g.arc);
            self.current[k] = (m, t);
            let tr = &mut self.traces[k];
            widen(&mut tr.moment_extremes, m);
            match dz {
                Some(d) if d > 1e-9 => widen(&mut tr.by_direction[0], m),
                Some(d) if d < -1e-9 => widen(&mut tr.by_direction[1], m),
                _ => {}
            }
            if s.record {
                tr.moment.push(m);
                tr.tension.push(t);
            }
        }
        self.last_top_z = Some(r.z[0]);
    }
}

impl Observer for Gauges {
    fn name(&self) -> &'static str {
        "gauges"
    }
    fn step(&mut self, ctx: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        self.take(&ctx.model.line.arc, s);
        Ok(Control::Continue)
    }
    fn save(&mut self) -> Result<Value, AppError> {
        Ok(serde_json::json!({ "traces": self.traces, "last_top_z": self.last_top_z }))
    }
    fn restore(&mut self, v: &Value) -> Result<(), String> {
        let traces: Vec<GaugeTrace> = decode(&v["traces"], "gauges.traces")?;
        if traces.len() != self.gauges.len() {
            return Err(format!(
                "gauges: {} traces saved, the scene has {} gauges",
                traces.len(),
                self.gauges.len()
            ));
        }
        self.traces = traces;
        self.last_top_z = decode(&v["last_top_z"], "gauges.last_top_z")?;
        Ok(())
    }
}

/// The top end: time, position and tension at the output interval (for plots and the gauge view);
/// the top tension's extremes over the envelope window from every step.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TopHistory {
    /// Time of each record, s.
    pub t: Vec<f64>,
    /// Top x at each record, m.
    pub top_x: Vec<f64>,
    /// Top height at each record, m.
    pub top_z: Vec<f64>,
    /// Top tension at each record, N.
    pub top_tension: Vec<f64>,
    /// Least and greatest top tension over every step of the envelope window, N.
    pub tension_extremes: (Option<f64>, Option<f64>),
}

impl TopHistory {
    fn take(&mut self, s: &StepView<'_>) {
        let r = s.results;
        if s.envelope {
            widen(&mut self.tension_extremes, r.tension[0]);
        }
        if s.record {
            self.t.push(s.t);
            self.top_x.push(r.x[0]);
            self.top_z.push(r.z[0]);
            self.top_tension.push(r.tension[0]);
        }
    }
}

impl Observer for TopHistory {
    fn name(&self) -> &'static str {
        "top"
    }
    fn step(&mut self, _: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        self.take(s);
        Ok(Control::Continue)
    }
    fn save(&mut self) -> Result<Value, AppError> {
        Ok(serde_json::to_value(&*self).unwrap_or(Value::Null))
    }
    fn restore(&mut self, v: &Value) -> Result<(), String> {
        *self = decode(v, "top")?;
        Ok(())
    }
}

/// Writes a checkpoint every `every` steps to `path` (atomically: a temporary file, then a rename).
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpointer {
    /// Steps between checkpoints (> 0).
    pub every: u64,
    /// The checkpoint file.
    pub path: PathBuf,
    /// Checkpoints written.
    pub written: u64,
}

impl Checkpointer {
    /// A checkpointer writing to `path` every `every` steps.
    pub fn new(path: &Path, every: u64) -> Self {
        Self {
            every,
            path: path.to_path_buf(),
            written: 0,
        }
    }
}

impl Observer for Checkpointer {
    fn name(&self) -> &'static str {
        "checkpointer"
    }
    fn step(&mut self, _: &RunContext<'_>, _: &StepView<'_>) -> Result<Control, AppError> {
        Ok(Control::Continue)
    }
    fn wants_checkpoint(&self, step: u64) -> bool {
        self.every > 0 && step % self.every == 0
    }
    fn checkpoint(&mut self, cp: &Checkpoint) -> Result<(), AppError> {
        cp.write(&self.path)?;
        self.written += 1;
        Ok(())
    }
}
