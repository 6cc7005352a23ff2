//! Wave kinematics sampled on a time grid and interpolated in between (`[waves]
//! kinematics_interval`).
//!
//! A JONSWAP sea of 400 components costs a sum of 400 terms (a sine, a cosine and an exponential
//! each) per node near the surface; evaluated at every node at every step, that sum costs more than
//! half a riser's step. The water kinematics vary on the wave periods (2.5 s and more in storm 23),
//! much slower than the structure's step, so catena evaluates them every `h` seconds (the grid
//! times `t_m = m·h`) and interpolates between, as RIFLEX does with its wave-kinematics time step.
//!
//! **Samples.** At each grid time `t_m` every node gets its velocity `u`, acceleration `u̇` and jerk
//! `ü` (all exact, [`crate::waves::Waves::kinematics_and_jerk_with`]), at the node's position
//! extrapolated from the committed State at the start of the step that first needs `t_m`:
//! `x(t_m) = x_n + v_n τ + ½ a_n τ²`, `τ = t_m − t_n`. The two samples around the step's end
//! time are committed history in the State ([`KinematicsGrid`]): a failed and retried step finds
//! the same samples, a restart from a checkpoint the same samples, so a run is still bit-for-bit
//! the same whatever its checkpoints.
//!
//! **Interpolation** at `t = t_{m−1} + s·h`, `s ∈ (0, 1]`, by cubic Hermite polynomials
//! `h00 = 2s³ − 3s² + 1`, `h10 = s³ − 2s² + s`, `h01 = −2s³ + 3s²`, `h11 = s³ − s²`:
//!
//! ```text
//! u(t)  = h00·u₀ + h·h10·u̇₀ + h01·u₁ + h·h11·u̇₁
//! u̇(t)  = h00·u̇₀ + h·h10·ü₀ + h01·u̇₁ + h·h11·ü₁
//! ```
//!
//! Exact at the grid times; for one component of frequency ω the error is at most
//! `(ωh)⁴/384` of its amplitude (the Hermite remainder `f⁗·h⁴/384`). With the default
//! `h = T/40` (`T`: the peak or the regular wave's period; storm 23: 0.2475 s, about five steps)
//! that is 1.6·10⁻⁶ at the spectral peak and 4·10⁻⁴ at the JONSWAP band's top (4ω_p). The slopes
//! are the Eulerian rates at the sampled points, while the node moves by `ẋ·h` between them, an
//! error of at most `0.1·k·ẋ·h` relative (`max s(1−s)(1−2s) ≈ 0.1`; 5·10⁻⁴ for storm 23's peak
//! with the node at 0.5 m/s). Near the surface, Wheeler's `z'` moves with η while the
//! accelerations are the linear ones at `z'` (as without sampling), so the slopes miss that
//! motion: at most about `0.1·k·a·ω·h` of `aω` (1.6·10⁻³ for storm 23 with `a = Hs/2` at its
//! peak). What this changes in a storm's results and what it saves is measured in
//! `docs/accuracy.md`.
//!
//! A node with no water at either sample (above the surface) gets the exact kinematics at its
//! predicted position, as without sampling. With `h = 0` (or no waves) nothing here runs.

use std::ops::Range;

use serde::{Deserialize, Serialize};

#[cfg(test)]
use crate::waves::Waves;
use crate::waves::{Kinematics, WaveKinematics};

/// The kinematics at one node at a grid time: velocity, acceleration and jerk, `[x, z]` each.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Sample {
    /// Velocity, m/s.
    pub v: [f64; 2],
    /// Acceleration, m/s².
    pub a: [f64; 2],
    /// Jerk, m/s³.
    pub j: [f64; 2],
}

/// The samples at the two grid times `(m − 1)·h` and `m·h` around the last committed step's end:
/// history, kept in the State. `None` for a node above the surface.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct KinematicsGrid {
    /// `m`, the later time's index.
    pub index: u64,
    /// The samples at `(m − 1)·h` and `m·h`, one per node.
    pub samples: [Vec<Option<Sample>>; 2],
}

/// The grid index `m` of the interval `((m − 1)·h, m·h]` that holds `t` (a `t` within 1e-9·h of a
/// grid time belongs to the interval that ends there).
pub fn grid_index(t: f64, h: f64) -> u64 {
    ((t / h - 1e-9).ceil()).max(1.0) as u64
}

/// The kinematics at `t = t₀ + s·h` between the samples `k0` at `t₀` and `k1` at `t₀ + h` (see the
/// module docs).
#[inline]
pub fn interpolate(k0: &Sample, k1: &Sample, s: f64, h: f64) -> Kinematics {
    let s2 = s * s;
    let s3 = s2 * s;
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = (s3 - 2.0 * s2 + s) * h;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = (s3 - s2) * h;
    let mut out = Kinematics::default();
    for c in 0..2 {
        out.velocity[c] = h00 * k0.v[c] + h10 * k0.a[c] + h01 * k1.v[c] + h11 * k1.a[c];
        out.acceleration[c] = h00 * k0.a[c] + h10 * k0.j[c] + h01 * k1.a[c] + h11 * k1.j[c];
    }
    out
}

/// Samples the nodes `nodes` at time `t` into `out` (one entry per node of the line), at the
/// positions `(x, z)` (z up from the still water level) that `position(i)` gives.
pub fn sample_nodes<W: WaveKinematics>(
    waves: &W,
    t: f64,
    position: impl Fn(usize) -> (f64, f64),
    (out, nodes): (&mut [Option<Sample>], Range<usize>),
    sc: &mut W::Scratch,
) {
    for i in nodes {
        let (x, z) = position(i);
        out[i] = waves.water_and_jerk_at(x, z, t, sc).map(|(k, j)| Sample {
            v: k.velocity,
            a: k.acceleration,
            j,
        });
    }
}

/// Makes `grid` hold, at the nodes `nodes`, the samples of the interval `((m − 1)·h, m·h]`: the
/// earlier one copied from `prev` when `prev` holds the interval before (each grid time is sampled
/// once), else sampled; the later one sampled. `position(t, i)` is node `i`'s `(x, z)` at grid
/// time `t`. A thread that steps a part of the line ([`crate::dynamics::Pair`]) samples its own
/// nodes; each node's samples are the same whichever thread takes them.
pub fn fill_interval<W: WaveKinematics>(
    waves: &W,
    (h, m): (f64, u64),
    prev: Option<&KinematicsGrid>,
    position: impl Fn(f64, usize) -> (f64, f64),
    (grid, nodes): (&mut KinematicsGrid, Range<usize>),
    sc: &mut W::Scratch,
) {
    let (t0, t1) = ((m - 1) as f64 * h, m as f64 * h);
    let [s0, s1] = &mut grid.samples;
    match prev {
        Some(g) if g.index + 1 == m => {
            s0[nodes.clone()].copy_from_slice(&g.samples[1][nodes.clone()]);
        }
        _ => sample_nodes(waves, t0, |i| position(t0, i), (s0, nodes.clone()), sc),
    }
    sample_nodes(waves, t1, |i| position(t1, i), (s1, nodes), sc);
    grid.index = m;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::waves::Direction;

    const G: f64 = 9.80665;

    fn sample(w: &Waves, x: f64, z: f64, t: f64) -> Sample {
        let (k, j) = w
            .kinematics_and_jerk_with(x, z, t, &mut w.scratch())
            .expect("under water");
        Sample {
            v: k.velocity,
            a: k.acceleration,
            j,
        }
    }

    /// The jerk is the acceleration's time derivative: central differences at a fixed point in
    /// deep water (no stretching), in the ramp and after it, within 1e-6 of the jerk's scale.
    #[test]
    fn jerk_is_the_time_derivative_of_the_acceleration() {
        let w = Waves::jonswap(5.0, 9.9, None, 23, 400, Direction::PlusX, 1000.0, G, 20.0)
            .expect("storm");
        let (x, z) = (130.0, -200.0);
        for t in [7.3, 13.9, 50.2, 361.0] {
            let dt = 1e-4;
            let a = |t| sample(&w, x, z, t).a;
            let (ap, am) = (a(t + dt), a(t - dt));
            let j = sample(&w, x, z, t).j;
            let scale = j[0].abs().max(j[1].abs()).max(1e-6);
            for c in 0..2 {
                let fd = (ap[c] - am[c]) / (2.0 * dt);
                assert!(
                    (fd - j[c]).abs() < 1e-6 * scale + 1e-12,
                    "t {t}, {c}: fd {fd} jerk {}",
                    j[c]
                );
            }
        }
    }

    /// The kinematics that come with the jerk are those without it, to the bit.
    #[test]
    fn the_jerk_leaves_the_kinematics_as_they_were() {
        let w = Waves::jonswap(5.0, 9.9, None, 23, 400, Direction::PlusX, 1000.0, G, 10.0)
            .expect("storm");
        let (mut a, mut b) = (w.scratch(), w.scratch());
        for i in 0..300 {
            let t = 3.0 + 0.41 * i as f64;
            let (x, z) = (900.0 - 0.7 * i as f64, 1.0 - 3.1 * i as f64);
            let plain = w.kinematics_with(x, z, t, &mut a);
            let with = w.kinematics_and_jerk_with(x, z, t, &mut b).map(|(k, _)| k);
            assert_eq!(
                plain.map(|k| (
                    k.velocity.map(f64::to_bits),
                    k.acceleration.map(f64::to_bits)
                )),
                with.map(|k| (
                    k.velocity.map(f64::to_bits),
                    k.acceleration.map(f64::to_bits)
                )),
                "{i}"
            );
        }
    }

    /// Interpolation between samples at a fixed point against the exact kinematics, a regular
    /// wave of period 10 s. Below the stretching depth: exact at the ends, and within the Hermite
    /// bound `(ωh)⁴/384` of the amplitude there (with a factor 1.5 for rounding) inside, for
    /// h = T/40 and h = T/10; linear interpolation would be off by `(ωh)²/8`, 160 times more at
    /// T/40. Near the surface Wheeler's `z'` moves with η, which the linear accelerations (the
    /// slopes) leave out: within `0.1·k·a·ω·h` of `aω` there (the module docs).
    #[test]
    fn hermite_interpolation_within_its_bound() {
        let w = Waves::regular(4.0, 10.0, Direction::PlusX, 1000.0, G, 0.0).expect("wave");
        let omega = std::f64::consts::TAU / 10.0;
        let k = w.components[0].k;
        let x = 37.0;
        assert!(w.stretch_depth() < 150.0, "{}", w.stretch_depth());
        for (z, stretched) in [(-150.0, false), (-12.0, true)] {
            for h in [0.25, 1.0] {
                let t0 = 40.0;
                let (k0, k1) = (sample(&w, x, z, t0), sample(&w, x, z, t0 + h));
                let amp_v = 2.0 * omega * (k * z).exp();
                let amp_a = omega * amp_v;
                let hermite = 1.5 * (omega * h).powi(4) / 384.0;
                let bound = if stretched {
                    hermite + 0.1 * k * 2.0 * omega * h
                } else {
                    hermite
                };
                let mut worst: f64 = 0.0;
                for i in 0..=20 {
                    let s = i as f64 / 20.0;
                    let got = interpolate(&k0, &k1, s, h);
                    let exact = w.kinematics(x, z, t0 + s * h).expect("wet");
                    for c in 0..2 {
                        let ev = (got.velocity[c] - exact.velocity[c]).abs() / amp_v;
                        let ea = (got.acceleration[c] - exact.acceleration[c]).abs() / amp_a;
                        worst = worst.max(ev).max(ea);
                        assert!(
                            ev <= bound + 1e-13,
                            "z {z} h {h} s {s}: velocity {ev:e} > {bound:e}"
                        );
                        assert!(
                            ea <= bound + 1e-13,
                            "z {z} h {h} s {s}: acceleration {ea:e} > {bound:e}"
                        );
                    }
                }
                // The Hermite bound is not loose by orders: the error is of its size.
                if !stretched {
                    assert!(
                        worst > 0.2 * bound,
                        "h {h}: worst {worst:e}, bound {bound:e}"
                    );
                }
            }
        }
    }

    #[test]
    fn grid_index_takes_a_grid_time_as_an_interval_end() {
        assert_eq!(grid_index(0.05, 0.2), 1);
        assert_eq!(grid_index(0.2, 0.2), 1);
        assert_eq!(grid_index(0.2 + 1e-12, 0.2), 1);
        assert_eq!(grid_index(0.25, 0.2), 2);
        assert_eq!(grid_index(3.0 * 0.1 * 2.0, 0.2), 3); // 0.6000000000000001
        assert_eq!(grid_index(0.0, 0.2), 1);
    }
}
