//! `catena run CASE.toml --out DIR`: the statics, then the dynamics.
//!
//! Writes `DIR/results.h5` (`/static` and `/dynamic`, streamed in chunks), `DIR/summary.json` (static
//! summary, run statistics, per-node envelopes of moment and tension from `envelope_start`, gauge
//! extremes), `DIR/static.png`, `DIR/dynamic.png` (envelopes and ranges along the line, top tension
//! history) and, with gauges, `DIR/gauges.png` (moment at each gauge against the top height, pull-up
//! and lay-down coloured apart). A progress bar shows on a terminal.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use catena_fe::dynamics::{self, DynWorkspace, Snapshot};
use serde_json::json;

use crate::error::AppError;
use crate::h5::{Record, Recorder};
use crate::scene::riser::DynamicSpec;
use crate::statics_cmd::{self, StaticRun};

/// Per-node envelopes.
#[derive(Debug, Clone, PartialEq)]
pub struct Envelopes {
    /// Minimum bending moment, N·m.
    pub moment_min: Vec<f64>,
    /// Maximum bending moment, N·m.
    pub moment_max: Vec<f64>,
    /// Minimum effective tension, N.
    pub tension_min: Vec<f64>,
    /// Maximum effective tension, N.
    pub tension_max: Vec<f64>,
    /// Maximum penetration, m.
    pub penetration_max: Vec<f64>,
    /// Minimum penetration, m (negative: clear of the seabed).
    pub penetration_min: Vec<f64>,
}

impl Envelopes {
    fn new(n: usize) -> Self {
        Self {
            moment_min: vec![f64::INFINITY; n],
            moment_max: vec![f64::NEG_INFINITY; n],
            tension_min: vec![f64::INFINITY; n],
            tension_max: vec![f64::NEG_INFINITY; n],
            penetration_max: vec![f64::NEG_INFINITY; n],
            penetration_min: vec![f64::INFINITY; n],
        }
    }
    fn update(&mut self, s: &Snapshot) {
        for i in 0..s.moment.len() {
            self.moment_min[i] = self.moment_min[i].min(s.moment[i]);
            self.moment_max[i] = self.moment_max[i].max(s.moment[i]);
            self.tension_min[i] = self.tension_min[i].min(s.tension[i]);
            self.tension_max[i] = self.tension_max[i].max(s.tension[i]);
            self.penetration_max[i] = self.penetration_max[i].max(s.penetration[i]);
            self.penetration_min[i] = self.penetration_min[i].min(s.penetration[i]);
        }
    }
    /// The moment range at each node.
    pub fn moment_range(&self) -> Vec<f64> {
        self.moment_max
            .iter()
            .zip(&self.moment_min)
            .map(|(a, b)| a - b)
            .collect()
    }
    /// The tension range at each node.
    pub fn tension_range(&self) -> Vec<f64> {
        self.tension_max
            .iter()
            .zip(&self.tension_min)
            .map(|(a, b)| a - b)
            .collect()
    }
}

/// Histories kept in memory for the summary and plots (at the output interval).
#[derive(Debug, Clone, Default)]
pub struct Histories {
    /// Time, s.
    pub t: Vec<f64>,
    /// Top height, m.
    pub top_z: Vec<f64>,
    /// Top tension, N.
    pub top_tension: Vec<f64>,
    /// Per gauge: bending moment, N·m.
    pub gauge_moment: Vec<Vec<f64>>,
    /// Per gauge: tension, N.
    pub gauge_tension: Vec<Vec<f64>>,
}

/// The result of a dynamic run.
#[derive(Debug)]
pub struct DynamicRun {
    /// The statics it started from.
    pub statics: StaticRun,
    /// The dynamic specification.
    pub spec: DynamicSpec,
    /// Envelopes from `envelope_start`.
    pub envelopes: Envelopes,
    /// Histories.
    pub hist: Histories,
    /// Converged steps.
    pub steps: u64,
    /// Newton iterations in all.
    pub iterations: usize,
    /// Step cuts in all.
    pub cuts: u32,
    /// Predictor retries in all (see `catena_fe::dynamics`).
    pub retries: u32,
    /// Wall time of the dynamics, s.
    pub wall_seconds: f64,
    /// The error that stopped the run early, if any.
    pub error: Option<String>,
}

/// Linear interpolation of nodal values at an arc length.
fn at_arc(arc: &[f64], v: &[f64], s: f64) -> f64 {
    let i = arc.partition_point(|a| *a < s).clamp(1, arc.len() - 1);
    let f = ((s - arc[i - 1]) / (arc[i] - arc[i - 1])).clamp(0.0, 1.0);
    v[i - 1] + f * (v[i] - v[i - 1])
}

/// Places the gauges defined by a touchdown rule: midway (in arc length) between the static touchdown
/// point and the one with the top raised by `lift` (a second static solve).
pub fn resolve_gauges(statics: &StaticRun, spec: &mut DynamicSpec) -> Result<(), AppError> {
    for (i, g) in spec.gauges.iter_mut().enumerate() {
        if let Some(lift) = g.midway_touchdown_lift {
            let fail = |what: &str| AppError::Run {
                file: statics.scene.file.clone(),
                message: format!("key `gauge[{i}].midway_touchdown_lift`: {what}"),
            };
            let t0 = statics
                .summary
                .touchdown_arc
                .ok_or_else(|| fail("the line does not touch down in the statics"))?;
            let mut raised = statics.scene.clone();
            raised.ends.top.1 += lift;
            let r = statics_cmd::solve(raised)
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

/// A checkpoint: everything a restart needs besides the Model, which is rebuilt from the scene.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Checkpoint {
    /// The catena version that wrote it.
    pub catena_version: String,
    /// The scene's text (a restart must use the same scene).
    pub scene: String,
    /// The number of completed time steps of `dynamic.time_step`.
    pub step: u64,
    /// The State.
    pub state: dynamics::DynState,
}

impl Checkpoint {
    /// Writes the checkpoint as JSON (exact: floats round-trip), replacing the file atomically.
    pub fn write(&self, path: &Path) -> Result<(), AppError> {
        let tmp = path.with_extension("json.tmp");
        let text = serde_json::to_string(self).map_err(|e| AppError::Io {
            path: path.to_path_buf(),
            source: std::io::Error::other(e.to_string()),
        })?;
        std::fs::write(&tmp, text).map_err(|e| AppError::io(&tmp, e))?;
        std::fs::rename(&tmp, path).map_err(|e| AppError::io(path, e))
    }

    /// Reads a checkpoint.
    pub fn read(path: &Path) -> Result<Self, AppError> {
        let text = std::fs::read_to_string(path).map_err(|e| AppError::io(path, e))?;
        serde_json::from_str(&text).map_err(|e| AppError::Run {
            file: path.display().to_string(),
            message: format!("not a catena checkpoint: {e}"),
        })
    }
}

/// Options of a dynamic run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Show a progress bar.
    pub progress: bool,
    /// Write a checkpoint every this many steps to `checkpoint_path`.
    pub checkpoint_every: Option<u64>,
    /// Where checkpoints go.
    pub checkpoint_path: Option<std::path::PathBuf>,
    /// Continue from this checkpoint instead of the statics.
    pub restart: Option<Checkpoint>,
    /// Stop (successfully) after this many time steps, e.g. to end a job at a checkpoint.
    pub stop_after: Option<u64>,
}

/// Runs statics then dynamics, streaming records to `recorder` if given.
pub fn run(
    statics: StaticRun,
    recorder: Option<&mut Recorder>,
    progress: bool,
) -> Result<DynamicRun, AppError> {
    run_with(
        statics,
        recorder,
        RunOptions {
            progress,
            ..RunOptions::default()
        },
    )
}

/// Runs the dynamics with checkpoint and restart options (see [`RunOptions`]). A restarted run
/// records and takes envelopes from its restart time on.
pub fn run_with(
    statics: StaticRun,
    mut recorder: Option<&mut Recorder>,
    opts: RunOptions,
) -> Result<DynamicRun, AppError> {
    let progress = opts.progress;
    let mut spec = statics.scene.dynamic.clone().ok_or_else(|| AppError::Run {
        file: statics.scene.file.clone(),
        message: "key `dynamic`: expected a [dynamic] table for `catena run` (use `catena static` for statics alone)".into(),
    })?;
    resolve_gauges(&statics, &mut spec)?;
    let model = &statics.model;
    let pl = &statics.placement;
    let set = &spec.settings;
    let n = model.nodes();
    let t0 = Instant::now();
    let mut ws = DynWorkspace::new(model).map_err(|e| AppError::Run {
        file: statics.scene.file.clone(),
        message: e.to_string(),
    })?;
    let mut state = dynamics::initial_state(model, pl, set.hydro.as_ref(), &statics.u, &mut ws);
    let mut snap = Snapshot::new(n);
    let mut env = Envelopes::new(n);
    let mut hist = Histories {
        gauge_moment: vec![Vec::new(); spec.gauges.len()],
        gauge_tension: vec![Vec::new(); spec.gauges.len()],
        ..Histories::default()
    };
    let mut gauge_vals = vec![(0.0, 0.0); spec.gauges.len()];
    let arc = &model.arc;
    let record = |state: &dynamics::DynState,
                  snap: &Snapshot,
                  hist: &mut Histories,
                  gauge_vals: &mut Vec<(f64, f64)>,
                  rec: &mut Option<&mut Recorder>|
     -> Result<(), AppError> {
        for (k, g) in spec.gauges.iter().enumerate() {
            gauge_vals[k] = (
                at_arc(arc, &snap.moment, g.arc),
                at_arc(arc, &snap.tension, g.arc),
            );
            hist.gauge_moment[k].push(gauge_vals[k].0);
            hist.gauge_tension[k].push(gauge_vals[k].1);
        }
        hist.t.push(state.t);
        hist.top_z.push(snap.z[0]);
        hist.top_tension.push(snap.tension[0]);
        if let Some(r) = rec.as_deref_mut() {
            r.push(&Record {
                t: state.t,
                top: [snap.x[0], snap.z[0]],
                top_tension: snap.tension[0],
                snap,
                gauges: gauge_vals,
            })?;
        }
        Ok(())
    };
    let mut first_step = 1;
    if let Some(cp) = &opts.restart {
        if cp.scene != statics.scene.text {
            return Err(AppError::Run {
                file: statics.scene.file.clone(),
                message: "the checkpoint was written for a different scene (its text differs)"
                    .into(),
            });
        }
        if cp.state.u.len() != state.u.len() || cp.state.history.len() != state.history.len() {
            return Err(AppError::Run {
                file: statics.scene.file.clone(),
                message: "the checkpoint does not fit this model (its node count differs)".into(),
            });
        }
        state = cp.state.clone();
        first_step = cp.step + 1;
    } else {
        dynamics::snapshot(model, pl, &state, &ws, &mut snap);
        record(&state, &snap, &mut hist, &mut gauge_vals, &mut recorder)?;
        if spec.envelope_start <= 0.0 {
            env.update(&snap);
        }
    }
    let n_steps = (spec.duration / spec.dt).round() as u64;
    let bar = if progress {
        let b = indicatif::ProgressBar::new(n_steps);
        b.set_style(
            indicatif::ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {pos}/{len} steps, t = {msg} s, eta {eta}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        Some(b)
    } else {
        None
    };
    let (mut iterations, mut cuts, mut retries) = (0usize, 0u32, 0u32);
    let mut error = None;
    for k in first_step..=n_steps {
        match dynamics::advance(model, pl, set, &mut state, &mut ws, spec.dt) {
            Ok(info) => {
                iterations += info.iterations;
                cuts += info.cuts;
                retries += info.retries;
                state.t = k as f64 * spec.dt;
                dynamics::snapshot(model, pl, &state, &ws, &mut snap);
                if state.t >= spec.envelope_start - 1e-9 * spec.dt {
                    env.update(&snap);
                }
                if k as usize % spec.output_every == 0 {
                    record(&state, &snap, &mut hist, &mut gauge_vals, &mut recorder)?;
                }
                if let (Some(every), Some(path)) = (opts.checkpoint_every, &opts.checkpoint_path) {
                    if every > 0 && k % every == 0 {
                        Checkpoint {
                            catena_version: env!("CARGO_PKG_VERSION").to_string(),
                            scene: statics.scene.text.clone(),
                            step: k,
                            state: state.clone(),
                        }
                        .write(path)?;
                        ws.forget_factorisation();
                    }
                }
                if opts.stop_after == Some(k) {
                    break;
                }
            }
            Err(e) => {
                error = Some(e.to_string());
                break;
            }
        }
        if let Some(b) = &bar {
            if k % 20 == 0 || k == n_steps {
                b.set_position(k);
                b.set_message(format!("{:.2}", state.t));
            }
        }
    }
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if let Some(r) = recorder {
        r.flush()?;
    }
    Ok(DynamicRun {
        steps: state.step,
        statics,
        spec,
        envelopes: env,
        hist,
        iterations,
        cuts,
        retries,
        wall_seconds: t0.elapsed().as_secs_f64(),
        error,
    })
}

fn finite_or_null(v: &[f64]) -> Vec<serde_json::Value> {
    v.iter()
        .map(|x| {
            if x.is_finite() {
                json!(x)
            } else {
                serde_json::Value::Null
            }
        })
        .collect()
}

/// `(least, greatest)` of a history (`(∞, −∞)` when it is empty).
pub fn extremes(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(*x), hi.max(*x))
        })
}

/// Extremes of a gauge's moment while the top rises and while it falls: `(rising min, rising max,
/// falling min, falling max)`, N·m (NaN if the top never moves that way).
pub fn gauge_by_direction(r: &DynamicRun, k: usize) -> (f64, f64, f64, f64) {
    let h = &r.hist;
    let (mut a, mut b, mut c, mut d) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for i in 1..h.t.len() {
        let dz = h.top_z[i] - h.top_z[i - 1];
        let m = h.gauge_moment[k][i];
        if dz > 1e-9 {
            a = a.min(m);
            b = b.max(m);
        } else if dz < -1e-9 {
            c = c.min(m);
            d = d.max(m);
        }
    }
    let nan = |v: f64| if v.is_finite() { v } else { f64::NAN };
    (nan(a), nan(b), nan(c), nan(d))
}

/// Key numbers of a run: `(max moment range, its arc, top tension min, max)`.
pub fn key_numbers(r: &DynamicRun) -> (f64, f64, f64, f64) {
    let range = r.envelopes.moment_range();
    let (mut best, mut at) = (0.0, 0.0);
    for (i, v) in range.iter().enumerate() {
        if v.is_finite() && *v > best {
            best = *v;
            at = r.statics.model.arc[i];
        }
    }
    let start = r.spec.envelope_start;
    let (mut tmin, mut tmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for (t, v) in r.hist.t.iter().zip(&r.hist.top_tension) {
        if *t >= start - 1e-9 {
            tmin = tmin.min(*v);
            tmax = tmax.max(*v);
        }
    }
    (best, at, tmin, tmax)
}

/// The summary JSON of a run.
pub fn summary_json(r: &DynamicRun) -> serde_json::Value {
    let mut js = statics_cmd::summary_json(&r.statics);
    let (mr, at, tmin, tmax) = key_numbers(r);
    let gauges: Vec<serde_json::Value> = r
        .spec
        .gauges
        .iter()
        .enumerate()
        .map(|(k, g)| {
            let (mmin, mmax) = extremes(&r.hist.gauge_moment[k]);
            let (rmin, rmax, fmin, fmax) = gauge_by_direction(r, k);
            let num = |v: f64| {
                if v.is_finite() {
                    json!(v)
                } else {
                    serde_json::Value::Null
                }
            };
            json!({
                "name": g.name, "arc": g.arc,
                "moment_min": mmin,
                "moment_max": mmax,
                "moment_min_top_rising": num(rmin), "moment_max_top_rising": num(rmax),
                "moment_min_top_falling": num(fmin), "moment_max_top_falling": num(fmax),
            })
        })
        .collect();
    js["dynamic"] = json!({
        "completed": r.error.is_none(),
        "error": r.error,
        "duration": r.spec.duration,
        "time_step": r.spec.dt,
        "scheme": format!("{:?}", r.spec.settings.scheme),
        "steps": r.steps,
        "newton_iterations": r.iterations,
        "iterations_per_step": r.iterations as f64 / (r.steps.max(1) as f64),
        "step_cuts": r.cuts,
        "predictor_retries": r.retries,
        "wall_seconds": r.wall_seconds,
        "envelope_start": r.spec.envelope_start,
        "max_moment_range": mr,
        "max_moment_range_arc": at,
        "top_tension_min": tmin,
        "top_tension_max": tmax,
        "top_tension_range": tmax - tmin,
        "gauges": gauges,
        "envelopes": {
            "arc": r.statics.model.arc,
            "moment_min": finite_or_null(&r.envelopes.moment_min),
            "moment_max": finite_or_null(&r.envelopes.moment_max),
            "tension_min": finite_or_null(&r.envelopes.tension_min),
            "tension_max": finite_or_null(&r.envelopes.tension_max),
            "moment_range": finite_or_null(&r.envelopes.moment_range()),
            "tension_range": finite_or_null(&r.envelopes.tension_range()),
            "penetration_max": finite_or_null(&r.envelopes.penetration_max),
            "penetration_min": finite_or_null(&r.envelopes.penetration_min),
        }
    });
    js
}

/// The summary as text.
pub fn summary_text(r: &DynamicRun) -> String {
    let mut t = statics_cmd::summary_text(&r.statics);
    let (mr, at, tmin, tmax) = key_numbers(r);
    let _ = writeln!(
        t,
        "dynamic: {:.1} s in {} steps of {} s ({:?}); {} Newton iterations ({:.2} per step), {} step cuts, {} predictor retries; {:.2} s wall",
        r.spec.duration,
        r.steps,
        r.spec.dt,
        r.spec.settings.scheme,
        r.iterations,
        r.iterations as f64 / r.steps.max(1) as f64,
        r.cuts,
        r.retries,
        r.wall_seconds
    );
    let _ = writeln!(t, "  from t = {} s:", r.spec.envelope_start);
    let _ = writeln!(
        t,
        "  top tension            {:>10.2} to {:.2} kN (range {:.2} kN)",
        tmin / 1e3,
        tmax / 1e3,
        (tmax - tmin) / 1e3
    );
    let _ = writeln!(
        t,
        "  max moment range       {:>10.2} kN·m at arc length {at:.2} m",
        mr / 1e3
    );
    for (k, g) in r.spec.gauges.iter().enumerate() {
        let (mmin, mmax) = extremes(&r.hist.gauge_moment[k]);
        let _ = writeln!(
            t,
            "  gauge {} (arc {:.2} m): moment {:.2} to {:.2} kN·m",
            g.name,
            g.arc,
            mmin / 1e3,
            mmax / 1e3
        );
        let (rmin, rmax, fmin, fmax) = gauge_by_direction(r, k);
        if rmin.is_finite() || fmin.is_finite() {
            let _ = writeln!(
                t,
                "    top rising (pull-up): {:.2} to {:.2} kN·m; top falling (lay-down): {:.2} to {:.2} kN·m",
                rmin / 1e3, rmax / 1e3, fmin / 1e3, fmax / 1e3
            );
        }
    }
    if let Some(e) = &r.error {
        let _ = writeln!(t, "  STOPPED EARLY: {e}");
    }
    t
}

/// The whole command.
pub fn command(case: &Path, out: &Path, progress: bool) -> Result<String, AppError> {
    command_with(case, out, progress, None, None)
}

/// The whole command with checkpoints every `checkpoint_every` steps (to `DIR/checkpoint.json`) and/or
/// a restart from a checkpoint file.
pub fn command_with(
    case: &Path,
    out: &Path,
    progress: bool,
    checkpoint_every: Option<u64>,
    restart: Option<&Path>,
) -> Result<String, AppError> {
    let restart = restart.map(Checkpoint::read).transpose()?;
    let scene = statics_cmd::read_scene(case)?;
    if scene.dynamic.is_none() {
        return Err(AppError::Run {
            file: scene.file.clone(),
            message: "key `dynamic`: expected a [dynamic] table for `catena run` (use `catena static` for statics alone)".into(),
        });
    }
    let statics = statics_cmd::solve(scene)?;
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let h5 = out.join("results.h5");
    let file = hdf5::File::create(&h5).map_err(crate::h5::h5err(&h5))?;
    crate::h5::write_static_into(&h5, &file, &statics)?;
    let gauge_names: Vec<String> = statics.scene.dynamic.as_ref().map_or_else(Vec::new, |d| {
        d.gauges.iter().map(|g| g.name.clone()).collect()
    });
    let mut rec = Recorder::new(&h5, &file, statics.model.nodes(), &gauge_names)?;
    crate::plot::static_line(
        &out.join("static.png"),
        &statics.scene.title,
        &statics.results,
    )?;
    let r = run_with(
        statics,
        Some(&mut rec),
        RunOptions {
            progress,
            checkpoint_every,
            checkpoint_path: Some(out.join("checkpoint.json")),
            restart,
            stop_after: None,
        },
    )?;
    let js = out.join("summary.json");
    std::fs::write(
        &js,
        serde_json::to_string_pretty(&summary_json(&r)).unwrap_or_default(),
    )
    .map_err(|e| AppError::io(&js, e))?;
    crate::plot::dynamic(&out.join("dynamic.png"), &r)?;
    if !r.spec.gauges.is_empty() {
        crate::plot::gauges(&out.join("gauges.png"), &r)?;
    }
    let mut t = summary_text(&r);
    let _ = writeln!(
        t,
        "  wrote {} ({} records), {}, plots in {}",
        h5.display(),
        rec.records(),
        js.display(),
        out.display()
    );
    if let Some(e) = &r.error {
        return Err(AppError::Run {
            file: r.statics.scene.file.clone(),
            message: format!(
                "{e}\n{t}results up to the last converged step are in {}",
                h5.display()
            ),
        });
    }
    Ok(t)
}
