//! Fatigue as an observer of a run: at every step from `start`, the stresses at the top and bottom of
//! each chosen fibre at every node go into a streaming rainflow counter, and every counted cycle's
//! Miner damage is added at once (`n/N(SCF·t_corr·Δσ)`); at the end the residue counts as half
//! cycles. No second pass over the output, and nothing of the history is kept.
//!
//! **Off the stepping thread.** When the run may keep two threads busy
//! ([`crate::run::RunOptions::threads`]: the machine's cores by default, one in a study that
//! already runs a storm on every core) the counting runs on a thread of its own: the observer copies each counted step's effective tension, moment and height at every
//! node (`3·n` numbers) into a batch, and hands the thread a batch every [`BATCH_STEPS`] steps
//! (fewer on a line so long that a batch would pass [`BATCH_VALUES`] numbers), at most
//! [`BATCHES_IN_FLIGHT`] of them waiting: a run never gets ahead of its counting by more. The
//! thread computes the same stresses from the same numbers and pushes them into the same counters
//! in the same order, so the damage is the same to the bit as counted on the stepping thread (tested).
//! `finish` and `save` (a checkpoint) wait for the thread to count every step handed to it and
//! take the counters back; the next counted step starts a new thread.
//!
//! **In the pair's waits.** Where two threads may step the line ([`catena_fe::dynamics::Pair`]),
//! a third busy thread would stall them, and counting on the stepping thread between steps keeps
//! the partner idle (issue 69: 8.3 % of the 3-hour storm). So the counting is split at the line's
//! middle node into two halves, each with its nodes' counters and damage, and lent to the pair's
//! waits ([`crate::run::lend`]): each counted step's tension, moment and height are copied into
//! each half, and while the pair steps the next step, the calling thread counts the first half and
//! the partner the second, [`crate::run::lend::CHORE_NODES`] nodes at a time, in what would have
//! been their waits for each other. Handed the next step, the observer first counts
//! whatever of the last is left (all of it where one thread stepped). Every counter takes the
//! same samples in the same order: the damage is the same to the bit (tested).

use std::sync::{mpsc, Arc, Mutex};
use std::thread::JoinHandle;

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::checks::fatigue::rainflow::{Cycle, Rainflow};
use crate::checks::fatigue::sn::SnCurve;
use crate::checks::fatigue::stress::Fibre;
use crate::checks::fatigue::FatigueSpec;
use crate::error::AppError;
use crate::run::lend::{Halves, Piece};
use crate::run::observe::{Control, Observer, RunContext, StepView, Stop};

/// Counted steps handed to the counting thread at a time, at most.
pub const BATCH_STEPS: usize = 64;

/// Numbers in a batch, at most (1 MiB): a line of more than 682 nodes hands over fewer steps at a
/// time.
pub const BATCH_VALUES: usize = 1 << 17;

/// Batches handed to the counting thread and not yet counted, at most.
pub const BATCHES_IN_FLIGHT: usize = 4;

/// The fatigue observer: damage per node, fibre and side (top, bottom).
#[derive(Debug)]
pub struct Fatigue {
    /// The specification.
    pub spec: FatigueSpec,
    /// First and last time counted, s.
    pub span: (Option<f64>, f64),
    /// The counting; `None` while the counting thread holds it.
    counting: Option<Counting>,
    /// The counting thread, while a run hands it batches.
    thread: Option<CountingThread>,
    /// Whether counting runs on a thread of its own (more than one core).
    threaded: bool,
    /// The two halves of the counting lent to the pair's waits, when two threads may step.
    lent: Option<Arc<Halves<Counting>>>,
    /// The batch being filled: per counted step, the tension, moment and height at every node.
    batch: Vec<f64>,
    /// Numbers in a full batch: `3·n` per step, [`BATCH_STEPS`] steps or fewer.
    batch_len: usize,
    n: usize,
}

/// What the stresses of a step go through (each node's section, curve and factor, the rainflow
/// counters) and the damage they add.
#[derive(Debug, Clone, PartialEq)]
pub struct Counting {
    spec: FatigueSpec,
    factor: f64,
    /// Each node's factor on its stress ranges (its type's SCF × its wall's thickness correction).
    pub node_factor: Vec<f64>,
    /// Each node's S-N curve.
    pub node_curve: Vec<SnCurve>,
    counters: Vec<Rainflow>,
    /// Miner damage, indexed `(node·fibres + fibre)·2 + side` (side 0 top, 1 bottom).
    pub damage: Vec<f64>,
}

/// The counting thread: batches go in, emptied batches come back for reuse, the counting comes
/// back when the batches stop.
#[derive(Debug)]
struct CountingThread {
    batches: mpsc::SyncSender<Vec<f64>>,
    /// (In a mutex only because an output must be `Sync`; one thread takes it.)
    emptied: Mutex<mpsc::Receiver<Vec<f64>>>,
    handle: JoinHandle<Counting>,
}

#[derive(Serialize, Deserialize)]
struct Saved {
    counters: Vec<Rainflow>,
    damage: Vec<f64>,
    first: Option<f64>,
    last: f64,
}

impl Counting {
    /// Counts one step's stresses at every node from its effective tension, moment and height.
    fn count(&mut self, tension: &[f64], moment: &[f64], z: &[f64]) {
        self.count_from(0, tension, moment, z);
    }

    /// Counts one step's stresses at the nodes from `first` on, as many as `tension` holds.
    fn count_from(&mut self, first: usize, tension: &[f64], moment: &[f64], z: &[f64]) {
        // Compiled for one section (its section, curve and factor constants of the loop, whose
        // areas the compiler takes out of it) and for a line of sections (each node's own).
        if self.spec.nodes.is_empty() {
            self.count_nodes::<false>(first, tension, moment, z);
        } else {
            self.count_nodes::<true>(first, tension, moment, z);
        }
    }

    /// [`Counting::count_from`] (`PER_NODE`: each node's section, curve and factor).
    #[inline(always)]
    fn count_nodes<const PER_NODE: bool>(
        &mut self,
        first: usize,
        tension: &[f64],
        moment: &[f64],
        z: &[f64],
    ) {
        let nf = self.spec.fibres.len();
        for (i, ((&te, &m), &z)) in tension.iter().zip(moment).zip(z).enumerate() {
            let i = first + i;
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
                let (top, bottom) = sec.fibre_stresses(*f, te, m, z);
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

    /// The counting of the nodes `..m` and that of the nodes `m..` (each with its counters, damage,
    /// curves and factors): [`Counting::join`] puts them back.
    fn split_at(mut self, m: usize) -> (Self, Self) {
        let per = 2 * self.spec.fibres.len();
        let mut spec = self.spec.clone();
        spec.nodes = if self.spec.nodes.is_empty() {
            Vec::new()
        } else {
            self.spec.nodes.split_off(m)
        };
        let second = Self {
            spec,
            factor: self.factor,
            node_factor: self.node_factor.split_off(m),
            node_curve: self.node_curve.split_off(m),
            counters: self.counters.split_off(m * per),
            damage: self.damage.split_off(m * per),
        };
        (self, second)
    }

    /// The counting of [`Counting::split_at`]'s two parts, whole again.
    fn join(mut self, mut second: Self) -> Self {
        self.spec.nodes.append(&mut second.spec.nodes);
        self.node_factor.append(&mut second.node_factor);
        self.node_curve.append(&mut second.node_curve);
        self.counters.append(&mut second.counters);
        self.damage.append(&mut second.damage);
        self
    }

    /// Counts each step of a batch (`3·n` numbers a step: tension, moment, height).
    fn count_batch(&mut self, batch: &[f64], n: usize) {
        for step in batch.chunks_exact(3 * n) {
            let (tension, rest) = step.split_at(n);
            let (moment, z) = rest.split_at(n);
            self.count(tension, moment, z);
        }
    }

    /// Counts the residues as half cycles (the end of the record).
    fn finish(&mut self) {
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
    }
}

/// A half of the counting, lent to a pair's waits: its nodes' counters and damage.
impl Piece for Counting {
    fn nodes(&self) -> usize {
        self.node_curve.len()
    }
    /// `step`: the tension, moment and height at the half's nodes.
    fn take(&mut self, step: &[&[f64]], nodes: std::ops::Range<usize>) {
        let (t, m, z) = (step[0], step[1], step[2]);
        let r = nodes.clone();
        self.count_from(nodes.start, &t[r.clone()], &m[r.clone()], &z[r]);
    }
}

impl CountingThread {
    /// Starts a thread counting the batches it is handed with `counting`, for `n` nodes.
    fn start(mut counting: Counting, n: usize) -> Result<Self, AppError> {
        let (batches, incoming) = mpsc::sync_channel::<Vec<f64>>(BATCHES_IN_FLIGHT);
        let (back, emptied) = mpsc::channel();
        let handle = std::thread::Builder::new()
            .name("catena-fatigue".into())
            .spawn(move || {
                for mut batch in incoming {
                    counting.count_batch(&batch, n);
                    batch.clear();
                    // The observer may have stopped taking buffers back: nothing to do then.
                    let _ = back.send(batch);
                }
                counting
            })
            .map_err(|e| failure(format!("could not start the counting thread: {e}")))?;
        Ok(Self {
            batches,
            emptied: Mutex::new(emptied),
            handle,
        })
    }
}

impl Fatigue {
    /// Whether the counting runs on a thread of its own.
    pub fn threaded(&self) -> bool {
        self.threaded
    }

    /// Whether the counting is lent to the waits of the pair that may step the line (see the
    /// module docs).
    pub fn in_the_pairs_waits(&self) -> bool {
        self.lent.is_some()
    }

    /// The observer for `n` nodes (each with the specification's section and curve, or, for a line
    /// of sections, its own: [`FatigueSpec::nodes`]), counting on a thread of its own (`threaded`:
    /// the run's [`crate::run::RunOptions::threads`] above one) or on the stepping thread.
    pub fn with_thread(spec: FatigueSpec, n: usize, threaded: bool) -> Self {
        Self::with_mode(spec, n, threaded, false)
    }

    /// The observer for `n` nodes counting in the waits of the two threads that may step the
    /// line (see the module docs): its [`Observer::chores`].
    pub fn lent(spec: FatigueSpec, n: usize) -> Self {
        Self::with_mode(spec, n, false, true)
    }

    fn with_mode(spec: FatigueSpec, n: usize, threaded: bool, lent: bool) -> Self {
        let factor = range_factor(&spec);
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
        let counting = Counting {
            spec: spec.clone(),
            factor,
            node_factor,
            node_curve,
            counters: vec![Rainflow::new(); m],
            damage: vec![0.0; m],
        };
        Self {
            spec,
            span: (None, 0.0),
            counting: Some(counting),
            thread: None,
            threaded,
            lent: lent.then(|| Arc::new(Halves::new(n / 2))),
            batch: Vec::new(),
            batch_len: 3 * n * (BATCH_VALUES / (3 * n).max(1)).clamp(1, BATCH_STEPS),
            n,
        }
    }

    fn take(&mut self, s: &StepView<'_>) -> Result<(), AppError> {
        if s.t < self.spec.start - 1e-9 {
            return Ok(());
        }
        self.span.0.get_or_insert(s.t);
        self.span.1 = s.t;
        let r = s.results;
        let n = self.n;
        let (tension, moment, z) = (&r.tension[..n], &r.moment[..n], &r.z[..n]);
        if let Some(lent) = &self.lent {
            if let Some(c) = self.counting.take() {
                let (a, b) = c.split_at(lent.at());
                lent.lend([a, b]);
            }
            lent.hand(&[tension, moment, z]);
            return Ok(());
        }
        if !self.threaded {
            if let Some(c) = &mut self.counting {
                c.count(tension, moment, z);
            }
            return Ok(());
        }
        if self.batch.capacity() == 0 {
            self.batch.reserve_exact(self.batch_len);
        }
        self.batch.extend_from_slice(tension);
        self.batch.extend_from_slice(moment);
        self.batch.extend_from_slice(z);
        if self.batch.len() >= self.batch_len {
            self.hand_over()?;
        }
        Ok(())
    }

    /// Hands the batch to the counting thread (started if need be) and takes an emptied one back
    /// to fill (or a new one while the first batches are in flight).
    fn hand_over(&mut self) -> Result<(), AppError> {
        if self.batch.is_empty() {
            return Ok(());
        }
        if self.thread.is_none() {
            let counting = self.counting.take().ok_or_else(lost)?;
            self.thread = Some(CountingThread::start(counting, self.n)?);
        }
        let t = self.thread.as_ref().ok_or_else(lost)?;
        let reused = match t.emptied.lock() {
            Ok(back) => back.try_recv().ok(),
            Err(_) => None,
        };
        let next = reused.unwrap_or_else(|| Vec::with_capacity(self.batch_len));
        let full = std::mem::replace(&mut self.batch, next);
        if t.batches.send(full).is_err() {
            // The thread has ended, which only a panic makes it do: `drain` reports it.
            return self.drain();
        }
        Ok(())
    }

    /// Hands over what is left of the batch and waits for the counting thread to count it all,
    /// taking the counting back.
    fn drain(&mut self) -> Result<(), AppError> {
        if let Some([a, b]) = self.lent.as_ref().and_then(|l| l.take_back()) {
            self.counting = Some(a.join(b));
        }
        if self.thread.is_some() {
            self.hand_over()?;
        } else if !self.batch.is_empty() {
            // Steps batched but no thread yet (fewer than a batch): count them here.
            let c = self.counting.as_mut().ok_or_else(lost)?;
            c.count_batch(&self.batch, self.n);
            self.batch.clear();
        }
        if let Some(t) = self.thread.take() {
            drop(t.batches);
            let counting = t
                .handle
                .join()
                .map_err(|_| failure("the counting thread stopped with a panic".into()))?;
            self.counting = Some(counting);
        }
        Ok(())
    }

    /// The factor on every stress range of the specification's own section and curve: SCF ×
    /// thickness correction (a line of sections has one per node, [`Counting::node_factor`]).
    pub fn factor(&self) -> f64 {
        range_factor(&self.spec)
    }

    /// The counting (each node's curve and factor, the damage): `None` during a run while its
    /// thread holds it (`finish` and `save` take it back).
    pub fn counting(&self) -> Option<&Counting> {
        self.counting.as_ref()
    }

    /// The damage per node for a fibre, the larger of its top and bottom (`None` for a fibre not
    /// counted, or during a run while the counting thread holds the damage).
    pub fn damage_of(&self, fibre: Fibre) -> Option<Vec<f64>> {
        let k = self.spec.fibres.iter().position(|f| *f == fibre)?;
        let damage = &self.counting.as_ref()?.damage;
        let nf = self.spec.fibres.len();
        Some(
            (0..self.n)
                .map(|i| {
                    let j = (i * nf + k) * 2;
                    damage[j].max(damage[j + 1])
                })
                .collect(),
        )
    }

    /// The seconds counted (from the first counted step to the last).
    pub fn counted_seconds(&self) -> f64 {
        self.span.0.map_or(0.0, |a| self.span.1 - a)
    }
}

/// SCF × thickness correction of the specification's own section and curve.
fn range_factor(spec: &FatigueSpec) -> f64 {
    spec.scf * spec.curve.thickness_factor(spec.section.wall)
}

/// The counting is neither here nor on a thread: cannot happen (each path that lends it takes it
/// back or reports why not).
fn lost() -> AppError {
    failure("the counting was lost with its thread".into())
}

/// An error of the fatigue counting, named by the scene table it serves.
fn failure(message: String) -> AppError {
    AppError::Run {
        file: "[fatigue]".into(),
        message,
    }
}

impl Observer for Fatigue {
    fn name(&self) -> &'static str {
        "fatigue"
    }
    fn chores(&self) -> Option<catena_fe::partner::SharedChores> {
        let lent = Arc::clone(self.lent.as_ref()?);
        Some(catena_fe::partner::SharedChores(lent))
    }
    fn step(&mut self, _: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        self.take(s)?;
        Ok(Control::Continue)
    }
    fn finish(&mut self, _: &RunContext<'_>, _: Option<&Stop>) -> Result<(), AppError> {
        self.drain()?;
        self.counting.as_mut().ok_or_else(lost)?.finish();
        Ok(())
    }
    fn save(&mut self) -> Result<Value, AppError> {
        self.drain()?;
        let c = self.counting.as_ref().ok_or_else(lost)?;
        Ok(serde_json::to_value(Saved {
            counters: c.counters.clone(),
            damage: c.damage.clone(),
            first: self.span.0,
            last: self.span.1,
        })
        .unwrap_or(Value::Null))
    }
    fn restore(&mut self, v: &Value) -> Result<(), String> {
        let s: Saved = serde_json::from_value(v.clone()).map_err(|e| format!("fatigue: {e}"))?;
        self.drain().map_err(|e| e.to_string())?;
        let c = self
            .counting
            .as_mut()
            .ok_or("fatigue: the counting was lost")?;
        if s.counters.len() != c.counters.len() || s.damage.len() != c.damage.len() {
            return Err(
                "fatigue: the saved counters do not fit the scene's nodes and fibres".into(),
            );
        }
        c.counters = s.counters;
        c.damage = s.damage;
        self.span = (s.first, s.last);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::checks::fatigue::stress::PipeSection;
    use catena_fe::dynamics::DynState;
    use catena_fe::statics::LineResults;

    fn section() -> PipeSection {
        PipeSection {
            od: 0.5,
            wall: 0.05,
            contents_density: 0.0,
            internal_pressure: 0.0,
            water_density: 1025.0,
            gravity: 9.80665,
            water_depth: 100.0,
        }
    }

    fn view<'a>(k: u64, state: &'a DynState, results: &'a LineResults) -> StepView<'a> {
        StepView {
            t: k as f64,
            step: k,
            state,
            results,
            info: Default::default(),
            record: false,
            envelope: true,
        }
    }

    /// The thickness correction reaches the damage: a 50 mm wall (twice the reference 25 mm) on
    /// curve E in free corrosion (one slope, m = 3, log ā = 11.533, k = 0.20), 1000 cycles of
    /// ±100 kN·m at the outer fibre of a 0.5 m pipe. By hand: Δσ = 2·M·r/I, the factor
    /// 2^0.2 = 1.148698, D = 1000·(factor·Δσ)³/10^11.533, to 1e-9. Without the correction the
    /// damage is 2^0.6 = 1.516 times smaller.
    #[test]
    fn the_thickness_correction_reaches_the_damage_along_the_line() {
        let section = section();
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
        // Counted here and on a thread: the same damage to the bit (the thread's own test below).
        let mut f = Fatigue::with_thread(spec, 1, true);
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
            f.take(&view(k as u64, &state, &results)).expect("counted");
        }
        // The residue as `finish` counts it (half cycles).
        f.drain().expect("drained");
        f.counting.as_mut().expect("counting").finish();
        let (r, i) = (0.25, section.inertia());
        let range = 2.0 * 1e5 * r / i * 1e-6; // MPa
        let factor = 2f64.powf(0.2);
        let want = cycles as f64 * (factor * range).powi(3) / 10f64.powf(11.533);
        let got = f.damage_of(Fibre::Outer).expect("outer")[0];
        println!("range {range:.3} MPa, damage {got:.6e} (by hand {want:.6e})");
        assert!((f.factor() - factor).abs() < 1e-12, "{}", f.factor());
        assert!((got / want - 1.0).abs() < 1e-9, "{got} against {want}");
    }

    /// A line of `n` nodes of two sections (each node's own curve and factor: curve E at the
    /// nodes `thin` says, D on a thicker wall elsewhere), two fibres, counted from 3 s.
    fn two_sections(n: usize, thin: impl Fn(usize) -> bool) -> FatigueSpec {
        let thick = PipeSection {
            wall: 0.04,
            ..section()
        };
        let e = SnCurve::dnv("dnv-e-seawater-cp").expect("curve");
        let d = SnCurve::dnv("dnv-d-free-corrosion").expect("curve");
        FatigueSpec {
            curve: e,
            curve_name: "dnv-e-seawater-cp".into(),
            scf: 1.2,
            fibres: vec![Fibre::Outer, Fibre::Inner],
            design_factor: None,
            start: 3.0,
            section: section(),
            nodes: (0..n)
                .map(|i| {
                    if thin(i) {
                        (section(), e, 1.2)
                    } else {
                        (thick, d, 1.1)
                    }
                })
                .collect(),
        }
    }

    /// Results of `n` nodes, and a function that fills them with the next step's pseudo-random
    /// tension, moment and height (xorshift, the same sequence each time).
    fn random_steps(n: usize) -> (LineResults, impl FnMut(&mut LineResults)) {
        let results = LineResults {
            tension: vec![0.0; n],
            moment: vec![0.0; n],
            z: vec![0.0; n],
            ..LineResults::default()
        };
        let mut next = crate::run::lend::xorshift(0x2545_f491_4f6c_dd1du64);
        let step = move |r: &mut LineResults| {
            for i in 0..r.tension.len() {
                r.tension[i] = 2e5 + 1e5 * next();
                r.moment[i] = 1e5 * next();
                r.z[i] = -50.0 + next();
            }
        };
        (results, step)
    }

    /// The counting thread counts what the stepping thread would, to the bit: two fibres at five
    /// nodes of a line of two sections (each node's own curve and factor), 1000 steps of a
    /// pseudo-random tension, moment and height (15 batches and a part), counted on the stepping
    /// thread and on a thread, this one saved (the thread drained and restarted) at step 300 and
    /// restored into a third observer that counts the rest. Every counter and damage equal.
    #[test]
    fn the_counting_thread_counts_to_the_same_bits() {
        let n = 5;
        let spec = two_sections(n, |i| i < 2);
        let mut here = Fatigue::with_thread(spec.clone(), n, false);
        let mut there = Fatigue::with_thread(spec.clone(), n, true);
        let mut restored = Fatigue::with_thread(spec, n, true);
        let state = DynState::default();
        let (mut results, mut step) = random_steps(n);
        for k in 0..1000u64 {
            step(&mut results);
            let v = view(k, &state, &results);
            here.take(&v).expect("counted");
            there.take(&v).expect("counted");
            if k == 300 {
                let saved = there.save().expect("saved");
                restored.restore(&saved).expect("restored");
            } else if k > 300 {
                restored.take(&v).expect("counted");
            }
        }
        assert!(there.thread.is_some(), "the thread was not used");
        for f in [&mut here, &mut there, &mut restored] {
            f.drain().expect("drained");
            f.counting.as_mut().expect("counting").finish();
        }
        let (a, b, c) = (&here.counting, &there.counting, &restored.counting);
        let bits = |f: &Option<Counting>| -> Vec<u64> {
            f.as_ref()
                .expect("counting")
                .damage
                .iter()
                .map(|x| x.to_bits())
                .collect()
        };
        assert!(a.as_ref().expect("c").damage.iter().all(|x| *x > 0.0));
        assert_eq!(bits(a), bits(b), "threaded against the stepping thread");
        assert_eq!(bits(a), bits(c), "saved, restored and counted on");
        assert_eq!(a, b);
        assert_eq!(here.span, there.span);
    }

    /// The counting lent to a pair's waits ([`crate::run::lend`]) counts to the same bits as on the stepping
    /// thread, whoever counts each piece: two threads doing the chores of the two halves while the
    /// steps are handed over (their pieces racing the observer's), none at all (the observer counts
    /// each step when handed the next), and saved halfway and restored. 37 nodes of two sections:
    /// halves of 18 and 19 nodes, each two pieces of [`crate::run::lend::CHORE_NODES`] or fewer.
    #[test]
    fn the_pairs_chores_count_to_the_same_bits() {
        let n = 37;
        let spec = two_sections(n, |i| i % 3 == 0);
        let mut here = Fatigue::with_thread(spec.clone(), n, false);
        let mut chored = Fatigue::lent(spec.clone(), n);
        let mut alone = Fatigue::lent(spec.clone(), n);
        let mut restored = Fatigue::lent(spec, n);
        assert!(
            here.chores().is_none(),
            "only a lent counting leaves chores"
        );
        let chores = chored.chores().expect("chores");
        let state = DynState::default();
        let (mut results, mut step) = random_steps(n);
        let pieces = crate::run::lend::racing_chores(&chores, || {
            for k in 0..1000u64 {
                step(&mut results);
                let v = view(k, &state, &results);
                here.take(&v).expect("counted");
                chored.take(&v).expect("counted");
                alone.take(&v).expect("counted");
                if k == 300 {
                    let saved = alone.save().expect("saved");
                    restored.restore(&saved).expect("restored");
                } else if k > 300 {
                    restored.take(&v).expect("counted");
                }
                if k % 7 == 0 {
                    // Some steps wait for the chores (others are handed over mid-way).
                    std::thread::sleep(std::time::Duration::from_micros(50));
                }
            }
        });
        assert!(pieces > 100, "the chores were not done");
        for f in [&mut here, &mut chored, &mut alone, &mut restored] {
            f.drain().expect("drained");
            f.counting.as_mut().expect("counting").finish();
        }
        let bits = |f: &Fatigue| -> Vec<u64> {
            let c = f.counting.as_ref().expect("counting");
            c.damage.iter().map(|x| x.to_bits()).collect()
        };
        assert!(here
            .counting
            .as_ref()
            .expect("c")
            .damage
            .iter()
            .all(|x| *x > 0.0));
        assert_eq!(bits(&here), bits(&chored), "counted in the chores");
        assert_eq!(bits(&here), bits(&alone), "lent, no chores done");
        assert_eq!(
            bits(&here),
            bits(&restored),
            "lent, saved, restored and counted on"
        );
        assert_eq!(here.counting, chored.counting);
        assert_eq!(here.span, chored.span);
    }
}
