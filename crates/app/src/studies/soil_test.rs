//! The soil element test (`catena soil-test`): the seabed law alone, on one pipe segment.
//!
//! The case file has a `[seabed]` table (see [`crate::scene::seabed`]) and a `[test]` table:
//!
//! | key | unit | default | meaning |
//! |---|---|---|---|
//! | `control` | — | required | `"displacement"` (waypoints are `z`, m) or `"load"` (total force `P + F_b`, N/m) |
//! | `waypoints` | m or N/m | required, not empty | targets of successive legs, from `z = 0` |
//! | `step` | m or N/m | required, > 0 | largest increment; a leg is split in `ceil(|Δ|/step)` equal increments |
//! | `cycles` | — | none | cycles appended after the waypoints (below) |
//!
//! Each entry of `[[test.cycles]]` has `count` (≥ 1) and `legs`, a list of
//! `{ control = "displacement" | "load", to = value }` or `{ control = ..., by = change }`, with an
//! optional `step` (default: `test.step` when the control is `test.control`; required otherwise).
//! The cycle's legs are repeated `count` times.
//!
//! The CSV has a header, a row for the initial state and one row per committed increment, with the
//! columns `step, leg, cycle, z, P, buoyancy, total, tangent, mode, branch` (SI units: m, N/m, N/m²).

use std::path::Path;

use catena_seabed::element_test::{self, Control, Leg, Target, TestError, TestResult};
use catena_seabed::law::Seabed;
use serde::Deserialize;

use crate::error::{AppError, SceneError};
use crate::scene::{self, invalid, seabed::SeabedTable};

/// The control mode as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ControlKey {
    /// Penetration control.
    Displacement,
    /// Total force control.
    Load,
}

impl From<ControlKey> for Control {
    fn from(c: ControlKey) -> Self {
        match c {
            ControlKey::Displacement => Control::Displacement,
            ControlKey::Load => Control::Load,
        }
    }
}

/// A leg of a cycle as written.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct LegTable {
    pub control: Option<ControlKey>,
    pub to: Option<f64>,
    pub by: Option<f64>,
    pub step: Option<f64>,
}

/// A `[[test.cycles]]` entry.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct CycleTable {
    pub count: i64,
    pub legs: Vec<LegTable>,
}

/// The `[test]` table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct TestTable {
    pub control: ControlKey,
    pub waypoints: Vec<f64>,
    pub step: f64,
    #[serde(default)]
    pub cycles: Vec<CycleTable>,
}

/// A soil-test case file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SoilTestFile {
    pub seabed: SeabedTable,
    pub test: TestTable,
}

/// A soil-test case, read and checked.
#[derive(Debug, Clone)]
pub struct SoilTestCase {
    /// The case file, as given.
    pub file: String,
    /// The seabed.
    pub seabed: Seabed,
    /// The legs, in order.
    pub legs: Vec<Leg>,
    /// Where each leg comes from in the file (`test.waypoints[2]`), for messages.
    pub origins: Vec<String>,
    /// For each leg, the cycle it belongs to (counted from 1 over all cycle tables), or 0.
    pub cycle_of_leg: Vec<usize>,
}

/// The largest soil element test (increments, and legs) a case may ask for: 10⁷, a few seconds.
pub const MAX_INCREMENTS: f64 = 1e7;

impl SoilTestCase {
    /// Reads and checks a case file.
    pub fn read(path: &Path) -> Result<Self, AppError> {
        let text = scene::read_text(path)?;
        Ok(Self::parse(&path.display().to_string(), &text)?)
    }

    /// Parses and checks case text (`file` is used in messages).
    pub fn parse(file: &str, text: &str) -> Result<Self, SceneError> {
        let raw: SoilTestFile = scene::parse(file, text)?;
        let seabed = raw.seabed.build(file, "seabed", None, None)?;
        if raw.seabed.profile.is_some() {
            return Err(invalid(
                file,
                "seabed.profile",
                "no profile in a soil element test (it shapes a riser's seabed)",
            ));
        }
        if !raw.seabed.zone.is_empty() {
            return Err(invalid(
                file,
                "seabed.zone",
                "no zones in a soil element test (they vary the soil along a riser's route)",
            ));
        }
        if raw.seabed.friction.is_some() {
            return Err(invalid(
                file,
                "seabed.friction",
                "no friction in a soil element test (it acts on a riser line's axial motion)",
            ));
        }
        let t = &raw.test;
        if t.waypoints.is_empty() {
            return Err(invalid(file, "test.waypoints", "at least one waypoint"));
        }
        if let Some(i) = t.waypoints.iter().position(|w| !w.is_finite()) {
            return Err(invalid(
                file,
                format!("test.waypoints[{i}]"),
                "a finite number",
            ));
        }
        if !(t.step.is_finite() && t.step > 0.0) {
            return Err(invalid(
                file,
                "test.step",
                format!("a finite step > 0 (got {})", t.step),
            ));
        }
        check_size(file, t)?;
        let mut legs = element_test::legs_through(t.control.into(), &t.waypoints, t.step);
        let mut origins: Vec<String> = (0..legs.len())
            .map(|i| format!("test.waypoints[{i}]"))
            .collect();
        let mut cycle_of_leg = vec![0; legs.len()];
        let mut cycle_no = 0;
        for (ci, c) in t.cycles.iter().enumerate() {
            let ck = format!("test.cycles[{ci}]");
            if c.count < 1 {
                return Err(invalid(
                    file,
                    format!("{ck}.count"),
                    format!("a count >= 1 (got {})", c.count),
                ));
            }
            if c.legs.is_empty() {
                return Err(invalid(file, format!("{ck}.legs"), "at least one leg"));
            }
            let cycle_legs = cycle_legs(file, t, &ck, c)?;
            for _ in 0..c.count {
                cycle_no += 1;
                for (leg, lk) in &cycle_legs {
                    legs.push(*leg);
                    origins.push(format!("{lk} (cycle {cycle_no})"));
                    cycle_of_leg.push(cycle_no);
                }
            }
        }
        Ok(Self {
            file: file.to_string(),
            seabed,
            legs,
            origins,
            cycle_of_leg,
        })
    }

    /// Runs the test.
    pub fn run(&self) -> Result<TestResult, AppError> {
        element_test::run(&self.seabed, &self.legs).map_err(|e| match e {
            TestError::LoadNotCarried { leg, .. }
            | TestError::BadStep { leg, .. }
            | TestError::BadTarget { leg, .. } => AppError::Run {
                file: self.file.clone(),
                message: format!("key `{}`: {e}", self.origins[leg - 1]),
            },
            TestError::Empty => AppError::Run {
                file: self.file.clone(),
                message: format!("key `test.waypoints`: {e}"),
            },
        })
    }

    /// The penetration at the end of each cycle: `(cycle, z)`.
    pub fn cycle_ends(&self, r: &TestResult) -> Vec<(usize, f64)> {
        let mut out: Vec<(usize, f64)> = Vec::new();
        for (li, &c) in self.cycle_of_leg.iter().enumerate() {
            if c == 0 {
                continue;
            }
            let z = r.rows[r.leg_ends[li]].z;
            match out.last_mut() {
                Some(last) if last.0 == c => last.1 = z,
                _ => out.push((c, z)),
            }
        }
        out
    }

    /// The penetration when the cycles start (the end of the waypoint legs).
    pub fn start_of_cycles(&self, r: &TestResult) -> f64 {
        let n = self.cycle_of_leg.iter().take_while(|&&c| c == 0).count();
        if n == 0 {
            0.0
        } else {
            r.rows[r.leg_ends[n - 1]].z
        }
    }
}

/// The test's size, before any leg is built: increments along the waypoints, then each cycle's
/// legs (a `to` leg bounded by its target's distance from the largest value seen), each at most
/// [`MAX_INCREMENTS`].
fn check_size(file: &str, t: &TestTable) -> Result<(), SceneError> {
    let mut increments: f64 = t
        .waypoints
        .windows(2)
        .map(|w| (w[1] - w[0]).abs() / t.step)
        .sum();
    let mut largest = t.waypoints.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let mut leg_count = t.waypoints.len() as f64;
    let limit = |increments: f64, legs: f64, key: String| -> Result<(), SceneError> {
        if increments > MAX_INCREMENTS || legs > MAX_INCREMENTS {
            Err(invalid(
                file,
                key,
                format!(
                    "a test of at most {MAX_INCREMENTS:e} increments and legs (this one asks for about {:.1e}); check the steps and cycle counts",
                    increments.max(legs)
                ),
            ))
        } else {
            Ok(())
        }
    };
    limit(increments, leg_count, "test.step".into())?;
    for (ci, c) in t.cycles.iter().enumerate() {
        let ck = format!("test.cycles[{ci}]");
        let mut per_cycle = 0.0;
        for l in &c.legs {
            let step = l.step.unwrap_or(t.step);
            let v = l.to.or(l.by).unwrap_or(0.0);
            if step > 0.0 {
                per_cycle += (v.abs() + largest) / step;
            }
            largest = largest.max(v.abs());
        }
        increments += c.count as f64 * per_cycle;
        leg_count += c.count as f64 * c.legs.len() as f64;
        limit(increments, leg_count, format!("{ck}.count"))?;
    }
    Ok(())
}

/// One cycle's legs, each checked, with its key (`test.cycles[i].legs[j]`).
fn cycle_legs(
    file: &str,
    t: &TestTable,
    ck: &str,
    c: &CycleTable,
) -> Result<Vec<(Leg, String)>, SceneError> {
    let mut cycle_legs = Vec::with_capacity(c.legs.len());
    for (li, l) in c.legs.iter().enumerate() {
        let lk = format!("{ck}.legs[{li}]");
        let control = l.control.unwrap_or(t.control);
        let target = match (l.to, l.by) {
            (Some(v), None) => Target::To(v),
            (None, Some(v)) => Target::By(v),
            _ => {
                return Err(invalid(
                    file,
                    lk,
                    "exactly one of `to` (a target) or `by` (a change)",
                ))
            }
        };
        let (Target::To(v) | Target::By(v)) = target;
        if !v.is_finite() {
            return Err(invalid(file, lk, "a finite target"));
        }
        let step = match l.step {
            Some(s) => s,
            None if control == t.control => t.step,
            None => {
                return Err(invalid(
                    file,
                    format!("{lk}.step"),
                    "a step for this leg (its control differs from test.control)",
                ))
            }
        };
        if !(step.is_finite() && step > 0.0) {
            return Err(invalid(
                file,
                format!("{lk}.step"),
                format!("a finite step > 0 (got {step})"),
            ));
        }
        cycle_legs.push((
            Leg {
                control: control.into(),
                target,
                step,
            },
            lk,
        ));
    }
    Ok(cycle_legs)
}
