//! Errors of the `catena` program. Every message says which file, which key and what was expected;
//! nothing reachable from input panics.

use std::path::PathBuf;

/// An error in a scene (case) file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// TOML syntax, an unknown key, a missing key or a value of the wrong type (the TOML reader's own
    /// message, with line and column).
    #[error("{file}: {message}")]
    Parse {
        /// The case file.
        file: String,
        /// What the TOML reader said.
        message: String,
    },
    /// A value that is read but not acceptable.
    #[error("{file}: key `{key}`: expected {expected}")]
    Invalid {
        /// The case file.
        file: String,
        /// The key, with its table (`seabed.b`).
        key: String,
        /// What the value must be.
        expected: String,
    },
}

/// An error of the program.
#[derive(Debug, thiserror::Error)]
pub enum AppError {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The system's reason.
        source: std::io::Error,
    },
    /// The case file is wrong.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The case ran but could not be completed.
    #[error("{file}: {message}")]
    Run {
        /// The case file.
        file: String,
        /// What happened, with the key it concerns.
        message: String,
    },
    /// A plot could not be drawn.
    #[error("plot {}: {message}", path.display())]
    Plot {
        /// The plot file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}

impl AppError {
    /// Wraps an I/O error with its path.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        AppError::Io {
            path: path.into(),
            source,
        }
    }
}
