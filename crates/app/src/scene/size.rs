//! A run's size, estimated from its tables before anything is built, and checked against `[limits]`.

use super::dynamic::DEFAULT_MAX_RECORDS;
use super::invalid;
use super::tables::RiserFile;
use crate::error::SceneError;

/// Bytes recorded per node per record in `/dynamic` (x, z, rotation, effective and wall tension,
/// moment, curvature, penetration, seabed force as f64 and the seabed mode).
pub const RECORD_BYTES_PER_NODE: f64 = 9.0 * 8.0 + 1.0;

/// What a scene would run: its size, estimated before anything is built.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSize {
    /// Elements of the mesh.
    pub elements: usize,
    /// Time steps of the dynamics (0 for a static scene).
    pub steps: u64,
    /// Records written to `results.h5`.
    pub records: u64,
    /// Bytes of those records (uncompressed).
    pub output_bytes: f64,
}

/// A scene's size from its tables alone, checked against `[limits]` (the error names the key to
/// change and the limit to raise).
pub fn run_size(file: &str, raw: &RiserFile) -> Result<RunSize, SceneError> {
    let lim = raw.limits.unwrap_or_default();
    let mut elements = 0.0f64;
    let mut from = 0.0;
    for m in &raw.mesh {
        if m.element_length > 0.0 && m.to > from {
            elements += ((m.to - from) / m.element_length).ceil();
            from = m.to;
        }
    }
    if elements > lim.max_elements {
        return Err(invalid(
            file,
            "mesh",
            format!(
                "at most {:e} elements (this mesh has {elements:e}); check each mesh[i].element_length, or raise limits.max_elements",
                lim.max_elements
            ),
        ));
    }
    let (mut steps, mut records) = (0.0f64, 0.0f64);
    if let Some(d) = &raw.dynamic {
        if d.time_step > 0.0 && d.duration > 0.0 {
            steps = (d.duration / d.time_step).ceil();
            if steps > lim.max_steps {
                return Err(invalid(
                    file,
                    "dynamic.duration",
                    format!(
                        "at most {:e} time steps (duration / time_step = {steps:e}); check dynamic.duration and dynamic.time_step, or raise limits.max_steps",
                        lim.max_steps
                    ),
                ));
            }
            let out = d
                .output_interval
                .unwrap_or(d.time_step * (steps / DEFAULT_MAX_RECORDS).ceil().max(1.0));
            if out > 0.0 {
                records = (d.duration / out.max(d.time_step)).floor() + 1.0;
            }
        }
    }
    let output_bytes = records * (elements + 1.0) * RECORD_BYTES_PER_NODE;
    if output_bytes > lim.max_output_bytes {
        return Err(invalid(
            file,
            "dynamic.output_interval",
            format!(
                "records of at most {:.1} GB ({records:e} records of {} nodes would be {:.1} GB); lengthen dynamic.output_interval, or raise limits.max_output_bytes",
                lim.max_output_bytes / 1e9,
                elements + 1.0,
                output_bytes / 1e9
            ),
        ));
    }
    Ok(RunSize {
        elements: elements as usize,
        steps: steps as u64,
        records: records as u64,
        output_bytes,
    })
}
