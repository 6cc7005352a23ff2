//! A dynamic run: the statics, then the dynamics, each converged step handed to the observers.
//!
//! [`run`] takes a solved [`StaticRun`], builds the [`DynamicModel`] (line, placement, environment,
//! top motion, settings), starts from rest at the static configuration (or from a checkpoint), and
//! steps to the end. The built-in observers ([`Envelopes`], [`Gauges`], [`TopHistory`]) are part of
//! the result; the caller adds its own (HDF5 recorder, progress, checkpoints, a signal watcher). A
//! step that fails, or an observer that asks to stop, ends the run early: the result then says
//! where it stopped and why ([`Stop`]), and every observer has seen every converged step up to it.
//!
//! The layer's modules, in the order they depend on each other: [`statics`] (the static
//! configuration the run starts from), [`checkpoint`] (what a restart needs), [`observe`] (the
//! `Observer` trait and the run's own observers: envelopes, gauges, top history, checkpoints,
//! ), [`records`] (the recorded steps, and in memory), [`observers`] (the observers that apply the checks), [`outputs`] (the
//! registry of built-in outputs a scene asks for), and this module, which drives them.

pub mod as_laid;
pub mod checkpoint;
pub mod cores;
pub mod lay;
pub mod lend;
pub mod observe;
pub mod observers;
pub mod outputs;
pub mod records;
pub mod statics;

pub use cores::{default_threads, Cores};

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

use catena_fe::assembly::LineResults;
use catena_fe::dynamics::{self, Drive, DynWorkspace, DynamicModel, StepInfo};

use crate::error::AppError;
use crate::run::checkpoint::{Checkpoint, VERSION};
use crate::run::observe::{
    Control, Envelopes, Gauges, Observer, RunContext, StepView, Stop, TopHistory,
};
use crate::run::observers::fatigue::Fatigue;
use crate::run::outputs::{Outputs, Setup};
use crate::scene::riser::DynamicSpec;
use statics::StaticRun;

/// The result of a dynamic run.
#[derive(Debug)]
pub struct DynamicRun {
    /// The statics it started from.
    pub statics: StaticRun,
    /// The dynamic specification (gauges placed).
    pub spec: DynamicSpec,
    /// The dynamic Model.
    pub model: DynamicModel,
    /// Per-node envelopes from `envelope_start`, every step.
    pub envelopes: Envelopes,
    /// The gauges.
    pub gauges: Gauges,
    /// The top end's history.
    pub top: TopHistory,
    /// Fatigue damage, if the scene has a `[fatigue]` table.
    pub fatigue: Option<Fatigue>,
    /// The other registered outputs ([`crate::run::outputs::BUILTINS`]; see [`DynamicRun::output`]).
    pub outputs: Outputs,
    /// Converged steps of `dynamic.time_step` (the time reached is `steps·Δt`).
    pub steps: u64,
    /// The time reached, s.
    pub t_reached: f64,
    /// Newton iterations in all.
    pub iterations: usize,
    /// Step cuts in all.
    pub cuts: u32,
    /// Predictor retries in all (see `catena_fe::dynamics`).
    pub retries: u32,
    /// The steps that were cut, when, where and how much (the first [`MAX_CUT_LOG`]).
    pub cut_log: Vec<CutEvent>,
    /// Wall time of the dynamics, s.
    pub wall_seconds: f64,
    /// The threads that stepped the line: 2 when a pair did for any step ([`Drive`]:
    /// [`RunOptions::threads`] from 2, and where two are faster than one), else 1.
    pub stepping_threads: usize,
    /// The steps two threads took ([`Drive`]: the others, one thread).
    pub steps_on_two: u64,
    /// Why the run ended before its duration, if it did.
    pub stop: Option<Stop>,
    /// What the last converged step leaves for a run that continues from rest (a storm sequence).
    pub carry: dynamics::Carry,
}

/// The cut steps kept in [`DynamicRun::cut_log`] (the count in [`DynamicRun::cuts`] is of all).
pub const MAX_CUT_LOG: usize = 1000;

/// A step that had to be cut: when, where and how much.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutEvent {
    /// The time at the start of the step, s.
    pub t: f64,
    /// The cuts the step needed.
    pub cuts: u32,
    /// The Δt of the last attempt that failed, s.
    pub dt: f64,
    /// That attempt's relative residual.
    pub residual: f64,
    /// The node with the largest residual entry, and its arc length from the top, m.
    pub node: usize,
    /// The node's arc length, m.
    pub arc: f64,
}

impl DynamicRun {
    /// Where the steps were cut: the arc lengths (m) of the nodes that failed most often, with the
    /// number of cut steps at each, most first (at most `n`).
    pub fn cut_hotspots(&self, n: usize) -> Vec<(f64, usize)> {
        let mut by_node: Vec<(usize, usize)> = Vec::new();
        for c in &self.cut_log {
            match by_node.iter_mut().find(|(node, _)| *node == c.node) {
                Some(e) => e.1 += 1,
                None => by_node.push((c.node, 1)),
            }
        }
        by_node.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        by_node
            .into_iter()
            .take(n)
            .map(|(node, count)| (self.model.line.arc[node], count))
            .collect()
    }

    /// A registered output of type `T` other than the envelopes, gauges, top history and fatigue
    /// (which are fields), if the run has one.
    pub fn output<T: std::any::Any>(&self) -> Option<&T> {
        self.outputs.get::<T>()
    }

    /// Whether the run reached its duration.
    pub fn completed(&self) -> bool {
        self.stop.is_none()
    }
}

/// Options of a dynamic run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Continue from this checkpoint instead of the statics (`restart_file` names it).
    pub restart: Option<Checkpoint>,
    /// The checkpoint's file, for messages.
    pub restart_file: String,
    /// Stop (successfully) after this many time steps, e.g. to end a job at a checkpoint.
    pub stop_after: Option<u64>,
    /// Start at rest from what an earlier run left ([`dynamics::Carry`]: positions, seabed
    /// histories, friction anchors) instead of the statics' state: a storm sequence's next storm.
    /// The carry must be of this scene's Model (the same line, mesh and seabed law).
    pub start: Option<dynamics::Carry>,
    /// The threads this run may keep busy. From 2 beside the threads its observers keep busy
    /// ([`Observer::busy_threads`]: the HDF5 writer's, when it compresses or records every
    /// step), the line may be stepped on two threads where the scene allows it
    /// ([`dynamics::Pair`]; a pipe-lay's window: [`crate::run::lay::LayOptions::threads`]), step
    /// by step where two are measured to be faster than one ([`Drive`]); the fatigue damage is
    /// counted on a thread of its own ([`crate::run::observers::fatigue`]) where one is left
    /// over, else on the stepping thread. `None` takes [`default_threads`]: the machine's cores
    /// less those the runs under way in this process hold, at least one ([`cores`]). A
    /// study running `jobs` runs side by side gives each
    /// [`crate::studies::schedule::threads_per_run`], so that its runs do not oversubscribe the
    /// cores. The results are the same to the bit whatever the number (only where the work is
    /// done changes). The plots of `catena run` are drawn on threads of their own.
    pub threads: Option<usize>,
}

impl RunOptions {
    /// The default options but for the threads the run may keep busy (`None`:
    /// [`default_threads`]): what each run of a study gets.
    pub fn with_threads(threads: Option<usize>) -> Self {
        Self {
            threads,
            ..Self::default()
        }
    }
}

/// Places the gauges defined by a touchdown rule: midway (in arc length) between the static
/// touchdown point and the one with the top raised by `lift` (a second static solve).
pub fn resolve_gauges(st: &StaticRun, spec: &mut DynamicSpec) -> Result<(), AppError> {
    for (i, g) in spec.gauges.iter_mut().enumerate() {
        if let Some(lift) = g.midway_touchdown_lift {
            let fail = |what: &str| AppError::Run {
                file: st.scene.file.clone(),
                message: format!("key `gauge[{i}].midway_touchdown_lift`: {what}"),
            };
            let t0 = st
                .summary
                .touchdown_arc
                .ok_or_else(|| fail("the line does not touch down in the statics"))?;
            let mut raised = st.scene.clone();
            raised.ends.top.1 += lift;
            let r = statics::solve(raised)
                .map_err(|e| fail(&format!("the static solve with the top raised failed: {e}")))?;
            let t1 = r
                .summary
                .touchdown_arc
                .ok_or_else(|| fail("with the top raised, the line no longer touches down"))?;
            g.arc = 0.5 * (t0 + t1);
        }
    }
    Ok(())
}

/// The dynamic specification of a solved scene, with its gauges placed, and its dynamic Model.
pub fn prepare(st: &StaticRun) -> Result<(DynamicSpec, DynamicModel), AppError> {
    let mut spec = st.scene.dynamic.clone().ok_or_else(|| AppError::Run {
        file: st.scene.file.clone(),
        message: "key `dynamic`: expected a [dynamic] table for `catena run` (use `catena static` for statics alone)".into(),
    })?;
    resolve_gauges(st, &mut spec)?;
    let model = DynamicModel {
        line: st.model.clone(),
        placement: st.placement.clone(),
        environment: spec.environment.clone(),
        motion: spec.motion.clone(),
        vessel: spec.vessel.clone(),
        structural_damping: spec.structural_damping,
        settings: spec.settings,
    };
    Ok((spec, model))
}

/// The whole path in one call: the statics of `scene`, then its dynamics, every converged step
/// handed to the built-in observers and to `extra` (what a study or a binding calls).
pub fn simulate(
    scene: crate::scene::riser::RiserScene,
    extra: &mut [&mut dyn Observer],
    opts: RunOptions,
) -> Result<DynamicRun, AppError> {
    run(statics::solve(scene)?, extra, opts)
}

/// Runs the dynamics of a solved scene, handing every converged step to the built-in outputs
/// ([`crate::run::outputs`]) and to `extra`.
pub fn run(
    statics: StaticRun,
    extra: &mut [&mut dyn Observer],
    opts: RunOptions,
) -> Result<DynamicRun, AppError> {
    let (spec, dm) = prepare(&statics)?;
    // Shared with the second stepping thread during each step, when there is one.
    let dm = Arc::new(dm);
    let t0 = Instant::now();
    let n = dm.line.nodes();
    let mut ws = DynWorkspace::new(&dm.line).map_err(|source| AppError::Solver {
        file: statics.scene.file.clone(),
        source,
    })?;
    let mut state = match &opts.start {
        Some(c) => dynamics::carried_state(&dm, c, &mut ws).map_err(|what| AppError::Run {
            file: statics.scene.file.clone(),
            message: format!("the carried state does not fit this scene: {what}"),
        })?,
        None => match &statics.scene.as_laid {
            Some(al) => as_laid::start_state(&dm, &statics.u, (&statics.scene, al), &mut ws)?.0,
            None => dynamics::initial_state(&dm, &statics.u, &mut ws),
        },
    };
    // Held until the run ends: a run beside it in this process takes the cores left ([`cores`]).
    let cores = Cores::take(opts.threads);
    let threads = cores.threads();
    let mut res = LineResults::new(n);
    let mut first_step = 1;
    let restarted = opts.restart.is_some();
    if let Some(cp) = &opts.restart {
        restore(cp, &opts, &statics, (&dm, &spec), (&mut state, &mut ws))?;
        first_step = cp.step + 1;
        // The results of the restored State: the forces at it are re-evaluated (the workspace of a
        // restored run holds no evaluation yet); nothing is committed.
        dynamics::refresh(&dm, &state, &mut ws);
    }
    dynamics::results(&dm, &state, &ws, &mut res);
    // Two threads step the line where the run may keep two busy beside the threads its observers
    // keep busy (the HDF5 writer's) and the scene allows it ([`Pair`]); the fatigue counting then
    // keeps a thread of its own only from three.
    let others: usize = extra.iter().map(|o| o.busy_threads()).sum();
    let stepping = threads.saturating_sub(others);
    // Two threads asked for are tried first whatever the machine's idle time, later only
    // beside an idle core ([`Drive::asked`]).
    let mut drive = match opts.threads {
        Some(_) => Drive::asked(stepping),
        None => Drive::new(stepping),
    };
    let on_two = drive.start(&dm, &state, &mut ws);
    let mut outputs = Outputs::build(&Setup {
        spec: &spec,
        model: &dm,
        threads: threads - usize::from(on_two),
        paired: on_two,
    });
    // The chores the observers leave: the pair's two threads do them while they wait.
    let mut chores: Vec<_> = outputs.iter_mut().filter_map(|o| o.chores()).collect();
    ws.set_chores(match chores.len() {
        0 | 1 => chores.pop(),
        _ => Some(catena_fe::partner::SharedChores(Arc::new(
            catena_fe::partner::ChoreList(chores.into_iter().map(|c| c.0).collect()),
        ))),
    });
    if let Some(cp) = &opts.restart {
        restore_observers(cp, &opts.restart_file, &mut outputs, extra)?;
    }
    let ctx = RunContext {
        statics: &statics,
        model: &dm,
        spec: &spec,
    };
    let first = StepView {
        t: state.t,
        step: first_step - 1,
        state: &state,
        results: &res,
        info: StepInfo::default(),
        record: true,
        envelope: state.t >= spec.envelope_start - 1e-9 * spec.dt,
    };
    each(&mut outputs, extra, |o| o.start(&ctx, &first, restarted))?;
    let mut stepper = Stepper {
        ctx: &ctx,
        state: &mut state,
        ws: &mut ws,
        drive: &mut drive,
        res: &mut res,
        outputs: &mut outputs,
        tally: Tally {
            steps: first_step - 1,
            ..Tally::default()
        },
    };
    let stop = stepper.steps(first_step, extra, &opts);
    let tally = std::mem::take(&mut stepper.tally);
    let (steps_on, _) = drive.tally();
    let stepping_threads = 1 + usize::from(steps_on[1] > 0);
    let steps_on_two = steps_on[1];
    drive.stop(&dm, &mut ws);
    let stop = stop?;
    each(&mut outputs, extra, |o| o.finish(&ctx, stop.as_ref()))?;
    let envelopes = outputs
        .take::<Envelopes>()
        .unwrap_or_else(|| Envelopes::new(&[], None));
    let gauges = outputs.take::<Gauges>().unwrap_or_else(|| Gauges::new(&[]));
    let top = outputs.take::<TopHistory>().unwrap_or_default();
    let fatigue = outputs.take::<Fatigue>();
    Ok(DynamicRun {
        t_reached: tally.steps as f64 * spec.dt,
        steps: tally.steps,
        statics,
        spec,
        model: Arc::unwrap_or_clone(dm),
        envelopes,
        gauges,
        top,
        fatigue,
        outputs,
        iterations: tally.iterations,
        cuts: tally.cuts,
        retries: tally.retries,
        cut_log: tally.cut_log,
        wall_seconds: t0.elapsed().as_secs_f64(),
        stepping_threads,
        steps_on_two,
        stop,
        carry: state.carry(),
    })
}

/// Takes a checkpoint's State and solver memory after checking it against the run.
fn restore(
    cp: &Checkpoint,
    opts: &RunOptions,
    statics: &StaticRun,
    (dm, spec): (&DynamicModel, &DynamicSpec),
    (state, ws): (&mut dynamics::DynState, &mut DynWorkspace),
) -> Result<(), AppError> {
    cp.check(&opts.restart_file, &statics.scene.text, dm, spec)?;
    *state = cp.state.clone();
    match &cp.solver {
        Some(m) => ws
            .restore_solver_memory(m)
            .map_err(|what| AppError::Checkpoint {
                file: opts.restart_file.clone(),
                what,
            }),
        None => {
            ws.forget_factorisation();
            Ok(())
        }
    }
}

/// Gives every observer its state back from a checkpoint, by name: a built-in output must find its
/// own; an observer of the caller's that the checkpointed run did not have starts from nothing (it
/// decides whether it can).
fn restore_observers(
    cp: &Checkpoint,
    file: &str,
    outputs: &mut Outputs,
    extra: &mut [&mut dyn Observer],
) -> Result<(), AppError> {
    let bad = |what: String| AppError::Checkpoint {
        file: file.to_string(),
        what,
    };
    for o in outputs.iter_mut() {
        let saved = cp
            .observers
            .get(o.name())
            .ok_or_else(|| bad(format!("it holds no state for `{}`", o.name())))?;
        o.restore(saved).map_err(bad)?;
    }
    for o in extra.iter_mut() {
        let saved = cp
            .observers
            .get(o.name())
            .unwrap_or(&serde_json::Value::Null);
        o.restore(saved).map_err(bad)?;
    }
    Ok(())
}

/// What the steps took, counted over the run.
#[derive(Debug, Default)]
struct Tally {
    steps: u64,
    iterations: usize,
    cuts: u32,
    retries: u32,
    cut_log: Vec<CutEvent>,
}

impl Tally {
    /// Counts a converged step `k` (starting at `t`).
    fn add(&mut self, k: u64, t: f64, info: &StepInfo, arc: &[f64]) {
        self.iterations += info.iterations;
        self.cuts += info.cuts;
        self.retries += info.retries;
        if let Some(c) = info.last_cut {
            if self.cut_log.len() < MAX_CUT_LOG {
                self.cut_log.push(CutEvent {
                    t,
                    cuts: info.cuts,
                    dt: c.dt,
                    residual: c.residual,
                    node: c.node,
                    arc: arc[c.node],
                });
            }
        }
        self.steps = k;
    }
}

/// The stepping of a run: its Model and specification, State, Workspace, results and outputs.
struct Stepper<'a, 'c> {
    ctx: &'c RunContext<'c>,
    state: &'a mut dynamics::DynState,
    ws: &'a mut DynWorkspace,
    /// One thread or two for each step ([`Drive`]).
    drive: &'a mut Drive,
    res: &'a mut LineResults,
    outputs: &'a mut Outputs,
    tally: Tally,
}

impl Stepper<'_, '_> {
    /// Steps from `first` to the end of the run, every converged step handed to every observer;
    /// returns why the run stopped early, if it did.
    fn steps(
        &mut self,
        first: u64,
        extra: &mut [&mut dyn Observer],
        opts: &RunOptions,
    ) -> Result<Option<Stop>, AppError> {
        let (dm, spec) = (self.ctx.model, self.ctx.spec);
        let n_steps = (spec.duration / spec.dt).round() as u64;
        for k in first..=n_steps {
            let step = self.drive.advance(dm, self.state, self.ws, spec.dt);
            let info = match step {
                Ok(info) => info,
                Err(e) => return Ok(Some(Stop::Failed(e))),
            };
            self.tally
                .add(k, (k - 1) as f64 * spec.dt, &info, &dm.line.arc);
            self.state.t = k as f64 * spec.dt;
            dynamics::results(dm, self.state, self.ws, self.res);
            if let Some((field, node)) = catena_fe::assembly::first_non_finite(
                self.res,
                &self.state.u,
                &self.state.v,
                &self.state.a,
            ) {
                // The step is not handed to the observers: the run ends at the one before.
                self.state.t = (k - 1) as f64 * spec.dt;
                self.tally.steps = k - 1;
                return Ok(Some(Stop::NonFinite {
                    t: k as f64 * spec.dt,
                    field,
                    node,
                    arc: dm.line.arc[node],
                }));
            }
            let view = StepView {
                t: self.state.t,
                step: k,
                state: self.state,
                results: self.res,
                info,
                record: k as usize % spec.output_every == 0,
                envelope: self.state.t >= spec.envelope_start - 1e-9 * spec.dt,
            };
            let (mut wants, mut stop) = (false, None);
            each(self.outputs, extra, |o| {
                if let Control::Stop(reason) = o.step(self.ctx, &view)? {
                    stop = Some(Stop::Interrupted(reason));
                }
                wants |= o.wants_checkpoint(k);
                Ok(())
            })?;
            if wants {
                self.checkpoint(k, extra)?;
            }
            if stop.is_some() {
                return Ok(stop);
            }
            if opts.stop_after == Some(k) && k < n_steps {
                return Ok(Some(Stop::StoppedAfter(k)));
            }
        }
        Ok(None)
    }

    /// A checkpoint after step `k`: the State, the solver memory and every observer's state by
    /// name, handed to the observers that asked for it.
    fn checkpoint(&mut self, k: u64, extra: &mut [&mut dyn Observer]) -> Result<(), AppError> {
        let mut observers = BTreeMap::new();
        for o in self.outputs.iter_mut() {
            observers.insert(o.name().to_string(), o.save()?);
        }
        for o in extra.iter_mut() {
            observers.insert(o.name().to_string(), o.save()?);
        }
        let scene = &self.ctx.statics.scene;
        let cp = Checkpoint {
            catena_version: VERSION.to_string(),
            scene_file: scene.file.clone(),
            scene_hash: crate::scene::text_hash(&scene.text),
            step: k,
            state: self.state.clone(),
            solver: self.drive.solver_memory(self.ws),
            observers,
        };
        for o in extra.iter_mut() {
            if o.wants_checkpoint(k) {
                o.checkpoint(&cp)?;
            }
        }
        Ok(())
    }
}

/// Calls `f` on every observer: the built-in outputs, then the caller's.
fn each(
    outputs: &mut Outputs,
    extra: &mut [&mut dyn Observer],
    mut f: impl FnMut(&mut dyn Observer) -> Result<(), AppError>,
) -> Result<(), AppError> {
    for o in outputs.iter_mut() {
        f(o)?;
    }
    for o in extra.iter_mut() {
        f(&mut **o)?;
    }
    Ok(())
}

/// Key numbers of a run over its envelope window, from every step: `(largest moment range, its arc
/// length, top tension minimum, maximum)`; NaN where nothing was measured (no step in the window).
pub fn key_numbers(r: &DynamicRun) -> (f64, f64, f64, f64) {
    let range = r.envelopes.moment.range();
    let mut best: Option<(f64, f64)> = None;
    for (i, v) in range.iter().enumerate() {
        if v.is_finite() && best.is_none_or(|b| *v > b.0) {
            best = Some((*v, r.model.line.arc[i]));
        }
    }
    let (tmin, tmax) = r.top.tension_extremes;
    (
        best.map_or(f64::NAN, |b| b.0),
        best.map_or(f64::NAN, |b| b.1),
        tmin.unwrap_or(f64::NAN),
        tmax.unwrap_or(f64::NAN),
    )
}
