//! The recorded steps: what each recorded step holds (the series and the per-node fields, with
//! `results.h5`'s names) and [`Records`], an observer that keeps them in memory (what the Python
//! package returns). The HDF5 recorder (`catena-io`) writes the same series and fields.

use catena_fe::assembly::LineResults;

use crate::error::AppError;
use crate::run::observe::{Control, Observer, RunContext, StepView};

/// The series of a recorded step, `(name, units)`, in the order of [`record_series`]: the names of
/// `results.h5`'s `/dynamic` datasets and of the Python package's arrays.
pub const RECORD_SERIES: [(&str, &str); 5] = [
    ("time", "s"),
    ("top_x", "m"),
    ("top_z", "m"),
    ("top_tension", "N"),
    // The touchdown point's arc length from the top, interpolated where the invert's penetration is
    // zero (`catena_fe::statics::touchdown_arc`); the anchor's arc length when no node touches down
    // after a clear one.
    ("touchdown_arc", "m"),
];

/// The fields of a recorded step (one value per node), `(name, units)`, in the order of
/// [`record_fields`].
pub const RECORD_FIELDS: [(&str, &str); 6] = [
    ("x", "m"),
    ("z", "m"),
    ("effective_tension", "N"),
    ("bending_moment", "N*m"),
    ("penetration", "m"),
    ("seabed_force", "N/m"),
];

/// The values of [`RECORD_SERIES`] at time `t` for the nodal results `r` on the arc lengths `arc`.
pub fn record_series(t: f64, arc: &[f64], r: &LineResults) -> [f64; 5] {
    let tdp = catena_fe::statics::touchdown_arc(arc, &r.penetration).unwrap_or(arc[arc.len() - 1]);
    [t, r.x[0], r.z[0], r.tension[0], tdp]
}

/// The values of [`RECORD_FIELDS`] for the nodal results `r`.
pub fn record_fields(r: &LineResults) -> [&[f64]; 6] {
    [
        &r.x,
        &r.z,
        &r.tension,
        &r.moment,
        &r.penetration,
        &r.seabed_force,
    ]
}

/// The recorded steps (every `output_interval`, and the initial state) kept in memory, with the
/// names and units of `results.h5`'s `/dynamic` group: what a binding returns instead of a file.
/// Series, one value per record: `time` (s), `top_x`, `top_z` (m), `top_tension` (N) and
/// `touchdown_arc` (m, the anchor's arc length when nothing touches down after a clear node).
/// Fields, one row of one value per node (in the order of `arc`) per record: `x`, `z` (m),
/// `effective_tension` (N), `bending_moment` (N·m, negative = sag), `penetration` (m, positive
/// down) and `seabed_force` (N/m). Memory grows with the records: `8·(5 + 6·nodes)` bytes each.
#[derive(Debug, Clone, Default)]
pub struct Records {
    /// Arc length of each node from the top, m.
    pub arc: Vec<f64>,
    /// The series, by name, in the order above.
    pub series: Vec<(&'static str, Vec<f64>)>,
    /// The fields, by name, each `records × nodes` values, row after row.
    pub fields: Vec<(&'static str, Vec<f64>)>,
}

impl Records {
    /// Empty records.
    pub fn new() -> Self {
        Self {
            arc: Vec::new(),
            series: RECORD_SERIES.iter().map(|n| (n.0, Vec::new())).collect(),
            fields: RECORD_FIELDS.iter().map(|n| (n.0, Vec::new())).collect(),
        }
    }

    /// The records held.
    pub fn len(&self) -> usize {
        self.series.first().map_or(0, |s| s.1.len())
    }

    /// Whether no record is held.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl Observer for Records {
    fn name(&self) -> &'static str {
        "records"
    }

    fn step(&mut self, ctx: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        if !s.record {
            return Ok(Control::Continue);
        }
        if self.series.is_empty() {
            *self = Self::new();
        }
        let arc = &ctx.model.line.arc;
        if self.arc.is_empty() {
            self.arc = arc.clone();
        }
        for ((_, v), x) in self
            .series
            .iter_mut()
            .zip(record_series(s.t, arc, s.results))
        {
            v.push(x);
        }
        for ((_, v), src) in self.fields.iter_mut().zip(record_fields(s.results)) {
            v.extend_from_slice(src);
        }
        Ok(Control::Continue)
    }
}
