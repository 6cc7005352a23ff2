//! Implicit dynamics: HHT-α (Hilber–Hughes–Taylor) and Newmark time integration with Newton
//! iterations in each step, lumped inertia with normal added mass, Morison drag, the hysteretic seabed
//! committed once per converged step, prescribed top-end motion, and automatic step cutting.
//!
//! The pieces live apart: the scheme (HHT-α/Newmark coefficients, predictors, the Newmark relations
//! and the residual `G = M a + (1 + α) F − α F_n`, with its conventions) in [`crate::integrator`];
//! the forces `F` — the structure ([`crate::assembly`]) and the one list of loads that the statics
//! share ([`crate::loads`]: seabed, drag and wave inertia, structural damping) — and the prescribed
//! dofs ([`crate::boundary`]); Newton's bookkeeping (what each iteration evaluates, the reuse of
//! the last factorisation, backtracking, the divergence and convergence tests) in
//! [`crate::newton`]. This module keeps the stepping: one attempt's loop (forces, residual,
//! solve), the commit, predictor retries and step cuts. `F` collects every non-inertial force as "internal
//! minus external"; `F_n` is kept in the State, so the step is exactly reproducible after a
//! restart. The Newton Jacobian is `M/(βΔt²) + (1 + α)(K + γ/(βΔt)·C)`.
//! The first Newton iteration of a step reuses the Jacobian factorised last (same Δt), and later
//! ones go on reusing it while its measured contraction rate lets the next correction converge;
//! otherwise Newton factorises the tangent. Every answer meets one tolerance ([`crate::newton`]).
//!
//! **Predictor.** A step starts from the constant-acceleration predictor `u_n + Δt v_n + Δt²/2 a_n`.
//! If Newton diverges from it, the same step is tried once more from the constant-velocity predictor
//! `u_n + Δt v_n` (a *predictor retry*) before the step is cut. After a step in the top-end velocity
//! the first free node next to the top rings at `ωΔt ≫ 1` (very short, stiff elements), and its
//! acceleration, carried into the constant-acceleration predictor, can fold the first elements;
//! the velocity is far smaller at such frequencies, so the second predictor is a physical shape.
//! (Watchet with 0.0625 m elements: 7 cuts before, 0 cuts and 7 retries now.)
//!
//! **Backtracking.** A Newton correction after which the residual norm is larger than before it is
//! halved (the iterate moved back halfway), up to [`MAX_BACKTRACKS`] times, before the next
//! correction is computed from wherever that leaves it. Steps whose residual falls at every
//! iteration (nearly all of them: the pinned regression numbers do not move) are unchanged. It is
//! for the seabed at lift-off: in uplift at a small penetration the Randolph–Quiggin force *rises*
//! as the pipe lifts (its suction bound `−f_suc·Pu(z)`, with `Pu ∝ z^b`, climbs to zero with an
//! infinite slope at the mudline) and then falls to zero across the lift-off band, a snap-through
//! on which full Newton steps cycled (period 3, worst node at the touchdown point) until the step
//! was cut. Measured (`validation/hard-cases.md`): stiff clay 66 → 43 cuts in 100 s, sticky soil
//! 2022 → 263 cuts and 46.5 → 12.0 iterations a step.
//!
//! **Prescribed motion.** The top node's position, velocity and acceleration at `t_{n+1}` are those of
//! the motion at `t_{n+1}`, exactly: only forces are α-weighted. (Evaluating the prescribed node at
//! `t_{n+1+α}`, as some codes do, lags it by `(1 − α)·Δt·v` and produces a spurious axial force in the
//! top element that halves when `Δt` halves.)
//!
//! **Mass** is lumped: each node carries half of each adjacent element's structural mass `m·L0/2` in
//! x and z, the normal added mass `Ca·ρw·πD²/4` per length as the 2×2 block `m_a·L·(I − t tᵀ)` with the
//! tangent `t` at the start of the step, and a small rotary inertia `m·L·D²/8` (a thin tube's).
//!
//! **Drag (Morison)** on the velocity relative to the current `U(z)`, split along the tangent `t`:
//! `f = ½ρ Cd_n D |v_n| v_n + ½ρ Cd_a πD |v_t| v_t t` per unit (unstretched) length, lumped at nodes
//! over their tributary lengths; its velocity derivative enters `C`, not its orientation's.
//!
//! **Seabed.** Each node's trial is evaluated from its committed history, its penetration rate and
//! Δt (pure); the histories are replaced by the trials' `next` only when the step converges. The
//! residual pass after a fresh correction, which nearly always converges, writes each node's trial
//! history into the workspace, and the commit takes them if that pass converged; otherwise it
//! evaluates the trials again at the converged iterate (the same pure call, the same values). A
//! failed attempt leaves the State untouched, and the step is retried with `Δt/2` (up to `max_cuts`
//! times). A step that fails after every cut leaves the State exactly as it was before the step
//! (step-level revert).
//!
//! **Model, State, Workspace.** [`DynamicModel`] holds what the scene fixes (the line, its placement,
//! the environment, the top motion and the solver settings) and is immutable; [`DynState`] is what a
//! restart needs; [`DynWorkspace`] is scratch. The first-iteration reuse of the last factorisation is
//! the one piece of the Workspace that changes converged bits; [`DynWorkspace::solver_memory`]
//! exports it (the tangent values last factorised, and their Δt) so that a checkpoint can carry it and
//! a restart continue bit for bit.
//!
//! **Convergence.** `‖G‖ ≤ tol·‖F_weight‖ + 10·ε·√(Σₑ (EAₑ(1 + U/L0ₑ))²)` on the free equations, U the
//! largest displacement from the base (the second term is the rounding floor of the axial forces), or a relative residual below 1e-6 with a correction below
//! 1e-10 m (machine-precision stagnation).

mod carry;
mod cut;
mod drive;
mod mass;
mod pair;
mod water;
mod workspace;

use carry::at_rest;
pub use carry::{carried_state, Carry};
pub use drive::Drive;
use mass::{add_mass_tangent, lump_mass, structural_mass};
pub use pair::{Pair, Samples};
use water::wave_kinematics;
use workspace::friction_anchor_len;
pub use workspace::DynWorkspace;

use catena_seabed::law::{SeabedHistory, TrialMemo};
use serde::{Deserialize, Serialize};

use crate::assembly::{LineResults, Placement};
use crate::boundary::{self};
use crate::environment::Environment;
use crate::integrator::StepCoefficients;
use crate::loads::{self, penetration, Iterate, LoadModel, SeabedPass, TangentScale};
use crate::model::LineModel;
use crate::motion::{Kinematics as TopKinematics, TopMotion};
pub use crate::newton::{max_abs, residual_floor, MAX_BACKTRACKS};
use crate::newton::{Accepted, Newton, Pass, Verdict};
use crate::sparse::SolveError;
use crate::vessel::Vessel;
use crate::wave_sampling::KinematicsGrid;

pub use crate::integrator::{sdof_free_vibration, Scheme};

/// Solver settings of a dynamic run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicSettings {
    /// The scheme.
    pub scheme: Scheme,
    /// Relative residual tolerance (on `‖F_weight‖`).
    pub tol: f64,
    /// Newton iterations per attempt.
    pub max_iter: usize,
    /// Step cuts (halvings) allowed before giving up.
    pub max_cuts: u32,
}

/// The Model of a dynamic run: everything the scene and the statics fix, immutable.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicModel {
    /// The line (mesh, sections, supports, seabed, flexjoint).
    pub line: LineModel,
    /// The base configuration the displacements are measured from.
    pub placement: Placement,
    /// The environment (hydrodynamics).
    pub environment: Environment,
    /// The top end's prescribed motion, if any.
    pub motion: Option<TopMotion>,
    /// The vessel carrying the top end, moved by the waves, if any (added to `motion`).
    pub vessel: Option<Vessel>,
    /// Stiffness-proportional structural damping `β` (s), if the scene has it: each element's
    /// damping is `β` times its material stiffness on its deformation rates
    /// ([`crate::beam::structural_damping`]).
    pub structural_damping: Option<f64>,
    /// The solver settings.
    pub settings: DynamicSettings,
}

pub use crate::motion::TopState;

impl DynamicModel {
    /// The loads of the dynamics ([`crate::loads`]): the seabed, the hydrodynamics and the
    /// structural damping the scene has.
    pub fn loads(&self) -> LoadModel<'_> {
        LoadModel {
            line: &self.line,
            placement: &self.placement,
            hydro: self.environment.hydro.as_ref(),
            structural_damping: self.structural_damping,
        }
    }

    /// The top end's prescribed state at `t`: the prescribed motion plus the vessel's motion at the
    /// hang-off, or `None` when the top does not move.
    pub fn top_at(&self, t: f64) -> Option<TopState> {
        if self.motion.is_none() && self.vessel.is_none() {
            return None;
        }
        let mut s = TopState::default();
        if let Some(m) = &self.motion {
            let (d, v, a): TopKinematics = m.at(t);
            (s.d, s.v, s.a) = (d, v, a);
        }
        if let (Some(vessel), Some(waves)) = (&self.vessel, &self.environment.waves) {
            let vm = vessel.motion(waves, t);
            for k in 0..2 {
                s.d[k] += vm.displacement[k];
                s.v[k] += vm.velocity[k];
                s.a[k] += vm.acceleration[k];
            }
            s.pitch = vm.motions[2];
            s.pitch_rates = vm.pitch_rates;
        }
        Some(s)
    }
}

/// Everything a restart needs.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct DynState {
    /// Time, s.
    pub t: f64,
    /// Converged steps so far.
    pub step: u64,
    /// Displacements from the placement's base, 3 per node.
    pub u: Vec<f64>,
    /// Velocities.
    pub v: Vec<f64>,
    /// Accelerations.
    pub a: Vec<f64>,
    /// The non-inertial forces `F` at the last converged state (for HHT's force averaging).
    pub f_prev: Vec<f64>,
    /// Each node's committed seabed history.
    pub history: Vec<SeabedHistory>,
    /// The wave kinematics samples around the last step's end, when the waves are sampled on a
    /// time grid ([`crate::wave_sampling`]); `None` otherwise.
    #[serde(default)]
    pub wave_grid: Option<KinematicsGrid>,
    /// Each node's axial friction anchor, m, when the seabed has friction ([`crate::loads`]): the
    /// x at which its friction spring is unstretched, or on a sloping mudline (a profile) the
    /// point `x, z` (two entries per node); empty otherwise.
    #[serde(default)]
    pub friction_anchor: Vec<f64>,
}

impl DynState {
    /// Checks that this State fits the Model (e.g. one read from a checkpoint): every array has
    /// the Model's length, every number is finite, each history is of the Model's seabed law, and
    /// `t ≥ 0`. The error says which field is wrong and how.
    pub fn check_fits(&self, dm: &DynamicModel) -> Result<(), String> {
        let n = dm.line.nodes();
        for (name, v) in [
            ("u", &self.u),
            ("v", &self.v),
            ("a", &self.a),
            ("f_prev", &self.f_prev),
        ] {
            if v.len() != 3 * n {
                return Err(format!(
                    "state.{name} has {} entries, expected {} (3 per node, {n} nodes)",
                    v.len(),
                    3 * n
                ));
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(format!("state.{name}[{i}] is not a finite number"));
            }
        }
        if self.history.len() != n {
            return Err(format!(
                "state.history has {} entries, expected {n} (one per node)",
                self.history.len()
            ));
        }
        if let Some(sb) = &dm.line.seabed {
            let want = std::mem::discriminant(&sb.seabed.untouched());
            if let Some(i) = self
                .history
                .iter()
                .position(|h| std::mem::discriminant(h) != want)
            {
                return Err(format!(
                    "state.history[{i}] is the history of another seabed law than the scene's"
                ));
            }
        }
        let n_fric = friction_anchor_len(&dm.line);
        if self.friction_anchor.len() != n_fric {
            return Err(format!(
                "state.friction_anchor has {} entries, expected {n_fric} (one per node with seabed friction, two on a sloping mudline, none without)",
                self.friction_anchor.len()
            ));
        }
        if let Some(i) = self.friction_anchor.iter().position(|x| !x.is_finite()) {
            return Err(format!("state.friction_anchor[{i}] is not a finite number"));
        }
        if !(self.t.is_finite() && self.t >= 0.0) {
            return Err(format!("state.t = {} is not a time >= 0 s", self.t));
        }
        if let Some(g) = &self.wave_grid {
            for (k, s) in g.samples.iter().enumerate() {
                if s.len() != n {
                    return Err(format!(
                        "state.wave_grid.samples[{k}] has {} entries, expected {n} (one per node)",
                        s.len()
                    ));
                }
                let finite = |x: &[f64; 2]| x.iter().all(|v| v.is_finite());
                if let Some(i) = s.iter().position(|o| {
                    o.is_some_and(|p| !(finite(&p.v) && finite(&p.a) && finite(&p.j)))
                }) {
                    return Err(format!(
                        "state.wave_grid.samples[{k}][{i}] holds a number that is not finite"
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Why a step failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StepError {
    /// Newton did not converge within the cuts allowed.
    #[error(
        "the dynamic step did not converge after {cuts} step cuts: t = {t:.6} s (step {step}, Δt = {dt:.3e} s), \
         iteration {iteration}, relative residual {residual:.3e}, largest at node {node} (arc length {arc:.3} m)"
    )]
    NotConverged {
        /// The time the failed attempt aimed at, s.
        t: f64,
        /// The step number.
        step: u64,
        /// The time step of the last attempt, s.
        dt: f64,
        /// Cuts made.
        cuts: u32,
        /// Newton iterations in all the step's attempts.
        iterations: usize,
        /// The last iteration.
        iteration: usize,
        /// Its relative residual.
        residual: f64,
        /// The node with the largest residual.
        node: usize,
        /// Its arc length, m.
        arc: f64,
    },
    /// The linear solver failed.
    #[error("linear solve: {0}")]
    Solve(#[from] SolveError),
}

/// What a step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepInfo {
    /// Newton iterations (all attempts).
    pub iterations: usize,
    /// Step cuts.
    pub cuts: u32,
    /// Predictor retries (a failed attempt tried again with the constant-velocity predictor).
    pub retries: u32,
    /// Sub-steps taken (1 without cuts).
    pub substeps: usize,
    /// The attempt that caused the last cut, if there was one: where and how much.
    pub last_cut: Option<CutCause>,
}

/// Why a step was cut: the failed attempt's Δt, its last iteration's relative residual and the node
/// with the largest residual entry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutCause {
    /// The Δt of the failed attempt, s.
    pub dt: f64,
    /// The relative residual at the attempt's last iteration.
    pub residual: f64,
    /// The node with the largest residual entry.
    pub node: usize,
}

/// The part of the Workspace that changes converged bits: the tangent factorised last, the Δt it
/// was factorised for (the first Newton iterations of a step of the same Δt reuse it) and the
/// contraction rate its corrections had. A checkpoint carries it so that a restart continues bit
/// for bit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SolverMemory {
    /// The Δt of the factorised Jacobian, s.
    pub dt: f64,
    /// Its values, in the sparse pattern's order.
    pub values: Vec<f64>,
    /// The contraction rate its corrections had, when measured (absent in checkpoints written
    /// before it was kept).
    #[serde(default)]
    pub rate: Option<f64>,
}

/// The dynamic State at the end of the statics: at rest, each node in contact starting in Initial
/// Penetration at its static penetration (the spec's decision). The initial acceleration is the
/// lumped `a0 = −M⁻¹F(u, 0)` on the free dofs (zero from a static equilibrium).
pub fn initial_state(dm: &DynamicModel, u: &[f64], ws: &mut DynWorkspace) -> DynState {
    let (model, pl) = (&dm.line, &dm.placement);
    let n = model.nodes();
    let v = vec![0.0; 3 * n];
    let history: Vec<SeabedHistory> = (0..n)
        .map(
            |i| match (model.seabed.as_ref(), penetration(model, pl, u, &v, i)) {
                (Some(sb), Some((z, _))) => model
                    .seabed_law(i)
                    .unwrap_or(&sb.seabed)
                    .start_of_dynamics(z),
                (Some(sb), None) => sb.seabed.untouched(),
                _ => SeabedHistory::Linear(Default::default()),
            },
        )
        .collect();
    // Friction acts from the start of the dynamics, each spring unstretched where the statics
    // left its node (the statics are frictionless).
    let friction_anchor = match friction_anchor_len(model) {
        0 => Vec::new(),
        k if k == n => (0..n).map(|i| pl.base[3 * i] + u[3 * i]).collect(),
        _ => (0..3 * n)
            .filter(|g| g % 3 != 2)
            .map(|g| pl.base[g] + u[g])
            .collect(),
    };
    at_rest(
        dm,
        Carry {
            u: u.to_vec(),
            history,
            friction_anchor,
        },
        ws,
    )
}

/// Assembles the non-inertial forces `F(u, v)` at the workspace's iterate `(ws.u, ws.v)` into
/// `ws.f`: the structure, then every load of [`crate::loads`]; with `Pass::Tangent`, also
/// `(1+α)(K + c_v·C)` into the tangent (`k_scale = 1 + α`). `dt` is the step the seabed laws see.
fn forces_at_iterate(
    dm: &DynamicModel,
    committed: &DynState,
    ws: &mut DynWorkspace,
    pass: Pass,
    k_scale: f64,
    c_v: f64,
    dt: f64,
) {
    let with_k = pass == Pass::Tangent;
    let keep = pass == Pass::KeepingHistories;
    ws.histories_kept = keep && dm.line.seabed.is_some();
    let (asm, part) = (&mut ws.asm, &ws.scope.part);
    let structure = (ws.fj_rotation, with_k);
    asm.assemble_structure_part(
        &dm.line,
        &dm.placement,
        &ws.u,
        structure,
        part.elements.clone(),
    );
    if with_k {
        asm.scale_tangent(k_scale);
    }
    let seabed = SeabedPass::Trial {
        committed: &committed.history,
        anchors: &committed.friction_anchor,
        dt,
        memo: &mut ws.trial_memo,
        keep: keep.then_some(&mut ws.trial_history[..]),
    };
    let at = Iterate {
        u: &ws.u,
        v: &ws.v,
        wave_kin: &ws.wave_kin,
    };
    let scale = TangentScale {
        with_k,
        k: k_scale,
        c_v,
    };
    loads::assemble_part(&dm.loads(), &at, seabed, scale, (asm, &mut ws.loads), part);
    // Exchanged, not copied: the next assembly's element pass writes every entry of the residual
    // before anything adds to it.
    std::mem::swap(&mut ws.f, &mut asm.residual);
}

/// One attempt at a step of `dt` from `state`. On success the State is advanced (histories
/// committed); on failure it is untouched and the error carries the last iterate's residual.
#[allow(clippy::needless_range_loop)]
fn attempt(
    dm: &DynamicModel,
    state: &mut DynState,
    ws: &mut DynWorkspace,
    dt: f64,
    (refn, noise): (f64, f64),
    careful: bool,
    iterations: &mut usize,
) -> Result<(), Failed> {
    let (model, set) = (&dm.line, &dm.settings);
    let sc = set.scheme.step(dt);
    let t1 = state.t + dt;
    lump_mass(dm, &state.u, ws);
    // Predictor: constant acceleration, or constant velocity when `careful` (a retry).
    let d = ws.scope.reach_dofs.clone();
    let start = (
        &state.u[d.clone()],
        &state.v[d.clone()],
        &state.a[d.clone()],
    );
    sc.predict(start, careful, &mut ws.u[d]);
    // Only the part with the top prescribes it (a pair's second never reads the top's dofs).
    let has_top = ws.scope.reach_dofs.start == 0;
    let top = has_top.then(|| dm.top_at(t1)).flatten();
    // A top that holds its rotation turns with the vessel's pitch since the step's start.
    let rotates = |c: &boundary::Constraint| c.by == boundary::Prescribed::TopRotation;
    let turns = has_top && dm.vessel.is_some() && ws.constraints.iter().any(rotates);
    let before = turns.then(|| dm.top_at(state.t).map_or(0.0, |s0| s0.pitch));
    let prescribed = top.map(|s| boundary::TopPrescribed::new(s, before));
    // The vessel turns the flexjoint's reference: its counter-clockwise rotation is −pitch.
    ws.fj_rotation = top.map_or(0.0, |s| -s.pitch);
    wave_kinematics(dm, state, t1, ws);
    let (c_m, c_v, k_scale) = (sc.c_m, sc.c_v, sc.k_scale());
    let mut nt = Newton::new(ws.factored_dt == Some(dt), ws.reuse_rate, set.tol + noise);
    for it in 0..set.max_iter {
        // Kinematics from the Newmark relations; prescribed dofs from the boundary conditions.
        relations(&sc, state, ws);
        boundary::apply(
            &ws.constraints,
            prescribed.as_ref(),
            &state.u,
            (&mut ws.u, &mut ws.v, &mut ws.a),
        );
        let pass = nt.pass();
        forces_at_iterate(dm, state, ws, pass, k_scale, c_v, dt);
        // Residual G = M a + (1+α) F − α F_n at every dof, then on the free equations.
        let (nodes, d) = ws.scope.own();
        let (mass, a, f) = (&ws.mass[nodes.clone()], &ws.a[d.clone()], &ws.f[d.clone()]);
        sc.residual(mass, a, f, &state.f_prev[d.clone()], &mut ws.g_all[d]);
        if pass == Pass::Tangent {
            add_mass_tangent(&mut ws.asm, model, c_m, (&ws.mass, nodes));
        }
        let r = ws.residual_sq().sqrt() / refn;
        let accepted = match nt.judge(it, r) {
            Verdict::Backtrack { back } => {
                for &(g0, e0, len) in &ws.free_runs[ws.scope.reach_runs.clone()] {
                    for (u, dq) in ws.u[g0..g0 + len].iter_mut().zip(&ws.dq[e0..e0 + len]) {
                        *u += back * dq;
                    }
                }
                continue;
            }
            Verdict::Accepted(a) => a,
        };
        // The free equations of an accepted iterate (a halved correction's are not kept: on
        // failure the worst equation is looked up in the last accepted one's,
        // [`DynWorkspace::worst_node`]).
        for &(g0, e0, len) in &ws.free_runs[ws.scope.own_runs.clone()] {
            ws.g[e0..e0 + len].copy_from_slice(&ws.g_all[g0..g0 + len]);
        }
        let (refresh_tangent, factor) = match accepted {
            Accepted::Diverged => {
                return Err(Failed {
                    last: ws.worst_node(model, nt.last()),
                    diverged: true,
                })
            }
            Accepted::Converged => {
                ws.reuse_rate = nt.rate();
                commit(dm, state, ws, t1, dt);
                return Ok(());
            }
            Accepted::Correct {
                refresh_tangent,
                factor,
            } => (refresh_tangent, factor),
        };
        *iterations += 1;
        if refresh_tangent {
            // Not converged after all: the tangent at this iterate (the residual is recomputed
            // with it, to the same values).
            forces_at_iterate(dm, state, ws, Pass::Tangent, k_scale, c_v, dt);
            let nodes = ws.scope.part.nodes.clone();
            add_mass_tangent(&mut ws.asm, model, c_m, (&ws.mass, nodes));
        }
        if factor {
            if ws.factor_tangent().is_err() {
                // `advance` drops the factorisation of every failed attempt.
                break;
            }
            ws.factored_dt = Some(dt);
        }
        let step = ws.correction();
        for &(g0, e0, len) in &ws.free_runs[ws.scope.reach_runs.clone()] {
            for (u, dq) in ws.u[g0..g0 + len].iter_mut().zip(&ws.dq[e0..e0 + len]) {
                *u -= dq;
            }
        }
        if Newton::stagnated(r, step) {
            // Converged to machine precision: re-evaluate at the final iterate and commit.
            relations(&sc, state, ws);
            forces_at_iterate(dm, state, ws, Pass::KeepingHistories, k_scale, c_v, dt);
            ws.reuse_rate = nt.rate();
            commit(dm, state, ws, t1, dt);
            return Ok(());
        }
    }
    Err(Failed {
        last: ws.worst_node(model, nt.last()),
        diverged: false,
    })
}

/// A failed attempt: the last iterate's (iteration, relative residual, worst node), and whether
/// Newton diverged (rather than failing to converge in `max_iter`).
struct Failed {
    last: (usize, f64, usize),
    diverged: bool,
}

/// `a_{n+1}` and `v_{n+1}` on the free dofs from the workspace's iterate (the Newmark relations,
/// [`crate::integrator`]).
#[inline]
fn relations(sc: &StepCoefficients, state: &DynState, ws: &mut DynWorkspace) {
    sc.relations(
        &ws.free_runs[ws.scope.reach_runs.clone()],
        (&state.u, &state.v, &state.a),
        (&ws.u, &mut ws.v, &mut ws.a),
    );
}

/// Commits the converged iterate: the seabed histories are the trial ones at `(ws.u, ws.v)`,
/// evaluated again from the committed ones (the same pure evaluation as the iterate's residual,
/// so the same values).
fn commit(dm: &DynamicModel, state: &mut DynState, ws: &mut DynWorkspace, t1: f64, dt: f64) {
    let (model, pl) = (&dm.line, &dm.placement);
    if ws.histories_kept {
        // Evaluated at this very iterate from these committed histories (the last pass).
        std::mem::swap(&mut state.history, &mut ws.trial_history);
        ws.histories_kept = false;
    } else if let Some(sb) = &model.seabed {
        let mut spare = TrialMemo::default();
        let nodes = ws.scope.part.nodes.clone();
        let own = state.history.iter_mut().enumerate();
        for (i, h) in own.take(nodes.end).skip(nodes.start) {
            let (z, zdot) = penetration(model, pl, &ws.u, &ws.v, i).unwrap_or((0.0, 0.0));
            *h = model
                .seabed_law(i)
                .unwrap_or(&sb.seabed)
                .evaluate_with(
                    h,
                    z,
                    zdot,
                    dt,
                    ws.trial_memo.get_mut(i).unwrap_or(&mut spare),
                )
                .next;
        }
    }
    // Exchanged, not copied: the next attempt writes every entry of the iterate's u, v, a and f
    // (predictor, Newmark relations and prescribed dofs, forces) before it reads them.
    std::mem::swap(&mut state.u, &mut ws.u);
    std::mem::swap(&mut state.v, &mut ws.v);
    std::mem::swap(&mut state.a, &mut ws.a);
    std::mem::swap(&mut state.f_prev, &mut ws.f);
    if let Some(f) = model.seabed.as_ref().and_then(|s| s.friction) {
        loads::commit_friction(
            &f,
            model,
            pl,
            &state.u,
            &ws.loads.seabed_force,
            &mut state.friction_anchor,
        );
    }
    if ws.grid_new {
        match &mut state.wave_grid {
            Some(g) => std::mem::swap(g, &mut ws.grid_trial),
            None => state.wave_grid = Some(std::mem::take(&mut ws.grid_trial)),
        }
        ws.grid_new = false;
    }
    state.t = t1;
    state.step += 1;
}

/// Copies `from` into `to` without allocating (both have the same lengths).
fn copy_state(to: &mut DynState, from: &DynState) {
    to.t = from.t;
    to.step = from.step;
    to.u.copy_from_slice(&from.u);
    to.v.copy_from_slice(&from.v);
    to.a.copy_from_slice(&from.a);
    to.f_prev.copy_from_slice(&from.f_prev);
    to.history.copy_from_slice(&from.history);
    to.friction_anchor.copy_from_slice(&from.friction_anchor);
    match (&mut to.wave_grid, &from.wave_grid) {
        (Some(a), Some(b)) if a.samples[0].len() == b.samples[0].len() => {
            a.index = b.index;
            for (x, y) in a.samples.iter_mut().zip(&b.samples) {
                x.copy_from_slice(y);
            }
        }
        (a, b) => a.clone_from(b),
    }
}

/// Advances the State by `dt`. When Newton diverges, the attempt is repeated once from the
/// constant-velocity predictor, then the step is cut (halving, up to `max_cuts` times), and
/// sub-stepping back up to the full `dt`. On success the State has advanced by one step (its
/// `step` counts the sub-steps); on failure it is exactly as it was before the call.
pub fn advance(
    dm: &DynamicModel,
    state: &mut DynState,
    ws: &mut DynWorkspace,
    dt: f64,
) -> Result<StepInfo, StepError> {
    let model = &dm.line;
    let refn = ws.reference;
    let noise = crate::newton::residual_floor_at(model, ws.largest_translation(&state.u)) / refn;
    let target = state.t + dt;
    // An attempt leaves the State untouched when it fails, so the State is saved only before the
    // first sub-step that does not complete the step (after a cut): later failures restore it.
    let mut saved = std::mem::take(&mut ws.saved);
    let mut was_saved = false;
    let mut info = StepInfo::default();
    let mut h = dt;
    let mut level = 0u32;
    let mut careful = false;
    let mut outcome = Ok(());
    // What is left of the step below this is rounding: the step is done.
    let allowance = 1e-9 * dt;
    while target - state.t > allowance {
        let remaining = target - state.t;
        let h_try = h.min(remaining);
        // A sub-step that leaves the step unfinished needs the State saved first; one that leaves
        // less than half the allowance (a full step's `target − t` is `dt` give or take an ulp, so
        // its `h_try` may fall short by that) finishes it.
        if !was_saved && remaining - h_try > 0.5 * allowance {
            copy_state(&mut saved, state);
            was_saved = true;
        }
        match attempt(
            dm,
            state,
            ws,
            h_try,
            (refn, noise),
            careful,
            &mut info.iterations,
        ) {
            Ok(()) => {
                info.substeps += 1;
                careful = false;
                // After two successes at a cut level, try a longer step again.
                if level > 0 && info.substeps % 2 == 0 {
                    level -= 1;
                    h *= 2.0;
                }
            }
            // A failed attempt's last factorisation is of a rejected iterate: never reuse it.
            Err(f) if f.diverged && !careful => {
                ws.forget_factorisation();
                careful = true;
                info.retries += 1;
            }
            Err(Failed {
                last: (iteration, residual, node),
                ..
            }) => {
                ws.forget_factorisation();
                if level >= dm.settings.max_cuts {
                    outcome = Err(StepError::NotConverged {
                        t: state.t + h_try,
                        step: saved.step + 1,
                        dt: h_try,
                        cuts: info.cuts,
                        iterations: info.iterations,
                        iteration,
                        residual,
                        node,
                        arc: model.arc[node],
                    });
                    break;
                }
                level += 1;
                info.cuts += 1;
                info.last_cut = Some(CutCause {
                    dt: h_try,
                    residual,
                    node,
                });
                h *= 0.5;
            }
        }
    }
    if outcome.is_err() {
        if was_saved {
            copy_state(state, &saved);
        }
    } else {
        state.t = target;
    }
    ws.saved = saved;
    outcome.map(|()| info)
}

/// Re-evaluates the forces and the lumped mass at a State (e.g. one restored from a checkpoint) so
/// that [`results`] can be taken from it. Commits nothing and leaves the reused factorisation alone.
pub fn refresh(dm: &DynamicModel, state: &DynState, ws: &mut DynWorkspace) {
    ws.u.copy_from_slice(&state.u);
    ws.v.copy_from_slice(&state.v);
    forces_at_iterate(dm, state, ws, Pass::Forces, 0.0, 0.0, 0.0);
    lump_mass(dm, &state.u, ws);
}

/// Fills `out` with the nodal results of the State just committed by [`advance`] (the workspace
/// still holds the converged evaluation); the end nodes' tension is the reaction `M a + F`.
/// Allocates nothing.
pub fn results(dm: &DynamicModel, state: &DynState, ws: &DynWorkspace, out: &mut LineResults) {
    let mass = &ws.mass;
    ws.asm.fill_results(
        &dm.line,
        &dm.placement,
        &state.u,
        |i| ws.loads.seabed_force[i],
        |i| state.history[i].mode().code(),
        |i| {
            let m = mass[i];
            let (ax, az) = (state.a[3 * i], state.a[3 * i + 1]);
            (
                m[0] * ax + m[1] * az + state.f_prev[3 * i],
                m[1] * ax + m[2] * az + state.f_prev[3 * i + 1],
            )
        },
        out,
    );
}
