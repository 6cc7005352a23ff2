//! A lay's frames: the whole pipe's shape at a few hundred records, for the animation that follows
//! the touchdown (`catena animate` on a lay's `results.h5`).
//!
//! Every `every`-th record (at most [`MOST`] over the lay's duration) keeps every material node's
//! position (the pipe still on the vessel at the window's top), penetration of the invert (signed: negative above the mudline), seabed force and
//! bending moment (0 for the nodes outside the window: on the vessel or frozen), and the tower's
//! exit. Single precision: a frame is drawn, not computed with (0.1 mm at 1 km).

use serde::{Deserialize, Serialize};

use super::Lay;

/// The most frames a lay keeps.
pub const MOST: usize = 240;

/// The frames of a lay (records × nodes, row-major).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct LayFrames {
    /// A frame every this many records.
    pub every: usize,
    /// Time of each frame, s.
    pub time: Vec<f64>,
    /// The tower's exit `(x, z)` at each frame, m.
    pub exit: Vec<[f64; 2]>,
    /// Node positions, m.
    pub x: Vec<f32>,
    /// Node elevations, m.
    pub z: Vec<f32>,
    /// Penetration of the invert below the mudline, m (positive down; negative above it).
    pub penetration: Vec<f32>,
    /// Seabed force, N/m (0 outside the window).
    pub seabed_force: Vec<f32>,
    /// Bending moment, N·m (0 outside the window).
    pub moment: Vec<f32>,
}

impl LayFrames {
    /// Frames for a lay of `records` records.
    pub fn new(records: usize) -> Self {
        Self {
            every: records.div_ceil(MOST).max(1),
            ..Self::default()
        }
    }

    /// Frames kept.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// Whether none is kept.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }
}

/// The contact diameter of material node `g` of the mesh `full` (its element's, the last node's
/// the last element's).
pub fn contact_od(full: &catena_fe::model::LineModel, g: usize) -> f64 {
    full.elements
        .get(g)
        .unwrap_or_else(|| &full.elements[g - 1])
        .contact_od
}

impl Lay {
    /// Keeps a frame if record `k` is one of them.
    pub(super) fn frame(&mut self, k: usize) {
        if k % self.frames.every != 0 {
            return;
        }
        let top = self.at_window(0);
        let exit = self.exit_point();
        self.frames.time.push(self.state.t);
        self.frames.exit.push(exit);
        for g in 0..self.full.nodes() {
            let inside = (self.first..=self.last).contains(&g);
            // The pipe still on the vessel is drawn at the window's top (the base keeps it along
            // the tower's line, hundreds of metres into the air).
            let p = if inside {
                self.at_window(g - self.first)
            } else if g < self.first {
                top
            } else {
                self.at(g)
            };
            let d = contact_od(&self.full, g);
            let pen = self
                .full
                .penetration(g, p[0], p[1])
                .map_or(0.0, |v| v + 0.5 * (d - self.full.node_od[g]));
            let (force, moment) = if inside {
                let i = g - self.first;
                (self.res.seabed_force[i], self.res.moment[i])
            } else {
                (0.0, 0.0)
            };
            let f = &mut self.frames;
            f.x.push(p[0] as f32);
            f.z.push(p[1] as f32);
            f.penetration.push(pen as f32);
            f.seabed_force.push(force as f32);
            f.moment.push(moment as f32);
        }
    }
}
