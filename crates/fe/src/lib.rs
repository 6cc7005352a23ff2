//! Finite elements for catena: the 2D corotational beam, sparse symmetric solves, and the static
//! (later dynamic) solvers for a line in contact with the seabed.
//!
//! - [`beam`]: the corotational Euler–Bernoulli element kernel (pure);
//! - [`sparse`]: the symmetric sparse pattern and faer's LDLᵀ with one symbolic factorisation per run;
//! - [`model`]: the Model (mesh, sections, loads, supports, seabed), immutable once built;
//! - [`analytical`]: closed-form solutions (catenaries, the touchdown boundary layer, the elastica),
//!   used to seed solves and to test them.

pub mod analytical;
pub mod beam;
pub mod dynamics;
pub mod model;
pub mod sparse;
pub mod statics;
