//! The dynamics' Workspace: scratch for a step, never saved but for the solver memory a
//! checkpoint carries so that a restart is bit-for-bit.

use crate::assembly::Assembler;
use crate::boundary::{self, Constraint};
use crate::loads::LoadScratch;
use crate::model::LineModel;
use crate::sparse::SolveError;
use crate::wave_sampling::KinematicsGrid;
use crate::waves::{Kinematics, WaveScratch};
use catena_seabed::law::{Law, SeabedHistory, TrialMemo};

use super::cut::{Lane, Scope, Split};
use super::*;
use crate::partner::SharedChores;

/// Scratch for the dynamics (never saved).
#[derive(Debug)]
pub struct DynWorkspace {
    /// The structural assembly (pattern, factorisation, element results).
    pub asm: Assembler,
    /// Lumped mass per node: `[xx, xz, zz, rot]`.
    pub(super) mass: Vec<[f64; 4]>,
    /// The line's own lumped mass per node (no added mass): it does not change with the motion.
    pub(super) structural_mass: Vec<[f64; 4]>,
    /// Non-inertial forces at the trial, 3 per node (after a commit, those of the step before:
    /// the converged ones are exchanged into the State's `f_prev`).
    pub f: Vec<f64>,
    /// What the loads fill per node: the seabed force per length at the trial (resistance,
    /// buoyancy and damping) and each node's tangent ([`crate::loads::LoadScratch`]).
    pub loads: LoadScratch,
    /// Each node's trial seabed history at the last iterate evaluated, when that evaluation kept
    /// them (`histories_kept`): the commit then takes them instead of evaluating them again.
    pub(super) trial_history: Vec<SeabedHistory>,
    pub(super) histories_kept: bool,
    /// What each node's seabed trials keep between them ([`TrialMemo`]: a pure cache).
    pub(super) trial_memo: Vec<TrialMemo>,
    pub(super) g: Vec<f64>,
    pub(super) dq: Vec<f64>,
    pub(super) u: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) a: Vec<f64>,
    /// The State at the start of the step (restored if the step fails).
    pub(super) saved: DynState,
    /// Water kinematics at each node for the step under way (evaluated once per attempt at the
    /// predicted positions; `None` above the surface or without waves).
    pub(super) wave_kin: Vec<Option<Kinematics>>,
    /// The wave trains' per-time scratch (sized on first use).
    pub(super) wave_scratch: WaveScratch,
    /// The wave kinematics samples of the step under way when it needed new ones (committed into
    /// the State with the step), and whether it did.
    pub(super) grid_trial: KinematicsGrid,
    pub(super) grid_new: bool,
    /// The flexjoint's vessel-side rotation for the step under way, rad.
    pub(super) fj_rotation: f64,
    /// The Δt of the Jacobian factorised last (its factorisation is reused for the first
    /// iterations of the next step of the same Δt).
    pub(super) factored_dt: Option<f64>,
    /// How fast corrections with that factorisation contracted the residual, when measured
    /// ([`crate::newton`]: more than one correction per step reuses it while it contracts fast).
    pub(super) reuse_rate: Option<f64>,
    /// The free dofs as runs `(g0, e0, len)`: dofs `g0..g0+len` are equations `e0..e0+len` (the
    /// Newton loop's vector operations run over these slices, without a lookup per dof).
    pub(super) free_runs: Vec<(usize, usize, usize)>,
    /// The prescribed dofs and what prescribes them ([`crate::boundary`]).
    pub(super) constraints: Vec<Constraint>,
    /// The residual of every dof (3 per node) before its free equations are taken.
    pub(super) g_all: Vec<f64>,
    /// The residual's reference norm ([`crate::statics::residual_reference`]) of the Model.
    pub(super) reference: f64,
    /// Where the line is cut in two parts ([`Split`]), when its band is factorised from both ends.
    pub(super) split: Option<Split>,
    /// What this workspace's thread steps: the whole line, or one of the two parts.
    pub(super) scope: Scope,
    /// Where it meets the thread that steps the other part, when there is one ([`Pair`]).
    pub(super) lane: Option<Lane>,
    /// What the two threads of a pair started from this workspace do while they wait
    /// ([`DynWorkspace::set_chores`]).
    pub(super) chores: Option<SharedChores>,
}

impl DynWorkspace {
    /// Makes the threads of each pair started from now on from this workspace ([`Pair::start`])
    /// do `chores` while they wait (at their meetings, and between steps): each its own side's,
    /// side 0 the calling thread's. Nothing on one thread.
    pub fn set_chores(&mut self, chores: Option<SharedChores>) {
        self.chores = chores;
    }

    /// Builds the workspace (pattern and symbolic factorisation once).
    pub fn new(line: &LineModel) -> Result<Self, SolveError> {
        let n = line.nodes();
        let untouched = line
            .seabed
            .as_ref()
            .map_or(SeabedHistory::Linear(Default::default()), |s| {
                s.seabed.untouched()
            });
        let mut asm = Assembler::new(line)?;
        // The line's two parts (issue 48): the runs are cut where a part's own nodes end and
        // where its neighbour's first node (which it reads) ends.
        let k = asm.split_at_node(line);
        let cuts = k.map_or([usize::MAX; 3], |k| [3 * k, 3 * (k + 1), 3 * (k + 2)]);
        let mut free_runs: Vec<(usize, usize, usize)> = Vec::new();
        for (g, e) in line.equation.iter().enumerate() {
            match (e, free_runs.last_mut()) {
                (Some(e), Some((g0, e0, len)))
                    if *g0 + *len == g && *e0 + *len == *e && !cuts.contains(&g) =>
                {
                    *len += 1
                }
                (Some(e), _) => free_runs.push((g, *e, 1)),
                (None, _) => {}
            }
        }
        let split = k.map(|k| Split {
            k,
            runs: free_runs.partition_point(|r| r.0 < 3 * (k + 1)),
        });
        Ok(Self {
            scope: Scope::whole(line, free_runs.len()),
            lane: None,
            chores: None,
            split,
            reference: crate::statics::residual_reference(line),
            free_runs,
            constraints: boundary::constraints(line),
            g_all: vec![0.0; 3 * n],
            asm,
            mass: vec![[0.0; 4]; n],
            structural_mass: structural_mass(line),
            f: vec![0.0; 3 * n],
            loads: LoadScratch::new(n),
            trial_history: vec![untouched; n],
            histories_kept: false,
            trial_memo: match line.seabed.as_ref().map(|s| &s.seabed.law) {
                Some(Law::RandolphQuiggin(_)) => vec![TrialMemo::default(); n],
                _ => Vec::new(),
            },
            g: vec![0.0; line.n_eq],
            dq: vec![0.0; line.n_eq],
            u: vec![0.0; 3 * n],
            v: vec![0.0; 3 * n],
            a: vec![0.0; 3 * n],
            saved: DynState {
                t: 0.0,
                step: 0,
                u: vec![0.0; 3 * n],
                v: vec![0.0; 3 * n],
                a: vec![0.0; 3 * n],
                f_prev: vec![0.0; 3 * n],
                history: vec![untouched; n],
                wave_grid: None,
                friction_anchor: vec![0.0; friction_anchor_len(line)],
            },
            factored_dt: None,
            reuse_rate: None,
            wave_kin: vec![None; n],
            wave_scratch: WaveScratch::default(),
            grid_trial: KinematicsGrid::default(),
            grid_new: false,
            fj_rotation: 0.0,
        })
    }

    /// Takes the top element's new rest length from the Model
    /// ([`LineModel::set_top_rest_length`]): its stiffness and the two top nodes' own lumped mass,
    /// as [`DynWorkspace::new`] would have them (no allocation).
    pub fn top_rest_length_changed(&mut self, line: &LineModel) {
        self.asm.element_changed(line, 0);
        for i in 0..2.min(line.nodes()) {
            let mut m = [0.0; 4];
            for el in line.elements[i.saturating_sub(1)..(i + 1).min(line.elements.len())].iter() {
                let half = 0.5 * el.mass * el.l0;
                m[0] += half;
                m[2] += half;
                m[3] += half * el.od * el.od / 8.0;
            }
            for a in line.attachments.iter().filter(|a| a.node == i) {
                m[0] += a.mass;
                m[2] += a.mass;
            }
            self.structural_mass[i] = m;
        }
        self.reference = crate::statics::residual_reference(line);
    }

    /// Drops the factorisation kept for reuse: the next step starts with a full Newton iteration.
    pub fn forget_factorisation(&mut self) {
        self.factored_dt = None;
        self.reuse_rate = None;
    }

    /// The factorisation kept for reuse, as data (see [`SolverMemory`]).
    pub fn solver_memory(&self) -> Option<SolverMemory> {
        self.factored_dt.map(|dt| SolverMemory {
            dt,
            rate: self.reuse_rate,
            values: self.asm.factored_values().to_vec(),
        })
    }

    /// Restores a [`SolverMemory`]: refactorises its values, so the next step reuses exactly the
    /// factorisation the run that exported it would have reused.
    pub fn restore_solver_memory(&mut self, m: &SolverMemory) -> Result<(), String> {
        if m.values.len() != self.asm.pattern_len() {
            return Err(format!(
                "solver memory has {} values, expected {} (the tangent's pattern)",
                m.values.len(),
                self.asm.pattern_len()
            ));
        }
        if !(m.dt.is_finite() && m.dt > 0.0) || m.values.iter().any(|x| !x.is_finite()) {
            return Err("solver memory holds a non-finite value".into());
        }
        self.asm
            .refactor_from(&m.values)
            .map_err(|e| e.to_string())?;
        self.factored_dt = Some(m.dt);
        self.reuse_rate = m.rate;
        Ok(())
    }
}

/// The friction anchors' entries: one per node (x) when the seabed has friction, two (x, z) on a
/// profile, none without friction.
pub(super) fn friction_anchor_len(line: &LineModel) -> usize {
    match line.seabed.as_ref().and_then(|s| s.friction) {
        Some(_) if line.mudline_profile.is_empty() => line.nodes(),
        Some(_) => 2 * line.nodes(),
        None => 0,
    }
}
