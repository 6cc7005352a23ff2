//! The static configuration of a riser or pipeline on the seabed, with the seabed in
//! initial-penetration mode only (the paper's prescription) and the steady current's drag if the
//! scene has one (so that the dynamics start in equilibrium with it): the catenary seed, the Newton
//! solve and, with a flexjoint whose neutral angle the scene leaves to the statics, a second solve with the
//! neutral angle at the static top angle (zero static flexjoint moment).
//!
//! The Model is immutable: the second solve uses a new Model
//! ([`catena_fe::model::LineModel::with_flexjoint_neutral`]), and that is the one the run keeps.

use std::path::Path;
use std::time::Instant;

use catena_fe::model::LineModel;
use catena_fe::statics::{
    self, LineResults, Placement, StaticOptions, StaticReport, StaticSummary, StaticWorkspace,
};

use crate::error::AppError;
use crate::scene::riser::RiserScene;
use crate::scene::DirResolver;

/// A solved static configuration.
#[derive(Debug, Clone)]
pub struct StaticRun {
    /// The scene.
    pub scene: RiserScene,
    /// The Model the statics ended with (the flexjoint's neutral angle final).
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

/// Reads a scene file; files it names are read relative to its directory.
pub fn read_scene(path: &Path) -> Result<RiserScene, AppError> {
    let text = crate::scene::read_text(path)?;
    Ok(RiserScene::parse(
        &path.display().to_string(),
        &text,
        &DirResolver::beside(path),
    )?)
}

/// Solves the statics of a scene.
pub fn solve(scene: RiserScene) -> Result<StaticRun, AppError> {
    let t0 = Instant::now();
    let file = scene.file.clone();
    let st_err = |source| AppError::Statics {
        file: file.clone(),
        source,
    };
    // A default anchor height is the pipe resting at its static embedment (found here, not in the
    // parser).
    let ends = scene.ends.positions(&scene.model);
    let q = statics::catenary_seed(&scene.model, &ends).map_err(st_err)?;
    let given_neutral = scene
        .flexjoint_neutral_from_vertical
        .map(|phi| -std::f64::consts::FRAC_PI_2 - phi);
    // Each node's soil: the zone under it in the base configuration (nothing without zones).
    let mut model = scene
        .model
        .clone()
        .zoned_at(&q)
        .with_flexjoint_neutral(given_neutral.unwrap_or(q[2]));
    let placement = Placement::new(&q);
    let mut u = vec![0.0; q.len()];
    let mut ws = StaticWorkspace::new(&model).map_err(|source| AppError::Solver {
        file: file.clone(),
        source,
    })?;
    let opts = StaticOptions {
        tol: scene.statics.tolerance,
        max_iter: scene.statics.max_iterations,
        ..StaticOptions::default()
    };
    let current = scene.hydro.as_ref();
    let mut report =
        statics::solve_in(&model, current, &placement, &mut u, &mut ws, &opts).map_err(st_err)?;
    if model.flexjoint.is_some() && given_neutral.is_none() {
        // Neutral angle = the static departure angle: zero static flexjoint moment.
        model = model.with_flexjoint_neutral(placement.base[2] + u[2]);
        let again = statics::solve_in(&model, current, &placement, &mut u, &mut ws, &opts)
            .map_err(st_err)?;
        report.iterations += again.iterations;
        report.residual = again.residual;
        report.assembly_seconds += again.assembly_seconds;
        report.solve_seconds += again.solve_seconds;
    }
    let results = statics::line_results(&model, &placement, &u, &mut ws, |i, p| {
        model.seabed_law(i).map_or(0.0, |s| s.backbone(p).total())
    });
    let zeros = vec![0.0; u.len()];
    if let Some((field, node)) = catena_fe::assembly::first_non_finite(&results, &u, &zeros, &zeros)
    {
        return Err(AppError::Run {
            file: scene.file.clone(),
            message: format!(
                "the static solution has a {field} that is not a finite number at node {node} \
                 (arc {:.3} m); check the loads, material and seabed numbers",
                model.arc[node]
            ),
        });
    }
    let res = &ws.asm.residual;
    let n3 = res.len();
    let summary = statics::summarise(
        &model.arc,
        &results,
        [(res[0], res[1]), (res[n3 - 3], res[n3 - 2])],
    );
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
