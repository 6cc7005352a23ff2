//! catena, the simulation library: every command, study and binding shares it. It has no
//! dependency on HDF5, plotting or a command-line parser; the crates above it (`catena-io`,
//! `catena-cli`) write files and talk to users.
//!
//! - [`scene`]: reading case files into checked scenes (pure: text in, scene out; files a scene
//!   names come through a [`scene::Resolver`]); edits by key path ([`scene::edit`]);
//! - [`statics`]: the static configuration (catenary seed, Newton, flexjoint neutral angle);
//! - [`run`]: the dynamic run, each converged step handed to [`observe::Observer`]s;
//! - [`observe`]: the observer trait and the built-in observers (envelopes, gauges, top history,
//!   checkpoints);
//! - [`outputs`]: the registry of built-in outputs a run builds from its scene;
//! - [`checkpoint`]: checkpoints (State, solver memory, observers' states, scene hash, version);
//! - [`convergence`]: the convergence study (what accuracy costs in time);
//! - [`soil_test`]: the soil element test;
//! - [`calibrate`]: the Randolph–Quiggin parameters fitted to an element test;
//! - [`fatigue`]: rainflow counting, S-N curves, stress recovery (pure);
//! - [`fatigue_observer`]: fatigue damage counted during a run;
//! - [`study`]: the storm-table fatigue study;
//! - [`sequence`]: storms in sequence, each from the state the last left (the seabed's memory);
//! - [`error`]: the error types.

pub mod calibrate;
pub mod checkpoint;
pub mod convergence;
pub mod design;
pub mod design_observer;
pub mod error;
pub mod extremes;
pub mod extremes_observer;
pub mod fatigue;
pub mod fatigue_observer;
pub mod observe;
pub mod outputs;
pub mod run;
pub mod scene;
pub mod sequence;
pub mod soil_test;
pub mod statics;
pub mod strength;
pub mod study;
pub mod sweep;

pub use error::{AppError, SceneError};
