//! What a lay gives back: the run ([`LayRun`]), its lay-down ([`LayDown`]) and what the caller sees
//! after each step ([`LayProgress`]).

use catena_fe::model::LineModel;

use super::laid::{LaidNodes, LayRecords, LaySummary};
use crate::run::observe::Stop;
use crate::run::statics::StaticRun;
use crate::scene::lay::LaySpec;
use crate::scene::riser::DynamicSpec;

/// A finished (or stopped) lay.
#[derive(Debug)]
pub struct LayRun {
    /// The statics of the start.
    pub statics: StaticRun,
    /// The lay's table.
    pub spec: LaySpec,
    /// The dynamic table (time step, output interval, sea).
    pub dynamic: DynamicSpec,
    /// The whole pipe's mesh.
    pub full: LineModel,
    /// Nodes on the vessel at the start.
    pub on_vessel: usize,
    /// The tower's angle from the vertical, rad.
    pub tower_angle: f64,
    /// The tensioner's target, N (tension control).
    pub target_tension: Option<f64>,
    /// The records.
    pub records: LayRecords,
    /// Each material node.
    pub nodes: LaidNodes,
    /// The lay's numbers.
    pub summary: LaySummary,
    /// Every node's position `(x, z)` at the end (nodes still on the vessel: along the tower).
    pub positions: Vec<[f64; 2]>,
    /// The window at the end `(first, last)`.
    pub window: (usize, usize),
    /// Converged steps.
    pub steps: u64,
    /// Newton iterations.
    pub iterations: usize,
    /// Step cuts.
    pub cuts: u32,
    /// Times the window moved.
    pub windows: u64,
    /// Times a node was taken back onto the tower (paid in).
    pub taken_back: u64,
    /// Wall time of the dynamics, s.
    pub wall_seconds: f64,
    /// Why the lay ended early, if it did.
    pub stop: Option<Stop>,
    /// The lay-down, if the scene has one.
    pub lay_down: Option<LayDown>,
    /// The installation check, if the scene has a `[design_check]`.
    pub installation: Option<super::install::InstallationCheck>,
}

/// What a lay-down did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayDown {
    /// When the pipe's end left the tower, s.
    pub left_tower: f64,
    /// The touchdown's KP then, m: the steady part ends there.
    pub kp_touchdown: f64,
    /// When the pipe's end came to rest on the seabed (90 % of W'), s; `None`: it did not before
    /// the run's end.
    pub rested: Option<f64>,
    /// The pipe's end's as-laid embedment, m.
    pub end_embedment: f64,
}

impl LayRun {
    /// x of the tower's exit at the start, m.
    pub fn positions_exit_x(&self) -> f64 {
        self.statics.placement.base[0] + self.statics.u[0]
    }
}

/// What the caller sees after each converged step (progress, interruption).
#[derive(Debug, Clone, Copy)]
pub struct LayProgress {
    /// Time, s.
    pub t: f64,
    /// The run's duration, s.
    pub duration: f64,
    /// Pipe paid out, m.
    pub paid_out: f64,
    /// Nodes in the solve.
    pub window_nodes: usize,
}
