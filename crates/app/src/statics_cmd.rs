//! `catena static CASE.toml --out DIR`: the static configuration of a riser or pipeline on the seabed,
//! with the seabed in initial-penetration mode only (the paper's prescription).
//!
//! Writes `DIR/results.h5` (group `/static`), `DIR/summary.json` and `DIR/static.png`, and prints a
//! summary.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use catena_fe::model::LineModel;
use catena_fe::statics::{
    self, LineResults, Placement, StaticOptions, StaticReport, StaticSummary, StaticWorkspace,
};
use serde_json::json;

use crate::error::AppError;
use crate::scene::riser::RiserScene;

/// A solved static configuration.
#[derive(Debug)]
pub struct StaticRun {
    /// The scene.
    pub scene: RiserScene,
    /// The Model (flexjoint neutral angle set).
    pub model: LineModel,
    /// The base configuration (the seed).
    pub placement: Placement,
    /// Displacements from the base at equilibrium.
    pub u: Vec<f64>,
    /// Nodal results.
    pub results: LineResults,
    /// Summary numbers.
    pub summary: StaticSummary,
    /// What the solver did.
    pub report: StaticReport,
    /// Wall time of the whole static analysis, s.
    pub wall_seconds: f64,
}

fn run_error(scene: &RiserScene, e: impl std::fmt::Display) -> AppError {
    AppError::Run {
        file: scene.file.clone(),
        message: e.to_string(),
    }
}

/// Reads a scene file.
pub fn read_scene(path: &Path) -> Result<RiserScene, AppError> {
    let text = crate::scene::read_text(path)?;
    Ok(RiserScene::parse(&path.display().to_string(), &text)?)
}

/// Solves the statics of a scene.
pub fn solve(scene: RiserScene) -> Result<StaticRun, AppError> {
    let t0 = Instant::now();
    let mut model = scene.model.clone();
    let q = statics::catenary_seed(&model, &scene.ends).map_err(|e| run_error(&scene, e))?;
    let given_neutral = scene
        .flexjoint_neutral_from_vertical
        .map(|phi| -std::f64::consts::FRAC_PI_2 - phi);
    model.set_flexjoint_neutral(given_neutral.unwrap_or(q[2]));
    let placement = Placement::new(&q);
    let mut u = vec![0.0; q.len()];
    let mut ws = StaticWorkspace::new(&model).map_err(|e| run_error(&scene, e))?;
    let opts = StaticOptions {
        tol: scene.statics.tolerance,
        max_iter: scene.statics.max_iterations,
        ..StaticOptions::default()
    };
    let mut report = statics::solve(&model, &placement, &mut u, &mut ws, &opts)
        .map_err(|e| run_error(&scene, e))?;
    if model.flexjoint.is_some() && given_neutral.is_none() {
        // Neutral angle = the static departure angle: zero static flexjoint moment.
        model.set_flexjoint_neutral(placement.base[2] + u[2]);
        let again = statics::solve(&model, &placement, &mut u, &mut ws, &opts)
            .map_err(|e| run_error(&scene, e))?;
        report.iterations += again.iterations;
        report.residual = again.residual;
        report.assembly_seconds += again.assembly_seconds;
        report.solve_seconds += again.solve_seconds;
    }
    let seabed = model.seabed;
    let results = statics::line_results(&model, &placement, &u, &mut ws, |_, p| {
        seabed.map_or(0.0, |s| s.seabed.backbone(p).total())
    });
    let summary = statics::summarise(&results, (ws.residual[0], ws.residual[1]));
    Ok(StaticRun {
        scene,
        model,
        placement,
        u,
        results,
        summary,
        report,
        wall_seconds: t0.elapsed().as_secs_f64(),
    })
}

/// The summary as text.
pub fn summary_text(run: &StaticRun) -> String {
    let s = &run.summary;
    let mut t = String::new();
    let _ = writeln!(t, "static: {} ({})", run.scene.title, run.scene.file);
    let _ = writeln!(
        t,
        "  {} nodes, {} elements; Newton: {} iterations, {} continuation steps, relative residual {:.2e}; {:.1} ms",
        run.model.nodes(),
        run.model.elements.len(),
        run.report.iterations,
        run.report.steps.max(1),
        run.report.residual,
        run.wall_seconds * 1e3
    );
    let _ = writeln!(
        t,
        "  top tension            {:>12.2} kN",
        s.top_tension / 1e3
    );
    let _ = writeln!(
        t,
        "  horizontal tension     {:>12.2} kN",
        s.horizontal_tension / 1e3
    );
    let _ = writeln!(
        t,
        "  top angle              {:>12.3} deg from vertical",
        s.top_angle_from_vertical.to_degrees()
    );
    match s.touchdown_arc {
        Some(a) => {
            let _ = writeln!(t, "  touchdown arc length   {a:>12.2} m");
        }
        None => {
            let _ = writeln!(
                t,
                "  touchdown              none (the line does not touch the seabed)"
            );
        }
    }
    let _ = writeln!(
        t,
        "  max sag moment         {:>12.2} kN·m at arc length {:.2} m",
        s.max_sag_moment.0 / 1e3,
        s.max_sag_moment.1
    );
    if let Some(m) = s.touchdown_moment {
        let _ = writeln!(t, "  moment at touchdown    {:>12.2} kN·m", m / 1e3);
    }
    if run.model.seabed.is_some() {
        // Far field: 95 % of the way from the top, away from touchdown and from the anchor pin.
        let i = run.results.penetration.len().saturating_sub(1) * 95 / 100;
        let _ = writeln!(
            t,
            "  far-field penetration  {:>12.5} m at arc length {:.1} m",
            run.results.penetration[i], run.results.arc[i]
        );
    }
    t
}

/// The summary as JSON.
pub fn summary_json(run: &StaticRun) -> serde_json::Value {
    let s = &run.summary;
    json!({
        "catena_version": env!("CARGO_PKG_VERSION"),
        "case": run.scene.file,
        "title": run.scene.title,
        "units": "SI (N, m, N·m, rad; angles in deg where the key says so)",
        "static": {
            "nodes": run.model.nodes(),
            "elements": run.model.elements.len(),
            "top_tension": s.top_tension,
            "horizontal_tension": s.horizontal_tension,
            "top_angle_from_vertical_deg": s.top_angle_from_vertical.to_degrees(),
            "touchdown_arc": s.touchdown_arc,
            "max_sag_moment": s.max_sag_moment.0,
            "max_sag_moment_arc": s.max_sag_moment.1,
            "touchdown_moment": s.touchdown_moment,
            "newton_iterations": run.report.iterations,
            "continuation_steps": run.report.steps.max(1),
            "step_cuts": run.report.cuts,
            "relative_residual": run.report.residual,
            "wall_seconds": run.wall_seconds,
        }
    })
}

/// The whole command.
pub fn command(case: &Path, out: &Path) -> Result<String, AppError> {
    let scene = read_scene(case)?;
    let run = solve(scene)?;
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let h5 = out.join("results.h5");
    crate::h5::write_static(&h5, &run)?;
    let js = out.join("summary.json");
    let text = serde_json::to_string_pretty(&summary_json(&run)).unwrap_or_default();
    std::fs::write(&js, text).map_err(|e| AppError::io(&js, e))?;
    let png: PathBuf = out.join("static.png");
    crate::plot::static_line(&png, &run.scene.title, &run.results)?;
    let mut t = summary_text(&run);
    let _ = writeln!(
        t,
        "  wrote {}, {}, {}",
        h5.display(),
        js.display(),
        png.display()
    );
    Ok(t)
}
