//! `catena sweep`: parameter sweeps, locally or as Slurm array shards.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use catena::AppError;

use super::{finite, write_json};

/// Options of `catena sweep`.
#[derive(Debug, Clone, Default)]
pub struct SweepOptions {
    /// The output directory (required unless listing).
    pub out: Option<PathBuf>,
    /// Print the runs and stop.
    pub list: bool,
    /// Merge only.
    pub merge_only: bool,
    /// Runs at once.
    pub jobs: usize,
    /// This shard.
    pub shard: Option<usize>,
    /// The number of shards.
    pub shards: Option<usize>,
    /// A line per run on standard error.
    pub progress: bool,
}

/// The shard to run: the flags, else Slurm's (`SLURM_ARRAY_TASK_ID`, `SLURM_ARRAY_TASK_COUNT`) or
/// PBS's (`PBS_ARRAY_INDEX`, `CATENA_SHARDS`) environment, else all of it.
fn shard_of(file: &str, o: &SweepOptions) -> Result<(usize, usize), AppError> {
    let env = |k: &str| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.trim().parse::<usize>().ok())
    };
    let (i, n) = match (o.shard, o.shards) {
        (Some(i), Some(n)) => (i, n),
        (None, None) => match (
            env("SLURM_ARRAY_TASK_ID").or_else(|| env("PBS_ARRAY_INDEX")),
            env("SLURM_ARRAY_TASK_COUNT").or_else(|| env("CATENA_SHARDS")),
        ) {
            (Some(i), Some(n)) => (i, n),
            _ => (0, 1),
        },
        _ => {
            return Err(AppError::Run {
                file: file.into(),
                message: "--shard and --shards go together".into(),
            })
        }
    };
    if n == 0 || i >= n {
        return Err(AppError::Run {
            file: file.into(),
            message: format!("shard {i} of {n}: expected 0 <= shard < shards"),
        });
    }
    Ok((i, n))
}

/// `catena sweep`: runs this shard's runs (skipping those already done with the same scene), then,
/// when this is the only shard or with `--merge`, writes `sweep.csv` and `sweep.json`.
pub fn sweep(plan_path: &Path, o: &SweepOptions) -> Result<String, AppError> {
    use catena::studies::sweep::{self, Plan, RunResult};
    let plan = Plan::read(plan_path)?;
    let runs = plan.runs();
    let mut text = String::new();
    if o.list {
        for r in &runs {
            let _ = writeln!(text, "{}	{}", r.id, plan.describe(r.point));
        }
        return Ok(text);
    }
    let out = o.out.as_ref().ok_or_else(|| AppError::Run {
        file: plan.file.clone(),
        message: "--out DIR: expected an output directory".into(),
    })?;
    let dir = out.join("runs");
    std::fs::create_dir_all(&dir).map_err(|e| AppError::io(&dir, e))?;
    // Results are kept by the hash of the run's scene, so a plan that gains or loses values
    // re-runs only the runs whose scene changed.
    let read = |hash: &str| -> Option<RunResult> {
        let t = std::fs::read_to_string(dir.join(format!("{hash}.json"))).ok()?;
        let r: RunResult = serde_json::from_str(&t).ok()?;
        (r.scene_hash == hash).then_some(r)
    };
    let (shard, shards) = shard_of(&plan.file, o)?;
    let t0 = Instant::now();
    if !o.merge_only {
        let mine: Vec<&sweep::RunSpec> =
            runs.iter().filter(|r| r.index % shards == shard).collect();
        let n = mine.len();
        // The cores shared between the runs side by side ([`catena::studies::schedule`]).
        let threads = catena::studies::schedule::threads_per_run(o.jobs.min(n));
        let done = std::sync::atomic::AtomicUsize::new(0);
        // The most expensive runs first (`catena::studies::schedule`); a run whose scene failed
        // to build costs nothing (it fails at once).
        let cost = |spec: &&sweep::RunSpec| {
            spec.scene
                .as_ref()
                .map_or(0.0, catena::studies::schedule::run_cost)
        };
        let ran: Vec<Result<bool, AppError>> =
            catena::studies::schedule::by_cost(&mine, o.jobs, cost, |spec| {
                let hash = sweep::run_hash(spec);
                if read(&hash).is_some_and(|r| r.error.is_none()) {
                    done.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                    return Ok(false);
                }
                let r = run_and_keep(&dir, &hash, spec, threads)?;
                let k = done.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
                if o.progress {
                    let el = t0.elapsed().as_secs_f64();
                    eprintln!(
                        "  {} ({}): {:.1} s{}; {k}/{n} done, {:.0} s elapsed, about {:.0} s left",
                        spec.id,
                        plan.describe(spec.point),
                        r.wall_seconds,
                        r.error
                            .as_ref()
                            .map_or(String::new(), |e| format!(", FAILED: {e}")),
                        el,
                        el / k as f64 * (n - k) as f64
                    );
                }
                Ok(true)
            });
        let mut fresh = 0;
        for r in ran {
            fresh += usize::from(r?);
        }
        let _ = writeln!(
            text,
            "sweep {}: shard {shard} of {shards}: {n} runs ({} from an earlier run), {:.1} s wall",
            plan.file,
            n - fresh,
            t0.elapsed().as_secs_f64()
        );
        if shards > 1 {
            let _ = writeln!(
                text,
                "  merge with: catena sweep {} --merge --out {}",
                plan_path.display(),
                out.display()
            );
            return Ok(text);
        }
    }
    let results: Vec<Option<RunResult>> = runs
        .iter()
        .map(|r| {
            read(&sweep::run_hash(r)).map(|x| RunResult {
                id: r.id.clone(),
                point: r.point,
                ..x
            })
        })
        .collect();
    let points = sweep::merge(&plan, &runs, &results);
    let csv_path = out.join("sweep.csv");
    std::fs::write(&csv_path, sweep::csv(&plan, &points))
        .map_err(|e| AppError::io(&csv_path, e))?;
    let js = serde_json::json!({
        "plan": plan.file,
        "parameters": plan.parameters.iter().map(|p| p.key.clone()).collect::<Vec<_>>(),
        "points": points.iter().map(|s| serde_json::json!({
            "values": s.values.iter().map(|v| v.to_string()).collect::<Vec<_>>(),
            "min_life_years": finite(s.min_life_years),
            "min_life_arc": finite(s.min_life_arc),
            "tdz_moment_range": finite(s.tdz_moment_range),
            "max_penetration": finite(s.max_penetration),
            "failed": s.failed,
        })).collect::<Vec<_>>(),
    });
    let json_path = out.join("sweep.json");
    write_json(&json_path, &js)?;
    let png = out.join("sweep.png");
    let title = figure_title(&plan);
    catena_io::plot::sweep::figure(&png, &plan, &points, &title)?;
    let failed = points.iter().filter(|p| p.failed.is_some()).count();
    let _ = writeln!(
        text,
        "  merged {} points ({failed} failed) into {}, {} and {}",
        points.len(),
        csv_path.display(),
        json_path.display(),
        png.display()
    );
    for (p, s) in points.iter().enumerate() {
        let _ = writeln!(
            text,
            "  {}: {}",
            plan.describe(p),
            match &s.failed {
                Some(e) => format!("FAILED ({e})"),
                None => format!(
                    "min life {:.4e} years at {:.1} m; moment range {:.2} kN·m; max penetration {:.4} m",
                    s.min_life_years,
                    s.min_life_arc,
                    s.tdz_moment_range / 1e3,
                    s.max_penetration
                ),
            }
        );
    }
    Ok(text)
}

/// Runs one point of the sweep and writes its result atomically to `DIR/runs/<hash>.json`.
fn run_and_keep(
    dir: &Path,
    hash: &str,
    spec: &catena::studies::sweep::RunSpec,
    threads: usize,
) -> Result<catena::studies::sweep::RunResult, AppError> {
    let r = catena::studies::sweep::run_one(spec, Some(threads));
    let path = dir.join(format!("{hash}.json"));
    let tmp = dir.join(format!("{hash}.{}.tmp", spec.id));
    let body = serde_json::to_string(&r).map_err(|e| AppError::Output {
        path: path.clone(),
        message: e.to_string(),
    })?;
    std::fs::write(&tmp, body).map_err(|e| AppError::io(&tmp, e))?;
    std::fs::rename(&tmp, &path).map_err(|e| AppError::io(&path, e))?;
    Ok(r)
}

/// The sweep figure's title: the base scene's and the swept keys.
fn figure_title(plan: &catena::studies::sweep::Plan) -> String {
    use catena::studies::sweep;
    format!(
        "{} — base of a sweep of {}",
        match &plan.base {
            sweep::Base::Study(s) => s.base.title.clone(),
            sweep::Base::Scene(s) => s.title.clone(),
        },
        plan.parameters
            .iter()
            .map(|p| p.key.as_str())
            .collect::<Vec<_>>()
            .join(" × ")
    )
}
