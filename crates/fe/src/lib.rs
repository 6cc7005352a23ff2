//! Finite elements for catena: the 2D corotational beam, sparse symmetric solves, and the static and
//! dynamic solvers for a line in contact with the seabed.
//!
//! - [`beam`]: the corotational Euler–Bernoulli element kernel (pure);
//! - [`sparse`]: the symmetric sparse pattern and faer's LDLᵀ with one symbolic factorisation per run;
//! - [`model`]: the line Model (mesh, sections, loads, supports, seabed, flexjoint), immutable once
//!   built;
//! - [`assembly`]: the structural residual and tangent that statics and dynamics share, and the
//!   nodal results ([`assembly::LineResults`]);
//! - [`environment`]: the sea (hydrodynamics, current) and the loads it makes on the line;
//! - [`loads`]: the one list of loads (seabed, hydrodynamics, structural damping) that the statics
//!   and the dynamics both assemble;
//! - [`motion`]: prescribed motion of the top end;
//! - [`waves`]: JONSWAP and Airy waves, their synthesis and kinematics (Wheeler stretching);
//! - [`vessel`]: vessel motion from RAOs on the same wave train, transferred to the hang-off;
//! - [`statics`]: the static Newton solve from a catenary seed;
//! - [`integrator`]: the HHT-α/Newmark coefficients, predictors, relations and residual;
//! - [`boundary`]: the prescribed dofs of the dynamics and what prescribes them;
//! - [`partner`]: the partner thread that gives one run its second processor;
//! - [`newton`]: Newton's bookkeeping for a time step (lazy tangent, reuse, backtracking, tests);
//! - [`dynamics`]: the time stepping (Newton in each step, step cutting) on a
//!   [`dynamics::DynamicModel`];
//! - [`analytical`]: closed-form solutions (catenaries, the touchdown boundary layer, the elastica),
//!   used to seed solves and to test them;
//! - [`sectioned`]: the catenary of a line of sections (weights that change along it, a lazy wave), the
//!   static seed of such a line.

pub mod analytical;
pub mod assembly;
pub mod beam;
pub mod boundary;
pub mod dynamics;
pub mod environment;
mod fastmath;
pub mod integrator;
pub mod loads;
pub mod model;
pub mod motion;
pub mod newton;
pub mod partner;
pub mod sectioned;
pub mod sparse;
pub mod statics;
#[cfg(test)]
mod test_rng;
pub mod vessel;
pub mod wave_sampling;
pub mod waves;
