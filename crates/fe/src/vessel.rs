//! Vessel motion from displacement RAOs, driven by the same wave train that loads the riser, and its
//! rigid-body transfer to the hang-off.
//!
//! **RAO conventions** (as OrcaFlex and CableDyn state them): for each motion j (surge, heave,
//! pitch) an amplitude per metre of wave amplitude and a phase **lag** after the wave crest passes
//! the RAO origin `X_o`. A component `a cos(ωt − s k X + ε)` drives
//!
//! ```text
//! ξ_j(t) = a·|R_j|·cos(ωt − s k X_o + ε − lag_j) = Re(a·R_j·e^{iψ}),   R_j = |R_j| e^{−i·lag_j},
//! ψ = ωt − s k X_o + ε.
//! ```
//!
//! RAOs are interpolated in period as complex numbers (re/im, linear in period), never amplitude and
//! phase apart; outside the table the end values are held. Pitch is positive bow down (rotation
//! about +y with z up), read in degrees per metre and used in radians. The table is for waves
//! travelling along +x; for waves along −x the hull is taken as fore-aft symmetric: surge and pitch
//! change sign (the motion is mirrored), heave does not.
//!
//! **A vessel under way** (a lay vessel, speed `U` along +x): the RAO origin is at
//! `X_o(t) = X_o(t_ref) + U·(t − t_ref)`, so the phase is `ψ = ωt − s k X_o(t) + ε` and its rate the
//! frequency of encounter `ω_e = ω − s k U`, which the velocities and accelerations use (`×iω_e`,
//! `×−ω_e²`; a change of `U` is not differentiated: `k·U̇` is some 10⁻⁴ of `ω_e²` at a lay's
//! speed-up). The RAOs stay those of the wave's own frequency: at lay speeds (below 0.2 m/s)
//! `ω_e` differs from `ω` by under 2 % for waves longer than 4 s.
//!
//! **Transfer to the hang-off** (rigid body, small angles), the hang-off at `(Δx, Δz)` from the RAO
//! origin: `X_h = X_h0 + ξ_1 + θ·Δz`, `Z_h = Z_h0 + ξ_3 − θ·Δx`. Velocities and accelerations are
//! exact (`×iω`, `×−ω²` per component), and the quintic ramp multiplies the motion with its exact
//! derivatives: `(r ξ)' = r ξ' + ṙ ξ`, `(r ξ)'' = r ξ'' + 2ṙ ξ' + r̈ ξ`.

use serde::{Deserialize, Serialize};

use crate::motion::quintic_ramp;
use crate::waves::Waves;

/// A complex number `(re, im)`.
pub type Complex = (f64, f64);

/// A displacement RAO table: per period, the complex RAOs of surge (m/m), heave (m/m) and pitch
/// (rad/m).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RaoTable {
    /// Periods, s, increasing.
    pub periods: Vec<f64>,
    /// `[surge, heave, pitch]` at each period, `|R| e^{−i·lag}`.
    pub rao: Vec<[Complex; 3]>,
}

/// Why an RAO table could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("line {line}: {what}")]
pub struct RaoError {
    /// The line (from 1).
    pub line: usize,
    /// What is wrong.
    pub what: String,
}

fn polar(amplitude: f64, lag_deg: f64) -> Complex {
    let (s, c) = (-lag_deg.to_radians()).sin_cos();
    (amplitude * c, amplitude * s)
}

impl RaoTable {
    /// Reads the CSV format of `semi-rao.csv`: `#` comment lines, a header line naming the columns
    /// `period_s, surge_m_per_m, surge_lag_deg, heave_m_per_m, heave_lag_deg, pitch_deg_per_m,
    /// pitch_lag_deg` (in that order), then one row per period, periods increasing.
    pub fn parse_csv(text: &str) -> Result<Self, RaoError> {
        const HEADER: [&str; 7] = [
            "period_s",
            "surge_m_per_m",
            "surge_lag_deg",
            "heave_m_per_m",
            "heave_lag_deg",
            "pitch_deg_per_m",
            "pitch_lag_deg",
        ];
        let mut periods = Vec::new();
        let mut rao = Vec::new();
        let mut header = false;
        for (i, raw) in text.lines().enumerate() {
            let line = raw.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            if !header {
                if cells != HEADER {
                    return Err(RaoError {
                        line: i + 1,
                        what: format!("expected the header `{}`", HEADER.join(",")),
                    });
                }
                header = true;
                continue;
            }
            if cells.len() != 7 {
                return Err(RaoError {
                    line: i + 1,
                    what: format!("expected 7 numbers, found {} cells", cells.len()),
                });
            }
            let mut v = [0.0; 7];
            for (k, c) in cells.iter().enumerate() {
                v[k] = c
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| RaoError {
                        line: i + 1,
                        what: format!("column `{}`: `{c}` is not a finite number", HEADER[k]),
                    })?;
            }
            if v[0] <= 0.0 || periods.last().is_some_and(|p| v[0] <= *p) {
                return Err(RaoError {
                    line: i + 1,
                    what: "periods must be > 0 s and increasing".into(),
                });
            }
            if v[1] < 0.0 || v[3] < 0.0 || v[5] < 0.0 {
                return Err(RaoError {
                    line: i + 1,
                    what: "RAO amplitudes must be >= 0".into(),
                });
            }
            periods.push(v[0]);
            rao.push([
                polar(v[1], v[2]),
                polar(v[3], v[4]),
                polar(v[5].to_radians(), v[6]),
            ]);
        }
        if periods.is_empty() {
            return Err(RaoError {
                line: text.lines().count(),
                what: "no RAO rows".into(),
            });
        }
        Ok(Self { periods, rao })
    }

    /// The complex RAOs at angular frequency `omega`, interpolated linearly in period (re and im),
    /// the end values held outside the table.
    pub fn at(&self, omega: f64) -> [Complex; 3] {
        let t = std::f64::consts::TAU / omega;
        let p = &self.periods;
        let n = p.len();
        if t <= p[0] {
            return self.rao[0];
        }
        if t >= p[n - 1] {
            return self.rao[n - 1];
        }
        let i = p.partition_point(|x| *x < t).clamp(1, n - 1);
        let f = (t - p[i - 1]) / (p[i] - p[i - 1]);
        let (a, b) = (&self.rao[i - 1], &self.rao[i]);
        let lerp = |x: Complex, y: Complex| (x.0 + f * (y.0 - x.0), x.1 + f * (y.1 - x.1));
        [lerp(a[0], b[0]), lerp(a[1], b[1]), lerp(a[2], b[2])]
    }
}

/// A vessel on the wave train: its RAOs, the RAO origin's x and the hang-off's offset from it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Vessel {
    /// The table.
    pub table: RaoTable,
    /// x of the RAO origin (absolute, the riser's frame) at `t_ref`, m.
    pub origin_x: f64,
    /// The vessel's speed along +x (a lay vessel under way; 0 for a moored one), m/s: the RAO
    /// origin is at `origin_x + speed·(t − t_ref)`.
    #[serde(default)]
    pub speed: f64,
    /// The time at which the RAO origin is at `origin_x`, s.
    #[serde(default)]
    pub t_ref: f64,
    /// The hang-off relative to the RAO origin `(Δx, Δz)`, m.
    pub hangoff_offset: [f64; 2],
    /// Per wave component, `[surge, heave, pitch]` RAOs at its frequency (mirrored for waves along −x).
    rao: Vec<[Complex; 3]>,
}

/// The vessel's motion at an instant: `[surge, heave, pitch]` and the hang-off's displacement,
/// velocity and acceleration `(x, z)`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VesselMotion {
    /// Surge, heave (m) and pitch (rad), ramped.
    pub motions: [f64; 3],
    /// Hang-off displacement from its static position `(x, z)`, m.
    pub displacement: [f64; 2],
    /// Hang-off velocity, m/s.
    pub velocity: [f64; 2],
    /// Hang-off acceleration, m/s².
    pub acceleration: [f64; 2],
    /// Pitch rate and pitch acceleration, rad/s and rad/s² (positive bow down, ramped): what turns a
    /// top held by the vessel ([`crate::boundary`]).
    pub pitch_rates: [f64; 2],
}

impl Vessel {
    /// The vessel for a wave train (the RAOs are interpolated once per component).
    pub fn new(table: RaoTable, origin_x: f64, hangoff_offset: [f64; 2], waves: &Waves) -> Self {
        let mirror = waves.direction.sign() < 0.0;
        let rao = waves
            .components
            .iter()
            .map(|c| {
                let mut r = table.at(c.omega);
                if mirror {
                    r[0] = (-r[0].0, -r[0].1);
                    r[2] = (-r[2].0, -r[2].1);
                }
                r
            })
            .collect();
        Self {
            table,
            origin_x,
            speed: 0.0,
            t_ref: 0.0,
            hangoff_offset,
            rao,
        }
    }

    /// Puts the RAO origin at `x` at time `t`, moving at `speed` along +x from there (a lay
    /// vessel under way: its phase in the waves follows it along the route).
    pub fn track(&mut self, x: f64, t: f64, speed: f64) {
        (self.origin_x, self.t_ref, self.speed) = (x, t, speed);
    }

    /// The motion at time `t` (see the module docs), from the same wave train.
    pub fn motion(&self, waves: &Waves, t: f64) -> VesselMotion {
        let (r, dr, ddr) = quintic_ramp(t, waves.ramp);
        // ξ, ξ', ξ'' of [surge, heave, pitch], unramped.
        let m = if r != 0.0 || dr != 0.0 || ddr != 0.0 {
            motion_sums(self, waves, t)
        } else {
            [[0.0; 3]; 3]
        };
        let ramped = |j: usize| {
            (
                r * m[0][j],
                r * m[1][j] + dr * m[0][j],
                r * m[2][j] + 2.0 * dr * m[1][j] + ddr * m[0][j],
            )
        };
        let (s1, s3, th) = (ramped(0), ramped(1), ramped(2));
        let [dx, dz] = self.hangoff_offset;
        VesselMotion {
            motions: [s1.0, s3.0, th.0],
            displacement: [s1.0 + th.0 * dz, s3.0 - th.0 * dx],
            velocity: [s1.1 + th.1 * dz, s3.1 - th.1 * dx],
            acceleration: [s1.2 + th.2 * dz, s3.2 - th.2 * dx],
            pitch_rates: [th.1, th.2],
        }
    }
}

/// The unramped `ξ, ξ', ξ''` of `[surge, heave, pitch]` at `t`: the components' phase sines and
/// cosines a chunk at a time (a loop without sums, which runs four or eight components at a time
/// where AVX2 or AVX-512 is found at run time), then the sums in the components' order: the same
/// operations in the same order as one loop, so the same values to the bit.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn motion_sums(v: &Vessel, waves: &Waves, t: f64) -> [[f64; 3]; 3] {
    const CHUNK: usize = 16;
    let s = waves.direction.sign();
    // The RAO origin now (`origin_x` itself for a vessel that does not move: `0·(t − t_ref)` adds
    // nothing, nor does `k·0` change ω below, so a moored vessel's motion keeps its bits).
    let origin = v.origin_x + v.speed * (t - v.t_ref);
    let mut m = [[0.0; 3]; 3];
    for (cs, raos) in waves.components.chunks(CHUNK).zip(v.rao.chunks(CHUNK)) {
        let (mut sps, mut cps) = ([0.0; CHUNK], [0.0; CHUNK]);
        for ((c, sp), cp) in cs.iter().zip(&mut sps).zip(&mut cps) {
            let psi = c.omega * t - s * c.k * origin + c.phase;
            (*sp, *cp) = crate::fastmath::sin_cos(psi);
        }
        for (((c, rao), sp), cp) in cs.iter().zip(raos).zip(&sps).zip(&cps) {
            // dψ/dt: the frequency of encounter `ω − s·k·U`.
            let omega = c.omega - s * c.k * v.speed;
            for j in 0..3 {
                let (re, im) = rao[j];
                // Re(a R e^{iψ}) and its time derivatives.
                let x = c.amplitude * (re * cp - im * sp);
                let y = c.amplitude * (re * sp + im * cp);
                m[0][j] += x;
                m[1][j] -= omega * y;
                m[2][j] -= omega * omega * x;
            }
        }
    }
    m
}
