//! Checkpoints: everything a restart needs besides the Model, which is rebuilt from the scene.
//!
//! A checkpoint holds the State, the solver's memory (the last factorised tangent, so the restarted
//! run is bit-for-bit the uninterrupted one whatever the checkpoint interval), every observer's
//! state, the scene's text hash and the catena version. [`Checkpoint::check`] refuses one that does
//! not match the run with an error that says what differs: another scene, another version, array
//! lengths, a step or time out of line.

use std::collections::BTreeMap;
use std::path::Path;

use catena_fe::dynamics::{DynState, DynamicModel, SolverMemory};
use serde::{Deserialize, Serialize};

use crate::error::AppError;
use crate::scene::riser::DynamicSpec;

/// The catena version checkpoints and results are stamped with.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// A checkpoint of a dynamic run after a converged step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checkpoint {
    /// The catena version that wrote it.
    pub catena_version: String,
    /// The scene file it was written for (for messages).
    pub scene_file: String,
    /// The hash of the scene's text ([`crate::scene::text_hash`]).
    pub scene_hash: String,
    /// Completed time steps of `dynamic.time_step`.
    pub step: u64,
    /// The State.
    pub state: DynState,
    /// The solver's memory (the factorisation the next step reuses), if any.
    pub solver: Option<SolverMemory>,
    /// Each observer's saved state, by name.
    pub observers: BTreeMap<String, serde_json::Value>,
}

impl Checkpoint {
    /// Writes the checkpoint as JSON (exact: floats round-trip), replacing the file atomically.
    pub fn write(&self, path: &Path) -> Result<(), AppError> {
        write_json(path, self)
    }

    /// Reads a checkpoint.
    pub fn read(path: &Path) -> Result<Self, AppError> {
        read_json(path, "a catena checkpoint")
    }

    /// Checks that the checkpoint continues this run: the same version and scene, a State that fits
    /// the Model, a step within the run, and a time equal to `step·Δt`. `file` names the checkpoint.
    pub fn check(
        &self,
        file: &str,
        scene_text: &str,
        dm: &DynamicModel,
        spec: &DynamicSpec,
    ) -> Result<(), AppError> {
        let bad = |what: String| AppError::Checkpoint {
            file: file.to_string(),
            what,
        };
        same_origin(
            (&self.catena_version, &self.scene_hash, &self.scene_file),
            scene_text,
        )
        .map_err(bad)?;
        self.state.check_fits(dm).map_err(bad)?;
        let n_steps = (spec.duration / spec.dt).round() as u64;
        if self.step == 0 || self.step > n_steps {
            return Err(bad(format!(
                "step {} is not within the run's {n_steps} steps",
                self.step
            )));
        }
        let t = self.step as f64 * spec.dt;
        if (self.state.t - t).abs() > 1e-9 * t.max(spec.dt) {
            return Err(bad(format!(
                "state.t = {} s does not match step {} of {} s (t = {t} s)",
                self.state.t, self.step, spec.dt
            )));
        }
        if self.state.step < self.step {
            return Err(bad(format!(
                "state.step = {} is fewer than the {} steps completed",
                self.state.step, self.step
            )));
        }
        Ok(())
    }
}

/// Writes a checkpoint (any of a run's kinds) as JSON, replacing the file atomically.
pub(crate) fn write_json(path: &Path, value: &impl Serialize) -> Result<(), AppError> {
    let tmp = path.with_extension("json.tmp");
    let text = serde_json::to_string(value).map_err(|e| AppError::Output {
        path: path.to_path_buf(),
        message: format!("cannot write the checkpoint: {e}"),
    })?;
    std::fs::write(&tmp, text).map_err(|e| AppError::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| AppError::io(path, e))
}

/// Reads a checkpoint (`what` it should be, for the message).
pub(crate) fn read_json<T: serde::de::DeserializeOwned>(
    path: &Path,
    what: &str,
) -> Result<T, AppError> {
    let text = std::fs::read_to_string(path).map_err(|e| AppError::io(path, e))?;
    serde_json::from_str(&text).map_err(|e| AppError::Checkpoint {
        file: path.display().to_string(),
        what: format!("not {what} ({e})"),
    })
}

/// Whether a checkpoint written by `(version, scene hash, scene file)` is of this catena and this
/// scene's text; else what differs.
pub(crate) fn same_origin(
    (version, hash, scene_file): (&str, &str, &str),
    scene_text: &str,
) -> Result<(), String> {
    if version != VERSION {
        return Err(format!(
            "it was written by catena {version}, this is catena {VERSION}"
        ));
    }
    if hash != crate::scene::text_hash(scene_text) {
        return Err(format!(
            "it was written for another scene (the text of {scene_file} differs)"
        ));
    }
    Ok(())
}
