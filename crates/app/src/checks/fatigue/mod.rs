//! Fatigue, the pure part: rainflow counting ([`rainflow`], ASTM E1049-85, streaming), S-N curves
//! with Miner's damage ([`sn`], DNV-RP-C203), stress recovery ([`stress`]: wall tension, fibre
//! stresses) and what a `[fatigue]` table asks for ([`FatigueSpec`]). The observer that counts during
//! a run is [`crate::run::observers::fatigue`]; the storm-table study is [`crate::studies::fatigue_study`].

pub mod rainflow;
pub mod sn;
pub mod spectral;
pub mod stress;

use sn::SnCurve;
use stress::{Fibre, PipeSection};

/// What a `[fatigue]` table asks for.
#[derive(Debug, Clone, PartialEq)]
pub struct FatigueSpec {
    /// The S-N curve.
    pub curve: SnCurve,
    /// Its name as given (a DNV name, or "user").
    pub curve_name: String,
    /// Stress concentration factor.
    pub scf: f64,
    /// The fibres to count.
    pub fibres: Vec<Fibre>,
    /// The design fatigue factor, reported separately, if given.
    pub design_factor: Option<f64>,
    /// Counting starts at this time, s (the ramp and the settling are discarded).
    pub start: f64,
    /// The pipe.
    pub section: PipeSection,
    /// A line of sections: each node's section, S-N curve and SCF (its line type's, else the
    /// table's); empty: `section`, `curve` and `scf` at every node.
    pub nodes: Vec<(PipeSection, SnCurve, f64)>,
}
