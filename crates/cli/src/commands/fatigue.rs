//! `catena fatigue`: the storm-table fatigue study.

use std::fmt::Write as _;
use std::path::Path;

use catena::run::statics;
use catena::AppError;

use super::{resumable, write_json};

/// `catena fatigue STUDY.toml --out DIR [--jobs N]`: every storm of the study as a full dynamic run
/// (in parallel over storms), each storm's result kept in `DIR/storms/<id>.json` (a rerun skips the
/// storms already done with the same scene), then `fatigue.h5`, `life.csv`, `summary.json`,
/// `life.png` and `storms.png`.
pub fn fatigue(
    study_path: &Path,
    out: &Path,
    jobs: usize,
    progress: bool,
) -> Result<String, AppError> {
    use catena::studies::fatigue_study::{run_storm, StormResult, Study};
    let t0 = std::time::Instant::now();
    let study = Study::read(study_path)?;
    let touchdown = statics::solve(study.base.clone())?.summary.touchdown_arc;
    let dir = out.join("storms");
    std::fs::create_dir_all(&dir).map_err(|e| AppError::io(&dir, e))?;
    let n = study.storms.len();
    // The cores shared between the storms side by side ([`catena::studies::schedule`]).
    let threads = Some(catena::studies::schedule::threads_per_run(jobs.min(n)));
    let (rs, reused) = resumable(
        &study.storms,
        (
            jobs,
            |(_, scene): &(_, catena::scene::riser::RiserScene)| {
                catena::studies::schedule::run_cost(scene)
            },
        ),
        |(storm, _)| dir.join(format!("{}.json", storm.id)),
        |(storm, scene), r: &StormResult| {
            r.scene_hash == catena::scene::text_hash(&scene.text)
                && r.error.is_none()
                && r.storm == *storm
        },
        |(storm, scene)| run_storm(storm, scene, threads),
        |(storm, _), r, k| {
            if progress {
                eprintln!(
                    "  storm {} (Hs {} m, Tp {} s): {:.1} s{}; {k}/{n} done, {:.0} s elapsed",
                    storm.id,
                    storm.hs,
                    storm.tp,
                    r.wall_seconds,
                    r.error
                        .as_ref()
                        .map_or(String::new(), |e| format!(", STOPPED EARLY: {e}")),
                    t0.elapsed().as_secs_f64()
                );
            }
        },
    )?;
    let l = catena_io::fatigue::lives(&study, &rs);
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    catena_io::fatigue::write_h5(&out.join("fatigue.h5"), &rs, &l)?;
    let csv = out.join("life.csv");
    std::fs::write(&csv, catena_io::fatigue::life_csv(&l)).map_err(|e| AppError::io(&csv, e))?;
    let wall = t0.elapsed().as_secs_f64();
    let js = catena_io::fatigue::summary_json(&study, &rs, &l, touchdown, wall);
    write_json(&out.join("summary.json"), &js)?;
    let title = format!("{} — fatigue life, {} storms", study.base.title, n);
    catena_io::plot::fatigue::life_png(&out.join("life.png"), &l, touchdown, &title)?;
    let (i, life, fibre) = catena_io::fatigue::minimum(&l).unwrap_or((0, f64::NAN, String::new()));
    let shares = catena::studies::fatigue_study::shares(&rs, &fibre, i);
    catena_io::plot::fatigue::storms_png(
        &out.join("storms.png"),
        &shares,
        &format!(
            "each storm's share of the damage at {:.1} m ({fibre} fibre)",
            l.arc[i]
        ),
    )?;
    let mut t = format!(
        "fatigue study {}: {n} storms ({reused} from an earlier run), {:.1} s wall\n",
        study.file, wall
    );
    let _ = writeln!(
        t,
        "  minimum life {life:.4e} years at arc length {:.2} m ({fibre} fibre); static touchdown at {}",
        l.arc[i],
        touchdown.map_or("none".into(), |x| format!("{x:.2} m"))
    );
    let mut top: Vec<(i64, f64)> = shares.clone();
    top.sort_by(|a, b| b.1.total_cmp(&a.1));
    let _ = writeln!(
        t,
        "  largest shares: {}",
        top.iter()
            .take(5)
            .map(|(id, s)| format!("storm {id} {:.1} %", 100.0 * s))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(
        t,
        "  wrote fatigue.h5, life.csv, summary.json, life.png and storms.png in {}",
        out.display()
    );
    Ok(t)
}
