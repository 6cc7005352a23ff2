//! The soil element test: one pipe segment on the seabed, driven along a path of legs under
//! displacement or load control.
//!
//! Each leg from the current value to its target is split into `n = ceil(|Δ| / step)` equal increments
//! and every increment is committed as one converged step.
//!
//! - **Displacement control:** the increment's penetration `z` is evaluated from the committed history
//!   and committed.
//! - **Load control:** the target is the total seabed force per unit length `F = P + F_b` (N/m). Each
//!   increment solves `F(z) = F_target`, evaluating every trial from the committed history, on the side
//!   of `z_prev` that the loading direction implies (down for a larger force, up for a smaller one):
//!   a scan away from `z_prev` in steps growing from `10⁻³` to `1` of `D/Kmax` brackets the first
//!   crossing, and bisection closes it to machine precision. A target that no penetration within
//!   `100·D` reaches is a load the soil cannot carry, and the test stops with an error.

use serde::Serialize;

use crate::law::{Law, Seabed, SeabedHistory, SeabedTrial};
use crate::rq::{Branch, Mode};

/// What a leg controls.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// The penetration `z`, m.
    Displacement,
    /// The total seabed force `P + F_b`, N/m.
    Load,
}

/// Where a leg ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// An absolute value (m or N/m).
    To(f64),
    /// A change from the value at the start of the leg (m or N/m).
    By(f64),
}

/// One leg of the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Leg {
    /// What the leg controls.
    pub control: Control,
    /// Where it ends.
    pub target: Target,
    /// The largest increment, in the unit of the control.
    pub step: f64,
}

/// One committed increment.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Row {
    /// Increment number, 0 for the initial state.
    pub step: usize,
    /// Leg number (0 for the initial state, legs counted from 1).
    pub leg: usize,
    /// Penetration, m.
    pub z: f64,
    /// Soil resistance without buoyancy, N/m.
    #[serde(rename = "P")]
    pub p: f64,
    /// Soil buoyancy, N/m.
    pub buoyancy: f64,
    /// `P + buoyancy`, N/m.
    pub total: f64,
    /// `d(P + buoyancy)/dz`, N/m².
    pub tangent: f64,
    /// The mode after the increment.
    pub mode: Mode,
    /// The formula the force came from.
    pub branch: Branch,
}

/// Why a test could not be run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TestError {
    /// No legs.
    #[error("the path is empty: give at least one waypoint")]
    Empty,
    /// A step that is not positive and finite.
    #[error("leg {leg}: step = {step}: expected a finite step > 0")]
    BadStep {
        /// Leg number (from 1).
        leg: usize,
        /// The step given.
        step: f64,
    },
    /// A target that is not finite.
    #[error("leg {leg}: the target {target} is not a finite number")]
    BadTarget {
        /// Leg number (from 1).
        leg: usize,
        /// The target given.
        target: f64,
    },
    /// A load the soil cannot carry.
    #[error(
        "leg {leg}, increment {increment}: the soil cannot carry a total force of {target:.6} N/m \
         (searched from z = {z_from:.6} m to z = {z_to:.6} m; the force there is {reached:.6} N/m)"
    )]
    LoadNotCarried {
        /// Leg number (from 1).
        leg: usize,
        /// Increment within the leg (from 1).
        increment: usize,
        /// The target total force, N/m.
        target: f64,
        /// The committed penetration the search started from, m.
        z_from: f64,
        /// Where the search gave up, m.
        z_to: f64,
        /// The force at `z_to`, N/m.
        reached: f64,
    },
}

/// The result of a test: the rows, and the index of the row that ends each leg.
#[derive(Debug, Clone, PartialEq)]
pub struct TestResult {
    /// Initial state, then one row per committed increment.
    pub rows: Vec<Row>,
    /// `leg_ends[i]` is the index in `rows` of the last row of leg `i + 1`.
    pub leg_ends: Vec<usize>,
}

fn row(step: usize, leg: usize, z: f64, t: &SeabedTrial) -> Row {
    Row {
        step,
        leg,
        z,
        p: t.resistance,
        buoyancy: t.buoyancy,
        total: t.total(),
        tangent: t.tangent,
        mode: t.next.mode(),
        branch: t.branch,
    }
}

/// The length scale of the force search: `D/Kmax` for Randolph–Quiggin, `D/1000` for linear.
fn search_unit(seabed: &Seabed) -> f64 {
    match &seabed.law {
        Law::RandolphQuiggin(rq) => rq.params().diameter / rq.params().k_max,
        Law::Linear(l) => l.diameter * 1e-3,
    }
}

/// Solves `F(z) = target` from the committed history `h` (see the module docs).
/// On failure returns `(z_to, F(z_to))` where the search gave up.
pub fn solve_load(
    seabed: &Seabed,
    h: &SeabedHistory,
    target: f64,
) -> Result<(f64, SeabedTrial), (f64, f64)> {
    let here = seabed.evaluate(h, h.z_prev(), 0.0, 0.0);
    let f0 = here.total();
    if target == f0 {
        return Ok((h.z_prev(), here));
    }
    let dir = if target > f0 { 1.0 } else { -1.0 };
    let unit = search_unit(seabed);
    let d = seabed.diameter();
    let (z_deep, z_clear) = (h.z_prev().max(0.0) + 100.0 * d, -d);
    let mut step = 1e-3 * unit;
    let mut za = h.z_prev();
    loop {
        let zb = za + dir * step;
        let tb = seabed.evaluate(h, zb, 0.0, 0.0);
        if dir * (tb.total() - target) >= 0.0 {
            // Bisect [za, zb]: the target lies between F(za) and F(zb). The end reached is the
            // bracket's far end (the first side at or beyond the target), as `roots::bisect` keeps
            // it oriented from za.
            let reached = |z: f64| dir * (seabed.evaluate(h, z, 0.0, 0.0).total() - target) >= 0.0;
            let z = if dir > 0.0 {
                crate::roots::bisect(za, zb, reached).1
            } else {
                crate::roots::bisect(zb, za, |z| !reached(z)).0
            };
            return Ok((z, seabed.evaluate(h, z, 0.0, 0.0)));
        }
        if zb > z_deep || zb < z_clear {
            return Err((zb, tb.total()));
        }
        za = zb;
        step = (step * 2.0).min(unit);
    }
}

/// Runs the test from an untouched node at `z = 0`.
pub fn run(seabed: &Seabed, legs: &[Leg]) -> Result<TestResult, TestError> {
    if legs.is_empty() {
        return Err(TestError::Empty);
    }
    for (i, leg) in legs.iter().enumerate() {
        if !(leg.step.is_finite() && leg.step > 0.0) {
            return Err(TestError::BadStep {
                leg: i + 1,
                step: leg.step,
            });
        }
        let t = match leg.target {
            Target::To(t) | Target::By(t) => t,
        };
        if !t.is_finite() {
            return Err(TestError::BadTarget {
                leg: i + 1,
                target: t,
            });
        }
    }
    let mut h = seabed.untouched();
    let first = seabed.evaluate(&h, 0.0, 0.0, 0.0);
    let mut rows = vec![row(0, 0, 0.0, &first)];
    let mut leg_ends = Vec::with_capacity(legs.len());
    let mut force = first.total();
    let mut previous: Option<(Control, f64)> = None;
    for (li, leg) in legs.iter().enumerate() {
        // A leg starts where the previous leg of the same control ended (its waypoint), not at the
        // force a load-controlled solve reached to its tolerance: otherwise a leg whose length is
        // a whole number of steps gets one increment more.
        let start = match (leg.control, previous) {
            (c, Some((pc, end))) if c == pc => end,
            (Control::Displacement, _) => h.z_prev(),
            (Control::Load, _) => force,
        };
        let end = match leg.target {
            Target::To(t) => t,
            Target::By(d) => start + d,
        };
        let delta = end - start;
        let n = (delta.abs() / leg.step).ceil() as usize;
        for k in 1..=n {
            let value = if k == n {
                end
            } else {
                start + delta * (k as f64) / (n as f64)
            };
            let (z, trial) = match leg.control {
                Control::Displacement => (value, seabed.evaluate(&h, value, 0.0, 0.0)),
                Control::Load => solve_load(seabed, &h, value).map_err(|(z_to, reached)| {
                    TestError::LoadNotCarried {
                        leg: li + 1,
                        increment: k,
                        target: value,
                        z_from: h.z_prev(),
                        z_to,
                        reached,
                    }
                })?,
            };
            h = trial.next;
            force = trial.total();
            rows.push(row(rows.len(), li + 1, z, &trial));
        }
        leg_ends.push(rows.len() - 1);
        previous = Some((leg.control, end));
    }
    Ok(TestResult { rows, leg_ends })
}

/// Legs through `waypoints` (absolute targets) under one control, as the `soil-test` case file gives
/// them: the test starts from `z = 0` (zero force), and the first leg runs to `waypoints[0]`.
pub fn legs_through(control: Control, waypoints: &[f64], step: f64) -> Vec<Leg> {
    waypoints
        .iter()
        .map(|&w| Leg {
            control,
            target: Target::To(w),
            step,
        })
        .collect()
}
