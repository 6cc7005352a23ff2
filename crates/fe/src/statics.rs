//! The static solve: Newton–Raphson with a backtracking line search and residual-homotopy load
//! continuation, from a catenary seed, with the seabed in initial-penetration mode only.
//!
//! **Equations.** With `q` the nodal values, the residual on every global dof is
//!
//! ```text
//! R(q) = Σ_e f_e(q)  +  k_θ (θ_fj − θ_n) e_fj  −  F_dead  −  Σ_i L_i·F_sb(z_pen,i) e_{z,i}
//! ```
//!
//! (element internal forces, flexjoint, submerged weight, seabed reaction `F_sb = P_IP + F_b` over the
//! tributary length `L_i`). Its tangent `K = ∂R/∂q` is symmetric.
//!
//! **Continuation.** Let `R0 = R(q_seed)`. For the load factor `λ ∈ [0, 1]` solve
//! `G(q; λ) = R(q) − (1 − λ) R0 = 0`: at `λ = 0` the seed is the solution, at `λ = 1` the true
//! equilibrium. The solver first tries `λ = 1` directly; if Newton fails, it halves the increment
//! (down to 2⁻¹⁰) and doubles it again after successes.
//!
//! **Convergence.** `‖G‖₂ / ‖F_dead‖₂ ≤ tol` (default 1e-9) over the free equations (moments are in
//! N·m; the meshes used here have elements of order 1 m, so the mix of units is benign); or, where
//! rounding forbids that (axial forces resolve only to `EA·ε` per element), a relative residual below
//! 1e-6 with a Newton correction below 1e-10 m (or rad).
//!
//! **Line search** (Crisfield's energy criterion). Along the Newton direction `Δq`, the slope
//! `s(α) = Δq·G(q − αΔq)` starts at `s(0) = Δq·K·Δq`; step lengths 1, ½, …, 1/64 are tried and the
//! first with `|s(α)| ≤ 0.8·|s(0)|` is taken, else the one with the smallest `|s|`. (A test on `‖G‖`
//! instead rejects good steps: a stiff axial mode makes `‖G‖` jump after the first, correct step.)

use std::time::Instant;

use crate::analytical::{CatenaryError, FreeCatenary, SlopedTouchdownCatenary, TouchdownCatenary};
use crate::assembly::Assembler;
pub use crate::assembly::{LineResults, Placement};
use crate::environment::Hydro;
use crate::loads::{self, Iterate, LoadModel, LoadScratch, SeabedPass, TangentScale};
use crate::model::LineModel;
use crate::sparse::SolveError;
use catena_seabed::law::{Seabed, SeabedHistory, TrialMemo};

/// Options of the static solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    /// Relative residual tolerance.
    pub tol: f64,
    /// Newton iterations per continuation step.
    pub max_iter: usize,
    /// The smallest load-factor increment before giving up.
    pub min_increment: f64,
    /// Stagnation: a relative residual at most this ...
    pub stagnation_residual: f64,
    /// ... with a Newton correction at most this (m or rad) is converged to machine precision.
    /// (Axial forces are resolved only to about `EA·ε` per element: a very stiff, lightly loaded line
    /// cannot reach a tight *relative* residual.)
    pub stagnation_step: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            tol: 1e-9,
            max_iter: 40,
            min_increment: 1.0 / 1024.0,
            stagnation_residual: 1e-6,
            stagnation_step: 1e-10,
        }
    }
}

/// What the static solve did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StaticReport {
    /// Newton iterations in all.
    pub iterations: usize,
    /// Continuation steps taken (1 when the full load converged at once).
    pub steps: usize,
    /// Failed continuation attempts (increment cuts).
    pub cuts: usize,
    /// The final relative residual.
    pub residual: f64,
    /// Time spent assembling, s.
    pub assembly_seconds: f64,
    /// Time spent in numeric factorisation and solves, s.
    pub solve_seconds: f64,
}

/// Why the static solve failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StaticError {
    /// Newton did not converge even with the smallest load increment.
    #[error(
        "the static solve did not converge: load factor {load_factor:.6}, iteration {iteration}, \
         relative residual {residual:.3e}, largest at node {node} (arc length {arc:.3} m)"
    )]
    NotConverged {
        /// The load factor being attempted.
        load_factor: f64,
        /// The last iteration.
        iteration: usize,
        /// The relative residual there.
        residual: f64,
        /// The node with the largest residual.
        node: usize,
        /// Its arc length from the top, m.
        arc: f64,
    },
    /// The linear solver failed.
    #[error("linear solve: {0}")]
    Solve(#[from] SolveError),
    /// The seed could not be made.
    #[error("catenary seed: {0}")]
    Seed(#[from] CatenaryError),
}

/// Scratch for the static solve: the structural assembly (pattern, factorisation) and vectors.
/// Never saved; rebuilt from the Model.
#[derive(Debug)]
pub struct StaticWorkspace {
    /// The structural assembly; after [`StaticWorkspace::assemble`] its residual includes the
    /// seabed and the current's drag.
    pub asm: Assembler,
    /// The steady current's hydrodynamics for the solve under way (set by [`solve_in`]).
    current: Option<Hydro>,
    /// Zero velocities (the line is at rest).
    at_rest: Vec<f64>,
    /// What the loads fill per node.
    loads: LoadScratch,
    g: Vec<f64>,
    g0: Vec<f64>,
    dq: Vec<f64>,
    q_trial: Vec<f64>,
    q_conv: Vec<f64>,
    /// A seabed with a past ([`StaticWorkspace::on_histories`]): each node's committed history,
    /// the friction anchors and the trial memos.
    committed: Option<(Vec<SeabedHistory>, Vec<f64>, Vec<TrialMemo>)>,
}

impl StaticWorkspace {
    /// The solves that follow find the equilibrium on a seabed with a past (the trench a lay dug):
    /// each node's seabed reaction is its law's trial from `history` (one per node) rather than
    /// the backbone, with axial friction from `anchors` where the seabed has it
    /// ([`crate::dynamics::DynState::friction_anchor`]'s layout).
    pub fn on_histories(&mut self, history: Vec<SeabedHistory>, anchors: Vec<f64>) {
        let memo = vec![TrialMemo::default(); history.len()];
        self.committed = Some((history, anchors, memo));
    }

    /// Builds the pattern and the symbolic factorisation for the Model.
    pub fn new(model: &LineModel) -> Result<Self, SolveError> {
        let n3 = 3 * model.nodes();
        Ok(Self {
            asm: Assembler::new(model)?,
            current: None,
            at_rest: vec![0.0; n3],
            loads: LoadScratch::new(model.nodes()),
            g: vec![0.0; model.n_eq],
            g0: vec![0.0; model.n_eq],
            dq: vec![0.0; model.n_eq],
            q_trial: vec![0.0; n3],
            q_conv: vec![0.0; n3],
            committed: None,
        })
    }

    /// Assembles the global residual `R(q)` into the assembler's residual and, if `with_k`, the
    /// tangent: the structure, then the loads of [`crate::loads`] as the statics have them — the
    /// seabed through its backbone (initial penetration only), a steady current (see [`solve_in`])
    /// through its drag on the line at rest, whose dependence on the orientation is left out of the
    /// tangent. Allocates nothing.
    pub fn assemble(&mut self, model: &LineModel, pl: &Placement, u: &[f64], with_k: bool) {
        self.asm.assemble_structure(model, pl, u, 0.0, with_k);
        let m = LoadModel {
            line: model,
            placement: pl,
            hydro: self.current.as_ref(),
            structural_damping: None,
        };
        let at = Iterate {
            u,
            v: &self.at_rest,
            wave_kin: &[],
        };
        let scale = TangentScale {
            with_k,
            k: 1.0,
            c_v: 0.0,
        };
        let pass = match &mut self.committed {
            Some((committed, anchors, memo)) => SeabedPass::Trial {
                committed,
                anchors,
                // The laws' rates are their own: the step is not used (the line is at rest).
                dt: 1.0,
                memo,
                keep: None,
            },
            None => SeabedPass::Backbone,
        };
        loads::assemble(&m, &at, pass, scale, &mut self.asm, &mut self.loads);
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn worst_node(model: &LineModel, g: &[f64]) -> usize {
    let mut best = (0.0, 0);
    for (gd, e) in model.equation.iter().enumerate() {
        if let Some(i) = e {
            if g[*i].abs() > best.0 {
                best = (g[*i].abs(), gd / 3);
            }
        }
    }
    best.1
}

/// The reference for the relative residual: `‖F_dead‖₂` over the free equations (1 if zero).
pub fn residual_reference(model: &LineModel) -> f64 {
    let r = model
        .equation
        .iter()
        .enumerate()
        .filter(|(_, e)| e.is_some())
        .map(|(g, _)| model.dead_load[g].powi(2))
        .sum::<f64>()
        .sqrt();
    if r > 0.0 {
        r
    } else {
        1.0
    }
}

/// Solves the static equilibrium for the displacements `u` from the placement `pl` (the prescribed
/// dofs keep their values), in place, without current.
pub fn solve(
    model: &LineModel,
    pl: &Placement,
    q: &mut [f64],
    ws: &mut StaticWorkspace,
    opts: &StaticOptions,
) -> Result<StaticReport, StaticError> {
    solve_in(model, None, pl, q, ws, opts)
}

/// [`solve`] in a steady current: `hydro`'s current profile drags on the line at rest (the
/// dynamics then start in equilibrium with it). The workspace keeps the current for the
/// [`line_results`] that follow.
pub fn solve_in(
    model: &LineModel,
    hydro: Option<&Hydro>,
    pl: &Placement,
    q: &mut [f64],
    ws: &mut StaticWorkspace,
    opts: &StaticOptions,
) -> Result<StaticReport, StaticError> {
    ws.current = hydro.filter(|h| !h.current.is_empty()).cloned();
    let mut rep = StaticReport::default();
    let refn = residual_reference(model);
    let t0 = Instant::now();
    ws.assemble(model, pl, q, false);
    rep.assembly_seconds += t0.elapsed().as_secs_f64();
    let mut g0 = std::mem::take(&mut ws.g0);
    ws.asm.gather(model, &mut g0);
    ws.g0 = g0;
    rep.residual = norm(&ws.g0) / refn;
    if rep.residual <= opts.tol {
        return Ok(rep);
    }
    let mut lam = 0.0;
    let mut dlam = 1.0f64;
    ws.q_conv.copy_from_slice(q);
    while lam < 1.0 {
        let target = (lam + dlam).min(1.0);
        match newton(model, pl, q, ws, opts, target, refn, &mut rep) {
            Ok(()) => {
                lam = target;
                rep.steps += 1;
                ws.q_conv.copy_from_slice(q);
                dlam = (dlam * 2.0).min(1.0);
            }
            Err(e) => {
                q.copy_from_slice(&ws.q_conv);
                rep.cuts += 1;
                dlam *= 0.5;
                if dlam < opts.min_increment {
                    return Err(e);
                }
            }
        }
    }
    Ok(rep)
}

#[allow(clippy::too_many_arguments)]
fn newton(
    model: &LineModel,
    pl: &Placement,
    q: &mut [f64],
    ws: &mut StaticWorkspace,
    opts: &StaticOptions,
    lam: f64,
    refn: f64,
    rep: &mut StaticReport,
) -> Result<(), StaticError> {
    let shift = 1.0 - lam;
    let mut last = (0, f64::INFINITY, 0);
    for it in 0..opts.max_iter {
        let t = Instant::now();
        ws.assemble(model, pl, q, true);
        rep.assembly_seconds += t.elapsed().as_secs_f64();
        let mut g = std::mem::take(&mut ws.g);
        ws.asm.gather(model, &mut g);
        for (gi, g0) in g.iter_mut().zip(&ws.g0) {
            *gi -= shift * g0;
        }
        let r = norm(&g) / refn;
        last = (it, r, worst_node(model, &g));
        rep.residual = r;
        // Given back before any way out (a singular tangent returns with `?` below): a load step
        // retried after an error finds the workspace whole.
        ws.g = g;
        if !r.is_finite() {
            break;
        }
        if r <= opts.tol {
            return Ok(());
        }
        rep.iterations += 1;
        let t = Instant::now();
        ws.asm.factor_tangent()?;
        ws.dq.copy_from_slice(&ws.g);
        ws.asm.solve_tangent(&mut ws.dq);
        rep.solve_seconds += t.elapsed().as_secs_f64();
        let step = ws.dq.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if r <= opts.stagnation_residual && step <= opts.stagnation_step {
            // Machine-precision stagnation: the correction is below what the state resolves.
            for (gd, e) in model.equation.iter().enumerate() {
                if let Some(i) = e {
                    q[gd] -= ws.dq[*i];
                }
            }
            return Ok(());
        }
        // Energy line search: the slope s(α) = dq·G(q − α·dq), with s(0) = dq·K·dq.
        let s0: f64 = ws.dq.iter().zip(&ws.g).map(|(a, b)| a * b).sum();
        let mut best = (f64::INFINITY, 0.0);
        let mut alpha = 1.0;
        for _ in 0..7 {
            ws.q_trial.copy_from_slice(q);
            for (gd, e) in model.equation.iter().enumerate() {
                if let Some(i) = e {
                    ws.q_trial[gd] -= alpha * ws.dq[*i];
                }
            }
            let t = Instant::now();
            let qt = std::mem::take(&mut ws.q_trial);
            ws.assemble(model, pl, &qt, false);
            ws.q_trial = qt;
            rep.assembly_seconds += t.elapsed().as_secs_f64();
            let mut g = std::mem::take(&mut ws.g);
            ws.asm.gather(model, &mut g);
            let mut slope = 0.0;
            for ((gi, g0), d) in g.iter_mut().zip(&ws.g0).zip(&ws.dq) {
                *gi -= shift * g0;
                slope += d * *gi;
            }
            ws.g = g;
            let ratio = (slope / s0).abs();
            if ratio.is_finite() && ratio < best.0 {
                best = (ratio, alpha);
            }
            if ratio <= 0.8 {
                break;
            }
            alpha *= 0.5;
        }
        let alpha = if best.0.is_finite() {
            best.1
        } else {
            1.0 / 64.0
        };
        for (gd, e) in model.equation.iter().enumerate() {
            if let Some(i) = e {
                q[gd] -= alpha * ws.dq[*i];
            }
        }
    }
    Err(StaticError::NotConverged {
        load_factor: lam,
        iteration: last.0,
        residual: last.1,
        node: last.2,
        arc: model.arc[last.2],
    })
}

/// Where the ends of the line are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndPositions {
    /// Top end `(x, z)`, m.
    pub top: (f64, f64),
    /// Anchor end `(x, z)`, m.
    pub anchor: (f64, f64),
}

/// The static embedment of a pipe of submerged weight `w` (N/m) resting on the seabed: the
/// penetration where the backbone plus soil buoyancy carries the weight. `None` without a seabed.
pub fn static_embedment(model: &LineModel, w: f64) -> Option<f64> {
    static_embedment_on(
        model.seabed_law(model.nodes() - 1)?,
        model.node_od[model.nodes() - 1],
        w,
    )
}

/// [`static_embedment`] on a given seabed law for a pipe of contact diameter `d`.
pub fn static_embedment_on(seabed: &Seabed, d: f64, w: f64) -> Option<f64> {
    let f = |z: f64| seabed.backbone(z).total() - w;
    let mut hi = 1e-3 * d;
    while f(hi) < 0.0 {
        hi *= 2.0;
        if hi > 100.0 * d {
            return None;
        }
    }
    let (lo, hi) = catena_seabed::roots::bisect(0.0, hi, |m| {
        let v = f(m);
        v >= 0.0 || v.is_nan()
    });
    Some(0.5 * (lo + hi))
}

/// The catenary seed: node positions and angles on the analytical catenary for the given ends, with
/// the line resting at its static embedment on the seabed if it reaches it, and hanging free
/// otherwise. Each element is placed stretched by `T/EA` (the catenary tension at its middle,
/// `T = H/|cos θ|`), and the catenary is re-solved for the stretched length (three passes), so the
/// seed already carries the right tension everywhere. Returns the state vector `q` (3 per node).
pub fn catenary_seed(model: &LineModel, ends: &EndPositions) -> Result<Vec<f64>, StaticError> {
    enum Shape {
        Touchdown(TouchdownCatenary, f64, f64),
        Sloped(SlopedTouchdownCatenary, f64, f64),
        Free(FreeCatenary),
    }
    impl Shape {
        fn point(&self, s: f64) -> (f64, f64, f64) {
            match self {
                Shape::Touchdown(c, x0, z0) => {
                    let (x, z, th) = c.point(s);
                    (x0 + x, z0 + z, th)
                }
                Shape::Sloped(c, x0, z0) => {
                    let (x, z, th) = c.point(s);
                    (x0 + x, z0 + z, th)
                }
                Shape::Free(c) => c.point(s),
            }
        }
    }
    let n = model.nodes();
    let (xt, zt) = ends.top;
    let (xa, za) = ends.anchor;
    let span = xt - xa;
    let w = model.mean_weight();
    let uniform = model
        .elements
        .iter()
        .all(|e| e.weight == model.elements[0].weight);
    // The seed's seabed is flat at the mudline under the anchor (a profile's nodes are draped onto
    // it below), the pipe there at the static embedment of its own weight.
    let w_anchor = if uniform {
        w
    } else {
        model.elements[n - 2].weight
    };
    let emb = static_embedment(model, w_anchor).unwrap_or(0.0);
    let contact = model
        .seabed
        .as_ref()
        .map(|_| model.mudline_at(xa).0 + 0.5 * model.node_od[n - 1] - emb);
    // On a profile sloping at the touchdown: the catenary tangent to the plane of the mudline's
    // slope there (`SlopedTouchdownCatenary`), the touchdown re-estimated twice from the flat one's.
    // The laid nodes are draped onto the profile below. A flat mudline at the touchdown: none.
    let sloped = |mut x_td: f64, length: f64| -> Option<(Shape, f64)> {
        let mut found = None;
        for _ in 0..3 {
            let (zm, m) = model.mudline_at(x_td);
            if m == 0.0 {
                return found;
            }
            let alpha = -m.atan();
            let z_td = zm + (0.5 * model.node_od[n - 1] - emb) / alpha.cos();
            let z_plane = z_td + alpha.tan() * (x_td - xa);
            let c = SlopedTouchdownCatenary::solve(w, alpha, span, zt - z_plane, length).ok()?;
            x_td = xa + c.touchdown_x();
            found = Some((Shape::Sloped(c, xa, z_plane), c.a));
        }
        found
    };
    let shape_for = |length: f64| -> Result<(Shape, f64), StaticError> {
        if let Some(z_contact) = contact {
            if let Ok(c) = TouchdownCatenary::solve(w, span, zt - z_contact, length) {
                let x_tdp = xt - c.point(0.0).0;
                if let Some(s) = sloped(x_tdp, length) {
                    return Ok(s);
                }
                return Ok((Shape::Touchdown(c, x_tdp, z_contact), c.a));
            }
        }
        let c = FreeCatenary::solve(span, zt - za, length)?;
        Ok((
            Shape::Free(FreeCatenary {
                x_vertex: c.x_vertex + xa,
                ..c
            }),
            c.a,
        ))
    };
    // A line whose weight changes along it (sections): the catenary of its sections, if the
    // anchor lies on the seabed and one exists; else the mean weight's below.
    if let (Some(zc), false) = (contact, uniform) {
        if (za - zc).abs() <= 1e-9 * zc.abs().max(1.0) {
            if let Some((mut q, _, _)) = crate::sectioned::seed(model, ends.top, (xa, zc)) {
                drape(model, &mut q, zc, emb);
                q[0] = xt;
                q[1] = zt;
                return Ok(q);
            }
        }
    }
    if w.is_nan() || w <= 0.0 {
        return Err(StaticError::Seed(CatenaryError::Invalid(
            "the line is net buoyant on the whole and has no catenary of its sections between its ends",
        )));
    }
    let mut length = model.length();
    let mut arcs = model.arc.clone();
    let mut shape = shape_for(length)?;
    for _ in 0..3 {
        let (sh, a) = &shape;
        let mut s_star = 0.0;
        for (e, el) in model.elements.iter().enumerate() {
            let th = sh.point(s_star + 0.5 * el.l0).2;
            let t = w * a / th.cos().abs().max(1e-6);
            s_star += el.l0 * (1.0 + t / el.section.ea);
            arcs[e + 1] = s_star;
        }
        length = s_star;
        shape = shape_for(length)?;
    }
    let mut q = vec![0.0; 3 * n];
    for i in 0..n {
        let (x, z, th) = shape.0.point(arcs[i].min(length));
        q[3 * i] = x;
        q[3 * i + 1] = if matches!(shape.0, Shape::Free(_)) {
            za + z
        } else {
            z
        };
        q[3 * i + 2] = th;
    }
    if let Shape::Sloped(c, ..) = &shape.0 {
        // The laid nodes from the plane onto the profile.
        for i in 0..n {
            if arcs[i] >= c.suspended {
                let (zm, m) = model.mudline_at(q[3 * i]);
                let cos = 1.0 / (1.0 + m * m).sqrt();
                q[3 * i + 1] = zm + (0.5 * model.node_od[i] - emb) / cos;
                q[3 * i + 2] = -std::f64::consts::PI + m.atan();
            }
        }
    } else if let Some(zc) = contact {
        drape(model, &mut q, zc, emb);
    }
    q[0] = xt;
    q[1] = zt;
    q[3 * (n - 1)] = xa;
    q[3 * (n - 1) + 1] = za;
    Ok(q)
}

/// On a profile: the nodes a seed lays on its flat seabed at `zc` follow the mudline, at the same
/// embedment `emb` normal to it, turned by its slope. Nothing on a flat seabed.
fn drape(model: &LineModel, q: &mut [f64], zc: f64, emb: f64) {
    if model.mudline_profile.is_empty() {
        return;
    }
    for i in 0..model.nodes() {
        if (q[3 * i + 1] - zc).abs() <= 1e-9 * zc.abs().max(1.0) {
            let (zm, m) = model.mudline_at(q[3 * i]);
            let c = 1.0 / (1.0 + m * m).sqrt();
            q[3 * i + 1] = zm + (0.5 * model.node_od[i] - emb) / c;
            q[3 * i + 2] += m.atan();
        }
    }
}

/// Nodal results at `u` (see [`Assembler::fill_results`]), with the loads of the last solve (the
/// current, if any); at the ends the tension is the support reaction's magnitude. `seabed_force` evaluates `force_at(node, z_pen)` where the node
/// penetrates, the law in the analysis' mode; the mode code is 1 (initial penetration) there.
pub fn line_results(
    model: &LineModel,
    pl: &Placement,
    u: &[f64],
    ws: &mut StaticWorkspace,
    force_at: impl Fn(usize, f64) -> f64,
) -> LineResults {
    ws.assemble(model, pl, u, false);
    let mut r = LineResults::new(model.nodes());
    let pen = |i: usize| {
        model
            .penetration(
                i,
                pl.base[3 * i] + u[3 * i],
                pl.base[3 * i + 1] + u[3 * i + 1],
            )
            .unwrap_or(0.0)
    };
    let res = &ws.asm.residual;
    ws.asm.fill_results(
        model,
        pl,
        u,
        |i| {
            let p = pen(i);
            if p > 0.0 {
                force_at(i, p)
            } else {
                0.0
            }
        },
        |i| u8::from(model.seabed.is_some() && pen(i) > 0.0),
        |i| (res[3 * i], res[3 * i + 1]),
        &mut r,
    );
    r
}

/// Summary numbers of a static configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticSummary {
    /// Top effective tension, N.
    pub top_tension: f64,
    /// Horizontal component of the top tension, N.
    pub horizontal_tension: f64,
    /// Horizontal component of the anchor's reaction, N (the same as at the top without current;
    /// a current's drag adds to it along the line).
    pub anchor_horizontal_tension: f64,
    /// Arc length of the touchdown point (first contact from the top), m, if any.
    pub touchdown_arc: Option<f64>,
    /// The most negative (sag) bending moment, N·m, and its arc length.
    pub max_sag_moment: (f64, f64),
    /// The largest absolute bending moment, N·m (signed), and its arc length.
    pub max_abs_moment: (f64, f64),
    /// The bending moment at the touchdown point (interpolated), N·m.
    pub touchdown_moment: Option<f64>,
    /// The top angle from the vertical, rad.
    pub top_angle_from_vertical: f64,
}

/// The touchdown point: the first node `i` from the top whose invert penetrates (`z_i > 0`) after
/// one that does not (`z_{i−1} ≤ 0`), and the fraction `f` of element `i−1..i` at which the
/// penetration, interpolated linearly, is zero (so the touchdown arc length is
/// `s_{i−1} + f·(s_i − s_{i−1})`). `None` if no node penetrates after a clear one.
pub fn touchdown_point(penetration: &[f64]) -> Option<(usize, f64)> {
    (1..penetration.len())
        .find(|&i| penetration[i] > 0.0 && penetration[i - 1] <= 0.0)
        .map(|i| {
            let (a, b) = (penetration[i - 1], penetration[i]);
            (i, -a / (b - a))
        })
}

/// The touchdown point's arc length (see [`touchdown_point`]), m.
pub fn touchdown_arc(arc: &[f64], penetration: &[f64]) -> Option<f64> {
    touchdown_point(penetration).map(|(i, f)| arc[i - 1] + f * (arc[i] - arc[i - 1]))
}

#[allow(clippy::needless_range_loop)]
/// Summarises nodal results at the arc lengths `arc` (`reactions` = the global residual at the top
/// node's and at the anchor node's x and z).
pub fn summarise(arc: &[f64], r: &LineResults, reactions: [(f64, f64); 2]) -> StaticSummary {
    let [top_reaction, anchor_reaction] = reactions;
    let n = arc.len();
    let mut touchdown_arc = None;
    let mut touchdown_moment = None;
    if let Some((i, f)) = touchdown_point(&r.penetration) {
        touchdown_arc = Some(arc[i - 1] + f * (arc[i] - arc[i - 1]));
        touchdown_moment = Some(r.moment[i - 1] + f * (r.moment[i] - r.moment[i - 1]));
    }
    let mut sag = (0.0, 0.0);
    let mut abs = (0.0f64, 0.0);
    for i in 0..n {
        if r.moment[i] < sag.0 {
            sag = (r.moment[i], arc[i]);
        }
        if r.moment[i].abs() > abs.0.abs() {
            abs = (r.moment[i], arc[i]);
        }
    }
    // The tangent at the top points down the line; its angle from the downward vertical.
    let th = r.theta[0];
    let (tx, tz) = (th.cos(), th.sin());
    let from_vertical = (tx.abs()).atan2(-tz);
    StaticSummary {
        top_tension: (top_reaction.0.powi(2) + top_reaction.1.powi(2)).sqrt(),
        horizontal_tension: top_reaction.0.abs(),
        anchor_horizontal_tension: anchor_reaction.0.abs(),
        touchdown_arc,
        max_sag_moment: sag,
        max_abs_moment: abs,
        touchdown_moment,
        top_angle_from_vertical: from_vertical,
    }
}
