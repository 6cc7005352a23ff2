//! Range checks shared by the scene's tables: each error names the file, the key and what was
//! expected.

use super::invalid;
use crate::error::SceneError;

/// A Newton tolerance: relative, in (0, 10⁻³] (a looser one would accept unconverged answers).
pub(super) fn tolerance_in_range(file: &str, key: &str, v: f64) -> Result<(), SceneError> {
    if v > 0.0 && v <= 1e-3 {
        Ok(())
    } else {
        Err(invalid(
            file,
            key,
            format!("a relative tolerance in (0, 1e-3] (got {v:e})"),
        ))
    }
}

pub(super) fn iterations_at_least_one(file: &str, key: &str, v: usize) -> Result<(), SceneError> {
    if v >= 1 {
        Ok(())
    } else {
        Err(invalid(file, key, "at least 1 iteration (got 0)"))
    }
}

pub(super) fn positive(file: &str, key: &str, v: f64, what: &str) -> Result<f64, SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(invalid(file, key, format!("{what} > 0 (got {v})")))
    }
}

/// What the dynamic tables need to know of the site.
#[derive(Debug, Clone, Copy)]
pub(super) struct Site {
    pub(super) length: f64,
    pub(super) water_depth: f64,
    pub(super) water_density: f64,
    pub(super) gravity: f64,
    pub(super) top_x: f64,
}
