//! Soil buoyancy, the paper's eq. 15.
//!
//! ```text
//! F_b = f_b · A_disp(z) · (ρ_soil − ρ_water) · g          (N/m, upward)
//! A_disp(z) = 0                                           z ≤ 0
//!           = R²·acos((R − z)/R) − (R − z)·sqrt(2Rz − z²)  0 < z < D,  R = D/2
//!           = π·D²/4                                      z ≥ D
//! dA_disp/dz = 2·sqrt(2Rz − z²)    (the chord at the mudline plane)
//! ```
//!
//! `A_disp` is the area of the pipe's circle below the mudline plane; `f_b ≥ 1` models the local heave
//! of displaced soil (1.5 recommended by the paper).

use serde::{Deserialize, Serialize};

use crate::{check, ParamError, G};

/// Soil buoyancy parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SoilBuoyancy {
    /// Contact diameter `D`, m.
    pub diameter: f64,
    /// Buoyancy factor `f_b` (≥ 1).
    pub f_b: f64,
    /// Saturated soil density, kg/m³.
    pub soil_density: f64,
    /// Sea water density, kg/m³.
    pub water_density: f64,
}

impl SoilBuoyancy {
    /// Validates and builds.
    pub fn new(
        diameter: f64,
        f_b: f64,
        soil_density: f64,
        water_density: f64,
    ) -> Result<Self, ParamError> {
        check(diameter > 0.0, "diameter", diameter, "D > 0 (m)")?;
        check(f_b >= 1.0, "f_b", f_b, "f_b >= 1 (Archimedes' principle)")?;
        check(
            water_density > 0.0,
            "water_density",
            water_density,
            "water_density > 0 (kg/m³)",
        )?;
        check(
            soil_density >= water_density,
            "soil_density",
            soil_density,
            "soil_density >= water_density (kg/m³)",
        )?;
        Ok(Self {
            diameter,
            f_b,
            soil_density,
            water_density,
        })
    }

    /// The displaced area `A_disp(z)` (m²) and `dA_disp/dz` (m).
    #[inline]
    pub fn displaced_area(&self, z: f64) -> (f64, f64) {
        let d = self.diameter;
        let r = 0.5 * d;
        if z <= 0.0 {
            (0.0, 0.0)
        } else if z >= d {
            (std::f64::consts::PI * r * r, 0.0)
        } else {
            let c = (2.0 * r * z - z * z).max(0.0).sqrt();
            let area = r * r * ((r - z) / r).clamp(-1.0, 1.0).acos() - (r - z) * c;
            (area, 2.0 * c)
        }
    }

    /// The buoyancy force `F_b` (N/m, upward) and `dF_b/dz`.
    #[inline]
    pub fn force(&self, z: f64) -> (f64, f64) {
        let w = self.f_b * (self.soil_density - self.water_density) * G;
        let (a, da) = self.displaced_area(z);
        (w * a, w * da)
    }
}
