//! `catena convergence CASE.toml --out DIR`: what accuracy costs in time.
//!
//! The scene is run as written (the *base* run) and again with every element length scaled by each
//! of the mesh factors (Δt as written) and with the time step scaled by each of the Δt factors (mesh
//! as written): by default ×2, ×1, ×½, ×¼ for both, seven runs in all. Each variant is the scene's
//! own TOML with `mesh[*].element_length` and `dynamic.time_step` scaled and `output_interval`
//! removed, so every time step is sampled; the variant files are written to `DIR/scenes/` and any of
//! them can be run alone with `catena run`.
//!
//! **Key outputs** of each run (from `dynamic.envelope_start`):
//! - the touchdown-zone moment range: the largest per-node range of the bending moment over the arc
//!   between the first and the last node that both touched the seabed and left it during the window
//!   (if no node changed contact, the nodes in contact); without a seabed, the largest moment range
//!   on the line. (A margin of a few boundary-layer lengths √(EI/H) would reach into Watchet's sag
//!   bend, whose larger range then sets the value at the margin's edge.)
//! - the top-tension range and the top-tension maximum;
//! - with a seabed, the largest penetration;
//! - for each gauge, its least and greatest bending moment (the whole run).
//!
//! Fatigue damage joins these outputs when catena computes it.
//!
//! **Errors.** In each series (mesh, Δt) with the three finest levels h₁ < h₂ < h₃ in a constant
//! ratio r = h₂/h₁ = h₃/h₂ and outputs f₁, f₂, f₃, the observed order and Richardson's estimate of
//! the converged value are
//!
//! ```text
//! p = ln((f₃ − f₂)/(f₂ − f₁)) / ln r,    f∞ = f₁ − (f₂ − f₁)/(rᵖ − 1),
//! GCI = 1.25 |(f₂ − f₁)/f₁| / (rᵖ − 1)    (Roache's grid convergence index of the finest run)
//! ```
//!
//! used when the three converge monotonically ((f₃ − f₂)/(f₂ − f₁) > 0) with 0.5 ≤ p ≤ 8; otherwise
//! the finest run is the reference (and its own error is unknown, shown as 0). Each run's error is
//! (f − reference)/|reference|. The wall time of a run is its statics (with gauge placement) plus
//! its dynamics, without output.
//!
//! Runs go one at a time by default so that their wall times are honest; `--jobs N` runs N at once
//! (each run is single-threaded and deterministic, so the values do not change, only the times).

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use plotters::prelude::*;
use rayon::prelude::*;
use serde_json::json;

use crate::error::AppError;
use crate::plot::{init_fonts, plot_err};
use crate::run_cmd::{self, DynamicRun, RunOptions};
use crate::scene::riser::RiserScene;
use crate::statics_cmd;

/// Which setting a series refines.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Series {
    /// Element lengths.
    Mesh,
    /// The time step.
    TimeStep,
}

impl Series {
    /// A short name.
    pub fn name(self) -> &'static str {
        match self {
            Series::Mesh => "mesh",
            Series::TimeStep => "dt",
        }
    }
}

/// Options of the study.
#[derive(Debug, Clone)]
pub struct ConvergenceOptions {
    /// Element-length factors (any order; 1 is added if missing).
    pub mesh_factors: Vec<f64>,
    /// Time-step factors (any order; 1 is added if missing).
    pub dt_factors: Vec<f64>,
    /// Runs at once.
    pub jobs: usize,
    /// Print a line as each run ends.
    pub progress: bool,
}

impl Default for ConvergenceOptions {
    fn default() -> Self {
        Self {
            mesh_factors: vec![2.0, 1.0, 0.5, 0.25],
            dt_factors: vec![2.0, 1.0, 0.5, 0.25],
            jobs: 1,
            progress: false,
        }
    }
}

/// A key output's definition.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputDef {
    /// Identifier (CSV column stem).
    pub id: String,
    /// What it is, in words.
    pub label: String,
    /// The unit it is reported in.
    pub unit: &'static str,
}

/// One run of the study.
#[derive(Debug, Clone)]
pub struct VariantRun {
    /// Element-length factor.
    pub mesh_factor: f64,
    /// Time-step factor.
    pub dt_factor: f64,
    /// Number of elements.
    pub elements: usize,
    /// The shortest element, m.
    pub min_element_length: f64,
    /// Time step, s.
    pub dt: f64,
    /// Converged steps.
    pub steps: u64,
    /// Newton iterations in all.
    pub newton_iterations: usize,
    /// Step cuts.
    pub step_cuts: u32,
    /// Wall time (statics and dynamics, no output), s.
    pub wall_seconds: f64,
    /// The key outputs, in the units of their definitions (NaN if the run failed).
    pub values: Vec<f64>,
    /// Why the run stopped early, if it did.
    pub error: Option<String>,
    /// The variant scene's TOML.
    pub scene_text: String,
}

/// The Richardson analysis of one output along one series.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesAnalysis {
    /// Factors, coarse to fine.
    pub factors: Vec<f64>,
    /// Values at those factors.
    pub values: Vec<f64>,
    /// Observed order, if the finest three completed runs converge monotonically at a plausible
    /// order.
    pub order: Option<f64>,
    /// Richardson's estimate of the converged value.
    pub extrapolated: Option<f64>,
    /// Grid convergence index of the finest run, %.
    pub gci_percent: Option<f64>,
    /// The reference the errors are measured from.
    pub reference: f64,
    /// `"richardson"`, `"finest"`, or `"none"` (a single level: the errors are unknown, NaN).
    pub reference_kind: &'static str,
    /// (value − reference)/|reference|, %, per factor.
    pub errors_percent: Vec<f64>,
}

/// Richardson analysis of `values` at `factors` (both coarse to fine, i.e. factors decreasing).
pub fn analyse(factors: &[f64], values: &[f64]) -> SeriesAnalysis {
    // Runs that stopped early (NaN) take no part.
    let ok: Vec<(f64, f64)> = factors
        .iter()
        .zip(values)
        .filter(|(_, v)| v.is_finite())
        .map(|(f, v)| (*f, *v))
        .collect();
    let n = ok.len();
    let mut order = None;
    let mut extrapolated = None;
    let mut gci = None;
    if n >= 3 {
        let ((h1, f1), (h2, f2), (h3, f3)) = (ok[n - 1], ok[n - 2], ok[n - 3]);
        let (r21, r32) = (h2 / h1, h3 / h2);
        let (e21, e32) = (f2 - f1, f3 - f2);
        if (r21 - r32).abs() <= 1e-9 * r21 && r21 > 1.0 && e21 != 0.0 && e32 / e21 > 0.0 {
            let p = (e32 / e21).ln() / r21.ln();
            if (0.5..=8.0).contains(&p) {
                let denom = r21.powf(p) - 1.0;
                order = Some(p);
                extrapolated = Some(f1 - e21 / denom);
                if f1 != 0.0 {
                    gci = Some(125.0 * (e21 / f1).abs() / denom);
                }
            }
        }
    }
    let (reference, reference_kind) = match extrapolated {
        Some(x) => (x, "richardson"),
        None if n >= 2 => (ok[n - 1].1, "finest"),
        // One level: nothing to compare with.
        None => (f64::NAN, "none"),
    };
    let scale = reference.abs().max(f64::MIN_POSITIVE);
    SeriesAnalysis {
        factors: factors.to_vec(),
        values: values.to_vec(),
        order,
        extrapolated,
        gci_percent: gci,
        reference,
        reference_kind,
        errors_percent: values
            .iter()
            .map(|v| 100.0 * (v - reference) / scale)
            .collect(),
    }
}

/// The key outputs a scene's runs report.
pub fn output_defs(scene: &RiserScene) -> Vec<OutputDef> {
    let mut v = Vec::new();
    let def = |id: &str, label: &str, unit| OutputDef {
        id: id.into(),
        label: label.into(),
        unit,
    };
    if scene.model.seabed.is_some() {
        v.push(def(
            "tdz_moment_range",
            "touchdown-zone moment range",
            "kN·m",
        ));
    } else {
        v.push(def("max_moment_range", "largest moment range", "kN·m"));
    }
    v.push(def("top_tension_range", "top tension range", "kN"));
    v.push(def("top_tension_max", "top tension maximum", "kN"));
    if scene.model.seabed.is_some() {
        v.push(def("max_penetration", "largest penetration", "mm"));
    }
    if let Some(d) = &scene.dynamic {
        for g in &d.gauges {
            v.push(def(
                &format!("gauge_{}_moment_min", g.name),
                &format!("gauge {} moment minimum", g.name),
                "kN·m",
            ));
            v.push(def(
                &format!("gauge_{}_moment_max", g.name),
                &format!("gauge {} moment maximum", g.name),
                "kN·m",
            ));
        }
    }
    v
}

/// The touchdown zone of a run, as an arc-length interval (see the module docs), or `None` if no
/// node touched the seabed in the envelope window.
pub fn touchdown_zone(r: &DynamicRun) -> Option<(f64, f64)> {
    let e = &r.envelopes;
    let arc = &r.statics.model.arc;
    let touched = |i: usize| e.penetration_max[i].is_finite() && e.penetration_max[i] > 0.0;
    let mut idx: Vec<usize> = (0..arc.len())
        .filter(|&i| touched(i) && e.penetration_min[i] < 0.0)
        .collect();
    if idx.is_empty() {
        idx = (0..arc.len()).filter(|&i| touched(i)).collect();
    }
    let (first, last) = (*idx.first()?, *idx.last()?);
    Some((arc[first], arc[last]))
}

/// The key outputs of a run, in the order and units of [`output_defs`].
pub fn key_outputs(r: &DynamicRun) -> Vec<f64> {
    let mut v = Vec::new();
    let e = &r.envelopes;
    let arc = &r.statics.model.arc;
    let range = e.moment_range();
    let has_seabed = r.statics.model.seabed.is_some();
    let zone = if has_seabed {
        touchdown_zone(r)
    } else {
        Some((f64::NEG_INFINITY, f64::INFINITY))
    };
    let mr = match zone {
        Some((a, b)) => arc
            .iter()
            .zip(&range)
            .filter(|(s, m)| **s >= a && **s <= b && m.is_finite())
            .map(|(_, m)| *m)
            .fold(f64::NAN, f64::max),
        None => f64::NAN,
    };
    v.push(mr * 1e-3);
    let (_, _, tmin, tmax) = run_cmd::key_numbers(r);
    v.push((tmax - tmin) * 1e-3);
    v.push(tmax * 1e-3);
    if has_seabed {
        let p = e
            .penetration_max
            .iter()
            .copied()
            .filter(|p| p.is_finite())
            .fold(f64::NAN, f64::max);
        v.push(p * 1e3);
    }
    for m in &r.hist.gauge_moment {
        let (lo, hi) = run_cmd::extremes(m);
        v.push(lo * 1e-3);
        v.push(hi * 1e-3);
    }
    v
}

/// The scene text with element lengths and the time step scaled, and the output interval removed.
pub fn variant_text(
    file: &str,
    text: &str,
    mesh_factor: f64,
    dt_factor: f64,
) -> Result<String, AppError> {
    let bad = |message: String| AppError::Run {
        file: file.to_string(),
        message,
    };
    let mut table: toml::Table = text
        .parse()
        .map_err(|e| bad(format!("not valid TOML: {e}")))?;
    let mesh = table
        .get_mut("mesh")
        .and_then(|m| m.as_array_mut())
        .ok_or_else(|| bad("key `mesh`: expected [[mesh]] sections".into()))?;
    for (i, sec) in mesh.iter_mut().enumerate() {
        let el = sec.get_mut("element_length").ok_or_else(|| {
            bad(format!(
                "key `mesh[{i}].element_length`: expected a length in m"
            ))
        })?;
        let l = el
            .as_float()
            .or_else(|| el.as_integer().map(|x| x as f64))
            .ok_or_else(|| bad(format!("key `mesh[{i}].element_length`: expected a number")))?;
        *el = toml::Value::Float(l * mesh_factor);
    }
    let dynamic = table
        .get_mut("dynamic")
        .and_then(|d| d.as_table_mut())
        .ok_or_else(|| {
            bad(
                "key `dynamic`: expected a [dynamic] table (a convergence study runs the dynamics)"
                    .into(),
            )
        })?;
    let dt = dynamic
        .get("time_step")
        .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|x| x as f64)))
        .ok_or_else(|| bad("key `dynamic.time_step`: expected a time in s".into()))?;
    dynamic.insert("time_step".into(), toml::Value::Float(dt * dt_factor));
    dynamic.remove("output_interval");
    let mut out = format!(
        "# catena convergence variant of {file}: element lengths x{mesh_factor}, time step x{dt_factor},\n\
         # every step sampled (output_interval removed). Generated; edit the original instead.\n"
    );
    out.push_str(&toml::to_string(&table).map_err(|e| bad(format!("cannot write TOML: {e}")))?);
    Ok(out)
}

fn run_variant(
    file: &str,
    text: &str,
    mesh_factor: f64,
    dt_factor: f64,
) -> Result<VariantRun, AppError> {
    let vtext = variant_text(file, text, mesh_factor, dt_factor)?;
    let scene = RiserScene::parse(file, &vtext)?;
    let elements = scene.model.elements.len();
    let min_el = scene
        .model
        .elements
        .iter()
        .map(|e| e.l0)
        .fold(f64::INFINITY, f64::min);
    let t0 = Instant::now();
    let statics = statics_cmd::solve(scene)?;
    let r = run_cmd::run_with(statics, None, RunOptions::default())?;
    let wall = t0.elapsed().as_secs_f64();
    let values = if r.error.is_none() {
        key_outputs(&r)
    } else {
        vec![f64::NAN; output_defs(&r.statics.scene).len()]
    };
    Ok(VariantRun {
        mesh_factor,
        dt_factor,
        elements,
        min_element_length: min_el,
        dt: r.spec.dt,
        steps: r.steps,
        newton_iterations: r.iterations,
        step_cuts: r.cuts,
        wall_seconds: wall,
        values,
        error: r.error.clone(),
        scene_text: vtext,
    })
}

/// The result of a study.
#[derive(Debug, Clone)]
pub struct Study {
    /// The case file.
    pub file: String,
    /// The scene's title.
    pub title: String,
    /// The key outputs.
    pub outputs: Vec<OutputDef>,
    /// Every run (the base run once).
    pub runs: Vec<VariantRun>,
    /// Per output: the mesh series and the Δt series.
    pub analyses: Vec<(SeriesAnalysis, SeriesAnalysis)>,
}

impl Study {
    /// The runs of a series, coarse to fine.
    pub fn series(&self, s: Series) -> Vec<&VariantRun> {
        let mut v: Vec<&VariantRun> = self
            .runs
            .iter()
            .filter(|r| match s {
                Series::Mesh => r.dt_factor == 1.0,
                Series::TimeStep => r.mesh_factor == 1.0,
            })
            .collect();
        let f = |r: &VariantRun| match s {
            Series::Mesh => r.mesh_factor,
            Series::TimeStep => r.dt_factor,
        };
        v.sort_by(|a, b| f(b).total_cmp(&f(a)));
        v
    }

    /// The base run (the scene as written).
    pub fn base(&self) -> Option<&VariantRun> {
        self.runs
            .iter()
            .find(|r| r.mesh_factor == 1.0 && r.dt_factor == 1.0)
    }
}

fn factors(list: &[f64], what: &str, file: &str) -> Result<Vec<f64>, AppError> {
    let mut v = list.to_vec();
    if v.iter().any(|f| !(f.is_finite() && *f > 0.0)) {
        return Err(AppError::Run {
            file: file.into(),
            message: format!("{what}: expected factors > 0 (got {list:?})"),
        });
    }
    if !v.contains(&1.0) {
        v.push(1.0);
    }
    v.sort_by(|a, b| b.total_cmp(a));
    v.dedup();
    Ok(v)
}

/// Runs the study.
pub fn study(case: &Path, opts: &ConvergenceOptions) -> Result<Study, AppError> {
    let file = case.display().to_string();
    let text = crate::scene::read_text(case)?;
    let scene = RiserScene::parse(&file, &text)?;
    if scene.dynamic.is_none() {
        return Err(AppError::Run {
            file,
            message:
                "key `dynamic`: expected a [dynamic] table (a convergence study runs the dynamics)"
                    .into(),
        });
    }
    let mesh = factors(&opts.mesh_factors, "--mesh-factors", &file)?;
    let dts = factors(&opts.dt_factors, "--dt-factors", &file)?;
    let mut pairs: Vec<(f64, f64)> = vec![(1.0, 1.0)];
    pairs.extend(mesh.iter().filter(|f| **f != 1.0).map(|f| (*f, 1.0)));
    pairs.extend(dts.iter().filter(|f| **f != 1.0).map(|f| (1.0, *f)));
    let one = |&(mf, df): &(f64, f64)| {
        let r = run_variant(&file, &text, mf, df);
        if opts.progress {
            match &r {
                Ok(v) => eprintln!(
                    "  element length x{mf}, time step x{df}: {} elements, dt {} s, {} steps, {} cuts, {:.2} s{}",
                    v.elements,
                    v.dt,
                    v.steps,
                    v.step_cuts,
                    v.wall_seconds,
                    if v.error.is_some() { " (STOPPED EARLY)" } else { "" }
                ),
                Err(e) => eprintln!("  element length x{mf}, time step x{df}: failed: {e}"),
            }
        }
        r
    };
    let results: Vec<Result<VariantRun, AppError>> = if opts.jobs > 1 {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(opts.jobs)
            .build()
            .map_err(|e| AppError::Run {
                file: file.clone(),
                message: format!("--jobs: cannot start {} threads: {e}", opts.jobs),
            })?;
        pool.install(|| pairs.par_iter().map(one).collect())
    } else {
        pairs.iter().map(one).collect()
    };
    let runs = results.into_iter().collect::<Result<Vec<_>, _>>()?;
    let outputs = output_defs(&scene);
    let mut st = Study {
        file,
        title: scene.title.clone(),
        outputs,
        runs,
        analyses: Vec::new(),
    };
    let an = |s: Series, k: usize| {
        let runs = st.series(s);
        let f: Vec<f64> = runs
            .iter()
            .map(|r| match s {
                Series::Mesh => r.mesh_factor,
                Series::TimeStep => r.dt_factor,
            })
            .collect();
        let v: Vec<f64> = runs.iter().map(|r| r.values[k]).collect();
        analyse(&f, &v)
    };
    st.analyses = (0..st.outputs.len())
        .map(|k| (an(Series::Mesh, k), an(Series::TimeStep, k)))
        .collect();
    Ok(st)
}

/// The error of a run in one output, %, in its series (the base run: mesh, then Δt).
fn error_of(st: &Study, k: usize, run: &VariantRun) -> (f64, f64) {
    let (m, d) = &st.analyses[k];
    let find = |a: &SeriesAnalysis, f: f64| {
        a.factors
            .iter()
            .position(|x| *x == f)
            .map_or(f64::NAN, |i| a.errors_percent[i])
    };
    (
        if run.dt_factor == 1.0 {
            find(m, run.mesh_factor)
        } else {
            f64::NAN
        },
        if run.mesh_factor == 1.0 {
            find(d, run.dt_factor)
        } else {
            f64::NAN
        },
    )
}

/// The table as CSV: a row per run; per output its value and its error (mesh series or Δt series).
pub fn csv(st: &Study) -> String {
    let mut s = String::from(
        "series,mesh_factor,dt_factor,elements,min_element_length_m,time_step_s,steps,newton_iterations,step_cuts,wall_s",
    );
    for o in &st.outputs {
        let unit = o.unit.replace('·', "");
        let _ = write!(s, ",{}_{unit},{}_error_percent", o.id, o.id);
    }
    s.push('\n');
    let mut rows: Vec<(Series, &VariantRun)> = Vec::new();
    for ser in [Series::Mesh, Series::TimeStep] {
        rows.extend(st.series(ser).into_iter().map(|r| (ser, r)));
    }
    for (ser, r) in rows {
        let _ = write!(
            s,
            "{},{},{},{},{},{},{},{},{},{:.4}",
            ser.name(),
            r.mesh_factor,
            r.dt_factor,
            r.elements,
            r.min_element_length,
            r.dt,
            r.steps,
            r.newton_iterations,
            r.step_cuts,
            r.wall_seconds
        );
        for (k, v) in r.values.iter().enumerate() {
            let (em, ed) = error_of(st, k, r);
            let e = if ser == Series::Mesh { em } else { ed };
            let _ = write!(s, ",{v},{e}");
        }
        s.push('\n');
    }
    s
}

/// The study as JSON.
pub fn to_json(st: &Study) -> serde_json::Value {
    let num = |v: f64| {
        if v.is_finite() {
            json!(v)
        } else {
            serde_json::Value::Null
        }
    };
    let an = |a: &SeriesAnalysis| {
        json!({
            "factors": a.factors,
            "values": a.values.iter().map(|v| num(*v)).collect::<Vec<_>>(),
            "observed_order": a.order,
            "richardson": a.extrapolated,
            "gci_percent": a.gci_percent,
            "reference": num(a.reference),
            "reference_kind": a.reference_kind,
            "errors_percent": a.errors_percent.iter().map(|v| num(*v)).collect::<Vec<_>>(),
        })
    };
    json!({
        "case": st.file,
        "title": st.title,
        "catena_version": env!("CARGO_PKG_VERSION"),
        "runs": st.runs.iter().map(|r| json!({
            "mesh_factor": r.mesh_factor, "dt_factor": r.dt_factor, "elements": r.elements,
            "min_element_length": r.min_element_length, "time_step": r.dt, "steps": r.steps,
            "newton_iterations": r.newton_iterations, "step_cuts": r.step_cuts,
            "wall_seconds": r.wall_seconds,
            "values": r.values.iter().map(|v| num(*v)).collect::<Vec<_>>(),
            "error": r.error,
        })).collect::<Vec<_>>(),
        "outputs": st.outputs.iter().zip(&st.analyses).map(|(o, (m, d))| json!({
            "id": o.id, "label": o.label, "unit": o.unit,
            "mesh": an(m), "time_step": an(d),
        })).collect::<Vec<_>>(),
    })
}

/// The study as text.
pub fn summary_text(st: &Study) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "{} — convergence study ({})", st.title, st.file);
    for ser in [Series::Mesh, Series::TimeStep] {
        let runs = st.series(ser);
        let _ = writeln!(
            t,
            "\n{}:",
            match ser {
                Series::Mesh => "element length refined (time step as written)",
                Series::TimeStep => "time step refined (mesh as written)",
            }
        );
        let _ = write!(
            t,
            "  {:>7} {:>8} {:>9} {:>8} {:>5} {:>8}",
            "factor", "elements", "min el m", "dt s", "cuts", "wall s"
        );
        for o in &st.outputs {
            let _ = write!(t, " | {:>24}", format!("{} ({})", o.id, o.unit));
        }
        t.push('\n');
        for r in &runs {
            let f = if ser == Series::Mesh {
                r.mesh_factor
            } else {
                r.dt_factor
            };
            let _ = write!(
                t,
                "  {:>7} {:>8} {:>9.4} {:>8.4} {:>5} {:>8.2}",
                format!("x{f}"),
                r.elements,
                r.min_element_length,
                r.dt,
                r.step_cuts,
                r.wall_seconds
            );
            for k in 0..st.outputs.len() {
                let (em, ed) = error_of(st, k, r);
                let e = if ser == Series::Mesh { em } else { ed };
                let _ = write!(t, " | {:>12.4} {:>+10.4}%", r.values[k], e);
            }
            if r.error.is_some() {
                t.push_str("  STOPPED EARLY");
            }
            t.push('\n');
        }
        let _ = write!(t, "  {:>58}", "reference (order p, GCI)");
        for (m, d) in &st.analyses {
            let a = if ser == Series::Mesh { m } else { d };
            let tag = match (a.order, a.gci_percent) {
                (Some(p), Some(g)) => format!("R p={p:.2} GCI {g:.3}%"),
                (Some(p), None) => format!("R p={p:.2}"),
                _ => a.reference_kind.into(),
            };
            let _ = write!(t, " | {:>12.4} {:>11}", a.reference, tag);
        }
        t.push('\n');
    }
    if let Some(b) = st.base() {
        let _ = writeln!(
            t,
            "\nthe scene as written ({} elements, dt {} s, {:.2} s): estimated error = |mesh| + |time step|:",
            b.elements, b.dt, b.wall_seconds
        );
        for (k, o) in st.outputs.iter().enumerate() {
            let (em, ed) = error_of(st, k, b);
            let pct = |e: f64| {
                if e.is_finite() {
                    format!("{e:+.4} %")
                } else {
                    "n/a".into()
                }
            };
            let _ = writeln!(
                t,
                "  {:<34} {:>12.4} {:<5} mesh {}, time step {}, together ≤ {}",
                o.label,
                b.values[k],
                o.unit,
                pct(em),
                pct(ed),
                pct(em.abs() + ed.abs()).trim_start_matches('+')
            );
        }
    }
    for r in &st.runs {
        if let Some(e) = &r.error {
            let _ = writeln!(
                t,
                "run x{} mesh, x{} dt stopped early: {e}",
                r.mesh_factor, r.dt_factor
            );
        }
    }
    t
}

/// The plot: per output, |error| (log) against wall time (log), the mesh series and the Δt series.
pub fn plot(path: &Path, st: &Study) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let n = st.outputs.len();
    let cols = n.clamp(1, 3);
    let rows = n.div_ceil(cols).max(1);
    let root =
        BitMapBackend::new(path, (680 * cols as u32, 480 * rows as u32 + 50)).into_drawing_area();
    root.fill(&WHITE).map_err(&err)?;
    let root = root
        .titled(
            &format!(
                "{}: error against wall time (blue: element length, orange: time step; labels: factor)",
                st.title
            ),
            ("sans-serif", 22),
        )
        .map_err(&err)?;
    let areas = root.split_evenly((rows, cols));
    let blue = RGBColor(20, 90, 200);
    let orange = RGBColor(230, 120, 20);
    for (k, o) in st.outputs.iter().enumerate() {
        // Per series: (wall time, |error|, factor) points and a colour.
        let mut series: Vec<(Vec<Pt>, RGBColor)> = Vec::new();
        for (ser, c) in [(Series::Mesh, blue), (Series::TimeStep, orange)] {
            let pts: Vec<(f64, f64, f64)> = st
                .series(ser)
                .iter()
                .filter_map(|r| {
                    let (em, ed) = error_of(st, k, r);
                    let (e, f) = if ser == Series::Mesh {
                        (em, r.mesh_factor)
                    } else {
                        (ed, r.dt_factor)
                    };
                    (e.is_finite() && e.abs() > 0.0 && r.wall_seconds > 0.0).then_some((
                        r.wall_seconds,
                        e.abs(),
                        f,
                    ))
                })
                .collect();
            series.push((pts, c));
        }
        let all = series.iter().flat_map(|(v, _)| v.iter());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
        for &(x, y, _) in all {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.1, 1.0, 1e-3, 1.0);
        }
        let a = (a_or(&st.analyses[k].0), a_or(&st.analyses[k].1));
        let caption = format!("{} ({}); ref.: mesh {}, dt {}", o.label, o.unit, a.0, a.1);
        let mut chart = ChartBuilder::on(&areas[k])
            .caption(caption, ("sans-serif", 15))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(
                (x0 / 1.5..x1 * 1.5)
                    .log_scale()
                    .with_key_points(one_two_five(x0 / 1.5, x1 * 1.5)),
                (y0 / 3.0..y1 * 3.0)
                    .log_scale()
                    .with_key_points(one_two_five(y0 / 3.0, y1 * 3.0)),
            )
            .map_err(&err)?;
        chart
            .configure_mesh()
            .x_desc("wall time of the run (s)")
            .y_desc("|error| (%)")
            .x_labels(6)
            .y_labels(6)
            .x_label_formatter(&|v| short(*v))
            .y_label_formatter(&|v| short(*v))
            .max_light_lines(1)
            .label_style(("sans-serif", 13))
            .draw()
            .map_err(&err)?;
        for (pts, c) in &series {
            chart
                .draw_series(LineSeries::new(
                    pts.iter().map(|p| (p.0, p.1)),
                    c.stroke_width(2),
                ))
                .map_err(&err)?;
            chart
                .draw_series(pts.iter().map(|p| {
                    EmptyElement::at((p.0, p.1))
                        + Circle::new((0, 0), 4, c.filled())
                        + Text::new(
                            format!("x{}", p.2),
                            (7, -16),
                            ("sans-serif", 14).into_font().color(c),
                        )
                }))
                .map_err(&err)?;
        }
    }
    root.present().map_err(&err)?;
    Ok(())
}

/// Axis key points 1, 2, 5 × 10ᵏ within `[lo, hi]`.
fn one_two_five(lo: f64, hi: f64) -> Vec<f64> {
    let mut v = Vec::new();
    let mut k = lo.log10().floor() as i32;
    while 10f64.powi(k) <= hi && k < 300 {
        for m in [1.0, 2.0, 5.0] {
            let x = m * 10f64.powi(k);
            if x >= lo && x <= hi {
                v.push(x);
            }
        }
        k += 1;
    }
    v
}

/// A short axis label: `0.001`, `0.5`, `2`, `30`.
fn short(v: f64) -> String {
    if v <= 0.0 || !v.is_finite() {
        return String::new();
    }
    let decimals = (-v.log10()).ceil().max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A plotted point: (wall time s, |error| %, factor).
type Pt = (f64, f64, f64);

fn a_or(a: &SeriesAnalysis) -> String {
    match (a.order, a.reference_kind) {
        (Some(p), _) => format!("Richardson p={p:.1}"),
        (None, "finest") => "finest".into(),
        _ => "none".into(),
    }
}

/// The whole command: runs the study and writes `DIR/convergence.csv`, `DIR/convergence.json`,
/// `DIR/convergence.png` and the variant scenes in `DIR/scenes/`.
pub fn command(case: &Path, out: &Path, opts: &ConvergenceOptions) -> Result<String, AppError> {
    let st = study(case, opts)?;
    std::fs::create_dir_all(out.join("scenes")).map_err(|e| AppError::io(out, e))?;
    let stem = case
        .file_stem()
        .map_or_else(|| "case".into(), |s| s.to_string_lossy().into_owned());
    for r in &st.runs {
        let p = out.join("scenes").join(format!(
            "{stem}-mesh{}-dt{}.toml",
            r.mesh_factor, r.dt_factor
        ));
        std::fs::write(&p, &r.scene_text).map_err(|e| AppError::io(&p, e))?;
    }
    let c = out.join("convergence.csv");
    std::fs::write(&c, csv(&st)).map_err(|e| AppError::io(&c, e))?;
    let j = out.join("convergence.json");
    std::fs::write(
        &j,
        serde_json::to_string_pretty(&to_json(&st)).unwrap_or_default(),
    )
    .map_err(|e| AppError::io(&j, e))?;
    let png = out.join("convergence.png");
    plot(&png, &st)?;
    let mut t = summary_text(&st);
    let _ = writeln!(
        t,
        "wrote {}, {}, {} and the variant scenes in {}",
        c.display(),
        j.display(),
        png.display(),
        out.join("scenes").display()
    );
    Ok(t)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn richardson_recovers_a_second_order_limit() {
        // f(h) = 3 + 0.4 h² exactly: p = 2 and f∞ = 3.
        let h = [2.0, 1.0, 0.5, 0.25];
        let f: Vec<f64> = h.iter().map(|h| 3.0 + 0.4 * h * h).collect();
        let a = analyse(&h, &f);
        assert!((a.order.expect("value") - 2.0).abs() < 1e-9);
        assert!((a.extrapolated.expect("value") - 3.0).abs() < 1e-12);
        assert_eq!(a.reference_kind, "richardson");
        // The ×2 run is 1.6/3 off.
        assert!((a.errors_percent[0] - 100.0 * 1.6 / 3.0).abs() < 1e-9);
        // GCI = 1.25·|f2 − f1|/|f1|/(4 − 1).
        let g = 125.0 * (0.4 * (0.25 - 0.0625) / (3.0 + 0.4 * 0.0625)) / 3.0;
        assert!((a.gci_percent.expect("value") - g).abs() < 1e-9);
    }

    #[test]
    fn oscillating_series_falls_back_to_the_finest() {
        let h = [2.0, 1.0, 0.5, 0.25];
        let f = [1.0, 1.2, 0.9, 1.05];
        let a = analyse(&h, &f);
        assert_eq!(a.order, None);
        assert_eq!(a.reference_kind, "finest");
        assert_eq!(a.errors_percent[3], 0.0);
        assert!((a.errors_percent[0] - 100.0 * (1.0 - 1.05) / 1.05).abs() < 1e-12);
    }

    #[test]
    fn a_failed_finest_run_leaves_the_rest_usable() {
        let h = [4.0, 2.0, 1.0, 0.5];
        let f = [3.0 + 0.4 * 16.0, 3.0 + 0.4 * 4.0, 3.0 + 0.4, f64::NAN];
        let a = analyse(&h, &f);
        assert!((a.order.expect("value") - 2.0).abs() < 1e-9);
        assert!((a.reference - 3.0).abs() < 1e-12);
        assert!(a.errors_percent[3].is_nan());
        let single = analyse(&[1.0], &[2.0]);
        assert_eq!(single.reference_kind, "none");
        assert!(single.errors_percent[0].is_nan());
    }

    #[test]
    fn variant_text_scales_lengths_and_step() {
        let text = "title = \"t\"\n[[mesh]]\nto = 10.0\nelement_length = 2\n[[mesh]]\nto = 20.0\nelement_length = 0.5\n[dynamic]\nduration = 1.0\ntime_step = 0.1\noutput_interval = 0.2\n";
        let v = variant_text("x.toml", text, 0.5, 0.25).expect("value");
        let t: toml::Table = v.parse().expect("value");
        let m = t["mesh"].as_array().expect("value");
        assert_eq!(m[0]["element_length"].as_float(), Some(1.0));
        assert_eq!(m[1]["element_length"].as_float(), Some(0.25));
        assert_eq!(t["dynamic"]["time_step"].as_float(), Some(0.025));
        assert!(t["dynamic"].get("output_interval").is_none());
        let e = variant_text("x.toml", "[dynamic]\ntime_step = 0.1\n", 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("mesh"), "{e}");
    }
}
