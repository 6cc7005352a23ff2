//! Two threads stepping one line (issue 48): each runs the same Newton loop ([`advance`]) on its
//! part of the line, and the two meet where the parts touch.
//!
//! The line is cut where the band's two ends meet ([`Assembler::split_at_node`]): the first part
//! owns the nodes `0..=k` and the equations `0..p` (the band's top end and middle), the second the
//! nodes `k+1..` and the equations `p..` (its bottom end). Each thread
//!
//! - predicts, and takes the Newmark relations, at its own nodes and at the other part's node
//!   next to them (the *halo*: the element across the cut is computed by both parts);
//! - assembles its part's forces and tangent columns ([`Part`]), its residual and lumped mass at
//!   its own nodes;
//! - factorises and solves its side of the band ([`Assembler::factor_tangent_side`]);
//! - commits its own nodes' histories.
//!
//! They meet four times in an iteration at most: for the residual's squared norm (two partial
//! sums, added in the same order as on one thread, [`Split`]), twice in a factorisation, twice in a
//! solve, and once after it for the largest correction and the halo's corrections. Every decision
//! (convergence, backtracking, refactorising, retries, cuts) is taken from the same numbers on
//! both, so both take it; and every number is computed by the same operations in the same order
//! as on one thread: the State after a step is the same to the bit whether one thread steps the
//! line or two (`two_threads_step_as_one_to_the_bit`). The second thread's part of the State is
//! handed over after each step ([`Pair::advance`]), so that the results and the observers read
//! one whole State.
//!
//! **One Model.** The second thread reads the caller's Model, handed over with each step
//! ([`Pair::advance`] takes it as an [`Arc`]; the second thread lets go of it before the step is
//! done): a caller that changes its Model between steps (a lay: the vessel's track, the top's
//! motion, the top element's rest length) changes it for both threads, and no stale copy can take
//! other decisions (the residual's floor sums over every element). What a Workspace keeps of the
//! top element ([`DynWorkspace::top_rest_length_changed`]) is the first part's alone: the cut is at
//! least two nodes down the line.
//!
//! The water kinematics of a scene with waves are taken at each thread's own nodes (the loads
//! read them there only): the samples on the wave grid too, from the committed State, so each
//! node's samples are the same whichever thread takes them, and the second part's are handed
//! over with its State when they are renewed (with the grid's index: storm 23, a step in five).
//! The samples cost most near the surface, which is all in the first part
//! (a riser's top). A pair started with [`Samples::Shared`] ([`Pair::start`]'s) has the second
//! thread also sample the first part's nodes `lent` (next to the cut, chosen at
//! [`Pair::start_with`] so that each thread's samples cost about half,
//! [`crate::waves::Waves::sampling_cost`]), from their committed State, which the first thread
//! hands it at a meeting each time new samples are due ([`Lane::lend_state`]: also in a sub-step
//! after a cut), and hand their samples to the first thread at another ([`Lane::lend_samples`]).
//! Measured against [`Samples::Own`] (each thread its own nodes): a J-lay in Hs 2 m 1.10× faster
//! on two threads, storm 23's pair about 6 % (`benches/README.md`). Either way, the same bits.

use std::ops::Range;
use std::sync::Arc;

use crate::newton::max_abs;
use crate::partner::{seats_with_chores, Partner, Seat};
use crate::waves::WaveKinematics;

use super::cut::{Lane, Scope, Split, SAMPLE_NUMBERS};
use super::*;

impl DynWorkspace {
    /// Makes this workspace step side `side` of the line, meeting the other at `seat`; the second
    /// thread samples the waves at the first part's nodes `lent` too.
    fn enter(
        &mut self,
        line: &LineModel,
        split: Split,
        (side, seat): (usize, Seat),
        lent: Range<usize>,
    ) {
        self.scope = Scope::side(line, split, &self.free_runs, side);
        let p = self.free_runs[split.runs].1;
        let halo = (3 * (split.k + 1)..3 * (split.k + 2))
            .filter(|&g| line.equation[g].is_some())
            .count();
        let (send, receive) = if side == 0 {
            (p..p, p..p + halo)
        } else {
            (p..p + halo, p..p)
        };
        self.lane = Some(Lane {
            side,
            seat,
            send,
            receive,
            mail: vec![0.0; 2 * SAMPLE_NUMBERS * lent.len()],
            lent,
        });
    }

    /// Makes this workspace step the whole line again.
    fn leave(&mut self, line: &LineModel) {
        self.scope = Scope::whole(line, self.free_runs.len());
        self.lane = None;
    }

    /// The squared norm of the residual's free equations (`g_all` on the free runs): eight
    /// interleaved partial sums per run ([`crate::fastmath::lane_dot`]: one running sum is a
    /// chain of dependent additions), each part's runs summed, then the two parts ([`Split`]),
    /// on one thread or two.
    pub(super) fn residual_sq(&mut self) -> f64 {
        let g_all = &self.g_all;
        let sum = |runs: &[(usize, usize, usize)]| -> f64 {
            runs.iter()
                .map(|&(g0, _, len)| {
                    let g = &g_all[g0..g0 + len];
                    crate::fastmath::lane_dot(g, g)
                })
                .sum()
        };
        match (&mut self.lane, self.split) {
            (None, None) => sum(&self.free_runs),
            (None, Some(s)) => sum(&self.free_runs[..s.runs]) + sum(&self.free_runs[s.runs..]),
            (Some(l), _) => {
                let mine = sum(&self.free_runs[self.scope.own_runs.clone()]);
                let mut theirs = [0.0];
                l.seat.exchange(&[mine], &mut theirs);
                match l.side {
                    0 => mine + theirs[0],
                    _ => theirs[0] + mine,
                }
            }
        }
    }

    /// The largest translational displacement of `u` ([`crate::newton::largest_translation`]),
    /// over both parts on two threads.
    pub(super) fn largest_translation(&mut self, u: &[f64]) -> f64 {
        let (_, dofs) = self.scope.own();
        let mine = crate::newton::largest_translation(&u[dofs]);
        let Some(l) = &mut self.lane else {
            return mine;
        };
        let mut theirs = [0.0];
        l.seat.exchange(&[mine], &mut theirs);
        mine.max(theirs[0])
    }

    /// After a step on two threads, each side checks that the other took the same one (its
    /// outcome, counts and time); a side that took another step (a bug) panics rather than
    /// waiting for ever at a meeting the other does not come to. Seven numbers: no other meeting
    /// has that many, so a side at another meeting panics too.
    fn same_step(&mut self, outcome: &Result<StepInfo, StepError>, t: f64) {
        let Some(l) = &mut self.lane else {
            return;
        };
        let info = outcome.as_ref().ok();
        let mine = [
            f64::from(u8::from(outcome.is_ok())),
            info.map_or(0.0, |i| i.iterations as f64),
            info.map_or(0.0, |i| f64::from(i.cuts)),
            info.map_or(0.0, |i| f64::from(i.retries)),
            info.map_or(0.0, |i| i.substeps as f64),
            t,
            1.0,
        ];
        let mut theirs = [0.0; 7];
        l.seat.exchange(&mine, &mut theirs);
        assert_eq!(
            mine.map(f64::to_bits),
            theirs.map(f64::to_bits),
            "the two threads stepping the line took different steps"
        );
    }

    /// Factorises the tangent assembled last (this thread's side of it on two).
    pub(super) fn factor_tangent(&mut self) -> Result<(), SolveError> {
        match &mut self.lane {
            None => self.asm.factor_tangent(),
            Some(l) => self.asm.factor_tangent_side(l.side, &mut l.seat),
        }
    }

    /// The Newton correction `dq = J⁻¹ g` on this thread's equations (on two, also the halo's);
    /// returns the largest `|dq|` over all the equations.
    pub(super) fn correction(&mut self) -> f64 {
        let own = self.scope.own_eqs.clone();
        self.dq[own.clone()].copy_from_slice(&self.g[own.clone()]);
        let Some(l) = &mut self.lane else {
            self.asm.solve_tangent(&mut self.dq);
            return max_abs(&self.dq);
        };
        self.asm
            .solve_tangent_side(l.side, &mut l.seat, &mut self.dq);
        // The largest over the two parts is the largest over the whole (a maximum is exact).
        let mine = max_abs(&self.dq[own]);
        let (mut sent, mut got) = ([0.0; 4], [0.0; 4]);
        let (s, r) = (l.send.len(), l.receive.len());
        sent[0] = mine;
        sent[1..=s].copy_from_slice(&self.dq[l.send.clone()]);
        l.seat.exchange(&sent[..=s], &mut got[..=r]);
        self.dq[l.receive.clone()].copy_from_slice(&got[1..=r]);
        mine.max(got[0])
    }

    /// `(iteration, residual)` of the last accepted iterate and the node of the largest entry of
    /// its residual on the free equations (the first of equal ones), over both parts on two
    /// threads.
    pub(super) fn worst_node(
        &mut self,
        model: &LineModel,
        (it, r): (usize, f64),
    ) -> (usize, f64, usize) {
        let (big, mut eq) = crate::newton::largest_entry(&self.g, self.scope.own_eqs.clone());
        if let Some(l) = &mut self.lane {
            // An equation number is exact in an f64.
            let mut theirs = [0.0; 2];
            l.seat.exchange(&[big, eq as f64], &mut theirs);
            let (first, second) = match l.side {
                0 => ((big, eq), (theirs[0], theirs[1] as usize)),
                _ => ((theirs[0], theirs[1] as usize), (big, eq)),
            };
            eq = if second.0 > first.0 {
                second.1
            } else {
                first.1
            };
        }
        let node = crate::newton::node_of_equation(model, eq);
        (it, r, node)
    }
}

/// The second thread's side of a [`Pair`]: the caller's Model during a step, and its own State and
/// Workspace.
struct Side {
    /// The caller's Model, from [`Pair::advance`] until the step is done.
    dm: Option<Arc<DynamicModel>>,
    state: DynState,
    ws: DynWorkspace,
    dt: f64,
    outcome: Result<StepInfo, StepError>,
}

/// The job that advances the second thread's side by its `dt`.
const ADVANCE: u8 = 1;

fn serve(w: &mut Side, code: u8) {
    if code == ADVANCE {
        // The caller's Model is let go of before the step is done (also if it panics), so that
        // the caller may change it between steps.
        let step = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let Some(dm) = w.dm.take() else {
                unreachable!("Pair::advance hands its Model over with the step")
            };
            advance(&dm, &mut w.state, &mut w.ws, w.dt)
        }));
        match step {
            Ok(outcome) => {
                w.ws.same_step(&outcome, w.state.t);
                w.outcome = outcome;
            }
            Err(panic) => {
                // Its seat goes, so that the other side does not wait for it for ever.
                w.ws.lane = None;
                std::panic::resume_unwind(panic)
            }
        }
    }
}

/// A run's second thread stepping the second part of the line (see the module docs): made with
/// [`Pair::start`], it advances with [`Pair::advance`] instead of [`advance`].
pub struct Pair {
    partner: Partner<Side>,
    split: Split,
    /// The wave grid's index when the second part's samples were last handed over (they change
    /// only with it).
    grid_handed: Option<u64>,
}

impl std::fmt::Debug for Pair {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pair").field("k", &self.split.k).finish()
    }
}

/// Which wave samples the second thread of a [`Pair`] takes (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Samples {
    /// Each thread samples its own nodes.
    Own,
    /// The second thread also samples the first part's nodes next to the cut, so that each
    /// thread's samples cost about half.
    Shared,
}

impl Pair {
    /// Starts the second thread from `state`, and makes `ws` (the calling thread's) step the first
    /// part; the wave samples are shared ([`Samples::Shared`]). `None` when the
    /// line is not cut in parts (a band factorised top-down: lines of fewer than
    /// [`crate::sparse::TWIST_MIN`] equations). The Model may change between steps (each step
    /// hands it to both threads), but not its line's nodes and elements: for another line,
    /// [`Pair::stop`] and start again.
    pub fn start(
        dm: &DynamicModel,
        state: &DynState,
        ws: &mut DynWorkspace,
    ) -> std::io::Result<Option<Self>> {
        Self::start_with(dm, state, ws, Samples::Shared)
    }

    /// [`Pair::start`], the wave samples shared as `samples` says (the nodes lent are chosen from
    /// `state`'s depths).
    pub fn start_with(
        dm: &DynamicModel,
        state: &DynState,
        ws: &mut DynWorkspace,
        samples: Samples,
    ) -> std::io::Result<Option<Self>> {
        let Some(split) = ws.split else {
            return Ok(None);
        };
        if ws.lane.is_some() {
            return Ok(None);
        }
        let mut theirs = DynWorkspace::new(&dm.line).map_err(std::io::Error::other)?;
        // The factorisation the first iterations of the next step reuse, to the bit.
        if let Some(m) = ws.solver_memory() {
            theirs
                .restore_solver_memory(&m)
                .map_err(std::io::Error::other)?;
        }
        let lent = match samples {
            Samples::Own => 0..0,
            Samples::Shared => lent_nodes(dm, state, split.k),
        };
        // The largest meeting: a factorisation's outcome and five band columns (31 numbers), or
        // the lent samples.
        // What each thread does while it waits (`DynWorkspace::set_chores`).
        let chores = || [0, 1].map(|side| ws.chores.as_ref().and_then(|c| c.side(side)));
        let (mine, other) = seats_with_chores(32.max(2 * SAMPLE_NUMBERS * lent.len()), chores());
        let sides = chores();
        ws.enter(&dm.line, split, (0, mine), lent.clone());
        theirs.enter(&dm.line, split, (1, other), lent);
        // The top element and the top two nodes (what a Workspace keeps of a top rest length
        // changed between steps) are the first part's.
        debug_assert!(split.k >= 2, "the cut is at least two nodes down the line");
        let side = Side {
            dm: None,
            state: state.clone(),
            ws: theirs,
            dt: 0.0,
            outcome: Ok(StepInfo::default()),
        };
        match Partner::start_with_chores(side, serve, sides) {
            Ok(partner) => Ok(Some(Self {
                partner,
                split,
                grid_handed: state.wave_grid.as_ref().map(|g| g.index),
            })),
            Err(e) => {
                ws.leave(&dm.line);
                Err(e)
            }
        }
    }

    /// [`advance`] on two threads: the same State and results to the bit. Both threads read `dm`
    /// (the second lets go of it before the step is done: `Arc::get_mut` or `Arc::make_mut` change
    /// it between steps without a copy). The second part's nodes of the State, its lumped mass,
    /// seabed forces and element results are handed over to `state` and `ws` afterwards, so that
    /// [`results`] reads the whole line.
    pub fn advance(
        &mut self,
        dm: &Arc<DynamicModel>,
        state: &mut DynState,
        ws: &mut DynWorkspace,
        dt: f64,
    ) -> Result<StepInfo, StepError> {
        {
            let mut w = self.partner.work();
            // The caller may set the time between steps (to the step count times Δt).
            w.state.t = state.t;
            w.dt = dt;
            w.dm = Some(Arc::clone(dm));
        }
        self.partner.ask(ADVANCE);
        let outcome = advance(dm, state, ws, dt);
        ws.same_step(&outcome, state.t);
        let w = self.partner.wait();
        let (k, n) = (self.split.k, dm.line.nodes());
        let (nodes, dofs) = (k + 1..n, 3 * (k + 1)..3 * n);
        for (to, from) in [
            (&mut state.u, &w.state.u),
            (&mut state.v, &w.state.v),
            (&mut state.a, &w.state.a),
            (&mut state.f_prev, &w.state.f_prev),
        ] {
            to[dofs.clone()].copy_from_slice(&from[dofs.clone()]);
        }
        state.history[nodes.clone()].copy_from_slice(&w.state.history[nodes.clone()]);
        let per = state.friction_anchor.len() / n;
        let anchors = per * (k + 1)..per * n;
        state.friction_anchor[anchors.clone()].copy_from_slice(&w.state.friction_anchor[anchors]);
        // The samples are renewed only when the grid's index moves (both threads at the same
        // steps; storm 23: a step in five), and the first thread's commit then brings its own
        // arrays into `state`, stale on the second part: handed over then only. A `state` whose
        // index is not the second thread's (set by the caller between steps) is handed them too.
        if let (Some(to), Some(from)) = (&mut state.wave_grid, &w.state.wave_grid) {
            if self.grid_handed != Some(from.index) || to.index != from.index {
                to.index = from.index;
                for (to, from) in to.samples.iter_mut().zip(&from.samples) {
                    to[nodes.clone()].copy_from_slice(&from[nodes.clone()]);
                }
                self.grid_handed = Some(from.index);
            }
        }
        ws.mass[nodes.clone()].copy_from_slice(&w.ws.mass[nodes.clone()]);
        let force = &mut ws.loads.seabed_force;
        force[nodes.clone()].copy_from_slice(&w.ws.loads.seabed_force[nodes]);
        ws.asm
            .take_element_results(&w.ws.asm, k + 1..dm.line.elements.len());
        debug_assert_eq!(outcome, w.outcome);
        outcome
    }

    /// How many of the first part's nodes the second thread samples the waves at (see the module
    /// docs).
    pub fn lent_nodes(&self, ws: &DynWorkspace) -> usize {
        ws.lane.as_ref().map_or(0, |l| l.lent.len())
    }

    /// The solver memory of the pair ([`DynWorkspace::solver_memory`]): the first side's with the
    /// second side's columns of the tangent factorised last.
    pub fn solver_memory(&self, ws: &mut DynWorkspace) -> Option<SolverMemory> {
        let w = self.partner.work();
        let p = ws.scope.own_eqs.end;
        ws.asm
            .take_factored_columns(&w.ws.asm, p..w.ws.scope.own_eqs.end);
        ws.solver_memory()
    }

    /// Ends the second thread and makes `ws` step the whole line again (its factorisation, of the
    /// first side only, is forgotten).
    pub fn stop(self, dm: &DynamicModel, ws: &mut DynWorkspace) {
        drop(self.partner);
        ws.leave(&dm.line);
        ws.forget_factorisation();
    }
}

/// The first part's nodes whose wave samples the second thread takes (see the module docs): the
/// last ones above the first part's last node `k` (whose sample the first thread takes), as many
/// as bring the second thread's share of the samples' cost at `state`
/// ([`crate::waves::Waves::sampling_cost`] at each node's depth) nearest half. Empty without
/// waves sampled on a grid, or where the second part costs half or more.
fn lent_nodes(dm: &DynamicModel, state: &DynState, k: usize) -> Range<usize> {
    let env = &dm.environment;
    let (Some(waves), Some(_)) = (&env.waves, &env.hydro) else {
        return 0..0;
    };
    if waves.sampling_interval() <= 0.0 {
        return 0..0;
    }
    let pl = &dm.placement;
    let cost = |i: usize| {
        let z = pl.base[3 * i + 1] + state.u[3 * i + 1] - env.water_level;
        waves.sampling_cost(z)
    };
    let n = dm.line.nodes();
    let total: f64 = (0..n).map(cost).sum();
    let mut second: f64 = (k + 1..n).map(cost).sum();
    let mut s = k;
    while s > 0 && second + cost(s - 1) <= 0.5 * total {
        s -= 1;
        second += cost(s);
    }
    s..k
}
