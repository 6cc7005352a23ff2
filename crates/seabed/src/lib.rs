//! Seabed contact laws for catena, one committed history per node.
//!
//! Conventions (SI throughout):
//! - `z` is the penetration of the pipe **invert** below the mudline, positive down (m);
//! - `P` is the soil resistance per unit length of pipe (N/m), positive pushes the pipe up,
//!   negative is suction; it excludes soil buoyancy, which [`buoyancy::SoilBuoyancy`] adds;
//! - a law's *tangent* is `dP/dz` (N/m per m).
//!
//! The contract for every history-dependent law (OpenSees' `setTrialStrain` / `commitState`, made
//! structural): a trial is a **pure function** of the committed history and the trial penetration,
//!
//! ```text
//! evaluate(&law, &committed, z_trial, ż, Δt) -> Trial { force, tangent, next }
//! ```
//!
//! and the caller replaces `committed` by `next` only when its step has converged. A trial can never
//! change committed state, so a Newton iteration cannot ratchet the soil.
//!
//! Modules:
//! - [`rq`]: the Randolph & Quiggin (2009) non-linear hysteretic law (OMAE2009-79259), read exactly as
//!   `docs/seabed-model.md` fixes it;
//! - [`degradation`]: cyclic strength degradation (Einav & Randolph 2005) and regain at rest, options
//!   of the Randolph–Quiggin law;
//! - [`linear`]: the linear elastic tensionless seabed, `P = k·D·z`, with optional damping;
//! - [`buoyancy`]: the soil buoyancy force of the paper's eq. 15;
//! - [`law`]: [`law::Seabed`], the law a scene chose plus optional buoyancy, behind one interface,
//!   and [`law::SeabedHistory`], the per-node history of whichever law it is;
//! - [`element_test`]: the soil element test driver (displacement and load control);
//! - [`roots`]: the bisection and safeguarded Newton root finder every scan shares.

pub mod buoyancy;
pub mod degradation;
pub mod element_test;
pub mod law;
pub mod linear;
pub mod roots;
pub mod rq;

pub use buoyancy::SoilBuoyancy;
pub use degradation::{Degradation, Regain, Wear};
pub use law::{Seabed, SeabedHistory, SeabedResponse, SeabedTrial, TrialMemo};
pub use linear::{LinearHistory, LinearSeabed};
pub use rq::{Mode, OnsetMemo, RandolphQuiggin, RateSuction, RqHistory, RqParams, RqTrial};

/// Standard gravity, m/s² (the value `cases.md` prescribes).
pub const G: f64 = 9.80665;

/// An invalid seabed parameter: names the parameter (as the scene key spells it) and what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("`{key}` = {value}: expected {expected}")]
pub struct ParamError {
    /// The scene key, for example `k_max`.
    pub key: &'static str,
    /// The offending value.
    pub value: f64,
    /// What the value must satisfy, in words.
    pub expected: &'static str,
}

pub(crate) fn check(
    ok: bool,
    key: &'static str,
    value: f64,
    expected: &'static str,
) -> Result<(), ParamError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(ParamError {
            key,
            value,
            expected,
        })
    }
}
