//! The wave trains' constants as columns ([`Columns`], padded to whole lanes) and the per-time
//! scratch of their evaluation ([`WaveScratch`]).

use serde::{Deserialize, Serialize};

use super::{Component, Direction};
use crate::fastmath::{sin_cos, LANES};

/// Per-time scratch for [`crate::waves::Waves::kinematics_with`]: the time phases at the last `t` and, for a
/// node near the surface, each component's phase sine and cosine.
#[derive(Debug, Clone, Default)]
pub struct WaveScratch {
    pub(super) t: f64,
    /// The last node's truncation and its first component without the seabed's image term
    /// (where the next node's searches start).
    pub(super) n_hint: usize,
    pub(super) deep_hint: usize,
    pub(super) theta: Vec<f64>,
    pub(super) sp: Vec<f64>,
    pub(super) cp: Vec<f64>,
    pub(super) terms: [Vec<f64>; 6],
}

impl WaveScratch {
    /// The sine and cosine of the first `n` components' phases `θ − s k x` at `x`.
    #[inline(always)]
    pub(super) fn phases(&mut self, cols: &Columns, x: f64, n: usize) {
        for (((sp, cp), th), ks) in self.sp[..n]
            .iter_mut()
            .zip(&mut self.cp[..n])
            .zip(&self.theta)
            .zip(&cols.ks)
        {
            (*sp, *cp) = sin_cos(th - ks * x);
        }
    }
}

/// The components' constants as columns (see [`Waves`]).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub(super) struct Columns {
    pub(super) ks: Vec<f64>,
    pub(super) k: Vec<f64>,
    pub(super) amp: Vec<f64>,
    pub(super) aw: Vec<f64>,
    pub(super) aw2: Vec<f64>,
    pub(super) aw3: Vec<f64>,
    pub(super) e2kd: Vec<f64>,
    pub(super) inv_den: Vec<f64>,
    pub(super) ln_tail: Vec<f64>,
}

impl Columns {
    pub(super) fn new(
        components: &[Component],
        direction: Direction,
        depth_factors: &[(f64, f64)],
        tail_max: &[f64],
    ) -> Self {
        let s = direction.sign();
        // Padded to a whole number of lanes with components of zero amplitude (and a truncation
        // bound no node reaches): the loops then have no scalar remainder.
        let len = components.len().next_multiple_of(LANES);
        let pad = |mut v: Vec<f64>, with: f64| {
            v.resize(len, with);
            v
        };
        Self {
            ln_tail: pad(tail_max.iter().map(|m| m.ln()).collect(), f64::NEG_INFINITY),
            ks: pad(components.iter().map(|c| s * c.k).collect(), 0.0),
            k: pad(components.iter().map(|c| c.k).collect(), 0.0),
            amp: pad(components.iter().map(|c| c.amplitude).collect(), 0.0),
            aw: pad(
                components.iter().map(|c| c.amplitude * c.omega).collect(),
                0.0,
            ),
            aw2: pad(
                components
                    .iter()
                    .map(|c| c.amplitude * c.omega * c.omega)
                    .collect(),
                0.0,
            ),
            aw3: pad(
                components
                    .iter()
                    .map(|c| c.amplitude * c.omega * c.omega * c.omega)
                    .collect(),
                0.0,
            ),
            e2kd: pad(depth_factors.iter().map(|f| f.0).collect(), 0.0),
            inv_den: pad(depth_factors.iter().map(|f| f.1).collect(), 0.0),
        }
    }
}
