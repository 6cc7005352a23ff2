//! Soil that softens under cycling and regains strength at rest: options of the Randolph–Quiggin
//! law ([`crate::rq`]), each absent unless a scene asks for it (absent, the law is the paper's to
//! the bit).
//!
//! **Cyclic degradation** (Einav & Randolph 2005, the strength-degradation form of their strain-path
//! analysis of the T-bar, also used for cyclic T-bar and pipe tests by Hodder, White & Cassidy 2009).
//! A node's strength is its intact profile times a factor
//!
//! ```text
//! δ(ξ) = δ_rem + (1 − δ_rem)·exp(−3ξ/ξ95),      δ_rem = 1/S_t,
//! ```
//!
//! where `S_t` is the sensitivity (intact over fully remoulded strength), `ξ` the accumulated
//! plastic displacement and `ξ95` the *ductility*, the accumulated plastic displacement at which
//! 95 % of the possible loss has occurred (`exp(−3) = 0.05`). Einav & Randolph accumulate plastic
//! shear strain; a pipe in the touchdown zone moves the same soil mechanism each cycle, so here `ξ`
//! is the accumulated plastic **displacement of the invert in pipe diameters** (the measure of
//! Hodder et al.'s cyclic tests: degradation per diameter of cumulative travel), and `ξ95` is in
//! diameters too. The strength scales `su0` and `ρ_su` alike, so `Pu`, the backbone, the suction
//! limit and every stiffness `Kmax·Pu/D` scale with `δ`.
//!
//! The plastic part of a step's displacement is the increment less its elastic part at the
//! episode's reversal stiffness `K_e = Kmax·δ·Pu(z_ref)/D` (the law's own unloading stiffness, eq. 5;
//! `z_ref` the deepest of the step's ends, the episode start and `z*`):
//!
//! ```text
//! Δξ = min(|Δz|, |Δz − ΔP/K_e|) / D,     Δz, ΔP over the step, z taken ≥ 0 (no travel in water).
//! ```
//!
//! so that a reversal's first, elastic response accumulates nothing and travel on the backbone
//! counts in full. **`δ` is fixed for an episode** (set from the committed `ξ` when the episode
//! starts: a reversal or a re-contact): within an episode the force is the paper's law on the
//! episode's strength, so its curves stay continuous and its suction onset is found once, and a
//! trial's tangent is the law's (`ξ` moves no force until the next episode). `ξ` is committed once per
//! converged step with the rest of the history.
//!
//! **Regain at rest** (consolidation). During a rest of duration `t` (a calm interval between storms)
//! the lost strength `1 − δ` is recovered by the degree of consolidation `U(t)` of the hyperbolic
//! fit to dissipation curves (the form used for pipelines by Chatterjee et al. 2012):
//!
//! ```text
//! U(t) = (t/t50)^m / (1 + (t/t50)^m),      δ' = 1 − (1 − δ)·(1 − U(t)),
//! ```
//!
//! `t50` the time to half the regain (s), `m` the exponent. The regained strength is recorded as the
//! `ξ` that gives it (`ξ' = −ξ95/3·ln((δ' − δ_rem)/(1 − δ_rem))`) and takes effect at the node's next
//! episode. Regain is towards the intact strength, never above it (no consolidation hardening).
//!
//! References: Einav, I. & Randolph, M.F. (2005). Combining upper bound and strain path methods for
//! evaluating penetration resistance. Int. J. Numer. Meth. Engng 63(14), 1991–2016. Hodder, M.S.,
//! White, D.J. & Cassidy, M.J. (2009). Analysis of soil strength degradation during episodes of
//! cyclic loading, illustrated by the T-bar penetration test. Int. J. Geomech. 10(3), 117–123.
//! Chatterjee, S., Yan, Y., Randolph, M.F. & White, D.J. (2012). Elastoplastic consolidation
//! beneath shallowly embedded offshore pipelines. Géotechnique Letters 2, 73–79.

use serde::{Deserialize, Serialize};

use crate::{check, ParamError};

/// Cyclic degradation of the strength, and optionally its regain at rest.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Degradation {
    /// Sensitivity `S_t` ≥ 1: intact over fully remoulded strength.
    pub sensitivity: f64,
    /// Ductility `ξ95` > 0: the accumulated plastic displacement, in pipe diameters, for 95 % of the
    /// loss.
    pub ductility: f64,
    /// Regain at rest, if any.
    #[serde(default)]
    pub regain: Option<Regain>,
}

/// Regain of lost strength at rest: `U(t) = (t/t50)^m / (1 + (t/t50)^m)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Regain {
    /// `t50` > 0, s: the rest that regains half the lost strength.
    pub t50: f64,
    /// `m` > 0: the exponent of the hyperbolic form.
    pub exponent: f64,
}

impl Degradation {
    /// Checks the parameters; the error names the key.
    pub fn validate(&self) -> Result<(), ParamError> {
        check(
            self.sensitivity >= 1.0,
            "degradation.sensitivity",
            self.sensitivity,
            "a sensitivity S_t >= 1 (intact over remoulded strength)",
        )?;
        check(
            self.ductility > 0.0,
            "degradation.ductility",
            self.ductility,
            "a ductility xi95 > 0 (pipe diameters of accumulated plastic displacement)",
        )?;
        if let Some(r) = &self.regain {
            check(
                r.t50 > 0.0,
                "degradation.regain_t50",
                r.t50,
                "a regain time t50 > 0 s",
            )?;
            check(
                r.exponent > 0.0,
                "degradation.regain_exponent",
                r.exponent,
                "a regain exponent m > 0",
            )?;
        }
        Ok(())
    }

    /// The remoulded strength factor `δ_rem = 1/S_t`.
    pub fn remoulded(&self) -> f64 {
        1.0 / self.sensitivity
    }

    /// The strength factor `δ(ξ)` after `ξ` diameters of accumulated plastic displacement.
    pub fn strength(&self, xi: f64) -> f64 {
        let r = self.remoulded();
        r + (1.0 - r) * (-3.0 * xi / self.ductility).exp()
    }

    /// The `ξ` whose strength factor is `delta` (the inverse of [`Degradation::strength`]; 0 at or
    /// above the intact strength, infinite at or below the remoulded one).
    pub fn xi_of_strength(&self, delta: f64) -> f64 {
        let r = self.remoulded();
        if delta >= 1.0 {
            0.0
        } else if delta <= r {
            f64::INFINITY
        } else {
            -self.ductility / 3.0 * ((delta - r) / (1.0 - r)).ln()
        }
    }

    /// The accumulated displacement after a rest of `t` seconds: the lost strength regained by
    /// `U(t)` (unchanged without regain or for `t ≤ 0`).
    pub fn rested(&self, xi: f64, t: f64) -> f64 {
        match &self.regain {
            Some(r) if t > 0.0 && xi > 0.0 => {
                let lost = 1.0 - self.strength(xi);
                self.xi_of_strength(1.0 - lost * (1.0 - r.fraction(t)))
            }
            _ => xi,
        }
    }
}

impl Regain {
    /// The degree of regain `U(t)` after a rest of `t` seconds, in [0, 1).
    pub fn fraction(&self, t: f64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let x = (t / self.t50).powf(self.exponent);
        x / (1.0 + x)
    }
}

/// A node's degradation state: the accumulated plastic displacement and the strength factor of
/// its current episode (`1` and `0` for intact soil, and always without degradation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Wear {
    /// Accumulated plastic displacement `ξ`, in pipe diameters.
    pub xi: f64,
    /// The strength factor `δ` of the current episode.
    pub strength: f64,
}

impl Default for Wear {
    fn default() -> Self {
        Self {
            xi: 0.0,
            strength: 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn soil() -> Degradation {
        Degradation {
            sensitivity: 4.0,
            ductility: 12.0,
            regain: Some(Regain {
                t50: 3600.0,
                exponent: 1.0,
            }),
        }
    }

    /// The published form's fixed points: intact at ξ = 0, 95 % of the loss at ξ95, remoulded far
    /// beyond; the inverse returns ξ to 1e-12.
    #[test]
    fn the_form_and_its_inverse() {
        let d = soil();
        assert_eq!(d.strength(0.0), 1.0);
        let lost95 = (1.0 - d.strength(12.0)) / (1.0 - 0.25);
        assert!((lost95 - (1.0 - (-3.0f64).exp())).abs() < 1e-15, "{lost95}");
        assert!((d.strength(1e4) - 0.25).abs() < 1e-15);
        for xi in [0.1, 1.0, 5.0, 30.0] {
            assert!((d.xi_of_strength(d.strength(xi)) - xi).abs() < 1e-12 * xi.max(1.0));
        }
    }

    /// A rest of t50 regains half the lost strength; a rest of 0 nothing; a long rest nearly all.
    #[test]
    fn regain_halves_the_loss_at_t50() {
        let d = soil();
        let xi = 8.0;
        let lost = 1.0 - d.strength(xi);
        let after = 1.0 - d.strength(d.rested(xi, 3600.0));
        assert!(
            (after - 0.5 * lost).abs() < 1e-12,
            "{after} vs {}",
            0.5 * lost
        );
        assert_eq!(d.rested(xi, 0.0), xi);
        assert!(1.0 - d.strength(d.rested(xi, 3.6e8)) < 1e-5 * lost);
        let no_regain = Degradation { regain: None, ..d };
        assert_eq!(no_regain.rested(xi, 1e6), xi);
    }

    #[test]
    fn out_of_range_parameters_name_their_key() {
        let bad = Degradation {
            sensitivity: 0.5,
            ..soil()
        };
        assert_eq!(
            bad.validate().expect_err("S_t < 1").key,
            "degradation.sensitivity"
        );
        let bad = Degradation {
            regain: Some(Regain {
                t50: -1.0,
                exponent: 1.0,
            }),
            ..soil()
        };
        assert_eq!(
            bad.validate().expect_err("t50 < 0").key,
            "degradation.regain_t50"
        );
    }
}
