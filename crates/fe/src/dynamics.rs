//! Implicit dynamics: HHT-α (Hilber–Hughes–Taylor) and Newmark time integration with Newton
//! iterations in each step, lumped inertia with normal added mass, Morison drag, the hysteretic seabed
//! committed once per converged step, prescribed top-end motion, and automatic step cutting.
//!
//! **Convention (Hilber 1977).** `α ∈ [−1/3, 0]`, `β = (1 − α)²/4`, `γ = 1/2 − α`; `α = 0` is the
//! trapezoidal rule (Newmark β = 1/4, γ = 1/2). The equations of step `n → n+1` are
//!
//! ```text
//! M a_{n+1} + (1 + α) F(u_{n+1}, v_{n+1}) − α F(u_n, v_n) = 0
//! u_{n+1} = u_n + Δt v_n + Δt² [(1/2 − β) a_n + β a_{n+1}]
//! v_{n+1} = v_n + Δt [(1 − γ) a_n + γ a_{n+1}]
//! ```
//!
//! where `F` collects every non-inertial force (elements, flexjoint, weight, seabed, drag, seabed
//! damping) as "internal minus external". `F_n` is kept in the State, so the step is exactly
//! reproducible after a restart. The Newton Jacobian is `M/(βΔt²) + (1 + α)(K + γ/(βΔt)·C)`.
//! The spectral radius at infinite frequency is `(1 + α)/(1 − α)`. The first Newton iteration of a
//! step reuses the Jacobian factorised last (same Δt) — a modified-Newton start that saves one
//! factorisation per step; the following iterations are full Newton, so the converged answer is the
//! same.
//!
//! **Predictor.** A step starts from the constant-acceleration predictor `u_n + Δt v_n + Δt²/2 a_n`.
//! If Newton diverges from it, the same step is tried once more from the constant-velocity predictor
//! `u_n + Δt v_n` (a *predictor retry*) before the step is cut. After a step in the top-end velocity
//! the first free node next to the top rings at `ωΔt ≫ 1` (very short, stiff elements), and its
//! acceleration, carried into the constant-acceleration predictor, can fold the first elements;
//! the velocity is far smaller at such frequencies, so the second predictor is a physical shape.
//! (Watchet with 0.0625 m elements: 7 cuts before, 0 cuts and 7 retries now.)
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
//! over their tributary lengths, like weight and mass. Its velocity
//! derivative enters `C`; its dependence on the orientation is left out of the Jacobian.
//!
//! **Seabed.** Each node's trial is evaluated from its committed history (pure); the histories are
//! replaced by the trials' `next` only when the step converges. A failed attempt leaves the State
//! untouched, and the step is retried with `Δt/2` (up to `max_cuts` times).
//!
//! **Convergence.** `‖G‖ ≤ tol·‖F_weight‖ + 10·ε·√(Σₑ (EAₑ(1 + U/L0ₑ))²)` on the free equations, U the
//! largest displacement from the base (the second term is the rounding floor of the axial forces), or a relative residual below 1e-6 with a correction below
//! 1e-10 m (machine-precision stagnation).

use catena_seabed::law::SeabedHistory;
use serde::{Deserialize, Serialize};

use crate::model::LineModel;
use crate::sparse::SolveError;
use crate::statics::{Placement, StaticWorkspace};

/// The time integration scheme.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Scheme {
    /// HHT-α with `α ∈ [−1/3, 0]` (Hilber's convention).
    Hht {
        /// α.
        alpha: f64,
    },
    /// Newmark with its own β and γ (no force averaging).
    Newmark {
        /// β.
        beta: f64,
        /// γ.
        gamma: f64,
    },
}

impl Scheme {
    /// `(α, β, γ)`.
    pub fn coefficients(&self) -> (f64, f64, f64) {
        match *self {
            Scheme::Hht { alpha } => (alpha, (1.0 - alpha).powi(2) / 4.0, 0.5 - alpha),
            Scheme::Newmark { beta, gamma } => (0.0, beta, gamma),
        }
    }
}

/// Hydrodynamic coefficients and the current.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Hydro {
    /// Sea water density, kg/m³.
    pub water_density: f64,
    /// Normal drag coefficient.
    pub cd_normal: f64,
    /// Axial drag coefficient (on the area πD per length).
    pub cd_axial: f64,
    /// Normal added-mass coefficient.
    pub ca_normal: f64,
    /// Current profile `(z, U_x)`, sorted by z (empty for none); linear in between, constant beyond.
    pub current: Vec<(f64, f64)>,
}

impl Hydro {
    /// The current speed (along +x) at height z, m/s.
    pub fn current_at(&self, z: f64) -> f64 {
        let c = &self.current;
        match c.len() {
            0 => 0.0,
            1 => c[0].1,
            _ => {
                if z <= c[0].0 {
                    return c[0].1;
                }
                for w in c.windows(2) {
                    if z <= w[1].0 {
                        let f = (z - w[0].0) / (w[1].0 - w[0].0);
                        return w[0].1 + f * (w[1].1 - w[0].1);
                    }
                }
                c[c.len() - 1].1
            }
        }
    }
}

/// Prescribed motion of the top end, relative to its static position.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum TopMotion {
    /// Constant velocities for successive durations `(duration s, vx m/s, vz m/s)`; still afterwards.
    Staged(Vec<(f64, f64, f64)>),
    /// `x = Ax·r(t)·sin(ωt + φ)`, `z = Az·r(t)·sin(ωt + φ)`, with the quintic ramp
    /// `r = σ³(10 − 15σ + 6σ²)`, `σ = min(t/T_ramp, 1)` (no ramp if `T_ramp = 0`).
    Harmonic {
        /// Surge amplitude, m.
        surge: f64,
        /// Heave amplitude, m.
        heave: f64,
        /// Period, s.
        period: f64,
        /// Phase, rad.
        phase: f64,
        /// Ramp duration, s.
        ramp: f64,
    },
    /// A time series `(t, dx, dz)`, linear in between (velocity piecewise constant, acceleration 0);
    /// held at its ends.
    Series(Vec<(f64, f64, f64)>),
}

/// Displacement, velocity and acceleration of a prescribed motion, `[x, z]` each.
pub type Kinematics = ([f64; 2], [f64; 2], [f64; 2]);

/// The quintic ramp and its first two time derivatives.
pub fn quintic_ramp(t: f64, duration: f64) -> (f64, f64, f64) {
    if duration <= 0.0 || t >= duration {
        return (1.0, 0.0, 0.0);
    }
    if t <= 0.0 {
        return (0.0, 0.0, 0.0);
    }
    let s = t / duration;
    let r = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
    let dr = 30.0 * s * s * (1.0 - s) * (1.0 - s) / duration;
    let ddr = 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s) / (duration * duration);
    (r, dr, ddr)
}

impl TopMotion {
    /// The motion at time t.
    pub fn at(&self, t: f64) -> Kinematics {
        match self {
            TopMotion::Staged(stages) => {
                let mut d = [0.0; 2];
                let mut t0 = 0.0;
                for &(dur, vx, vz) in stages {
                    if t < t0 + dur {
                        let tau = (t - t0).max(0.0);
                        return ([d[0] + vx * tau, d[1] + vz * tau], [vx, vz], [0.0; 2]);
                    }
                    d[0] += vx * dur;
                    d[1] += vz * dur;
                    t0 += dur;
                }
                (d, [0.0; 2], [0.0; 2])
            }
            TopMotion::Harmonic {
                surge,
                heave,
                period,
                phase,
                ramp,
            } => {
                let w = std::f64::consts::TAU / period;
                let (r, dr, ddr) = quintic_ramp(t, *ramp);
                let (s, c) = (w * t + phase).sin_cos();
                let f = r * s;
                let df = dr * s + r * w * c;
                let ddf = ddr * s + 2.0 * dr * w * c - r * w * w * s;
                (
                    [surge * f, heave * f],
                    [surge * df, heave * df],
                    [surge * ddf, heave * ddf],
                )
            }
            TopMotion::Series(pts) => {
                if pts.is_empty() {
                    return ([0.0; 2], [0.0; 2], [0.0; 2]);
                }
                if t <= pts[0].0 {
                    return ([pts[0].1, pts[0].2], [0.0; 2], [0.0; 2]);
                }
                for w in pts.windows(2) {
                    if t < w[1].0 {
                        let h = w[1].0 - w[0].0;
                        let f = (t - w[0].0) / h;
                        let vx = (w[1].1 - w[0].1) / h;
                        let vz = (w[1].2 - w[0].2) / h;
                        return (
                            [
                                w[0].1 + f * (w[1].1 - w[0].1),
                                w[0].2 + f * (w[1].2 - w[0].2),
                            ],
                            [vx, vz],
                            [0.0; 2],
                        );
                    }
                }
                let l = pts[pts.len() - 1];
                ([l.1, l.2], [0.0; 2], [0.0; 2])
            }
        }
    }
}

/// Settings of a dynamic run (part of the Model).
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicSettings {
    /// The scheme.
    pub scheme: Scheme,
    /// Hydrodynamics, if the scene has them.
    pub hydro: Option<Hydro>,
    /// Top-end motion, if any.
    pub motion: Option<TopMotion>,
    /// Relative residual tolerance (on `‖F_weight‖`).
    pub tol: f64,
    /// Newton iterations per attempt.
    pub max_iter: usize,
    /// Step cuts (halvings) allowed before giving up.
    pub max_cuts: u32,
}

/// Everything a restart needs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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
}

/// Scratch for the dynamics (never saved).
#[derive(Debug)]
pub struct DynWorkspace {
    /// The structural workspace (pattern, factorisation, element results).
    pub st: StaticWorkspace,
    /// Lumped mass per node: `[xx, xz, zz, rot]`.
    mass: Vec<[f64; 4]>,
    /// Non-inertial forces at the trial, 3 per node.
    pub f: Vec<f64>,
    /// The trial histories (committed on convergence).
    pub next: Vec<SeabedHistory>,
    /// Seabed force (resistance plus buoyancy) per unit length at the trial, per node.
    pub seabed_force: Vec<f64>,
    g: Vec<f64>,
    dq: Vec<f64>,
    u: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    /// The Δt of the Jacobian factorised last (its factorisation is reused for the first iteration
    /// of the next step of the same Δt).
    factored_dt: Option<f64>,
}

impl DynWorkspace {
    /// Builds the workspace (pattern and symbolic factorisation once).
    pub fn new(model: &LineModel) -> Result<Self, SolveError> {
        let n = model.nodes();
        Ok(Self {
            st: StaticWorkspace::new(model)?,
            mass: vec![[0.0; 4]; n],
            f: vec![0.0; 3 * n],
            next: vec![
                model
                    .seabed
                    .as_ref()
                    .map_or(SeabedHistory::Linear(Default::default()), |s| s
                        .seabed
                        .untouched());
                n
            ],
            seabed_force: vec![0.0; n],
            g: vec![0.0; model.n_eq],
            dq: vec![0.0; model.n_eq],
            u: vec![0.0; 3 * n],
            v: vec![0.0; 3 * n],
            a: vec![0.0; 3 * n],
            factored_dt: None,
        })
    }
}

impl DynWorkspace {
    /// Drops the factorisation kept for reuse: the next step starts with a full Newton iteration.
    /// Done at checkpoints, so that a run restored from one (whose new workspace has nothing to
    /// reuse) continues bit-for-bit like the uninterrupted run.
    pub fn forget_factorisation(&mut self) {
        self.factored_dt = None;
    }
}

/// The penetration of node `i` and its rate (positive down).
#[inline]
fn penetration(
    model: &LineModel,
    pl: &Placement,
    u: &[f64],
    v: &[f64],
    i: usize,
) -> Option<(f64, f64)> {
    model.seabed.as_ref().map(|sb| {
        (
            sb.mudline_z - (pl.base[3 * i + 1] + u[3 * i + 1] - 0.5 * model.node_od[i]),
            -v[3 * i + 1],
        )
    })
}

/// The dynamic State at the end of the statics: at rest, each node in contact starting in Initial
/// Penetration at its static penetration (the spec's decision). The initial acceleration is the
/// lumped `a0 = −M⁻¹F(u, 0)` on the free dofs (zero from a static equilibrium).
pub fn initial_state(
    model: &LineModel,
    pl: &Placement,
    hydro: Option<&Hydro>,
    u: &[f64],
    ws: &mut DynWorkspace,
) -> DynState {
    let n = model.nodes();
    let v = vec![0.0; 3 * n];
    let history: Vec<SeabedHistory> = (0..n)
        .map(
            |i| match (model.seabed.as_ref(), penetration(model, pl, u, &v, i)) {
                (Some(sb), Some((z, _))) => sb.seabed.start_of_dynamics(z),
                (Some(sb), None) => sb.seabed.untouched(),
                _ => SeabedHistory::Linear(Default::default()),
            },
        )
        .collect();
    ws.factored_dt = None;
    let mut state = DynState {
        t: 0.0,
        step: 0,
        u: u.to_vec(),
        v: v.clone(),
        a: v,
        f_prev: vec![0.0; 3 * n],
        history,
    };
    forces(
        model,
        pl,
        hydro,
        &state.u.clone(),
        &state.v.clone(),
        &state.history,
        ws,
        false,
        0.0,
        0.0,
        0.0,
    );
    state.f_prev.copy_from_slice(&ws.f);
    ws.next.copy_from_slice(&state.history);
    lump_mass(model, pl, hydro, &state.u, &mut ws.mass);
    for i in 0..n {
        let m = ws.mass[i];
        let (fx, fz, fr) = (ws.f[3 * i], ws.f[3 * i + 1], ws.f[3 * i + 2]);
        let det = m[0] * m[2] - m[1] * m[1];
        if det > 0.0 {
            let ax = -(m[2] * fx - m[1] * fz) / det;
            let az = -(m[0] * fz - m[1] * fx) / det;
            if model.equation[3 * i].is_some() {
                state.a[3 * i] = ax;
            }
            if model.equation[3 * i + 1].is_some() {
                state.a[3 * i + 1] = az;
            }
        }
        if m[3] > 0.0 && model.equation[3 * i + 2].is_some() {
            state.a[3 * i + 2] = -fr / m[3];
        }
    }
    state
}

#[allow(clippy::needless_range_loop)]
/// Assembles the non-inertial forces `F(u, v)` into `ws.f` (and the trial histories into `ws.next`);
/// with `with_k`, also `(1+α)(K + c_v·C)` into the tangent (scaled by `k_scale = 1 + α`).
#[allow(clippy::too_many_arguments)]
fn forces(
    model: &LineModel,
    pl: &Placement,
    hydro: Option<&Hydro>,
    u: &[f64],
    v: &[f64],
    committed: &[SeabedHistory],
    ws: &mut DynWorkspace,
    with_k: bool,
    k_scale: f64,
    c_v: f64,
    dt: f64,
) {
    ws.st.assemble_structure(model, pl, u, with_k);
    if with_k {
        ws.st.scale_tangent(k_scale);
    }
    let n = model.nodes();
    if let Some(sb) = &model.seabed {
        for i in 0..n {
            let (z, zdot) = penetration(model, pl, u, v, i).unwrap_or((0.0, 0.0));
            let t = sb.seabed.evaluate(&committed[i], z, zdot, dt);
            ws.next[i] = t.next;
            let l = model.tributary[i];
            let up = t.total();
            let mut k = t.tangent;
            let mut c = t.damping_coefficient;
            ws.seabed_force[i] = up;
            ws.st.residual[3 * i + 1] -= l * up;
            if with_k && (k != 0.0 || c != 0.0) {
                // z_pen = const − z, ż_pen = −v_z: d(−L·F)/dz = L·F', d(−L·F)/dv_z = L·c.
                k *= l;
                c *= l;
                ws.st
                    .add_dof_tangent(model, 3 * i + 1, k_scale * (k + c_v * c));
            }
        }
    }
    if let Some(h) = hydro {
        let kn0 = 0.5 * h.water_density * h.cd_normal;
        let ka0 = 0.5 * h.water_density * h.cd_axial * std::f64::consts::PI;
        for i in 0..n {
            let l = model.tributary[i];
            let d = model.node_od[i];
            let th = pl.base[3 * i + 2] + u[3 * i + 2];
            let (ty, tx) = th.sin_cos();
            let z = pl.base[3 * i + 1] + u[3 * i + 1];
            let rx = h.current_at(z) - v[3 * i];
            let rz = -v[3 * i + 1];
            let s = rx * tx + rz * ty;
            let (nx, nz) = (rx - s * tx, rz - s * ty);
            let vn = (nx * nx + nz * nz).sqrt();
            let kn = kn0 * d * l;
            let ka = ka0 * d * l;
            let fx = kn * vn * nx + ka * s.abs() * s * tx;
            let fz = kn * vn * nz + ka * s.abs() * s * ty;
            ws.st.residual[3 * i] -= fx;
            ws.st.residual[3 * i + 1] -= fz;
            if with_k {
                // C = kn (|v_n| P + v_n v_nᵀ/|v_n|) + 2 ka |s| t tᵀ, P = I − t tᵀ.
                let mut cxx = 2.0 * ka * s.abs() * tx * tx;
                let mut cxz = 2.0 * ka * s.abs() * tx * ty;
                let mut czz = 2.0 * ka * s.abs() * ty * ty;
                if vn > 0.0 {
                    cxx += kn * (vn * (1.0 - tx * tx) + nx * nx / vn);
                    cxz += kn * (-vn * tx * ty + nx * nz / vn);
                    czz += kn * (vn * (1.0 - ty * ty) + nz * nz / vn);
                }
                let f = k_scale * c_v;
                ws.st.add_node_block(model, i, f * cxx, f * cxz, f * czz);
            }
        }
    }
    ws.f.copy_from_slice(&ws.st.residual);
}

/// Lumped mass at the orientation `u` (added mass normal to the tangent there).
fn lump_mass(
    model: &LineModel,
    pl: &Placement,
    hydro: Option<&Hydro>,
    u: &[f64],
    mass: &mut [[f64; 4]],
) {
    for m in mass.iter_mut() {
        *m = [0.0; 4];
    }
    for (e, el) in model.elements.iter().enumerate() {
        let half = 0.5 * el.mass * el.l0;
        for i in [e, e + 1] {
            mass[i][0] += half;
            mass[i][2] += half;
            mass[i][3] += half * el.od * el.od / 8.0;
        }
    }
    if let Some(h) = hydro {
        for (i, m) in mass.iter_mut().enumerate() {
            let d = model.node_od[i];
            let ma = h.ca_normal * h.water_density * std::f64::consts::PI * d * d / 4.0
                * model.tributary[i];
            let th = pl.base[3 * i + 2] + u[3 * i + 2];
            let (ty, tx) = th.sin_cos();
            m[0] += ma * (1.0 - tx * tx);
            m[1] += -ma * tx * ty;
            m[2] += ma * (1.0 - ty * ty);
        }
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
/// One attempt at a step of `dt` from `state`. On success the State is advanced (histories
/// committed); on failure it is untouched and the error carries the last iterate's residual.
fn attempt(
    model: &LineModel,
    pl: &Placement,
    set: &DynamicSettings,
    state: &mut DynState,
    ws: &mut DynWorkspace,
    dt: f64,
    refn: f64,
    noise: f64,
    careful: bool,
    iterations: &mut usize,
) -> Result<(), Failed> {
    let (alpha, beta, gamma) = set.scheme.coefficients();
    let hydro = set.hydro.as_ref();
    let t1 = state.t + dt;
    let n = model.nodes();
    lump_mass(model, pl, hydro, &state.u, &mut ws.mass);
    // Predictor: constant acceleration, or constant velocity when `careful` (a retry).
    let c_pred = if careful { 0.0 } else { 0.5 * dt * dt };
    for g in 0..3 * n {
        ws.u[g] = state.u[g] + dt * state.v[g] + c_pred * state.a[g];
    }
    let prescribed = set.motion.as_ref().map(|m| m.at(t1));
    let c_m = 1.0 / (beta * dt * dt);
    let c_v = gamma / (beta * dt);
    let mut last = (0, f64::INFINITY, 0);
    let mut first = f64::INFINITY;
    for it in 0..set.max_iter {
        // Kinematics from the Newmark relations; prescribed dofs from the motion.
        newmark_kinematics(model, state, ws, dt, beta, gamma);
        for g in 0..3 * n {
            if model.equation[g].is_none() {
                let node = g / 3;
                let k = g % 3;
                match (&prescribed, node == 0 && k < 2) {
                    (Some((d, v, a)), true) => {
                        ws.u[g] = d[k];
                        ws.v[g] = v[k];
                        ws.a[g] = a[k];
                    }
                    _ => {
                        ws.u[g] = state.u[g];
                        ws.v[g] = 0.0;
                        ws.a[g] = 0.0;
                    }
                }
            }
        }
        // The first iteration reuses the last factorised Jacobian (same Δt): one factorisation per
        // step instead of two; later iterations are full Newton.
        let reuse = it == 0 && ws.factored_dt == Some(dt);
        forces_at_iterate(
            model,
            pl,
            hydro,
            &state.history,
            ws,
            !reuse,
            1.0 + alpha,
            c_v,
            dt,
        );
        // Residual G = M a + (1+α) F − α F_n on the free equations.
        for i in 0..n {
            let m = ws.mass[i];
            let (ax, az, ar) = (ws.a[3 * i], ws.a[3 * i + 1], ws.a[3 * i + 2]);
            let inertia = [m[0] * ax + m[1] * az, m[1] * ax + m[2] * az, m[3] * ar];
            for k in 0..3 {
                let g = 3 * i + k;
                if let Some(e) = model.equation[g] {
                    ws.g[e] = inertia[k] + (1.0 + alpha) * ws.f[g] - alpha * state.f_prev[g];
                }
            }
            if !reuse {
                ws.st
                    .add_node_block(model, i, c_m * m[0], c_m * m[1], c_m * m[2]);
                ws.st.add_dof_tangent(model, 3 * i + 2, c_m * m[3]);
            }
        }
        let r = norm(&ws.g) / refn;
        let worst =
            ws.g.iter()
                .enumerate()
                .fold(
                    (0.0, 0),
                    |b, (e, x)| if x.abs() > b.0 { (x.abs(), e) } else { b },
                )
                .1;
        let node = model
            .equation
            .iter()
            .position(|e| *e == Some(worst))
            .map_or(0, |g| g / 3);
        last = (it, r, node);
        if it == 0 {
            first = r;
        }
        // Diverging (the residual 10⁴ times its start): give up at once, retry or cut.
        if !r.is_finite() || (it >= 2 && r > 1e4 * first) {
            return Err(Failed {
                last,
                diverged: true,
            });
        }
        if r <= set.tol + noise {
            commit(state, ws, t1);
            return Ok(());
        }
        *iterations += 1;
        if !reuse {
            if ws.st.factor_tangent().is_err() {
                // `advance` drops the factorisation of every failed attempt.
                break;
            }
            ws.factored_dt = Some(dt);
        }
        ws.dq.copy_from_slice(&ws.g);
        let mut dq = std::mem::take(&mut ws.dq);
        ws.st.solve_tangent(&mut dq);
        let step = dq.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (g, e) in model.equation.iter().enumerate() {
            if let Some(i) = e {
                ws.u[g] -= dq[*i];
            }
        }
        ws.dq = dq;
        if r <= 1e-6 && step <= 1e-10 {
            // Converged to machine precision: re-evaluate at the final iterate and commit.
            newmark_kinematics(model, state, ws, dt, beta, gamma);
            forces_at_iterate(
                model,
                pl,
                hydro,
                &state.history,
                ws,
                false,
                1.0 + alpha,
                c_v,
                dt,
            );
            commit(state, ws, t1);
            return Ok(());
        }
    }
    Err(Failed {
        last,
        diverged: false,
    })
}

/// A failed attempt: the last iterate's (iteration, relative residual, worst node), and whether
/// Newton diverged (rather than failing to converge in `max_iter`).
struct Failed {
    last: (usize, f64, usize),
    diverged: bool,
}

/// The rounding floor of the residual (N): `10·ε·√(Σₑ (EAₑ·(1 + U/L0ₑ))²)` with `U` the largest
/// translational displacement from the base configuration. An element's axial force is EA times a
/// strain computed from a chord `base + (uⱼ − uᵢ)` whose rounding is about `ε·U`, so the force is
/// known to about `EA·ε·(1 + U/L0)`, and no iteration can bring the residual below that. The step
/// converges when `‖G‖ ≤ tol·‖F_weight‖ + floor`. (Without the `U/L0` term the floor was too low
/// for short elements far from the base: Watchet with 0.0625 m elements stalled at a relative
/// residual of 1.05e-6 with the worst node wandering along the line.)
pub fn residual_floor(model: &LineModel, u: &[f64]) -> f64 {
    let big = u
        .chunks_exact(3)
        .fold(0.0f64, |m, c| m.max(c[0].abs()).max(c[1].abs()));
    10.0 * f64::EPSILON
        * model
            .elements
            .iter()
            .map(|e| (e.section.ea * (1.0 + big / e.l0)).powi(2))
            .sum::<f64>()
            .sqrt()
}

/// [`forces`] at the workspace's current iterate `(ws.u, ws.v)`.
#[allow(clippy::too_many_arguments)]
fn forces_at_iterate(
    model: &LineModel,
    pl: &Placement,
    hydro: Option<&Hydro>,
    committed: &[SeabedHistory],
    ws: &mut DynWorkspace,
    with_k: bool,
    k_scale: f64,
    c_v: f64,
    dt: f64,
) {
    let (u, v) = (std::mem::take(&mut ws.u), std::mem::take(&mut ws.v));
    forces(
        model, pl, hydro, &u, &v, committed, ws, with_k, k_scale, c_v, dt,
    );
    ws.u = u;
    ws.v = v;
}

/// `a_{n+1}` and `v_{n+1}` on the free dofs from the iterate `u_{n+1}` (the Newmark relations).
fn newmark_kinematics(
    model: &LineModel,
    state: &DynState,
    ws: &mut DynWorkspace,
    dt: f64,
    beta: f64,
    gamma: f64,
) {
    let c_m = 1.0 / (beta * dt * dt);
    for (g, e) in model.equation.iter().enumerate() {
        if e.is_some() {
            ws.a[g] =
                c_m * (ws.u[g] - state.u[g] - dt * state.v[g]) - (0.5 / beta - 1.0) * state.a[g];
            ws.v[g] = state.v[g] + dt * ((1.0 - gamma) * state.a[g] + gamma * ws.a[g]);
        }
    }
}

fn commit(state: &mut DynState, ws: &DynWorkspace, t1: f64) {
    state.u.copy_from_slice(&ws.u);
    state.v.copy_from_slice(&ws.v);
    state.a.copy_from_slice(&ws.a);
    state.f_prev.copy_from_slice(&ws.f);
    state.history.copy_from_slice(&ws.next);
    state.t = t1;
    state.step += 1;
}

/// Advances the State by `dt`. When Newton diverges, the attempt is repeated once from the
/// constant-velocity predictor, then the step is cut (halving, up to `max_cuts` times),
/// and sub-stepping back up to the full `dt`. On failure the State is left at the last converged
/// sub-step.
pub fn advance(
    model: &LineModel,
    pl: &Placement,
    set: &DynamicSettings,
    state: &mut DynState,
    ws: &mut DynWorkspace,
    dt: f64,
) -> Result<StepInfo, StepError> {
    let refn = crate::statics::residual_reference(model);
    let noise = residual_floor(model, &state.u) / refn;
    let target = state.t + dt;
    let mut info = StepInfo::default();
    let mut h = dt;
    let mut level = 0u32;
    let mut careful = false;
    while target - state.t > 1e-9 * dt {
        let h_try = h.min(target - state.t);
        match attempt(
            model,
            pl,
            set,
            state,
            ws,
            h_try,
            refn,
            noise,
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
                if level >= set.max_cuts {
                    return Err(StepError::NotConverged {
                        t: state.t + h_try,
                        step: state.step + 1,
                        dt: h_try,
                        cuts: info.cuts,
                        iteration,
                        residual,
                        node,
                        arc: model.arc[node],
                    });
                }
                level += 1;
                info.cuts += 1;
                h *= 0.5;
            }
        }
    }
    state.t = target;
    Ok(info)
}

/// HHT-α on one degree of freedom `m ü + k u = 0` (the same coefficients as [`advance`]): returns the
/// displacement after `steps` steps. Used to check the scheme against cases.md §5.
pub fn sdof_free_vibration(
    scheme: Scheme,
    omega: f64,
    u0: f64,
    v0: f64,
    dt: f64,
    steps: usize,
) -> f64 {
    let (alpha, beta, gamma) = scheme.coefficients();
    let k = omega * omega;
    let (mut u, mut v) = (u0, v0);
    let mut a = -k * u;
    for _ in 0..steps {
        // m a1 + (1+α) k u1 − α k u = 0, u1 = u + dt v + dt²((1/2−β) a + β a1).
        let up = u + dt * v + dt * dt * (0.5 - beta) * a;
        let a1 =
            -((1.0 + alpha) * k * up - alpha * k * u) / (1.0 + (1.0 + alpha) * k * beta * dt * dt);
        let u1 = up + beta * dt * dt * a1;
        let v1 = v + dt * ((1.0 - gamma) * a + gamma * a1);
        (u, v, a) = (u1, v1, a1);
    }
    u
}

/// Nodal results of a converged dynamic state (preallocated; refilled without allocating).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Snapshot {
    /// x, m.
    pub x: Vec<f64>,
    /// z, m.
    pub z: Vec<f64>,
    /// Effective tension, N (end nodes: the support reaction's magnitude, inertia included).
    pub tension: Vec<f64>,
    /// Bending moment, N·m (negative = sag).
    pub moment: Vec<f64>,
    /// Invert penetration, m (positive down).
    pub penetration: Vec<f64>,
    /// Seabed force per unit length (resistance, buoyancy and damping), N/m.
    pub seabed_force: Vec<f64>,
    /// Contact mode code (0 not in contact, 1 initial penetration, 2 uplift, 3 repenetration).
    pub mode: Vec<u8>,
}

impl Snapshot {
    /// A snapshot for `n` nodes.
    pub fn new(n: usize) -> Self {
        Self {
            x: vec![0.0; n],
            z: vec![0.0; n],
            tension: vec![0.0; n],
            moment: vec![0.0; n],
            penetration: vec![0.0; n],
            seabed_force: vec![0.0; n],
            mode: vec![0; n],
        }
    }
}

/// Fills `out` from the State just committed by [`advance`] (the workspace still holds the
/// converged evaluation).
pub fn snapshot(
    model: &LineModel,
    pl: &Placement,
    state: &DynState,
    ws: &DynWorkspace,
    out: &mut Snapshot,
) {
    let n = model.nodes();
    for i in 0..n {
        out.x[i] = pl.base[3 * i] + state.u[3 * i];
        out.z[i] = pl.base[3 * i + 1] + state.u[3 * i + 1];
        (out.tension[i], out.moment[i]) = ws.st.nodal_tension_moment(i);
        out.penetration[i] = penetration(model, pl, &state.u, &state.v, i).map_or(0.0, |p| p.0);
        out.seabed_force[i] = if model.seabed.is_some() {
            ws.seabed_force[i]
        } else {
            0.0
        };
        out.mode[i] = state.history[i].mode().code();
    }
    for i in [0, n - 1] {
        let m = ws.mass[i];
        let (ax, az) = (state.a[3 * i], state.a[3 * i + 1]);
        let rx = m[0] * ax + m[1] * az + state.f_prev[3 * i];
        let rz = m[1] * ax + m[2] * az + state.f_prev[3 * i + 1];
        out.tension[i] = (rx * rx + rz * rz).sqrt();
    }
}
