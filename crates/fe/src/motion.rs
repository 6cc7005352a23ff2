//! Prescribed motion of the top end (the vessel's hang-off), relative to its static position:
//! displacement, velocity and acceleration at any time, exactly (HHT sees consistent prescribed
//! motion). Sources: staged constant velocities, a harmonic with the quintic ramp, a CSV series.
//!
//! The quintic ramp `r(σ) = σ³(10 − 15σ + 6σ²)`, `σ = min(t/T_ramp, 1)`, rises from 0 to 1 with zero
//! first and second derivatives at both ends.

use serde::{Deserialize, Serialize};

/// Prescribed motion of the top end, relative to its static position.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum TopMotion {
    /// Constant velocities for successive durations `(duration s, vx m/s, vz m/s)`; still afterwards.
    Staged(Vec<(f64, f64, f64)>),
    /// `x = Ax·r(t)·sin(ωt + φ)`, `z = Az·r(t)·sin(ωt + φ)`, with the quintic ramp
    /// `r = σ³(10 − 15σ + 6σ²)`, `σ = min(t/T_ramp, 1)` (no ramp if `T_ramp = 0`).
    Harmonic {
        /// Surge amplitude, m.
        surge: f64,
        /// Heave amplitude, m.
        heave: f64,
        /// Period, s.
        period: f64,
        /// Phase, rad.
        phase: f64,
        /// Ramp duration, s.
        ramp: f64,
    },
    /// A time series `(t, dx, dz)`, linear in between (velocity piecewise constant, acceleration 0);
    /// held at its ends.
    Series(Vec<(f64, f64, f64)>),
}

/// Displacement, velocity and acceleration of a prescribed motion, `[x, z]` each.
pub type Kinematics = ([f64; 2], [f64; 2], [f64; 2]);

/// The quintic ramp and its first two time derivatives.
pub fn quintic_ramp(t: f64, duration: f64) -> (f64, f64, f64) {
    if duration <= 0.0 || t >= duration {
        return (1.0, 0.0, 0.0);
    }
    if t <= 0.0 {
        return (0.0, 0.0, 0.0);
    }
    let s = t / duration;
    let r = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
    let dr = 30.0 * s * s * (1.0 - s) * (1.0 - s) / duration;
    let ddr = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) / (duration * duration);
    (r, dr, ddr)
}

impl TopMotion {
    /// The motion at time t.
    pub fn at(&self, t: f64) -> Kinematics {
        match self {
            TopMotion::Staged(stages) => {
                let mut d = [0.0; 2];
                let mut t0 = 0.0;
                for &(dur, vx, vz) in stages {
                    if t < t0 + dur {
                        let tau = (t - t0).max(0.0);
                        return ([d[0] + vx * tau, d[1] + vz * tau], [vx, vz], [0.0; 2]);
                    }
                    d[0] += vx * dur;
                    d[1] += vz * dur;
                    t0 += dur;
                }
                (d, [0.0; 2], [0.0; 2])
            }
            TopMotion::Harmonic {
                surge,
                heave,
                period,
                phase,
                ramp,
            } => {
                let w = std::f64::consts::TAU / period;
                let (r, dr, ddr) = quintic_ramp(t, *ramp);
                let (s, c) = (w * t + phase).sin_cos();
                let f = r * s;
                let df = dr * s + r * w * c;
                let ddf = ddr * s + 2.0 * dr * w * c - r * w * w * s;
                (
                    [surge * f, heave * f],
                    [surge * df, heave * df],
                    [surge * ddf, heave * ddf],
                )
            }
            TopMotion::Series(pts) => {
                if pts.is_empty() {
                    return ([0.0; 2], [0.0; 2], [0.0; 2]);
                }
                if t <= pts[0].0 {
                    return ([pts[0].1, pts[0].2], [0.0; 2], [0.0; 2]);
                }
                for w in pts.windows(2) {
                    if t < w[1].0 {
                        let h = w[1].0 - w[0].0;
                        let f = (t - w[0].0) / h;
                        let vx = (w[1].1 - w[0].1) / h;
                        let vz = (w[1].2 - w[0].2) / h;
                        return (
                            [
                                w[0].1 + f * (w[1].1 - w[0].1),
                                w[0].2 + f * (w[1].2 - w[0].2),
                            ],
                            [vx, vz],
                            [0.0; 2],
                        );
                    }
                }
                let l = pts[pts.len() - 1];
                ([l.1, l.2], [0.0; 2], [0.0; 2])
            }
        }
    }
}

/// The top end's prescribed state at an instant: displacement, velocity and acceleration from its
/// static position `(x, z)`, and the vessel's pitch (rad, positive bow down).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TopState {
    /// Displacement, m.
    pub d: [f64; 2],
    /// Velocity, m/s.
    pub v: [f64; 2],
    /// Acceleration, m/s².
    pub a: [f64; 2],
    /// Vessel pitch, rad (0 without a vessel).
    pub pitch: f64,
    /// Its rate and acceleration, rad/s and rad/s².
    pub pitch_rates: [f64; 2],
}
