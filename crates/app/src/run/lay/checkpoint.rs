//! A lay's checkpoint: everything a restart needs besides the Models, which are rebuilt from the
//! scene (the whole pipe's mesh from its statics, the window's from its two nodes). It holds the
//! window, its State and the solver's memory, the store of every node's State, the payout (paid-out
//! length, the tensioner's rate and the tension it read), the set of frozen nodes (the window's last
//! node: every node below it is frozen), the records and what each node went through. Numbers
//! that may be NaN (a node not laid yet) are kept as their bits, so that a restart continues bit
//! for bit.

use catena_fe::dynamics::{DynState, SolverMemory};
use catena_seabed::law::SeabedHistory;
use serde::{Deserialize, Serialize};

use super::laid::{LaidNodes, LayRecords};
use crate::error::AppError;
use crate::run::checkpoint::{read_json, same_origin, write_json, VERSION};

/// The bits of each number (NaN kept).
pub(super) fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// The numbers of their bits.
pub(super) fn floats(v: &[u64]) -> Vec<f64> {
    v.iter().map(|&b| f64::from_bits(b)).collect()
}

/// The lay's scalars.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Payout {
    /// The top node's direction up the tower (or the wire's line).
    pub up: [f64; 2],
    /// The top node's distance above the exit, m.
    pub d_top: f64,
    /// The vessel's travel, m.
    pub vessel_x: f64,
    /// Pipe paid out, m.
    pub paid: f64,
    /// The last step's payout rate, m/s.
    pub rate: f64,
    /// The tension at the exit, N, and what the tensioner read.
    pub tension: f64,
    /// What the tensioner read, N.
    pub measured: f64,
    /// The strain the top's elements were placed with.
    pub eps: f64,
    /// Full steps, iterations, cuts, window moves, nodes taken back.
    pub counts: (u64, usize, u32, u64, u64),
    /// A lay-down's times and KP, as bits (`left_tower`, `rested`).
    pub lay_down: (Option<(u64, u64)>, Option<u64>),
}

/// A lay's checkpoint after a converged step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayCheckpoint {
    /// The catena version that wrote it.
    pub catena_version: String,
    /// The scene file (for messages).
    pub scene_file: String,
    /// The hash of the scene's text.
    pub scene_hash: String,
    /// The window `(first, last)`: the nodes above `first` are on the vessel, below `last` frozen.
    pub window: (usize, usize),
    /// The window's State.
    pub state: DynState,
    /// The solver's memory, if any.
    pub solver: Option<SolverMemory>,
    /// Every node's displacements, velocities, accelerations and forces (bits), histories and
    /// friction anchors.
    pub store: (Vec<u64>, Vec<u64>, Vec<u64>, Vec<u64>),
    /// Every node's seabed history.
    pub history: Vec<SeabedHistory>,
    /// Every node's friction anchors (bits) and how many per node.
    pub friction: (Vec<u64>, usize),
    /// The payout and the counters.
    pub payout: Payout,
    /// Each node's position when the window last moved (bits, x then z).
    pub moved_from: Vec<[u64; 2]>,
    /// The records, each series as bits, in the order of [`records_of`].
    pub records: Vec<Vec<u64>>,
    /// Each node: as laid, laid x, largest contact, strength, where its uplift began (bits),
    /// episodes, last mode, landed.
    pub nodes: (Vec<Vec<u64>>, Vec<u32>, Vec<u8>, Vec<bool>),
    /// The installation check's findings: each node's LCC, the largest LCC and DCC, the strain
    /// resistance (bits).
    pub check: Option<CheckFindings>,
    /// The animation's frames so far (numbers that read back to the bit; none in a checkpoint of
    /// a build before frames).
    #[serde(default)]
    pub frames: super::frames::LayFrames,
}

/// The installation check's findings in a checkpoint: each node's LCC, the largest LCC and DCC
/// (value, and when and where), the strain resistance, as bits.
pub type CheckFindings = (Vec<u64>, [u64; 4], [u64; 4], u64);

/// The records' series, in the checkpoint's order.
pub(super) fn records_of(r: &mut LayRecords) -> [&mut Vec<f64>; 9] {
    [
        &mut r.time,
        &mut r.paid_out,
        &mut r.vessel_x,
        &mut r.top_tension,
        &mut r.payout_rate,
        &mut r.touchdown_x,
        &mut r.touchdown_arc,
        &mut r.window_nodes,
        &mut r.sag_moment,
    ]
}

/// Each node's numbers, in the checkpoint's order.
pub(super) fn node_numbers(n: &mut LaidNodes) -> [&mut Vec<f64>; 5] {
    [
        &mut n.as_laid,
        &mut n.laid_x,
        &mut n.max_contact,
        &mut n.strength,
        &mut n.uplift_from,
    ]
}

impl LayCheckpoint {
    /// Writes it as JSON, replacing the file atomically.
    pub fn write(&self, path: &std::path::Path) -> Result<(), AppError> {
        write_json(path, self)
    }

    /// Reads one.
    pub fn read(path: &std::path::Path) -> Result<Self, AppError> {
        read_json(path, "a catena lay checkpoint")
    }

    /// Checks that it continues this lay: the same version and scene, a window within the pipe
    /// and a store of its length.
    pub fn check(&self, file: &str, scene_text: &str, nodes: usize) -> Result<(), AppError> {
        let bad = |what: String| AppError::Checkpoint {
            file: file.to_string(),
            what,
        };
        same_origin(
            (&self.catena_version, &self.scene_hash, &self.scene_file),
            scene_text,
        )
        .map_err(bad)?;
        let (first, last) = self.window;
        if !(first < last && last < nodes) || self.history.len() != nodes {
            return Err(bad(format!(
                "its window {first}..={last} or its {} nodes do not fit this pipe of {nodes} nodes",
                self.history.len()
            )));
        }
        if self.state.history.len() != last - first + 1 {
            return Err(bad("its State does not fit its window".into()));
        }
        Ok(())
    }
}

impl super::Lay {
    /// The checkpoint of the lay after its last converged step.
    pub fn checkpoint(&self) -> LayCheckpoint {
        let s = &self.store;
        let mut records = self.records.clone();
        let mut nodes = self.nodes.clone();
        LayCheckpoint {
            catena_version: VERSION.into(),
            scene_file: self.file.clone(),
            scene_hash: self.scene_hash.clone(),
            window: (self.first, self.last),
            state: self.state.clone(),
            solver: self.ws.solver_memory(),
            store: (bits(&s.u), bits(&s.v), bits(&s.a), bits(&s.f)),
            history: s.history.clone(),
            friction: (bits(&s.friction), s.stride),
            payout: Payout {
                up: self.up,
                d_top: self.d_top,
                vessel_x: self.vessel_x,
                paid: self.paid,
                rate: self.rate,
                tension: self.tension,
                measured: self.measured,
                eps: self.eps,
                counts: (
                    self.full_steps,
                    self.iterations,
                    self.cuts,
                    self.windows,
                    self.taken_back,
                ),
                lay_down: (
                    self.left_tower.map(|(t, kp)| (t.to_bits(), kp.to_bits())),
                    self.rested.map(f64::to_bits),
                ),
            },
            moved_from: self
                .moved_from
                .iter()
                .map(|p| [p[0].to_bits(), p[1].to_bits()])
                .collect(),
            records: records_of(&mut records).iter().map(|v| bits(v)).collect(),
            nodes: (
                node_numbers(&mut nodes).iter().map(|v| bits(v)).collect(),
                nodes.episodes.clone(),
                nodes.last_mode.clone(),
                nodes.landed.clone(),
            ),
            check: self.check.as_ref().map(|c| {
                let four = |t: (f64, f64, f64, f64)| {
                    [t.0.to_bits(), t.1.to_bits(), t.2.to_bits(), t.3.to_bits()]
                };
                (
                    bits(&c.lcc_of_node),
                    four(c.lcc_max),
                    four(c.dcc_max),
                    c.strain_resistance.to_bits(),
                )
            }),
            frames: self.frames.clone(),
        }
    }

    /// Continues from a checkpoint (`file` names it) of this scene (`scene_text`): the store, the
    /// window, its State and the solver's memory, the payout, the records and the nodes; the
    /// window's Model and Workspace rebuilt.
    pub fn restore(
        &mut self,
        cp: &LayCheckpoint,
        file: &str,
        scene_text: &str,
    ) -> Result<(), AppError> {
        cp.check(file, scene_text, self.full.nodes())?;
        let bad = |what: String| AppError::Checkpoint {
            file: file.to_string(),
            what,
        };
        let s = &mut self.store;
        (s.u, s.v, s.a, s.f) = (
            floats(&cp.store.0),
            floats(&cp.store.1),
            floats(&cp.store.2),
            floats(&cp.store.3),
        );
        s.history = cp.history.clone();
        (s.friction, s.stride) = (floats(&cp.friction.0), cp.friction.1);
        let p = &cp.payout;
        (self.up, self.d_top, self.vessel_x, self.paid) = (p.up, p.d_top, p.vessel_x, p.paid);
        (self.rate, self.tension, self.measured, self.eps) = (p.rate, p.tension, p.measured, p.eps);
        (
            self.full_steps,
            self.iterations,
            self.cuts,
            self.windows,
            self.taken_back,
        ) = p.counts;
        self.left_tower = p
            .lay_down
            .0
            .map(|(t, kp)| (f64::from_bits(t), f64::from_bits(kp)));
        self.rested = p.lay_down.1.map(f64::from_bits);
        self.moved_from = cp
            .moved_from
            .iter()
            .map(|b| [f64::from_bits(b[0]), f64::from_bits(b[1])])
            .collect();
        for (dst, src) in records_of(&mut self.records).into_iter().zip(&cp.records) {
            *dst = floats(src);
        }
        for (dst, src) in node_numbers(&mut self.nodes).into_iter().zip(&cp.nodes.0) {
            *dst = floats(src);
        }
        self.nodes.episodes = cp.nodes.1.clone();
        self.nodes.last_mode = cp.nodes.2.clone();
        self.nodes.landed = cp.nodes.3.clone();
        self.frames = cp.frames.clone();
        if let (Some(c), Some((lcc, lmax, dmax, sr))) = (self.check.as_mut(), &cp.check) {
            let four = |b: &[u64; 4]| {
                (
                    f64::from_bits(b[0]),
                    f64::from_bits(b[1]),
                    f64::from_bits(b[2]),
                    f64::from_bits(b[3]),
                )
            };
            c.lcc_of_node = floats(lcc);
            (c.lcc_max, c.dcc_max) = (four(lmax), four(dmax));
            c.strain_resistance = f64::from_bits(*sr);
        }
        // The window's Model and Workspace, its State and the solver's memory.
        let (first, last) = cp.window;
        (self.first, self.last) = (first, last);
        let top_l0 = self.top_rest_length(first);
        self.dm = std::sync::Arc::new(super::window::model(
            &self.full,
            &self.base,
            (first, last, top_l0),
            (self.spec.tower, self.theta, first < self.pipe_end),
            &self.dspec,
        ));
        cp.state.check_fits(&self.dm).map_err(bad)?;
        self.state = cp.state.clone();
        self.ws = catena_fe::dynamics::DynWorkspace::new(&self.dm.line).map_err(|source| {
            AppError::Solver {
                file: self.file.clone(),
                source,
            }
        })?;
        match &cp.solver {
            Some(m) => self.ws.restore_solver_memory(m).map_err(bad)?,
            None => self.ws.forget_factorisation(),
        }
        catena_fe::dynamics::refresh(&self.dm, &self.state, &mut self.ws);
        self.res = catena_fe::assembly::LineResults::new(last - first + 1);
        catena_fe::dynamics::results(&self.dm, &self.state, &self.ws, &mut self.res);
        self.res.tension[0] = self.tension;
        Ok(())
    }
}
