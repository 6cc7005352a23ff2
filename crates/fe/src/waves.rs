//! Long-crested waves in the riser plane: the JONSWAP spectrum, its synthesis into components, and
//! linear (Airy) kinematics with Wheeler stretching.
//!
//! **Spectrum** (DNV-RP-C205 §3.5.5), one-sided in ω (rad/s), `ω_p = 2π/T_p`:
//!
//! ```text
//! S_PM(ω) = (5/16)·Hs²·ω_p⁴·ω⁻⁵·exp(−(5/4)(ω/ω_p)⁻⁴)
//! S_J(ω)  = A_γ·S_PM(ω)·γ^exp(−½((ω − ω_p)/(σ ω_p))²),   A_γ = 1 − 0.287 ln γ,
//! σ = 0.07 for ω ≤ ω_p, 0.09 above.
//! ```
//!
//! When a sea state does not give γ, catena uses the DNV-RP-C205 rule ([`dnv_gamma`]): γ = 5 for
//! `T_p/√Hs ≤ 3.6`, `exp(5.75 − 1.15·T_p/√Hs)` up to 5, and 1 beyond (not OrcaFlex's "automatic" γ,
//! which follows Isherwood 1987).
//!
//! **Synthesis.** `η(x, t) = Σ a_i cos(ω_i t − s k_i x + ε_i)` with `s = +1` for waves travelling
//! along +x (from the anchor towards the hang-off) and `−1` along −x. The band `[0.5, 4]·ω_p` is cut
//! into N equal bins; each component's frequency is drawn uniformly inside its bin (equal spacing
//! would repeat the record after `2π/Δω`), its amplitude is `a_i = √(2 S(ω_i) Δω)`, its phase uniform
//! on [0, 2π). The amplitudes are then scaled so that `m0 = Σ a_i²/2 = Hs²/16` exactly (the band
//! holds 99.5–99.7 % of the energy). The random numbers come from ChaCha8 (`rand_chacha`, value-
//! stable across platforms and versions) seeded by `seed_from_u64(seed)`: for each component in
//! order of frequency, one draw for the frequency within its bin, then one for its phase, each
//! `u64 >> 11` scaled by 2⁻⁵³ into [0, 1). The same seed gives the same storm on every machine.
//!
//! **Kinematics** (Airy), with `z` measured up from the still water level, depth `d`, the dispersion
//! relation `ω² = g k tanh(k d)` and `φ = ωt − s k x + ε`:
//!
//! ```text
//! u  =  s·Σ aω·C(z)·cos φ,     w  = −Σ aω·S(z)·sin φ,
//! u̇  = −s·Σ aω²·C(z)·sin φ,    ẇ  = −Σ aω²·S(z)·cos φ,
//! C(z) = cosh k(z+d)/sinh kd = (e^{kz} + e^{−k(z+2d)})/(1 − e^{−2kd}),
//! S(z) = sinh k(z+d)/sinh kd = (e^{kz} − e^{−k(z+2d)})/(1 − e^{−2kd}),
//! ```
//!
//! (the stable form: no overflow in deep water). The signs make `w = ∂η/∂t` at the still water level
//! (the linear kinematic surface condition): with `η = a cos φ`, `∂η/∂t = −aω sin φ`.
//! **Wheeler stretching**: below the instantaneous surface `η` the kinematics are evaluated at
//! `z' = (z − η)·d/(d + η)`; above it there is no water. The accelerations are the linear ones at
//! `z'` (as is usual with stretching), not the derivative at a fixed point, which would add the
//! O(ka) motion of `z'` with `η`. Components whose contribution is
//! below 1e-6 of the surface velocity scale are skipped, and so is the whole evaluation below the
//! depth where every component has decayed that far (for storm 23, Tp 9.9 s, about 1300 m for the
//! longest component, much shallower for most: see [`Waves::kinematics`]).
//!
//! **Evaluation.** [`Waves::kinematics_with`] keeps a [`WaveScratch`]: the time phases
//! `(ωt + ε) mod 2π` once per time, and for a node near the surface each component's phase sine and
//! cosine, computed once for its elevation and reused by its kinematics. Sines, cosines and
//! exponentials come from [`crate::fastmath`] (branch-free, within 4e-16 of the C library), in
//! loops over the components' columns, compiled for the baseline processor and for AVX2 and
//! AVX-512, chosen at run time with the same result to the bit.
//!
//! **Ramp.** Waves start from rest under the quintic ramp `r(t)` of [`crate::motion::quintic_ramp`]:
//! elevation and velocities are multiplied by `r`, accelerations are the exact time derivatives
//! (`r·u̇ + ṙ·u`).

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::fastmath::{combine_lanes, exp_nonpositive, lane_dot, lane_sum, sin_cos, LANES};
use crate::motion::quintic_ramp;

mod columns;
mod spectrum;

use columns::Columns;
pub use columns::WaveScratch;
pub use spectrum::{dnv_gamma, jonswap, wavenumber};

/// The direction waves travel in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Direction {
    /// Along +x, from the anchor towards the hang-off.
    PlusX,
    /// Along −x.
    MinusX,
}

impl Direction {
    /// `s = ±1`.
    pub fn sign(self) -> f64 {
        match self {
            Direction::PlusX => 1.0,
            Direction::MinusX => -1.0,
        }
    }
}

/// One wave component.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Component {
    /// Angular frequency ω, rad/s.
    pub omega: f64,
    /// Wavenumber k, rad/m.
    pub k: f64,
    /// Amplitude a, m.
    pub amplitude: f64,
    /// Phase ε, rad.
    pub phase: f64,
}

/// Water particle kinematics at a point: velocity and acceleration `(x, z)`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Kinematics {
    /// Velocity, m/s.
    pub velocity: [f64; 2],
    /// Acceleration, m/s².
    pub acceleration: [f64; 2],
}

/// A long-crested wave train.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Waves {
    /// The components, in order of frequency.
    pub components: Vec<Component>,
    /// Direction of travel.
    pub direction: Direction,
    /// Water depth, m.
    pub depth: f64,
    /// Ramp duration, s (0 for none).
    pub ramp: f64,
    /// The interval `h` of the time grid the kinematics are sampled on in a dynamic run, s; 0 for
    /// every step at the nodes' predicted positions ([`crate::wave_sampling`]).
    #[serde(default)]
    pub kinematics_interval: f64,
    /// A bound on the elevation, `min(Σ a_i, 12σ)`, m.
    eta_bound: f64,
    /// `Σ a_i ω_i`, m/s: the truncation bound (see [`Waves::kinematics`]).
    aw_sum: f64,
    /// `ln(1e-6·Σ a_i ω_i)`: the truncation tolerance as a logarithm.
    ln_tol: f64,
    /// The components as columns for the kinematics loops: `s·k`, `k`, `a`, `aω`, `aω²`, `aω³`,
    /// `e^{−2kd}`, `1/(1 − e^{−2kd})` and the truncation bound `ln max_{j≥i} a_j ω_j`.
    cols: Columns,
    /// Below this depth (m below the still water level) stretching is left out (see
    /// [`Waves::kinematics`]).
    stretch_depth: f64,
}

/// Why a wave train could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WaveError {
    /// A parameter out of range.
    #[error("`{key}` = {value}: expected {expected}")]
    Bad {
        /// The key.
        key: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
}

fn need(ok: bool, key: &'static str, value: f64, expected: &'static str) -> Result<(), WaveError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(WaveError::Bad {
            key,
            value,
            expected,
        })
    }
}

fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

impl Waves {
    /// Builds a train from components (their wavenumbers are recomputed from ω and the depth).
    pub fn from_components(
        components: Vec<Component>,
        direction: Direction,
        depth: f64,
        g: f64,
        ramp: f64,
    ) -> Self {
        let components: Vec<Component> = components
            .into_iter()
            .map(|c| Component {
                k: wavenumber(c.omega, depth, g),
                ..c
            })
            .collect();
        // No elevation exceeds Σ a; 12 standard deviations (3·Hs) is far beyond any crest of a
        // Gaussian sea and much tighter for many components.
        let m0: f64 = components
            .iter()
            .map(|c| 0.5 * c.amplitude * c.amplitude)
            .sum();
        let eta_bound = components
            .iter()
            .map(|c| c.amplitude.abs())
            .sum::<f64>()
            .min(12.0 * m0.sqrt());
        let aw_sum = components
            .iter()
            .map(|c| (c.amplitude * c.omega).abs())
            .sum();
        let depth_factors: Vec<(f64, f64)> = components
            .iter()
            .map(|c| {
                let e = (-2.0 * c.k * depth).exp();
                (e, 1.0 / (1.0 - e))
            })
            .collect();
        let mut tail_max = vec![0.0; components.len()];
        let mut m = 0.0f64;
        for (i, c) in components.iter().enumerate().rev() {
            m = m.max((c.amplitude * c.omega).abs());
            tail_max[i] = m;
        }
        // The depth below which stretching changes the velocity by less than 1e-3·Σaω: the shift
        // of z' is at most η_max, and ∂u/∂z' ≤ Σ a ω k e^{kz'} (bisection on the depth).
        let effect = |depth_below: f64| {
            let zu = -depth_below + 1.1 * eta_bound;
            eta_bound
                * components
                    .iter()
                    .map(|c| (c.amplitude * c.omega * c.k).abs() * (c.k * zu.min(0.0)).exp())
                    .sum::<f64>()
        };
        let (mut lo, mut hi) = (0.0, depth);
        if effect(depth) >= 1e-3 * aw_sum {
            lo = depth;
        }
        for _ in 0..60 {
            if hi - lo < 1e-3 {
                break;
            }
            let mid = 0.5 * (lo + hi);
            if effect(mid) >= 1e-3 * aw_sum {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let stretch_depth = hi;
        let cols = Columns::new(&components, direction, &depth_factors, &tail_max);
        Self {
            components,
            direction,
            depth,
            ramp,
            kinematics_interval: 0.0,
            eta_bound,
            aw_sum,
            ln_tol: (1e-6 * aw_sum).ln(),
            cols,
            stretch_depth,
        }
    }

    /// A regular (Airy) wave of height `height` (crest to trough) and period `period`, its crest at
    /// x = 0 at t = 0 (before the ramp).
    pub fn regular(
        height: f64,
        period: f64,
        direction: Direction,
        depth: f64,
        g: f64,
        ramp: f64,
    ) -> Result<Self, WaveError> {
        need(height > 0.0, "height", height, "a wave height > 0 m")?;
        need(period > 0.0, "period", period, "a period > 0 s")?;
        Ok(Self::from_components(
            vec![Component {
                omega: std::f64::consts::TAU / period,
                k: 0.0,
                amplitude: 0.5 * height,
                phase: 0.0,
            }],
            direction,
            depth,
            g,
            ramp,
        ))
    }

    /// An irregular JONSWAP sea (see the module docs): `n` components over `[0.5, 4]·ω_p`, γ from
    /// the DNV rule when `gamma` is `None`, phases and jitter from `seed`, `m0 = Hs²/16` exactly.
    #[allow(clippy::too_many_arguments)]
    pub fn jonswap(
        hs: f64,
        tp: f64,
        gamma: Option<f64>,
        seed: u64,
        n: usize,
        direction: Direction,
        depth: f64,
        g: f64,
        ramp: f64,
    ) -> Result<Self, WaveError> {
        need(hs > 0.0, "hs", hs, "a significant wave height > 0 m")?;
        need(tp > 0.0, "tp", tp, "a peak period > 0 s")?;
        let gamma = gamma.unwrap_or_else(|| dnv_gamma(hs, tp));
        need(
            (1.0..=10.0).contains(&gamma),
            "gamma",
            gamma,
            "a peak enhancement factor in [1, 10]",
        )?;
        need(
            (1..=100_000).contains(&n),
            "components",
            n as f64,
            "a number of components in [1, 100000]",
        )?;
        let wp = std::f64::consts::TAU / tp;
        let (lo, hi) = (0.5 * wp, 4.0 * wp);
        let dw = (hi - lo) / n as f64;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut comps = Vec::with_capacity(n);
        for i in 0..n {
            let omega = lo + dw * (i as f64 + unit(&mut rng));
            let phase = std::f64::consts::TAU * unit(&mut rng);
            comps.push(Component {
                omega,
                k: 0.0,
                amplitude: (2.0 * jonswap(omega, hs, tp, gamma) * dw).sqrt(),
                phase,
            });
        }
        let m0: f64 = comps.iter().map(|c| 0.5 * c.amplitude * c.amplitude).sum();
        let scale = (hs * hs / 16.0 / m0).sqrt();
        for c in &mut comps {
            c.amplitude *= scale;
        }
        Ok(Self::from_components(comps, direction, depth, g, ramp))
    }

    /// The depth below the still water level below which stretching is left out, m (see
    /// [`Waves::kinematics`]).
    pub fn stretch_depth(&self) -> f64 {
        self.stretch_depth
    }

    /// What a sample of the kinematics and jerk at depth `z` (up from the still water level, at a
    /// time whose phases are already taken) costs, in about 3 ns: 5 for a node so deep that
    /// nothing is evaluated, else 90 and two for each component summed there (see the truncation
    /// in [`Waves::kinematics`]) and one for each component's phase (all of them where the
    /// elevation is evaluated for stretching). Fitted to storm 23's samples at 1 to 900 m (within
    /// 20 % from 1 to 400 m). A weight for sharing the samples between two threads
    /// ([`crate::dynamics::Pair`]): it changes no value.
    pub fn sampling_cost(&self, z: f64) -> f64 {
        let z_up = z + 1.1 * self.eta_bound;
        let above = |i: usize| self.cols.ln_tail[i] + self.cols.k[i] * z_up >= self.ln_tol;
        let n = first_false(above, 0, self.components.len());
        if n == 0 && z_up < 0.0 {
            return 5.0;
        }
        let phases = if z >= -self.stretch_depth {
            self.components.len()
        } else {
            n
        };
        90.0 + 2.0 * n as f64 + phases as f64
    }

    /// The zeroth spectral moment of the components, `Σ a²/2`, m².
    pub fn m0(&self) -> f64 {
        self.components
            .iter()
            .map(|c| 0.5 * c.amplitude * c.amplitude)
            .sum()
    }

    /// The time part of component `c`'s phase, `(ωt + ε) mod 2π` (the same bits wherever it is
    /// computed, so that [`Waves::elevation`] and the stretching in [`Waves::kinematics`] agree
    /// exactly).
    #[inline(always)]
    fn time_phase(c: &Component, t: f64) -> f64 {
        (c.omega * t + c.phase).rem_euclid(std::f64::consts::TAU)
    }

    /// The surface elevation above the still water level at `x`, time `t` (ramped), m.
    pub fn elevation(&self, x: f64, t: f64) -> f64 {
        let (r, _, _) = quintic_ramp(t, self.ramp);
        if r == 0.0 {
            return 0.0;
        }
        // The lanes of `lane_dot`, in its order: the same elevation as the kinematics' stretching.
        let mut acc = [0.0; LANES];
        for (i, ((c, ks), a)) in self
            .components
            .iter()
            .zip(&self.cols.ks)
            .zip(&self.cols.amp)
            .enumerate()
        {
            let (_, cp) = sin_cos(Self::time_phase(c, t) - ks * x);
            acc[i % LANES] += a * cp;
        }
        r * combine_lanes(acc)
    }

    /// A scratch for [`Waves::kinematics_with`], sized for this train.
    pub fn scratch(&self) -> WaveScratch {
        let n = self.cols.k.len();
        WaveScratch {
            t: f64::NAN,
            n_hint: 0,
            deep_hint: 0,
            theta: vec![0.0; n],
            sp: vec![0.0; n],
            cp: vec![0.0; n],
            terms: std::array::from_fn(|_| vec![0.0; n]),
        }
    }

    /// Water particle kinematics at `(x, z)` (z up from the still water level), time `t`, with
    /// Wheeler stretching under the ramped elevation. `None` above the surface (no water).
    ///
    /// **Truncation.** The components come in order of increasing ω, hence of increasing k, and
    /// components i and later contribute at most `max_{j≥i}(a_j ω_j)·e^{k_i z'}` each, a bound that
    /// decreases with i; the sum stops at the first component where it falls below `1e-6·Σ aω`,
    /// using `z' ≤ z + 1.1·η_max` with `η_max = min(Σ a, 12σ_η)`. A node so deep that even the
    /// first component is below the bound gets zero kinematics without evaluating anything. Below
    /// the depth where Wheeler's shift of `z'` (at most `η_max`) changes the velocity by less than
    /// `1e-3·Σ aω` (`η_max·Σ a ω k e^{k z'} < 1e-3 Σ aω`, [`Waves::stretch_depth`]), the elevation
    /// is not evaluated and the kinematics are the unstretched ones (storm 23: below 156 m).
    pub fn kinematics(&self, x: f64, z: f64, t: f64) -> Option<Kinematics> {
        self.kinematics_with(x, z, t, &mut self.scratch())
    }

    /// [`Waves::kinematics`] with a scratch from [`Waves::scratch`] kept between calls: the time
    /// phases are computed once per `t`, and nothing is allocated. The answer is the same.
    ///
    /// On x86-64 processors with AVX2 the same code is compiled a second time for AVX2 and
    /// chosen at run time: its loops over components then run four at a time. The arithmetic is
    /// the same IEEE operations in the same order (no fused multiply-add), so the answer is the
    /// same to the last bit on every machine (`simd_and_scalar_agree_to_the_bit`).
    pub fn kinematics_with(
        &self,
        x: f64,
        z: f64,
        t: f64,
        sc: &mut WaveScratch,
    ) -> Option<Kinematics> {
        kinematics_dispatch(self, x, z, t, sc)
    }

    /// [`Waves::kinematics_with`] and the acceleration's time derivative (the jerk, m/s³) at the
    /// same point: `ü = −s·Σ aω³·C(z')·cos φ`, `ẅ = Σ aω³·S(z')·sin φ`, ramped as
    /// `r·ü + 2ṙ·u̇ + r̈·u` (like the accelerations, the linear ones at the stretched `z'`). The
    /// velocity and acceleration are those of [`Waves::kinematics_with`] to the bit. For the
    /// sampled kinematics of [`crate::wave_sampling`].
    pub fn kinematics_and_jerk_with(
        &self,
        x: f64,
        z: f64,
        t: f64,
        sc: &mut WaveScratch,
    ) -> Option<(Kinematics, [f64; 2])> {
        jerk_dispatch(self, x, z, t, sc)
    }

    /// The kinematics without processor-specific code (see [`Waves::kinematics_with`]).
    #[inline(always)]
    fn kinematics_scalar(
        &self,
        x: f64,
        z: f64,
        t: f64,
        sc: &mut WaveScratch,
    ) -> Option<Kinematics> {
        self.kinematics_generic::<false>(x, z, t, sc)
            .map(|(k, _)| k)
    }

    /// The kinematics and, with `JERK`, the jerk (zero without): one body for both, so that the
    /// velocity and acceleration are the same operations either way.
    #[inline(always)]
    fn kinematics_generic<const JERK: bool>(
        &self,
        x: f64,
        z: f64,
        t: f64,
        sc: &mut WaveScratch,
    ) -> Option<(Kinematics, [f64; 2])> {
        let (r, dr, ddr) = quintic_ramp(t, self.ramp);
        let d = self.depth;
        let z_up = z + 1.1 * self.eta_bound;
        // The bound tail_max[i]·e^{k_i z'} decreases with i: the first i below tol ends the sum
        // (compared as logarithms: ln tail_max[i] + k_i z' ≥ ln tol).
        let ln_tol = self.ln_tol;
        // Searched from the last node's answer: the nodes of a line come in order, a few
        // components apart (a bisection's branches were mispredicted half the time).
        let above = |i: usize| self.cols.ln_tail[i] + self.cols.k[i] * z_up >= ln_tol;
        let n = first_false(above, sc.n_hint, self.components.len());
        sc.n_hint = n;
        if n == 0 && z_up < 0.0 {
            // Deep: under water, and every component negligible.
            return Some(Default::default());
        }
        if sc.theta.len() != self.cols.k.len() {
            *sc = self.scratch(); // sized once, on first use
        }
        if sc.t.to_bits() != t.to_bits() {
            for (th, c) in sc.theta.iter_mut().zip(&self.components) {
                *th = Self::time_phase(c, t);
            }
            sc.t = t;
        }
        let s = self.direction.sign();
        // Stretching only where it matters (and where the surface may be near): the elevation
        // needs every component's phase, which the kinematics below then reuse.
        let shallow = z >= -self.stretch_depth;
        let eta = if shallow && r != 0.0 {
            let cols = &self.cols;
            sc.phases(cols, x, cols.ks.len());
            r * lane_dot(&cols.amp, &sc.cp)
        } else {
            0.0
        };
        if z > eta {
            return None;
        }
        if r == 0.0 && dr == 0.0 && (!JERK || ddr == 0.0) {
            return Some(Default::default());
        }
        let zs = (z - eta) * d / (d + eta);
        // Each component's four terms first (a loop without a running sum, which the compiler can
        // keep in registers and vectorise), then the four sums. The loops run over whole lanes:
        // the terms past the truncation `n` are computed, then set to zero (the sums are those of
        // the first `n` terms, to the bit).
        let c = &self.cols;
        let n_all = n;
        let n = n.next_multiple_of(LANES);
        if !shallow {
            sc.phases(c, x, n);
        }
        let (k, e2kd, inv_den, aw, aw2, aw3) = (
            &c.k[..n],
            &c.e2kd[..n],
            &c.inv_den[..n],
            &c.aw[..n],
            &c.aw2[..n],
            &c.aw3[..n],
        );
        // Where `k(z' + d) > 21` the seabed's image term `e^{−k(z'+2d)}` is below 2⁻⁵⁴ of `e^{kz'}`
        // and vanishes in the roundings of `e^{kz'} ± e^{−k(z'+2d)}`: those components (the
        // shorter waves, from `deep` on, rounded up to whole lanes) skip it with the same result
        // to the bit, and without its division.
        let deep_from = first_false(|j| k[j] * (d + zs) <= 21.0, sc.deep_hint, n);
        sc.deep_hint = deep_from;
        let deep = deep_from.next_multiple_of(LANES).min(n);
        // Each loop's slices cut to its exact length: no bounds checks, so no scalar iterations.
        let (sps, cps) = (&sc.sp[..n], &sc.cp[..n]);
        let [t0, t1, t2, t3, t4, t5] = &mut sc.terms;
        let (t0, t1, t2, t3) = (&mut t0[..n], &mut t1[..n], &mut t2[..n], &mut t3[..n]);
        // The jerk's terms only with `JERK` (empty slices otherwise).
        let nj = if JERK { n } else { 0 };
        let (t4, t5) = (&mut t4[..nj], &mut t5[..nj]);
        {
            let m = deep;
            let (k, e2kd, inv_den, aw, aw2) =
                (&k[..m], &e2kd[..m], &inv_den[..m], &aw[..m], &aw2[..m]);
            let (sps, cps) = (&sps[..m], &cps[..m]);
            let (t0, t1, t2, t3) = (&mut t0[..m], &mut t1[..m], &mut t2[..m], &mut t3[..m]);
            let mj = if JERK { m } else { 0 };
            let (aw3, t4, t5) = (&aw3[..mj], &mut t4[..mj], &mut t5[..mj]);
            for j in 0..m {
                // e^{kz'} and e^{−k(z'+2d)} = e^{−2kd}/e^{kz'}: one exponential per component.
                let e1 = exp_nonpositive(k[j] * zs);
                let e2 = e2kd[j] / e1;
                let (cz, sz) = ((e1 + e2) * inv_den[j], (e1 - e2) * inv_den[j]);
                let a = (aw[j], aw2[j], if JERK { aw3[j] } else { 0.0 });
                let t = component_terms::<JERK>(a, (cz, sz), (sps[j], cps[j]));
                (t0[j], t1[j], t2[j], t3[j]) = (t[0], t[1], t[2], t[3]);
                if JERK {
                    (t4[j], t5[j]) = (t[4], t[5]);
                }
            }
        }
        {
            let (k, inv_den, aw, aw2) = (&k[deep..], &inv_den[deep..], &aw[deep..], &aw2[deep..]);
            let (sps, cps) = (&sps[deep..], &cps[deep..]);
            let (t0, t1, t2, t3) = (
                &mut t0[deep..],
                &mut t1[deep..],
                &mut t2[deep..],
                &mut t3[deep..],
            );
            let dj = if JERK { deep } else { 0 };
            let (aw3, t4, t5) = (&aw3[dj..nj], &mut t4[dj..], &mut t5[dj..]);
            for j in 0..k.len() {
                let cz = exp_nonpositive(k[j] * zs) * inv_den[j];
                // Deep water: both depth factors are e^{kz'}.
                let a = (aw[j], aw2[j], if JERK { aw3[j] } else { 0.0 });
                let t = component_terms::<JERK>(a, (cz, cz), (sps[j], cps[j]));
                (t0[j], t1[j], t2[j], t3[j]) = (t[0], t[1], t[2], t[3]);
                if JERK {
                    (t4[j], t5[j]) = (t[4], t[5]);
                }
            }
        }
        // The terms past the truncation are left out (zero in their lanes).
        for t in [t0, t1, t2, t3, t4, t5] {
            let from = n_all.min(t.len());
            t[from..].fill(0.0);
        }
        let sum = |v: &[f64]| lane_sum(&v[..n]);
        let (u, w, ut, wt) = (
            s * sum(&sc.terms[0]),
            -sum(&sc.terms[1]),
            -s * sum(&sc.terms[2]),
            -sum(&sc.terms[3]),
        );
        let kin = Kinematics {
            velocity: [r * u, r * w],
            acceleration: [r * ut + dr * u, r * wt + dr * w],
        };
        let jerk = if JERK {
            let (utt, wtt) = (-s * sum(&sc.terms[4]), sum(&sc.terms[5]));
            [
                r * utt + 2.0 * dr * ut + ddr * u,
                r * wtt + 2.0 * dr * wt + ddr * w,
            ]
        } else {
            [0.0; 2]
        };
        Some((kin, jerk))
    }
}

/// The water kinematics a wave theory gives the line: what the dynamics' loads and the sampled
/// kinematics ([`crate::wave_sampling`]) use of it, and all they use. Airy waves ([`Waves`])
/// implement it; a new wave theory (a stream function, a Stokes wave, a kinematics table) is a type
/// that implements it, in its own module beside this one.
pub trait WaveKinematics {
    /// What the kinematics keep between calls (e.g. the time phases of a `t`), in the Workspace.
    type Scratch: Default + std::fmt::Debug + Send;

    /// The velocity and acceleration of the water at `(x, z)` (z up from the still water level) at
    /// `t`, or `None` above the surface.
    fn water_at(&self, x: f64, z: f64, t: f64, sc: &mut Self::Scratch) -> Option<Kinematics>;

    /// [`WaveKinematics::water_at`] and the acceleration's time derivative (m/s³).
    fn water_and_jerk_at(
        &self,
        x: f64,
        z: f64,
        t: f64,
        sc: &mut Self::Scratch,
    ) -> Option<(Kinematics, [f64; 2])>;

    /// The interval the kinematics are sampled at in the dynamics, s (0: exact at every step).
    fn sampling_interval(&self) -> f64;
}

impl WaveKinematics for Waves {
    type Scratch = WaveScratch;

    #[inline]
    fn water_at(&self, x: f64, z: f64, t: f64, sc: &mut WaveScratch) -> Option<Kinematics> {
        self.kinematics_with(x, z, t, sc)
    }

    #[inline]
    fn water_and_jerk_at(
        &self,
        x: f64,
        z: f64,
        t: f64,
        sc: &mut WaveScratch,
    ) -> Option<(Kinematics, [f64; 2])> {
        self.kinematics_and_jerk_with(x, z, t, sc)
    }

    fn sampling_interval(&self) -> f64 {
        self.kinematics_interval
    }
}

/// One component's terms of the kinematics' sums (the one place they are written; the finite-depth
/// and the deep-water loops both call it): velocity `aω·C·cos φ`, `aω·S·sin φ`, acceleration
/// `aω²·C·sin φ`, `aω²·S·cos φ` and, with `JERK`, `aω³·C·cos φ`, `aω³·S·sin φ`, for the amplitudes
/// `(aω, aω², aω³)`, the depth factors `(C, S)` (`cosh k(z'+d)/sinh kd`, `sinh k(z'+d)/sinh kd`; both
/// `e^{kz'}` in deep water) and `(sin φ, cos φ)`.
#[inline(always)]
fn component_terms<const JERK: bool>(
    (aw, aw2, aw3): (f64, f64, f64),
    (cz, sz): (f64, f64),
    (sp, cp): (f64, f64),
) -> [f64; 6] {
    let mut t = [
        aw * cz * cp,
        aw * sz * sp,
        aw2 * cz * sp,
        aw2 * sz * cp,
        0.0,
        0.0,
    ];
    if JERK {
        (t[4], t[5]) = (aw3 * cz * cp, aw3 * sz * sp);
    }
    t
}

/// [`Waves::kinematics_with`], compiled for the baseline processor and again for AVX2, chosen
/// at run time.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn kinematics_dispatch(
    w: &Waves,
    x: f64,
    z: f64,
    t: f64,
    sc: &mut WaveScratch,
) -> Option<Kinematics> {
    w.kinematics_scalar(x, z, t, sc)
}

/// [`Waves::kinematics_and_jerk_with`], compiled like [`kinematics_dispatch`].
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn jerk_dispatch(
    w: &Waves,
    x: f64,
    z: f64,
    t: f64,
    sc: &mut WaveScratch,
) -> Option<(Kinematics, [f64; 2])> {
    w.kinematics_generic::<true>(x, z, t, sc)
}

/// The first `i < len` where `pred(i)` is false (`len` if none), for a `pred` true then false,
/// searched from `hint` (up while true, down while the one before is false).
#[inline(always)]
fn first_false(pred: impl Fn(usize) -> bool, hint: usize, len: usize) -> usize {
    let mut i = hint.min(len);
    if i < len && pred(i) {
        i += 1;
        while i < len && pred(i) {
            i += 1;
        }
    } else {
        while i > 0 && !pred(i - 1) {
            i -= 1;
        }
    }
    i
}

#[cfg(test)]
mod tests;
