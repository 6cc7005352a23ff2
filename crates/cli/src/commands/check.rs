//! `catena check`: what a scene (or a study, sweep or sequence) would run, without running it.

use std::fmt::Write as _;
use std::path::Path;

use catena::run::statics;
use catena::studies::soil_test::SoilTestCase;
use catena::AppError;

/// Measured cost of one element-step (`benches/README.md`, the scaling table: 0.38–0.39 µs for the
/// linear seabed on this project's reference machine; a seabed law's factor is its
/// `Law::relative_cost`, e.g. 1.9 for the Randolph–Quiggin law: a 300 s storm, 4.45 s against
/// 2.31 s) and for 400 wave components (+52 % a step).
const US_PER_ELEMENT_STEP: f64 = 0.39;
const WAVES_FACTOR_400: f64 = 1.52;

/// What one riser scene would run, as lines of text, with its warnings.
fn describe_scene(
    scene: &catena::scene::riser::RiserScene,
    t: &mut String,
    warnings: &mut Vec<String>,
) -> f64 {
    warnings.extend(scene.warnings.iter().cloned());
    let size = scene.size;
    let _ = writeln!(t, "  title: {}", scene.title);
    let mut effects = vec![format!(
        "line ({} elements, {} nodes)",
        size.elements,
        size.elements + 1
    )];
    let mut factor = 1.0;
    if let Some(sb) = &scene.model.seabed {
        factor *= sb.seabed.law.relative_cost();
        effects.push(sb.seabed.law.title().to_string());
        if let catena_seabed::law::Law::RandolphQuiggin(rq) = &sb.seabed.law {
            if let Some(d) = &rq.params().degradation {
                effects.push(format!(
                    "cyclic degradation (S_t {}, ξ95 {} D){}",
                    d.sensitivity,
                    d.ductility,
                    if d.regain.is_some() {
                        " with regain at rest"
                    } else {
                        ""
                    }
                ));
            }
        }
        if sb.seabed.buoyancy.is_some() {
            effects.push("soil buoyancy".into());
        }
        let zones = scene.model.seabed_zones.len();
        if zones > 0 {
            effects.push(format!("{zones} soil zone(s) along the route"));
        }
        if let Some(f) = sb.friction {
            effects.push(format!(
                "axial seabed friction (μ {}, δ {} m; dynamics only)",
                f.mu, f.mobilisation
            ));
        }
    }
    let bodies = scene.model.attachments.len();
    if bodies > 0 {
        effects.push(format!(
            "{bodies} attached bod{}",
            if bodies == 1 { "y" } else { "ies" }
        ));
    }
    if scene.model.flexjoint.is_some() {
        effects.push("flexjoint".into());
    }
    if let Some(h) = &scene.hydro {
        effects.push(if !h.current.is_empty() {
            "hydrodynamics with current (statics too)".into()
        } else {
            "hydrodynamics".into()
        });
    }
    let mut seconds = 0.0;
    match &scene.dynamic {
        None => {
            let _ = writeln!(t, "  runs: statics only (no [dynamic] table)");
        }
        Some(d) => {
            if let Some(w) = &d.environment.waves {
                effects.push(format!("waves ({} components)", w.components.len()));
                factor *= 1.0 + (WAVES_FACTOR_400 - 1.0) * w.components.len() as f64 / 400.0;
                if d.environment.hydro.is_none() {
                    warnings.push("[waves] without [hydrodynamics]: the waves load nothing".into());
                }
            }
            if d.vessel.is_some() {
                effects.push("vessel motion from RAOs".into());
            }
            if let Some(m) = &d.motion {
                effects.push(match m {
                    catena_fe::motion::TopMotion::Harmonic { period, .. } => {
                        if d.dt > period / 40.0 {
                            warnings.push(format!(
                                "dynamic.time_step {} s is more than 1/40 of the motion's period {period} s: see `catena convergence`",
                                d.dt
                            ));
                        }
                        "harmonic top motion".into()
                    }
                    catena_fe::motion::TopMotion::Staged(_) => "staged top motion".into(),
                    catena_fe::motion::TopMotion::Series(_) => "top motion from a series".into(),
                });
            }
            if d.structural_damping.is_some() {
                effects.push("structural damping".into());
            }
            if d.fatigue.is_some() {
                effects.push("fatigue (stress, rainflow, S-N damage)".into());
            }
            if let Some(c) = &d.design_check {
                effects.push(format!("strength check ({})", c.code.name()));
            }
            if let Some(x) = &d.extremes {
                effects.push(format!("extremes of {} channels", x.channels.len()));
            }
            if !d.gauges.is_empty() {
                effects.push(format!("{} gauges", d.gauges.len()));
            }
            seconds =
                size.steps as f64 * size.elements as f64 * US_PER_ELEMENT_STEP * 1e-6 * factor;
            let _ = writeln!(
                t,
                "  runs: statics, then {} steps of {} s ({} s), {} records",
                size.steps, d.dt, d.duration, size.records
            );
            if let Some(l) = &scene.lay {
                let _ = writeln!(t, "  {}", lay_line(l));
            } else if d.motion.is_none() && d.vessel.is_none() && d.environment.waves.is_none() {
                warnings.push("nothing moves the line: no [motion], [vessel] or [waves]".into());
            }
        }
    }
    let _ = writeln!(t, "  effects built: {}", effects.join(", "));
    // Resident memory: measured 34 MB for 860 elements (the 3-hour storm), flat in the run length.
    let memory = 20e6 + 16e3 * size.elements as f64;
    let _ = writeln!(
        t,
        "  estimated: {:.1} s of dynamics on one core, {:.0} MB of memory, {:.1} MB of results.h5 (before compression)",
        seconds,
        memory / 1e6,
        size.output_bytes / 1e6
    );
    seconds
}

/// What a `[lay]` does, in a line.
fn lay_line(l: &catena::scene::lay::LaySpec) -> String {
    use catena::scene::lay::{Payout, Tower};
    format!(
        "a J-lay: the vessel at {} m/s along +x, {}; a {} tower{}; {} m of pipe{}{}",
        l.speed,
        match l.payout {
            Payout::Position => "the pipe paid out at its speed".to_string(),
            Payout::Tension { .. } => "the pipe paid out by a tensioner".to_string(),
        },
        match l.tower {
            Tower::Clamped => "clamped",
            Tower::Hinged(_) => "hinged",
        },
        l.tower_angle.map_or(String::new(), |a| format!(
            " at {:.1}° from the vertical",
            a.to_degrees()
        )),
        l.pipe_length,
        l.length
            .map_or(String::new(), |len| format!(", {len} m of it laid")),
        if l.lay_down.is_some() {
            ", its end lowered on a wire to the seabed"
        } else {
            ""
        }
    )
}

/// `catena check CASE`: reads and checks a scene, a fatigue study, a sweep plan or a soil test
/// without running it, and says what would run (effects built, elements, steps, estimated time,
/// memory and disk) and every warning.
pub fn check(case: &Path) -> Result<String, AppError> {
    let text = catena::scene::read_text(case)?;
    let file = case.display().to_string();
    let doc: toml::Table =
        text.parse()
            .map_err(|e: toml::de::Error| catena::error::SceneError::Parse {
                file: file.clone(),
                message: e.to_string().trim_end().to_string(),
            })?;
    let mut t = String::new();
    let mut warnings = Vec::new();
    if doc.contains_key("sweep") {
        let plan = catena::studies::sweep::Plan::read(case)?;
        let runs = plan.runs();
        let _ = writeln!(
            t,
            "{file}: a sweep of {} points, {} runs",
            plan.points.len(),
            runs.len()
        );
        let per_run = match &plan.base {
            catena::studies::sweep::Base::Study(s) => {
                let mut sum = 0.0;
                for (_, sc) in &s.storms {
                    let mut scratch = String::new();
                    sum += describe_scene(sc, &mut scratch, &mut warnings);
                }
                sum / s.storms.len().max(1) as f64
            }
            catena::studies::sweep::Base::Scene(sc) => describe_scene(sc, &mut t, &mut warnings),
        };
        let _ = writeln!(
            t,
            "  estimated: {:.2} core-hours in all ({:.0} s a run on average)",
            per_run * runs.len() as f64 / 3600.0,
            per_run
        );
    } else if doc.contains_key("sequence") {
        let seq = catena::studies::sequence::Sequence::read(case)?;
        let ids: Vec<String> = seq
            .visits
            .iter()
            .map(|(v, _)| v.storm.id.to_string())
            .collect();
        let _ = writeln!(
            t,
            "{file}: a storm sequence of {} visits (storms {}), {:.1} % of the year's sea states covered, {} s of rest between visits{}",
            seq.visits.len(),
            ids.join(", "),
            100.0 * seq.coverage,
            seq.calm,
            if seq.as_laid { "; each visit also from the as-laid state" } else { "" }
        );
        let mut sum = 0.0;
        for (i, (_, sc)) in seq.visits.iter().enumerate() {
            if i == 0 {
                let _ = writeln!(t, "  each visit's scene (the first shown):");
                sum += describe_scene(sc, &mut t, &mut warnings);
            } else {
                let mut scratch = String::new();
                sum += describe_scene(sc, &mut scratch, &mut warnings);
            }
        }
        // The calm scene moves nothing by design: its warnings are not the user's.
        let (mut scratch, mut quiet) = (String::new(), Vec::new());
        let calm = describe_scene(&seq.calm_scene, &mut scratch, &mut quiet);
        let _ = writeln!(
            t,
            "  estimated: {:.0} s on one core for the sequence (its settling {:.0} s of it){}",
            sum + calm * seq.visits.len() as f64,
            calm * seq.visits.len() as f64,
            if seq.as_laid {
                format!(", {sum:.0} s more for the as-laid visits alongside")
            } else {
                String::new()
            }
        );
    } else if doc.contains_key("study") && !doc.contains_key("fatigue") {
        let study = catena::studies::strength::StrengthStudy::read(case)?;
        let _ = writeln!(
            t,
            "{file}: a strength study of {} runs (storms × seeds)",
            study.runs.len()
        );
        let mut sum = 0.0;
        for (i, run) in study.runs.iter().enumerate() {
            if i == 0 {
                let _ = writeln!(t, "  each run's scene (the first shown):");
                sum += describe_scene(&run.scene, &mut t, &mut warnings);
            } else {
                let mut scratch = String::new();
                sum += describe_scene(&run.scene, &mut scratch, &mut warnings);
            }
        }
        let _ = writeln!(
            t,
            "  estimated: {:.0} s on one core for the whole study",
            sum
        );
    } else if doc.contains_key("study") {
        let study = catena::studies::fatigue_study::Study::read(case)?;
        let _ = writeln!(
            t,
            "{file}: a fatigue study of {} storms, {} s counted each after {} s",
            study.storms.len(),
            study.record,
            study.transient
        );
        let mut sum = 0.0;
        for (i, (_, sc)) in study.storms.iter().enumerate() {
            if i == 0 {
                let _ = writeln!(t, "  each storm's scene (the first shown):");
                sum += describe_scene(sc, &mut t, &mut warnings);
            } else {
                let mut scratch = String::new();
                sum += describe_scene(sc, &mut scratch, &mut warnings);
            }
        }
        let _ = writeln!(
            t,
            "  estimated: {:.0} s on one core for the whole study",
            sum
        );
    } else if doc.contains_key("test") {
        let st = SoilTestCase::read(case)?;
        let _ = writeln!(t, "{file}: a soil element test of {} legs", st.legs.len());
    } else {
        let scene = statics::read_scene(case)?;
        let _ = writeln!(t, "{file}: a riser scene");
        describe_scene(&scene, &mut t, &mut warnings);
    }
    warnings.sort();
    warnings.dedup();
    if warnings.is_empty() {
        let _ = writeln!(t, "  no warnings");
    }
    for w in warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    Ok(t)
}
