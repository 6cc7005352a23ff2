//! S-N curves: DNV-RP-C203 (the values are unchanged from the 2010 to the 2024 edition for curves D,
//! E and F1), and any bilinear curve a user gives. `log N = log ā − m·log Δσ`, Δσ in MPa.
//!
//! | curve | environment | m1 | log ā1 | m2 | log ā2 | knee at N |
//! |---|---|---|---|---|---|---|
//! | D | air | 3 | 12.164 | 5 | 15.606 | 1e7 |
//! | E | air | 3 | 12.010 | 5 | 15.350 | 1e7 |
//! | F1 | air | 3 | 11.699 | 5 | 14.832 | 1e7 |
//! | D | seawater with cathodic protection | 3 | 11.764 | 5 | 15.606 | 1e6 |
//! | E | seawater with cathodic protection | 3 | 11.610 | 5 | 15.350 | 1e6 |
//! | F1 | seawater with cathodic protection | 3 | 11.299 | 5 | 14.832 | 1e6 |
//! | D / E / F1 | free corrosion | 3 | 11.687 / 11.533 / 11.222 | — | — | — |
//!
//! The upper slope applies for `N ≤` the knee (large ranges), the lower one beyond; no cut-off
//! (fatigue limit) below the lower slope. Thickness correction (DNV-RP-C203 §2.4.3): stresses are
//! multiplied by `(t/25 mm)^k` for `t > 25 mm`, `k` = 0.20 for D and E, 0.25 for F1.

/// A bilinear (or single-slope) S-N curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnCurve {
    /// Slope for large ranges.
    pub m1: f64,
    /// `log10 ā1` (Δσ in MPa).
    pub log_a1: f64,
    /// Slope for small ranges, and its `log10 ā2`, if bilinear.
    pub lower: Option<(f64, f64)>,
    /// The number of cycles at the knee, if bilinear.
    pub knee_cycles: Option<f64>,
    /// Thickness exponent k.
    pub thickness_exponent: f64,
}

/// The names `catena` knows: `dnv-{d,e,f1}-{air,seawater-cp,free-corrosion}`.
pub const NAMES: [&str; 9] = [
    "dnv-d-air",
    "dnv-e-air",
    "dnv-f1-air",
    "dnv-d-seawater-cp",
    "dnv-e-seawater-cp",
    "dnv-f1-seawater-cp",
    "dnv-d-free-corrosion",
    "dnv-e-free-corrosion",
    "dnv-f1-free-corrosion",
];

impl SnCurve {
    /// A DNV-RP-C203 curve by name (see [`NAMES`]).
    pub fn dnv(name: &str) -> Option<Self> {
        let bilinear = |m1, a1, a2, knee, k| SnCurve {
            m1,
            log_a1: a1,
            lower: Some((5.0, a2)),
            knee_cycles: Some(knee),
            thickness_exponent: k,
        };
        let single = |a1, k| SnCurve {
            m1: 3.0,
            log_a1: a1,
            lower: None,
            knee_cycles: None,
            thickness_exponent: k,
        };
        Some(match name {
            "dnv-d-air" => bilinear(3.0, 12.164, 15.606, 1e7, 0.20),
            "dnv-e-air" => bilinear(3.0, 12.010, 15.350, 1e7, 0.20),
            "dnv-f1-air" => bilinear(3.0, 11.699, 14.832, 1e7, 0.25),
            "dnv-d-seawater-cp" => bilinear(3.0, 11.764, 15.606, 1e6, 0.20),
            "dnv-e-seawater-cp" => bilinear(3.0, 11.610, 15.350, 1e6, 0.20),
            "dnv-f1-seawater-cp" => bilinear(3.0, 11.299, 14.832, 1e6, 0.25),
            "dnv-d-free-corrosion" => single(11.687, 0.20),
            "dnv-e-free-corrosion" => single(11.533, 0.20),
            "dnv-f1-free-corrosion" => single(11.222, 0.25),
            _ => return None,
        })
    }

    /// The stress range at the knee, MPa (`None` for a single slope).
    pub fn knee_range(&self) -> Option<f64> {
        self.knee_cycles
            .map(|n| 10f64.powf((self.log_a1 - n.log10()) / self.m1))
    }

    /// Cycles to failure at the stress range `ds` (MPa); infinite for `ds ≤ 0`.
    pub fn cycles(&self, ds: f64) -> f64 {
        if ds <= 0.0 {
            return f64::INFINITY;
        }
        let lg = ds.log10();
        match (self.lower, self.knee_range()) {
            (Some((m2, a2)), Some(knee)) if ds < knee => 10f64.powf(a2 - m2 * lg),
            _ => 10f64.powf(self.log_a1 - self.m1 * lg),
        }
    }

    /// The thickness correction factor `(t/25 mm)^k` for a wall `t` (m); 1 for t ≤ 25 mm.
    pub fn thickness_factor(&self, t: f64) -> f64 {
        if t > 0.025 {
            (t / 0.025).powf(self.thickness_exponent)
        } else {
            1.0
        }
    }
}

/// Miner's damage of counted cycles of stress range (MPa) on a curve, each range multiplied by
/// `factor` (SCF × thickness correction): `Σ n/N(factor·Δσ)`.
pub fn miner(cycles: impl IntoIterator<Item = (f64, f64)>, curve: &SnCurve, factor: f64) -> f64 {
    cycles
        .into_iter()
        .map(|(range, count)| count / curve.cycles(factor * range))
        .sum()
}
