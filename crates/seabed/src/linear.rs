//! The linear elastic, tensionless seabed.
//!
//! Stiffness and damping are given per unit contact area, as riser engineers quote them, so that
//! per unit length of pipe
//!
//! ```text
//! P = k·D·z        for z > 0, else 0           (N/m)
//! F_damp = c·D·ż   for z > 0, else 0           (N/m, opposing the penetration rate ż)
//! ```
//!
//! with `k` in N/m/m² (Pa/m) and `c` in N·s/m/m². The force has no memory; [`LinearHistory`] keeps
//! only what output reports (the last penetration and the deepest one). A node is reported as
//! `initial_penetration` while in contact and `not_in_contact` otherwise.

use serde::{Deserialize, Serialize};

use crate::rq::Mode;
use crate::{check, ParamError};

/// The committed history of one node on the linear seabed.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct LinearHistory {
    /// Penetration at the last converged step, m.
    pub z_prev: f64,
    /// The deepest penetration so far, m (0 until the node touches).
    pub z_max: f64,
}

impl LinearHistory {
    /// The history after a converged step at penetration `z`.
    #[inline]
    pub fn next(&self, z: f64) -> Self {
        Self {
            z_prev: z,
            z_max: self.z_max.max(z),
        }
    }

    /// The contact mode: in contact (initial penetration) while `z > 0`.
    pub fn mode(&self) -> Mode {
        if self.z_prev > 0.0 {
            Mode::InitialPenetration
        } else {
            Mode::NotInContact
        }
    }
}

/// A linear elastic tensionless seabed with optional linear damping.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LinearSeabed {
    /// Contact diameter `D`, m.
    pub diameter: f64,
    /// Stiffness per unit contact area `k`, N/m/m².
    pub stiffness: f64,
    /// Damping per unit contact area `c`, N·s/m/m² (0 for none).
    pub damping: f64,
}

impl LinearSeabed {
    /// Validates and builds the law.
    pub fn new(diameter: f64, stiffness: f64, damping: f64) -> Result<Self, ParamError> {
        check(diameter > 0.0, "diameter", diameter, "D > 0 (m)")?;
        check(
            stiffness > 0.0,
            "stiffness",
            stiffness,
            "stiffness > 0 (N/m/m²)",
        )?;
        check(
            damping >= 0.0,
            "damping",
            damping,
            "damping >= 0 (N·s/m/m²)",
        )?;
        Ok(Self {
            diameter,
            stiffness,
            damping,
        })
    }

    /// `P(z)` and `dP/dz`.
    #[inline]
    pub fn force(&self, z: f64) -> (f64, f64) {
        if z > 0.0 {
            let kd = self.stiffness * self.diameter;
            (kd * z, kd)
        } else {
            (0.0, 0.0)
        }
    }

    /// The damping force `c·D·ż` while in contact, and its derivative with respect to `ż`.
    #[inline]
    pub fn damping_force(&self, z: f64, z_rate: f64) -> (f64, f64) {
        if z > 0.0 && self.damping > 0.0 {
            let cd = self.damping * self.diameter;
            (cd * z_rate, cd)
        } else {
            (0.0, 0.0)
        }
    }
}
