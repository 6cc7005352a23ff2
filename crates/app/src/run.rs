//! A dynamic run: the statics, then the dynamics, each converged step handed to the observers.
//!
//! [`run`] takes a solved [`StaticRun`], builds the [`DynamicModel`] (line, placement, environment,
//! top motion, settings), starts from rest at the static configuration (or from a checkpoint), and
//! steps to the end. The built-in observers ([`Envelopes`], [`Gauges`], [`TopHistory`]) are part of
//! the result; the caller adds its own (HDF5 recorder, progress, checkpoints, a signal watcher). A
//! step that fails, or an observer that asks to stop, ends the run early: the result then says
//! where it stopped and why ([`Stop`]), and every observer has seen every converged step up to it.

use std::collections::BTreeMap;
use std::time::Instant;

use catena_fe::assembly::LineResults;
use catena_fe::dynamics::{self, DynWorkspace, DynamicModel, StepInfo};

use crate::checkpoint::{Checkpoint, VERSION};
use crate::error::AppError;
use crate::fatigue_observer::Fatigue;
use crate::observe::{
    Control, Envelopes, Gauges, Observer, RunContext, StepView, Stop, TopHistory,
};
use crate::scene::riser::DynamicSpec;
use crate::statics::{self, StaticRun};

/// The result of a dynamic run.
#[derive(Debug, Clone)]
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
    /// Why the run ended before its duration, if it did.
    pub stop: Option<Stop>,
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

/// Runs the dynamics of a solved scene, handing every converged step to the built-in observers and
/// to `extra`.
pub fn run(
    statics: StaticRun,
    extra: &mut [&mut dyn Observer],
    opts: RunOptions,
) -> Result<DynamicRun, AppError> {
    let (spec, dm) = prepare(&statics)?;
    let file = statics.scene.file.clone();
    let t0 = Instant::now();
    let n = dm.line.nodes();
    let mut ws = DynWorkspace::new(&dm.line).map_err(|source| AppError::Solver {
        file: file.clone(),
        source,
    })?;
    let mut state = dynamics::initial_state(&dm, &statics.u, &mut ws);
    let ei: Vec<f64> = dm.line.elements.iter().map(|e| e.section.ei).collect();
    let mut envelopes = Envelopes::new(&ei, spec.section);
    let mut gauges = Gauges::new(&spec.gauges);
    let mut top = TopHistory::default();
    let mut fatigue = spec.fatigue.clone().map(|f| Fatigue::new(f, n));
    let mut res = LineResults::new(n);
    let n_steps = (spec.duration / spec.dt).round() as u64;
    let mut first_step = 1;
    let restarted = opts.restart.is_some();
    if let Some(cp) = &opts.restart {
        cp.check(&opts.restart_file, &statics.scene.text, &dm, &spec)?;
        let bad = |what: String| AppError::Checkpoint {
            file: opts.restart_file.clone(),
            what,
        };
        state = cp.state.clone();
        match &cp.solver {
            Some(m) => ws.restore_solver_memory(m).map_err(bad)?,
            None => ws.forget_factorisation(),
        }
        {
            let builtin = builtins(&mut envelopes, &mut gauges, &mut top, &mut fatigue);
            for o in builtin.into_iter().flatten() {
                let saved = cp
                    .observers
                    .get(o.name())
                    .ok_or_else(|| bad(format!("it holds no state for `{}`", o.name())))?;
                o.restore(saved).map_err(bad)?;
            }
            // An observer the checkpointed run did not have starts from nothing (it decides
            // whether it can).
            for o in extra.iter_mut() {
                let saved = cp
                    .observers
                    .get(o.name())
                    .unwrap_or(&serde_json::Value::Null);
                o.restore(saved).map_err(bad)?;
            }
        }
        first_step = cp.step + 1;
        // The results of the restored State: the forces at it are re-evaluated (the workspace of a
        // restored run holds no evaluation yet); nothing is committed.
        dynamics::refresh(&dm, &state, &mut ws);
    }
    dynamics::results(&dm, &state, &ws, &mut res);
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
    {
        let builtin = builtins(&mut envelopes, &mut gauges, &mut top, &mut fatigue);
        each(builtin, extra, |o| o.start(&ctx, &first, restarted))?;
    }
    let (mut iterations, mut cuts, mut retries) = (0usize, 0u32, 0u32);
    let mut cut_log = Vec::new();
    let mut stop = None;
    let mut steps = first_step - 1;
    for k in first_step..=n_steps {
        match dynamics::advance(&dm, &mut state, &mut ws, spec.dt) {
            Ok(info) => {
                iterations += info.iterations;
                cuts += info.cuts;
                if let Some(c) = info.last_cut {
                    if cut_log.len() < MAX_CUT_LOG {
                        cut_log.push(CutEvent {
                            t: (k - 1) as f64 * spec.dt,
                            cuts: info.cuts,
                            dt: c.dt,
                            residual: c.residual,
                            node: c.node,
                            arc: dm.line.arc[c.node],
                        });
                    }
                }
                retries += info.retries;
                steps = k;
                state.t = k as f64 * spec.dt;
                dynamics::results(&dm, &state, &ws, &mut res);
                if let Some((field, node)) =
                    catena_fe::assembly::first_non_finite(&res, &state.u, &state.v, &state.a)
                {
                    stop = Some(Stop::NonFinite {
                        t: state.t,
                        field,
                        node,
                        arc: dm.line.arc[node],
                    });
                    // The step is not handed to the observers: the run ends at the one before.
                    state.t = (k - 1) as f64 * spec.dt;
                    steps = k - 1;
                    break;
                }
                let view = StepView {
                    t: state.t,
                    step: k,
                    state: &state,
                    results: &res,
                    info,
                    record: k as usize % spec.output_every == 0,
                    envelope: state.t >= spec.envelope_start - 1e-9 * spec.dt,
                };
                let mut wants = false;
                {
                    let builtin = builtins(&mut envelopes, &mut gauges, &mut top, &mut fatigue);
                    each(builtin, extra, |o| {
                        if let Control::Stop(reason) = o.step(&ctx, &view)? {
                            stop = Some(Stop::Interrupted(reason));
                        }
                        wants |= o.wants_checkpoint(k);
                        Ok(())
                    })?;
                }
                if wants {
                    let mut observers = BTreeMap::new();
                    observers.insert(envelopes.name().to_string(), envelopes.save()?);
                    observers.insert(gauges.name().to_string(), gauges.save()?);
                    observers.insert(top.name().to_string(), top.save()?);
                    if let Some(f) = fatigue.as_mut() {
                        observers.insert(f.name().to_string(), f.save()?);
                    }
                    for o in extra.iter_mut() {
                        observers.insert(o.name().to_string(), o.save()?);
                    }
                    let cp = Checkpoint {
                        catena_version: VERSION.to_string(),
                        scene_file: file.clone(),
                        scene_hash: crate::scene::text_hash(&statics.scene.text),
                        step: k,
                        state: state.clone(),
                        solver: ws.solver_memory(),
                        observers,
                    };
                    for o in extra.iter_mut() {
                        if o.wants_checkpoint(k) {
                            o.checkpoint(&cp)?;
                        }
                    }
                }
                if stop.is_some() {
                    break;
                }
                if opts.stop_after == Some(k) && k < n_steps {
                    stop = Some(Stop::StoppedAfter(k));
                    break;
                }
            }
            Err(e) => {
                stop = Some(Stop::Failed(e));
                break;
            }
        }
    }
    {
        let builtin = builtins(&mut envelopes, &mut gauges, &mut top, &mut fatigue);
        each(builtin, extra, |o| o.finish(&ctx, stop.as_ref()))?;
    }
    Ok(DynamicRun {
        t_reached: steps as f64 * spec.dt,
        steps,
        statics,
        spec,
        model: dm,
        envelopes,
        gauges,
        top,
        fatigue,
        iterations,
        cuts,
        retries,
        cut_log,
        wall_seconds: t0.elapsed().as_secs_f64(),
        stop,
    })
}

/// The built-in observers, in their fixed order (the optional ones `None` when absent).
type Builtins<'a> = [Option<&'a mut (dyn Observer + 'static)>; 4];

fn builtins<'a>(
    envelopes: &'a mut Envelopes,
    gauges: &'a mut Gauges,
    top: &'a mut TopHistory,
    fatigue: &'a mut Option<Fatigue>,
) -> Builtins<'a> {
    [
        Some(envelopes),
        Some(gauges),
        Some(top),
        fatigue.as_mut().map(|f| f as &mut (dyn Observer + 'static)),
    ]
}

/// Calls `f` on every observer: the built-in ones, then the caller's.
fn each(
    builtin: Builtins<'_>,
    extra: &mut [&mut dyn Observer],
    mut f: impl FnMut(&mut dyn Observer) -> Result<(), AppError>,
) -> Result<(), AppError> {
    for o in builtin.into_iter().flatten() {
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
