//! `catena run`: statics and dynamics with every output; the files and plots are kept off the
//! stepping path.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use catena::run::checkpoint::Checkpoint;
use catena::run::observe::{Checkpointer, Observer, Stop};
use catena::run::statics;
use catena::run::{self, RunOptions};
use catena::AppError;
use catena_io::h5::{self, Recorder};
use catena_io::{plot, report};

use crate::progress::{ProgressBar, SignalStop};

use super::{warn, write_json, RunCommandOptions};

/// Whether `results.h5`'s float fields are compressed when the user did not say: when the records
/// are decimated (`output_interval` > `time_step`) and the run may keep three threads busy or more
/// (`threads`, [`RunOptions::threads`]). Recording every step, the writer thread's deflate (about
/// 100 MB/s of doubles on this machine, for a third off the file) cannot keep up with the run and
/// would slow it (the heave benchmark 0.34 → 0.44 s). Decimated, it runs alongside for nothing
/// where it has a core of its own (Watchet: 15 → 7.8 MB, same run time); with two threads or fewer
/// the records stay uncompressed, so that the writer keeps no core busy and the line steps on two
/// threads beside it ([`catena_io::h5::writer_keeps_core`]: storm 23 in 10.1–12.2 s against
/// 13.9–15.0 s on one thread compressing, on two cores; `--compress yes` keeps the smaller file).
pub fn compress_by_default(spec: &catena::scene::riser::DynamicSpec, threads: usize) -> bool {
    spec.output_every > 1 && threads >= 3
}

/// The text summary's line of where the time went: the statics, the dynamics (on how many threads
/// the line stepped), the recording on the run's thread (`recording`: its seconds, the writer's
/// alongside, and whether it compressed) and the outputs after the run.
fn time_line(
    r: &run::DynamicRun,
    statics_seconds: f64,
    (recording, writer, compressed): (f64, f64, bool),
    outputs_seconds: f64,
) -> String {
    let threads = r.stepping_threads;
    let writing = match compressed {
        true => "writing and compressing",
        false => "writing",
    };
    format!(
        "  time: statics {statics_seconds:.3} s; dynamics {:.2} s on {threads} thread{}{} ({:.0} \
         steps/s), of which recording {recording:.2} s ({writing} {writer:.2} s alongside, on its \
         own thread); plots and summary {outputs_seconds:.2} s\n",
        r.wall_seconds,
        if threads == 1 { "" } else { "s" },
        catena_io::report::share_on_two(r.steps_on_two, r.steps),
        r.steps as f64 / r.wall_seconds.max(1e-9),
    )
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
    let scene = statics::read_scene(case)?;
    warn(&scene);
    if scene.lay.is_some() {
        return super::lay::run_lay(scene, out, opts);
    }
    let restart = opts.restart.as_deref().map(Checkpoint::read).transpose()?;
    needs_dynamic(&scene)?;
    let (st, statics_seconds) = {
        let t = Instant::now();
        (statics::solve(scene)?, t.elapsed().as_secs_f64())
    };
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let h5p = out.join("results.h5");
    let gauge_names: Vec<String> = st.scene.dynamic.as_ref().map_or_else(Vec::new, |d| {
        d.gauges.iter().map(|g| g.name.clone()).collect()
    });
    let mut old_file = None;
    let mut rec = if restart.is_some() && h5p.exists() {
        Recorder::open(&h5p, &st, &gauge_names)?
    } else {
        let threads = opts.threads.unwrap_or_else(run::default_threads);
        let compress = opts.compress.unwrap_or_else(|| {
            let dynamic = st.scene.dynamic.as_ref();
            dynamic.is_some_and(|d| compress_by_default(d, threads))
        });
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
            threads: opts.threads,
        },
    )?;
    drop(extra);
    let records = rec.records();
    let recording = (rec.busy_seconds(), rec.writer_seconds(), rec.compressed());
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
    t += &time_line(&r, statics_seconds, recording, outputs_seconds);
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

/// `catena run` needs a `[dynamic]` table.
fn needs_dynamic(scene: &catena::scene::riser::RiserScene) -> Result<(), AppError> {
    match scene.dynamic {
        Some(_) => Ok(()),
        None => Err(AppError::Run {
            file: scene.file.clone(),
            message: "key `dynamic`: expected a [dynamic] table for `catena run` (use `catena static` for statics alone)".into(),
        }),
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
    if r.output::<catena::run::observers::design::DesignCheck>()
        .is_some()
    {
        plot::design_check(&out.join("design_check.png"), r)?;
    }
    if let Some(x) = r.output::<catena::run::observers::extremes::ExtremesObserver>() {
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
