//! The commands, one module each: read the case, run the library, write the outputs. The helpers
//! they share (a JSON file written, a scene's warnings, resumable parallel runs) are here; each
//! command's function is re-exported under its old name (`commands::run`, `commands::check`, …).
//! A new command: its module here, its `pub use` below, its clap variant in `main.rs`.

pub mod animate;
pub mod calibrate;
pub mod check;
pub mod convergence;
pub mod extremes;
pub mod fatigue;
pub mod lay;
pub mod rainflow;
pub mod run;
pub mod sequence;
pub mod soil_test;
pub mod statics;
pub mod strength;
pub mod sweep;

pub use animate::animate;
pub use check::check;
pub use convergence::convergence;
pub use extremes::{extremes, ExtremesOptions};
pub use fatigue::fatigue;
pub use rainflow::rainflow;
pub use run::{compress_by_default, run};
pub use soil_test::soil_test;
pub use statics::static_;
pub use strength::strength;
pub use sweep::{sweep, SweepOptions};

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use catena::AppError;

/// Options of `catena run` (a lay's too: `run` hands a scene with a `[lay]` to [`lay::run_lay`]).
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
    /// [`run::compress_by_default`]).
    pub compress: Option<bool>,
    /// The threads the run may keep busy (`None`: the machine's cores;
    /// [`catena::run::RunOptions::threads`]).
    pub threads: Option<usize>,
}

pub(crate) fn write_json(path: &Path, v: &serde_json::Value) -> Result<(), AppError> {
    let text = serde_json::to_string_pretty(v).map_err(|e| AppError::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    std::fs::write(path, text).map_err(|e| AppError::io(path, e))
}

/// A finite number, or JSON null.
fn finite(x: f64) -> serde_json::Value {
    if x.is_finite() {
        serde_json::json!(x)
    } else {
        serde_json::Value::Null
    }
}

/// A scene's warnings (what it does that may not be meant), on standard error.
fn warn(scene: &catena::scene::riser::RiserScene) {
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
}

/// Runs `items` on `jobs` threads, the most expensive first by `cost`
/// ([`catena::studies::schedule`]), each result written atomically to its JSON file (`path_of`) as
/// it finishes and `done` told (with how many are done); an item whose file holds a result that
/// `reuse` accepts is taken from there and not run. Returns the results in the items' order and
/// how many were reused. (The fatigue and the strength studies: a rerun resumes.)
#[allow(clippy::too_many_arguments)]
pub(crate) fn resumable<I: Sync, R: serde::Serialize + serde::de::DeserializeOwned + Send>(
    items: &[I],
    (jobs, cost): (usize, impl Fn(&I) -> f64),
    path_of: impl Fn(&I) -> PathBuf + Sync,
    reuse: impl Fn(&I, &R) -> bool + Sync,
    run: impl Fn(&I) -> Result<R, AppError> + Sync,
    done: impl Fn(&I, &R, usize) + Sync,
) -> Result<(Vec<R>, usize), AppError> {
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
    let results: Vec<Result<(R, bool), AppError>> =
        catena::studies::schedule::by_cost(items, jobs, cost, one);
    let mut out = Vec::with_capacity(items.len());
    let mut reused = 0;
    for r in results {
        let (r, old) = r?;
        reused += usize::from(old);
        out.push(r);
    }
    Ok((out, reused))
}
