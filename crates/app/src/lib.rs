//! catena, the simulation library: every command, study and binding shares it. It has no
//! dependency on HDF5, plotting or a command-line parser; the crates above it (`catena-io`,
//! `catena-cli`) write files and talk to users.
//!
//! Its folders are its layers, each using only those before it in this list (CI checks the order
//! with `scripts/check-layers.py`). A step's data flows from the scene through a run to the checks
//! and the studies; the checks come first in the code's order because they are pure functions of
//! numbers that the scene's tables configure and the run's observers apply:
//!
//! 1. [`checks`]: what is computed from a step's results, pure — fatigue (stresses, rainflow,
//!    S-N), the design criteria, extreme statistics;
//! 2. [`scene`]: reading case files into checked scenes (pure: text in, scene out; files a scene
//!    names come through a [`scene::Resolver`]); edits by key path ([`scene::edit`]);
//! 3. [`run`]: one run — the statics ([`run::statics`]), the dynamics with each converged step
//!    handed to [`run::observe::Observer`]s, the observers that apply the checks
//!    ([`run::observers`]), the registry of outputs a scene asks for ([`run::outputs`]),
//!    checkpoints ([`run::checkpoint`]);
//! 4. [`studies`]: many runs — the storm-table fatigue study, strength, sweeps, storms in
//!    sequence, convergence, the soil element test and its calibration.
//!
//! [`error`] is shared by all of them.
//!
//! The flat names of earlier versions (`catena::statics`, `catena::fatigue_observer`,
//! `catena::study`, …) are re-exported below, so code written against them keeps working.

pub mod checks;
pub mod error;
pub mod run;
pub mod scene;
pub mod studies;

pub use error::{AppError, SceneError};

pub use checks::{design, extremes, fatigue};
pub use run::observers::design as design_observer;
pub use run::observers::extremes as extremes_observer;
pub use run::observers::fatigue as fatigue_observer;
pub use run::{checkpoint, observe, outputs, statics};
pub use studies::fatigue_study as study;
pub use studies::{calibrate, convergence, sequence, soil_test, strength, sweep};
