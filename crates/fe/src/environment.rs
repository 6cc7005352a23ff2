//! The environment a line moves in, and the loads it makes: the sea water (its density, the Morison
//! coefficients and a current profile) and, optionally, waves ([`crate::waves`]).
//!
//! Every effect is optional: without `[hydrodynamics]` there is no [`Hydro`], and nothing here is
//! evaluated.
//!
//! **Drag (Morison)** on the velocity of the water relative to the node, `r = U(z) e_x + u_w − v`
//! (current, wave particle velocity, node velocity), split along the node's tangent
//! `t = (cos θ, sin θ)` into `s = r·t` and `r_n = r − s t`:
//!
//! ```text
//! f = ½ρ Cd_n D |r_n| r_n + ½ρ Cd_a πD |s| s t        (per unit unstretched length)
//! ```
//!
//! lumped at the nodes over their tributary lengths, like weight and mass. Its derivative with
//! respect to the node's velocity is the damping block
//! `C = k_n (|r_n| P + r_n r_nᵀ/|r_n|) + 2 k_a |s| t tᵀ` with `P = I − t tᵀ`; its dependence on the
//! orientation is left out of the Jacobian.
//!
//! **Added mass** acts normal to the line only: the 2×2 block `m_a·L·(I − t tᵀ)` with
//! `m_a = Ca·ρ·πD²/4` per unit length.
//!
//! **Wave inertia** (Froude–Krylov plus the added-mass part), normal and axial:
//!
//! ```text
//! f = ρ·(πD²/4)·L·[(1 + Ca)·u̇_n + u̇_a t],   u̇_a = u̇_w·t,  u̇_n = u̇_w − u̇_a t
//! ```
//!
//! The normal part carries the added mass; the axial part is the Froude–Krylov force alone (no
//! axial added mass, as the mass matrix has none). Both belong to the effective-tension
//! formulation: the weight already carries the buoyancy as a body force, so the wave's dynamic
//! pressure gradient acts as one too, in every direction (as in OrcaFlex and CableDyn). On a
//! steep riser in waves the axial part is most of the top tension's wave-frequency range
//! (`validation/sea.md`: 3.85 kN with it, 1.63 kN without, 3.75 kN in CableDyn). It does not
//! depend on the node's motion and adds nothing to the Jacobian.

use serde::{Deserialize, Serialize};

use crate::waves::Waves;

/// Hydrodynamic coefficients and the current.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Hydro {
    /// Sea water density, kg/m³.
    pub water_density: f64,
    /// Normal drag coefficient.
    pub cd_normal: f64,
    /// Axial drag coefficient (on the area πD per length).
    pub cd_axial: f64,
    /// Normal added-mass coefficient.
    pub ca_normal: f64,
    /// Current profile `(z, U_x)`, sorted by z (empty for none); linear in between, constant beyond.
    pub current: Vec<(f64, f64)>,
}

/// A line type's own Morison coefficients (a line section's `cd_normal`, `cd_axial`, `ca_normal`,
/// overriding [`Hydro`]'s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Coefficients {
    /// Normal drag coefficient.
    pub cd_normal: f64,
    /// Axial drag coefficient (on the area πD per length).
    pub cd_axial: f64,
    /// Normal added-mass coefficient.
    pub ca_normal: f64,
}

/// The drag on one node and, if asked for, its velocity derivative.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NodeDrag {
    /// Force, N (x and z).
    pub force: [f64; 2],
    /// `−∂f/∂v` as `[xx, xz, zz]`, N·s/m (the damping block; zero unless asked for).
    pub damping: [f64; 3],
}

impl Hydro {
    /// The sea's own coefficients (a node without a line type's own uses these).
    pub fn coefficients(&self) -> Coefficients {
        Coefficients {
            cd_normal: self.cd_normal,
            cd_axial: self.cd_axial,
            ca_normal: self.ca_normal,
        }
    }

    /// The current speed (along +x) at height z, m/s.
    pub fn current_at(&self, z: f64) -> f64 {
        let c = &self.current;
        match c.len() {
            0 => 0.0,
            1 => c[0].1,
            _ => {
                if z <= c[0].0 {
                    return c[0].1;
                }
                for w in c.windows(2) {
                    if z <= w[1].0 {
                        let f = (z - w[0].0) / (w[1].0 - w[0].0);
                        return w[0].1 + f * (w[1].1 - w[0].1);
                    }
                }
                c[c.len() - 1].1
            }
        }
    }

    /// The normal added mass of a length `l` of pipe of diameter `d` with the coefficients `c`, kg.
    #[inline]
    pub fn added_mass(&self, c: &Coefficients, d: f64, l: f64) -> f64 {
        c.ca_normal * self.water_density * std::f64::consts::PI * d * d / 4.0 * l
    }

    /// The drag's factors per diameter and length with the coefficients `c`: `(½ρ·Cd_n, ½ρ·Cd_a·π)`
    /// (normal, on the projected area `D`; axial, on the surface `πD`), N·s²/m⁴.
    #[inline]
    pub fn drag_factors(&self, c: &Coefficients) -> (f64, f64) {
        let kn0 = 0.5 * self.water_density * c.cd_normal;
        let ka0 = 0.5 * self.water_density * c.cd_axial * std::f64::consts::PI;
        (kn0, ka0)
    }

    /// The Morison drag with the coefficients `c` on a node of diameter `d` and tributary length
    /// `l`, at height `z`, with the tangent `(tx, tz)`, the velocity `(vx, vz)` and the wave
    /// particle velocity `wave` (if any); with `with_c`, also the damping block.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn drag(
        &self,
        c: &Coefficients,
        d: f64,
        l: f64,
        (tx, tz): (f64, f64),
        z: f64,
        (vx, vz): (f64, f64),
        wave: Option<[f64; 2]>,
        with_c: bool,
    ) -> NodeDrag {
        let (kn0, ka0) = self.drag_factors(c);
        let (rx, rz) = match wave {
            None => (self.current_at(z) - vx, -vz),
            Some([wx, wz]) => (self.current_at(z) + wx - vx, wz - vz),
        };
        let s = rx * tx + rz * tz;
        let (nx, nz) = (rx - s * tx, rz - s * tz);
        let vn = (nx * nx + nz * nz).sqrt();
        let kn = kn0 * d * l;
        let ka = ka0 * d * l;
        let force = [
            kn * vn * nx + ka * s.abs() * s * tx,
            kn * vn * nz + ka * s.abs() * s * tz,
        ];
        let mut damping = [0.0; 3];
        if with_c {
            let mut cxx = 2.0 * ka * s.abs() * tx * tx;
            let mut cxz = 2.0 * ka * s.abs() * tx * tz;
            let mut czz = 2.0 * ka * s.abs() * tz * tz;
            if vn > 0.0 {
                cxx += kn * (vn * (1.0 - tx * tx) + nx * nx / vn);
                cxz += kn * (-vn * tx * tz + nx * nz / vn);
                czz += kn * (vn * (1.0 - tz * tz) + nz * nz / vn);
            }
            damping = [cxx, cxz, czz];
        }
        NodeDrag { force, damping }
    }
}

impl Hydro {
    /// The wave inertia force with the coefficients `c` on a node of diameter `d` and tributary
    /// length `l` with the tangent `(tx, tz)`, from the water's acceleration `acc` (see the module
    /// docs), N.
    #[inline]
    pub fn wave_inertia(
        &self,
        c: &Coefficients,
        d: f64,
        l: f64,
        (tx, tz): (f64, f64),
        acc: [f64; 2],
    ) -> [f64; 2] {
        let fk = self.water_density * std::f64::consts::PI * d * d / 4.0 * l;
        let c = fk * (1.0 + c.ca_normal);
        let s = acc[0] * tx + acc[1] * tz;
        [
            c * (acc[0] - s * tx) + fk * s * tx,
            c * (acc[1] - s * tz) + fk * s * tz,
        ]
    }
}

/// The environment of a run. Absent parts are `None` and cost nothing.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Environment {
    /// The sea water's hydrodynamics, if the scene has them (steady current drag acts in the
    /// statics too).
    pub hydro: Option<Hydro>,
    /// Waves, if the scene has them (they load the line through `hydro`, and drive the vessel).
    pub waves: Option<Waves>,
    /// Height of the still water level above the mudline (the water depth), m: waves' `z` is
    /// measured from it.
    pub water_level: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The current profile is linear between its points and constant beyond them: with points
    /// (−100 m, 0.2 m/s) and (0 m, 0.6 m/s), 0.4 m/s at −50 m and 0.3 m/s at −75 m, 0.2 m/s below
    /// −100 m and 0.6 m/s above 0 m (z is the height above the mudline; to rounding).
    #[test]
    fn the_current_is_linear_between_its_points() {
        let h = Hydro {
            water_density: 1025.0,
            cd_normal: 1.0,
            cd_axial: 0.0,
            ca_normal: 1.0,
            current: vec![(-100.0, 0.2), (0.0, 0.6)],
        };
        for (z, u) in [
            (-50.0, 0.4),
            (-75.0, 0.3),
            (-150.0, 0.2),
            (-100.0, 0.2),
            (5.0, 0.6),
        ] {
            assert!(
                (h.current_at(z) - u).abs() < 1e-15,
                "at {z} m: {}",
                h.current_at(z)
            );
        }
        let uniform = Hydro {
            current: vec![(-100.0, 0.5)],
            ..h.clone()
        };
        assert_eq!(uniform.current_at(-30.0), 0.5);
        let none = Hydro {
            current: vec![],
            ..h
        };
        assert_eq!(none.current_at(-30.0), 0.0);
    }
}
