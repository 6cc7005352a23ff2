//! The studies: many runs of one scene, edited key by key ([`crate::scene::edit`]), each run through
//! [`crate::run`], their results merged.
//!
//! - [`fatigue_study`]: the storm-table fatigue study (`catena fatigue`);
//! - [`strength`]: design storms × seeds, extremes across seeds (`catena strength`);
//! - [`sweep`]: parameter sweeps over a study, locally or as Slurm array shards (`catena sweep`);
//! - [`sequence`]: storms in sequence, each from the seabed the last one left (`catena sequence`);
//! - [`convergence`]: what accuracy costs in time (`catena convergence`);
//! - [`soil_test`]: the soil element test (`[seabed]` + `[test]`, no line);
//! - [`calibrate`]: the Randolph–Quiggin parameters fitted to an element test (`catena calibrate`).

pub mod calibrate;
pub mod convergence;
pub mod fatigue_study;
pub mod schedule;
pub mod sequence;
pub mod soil_test;
pub mod strength;
pub mod sweep;
