//! `[as_laid]`: a scene whose dynamics start on the seabed a lay left.
//!
//! A lay run writes `laid-seabed.json` ([`LaidSeabed`]): every point of the pipe that came to rest
//! on the seabed, with its position along the route `x` (the lay's frame: the initiation anchor at
//! 0), its as-laid embedment, its seabed history (the trench it dug, the strength it kept) and its
//! friction anchors. A following scene (the pipeline in service, a riser after hook-up) names it:
//!
//! ```toml
//! [as_laid]
//! file = "../lay-out/laid-seabed.json"
//! x_shift = -250.0    # m: this scene's x of a laid point = its laid x + x_shift (default 0)
//! ```
//!
//! At the start of the dynamics each node of the scene whose x (static configuration) lies within
//! the laid points' span takes the history and friction anchors of the laid point nearest to it
//! (the anchors' x shifted): the seabed under the node is the one the lay left. The statics do not
//! see the trench (they are the paper's initial penetration); the dynamics' first seconds settle
//! the line into it, so such a run wants a calm start (a ramp, a transient not counted). A node
//! keeps its own history from then on (one contact state per node).

use serde::{Deserialize, Serialize};

use catena_seabed::law::SeabedHistory;

use super::tables::RiserFile;
use super::{invalid, Resolver};
use crate::error::SceneError;

/// What `laid-seabed.json` says it is.
pub const FORMAT: &str = "catena laid seabed";

/// One point of the laid pipe at rest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaidPoint {
    /// Distance along the pipe from the initiation anchor, m.
    pub kp: f64,
    /// Position along the route (the lay's frame), m.
    pub x: f64,
    /// Height above the mudline of the node at rest (the pipe's axis), m.
    pub z: f64,
    /// The as-laid embedment of the invert (positive down), m.
    pub as_laid: f64,
    /// The seabed history when the lay ended.
    pub history: SeabedHistory,
    /// The friction anchors when the lay ended (the lay's frame; none without friction).
    pub friction: Vec<f64>,
}

/// The seabed a lay left (`laid-seabed.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaidSeabed {
    /// [`FORMAT`].
    pub format: String,
    /// The catena version that wrote it.
    pub catena_version: String,
    /// The lay scene's file.
    pub scene_file: String,
    /// The pipe's contact diameter, m (a following scene's must be the same: the histories are of
    /// this pipe).
    pub contact_od: f64,
    /// The points at rest, by increasing `x`.
    pub points: Vec<LaidPoint>,
}

impl LaidSeabed {
    /// The laid point nearest to the route position `x` (the lay's frame), if `x` lies within the
    /// points' span.
    pub fn nearest(&self, x: f64) -> Option<&LaidPoint> {
        let (first, last) = (self.points.first()?, self.points.last()?);
        if x.is_nan() || x < first.x || x > last.x {
            return None;
        }
        let i = self.points.partition_point(|p| p.x < x);
        let after = self.points.get(i);
        let before = i.checked_sub(1).map(|k| &self.points[k]);
        match (before, after) {
            (Some(b), Some(a)) => Some(if x - b.x <= a.x - x { b } else { a }),
            (b, a) => b.or(a),
        }
    }
}

/// `[as_laid]` of a scene, read and checked.
#[derive(Debug, Clone, PartialEq)]
pub struct AsLaid {
    /// The file as the scene names it.
    pub file: String,
    /// This scene's x of a laid point: its laid x plus this, m.
    pub x_shift: f64,
    /// The laid seabed.
    pub seabed: LaidSeabed,
}

/// Reads `[as_laid]`, if any, and the file it names.
pub fn as_laid(
    file: &str,
    raw: &RiserFile,
    files: &dyn Resolver,
) -> Result<Option<AsLaid>, SceneError> {
    let Some(t) = &raw.as_laid else {
        return Ok(None);
    };
    if raw.lay.is_some() {
        return Err(invalid(file, "as_laid", "a scene without [lay]"));
    }
    if raw.seabed.is_none() || raw.dynamic.is_none() {
        return Err(invalid(
            file,
            "as_laid",
            "a [seabed] and a [dynamic] table as well (the laid seabed acts in the dynamics)",
        ));
    }
    let x_shift = t.x_shift.unwrap_or(0.0);
    if !x_shift.is_finite() {
        return Err(invalid(file, "as_laid.x_shift", "a finite distance in m"));
    }
    let text = files.read(&t.file).map_err(|e| {
        invalid(
            file,
            "as_laid.file",
            format!("a readable laid-seabed.json ({e})"),
        )
    })?;
    let bad = |what: String| {
        invalid(
            file,
            "as_laid.file",
            format!("the laid-seabed.json a lay run writes ({}: {what})", t.file),
        )
    };
    let seabed: LaidSeabed = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
    if seabed.format != FORMAT {
        return Err(bad(format!("its format is {:?}", seabed.format)));
    }
    if seabed.points.is_empty() {
        return Err(bad("no point of the pipe came to rest".into()));
    }
    let finite = seabed
        .points
        .iter()
        .all(|p| [p.kp, p.x, p.z, p.as_laid].iter().all(|v| v.is_finite()));
    let sorted = seabed.points.windows(2).all(|w| w[0].x < w[1].x);
    let od_ok = seabed.contact_od.is_finite() && seabed.contact_od > 0.0;
    if !finite || !sorted || !od_ok {
        return Err(bad(
            "points not finite, not by increasing x, or no contact diameter".into(),
        ));
    }
    Ok(Some(AsLaid {
        file: t.file.clone(),
        x_shift,
        seabed,
    }))
}
