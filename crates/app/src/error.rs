//! Errors of catena. Every message says which file, which key and what was expected, or when, where
//! and how much a solve failed; nothing reachable from input panics.

use std::path::PathBuf;

use catena_fe::dynamics::StepError;
use catena_fe::sparse::SolveError;
use catena_fe::statics::StaticError;

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

/// An error of catena (library and front ends).
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
    /// The static solve failed (load factor, iteration, residual, node and arc length).
    #[error("{file}: {source}")]
    Statics {
        /// The case file.
        file: String,
        /// What the solver reports.
        source: StaticError,
    },
    /// A dynamic step failed (time, step, Δt, cuts, iterations, residual, node and arc length).
    #[error("{file}: {source}")]
    Step {
        /// The case file.
        file: String,
        /// What the stepper reports.
        source: StepError,
    },
    /// The linear solver could not be set up.
    #[error("{file}: {source}")]
    Solver {
        /// The case file.
        file: String,
        /// What faer reports.
        source: SolveError,
    },
    /// A checkpoint that does not fit the run it is to continue.
    #[error("{file}: the checkpoint does not match this run: {what}")]
    Checkpoint {
        /// The checkpoint file.
        file: String,
        /// What does not match.
        what: String,
    },
    /// The case ran but could not be completed, or a request about it is wrong.
    #[error("{file}: {message}")]
    Run {
        /// The case file.
        file: String,
        /// What happened, with the key it concerns.
        message: String,
    },
    /// An output (HDF5, CSV, JSON) could not be written.
    #[error("{}: {message}", path.display())]
    Output {
        /// The file.
        path: PathBuf,
        /// What went wrong.
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

impl SceneError {
    /// The error with its file set to `file` when it is about a key of `table` (`table` itself,
    /// `table.key`, `table[i]…`): a table a study or a sequence writes into its base scene is
    /// checked in the scene, but its keys are in the study's file, which the message must name.
    pub fn in_table_of(self, table: &str, file: &str) -> Self {
        match self {
            SceneError::Invalid { key, expected, .. }
                if key == table
                    || key.starts_with(&format!("{table}."))
                    || key.starts_with(&format!("{table}[")) =>
            {
                SceneError::Invalid {
                    file: file.to_string(),
                    key,
                    expected,
                }
            }
            other => other,
        }
    }
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
