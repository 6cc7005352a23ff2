//! `catena run` on a scene with `[lay]`: the pipe's installation. Writes `results.h5` (`/lay/`),
//! `summary.json` (`lay`), `summary.txt`, `lay.png` and `laid-seabed.json` (the seabed it left,
//! for a following scene's `[as_laid]`), also when the lay stopped early (everything up to its
//! last converged step).

use std::fmt::Write as _;
use std::path::Path;
use std::sync::atomic::Ordering;

use catena::run::lay::{self, LayRun};
use catena::run::observe::Stop;
use catena::scene::riser::RiserScene;
use catena::AppError;
use catena_io::{h5, lay as report, plot};

use super::{write_json, RunCommandOptions};

/// Lays the pipe of `scene` and writes its outputs into `out`: with `--checkpoint-every N`, a
/// checkpoint `DIR/checkpoint.json` every N steps; with `--restart FILE`, from that checkpoint;
/// `--stop-after N` ends after N steps.
pub fn run_lay(
    scene: RiserScene,
    out: &Path,
    opts: &RunCommandOptions,
) -> Result<String, AppError> {
    let (progress, stop) = (opts.progress, opts.stop.clone());
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let restart = match &opts.restart {
        Some(p) => Some((
            lay::checkpoint::LayCheckpoint::read(p)?,
            p.display().to_string(),
        )),
        None => None,
    };
    let lay_opts = lay::LayOptions {
        checkpoint: opts
            .checkpoint_every
            .map(|every| (out.join("checkpoint.json"), every)),
        restart,
        stop_after: opts.stop_after,
        threads: opts.threads,
        pair_schedule: None,
    };
    let mut last_shown = 0.0;
    let mut on_step = |p: &lay::LayProgress| {
        if progress && p.t - last_shown >= 0.02 * p.duration {
            last_shown = p.t;
            eprint!(
                "\r  lay: t = {:.0} / {:.0} s, {:.1} m paid out, {} nodes in the solve   ",
                p.t, p.duration, p.paid_out, p.window_nodes
            );
        }
        !stop.as_ref().is_some_and(|s| s.load(Ordering::Relaxed))
    };
    let st = catena::run::statics::solve(lay::statics_scene(scene))?;
    let r = lay::lay_with(st, lay_opts, &mut on_step)?;
    if progress {
        eprintln!();
    }
    write_outputs(&r, out)?;
    let t = report::text(&r);
    let mut t = t;
    let _ = writeln!(
        t,
        "  wrote results.h5, summary.json, summary.txt, lay.png and laid-seabed.json in {}",
        out.display()
    );
    match &r.stop {
        Some(s @ (Stop::Failed(_) | Stop::Interrupted(_) | Stop::NonFinite { .. })) => {
            Err(AppError::Run {
                file: r.statics.scene.file.clone(),
                message: format!(
                    "{s}\n{t}results up to the last converged step (t = {:.3} s) are in {}",
                    r.records.time.last().copied().unwrap_or(0.0),
                    out.display()
                ),
            })
        }
        _ => Ok(t),
    }
}

/// The files of a lay (`laid-seabed.json`: the seabed it left, for a following scene's
/// `[as_laid]`).
pub fn write_outputs(r: &LayRun, out: &Path) -> Result<(), AppError> {
    write_json(&out.join("summary.json"), &report::json(r))?;
    let laid = serde_json::to_value(r.laid_seabed()).map_err(|e| AppError::Output {
        path: out.join("laid-seabed.json"),
        message: e.to_string(),
    })?;
    write_json(&out.join("laid-seabed.json"), &laid)?;
    let txt = out.join("summary.txt");
    std::fs::write(&txt, report::text(r)).map_err(|e| AppError::io(&txt, e))?;
    h5::write_lay(&out.join("results.h5"), r)?;
    plot::lay(&out.join("lay.png"), r)
}
