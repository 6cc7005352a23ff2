//! `catena strength`: the strength study over design storms and seeds.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use catena::run::statics;
use catena::studies::strength::StormSummary;
use catena::AppError;

use super::{resumable, write_json};

/// `catena strength STUDY.toml --out DIR [--jobs N]`: the strength study
/// ([`catena::studies::strength`]): every storm and seed run (in parallel with `--jobs`), each written to
/// DIR/runs/<storm>-<seed>.json as it finishes (a rerun skips the runs whose scene is unchanged),
/// then per storm the utilisation along the line over its seeds and the extremes across them:
/// DIR/summary.json, DIR/utilisation.csv, DIR/strength.png.
pub fn strength(
    study_path: &Path,
    out: &Path,
    jobs: usize,
    progress: bool,
) -> Result<String, AppError> {
    use catena::studies::strength::{run_one, RunResult, StrengthStudy};
    let t0 = std::time::Instant::now();
    let study = StrengthStudy::read(study_path)?;
    let st = statics::solve(study.base.clone())?;
    let dir = out.join("runs");
    std::fs::create_dir_all(&dir).map_err(|e| AppError::io(&dir, e))?;
    let n = study.runs.len();
    // The cores shared between the runs side by side ([`catena::studies::schedule`]).
    let threads = Some(catena::studies::schedule::threads_per_run(jobs.min(n)));
    let (rs, reused) = resumable(
        &study.runs,
        (jobs, |run: &catena::studies::strength::StrengthRun| {
            catena::studies::schedule::run_cost(&run.scene)
        }),
        |run| dir.join(format!("{}-{}.json", run.storm.id, run.seed)),
        |run, r: &RunResult| {
            r.scene_hash == catena::scene::text_hash(&run.scene.text)
                && r.error.is_none()
                && r.storm == run.storm
        },
        |run| run_one(run, threads),
        |run, r, k| {
            if progress {
                eprintln!(
                    "  storm {} seed {} (Hs {} m, Tp {} s): largest utilisation {}; {:.1} s{}; {k}/{n} done, {:.0} s elapsed",
                    run.storm.id,
                    run.seed,
                    run.storm.hs,
                    run.storm.tp,
                    r.worst.as_ref().map_or("—".into(), |w| format!("{:.4}", w.1)),
                    r.wall_seconds,
                    r.error
                        .as_ref()
                        .map_or(String::new(), |e| format!(", STOPPED EARLY: {e}")),
                    t0.elapsed().as_secs_f64()
                );
            }
        },
    )?;
    let quantile = study
        .runs
        .first()
        .and_then(|r| r.scene.dynamic.as_ref())
        .and_then(|d| d.extremes.as_ref())
        .map_or(0.9, |e| e.settings.quantile);
    let summary = catena::studies::strength::summarise(&rs, quantile);
    let arc = &st.model.arc;
    let static_u: Vec<f64> = study
        .runs
        .first()
        .and_then(|r| r.scene.dynamic.as_ref())
        .and_then(|d| catena::run::observers::design::evaluator_for(d, &st.results))
        .map(|ev| {
            let mut u = vec![0.0; arc.len()];
            ev.along(&st.results, &mut u);
            u
        })
        .unwrap_or_default();
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let wall = t0.elapsed().as_secs_f64();
    let failed: Vec<_> = rs
        .iter()
        .filter_map(|r| {
            r.error
                .as_ref()
                .map(|e| serde_json::json!({"storm": r.storm.id, "seed": r.seed, "error": e}))
        })
        .collect();
    let js = serde_json::json!({
        "study": study.file,
        "runs": n,
        "reused": reused,
        "wall_seconds": wall,
        "failed": failed,
        "arc": arc,
        "static_utilisation": static_u,
        "storms": summary,
        "per_run": rs.iter().map(|r| serde_json::json!({
            "storm": r.storm.id, "seed": r.seed, "worst": r.worst,
            "compression": r.compression, "wall_seconds": r.wall_seconds,
        })).collect::<Vec<_>>(),
    });
    write_json(&out.join("summary.json"), &js)?;
    let cp = write_utilisation(out, arc, &static_u, &summary)?;
    catena_io::plot::strength(
        &out.join("strength.png"),
        &format!("{} — strength study", study.base.title),
        arc,
        &static_u,
        &rs,
        &summary,
    )?;
    let mut t = format!(
        "strength study {}: {n} runs ({reused} from an earlier run), {wall:.1} s wall\n",
        study.file
    );
    storm_lines(&mut t, &summary, arc, quantile);
    if !failed.is_empty() {
        let _ = writeln!(
            t,
            "  {} runs STOPPED EARLY (see summary.json `failed`)",
            failed.len()
        );
    }
    let _ = writeln!(
        t,
        "  wrote {}, {}, {}",
        out.join("summary.json").display(),
        cp.display(),
        out.join("strength.png").display()
    );
    Ok(t)
}

/// `utilisation.csv`: the static utilisation along the arc and, per storm, the envelope and the
/// mean over its seeds. Returns the file's path.
fn write_utilisation(
    out: &Path,
    arc: &[f64],
    static_u: &[f64],
    summary: &[StormSummary],
) -> Result<PathBuf, AppError> {
    let mut csv = String::from("arc_m,static_utilisation");
    for s in summary {
        let _ = write!(
            csv,
            ",storm{}_envelope,storm{}_mean_over_seeds",
            s.storm.id, s.storm.id
        );
    }
    csv.push('\n');
    for (i, a) in arc.iter().enumerate() {
        let _ = write!(csv, "{a},{}", static_u.get(i).copied().unwrap_or(f64::NAN));
        for s in summary {
            let _ = write!(
                csv,
                ",{},{}",
                s.utilisation_envelope[i], s.utilisation_mean[i]
            );
        }
        csv.push('\n');
    }
    let cp = out.join("utilisation.csv");
    std::fs::write(&cp, csv).map_err(|e| AppError::io(&cp, e))?;
    Ok(cp)
}

/// The text summary's lines for each storm: its largest utilisation and where, and each
/// channel's statistics across the seeds.
fn storm_lines(t: &mut String, summary: &[StormSummary], arc: &[f64], quantile: f64) {
    for s in summary {
        let u = &s.across_seeds[0];
        let (i, umax) = s
            .utilisation_envelope
            .iter()
            .copied()
            .enumerate()
            .fold((0, 0.0), |b, (i, v)| if v > b.1 { (i, v) } else { b });
        let _ = writeln!(
            t,
            "  storm {} (Hs {} m, Tp {} s), {} seeds of {:.0} s: largest utilisation {umax:.4} at arc length {:.2} m; over the seeds mean {:.4}, standard deviation {:.4}{}",
            s.storm.id,
            s.storm.hs,
            s.storm.tp,
            s.seeds.len(),
            s.record,
            arc[i],
            u.mean,
            u.std_dev,
            u.gumbel.map_or(String::new(), |(_, v)| format!(
                "; Gumbel across seeds: most probable {:.4}, {:.0} % quantile {:.4}",
                v[0],
                100.0 * quantile,
                v[1]
            ))
        );
        for c in &s.across_seeds[1..] {
            let value = |v: f64| catena_io::report::channel_value(&c.channel, v);
            let _ = writeln!(
                t,
                "    {}: per seed mean {} (sd {}){}",
                c.channel,
                value(c.mean),
                value(c.std_dev),
                c.gumbel.map_or(String::new(), |(_, v)| format!(
                    "; Gumbel across seeds: most probable {}, quantile {}",
                    value(v[0]),
                    value(v[1])
                ))
            );
        }
    }
}
