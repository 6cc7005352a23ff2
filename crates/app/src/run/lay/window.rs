//! The part of the pipe a lay solves: its window of material nodes, and the State carried from one
//! window to the next.
//!
//! The whole pipe is one material mesh (`full`, node 0 the pipe's last end on the vessel, arc
//! length from there), with one base configuration (`Placement`: the tower's nodes along the
//! tower, the rest where the statics' seed put them). A window is the nodes `first..=last`: the
//! top node `first` prescribed at the tower's exit itself (clamped at the tower's angle, or on the
//! tower's rotational spring), every node below it free, and `last` held where it lies (a frozen
//! node). The clamp is at the exit, not at a node: the top element runs from the exit to node
//! `first + 1`, its rest length the pipe between them, growing with the payout between half an
//! element and one and a half; node `first` stands for the exit while its own material is within
//! half an element of it, and leaves the tower when it is half an element below it, placed on the
//! top element's cubic (`Lay::release`). So each node leaves the tower where the pipe already
//! is, and the tower's moment stays at the exit: a tower off the pipe's departure angle lays the
//! same at 1 m elements as at 0.5 m (`validation/lay.md`).
//! Nodes above the window wait on the vessel and nodes below it are frozen: neither is in the
//! solve, so a step costs what the window costs, whatever the length already laid.
//!
//! The State of the nodes outside the window is kept in [`Store`] (positions, velocities,
//! accelerations, forces, seabed histories, friction anchors): a window's State is a slice of it,
//! and goes back into it when the window moves. Moving a window changes the equations, so its
//! workspace (and its reused factorisation) is made anew; the forces `F_n` of its end nodes and of
//! the node that has just left the tower are evaluated at the State ([`dynamics::refresh`]), the
//! others' are carried.

use catena_fe::assembly::Placement;
use catena_fe::dynamics::{self, DynState, DynWorkspace, DynamicModel};
use catena_fe::model::{FlexJoint, LineModel, Support};
use catena_fe::wave_sampling::KinematicsGrid;
use catena_seabed::law::SeabedHistory;

use crate::scene::lay::Tower;
use crate::scene::riser::DynamicSpec;

/// The State of every material node, for the nodes outside the window.
#[derive(Debug, Clone, Default)]
pub struct Store {
    /// Displacements from the base, 3 per node.
    pub u: Vec<f64>,
    /// Velocities.
    pub v: Vec<f64>,
    /// Accelerations.
    pub a: Vec<f64>,
    /// Non-inertial forces at the last converged step.
    pub f: Vec<f64>,
    /// Seabed histories.
    pub history: Vec<SeabedHistory>,
    /// Friction anchors, `stride` per node (0 without friction).
    pub friction: Vec<f64>,
    /// Friction anchor entries per node.
    pub stride: usize,
}

/// The Model of the window `first..=last` of the material mesh, its top element `top_l0` long
/// (from the tower's exit to node `first + 1`); `over_sheave`: its top node is the lay-down's
/// wire, which runs over a sheave (pinned: it takes no moment).
pub fn model(
    full: &LineModel,
    base: &Placement,
    (first, last, top_l0): (usize, usize, f64),
    (tower, tower_theta, over_sheave): (Tower, f64, bool),
    spec: &DynamicSpec,
) -> DynamicModel {
    let (support, flexjoint) = match tower {
        _ if over_sheave => (Support::Pinned, None),
        Tower::Clamped => (Support::Fixed, None),
        Tower::Hinged(stiffness) => (
            Support::Pinned,
            Some(FlexJoint {
                node: 0,
                stiffness,
                neutral: tower_theta,
            }),
        ),
    };
    let mut line = full.window(first, last, support, flexjoint);
    if top_l0 != line.elements[0].l0 {
        line.set_top_rest_length(top_l0);
    }
    DynamicModel {
        line,
        placement: Placement {
            base: base.base[3 * first..3 * (last + 1)].to_vec(),
            chords: base.chords[first..last].to_vec(),
        },
        environment: spec.environment.clone(),
        motion: None,
        vessel: spec.vessel.clone(),
        structural_damping: spec.structural_damping,
        settings: spec.settings,
    }
}

impl Store {
    /// Writes a window's State (nodes from `first`) into the store.
    pub fn keep(&mut self, first: usize, state: &DynState) {
        let n = state.history.len();
        let r = 3 * first..3 * (first + n);
        self.u[r.clone()].copy_from_slice(&state.u);
        self.v[r.clone()].copy_from_slice(&state.v);
        self.a[r.clone()].copy_from_slice(&state.a);
        self.f[r].copy_from_slice(&state.f_prev);
        self.history[first..first + n].clone_from_slice(&state.history);
        let s = self.stride;
        self.friction[s * first..s * (first + n)].copy_from_slice(&state.friction_anchor);
    }

    /// The State of the window `first..=last` from the store, at `t` after `step` steps, with the
    /// wave kinematics samples of the nodes that were in the window `old` (`None` elsewhere).
    pub fn window_state(
        &self,
        (first, last): (usize, usize),
        (t, step): (f64, u64),
        old: Option<(usize, &KinematicsGrid)>,
    ) -> DynState {
        let r = 3 * first..3 * (last + 1);
        let s = self.stride;
        let wave_grid = old.map(|(old_first, g)| {
            let pick = |samples: &Vec<Option<_>>| {
                (first..=last)
                    .map(|k| {
                        k.checked_sub(old_first)
                            .and_then(|i| samples.get(i).copied().flatten())
                    })
                    .collect()
            };
            KinematicsGrid {
                index: g.index,
                samples: [pick(&g.samples[0]), pick(&g.samples[1])],
            }
        });
        DynState {
            t,
            step,
            u: self.u[r.clone()].to_vec(),
            v: self.v[r.clone()].to_vec(),
            a: self.a[r.clone()].to_vec(),
            f_prev: self.f[r].to_vec(),
            history: self.history[first..=last].to_vec(),
            wave_grid,
            friction_anchor: self.friction[s * first..s * (last + 1)].to_vec(),
        }
    }
}

/// Brings the window's start `u` (its nodes' displacements from the statics of the scene's line)
/// to the window Model's own static equilibrium: the scene's statics hold the tower's moment at the
/// exit node, the window one element above it on the tower. Returns at once (changing nothing)
/// where the statics' state is already in equilibrium, as at the pipe's departure angle.
pub fn settle(
    dm: &DynamicModel,
    scene: &crate::scene::riser::RiserScene,
    u: &mut [f64],
) -> Result<(), catena_fe::statics::StaticError> {
    use catena_fe::statics::{self, StaticOptions, StaticWorkspace};
    let mut ws = StaticWorkspace::new(&dm.line).map_err(statics::StaticError::from)?;
    let opts = StaticOptions {
        tol: scene.statics.tolerance,
        max_iter: scene.statics.max_iterations,
        ..StaticOptions::default()
    };
    statics::solve_in(
        &dm.line,
        scene.hydro.as_ref(),
        &dm.placement,
        u,
        &mut ws,
        &opts,
    )?;
    Ok(())
}

/// A fresh workspace for the window, with the forces `F_n` of the nodes `fresh` (window-local)
/// evaluated at the State (the others' are carried).
pub fn workspace(
    dm: &DynamicModel,
    state: &mut DynState,
    fresh: &[usize],
) -> Result<DynWorkspace, catena_fe::sparse::SolveError> {
    let mut ws = DynWorkspace::new(&dm.line)?;
    dynamics::refresh(dm, state, &mut ws);
    for &i in fresh {
        state.f_prev[3 * i..3 * i + 3].copy_from_slice(&ws.f[3 * i..3 * i + 3]);
    }
    Ok(ws)
}
