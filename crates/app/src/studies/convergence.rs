//! The convergence study (`catena convergence`): what accuracy costs in time.
//!
//! The scene is run as written (the *base* run) and again with every element length scaled by each
//! of the mesh factors (Δt as written) and with the time step scaled by each of the Δt factors (mesh
//! as written): by default ×2, ×1, ×½, ×¼ for both, seven runs in all. Each variant is the parsed
//! scene edited by key path ([`crate::scene::edit`]): `mesh[*].element_length` and
//! `dynamic.time_step` scaled and `dynamic.output_interval` removed, so every time step is sampled;
//! the variant scenes' text is kept (the command writes it to `DIR/scenes/`, and any of them can be
//! run alone with `catena run`).
//!
//! **Key outputs** of each run (from `dynamic.envelope_start`):
//! - the touchdown-zone moment range: the largest per-node range of the bending moment over the arc
//!   between the first and the last node that both touched the seabed and left it during the window
//!   (if no node changed contact, the nodes in contact); without a seabed, the largest moment range
//!   on the line. (A margin of a few boundary-layer lengths √(EI/H) would reach into Watchet's sag
//!   bend, whose larger range then sets the value at the margin's edge.)
//! - the top-tension range and the top-tension maximum;
//! - with a seabed, the largest penetration;
//! - for each gauge, its least and greatest bending moment (the whole run);
//! - with a `[fatigue]` table, the largest damage along the line for each fibre.
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

use std::path::Path;
use std::time::Instant;

use rayon::prelude::*;

use crate::error::AppError;
use crate::run::observe::Stop;
use crate::run::{self, DynamicRun, RunOptions};
use crate::scene::edit::Edit;
use crate::scene::riser::RiserScene;
use crate::scene::{DirResolver, Resolver};

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
    pub error: Option<Stop>,
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
    /// (value − reference)/|reference|, %, per factor (NaN, unknown, for the run that is itself the
    /// reference when there is no extrapolation).
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
    // The run that is itself the reference (the finest, without an extrapolation) has no estimated
    // error: its zero would read as "exact".
    let finest_factor = ok.last().map(|(f, _)| *f);
    SeriesAnalysis {
        factors: factors.to_vec(),
        values: values.to_vec(),
        order,
        extrapolated,
        gci_percent: gci,
        reference,
        reference_kind,
        errors_percent: factors
            .iter()
            .zip(values)
            .map(|(f, v)| {
                if reference_kind == "finest" && Some(*f) == finest_factor {
                    f64::NAN
                } else {
                    100.0 * (v - reference) / scale
                }
            })
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
    if scene.lay.is_some() {
        return vec![
            def("as_laid_embedment", "mean as-laid embedment", "mm"),
            def("lay_factor", "touchdown lay factor", "1"),
            def("top_tension_range", "top tension range", "kN"),
            def("sag_moment_max", "sag bend's largest moment", "kN·m"),
        ];
    }
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
        if let Some(f) = &d.fatigue {
            for fib in &f.fibres {
                v.push(def(
                    &format!("fatigue_damage_{}", fib.name()),
                    &format!("largest fatigue damage ({} fibre)", fib.name()),
                    "1",
                ));
            }
        }
    }
    v
}

/// The touchdown zone of a run, as an arc-length interval (see the module docs), or `None` if no
/// node touched the seabed in the envelope window.
pub fn touchdown_zone(r: &DynamicRun) -> Option<(f64, f64)> {
    let e = &r.envelopes;
    let arc = &r.model.line.arc;
    let touched = |i: usize| e.penetration.max[i].is_finite() && e.penetration.max[i] > 0.0;
    let mut idx: Vec<usize> = (0..arc.len())
        .filter(|&i| touched(i) && e.penetration.min[i] < 0.0)
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
    let arc = &r.model.line.arc;
    let range = e.moment.range();
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
    let (_, _, tmin, tmax) = run::key_numbers(r);
    v.push((tmax - tmin) * 1e-3);
    v.push(tmax * 1e-3);
    if has_seabed {
        let p = e
            .penetration
            .max
            .iter()
            .copied()
            .filter(|p| p.is_finite())
            .fold(f64::NAN, f64::max);
        v.push(p * 1e3);
    }
    for tr in &r.gauges.traces {
        let (lo, hi) = tr.moment_extremes;
        v.push(lo.unwrap_or(f64::NAN) * 1e-3);
        v.push(hi.unwrap_or(f64::NAN) * 1e-3);
    }
    if let Some(f) = &r.fatigue {
        for fib in &f.spec.fibres {
            let d = f.damage_of(*fib).unwrap_or_default();
            v.push(d.iter().copied().fold(f64::NAN, f64::max));
        }
    }
    v
}

/// The variant scene: element lengths scaled by `mesh_factor`, the time step by `dt_factor`, the
/// output interval removed (edits to the parsed scene), with its text headed by a comment saying so.
pub fn variant(
    scene: &RiserScene,
    mesh_factor: f64,
    dt_factor: f64,
    files: &dyn Resolver,
) -> Result<RiserScene, AppError> {
    if scene.dynamic.is_none() {
        return Err(AppError::Run {
            file: scene.file.clone(),
            message:
                "key `dynamic`: expected a [dynamic] table (a convergence study runs the dynamics)"
                    .into(),
        });
    }
    let mut edits = vec![
        Edit::scale("mesh[*].element_length", mesh_factor),
        Edit::scale("dynamic.time_step", dt_factor),
        Edit::remove("dynamic.output_interval"),
    ];
    if scene
        .lay
        .as_ref()
        .is_some_and(|l| l.element_length.is_some())
    {
        edits.push(Edit::scale("lay.element_length", mesh_factor));
    }
    let mut v = scene.edited(&edits, files)?;
    v.text = format!(
        "# catena convergence variant of {}: element lengths x{mesh_factor}, time step x{dt_factor},\n\
         # every step sampled (output_interval removed). Generated; edit the original instead.\n{}",
        scene.file, v.text
    );
    Ok(v)
}

fn run_variant(
    scene: &RiserScene,
    (mesh_factor, dt_factor): (f64, f64),
    files: &dyn Resolver,
    threads: usize,
) -> Result<VariantRun, AppError> {
    let vscene = variant(scene, mesh_factor, dt_factor, files)?;
    let scene_text = vscene.text.clone();
    let elements = vscene.model.elements.len();
    let min_el = vscene
        .model
        .elements
        .iter()
        .map(|e| e.l0)
        .fold(f64::INFINITY, f64::min);
    if vscene.lay.is_some() {
        return lay_variant(
            vscene,
            (mesh_factor, dt_factor),
            (elements, min_el),
            threads,
        );
    }
    let t0 = Instant::now();
    // The runs side by side share the cores (`schedule::threads_per_run`).
    let opts = RunOptions::with_threads(Some(threads));
    let r = run::simulate(vscene, &mut [], opts)?;
    let wall = t0.elapsed().as_secs_f64();
    let values = if r.completed() {
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
        error: r.stop.clone(),
        scene_text,
    })
}

/// A lay's variant: the mean as-laid embedment (mm), the lay factor, the top tension's range (kN)
/// and the sag bend's largest moment (kN·m).
fn lay_variant(
    vscene: RiserScene,
    (mesh_factor, dt_factor): (f64, f64),
    (elements, min_element_length): (usize, f64),
    threads: usize,
) -> Result<VariantRun, AppError> {
    let scene_text = vscene.text.clone();
    let t0 = Instant::now();
    // The lays side by side share the cores, as the runs do.
    let st = run::statics::solve(run::lay::statics_scene(vscene))?;
    let opts = run::lay::LayOptions {
        threads: Some(threads),
        ..Default::default()
    };
    let r = run::lay::lay_with(st, opts, &mut |_| true)?;
    let wall = t0.elapsed().as_secs_f64();
    let s = &r.summary;
    let values = if r.stop.is_none() {
        vec![
            s.as_laid_mean * 1e3,
            s.lay_factor,
            (s.top_tension_max - s.top_tension_min) * 1e-3,
            s.sag_moment_max * 1e-3,
        ]
    } else {
        vec![f64::NAN; 4]
    };
    Ok(VariantRun {
        mesh_factor,
        dt_factor,
        elements,
        min_element_length,
        dt: r.dynamic.dt,
        steps: r.steps,
        newton_iterations: r.iterations,
        step_cuts: r.cuts,
        wall_seconds: wall,
        values,
        error: r.stop.clone(),
        scene_text,
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
    let files = DirResolver::beside(case);
    let scene = RiserScene::parse(&file, &text, &files)?;
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
    let threads = crate::studies::schedule::threads_per_run(opts.jobs.min(pairs.len()));
    let one = |&(mf, df): &(f64, f64)| {
        let r = run_variant(&scene, (mf, df), &files, threads);
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
pub fn error_of(st: &Study, k: usize, run: &VariantRun) -> (f64, f64) {
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
        // The finest run is the reference: its error is unknown, not zero.
        assert!(a.errors_percent[3].is_nan());
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
}
