//! Reading case files. Every table is deserialised with unknown keys denied, then checked; an error
//! names the file, the key and what was expected.

pub mod riser;
pub mod seabed;

use std::path::Path;

use serde::de::DeserializeOwned;

use crate::error::{AppError, SceneError};

/// Reads `path` as UTF-8 text.
pub fn read_text(path: &Path) -> Result<String, AppError> {
    std::fs::read_to_string(path).map_err(|e| AppError::io(path, e))
}

/// Parses TOML `text` (from `file`) into `T`. The TOML reader's message names the key and the line.
pub fn parse<T: DeserializeOwned>(file: &str, text: &str) -> Result<T, SceneError> {
    toml::from_str(text).map_err(|e| SceneError::Parse {
        file: file.to_string(),
        message: e.to_string().trim_end().to_string(),
    })
}

/// An [`SceneError::Invalid`] for `key` in `file`.
pub fn invalid(file: &str, key: impl Into<String>, expected: impl Into<String>) -> SceneError {
    SceneError::Invalid {
        file: file.to_string(),
        key: key.into(),
        expected: expected.into(),
    }
}

/// Requires an optional key.
pub fn required<T: Copy>(file: &str, key: &str, v: Option<T>, what: &str) -> Result<T, SceneError> {
    v.ok_or_else(|| invalid(file, key, format!("{what} (the key is missing)")))
}
