//! The commands: read the case, run the library, write the outputs.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Instant;

use catena::checkpoint::Checkpoint;
use catena::convergence::ConvergenceOptions;
use catena::observe::{Checkpointer, Observer, Stop};
use catena::run::{self, RunOptions};
use catena::soil_test::SoilTestCase;
use catena::statics;
use catena::AppError;
use catena_io::convergence as cv;
use catena_io::h5::{self, Recorder};
use catena_io::{plot, report, soil};

use crate::progress::{ProgressBar, SignalStop};

pub(crate) fn write_json(path: &Path, v: &serde_json::Value) -> Result<(), AppError> {
    let text = serde_json::to_string_pretty(v).map_err(|e| AppError::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    std::fs::write(path, text).map_err(|e| AppError::io(path, e))
}

/// `catena static CASE --out DIR`: `results.h5` (`/static`), `summary.json`, `static.png`.
pub fn static_(case: &Path, out: &Path) -> Result<String, AppError> {
    let scene = statics::read_scene(case)?;
    warn(&scene);
    let run = statics::solve(scene)?;
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let h5p = out.join("results.h5");
    h5::write_static(&h5p, &run)?;
    let js = out.join("summary.json");
    write_json(&js, &report::static_json(&run))?;
    let png: PathBuf = out.join("static.png");
    plot::static_line(&png, &run.scene.title, &run.model, &run.results)?;
    let mut t = report::static_text(&run);
    let _ = writeln!(
        t,
        "  wrote {}, {}, {}",
        h5p.display(),
        js.display(),
        png.display()
    );
    Ok(t)
}

/// Options of `catena run`.
#[derive(Debug, Clone, Default)]
pub struct RunCommandOptions {
    /// Show a progress bar.
    pub progress: bool,
    /// Write `DIR/checkpoint.json` every this many steps.
    pub checkpoint_every: Option<u64>,
    /// Continue from this checkpoint.
    pub restart: Option<PathBuf>,
    /// Set by the SIGINT/SIGTERM handler: the run ends at the next step.
    pub stop: Option<Arc<AtomicBool>>,
    /// Stop (successfully) after this many steps.
    pub stop_after: Option<u64>,
    /// Compress the recorded float fields (`None`: when the records are decimated, see
    /// [`compress_by_default`]).
    pub compress: Option<bool>,
}

/// Whether `results.h5`'s float fields are compressed when the user did not say: when the records
/// are decimated (`output_interval` > `time_step`). Recording every step, the writer thread's
/// deflate (about 100 MB/s of doubles on this machine, for a third off the file) cannot keep up
/// with the run and would slow it (the heave benchmark 0.34 → 0.44 s); decimated, it runs alongside
/// for nothing (Watchet: 15 → 7.8 MB, same run time).
pub fn compress_by_default(spec: &catena::scene::riser::DynamicSpec) -> bool {
    spec.output_every > 1
}

/// `catena run CASE --out DIR`: statics then dynamics; `results.h5` streamed, `summary.json`
/// (also for a run that stopped: `"completed": false` and the reason), `static.png`,
/// `dynamic.png`, `ranges.png` and, with gauges, `gauges.png`. A restart into the same DIR continues its
/// `results.h5`.
pub fn run(case: &Path, out: &Path, opts: &RunCommandOptions) -> Result<String, AppError> {
    if opts.checkpoint_every == Some(0) {
        return Err(AppError::Run {
            file: case.display().to_string(),
            message: "--checkpoint-every: expected a number of steps >= 1".into(),
        });
    }
    let restart = opts.restart.as_deref().map(Checkpoint::read).transpose()?;
    let scene = statics::read_scene(case)?;
    warn(&scene);
    if scene.dynamic.is_none() {
        return Err(AppError::Run {
            file: scene.file.clone(),
            message: "key `dynamic`: expected a [dynamic] table for `catena run` (use `catena static` for statics alone)".into(),
        });
    }
    let t_statics = Instant::now();
    let st = statics::solve(scene)?;
    let statics_seconds = t_statics.elapsed().as_secs_f64();
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let h5p = out.join("results.h5");
    let gauge_names: Vec<String> = st.scene.dynamic.as_ref().map_or_else(Vec::new, |d| {
        d.gauges.iter().map(|g| g.name.clone()).collect()
    });
    let mut old_file = None;
    let mut rec = if restart.is_some() && h5p.exists() {
        Recorder::open(&h5p, st.model.nodes(), &gauge_names)?
    } else {
        let compress = opts
            .compress
            .unwrap_or_else(|| st.scene.dynamic.as_ref().is_some_and(compress_by_default));
        // A results file of an earlier run is moved aside and deleted on another thread: truncating
        // a large file in place costs the filesystem as long as a short run's statics.
        let old = set_aside(&h5p);
        let rec = Recorder::create(&h5p, &st, &gauge_names, compress)?;
        old_file = old;
        rec
    };
    // The static plot is drawn on the other core while the dynamics run (off the stepping path),
    // then the white canvases of the two large plots drawn after the run are made there.
    let static_plot = {
        let (path, title) = (out.join("static.png"), st.scene.title.clone());
        let (model, results) = (st.model.clone(), st.results.clone());
        let created = rec.when_created(std::time::Duration::from_secs(1));
        std::thread::spawn(move || {
            created();
            plot::static_line(&path, &title, &model, &results)?;
            let dynamic = plot::Canvas::white(plot::DYNAMIC_SIZE);
            Ok((dynamic, plot::Canvas::white(plot::RANGES_MAX_SIZE)))
        })
    };
    let mut bar = ProgressBar::new();
    let mut cp = opts
        .checkpoint_every
        .map(|every| Checkpointer::new(&out.join("checkpoint.json"), every));
    let mut sig = opts.stop.clone().map(SignalStop::new);
    let mut extra: Vec<&mut dyn Observer> = vec![&mut rec];
    if opts.progress {
        extra.push(&mut bar);
    }
    if let Some(c) = cp.as_mut() {
        extra.push(c);
    }
    if let Some(s) = sig.as_mut() {
        extra.push(s);
    }
    let r = run::run(
        st,
        &mut extra,
        RunOptions {
            restart_file: opts
                .restart
                .as_deref()
                .map(|p| p.display().to_string())
                .unwrap_or_default(),
            restart,
            stop_after: opts.stop_after,
            start: None,
        },
    )?;
    drop(extra);
    let records = rec.records();
    let recording_seconds = rec.busy_seconds();
    let writer_seconds = rec.writer_seconds();
    let t_outputs = Instant::now();
    let js = out.join("summary.json");
    let (dynamic_canvas, ranges_canvas) = joined(static_plot.join(), out)?;
    // The two large plots on threads of their own while this one closes the recorder (its writer
    // writes the last records), writes the HDF5 datasets, the summary and the other plots.
    let (drawn, written) = std::thread::scope(|scope| {
        let r = &r;
        let dynamic = scope
            .spawn(move || plot::dynamic_on(&out.join("dynamic.png"), r, Some(dynamic_canvas)));
        let ranges =
            scope.spawn(move || plot::ranges_on(&out.join("ranges.png"), r, Some(ranges_canvas)));
        let written = (|| -> Result<(), AppError> {
            drop(rec);
            h5::write_fatigue(&h5p, r)?;
            h5::write_design_check(&h5p, r)?;
            h5::write_ranges(&h5p, r)?;
            write_json(&js, &report::dynamic_json(r))?;
            other_run_plots(out, r)
        })();
        (
            joined(dynamic.join(), out).and(joined(ranges.join(), out)),
            written,
        )
    });
    drawn?;
    written?;
    if let Some(t) = old_file.take() {
        let _ = t.join();
    }
    let outputs_seconds = t_outputs.elapsed().as_secs_f64();
    let mut t = report::dynamic_text(&r);
    let _ = writeln!(
        t,
        "  time: statics {:.3} s; dynamics {:.2} s ({:.0} steps/s), of which recording {:.2} s (writing and compressing {:.2} s alongside, on its own thread); plots and summary {:.2} s",
        statics_seconds,
        r.wall_seconds,
        r.steps as f64 / r.wall_seconds.max(1e-9),
        recording_seconds,
        writer_seconds,
        outputs_seconds
    );
    let _ = writeln!(
        t,
        "  wrote {} ({} records), {}, plots in {}",
        h5p.display(),
        records,
        js.display(),
        out.display()
    );
    match &r.stop {
        Some(Stop::Failed(_)) | Some(Stop::Interrupted(_)) | Some(Stop::NonFinite { .. }) => {
            Err(AppError::Run {
                file: r.statics.scene.file.clone(),
                message: format!(
                    "{}\n{t}results up to the last converged step (t = {} s) are in {}",
                    r.stop.as_ref().map(ToString::to_string).unwrap_or_default(),
                    r.t_reached,
                    h5p.display()
                ),
            })
        }
        _ => Ok(t),
    }
}

/// Moves an existing file aside (a hidden name beside it) and deletes it on a thread of its own,
/// returned to be joined; `None` if there is no such file or it cannot be moved (then it is
/// truncated in place as before).
fn set_aside(path: &Path) -> Option<std::thread::JoinHandle<()>> {
    if !path.exists() {
        return None;
    }
    let name = path.file_name()?.to_string_lossy().into_owned();
    let aside = path.with_file_name(format!(".{name}.old-{}", std::process::id()));
    std::fs::rename(path, &aside).ok()?;
    Some(std::thread::spawn(move || {
        let _ = std::fs::remove_file(aside);
    }))
}

/// A plotting thread's result: its error, or its panic as an error naming the output folder.
fn joined<T>(r: std::thread::Result<Result<T, AppError>>, out: &Path) -> Result<T, AppError> {
    r.unwrap_or_else(|_| {
        Err(AppError::Plot {
            path: out.to_path_buf(),
            message: "a plotting thread panicked".into(),
        })
    })
}

/// The plots of `catena run` besides the static, dynamic and range plots: the design check, the
/// extremes (with `extremes.json`), the gauges and the sea, each when the run has it.
fn other_run_plots(out: &Path, r: &catena::run::DynamicRun) -> Result<(), AppError> {
    if r.output::<catena::design_observer::DesignCheck>().is_some() {
        plot::design_check(&out.join("design_check.png"), r)?;
    }
    if let Some(x) = r.output::<catena::extremes_observer::ExtremesObserver>() {
        write_json(
            &out.join("extremes.json"),
            &serde_json::to_value(&x.results).unwrap_or_default(),
        )?;
        let items: Vec<_> = x
            .results
            .iter()
            .filter_map(|e| {
                let k = x.spec.channels.iter().position(|c| c.name == e.channel)?;
                Some((e, x.records[k].as_slice(), x.dt))
            })
            .collect();
        plot::extremes(
            &out.join("extremes.png"),
            &format!("{} — short-term extremes", r.statics.scene.title),
            &items,
        )?;
    }
    if !r.spec.gauges.is_empty() {
        plot::gauges(&out.join("gauges.png"), r)?;
    }
    if r.model.environment.waves.is_some() {
        plot::sea(&out.join("sea.png"), r)?;
    }
    Ok(())
}

/// `catena rainflow SERIES.csv --out CYCLES.csv [--column NAME] [--sn CURVE] [--scf X]`: rainflow
/// counting (ASTM E1049-85) of one column; with an S-N curve, Miner's damage of the series (its
/// values taken as stress in MPa, multiplied by the SCF).
pub fn rainflow(
    series: &Path,
    out: &Path,
    column: Option<&str>,
    sn: Option<&str>,
    scf: f64,
) -> Result<String, AppError> {
    let curve = match sn {
        Some(name) => {
            Some(
                catena::fatigue::sn::SnCurve::dnv(name).ok_or_else(|| AppError::Run {
                    file: series.display().to_string(),
                    message: format!(
                        "--sn {name}: not a curve catena knows; expected one of {}",
                        catena::fatigue::sn::NAMES.join(", ")
                    ),
                })?,
            )
        }
        None => None,
    };
    if !(scf.is_finite() && scf > 0.0) {
        return Err(AppError::Run {
            file: series.display().to_string(),
            message: format!("--scf {scf}: expected a stress concentration factor > 0"),
        });
    }
    let v = catena_io::series::read_series(series, column)?;
    let cycles = catena::fatigue::rainflow::count(&v);
    catena_io::series::write_cycles(out, &cycles)?;
    let total: f64 = cycles.iter().map(|c| c.count).sum();
    let largest = cycles.iter().map(|c| c.range).fold(0.0, f64::max);
    let mut t = format!(
        "rainflow {}: {} samples, {} cycles counted ({} in all, halves included), largest range {largest}\n  wrote {}\n",
        series.display(),
        v.len(),
        cycles.len(),
        total,
        out.display()
    );
    if let (Some(c), Some(name)) = (curve, sn) {
        let d = catena::fatigue::sn::miner(cycles.iter().map(|c| (c.range, c.count)), &c, scf);
        let _ = writeln!(
            t,
            "  Miner damage on {name} (SCF {scf}, ranges in MPa): {d:.6e}"
        );
    }
    Ok(t)
}

/// `catena soil-test CASE --out RESULT.csv [--plot PNG]`.
pub fn soil_test(
    case_path: &Path,
    out: &Path,
    plot_path: Option<&Path>,
) -> Result<String, AppError> {
    let case = SoilTestCase::read(case_path)?;
    let r = case.run()?;
    soil::write_csv(out, &case, &r)?;
    if let Some(p) = plot_path {
        let cycles = case.cycle_ends(&r);
        let z_start = case.start_of_cycles(&r);
        plot::soil_test(p, &case, &r, &cycles, z_start)?;
    }
    Ok(soil::text(&case, &r, out, plot_path))
}

/// The whole command: runs the study and writes `DIR/convergence.csv`, `DIR/convergence.json`,
/// `DIR/convergence.png` and the variant scenes in `DIR/scenes/`.
pub fn convergence(case: &Path, out: &Path, opts: &ConvergenceOptions) -> Result<String, AppError> {
    let st = catena::convergence::study(case, opts)?;
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
    std::fs::write(&c, cv::csv(&st)).map_err(|e| AppError::io(&c, e))?;
    let j = out.join("convergence.json");
    std::fs::write(
        &j,
        serde_json::to_string_pretty(&cv::to_json(&st)).unwrap_or_default(),
    )
    .map_err(|e| AppError::io(&j, e))?;
    let png = out.join("convergence.png");
    cv::plot(&png, &st)?;
    let mut t = cv::summary_text(&st);
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
    use catena::study::{run_storm, StormResult, Study};
    let t0 = std::time::Instant::now();
    let study = Study::read(study_path)?;
    let touchdown = statics::solve(study.base.clone())?.summary.touchdown_arc;
    let dir = out.join("storms");
    std::fs::create_dir_all(&dir).map_err(|e| AppError::io(&dir, e))?;
    let n = study.storms.len();
    let (rs, reused) = resumable(
        &study.file,
        &study.storms,
        jobs,
        |(storm, _)| dir.join(format!("{}.json", storm.id)),
        |(storm, scene), r: &StormResult| {
            r.scene_hash == catena::scene::text_hash(&scene.text)
                && r.error.is_none()
                && r.storm == *storm
        },
        |(storm, scene)| run_storm(storm, scene),
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
    catena_io::fatigue::life_png(&out.join("life.png"), &l, touchdown, &title)?;
    let (i, life, fibre) = catena_io::fatigue::minimum(&l).unwrap_or((0, f64::NAN, String::new()));
    let shares = catena::study::shares(&rs, &fibre, i);
    catena_io::fatigue::storms_png(
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
    use catena::sweep::{self, Plan, RunResult};
    use rayon::prelude::*;
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
        let done = std::sync::atomic::AtomicUsize::new(0);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(o.jobs.max(1))
            .build()
            .map_err(|e| AppError::Run {
                file: plan.file.clone(),
                message: format!("--jobs: cannot start {} threads: {e}", o.jobs),
            })?;
        let ran: Vec<Result<bool, AppError>> = pool.install(|| {
            mine.par_iter()
                .map(|spec| {
                    let hash = sweep::run_hash(spec);
                    if read(&hash).is_some_and(|r| r.error.is_none()) {
                        done.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                        return Ok(false);
                    }
                    let r = sweep::run_one(spec);
                    let path = dir.join(format!("{hash}.json"));
                    let tmp = dir.join(format!("{hash}.{}.tmp", spec.id));
                    let body = serde_json::to_string(&r).map_err(|e| AppError::Output {
                        path: path.clone(),
                        message: e.to_string(),
                    })?;
                    std::fs::write(&tmp, body).map_err(|e| AppError::io(&tmp, e))?;
                    std::fs::rename(&tmp, &path).map_err(|e| AppError::io(&path, e))?;
                    let k = done.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
                    if o.progress {
                        let el = t0.elapsed().as_secs_f64();
                        eprintln!(
                            "  {} ({}): {:.1} s{}; {k}/{n} done, {:.0} s elapsed, about {:.0} s left",
                            spec.id,
                            plan.describe(spec.point),
                            r.wall_seconds,
                            r.error.as_ref().map_or(String::new(), |e| format!(", FAILED: {e}")),
                            el,
                            el / k as f64 * (n - k) as f64
                        );
                    }
                    Ok(true)
                })
                .collect()
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
    let title = format!(
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
    );
    catena_io::sweep::figure(&png, &plan, &points, &title)?;
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

/// A finite number, or JSON null.
fn finite(x: f64) -> serde_json::Value {
    if x.is_finite() {
        serde_json::json!(x)
    } else {
        serde_json::Value::Null
    }
}

/// Measured cost of one element-step (`benches/README.md`, the scaling table: 0.38–0.39 µs for the
/// linear seabed on this project's reference machine; a seabed law's factor is its
/// `Law::relative_cost`, e.g. 1.9 for the Randolph–Quiggin law: a 300 s storm, 4.45 s against
/// 2.31 s) and for 400 wave components (+52 % a step).
const US_PER_ELEMENT_STEP: f64 = 0.39;
const WAVES_FACTOR_400: f64 = 1.52;

/// A scene's warnings (what it does that may not be meant), on standard error.
fn warn(scene: &catena::scene::riser::RiserScene) {
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
}

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
            if d.motion.is_none() && d.vessel.is_none() && d.environment.waves.is_none() {
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
        let plan = catena::sweep::Plan::read(case)?;
        let runs = plan.runs();
        let _ = writeln!(
            t,
            "{file}: a sweep of {} points, {} runs",
            plan.points.len(),
            runs.len()
        );
        let per_run = match &plan.base {
            catena::sweep::Base::Study(s) => {
                let mut sum = 0.0;
                for (_, sc) in &s.storms {
                    let mut scratch = String::new();
                    sum += describe_scene(sc, &mut scratch, &mut warnings);
                }
                sum / s.storms.len().max(1) as f64
            }
            catena::sweep::Base::Scene(sc) => describe_scene(sc, &mut t, &mut warnings),
        };
        let _ = writeln!(
            t,
            "  estimated: {:.2} core-hours in all ({:.0} s a run on average)",
            per_run * runs.len() as f64 / 3600.0,
            per_run
        );
    } else if doc.contains_key("sequence") {
        let seq = catena::sequence::Sequence::read(case)?;
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
        let study = catena::strength::StrengthStudy::read(case)?;
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
        let study = catena::study::Study::read(case)?;
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

/// What `catena extremes` is asked for.
#[derive(Debug, Clone, Default)]
pub struct ExtremesOptions {
    /// The channels (empty: the defaults of the input).
    pub channels: Vec<String>,
    /// The record starts here, s (default: the file's first time).
    pub start: Option<f64>,
    /// The analysis' target duration, quantile and block (defaults: 3 h, 0.9, 600 s).
    pub settings: catena::extremes::Settings,
}

/// `catena animate RESULTS.h5 --out tdz.gif`: the animated touchdown zone
/// ([`catena_io::animate`]); prints the frames, the file's size and the time it took.
pub fn animate(
    results: &Path,
    out: &Path,
    frames: usize,
    fps: f64,
    colour: &str,
) -> Result<String, AppError> {
    let bad = |key: &str, what: String| AppError::Run {
        file: results.display().to_string(),
        message: format!("{key}: {what}"),
    };
    let colour = catena_io::animate::Colour::parse(colour).ok_or_else(|| {
        bad(
            "--colour",
            format!("expected penetration or seabed-force, got `{colour}`"),
        )
    })?;
    if frames < 2 {
        return Err(bad(
            "--frames",
            format!("expected at least 2, got {frames}"),
        ));
    }
    if !(fps.is_finite() && fps > 0.0 && fps <= 50.0) {
        return Err(bad("--fps", format!("expected 0 < fps <= 50, got {fps}")));
    }
    if out.extension().and_then(|e| e.to_str()) != Some("gif") {
        return Err(bad(
            "--out",
            format!("expected a file name ending in .gif, got {}", out.display()),
        ));
    }
    let t0 = std::time::Instant::now();
    let rec = catena_io::h5::read_animation(results)?;
    let opts = catena_io::animate::Options {
        frames,
        fps,
        colour,
        ..Default::default()
    };
    let r = catena_io::animate::animate(out, &rec, &opts)?;
    Ok(format!(
        "animation: {} ({} frames of {:.1} s of the run, {:.0} kB, {:.1} s to draw)\n",
        out.display(),
        r.frames,
        r.seconds,
        r.bytes as f64 / 1e3,
        t0.elapsed().as_secs_f64()
    ))
}

/// `catena extremes RESULTS.h5|SERIES.csv --out DIR`: the short-term extremes of recorded channels
/// (`catena::extremes`): from a results file, `top_tension`, `least_tension`, `sag_moment`,
/// `utilisation` (with a design check) and `gauge:NAME[:max]`; from a CSV file (a header with
/// `time` first, then one column per channel; a `:min` suffix on a column's name analyses its
/// least), every column or the chosen ones. Writes DIR/extremes.json and DIR/extremes.png.
pub fn extremes(input: &Path, out: &Path, opts: &ExtremesOptions) -> Result<String, AppError> {
    use catena::extremes::{analyse, Tail};
    let bad = |message: String| AppError::Run {
        file: input.display().to_string(),
        message,
    };
    let s = &opts.settings;
    if !(s.target > 0.0 && s.block > 0.0 && s.quantile > 0.0 && s.quantile < 1.0) {
        return Err(bad(
            "--target and --block must be > 0 s and --quantile in (0, 1)".into(),
        ));
    }
    let is_h5 = input.extension().is_some_and(|e| e == "h5" || e == "hdf5");
    let (time, channels) = if is_h5 {
        catena_io::h5::read_extreme_channels(input, &opts.channels)?
    } else {
        let names = catena_io::series::column_names(input)?;
        if names.first().map(String::as_str) != Some("time") {
            return Err(bad(format!(
                "expected `time` (s) as the first column, then one column per channel; the header has {}",
                names.join(", ")
            )));
        }
        let time = catena_io::series::read_series(input, Some("time"))?;
        let wanted: Vec<String> = if opts.channels.is_empty() {
            names[1..].to_vec()
        } else {
            opts.channels.clone()
        };
        let mut v = Vec::new();
        for w in wanted {
            if !names.contains(&w) {
                return Err(bad(format!(
                    "--channel {w}: no such column (the header has {})",
                    names.join(", ")
                )));
            }
            let tail = if w.ends_with(":min") {
                Tail::Min
            } else {
                Tail::Max
            };
            v.push((
                w.clone(),
                tail,
                catena_io::series::read_series(input, Some(&w))?,
            ));
        }
        (time, v)
    };
    if time.len() < 3 {
        return Err(bad("fewer than three samples".into()));
    }
    let dt = time[1] - time[0];
    if time
        .windows(2)
        .any(|w| ((w[1] - w[0]) - dt).abs() > 1e-6 * dt.abs().max(1e-12))
        || dt <= 0.0
    {
        return Err(bad(
            "the times are not equally spaced and increasing (the statistics need a uniform record)".into(),
        ));
    }
    let from = opts.start.unwrap_or(time[0]);
    let first = time.partition_point(|t| *t < from - 1e-9);
    let mut results = Vec::new();
    let mut records = Vec::new();
    for (name, tail, v) in &channels {
        let x = &v[first..];
        match analyse(name, *tail, x, dt, s) {
            Some(e) => {
                results.push(e);
                records.push(x);
            }
            None => {
                return Err(bad(format!(
                    "--channel {name}: too short or constant from t = {from} s to analyse"
                )))
            }
        }
    }
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let js = out.join("extremes.json");
    write_json(&js, &serde_json::to_value(&results).unwrap_or_default())?;
    let items: Vec<_> = results
        .iter()
        .zip(&records)
        .map(|(e, x)| (e, *x, dt))
        .collect();
    catena_io::plot::extremes(
        &out.join("extremes.png"),
        &format!("{} — short-term extremes", input.display()),
        &items,
    )?;
    let mut t = format!(
        "extremes of {}: {} channels, records from t = {from} s every {dt} s\n",
        input.display(),
        results.len()
    );
    for e in &results {
        t.push_str(&catena_io::report::extremes_line(e));
    }
    let _ = writeln!(
        t,
        "  wrote {} and {}",
        js.display(),
        out.join("extremes.png").display()
    );
    Ok(t)
}

/// `catena strength STUDY.toml --out DIR [--jobs N]`: the strength study
/// ([`catena::strength`]): every storm and seed run (in parallel with `--jobs`), each written to
/// DIR/runs/<storm>-<seed>.json as it finishes (a rerun skips the runs whose scene is unchanged),
/// then per storm the utilisation along the line over its seeds and the extremes across them:
/// DIR/summary.json, DIR/utilisation.csv, DIR/strength.png.
pub fn strength(
    study_path: &Path,
    out: &Path,
    jobs: usize,
    progress: bool,
) -> Result<String, AppError> {
    use catena::strength::{run_one, RunResult, StrengthStudy};
    let t0 = std::time::Instant::now();
    let study = StrengthStudy::read(study_path)?;
    let st = statics::solve(study.base.clone())?;
    let dir = out.join("runs");
    std::fs::create_dir_all(&dir).map_err(|e| AppError::io(&dir, e))?;
    let n = study.runs.len();
    let (rs, reused) = resumable(
        &study.file,
        &study.runs,
        jobs,
        |run| dir.join(format!("{}-{}.json", run.storm.id, run.seed)),
        |run, r: &RunResult| {
            r.scene_hash == catena::scene::text_hash(&run.scene.text)
                && r.error.is_none()
                && r.storm == run.storm
        },
        run_one,
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
    let summary = catena::strength::summarise(&rs, quantile);
    let arc = &st.model.arc;
    let static_u: Vec<f64> = study
        .runs
        .first()
        .and_then(|r| r.scene.dynamic.as_ref())
        .and_then(|d| catena::design_observer::evaluator_for(d, &st.results))
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
    let mut csv = String::from("arc_m,static_utilisation");
    for s in &summary {
        let _ = write!(
            csv,
            ",storm{}_envelope,storm{}_mean_over_seeds",
            s.storm.id, s.storm.id
        );
    }
    csv.push('\n');
    for (i, a) in arc.iter().enumerate() {
        let _ = write!(csv, "{a},{}", static_u.get(i).copied().unwrap_or(f64::NAN));
        for s in &summary {
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
    for s in &summary {
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
            let _ = writeln!(
                t,
                "    {}: per seed mean {:.6e} (sd {:.3e}){}",
                c.channel,
                c.mean,
                c.std_dev,
                c.gumbel.map_or(String::new(), |(_, v)| format!(
                    "; Gumbel across seeds: most probable {:.6e}, quantile {:.6e}",
                    v[0], v[1]
                ))
            );
        }
    }
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

/// Runs `items` on `jobs` threads, each result written atomically to its JSON file (`path_of`) as
/// it finishes and `done` told (with how many are done); an item whose file holds a result that
/// `reuse` accepts is taken from there and not run. Returns the results in the items' order and
/// how many were reused. (The fatigue and the strength studies: a rerun resumes.)
pub(crate) fn resumable<I: Sync, R: serde::Serialize + serde::de::DeserializeOwned + Send>(
    file: &str,
    items: &[I],
    jobs: usize,
    path_of: impl Fn(&I) -> PathBuf + Sync,
    reuse: impl Fn(&I, &R) -> bool + Sync,
    run: impl Fn(&I) -> Result<R, AppError> + Sync,
    done: impl Fn(&I, &R, usize) + Sync,
) -> Result<(Vec<R>, usize), AppError> {
    use rayon::prelude::*;
    let count = std::sync::atomic::AtomicUsize::new(0);
    let one = |item: &I| -> Result<(R, bool), AppError> {
        let path = path_of(item);
        if let Ok(text) = std::fs::read_to_string(&path) {
            if let Ok(r) = serde_json::from_str::<R>(&text) {
                if reuse(item, &r) {
                    count.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                    return Ok((r, true));
                }
            }
        }
        let r = run(item)?;
        let tmp = path.with_extension("json.tmp");
        let text = serde_json::to_string(&r).map_err(|e| AppError::Output {
            path: path.clone(),
            message: e.to_string(),
        })?;
        std::fs::write(&tmp, text).map_err(|e| AppError::io(&tmp, e))?;
        std::fs::rename(&tmp, &path).map_err(|e| AppError::io(&path, e))?;
        let k = count.fetch_add(1, std::sync::atomic::Ordering::SeqCst) + 1;
        done(item, &r, k);
        Ok((r, false))
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.max(1))
        .build()
        .map_err(|e| AppError::Run {
            file: file.to_string(),
            message: format!("--jobs: cannot start {jobs} threads: {e}"),
        })?;
    let results: Vec<Result<(R, bool), AppError>> =
        pool.install(|| items.par_iter().map(one).collect());
    let mut out = Vec::with_capacity(items.len());
    let mut reused = 0;
    for r in results {
        let (r, old) = r?;
        reused += usize::from(old);
        out.push(r);
    }
    Ok((out, reused))
}
