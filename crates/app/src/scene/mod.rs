//! Reading case files. Parsing is pure: text goes in, a checked scene comes out. Files a scene names
//! (a motion CSV today; RAO and storm tables later) are read through a [`Resolver`] the caller passes
//! in, so a library user can serve them from memory. Every table is deserialised with unknown keys
//! denied, then checked; an error names the file, the key and what was expected.
//!
//! A parsed scene keeps its TOML document, so that studies edit it by key path
//! ([`edit`]: `dynamic.time_step`, `mesh[*].element_length`) and build the edited scene from the
//! document, never by editing text.

pub mod as_laid;
mod checks;
mod dynamic;
pub mod edit;
pub mod lay;
mod line;
mod outputs;
pub mod riser;
mod sea;
pub mod seabed;
pub mod sections;
mod size;
pub mod tables;

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use crate::error::{AppError, SceneError};

/// Reads the files a scene names, by the name the scene gives (relative to the scene's own file).
pub trait Resolver: Sync {
    /// The text of the file `name`, or a message saying why it cannot be read (naming the path).
    fn read(&self, name: &str) -> Result<String, String>;
}

/// Resolves names relative to a directory (the case file's own).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DirResolver {
    /// The directory names are relative to.
    pub dir: PathBuf,
}

impl DirResolver {
    /// Resolves relative to the directory of the case file `case`.
    pub fn beside(case: &Path) -> Self {
        Self {
            dir: case
                .parent()
                .map_or_else(|| PathBuf::from("."), Path::to_path_buf),
        }
    }
}

impl Resolver for DirResolver {
    fn read(&self, name: &str) -> Result<String, String> {
        let path = self.dir.join(name);
        std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// A resolver that has no files: every read fails (for scenes that name none).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct NoFiles;

impl Resolver for NoFiles {
    fn read(&self, name: &str) -> Result<String, String> {
        Err(format!(
            "{name}: this scene was given without access to files"
        ))
    }
}

/// Reads `path` as UTF-8 text.
pub fn read_text(path: &Path) -> Result<String, AppError> {
    std::fs::read_to_string(path).map_err(|e| AppError::io(path, e))
}

/// Parses TOML `text` (from `file`) into `T`. The TOML reader's message names the key and the line.
/// Every number is checked first ([`check_numbers`]).
pub fn parse<T: DeserializeOwned>(file: &str, text: &str) -> Result<T, SceneError> {
    if let Ok(doc) = text.parse::<toml::Table>() {
        check_numbers(file, &doc)?;
    }
    toml::from_str(text).map_err(|e| SceneError::Parse {
        file: file.to_string(),
        message: e.to_string().trim_end().to_string(),
    })
}

/// Reads a TOML document (`file` names it in messages) into `T`: for scenes built from an edited
/// document.
pub fn from_doc<T: DeserializeOwned>(file: &str, doc: &toml::Table) -> Result<T, SceneError> {
    check_numbers(file, doc)?;
    toml::Value::Table(doc.clone())
        .try_into()
        .map_err(|e: toml::de::Error| SceneError::Parse {
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

/// A stable 64-bit hash of a scene's text (FNV-1a), as 16 hex digits: checkpoints carry it so that a
/// restart with another scene is refused.
pub fn text_hash(text: &str) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// The largest magnitude any number in a scene may have (SI units): 10¹². Larger values (1e300 for a
/// stiffness, a current or a waypoint) are typing slips that would overflow the solve into `inf` and
/// `NaN`, or ask for unbounded work; they are refused before anything runs.
pub const MAX_MAGNITUDE: f64 = 1e12;

/// The smallest magnitude a non-zero number may have: 10⁻¹² (a diameter of 1e-300 m made the
/// seabed's length scale underflow).
pub const MIN_MAGNITUDE: f64 = 1e-12;

/// Checks every number of a scene document, before anything else: finite (`nan` and `inf` are
/// refused) and within ±[`MAX_MAGNITUDE`]. Integers named `seed` are exempt (any 64-bit seed).
/// The error names the key path (`motion.harmonic.heave`, `current.profile[1][0]`).
pub fn check_numbers(file: &str, doc: &toml::Table) -> Result<(), SceneError> {
    fn walk(file: &str, path: &str, v: &toml::Value) -> Result<(), SceneError> {
        let bad = |x: String| {
            Err(invalid(
                file,
                path,
                format!(
                    "a finite number, 0 or of magnitude between {MIN_MAGNITUDE:e} and {MAX_MAGNITUDE:e} in SI units (got {x})"
                ),
            ))
        };
        match v {
            toml::Value::Float(x)
                if !x.is_finite()
                    || x.abs() > MAX_MAGNITUDE
                    || (*x != 0.0 && x.abs() < MIN_MAGNITUDE) =>
            {
                return bad(format!("{x:e}"));
            }
            toml::Value::Integer(i)
                if path.rsplit('.').next() != Some("seed") && (*i as f64).abs() > MAX_MAGNITUDE =>
            {
                return bad(format!("{i:e}"));
            }
            toml::Value::Array(a) => {
                for (k, x) in a.iter().enumerate() {
                    walk(file, &format!("{path}[{k}]"), x)?;
                }
            }
            toml::Value::Table(t) => {
                for (k, x) in t {
                    let p = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}.{k}")
                    };
                    walk(file, &p, x)?;
                }
            }
            _ => {}
        }
        Ok(())
    }
    for (k, v) in doc {
        walk(file, k, v)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_checked_by_key_path() {
        let doc: toml::Table =
            "a = 1.0\n[b]\nc = [[0.0, 1.0], [2.0, nan]]\nseed = 12345678901234\n"
                .parse()
                .expect("toml");
        let e = check_numbers("f.toml", &doc).expect_err("nan").to_string();
        assert!(e.contains("f.toml") && e.contains("`b.c[1][1]`"), "{e}");
        let ok: toml::Table = "seed = 12345678901234\nx = 1e12".parse().expect("toml");
        assert!(check_numbers("f.toml", &ok).is_ok());
        let big: toml::Table = "[line]\nea = 1e300".parse().expect("toml");
        let e = check_numbers("f.toml", &big).expect_err("big").to_string();
        assert!(e.contains("`line.ea`") && e.contains("1e300"), "{e}");
    }
}
