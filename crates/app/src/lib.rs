//! The `catena` command-line program, as a library so that its commands can be tested.
//!
//! - [`scene`]: reading TOML case files into validated models, with errors that name the file and key;
//! - [`soil_test`]: `catena soil-test`, the seabed law alone on one pipe segment;
//! - [`statics_cmd`]: `catena static`, the static configuration of a line on the seabed;
//! - [`run_cmd`]: `catena run`, the statics then the dynamics;
//! - [`convergence`]: `catena convergence`, the same scene with the mesh and the time step refined:
//!   key outputs, their errors (Richardson) and the wall time of each run;
//! - [`h5`]: the HDF5 results layout;
//! - [`plot`]: PNG plots (plotters, with an embedded DejaVu Sans font so no system font is needed);
//! - [`error`]: the program's error type.

pub mod convergence;
pub mod error;
pub mod h5;
pub mod plot;
pub mod run_cmd;
pub mod scene;
pub mod soil_test;
pub mod statics_cmd;

pub use error::AppError;
