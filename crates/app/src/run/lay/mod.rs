//! A pipe's installation by J-lay: the vessel moves along the route, the pipe leaves the tower and
//! is paid out, each point of it passes through the touchdown zone and comes to rest on the
//! seabed with the embedment the hysteretic law gives it.
//!
//! **Material points.** The whole pipe is one mesh from the start (`full`; node 0 is the pipe's
//! last end, on the vessel; arc length from there), so each node is a point of the pipe and keeps
//! its own seabed history from the moment it lands. The part not yet paid out waits on the vessel
//! along the tower; the part far behind the touchdown is frozen where it lies. Only the window
//! between them is solved ([`window`]), so the cost of a simulated second does not grow with the
//! length laid.
//!
//! **The tower.** The window's top node is the pipe's node just above the tower's exit, held on the
//! tower's line (clamped at the tower's angle, or hinged on a rotational spring); the exit moves
//! with the vessel (its speed `V` along +x, plus the wave-driven motion of `[vessel]` at the
//! tower). Paying out a length `ds` of pipe slides that node down the tower by `ds·(1 + ε)`, `ε =
//! T/EA` the strain at the top when it came onto the tower; when it reaches the exit it is free, and
//! the next node of the pipe becomes the window's top, one element above the exit along the tower
//! (the element between them stretched by the same `ε`, so that it carries the top tension from
//! the start). Paid in (a tensioner that pays in), the node below the top is taken back onto the
//! tower when the top rises an element above the exit.
//!
//! The clamp acts at the top node, which is up to one element above the exit: where the tower's
//! angle is the pipe's natural departure angle (the default) this moves nothing; otherwise the
//! clamp's place jitters by up to one element along the tower.
//!
//! **Payout.** Position control pays out at the vessel's speed. Tension control moves the payout
//! rate towards the demand `V + g·(T − T_target)` (`g` the gain) with the tensioner's time
//! constant `τ`, limited to ±`max_payout_rate`, from the top tension `T` (at the exit) of the last
//! converged step (explicit in the step), read through a first-order filter ([`TENSION_FILTER`]).
//! The vessel's speed (and position control's payout) rises from 0 to `V` over `[lay] ramp` (a
//! quintic, as the waves' ramp). The time constant is what keeps the loop stable: paying
//! out faster by `Δr` drops the tension at once by the pipe's axial impedance `√(EA·m)·Δr` (an
//! axial wave), so a demand taken at once would swing by `g·√(EA·m)` times its error each step (16
//! for the 12-inch pipe at `g` = 2e-5 (m/s)/N); followed at `Δt/τ` a step, the error shrinks by
//! `1 − (Δt/τ)(1 + g·√(EA·m))` instead.
//!
//! **Freezing.** Each time a node leaves the tower, the nodes at the window's bottom that lie at
//! least `freeze_behind` behind the touchdown point (in x) and moved less than `freeze_tolerance`
//! since the last time are frozen: the lowest node still in the window is held where it lies, and
//! its as-laid embedment is taken ([`laid`]).
//!
//! The vessel's wave-driven motion follows it along the route: its RAO origin moves with it, so it
//! meets the waves at its own position and at the frequency of encounter
//! ([`catena_fe::vessel::Vessel::track`], set each step). Its pitch turns the tower with it: a
//! clamped tower's top node turns by `−β` ([`catena_fe::boundary`]), a hinged tower's spring's
//! reference likewise, and the tower's line above the exit (where the top node stands and a new
//! top is put) turns about the exit. The lay's records are kept in memory and written when the run ends
//! (also when it fails or is interrupted: everything up to the last converged step).

pub mod checkpoint;
mod exit;
pub mod frames;
pub mod install;
pub mod laid;
mod mesh;
mod result;
mod stepping;
pub mod window;

pub use mesh::statics_scene;
use mesh::{material_mesh, station_height};
pub use result::{LayDown, LayProgress, LayRun};

use std::sync::Arc;
use std::time::Instant;

use catena_fe::assembly::{LineResults, Placement};
use catena_fe::dynamics::{self, DynState, DynWorkspace, DynamicModel};
use catena_fe::model::LineModel;

use crate::error::AppError;
use crate::run::observe::Stop;
use crate::run::statics::{self, StaticRun};
use crate::scene::lay::{LaySpec, Payout};
use crate::scene::riser::{DynamicSpec, RiserScene};
use laid::{LaidNodes, LayRecords};
use window::Store;

/// The time constant of the filter through which a tensioner reads the top tension, s [A]: it
/// leaves out the top element's axial ringing at the time step's period, which the tensioner
/// would otherwise feed back.
pub const TENSION_FILTER: f64 = 1.0;

/// The whole path: the statics of the start, then the lay.
pub fn simulate_lay(
    scene: RiserScene,
    on_step: &mut dyn FnMut(&LayProgress) -> bool,
) -> Result<LayRun, AppError> {
    lay(statics::solve(statics_scene(scene))?, on_step)
}

/// Options of a lay: checkpoints, a restart, a stop after some steps.
#[derive(Debug, Clone, Default)]
pub struct LayOptions {
    /// Write a checkpoint to this file every this many steps.
    pub checkpoint: Option<(std::path::PathBuf, u64)>,
    /// Continue from this checkpoint (read from the file named).
    pub restart: Option<(checkpoint::LayCheckpoint, String)>,
    /// Stop (successfully) after this many steps, e.g. to end a job at a checkpoint.
    pub stop_after: Option<u64>,
    /// The threads the lay may keep busy (`None`: the machine's cores): from two, the window is
    /// stepped by a [`catena_fe::dynamics::Pair`], the same bits as on one.
    pub threads: Option<usize>,
    /// The steps a second thread takes, fixed (`Some(|_| true)`: every step a window can be cut;
    /// for tests of the pair, whose timing-driven choice could leave it few steps); `None`: the
    /// drive's choice ([`catena_fe::dynamics::Drive`]).
    pub pair_schedule: Option<fn(u64) -> bool>,
}

/// Lays the pipe of a solved lay scene (see [`statics_scene`]); `on_step` sees every converged
/// step and stops the lay by returning `false`.
pub fn lay(
    st: StaticRun,
    on_step: &mut dyn FnMut(&LayProgress) -> bool,
) -> Result<LayRun, AppError> {
    lay_with(st, LayOptions::default(), on_step)
}

/// [`lay`] with checkpoints, a restart or a stop after some steps.
pub fn lay_with(
    st: StaticRun,
    opts: LayOptions,
    on_step: &mut dyn FnMut(&LayProgress) -> bool,
) -> Result<LayRun, AppError> {
    let t0 = Instant::now();
    let mut l = Lay::start(&st)?;
    if let Some((cp, file)) = &opts.restart {
        l.restore(cp, file, &st.scene.text)?;
    }
    l.checkpoint_to = opts.checkpoint;
    l.stop_after = opts.stop_after;
    // Held until the lay ends: a run beside it in this process takes the cores left.
    let cores = crate::run::Cores::take(opts.threads);
    l.stepping.drive = match (opts.pair_schedule, opts.threads) {
        (Some(two), _) => catena_fe::dynamics::Drive::with_schedule(two),
        (None, Some(_)) => catena_fe::dynamics::Drive::asked(cores.threads()),
        (None, None) => catena_fe::dynamics::Drive::new(cores.threads()),
    };
    let stop = l.run_until(l.dspec.duration, on_step);
    // As a run's: 2 where a pair took any step (a window too short to cut steps on one).
    let steps_on_two = l.stepping.drive.tally().0[1];
    let stepping_threads = 1 + usize::from(steps_on_two > 0);
    l.unpair();
    let stop = stop?;
    l.finish();
    let summary = l.summary(&st);
    let warnings = Vec::new();
    let lay_down = l.left_tower.map(|(t, kp)| LayDown {
        left_tower: t,
        kp_touchdown: kp,
        rested: l.rested,
        end_embedment: l.nodes.as_laid[l.pipe_end],
    });
    Ok(LayRun {
        spec: l.spec.clone(),
        dynamic: l.dspec.clone(),
        on_vessel: l.on_vessel,
        tower_angle: l.phi,
        target_tension: l.target,
        records: std::mem::take(&mut l.records),
        positions: l.positions(),
        window: (l.first, l.last),
        steps: l.state.step,
        iterations: l.iterations,
        cuts: l.cuts,
        windows: l.windows,
        taken_back: l.taken_back,
        stepping_threads,
        steps_on_two,
        nodes: l.nodes,
        full: l.full,
        summary,
        wall_seconds: t0.elapsed().as_secs_f64(),
        lay_down,
        installation: l.check.take(),
        warnings,
        histories: std::mem::take(&mut l.store.history),
        frames: std::mem::take(&mut l.frames),
        friction: (std::mem::take(&mut l.store.friction), l.store.stride),
        stop,
        statics: st,
    })
}

/// The lay in progress: the Model of the whole pipe, the store, the window and the tower
/// ([`lay`] runs one from the statics to the end; a benchmark steps one on).
pub struct Lay {
    file: String,
    spec: LaySpec,
    dspec: DynamicSpec,
    full: LineModel,
    base: Placement,
    store: Store,
    on_vessel: usize,
    first: usize,
    last: usize,
    /// The window's Model, shared with its second stepping thread during a step (changed
    /// between steps through [`Lay::model_mut`]).
    dm: Arc<DynamicModel>,
    ws: DynWorkspace,
    state: DynState,
    res: LineResults,
    /// The tower: its angle from the vertical, the nodes' angle on it, its upward direction.
    phi: f64,
    theta: f64,
    up: [f64; 2],
    exit0: [f64; 2],
    eps: f64,
    d_top: f64,
    vessel_x: f64,
    paid: f64,
    rate: f64,
    target: Option<f64>,
    tension: f64,
    /// The tension the tensioner reads: `tension` through a first-order filter.
    measured: f64,
    nodes: LaidNodes,
    records: LayRecords,
    moved_from: Vec<[f64; 2]>,
    iterations: usize,
    cuts: u32,
    windows: u64,
    taken_back: u64,
    /// The pipe's last end's node (0 without a lay-down wire above it).
    pipe_end: usize,
    /// Whether the window's top is at the tower's exit (the tower holds a moment), else it moves
    /// down the tower above it ([`exit::Top`]).
    clamp_at_exit: bool,
    /// A lay-down's station height, m ([`LayRun::vessel_speed_at`]).
    station_height: f64,
    /// When the pipe's end left the tower, and the touchdown's KP then (a lay-down).
    left_tower: Option<(f64, f64)>,
    /// When the pipe's end came to rest on the seabed (the lay-down's end).
    rested: Option<f64>,
    /// The installation check, if the scene has a `[design_check]`.
    check: Option<install::InstallationCheck>,
    /// Full steps taken (of `[dynamic] time_step`).
    full_steps: u64,
    /// Checkpoints: the file and the interval in steps.
    checkpoint_to: Option<(std::path::PathBuf, u64)>,
    /// Stop after this many steps.
    stop_after: Option<u64>,
    /// The scene's text hash (checkpoints).
    scene_hash: String,
    /// The frames for the animation.
    frames: frames::LayFrames,
    /// The threads the window is stepped on ([`stepping`]).
    stepping: stepping::Stepping,
}

impl Lay {
    /// The lay at its start, from the statics of a lay scene (see [`statics_scene`]).
    pub fn start(st: &StaticRun) -> Result<Self, AppError> {
        let scene = &st.scene;
        let file = scene.file.clone();
        let fail = |message: String| AppError::Run {
            file: file.clone(),
            message,
        };
        let spec = scene
            .lay
            .clone()
            .ok_or_else(|| fail("key `lay`: expected a [lay] table for a lay run".into()))?;
        let dspec = scene
            .dynamic
            .clone()
            .ok_or_else(|| fail("key `dynamic`: expected a [dynamic] table".into()))?;
        let (full, o, pipe_end) = material_mesh(&st.model, &spec);
        let theta0 = st.placement.base[2] + st.u[2];
        // The static top's angle from the downward vertical (the line runs to −x from the top).
        let phi0 = theta0.cos().abs().atan2(-theta0.sin());
        let phi = spec.tower_angle.unwrap_or(phi0);
        let up = [phi.sin(), phi.cos()];
        // The tower's angle on the static top angle's branch (the same angle when `phi = phi0`).
        let down = (-up[1]).atan2(-up[0]);
        let theta = theta0
            + ((down - theta0 + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI);
        let exit0: [f64; 2] = std::array::from_fn(|c| st.placement.base[c] + st.u[c]);
        let (tension, top) = (st.results.tension[0], st.model.elements[0]);
        let eps = tension / top.section.ea;
        // The base: the tower's nodes along the tower above the exit (each element stretched by
        // the top's strain), the line's where the statics' seed put them.
        let n = full.nodes();
        let mut q = vec![0.0; 3 * n];
        for j in 0..o {
            let d = (full.arc[o] - full.arc[j]) * (1.0 + eps);
            q[3 * j] = exit0[0] + d * up[0];
            q[3 * j + 1] = exit0[1] + d * up[1];
            q[3 * j + 2] = theta;
        }
        q[3 * o..].copy_from_slice(&st.placement.base);
        let base = Placement::new(&q);
        let mut u = vec![0.0; 3 * n];
        u[3 * o..].copy_from_slice(&st.u);
        let untouched = full.seabed.as_ref().map_or(
            catena_seabed::law::SeabedHistory::Linear(Default::default()),
            |s| s.seabed.untouched(),
        );
        let (clamp_at_exit, first, d_top) = exit::start(st, &full, o, eps);
        let last = n - 1;
        let dm = window::model(
            &full,
            &base,
            (first, last, full.elements[first].l0),
            (spec.tower, theta, first < pipe_end),
            &dspec,
        );
        let mut ws = DynWorkspace::new(&dm.line).map_err(|source| AppError::Solver {
            file: file.clone(),
            source,
        })?;
        // The window's own equilibrium: a tower that holds a moment (tilted off the departure
        // angle, or a hinge's spring) has it at the exit in the statics but one element higher in
        // the window (nothing changes at the departure angle: the residual is already within
        // tolerance).
        window::settle(&dm, scene, &mut u[3 * first..]).map_err(|source| AppError::Statics {
            file: file.clone(),
            source,
        })?;
        let state = dynamics::initial_state(&dm, &u[3 * first..], &mut ws);
        let stride = state.friction_anchor.len() / dm.line.nodes();
        let mut store = Store {
            u,
            v: vec![0.0; 3 * n],
            a: vec![0.0; 3 * n],
            f: vec![0.0; 3 * n],
            history: vec![untouched; n],
            friction: vec![0.0; stride * n],
            stride,
        };
        store.keep(first, &state);
        let target = match spec.payout {
            Payout::Tension { target, .. } => Some(target.unwrap_or(tension)),
            Payout::Position => None,
        };
        let mut res = LineResults::new(dm.line.nodes());
        dynamics::results(&dm, &state, &ws, &mut res);
        let nodes = LaidNodes::new(&full, (o, pipe_end), &st.results.seabed_force);
        let check = dspec
            .design_check
            .zip(dspec.section)
            .map(|(spec, section)| {
                install::InstallationCheck::new(
                    spec,
                    section,
                    (top.section.ei, top.section.ea),
                    (&st.model.arc, &st.results.moment, &st.results.tension),
                    full.nodes(),
                )
            });
        let records = (dspec.duration / (dspec.dt * dspec.output_every as f64)).ceil() as usize + 1;
        let mut l = Self {
            file,
            d_top,
            clamp_at_exit,
            rate: 0.0,
            station_height: station_height(&full, pipe_end, &spec),
            spec,
            dspec,
            base,
            store,
            on_vessel: o,
            first,
            last,
            dm: Arc::new(dm),
            ws,
            state,
            res,
            phi,
            theta,
            up,
            exit0,
            eps,
            vessel_x: 0.0,
            paid: 0.0,
            target,
            tension,
            measured: tension,
            nodes,
            records: LayRecords::default(),
            moved_from: vec![[f64::NAN; 2]; n],
            iterations: 0,
            cuts: 0,
            windows: 0,
            taken_back: 0,
            pipe_end,
            left_tower: None,
            rested: None,
            check,
            full_steps: 0,
            checkpoint_to: None,
            stop_after: None,
            scene_hash: crate::scene::text_hash(&scene.text),
            frames: frames::LayFrames::new(records),
            full,
            stepping: Default::default(),
        };
        l.mark_positions();
        l.record();
        Ok(l)
    }

    /// Node `g`'s position `(x, z)` from the store.
    fn at(&self, g: usize) -> [f64; 2] {
        [
            self.base.base[3 * g] + self.store.u[3 * g],
            self.base.base[3 * g + 1] + self.store.u[3 * g + 1],
        ]
    }

    /// Window node `i`'s position from the State.
    fn at_window(&self, i: usize) -> [f64; 2] {
        let g = self.first + i;
        [
            self.base.base[3 * g] + self.state.u[3 * i],
            self.base.base[3 * g + 1] + self.state.u[3 * i + 1],
        ]
    }

    fn mark_positions(&mut self) {
        for i in 0..=self.last - self.first {
            self.moved_from[self.first + i] = self.at_window(i);
        }
    }

    /// The payout rate of the next step of `dt`: the vessel's speed, or the tensioner's rate
    /// moved towards its demand `V + g·(T − T_target)` (explicit: from the last converged tension)
    /// by `dt/τ` of the difference, within ±`max_rate`.
    fn payout_rate(&self, dt: f64) -> f64 {
        match (self.spec.payout, self.target) {
            // A lay-down lowers the pipe's end at the lay's speed, whatever the lay's control.
            _ if self.left_tower.is_some() => self.speed_at(self.state.t + 0.5 * dt),
            (
                Payout::Tension {
                    gain,
                    max_rate,
                    time_constant,
                    ..
                },
                Some(target),
            ) => {
                let demand =
                    self.speed_at(self.state.t + 0.5 * dt) + gain * (self.measured - target);
                let f = (dt / time_constant).min(1.0);
                (self.rate + f * (demand - self.rate)).clamp(-max_rate, max_rate)
            }
            _ => self.speed_at(self.state.t + 0.5 * dt),
        }
    }

    /// The lay's speed at `t`: `V` after the quintic ramp of `[lay] ramp`.
    fn speed_at(&self, t: f64) -> f64 {
        self.spec.speed * catena_fe::motion::quintic_ramp(t, self.spec.ramp).0
    }

    /// The vessel's speed at `t`: the lay's; in a lay-down with `[lay.wire] station = true`,
    /// `V·r((z_e − h)/h)` once the pipe's end has left the tower, with `r` the quintic ramp, `z_e`
    /// the end's height above the mudline in the last converged state (explicit, like the
    /// tensioner's tension) and `h` the station height: the vessel slows as the end comes down
    /// from `2h` to `h` and holds station below `h` until the end rests.
    fn vessel_speed_at(&self, t: f64) -> f64 {
        let v = self.speed_at(t);
        match (self.left_tower, self.spec.lay_down) {
            (Some(_), Some(w))
                if w.station && (self.first..=self.last).contains(&self.pipe_end) =>
            {
                let h = self.station_height;
                let [x, z] = self.at_window(self.pipe_end - self.first);
                let above = z - self.full.mudline_at(x).0;
                v * catena_fe::motion::quintic_ramp(above - h, h).0
            }
            _ => v,
        }
    }

    /// The time reached, s.
    pub fn time(&self) -> f64 {
        self.state.t
    }

    /// Pipe paid out, m.
    pub fn paid_out(&self) -> f64 {
        self.paid
    }

    /// Nodes in the solve.
    pub fn window_nodes(&self) -> usize {
        self.last - self.first + 1
    }

    /// The window's top node now: its material index and its position and angle `(x, z, θ)`, m
    /// and rad.
    pub fn top_node(&self) -> (usize, [f64; 3]) {
        let [x, z] = self.at_window(0);
        let theta = self.base.base[3 * self.first + 2] + self.state.u[2];
        (self.first, [x, z, theta])
    }

    /// How far the vessel has moved along the route, m.
    pub fn vessel_travel(&self) -> f64 {
        self.vessel_x
    }

    /// Steps to `t_end` (or to the end of the lay, `[lay] length`); the reason it stopped early, if
    /// it did.
    pub fn run_until(
        &mut self,
        t_end: f64,
        on_step: &mut dyn FnMut(&LayProgress) -> bool,
    ) -> Result<Option<Stop>, AppError> {
        let dt = self.dspec.dt;
        let duration = self.dspec.duration;
        self.pair_up()?;
        while self.state.t < t_end - 1e-6 * dt {
            if self.spec.length.is_some_and(|len| self.paid >= len - 1e-9) {
                break;
            }
            if let Err(e) = self.step(dt) {
                return Ok(Some(Stop::Failed(e)));
            }
            if let Some((field, node)) = catena_fe::assembly::first_non_finite(
                &self.res,
                &self.state.u,
                &self.state.v,
                &self.state.a,
            ) {
                return Ok(Some(Stop::NonFinite {
                    t: self.state.t,
                    field,
                    node: self.first + node,
                    arc: self.full.arc[self.first + node],
                }));
            }
            self.nodes.observe(
                self.first,
                &self.res,
                1e-3 * self.full.elements[self.pipe_end].contact_od,
            );
            self.check_installation();
            if self.pipe_end_rests() {
                self.rested = Some(self.state.t);
                self.record();
                break;
            }
            if self.state.step % self.dspec.output_every as u64 == 0 {
                self.record();
            }
            self.move_window()?;
            let p = LayProgress {
                t: self.state.t,
                duration,
                paid_out: self.paid,
                window_nodes: self.last - self.first + 1,
            };
            if !on_step(&p) {
                return Ok(Some(Stop::Interrupted("interrupted".into())));
            }
            self.full_steps += 1;
            if let Some((path, every)) = &self.checkpoint_to {
                if self.full_steps % every == 0 {
                    // The whole tangent in the solver's memory (its second side's columns).
                    self.stepping.drive.solver_memory(&mut self.ws);
                    self.checkpoint().write(path)?;
                }
            }
            if self.stop_after == Some(self.full_steps) {
                return Ok(Some(Stop::StoppedAfter(self.full_steps)));
            }
        }
        Ok(None)
    }

    /// The installation check of the step's free span (nothing without a `[design_check]`).
    fn check_installation(&mut self) {
        let Some(c) = self.check.as_mut() else {
            return;
        };
        let span = catena_fe::statics::touchdown_point(&self.res.penetration)
            .map_or(self.res.moment.len(), |(i, _)| i);
        let a_exit = self.full.arc[self.first] + self.d_top / (1.0 + self.eps);
        let (arc, first) = (&self.full.arc, self.first);
        c.observe(
            (self.state.t, first, span),
            &self.res,
            |i| arc[first + i] - a_exit,
            &self.nodes.kp,
        );
    }

    /// Whether the lay-down is over: the pipe's end, off the tower, presses on the seabed with 90 %
    /// of the pipe's submerged weight. Read at the pipe's first node below its end: the end's own
    /// node has the mean of the wire's and the pipe's contact diameters (0.200 m for the 12-inch
    /// pipe on its 76 mm wire), so a pipe end at rest a few centimetres deep does not touch there.
    fn pipe_end_rests(&self) -> bool {
        let w = self.full.elements[self.pipe_end].weight;
        let k = self.pipe_end + 1;
        self.left_tower.is_some()
            && self.pipe_end > self.first
            && (k >= self.last || self.res.seabed_force[k - self.first] >= 0.9 * w)
    }

    /// Moves the window when the top node leaves the tower (the node above it becomes the top) or,
    /// paid in, goes back onto it (the node below it becomes the top), at the thresholds of
    /// [`exit::Top::thresholds`].
    fn move_window(&mut self) -> Result<(), AppError> {
        let l_top = self.full.elements[self.first].l0 * (1.0 + self.eps);
        let top = self.top();
        let (release_at, take_back_at) = top.thresholds(l_top);
        if self.d_top <= release_at {
            if self.first == 0 {
                return Err(AppError::Run {
                    file: self.file.clone(),
                    message: format!(
                        "key `lay.pipe_length`: the pipe's last end left the tower at t = {:.3} s \
                         ({:.3} m paid out); expected a pipe long enough for the lay",
                        self.state.t, self.paid
                    ),
                });
            }
            self.store.keep(self.first, &self.state);
            let last = self.freeze();
            let k = self.first;
            self.eps = self.tension / self.full.elements[k - 1].section.ea;
            let l = self.full.elements[k - 1].l0 * (1.0 + self.eps);
            if k <= self.pipe_end && self.left_tower.is_none() && self.spec.lay_down.is_some() {
                let kp = self
                    .touchdown()
                    .map_or(f64::NAN, |(_, a)| self.full.length() - a);
                self.left_tower = Some((self.state.t, kp));
            }
            self.leave_tower(k, l, top);
            self.d_top += l;
            self.rewindow(k - 1, last)
        } else if self.d_top > take_back_at && self.first + 3 < self.last {
            self.store.keep(self.first, &self.state);
            let k = self.first;
            self.back_onto_tower(k, l_top, top);
            self.d_top -= l_top;
            self.taken_back += 1;
            self.rewindow(k + 1, self.last)
        } else {
            Ok(())
        }
    }

    /// Freezes the nodes at the window's bottom that lie far enough behind the touchdown and have
    /// stopped moving; takes their as-laid embedment; the window's new last node.
    fn freeze(&mut self) -> usize {
        let Some((i_td, _)) = catena_fe::statics::touchdown_point(&self.res.penetration) else {
            return self.last;
        };
        let x_td = self.at(self.first + i_td)[0];
        let mut last = self.last;
        let lowest = (self.first + i_td + 2).max(self.first + 4);
        let mut g = self.last;
        while g > lowest {
            g -= 1;
            let p = self.at(g);
            let m = self.moved_from[g];
            let moved = (p[0] - m[0]).hypot(p[1] - m[1]);
            let still = moved < self.spec.freeze_tolerance; // false for a NaN (a node new to the window)
            if p[0] > x_td - self.spec.freeze_behind || !still {
                break;
            }
            last = g;
        }
        for g in last..self.last {
            let h = self.store.history[g];
            self.nodes.lay(&self.full, g, self.at(g).into(), &h);
        }
        last
    }

    /// Makes the window `first..=last` from the store.
    fn rewindow(&mut self, first: usize, last: usize) -> Result<(), AppError> {
        self.unpair();
        let grid = self.state.wave_grid.take();
        let old_first = self.first;
        let mut state = self.store.window_state(
            (first, last),
            (self.state.t, self.state.step),
            grid.as_ref().map(|g| (old_first, g)),
        );
        let top_l0 = self.top_rest_length(first);
        let dm = window::model(
            &self.full,
            &self.base,
            (first, last, top_l0),
            (self.spec.tower, self.theta, first < self.pipe_end),
            &self.dspec,
        );
        let n = last - first + 1;
        let ws = window::workspace(&dm, &mut state, &[0, 1, 2, n - 1]).map_err(|source| {
            AppError::Solver {
                file: self.file.clone(),
                source,
            }
        })?;
        (self.first, self.last) = (first, last);
        self.dm = Arc::new(dm);
        self.ws = ws;
        self.state = state;
        self.res = LineResults::new(n);
        dynamics::results(&self.dm, &self.state, &self.ws, &mut self.res);
        self.res.tension[0] = self.tension;
        self.windows += 1;
        self.mark_positions();
        self.pair_up()
    }

    /// The touchdown point in the window: `(x, arc from the pipe's last end)`, interpolated
    /// where the penetration crosses zero ([`catena_fe::statics::touchdown_point`]).
    fn touchdown(&self) -> Option<(f64, f64)> {
        let (i, f) = catena_fe::statics::touchdown_point(&self.res.penetration)?;
        let (a, b) = (self.at_window(i - 1)[0], self.at_window(i)[0]);
        let arc = &self.full.arc;
        let g = self.first + i;
        Some((a + f * (b - a), arc[g - 1] + f * (arc[g] - arc[g - 1])))
    }

    fn record(&mut self) {
        let td = self.touchdown();
        let a_exit = self.full.arc[self.first] + self.d_top / (1.0 + self.eps);
        let td_x = td.map_or(f64::NAN, |p| p.0);
        let r = &mut self.records;
        r.time.push(self.state.t);
        r.paid_out.push(self.paid);
        r.vessel_x.push(self.vessel_x);
        r.top_tension.push(self.tension);
        r.payout_rate.push(self.rate);
        r.touchdown_x.push(td_x);
        r.touchdown_arc.push(td.map_or(f64::NAN, |p| p.1 - a_exit));
        r.window_nodes.push((self.last - self.first + 1) as f64);
        let n = self.res.moment.len();
        let sag = self.res.moment[1..n - 1]
            .iter()
            .fold(0.0f64, |m, &x| m.min(x));
        r.sag_moment.push(sag);
        let k = r.time.len() - 1;
        self.frame(k);
    }

    /// The end: the window's State into the store, and the as-laid embedment of the nodes that lie
    /// far enough behind the touchdown but were not frozen.
    fn finish(&mut self) {
        self.store.keep(self.first, &self.state);
        if self.rested.is_some() {
            // The lay-down's end: every node of the pipe in contact is at rest, and the pipe's end
            // (whose node's own contact diameter, the wire's and the pipe's mean, may not touch).
            for g in self.pipe_end.max(self.first)..self.last {
                let touches = g == self.pipe_end || self.res.penetration[g - self.first] > 0.0;
                if touches && self.nodes.as_laid[g].is_nan() {
                    let h = self.store.history[g];
                    self.nodes.lay(&self.full, g, self.at(g).into(), &h);
                }
            }
        }
        let Some((i_td, _)) = catena_fe::statics::touchdown_point(&self.res.penetration) else {
            return;
        };
        let x_td = self.at(self.first + i_td)[0];
        for g in self.first + i_td..self.last {
            let p = self.at(g);
            if p[0] <= x_td - self.spec.freeze_behind && self.nodes.as_laid[g].is_nan() {
                let h = self.store.history[g];
                self.nodes.lay(&self.full, g, p.into(), &h);
            }
        }
    }

    fn positions(&self) -> Vec<[f64; 2]> {
        (0..self.full.nodes()).map(|g| self.at(g)).collect()
    }
}
