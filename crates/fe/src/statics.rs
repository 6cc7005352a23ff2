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

use crate::analytical::{CatenaryError, FreeCatenary, TouchdownCatenary};
use crate::beam::corotational_beam_chord;
use crate::model::LineModel;
use crate::sparse::{LdltSolver, SolveError, SparseSym};

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

/// A fixed base configuration `q_b` (3 values per node) and its element chords, precomputed once.
/// The unknowns are displacements `u` from it: `q = q_b + u`. Element chords are then
/// `chord_b + (u_2 − u_1)`, resolved to the precision of `u` rather than of coordinates of order
/// 1000 m (which would limit equilibrium to about 1e-3 N in a 0.5 m element of EA = 3.4 GN).
#[derive(Debug, Clone, PartialEq)]
pub struct Placement {
    /// The base configuration, 3 per node.
    pub base: Vec<f64>,
    /// `(x_{e+1} − x_e, z_{e+1} − z_e)` of the base, per element.
    pub chords: Vec<[f64; 2]>,
}

impl Placement {
    /// The placement of a configuration `q`.
    pub fn new(q: &[f64]) -> Self {
        let n = q.len() / 3;
        let chords = (0..n.saturating_sub(1))
            .map(|e| [q[3 * e + 3] - q[3 * e], q[3 * e + 4] - q[3 * e + 1]])
            .collect();
        Self {
            base: q.to_vec(),
            chords,
        }
    }

    /// Absolute values `q = q_b + u`.
    pub fn absolute(&self, u: &[f64]) -> Vec<f64> {
        self.base.iter().zip(u).map(|(b, d)| b + d).collect()
    }
}

/// Scratch for the static solve: the sparse pattern, the factorisation and vectors. Never saved;
/// rebuilt from the Model.
#[derive(Debug)]
pub struct StaticWorkspace {
    /// The tangent (free equations), upper triangle.
    pub k: SparseSym,
    solver: LdltSolver,
    /// For element `e`, the value slot of local pair `(a, b)` (`usize::MAX` if not stored).
    elem_slots: Vec<[usize; 36]>,
    /// The diagonal slot of each equation.
    diag_slots: Vec<usize>,
    /// Global residual `R(q)`, 3 per node.
    pub residual: Vec<f64>,
    /// Element axial forces, N.
    pub axial: Vec<f64>,
    /// Element internal end moments `(M(0), M(1))`, N·m.
    pub moments: Vec<(f64, f64)>,
    g: Vec<f64>,
    g0: Vec<f64>,
    dq: Vec<f64>,
    q_trial: Vec<f64>,
    q_conv: Vec<f64>,
}

const NONE: usize = usize::MAX;

impl StaticWorkspace {
    /// Builds the pattern and the symbolic factorisation for the Model.
    pub fn new(model: &LineModel) -> Result<Self, SolveError> {
        let ne = model.elements.len();
        let eq = |g: usize| model.equation[g];
        let mut pairs = Vec::with_capacity(ne * 36);
        for e in 0..ne {
            for a in 0..6 {
                for b in 0..6 {
                    if let (Some(i), Some(j)) = (eq(3 * e + a), eq(3 * e + b)) {
                        pairs.push((i, j));
                    }
                }
            }
        }
        let k = SparseSym::from_couplings(model.n_eq, pairs);
        let mut elem_slots = vec![[NONE; 36]; ne];
        for (e, slots) in elem_slots.iter_mut().enumerate() {
            for a in 0..6 {
                for b in 0..6 {
                    if let (Some(i), Some(j)) = (eq(3 * e + a), eq(3 * e + b)) {
                        if i <= j {
                            slots[a * 6 + b] = k.slot(i, j).unwrap_or(NONE);
                        }
                    }
                }
            }
        }
        let diag_slots = (0..model.n_eq)
            .map(|i| k.slot(i, i).unwrap_or(NONE))
            .collect();
        let solver = LdltSolver::with_ordering(&k, true)?;
        let n3 = 3 * model.nodes();
        Ok(Self {
            k,
            solver,
            elem_slots,
            diag_slots,
            residual: vec![0.0; n3],
            axial: vec![0.0; ne],
            moments: vec![(0.0, 0.0); ne],
            g: vec![0.0; model.n_eq],
            g0: vec![0.0; model.n_eq],
            dq: vec![0.0; model.n_eq],
            q_trial: vec![0.0; n3],
            q_conv: vec![0.0; n3],
        })
    }

    /// Assembles the global residual `R(q)` into [`StaticWorkspace::residual`] and, if `with_k`, the
    /// tangent into [`StaticWorkspace::k`]. The seabed acts through its backbone (initial
    /// penetration only). Allocates nothing.
    pub fn assemble(&mut self, model: &LineModel, pl: &Placement, u: &[f64], with_k: bool) {
        self.assemble_structure(model, pl, u, with_k);
        let q = &pl.base;
        if let Some(sb) = &model.seabed {
            for i in 0..model.nodes() {
                let z_pen = sb.mudline_z - (q[3 * i + 1] + u[3 * i + 1] - 0.5 * model.node_od[i]);
                if z_pen <= 0.0 {
                    continue;
                }
                let t = sb.seabed.backbone(z_pen);
                let l = model.tributary[i];
                self.residual[3 * i + 1] -= l * t.total();
                if with_k {
                    // d(−L·F(z_pen))/dz = L·F'(z_pen), since dz_pen/dz = −1.
                    self.add_dof_tangent(model, 3 * i + 1, l * t.tangent);
                }
            }
        }
    }

    /// Adds `v` to the tangent's diagonal at global dof `g` (nothing if `g` is prescribed).
    #[inline]
    pub fn add_dof_tangent(&mut self, model: &LineModel, g: usize, v: f64) {
        if let Some(eq) = model.equation[g] {
            self.k.values[self.diag_slots[eq]] += v;
        }
    }

    /// Adds a symmetric 2×2 block `[[xx, xz], [xz, zz]]` to the tangent at node `i`'s translations.
    #[inline]
    pub fn add_node_block(&mut self, model: &LineModel, i: usize, xx: f64, xz: f64, zz: f64) {
        let (ex, ez) = (model.equation[3 * i], model.equation[3 * i + 1]);
        if let Some(a) = ex {
            self.k.values[self.diag_slots[a]] += xx;
        }
        if let Some(b) = ez {
            self.k.values[self.diag_slots[b]] += zz;
        }
        if let (Some(a), Some(b)) = (ex, ez) {
            if let Some(s) = self.k.slot(a, b) {
                self.k.values[s] += xz;
            }
        }
    }

    /// Multiplies every assembled tangent value by `f`.
    pub fn scale_tangent(&mut self, f: f64) {
        for v in &mut self.k.values {
            *v *= f;
        }
    }

    /// The structural part of the residual and tangent: elements, submerged weight and flexjoint
    /// (no seabed). Allocates nothing.
    pub fn assemble_structure(
        &mut self,
        model: &LineModel,
        pl: &Placement,
        u: &[f64],
        with_k: bool,
    ) {
        self.residual.fill(0.0);
        if with_k {
            self.k.clear();
        }
        let q = &pl.base;
        for (e, el) in model.elements.iter().enumerate() {
            let b = 3 * e;
            let [cx, cz] = pl.chords[e];
            let r = corotational_beam_chord(
                cx + (u[b + 3] - u[b]),
                cz + (u[b + 4] - u[b + 1]),
                q[b + 2] + u[b + 2],
                q[b + 5] + u[b + 5],
                el.l0,
                &el.section,
                with_k,
            );
            for a in 0..6 {
                self.residual[b + a] += r.force[a];
            }
            self.axial[e] = r.axial;
            self.moments[e] = (r.moment1, r.moment2);
            if with_k {
                let slots = &self.elem_slots[e];
                for a in 0..6 {
                    for c in 0..6 {
                        let s = slots[a * 6 + c];
                        if s != NONE {
                            self.k.values[s] += r.stiffness[a][c];
                        }
                    }
                }
            }
        }
        for (g, f) in model.dead_load.iter().enumerate() {
            self.residual[g] -= f;
        }
        if let Some(fj) = &model.flexjoint {
            let g = 3 * fj.node + 2;
            self.residual[g] += fj.stiffness * (q[g] + u[g] - fj.neutral);
            if with_k {
                if let Some(eq) = model.equation[g] {
                    self.k.values[self.diag_slots[eq]] += fj.stiffness;
                }
            }
        }
    }

    /// Tension and bending moment at node `i` from the last assembly: the means of the adjacent
    /// elements' axial forces and of their internal moments at that node.
    pub fn nodal_tension_moment(&self, i: usize) -> (f64, f64) {
        let ne = self.axial.len();
        let (mut t, mut m, mut c) = (0.0, 0.0, 0.0);
        if i > 0 {
            t += self.axial[i - 1];
            m += self.moments[i - 1].1;
            c += 1.0;
        }
        if i < ne {
            t += self.axial[i];
            m += self.moments[i].0;
            c += 1.0;
        }
        (t / c, m / c)
    }

    /// Numeric factorisation of the tangent last assembled.
    pub fn factor_tangent(&mut self) -> Result<(), SolveError> {
        self.solver.factor(&self.k)
    }

    /// Solves with the last factorisation, in place.
    pub fn solve_tangent(&mut self, rhs: &mut [f64]) {
        self.solver.solve_in_place(rhs);
    }

    /// Copies the residual's free equations into `out`.
    pub fn gather(&self, model: &LineModel, out: &mut [f64]) {
        for (g, e) in model.equation.iter().enumerate() {
            if let Some(i) = e {
                out[*i] = self.residual[g];
            }
        }
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
/// dofs keep their values), in place.
pub fn solve(
    model: &LineModel,
    pl: &Placement,
    q: &mut [f64],
    ws: &mut StaticWorkspace,
    opts: &StaticOptions,
) -> Result<StaticReport, StaticError> {
    let mut rep = StaticReport::default();
    let refn = residual_reference(model);
    let t0 = Instant::now();
    ws.assemble(model, pl, q, false);
    rep.assembly_seconds += t0.elapsed().as_secs_f64();
    let mut g0 = std::mem::take(&mut ws.g0);
    ws.gather(model, &mut g0);
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
        ws.gather(model, &mut g);
        for (gi, g0) in g.iter_mut().zip(&ws.g0) {
            *gi -= shift * g0;
        }
        let r = norm(&g) / refn;
        last = (it, r, worst_node(model, &g));
        rep.residual = r;
        if !r.is_finite() {
            ws.g = g;
            break;
        }
        if r <= opts.tol {
            ws.g = g;
            return Ok(());
        }
        rep.iterations += 1;
        let t = Instant::now();
        ws.solver.factor(&ws.k)?;
        ws.dq.copy_from_slice(&g);
        ws.solver.solve_in_place(&mut ws.dq);
        rep.solve_seconds += t.elapsed().as_secs_f64();
        ws.g = g;
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
            ws.gather(model, &mut g);
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
    let sb = model.seabed.as_ref()?;
    let d = model.node_od[model.nodes() - 1];
    let f = |z: f64| sb.seabed.backbone(z).total() - w;
    let mut hi = 1e-3 * d;
    while f(hi) < 0.0 {
        hi *= 2.0;
        if hi > 100.0 * d {
            return None;
        }
    }
    let (mut lo, mut hi) = (0.0, hi);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if m <= lo || m >= hi {
            break;
        }
        if f(m) < 0.0 {
            lo = m;
        } else {
            hi = m;
        }
    }
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
        Free(FreeCatenary),
    }
    impl Shape {
        fn point(&self, s: f64) -> (f64, f64, f64) {
            match self {
                Shape::Touchdown(c, x0, z0) => {
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
    let contact = model.seabed.as_ref().map(|sb| {
        let d = model.node_od[n - 1];
        let emb = static_embedment(model, w).unwrap_or(0.0);
        sb.mudline_z + 0.5 * d - emb
    });
    let shape_for = |length: f64| -> Result<(Shape, f64), StaticError> {
        if let Some(z_contact) = contact {
            if let Ok(c) = TouchdownCatenary::solve(w, span, zt - z_contact, length) {
                let x_tdp = xt - c.point(0.0).0;
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
    q[0] = xt;
    q[1] = zt;
    q[3 * (n - 1)] = xa;
    q[3 * (n - 1) + 1] = za;
    Ok(q)
}

/// Results along the line, one value per node (node 0 at the top).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LineResults {
    /// Arc length from the top, m.
    pub arc: Vec<f64>,
    /// x, m.
    pub x: Vec<f64>,
    /// z, m.
    pub z: Vec<f64>,
    /// Tangent angle θ, rad.
    pub theta: Vec<f64>,
    /// Effective tension, N (end nodes: the support reaction's magnitude).
    pub tension: Vec<f64>,
    /// Bending moment, N·m (negative = sag).
    pub moment: Vec<f64>,
    /// Invert penetration below the mudline, m (positive down, ≤ 0 clear; 0 without a seabed).
    pub penetration: Vec<f64>,
    /// Seabed force (resistance plus buoyancy) per unit length, N/m.
    pub seabed_force: Vec<f64>,
}

/// Nodal results at `q`. Tension and moment at an interior node are the means of the two adjacent
/// elements' values there; at a supported end node the tension is the reaction's magnitude.
/// `seabed_force` evaluates `force_at(node, z_pen)`, the law in the analysis' mode.
pub fn line_results(
    model: &LineModel,
    pl: &Placement,
    u: &[f64],
    ws: &mut StaticWorkspace,
    force_at: impl Fn(usize, f64) -> f64,
) -> LineResults {
    ws.assemble(model, pl, u, false);
    let q = pl.absolute(u);
    let n = model.nodes();
    let mut r = LineResults {
        arc: model.arc.clone(),
        x: (0..n).map(|i| q[3 * i]).collect(),
        z: (0..n).map(|i| q[3 * i + 1]).collect(),
        theta: (0..n).map(|i| q[3 * i + 2]).collect(),
        tension: vec![0.0; n],
        moment: vec![0.0; n],
        penetration: vec![0.0; n],
        seabed_force: vec![0.0; n],
    };
    for i in 0..n {
        (r.tension[i], r.moment[i]) = ws.nodal_tension_moment(i);
        if let Some(p) = model.penetration(i, q[3 * i + 1]) {
            r.penetration[i] = p;
            r.seabed_force[i] = if p > 0.0 { force_at(i, p) } else { 0.0 };
        }
    }
    for i in [0, n - 1] {
        let rx = ws.residual[3 * i];
        let rz = ws.residual[3 * i + 1];
        r.tension[i] = (rx * rx + rz * rz).sqrt();
    }
    r
}

/// Summary numbers of a static configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticSummary {
    /// Top effective tension, N.
    pub top_tension: f64,
    /// Horizontal component of the top tension, N.
    pub horizontal_tension: f64,
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

/// Summarises nodal results (`top_reaction` = the global residual at the top node's x and z).
pub fn summarise(r: &LineResults, top_reaction: (f64, f64)) -> StaticSummary {
    let n = r.arc.len();
    let mut touchdown_arc = None;
    let mut touchdown_moment = None;
    for i in 1..n {
        if r.penetration[i] > 0.0 && r.penetration[i - 1] <= 0.0 {
            let f = -r.penetration[i - 1] / (r.penetration[i] - r.penetration[i - 1]);
            touchdown_arc = Some(r.arc[i - 1] + f * (r.arc[i] - r.arc[i - 1]));
            touchdown_moment = Some(r.moment[i - 1] + f * (r.moment[i] - r.moment[i - 1]));
            break;
        }
    }
    let mut sag = (0.0, 0.0);
    let mut abs = (0.0f64, 0.0);
    for i in 0..n {
        if r.moment[i] < sag.0 {
            sag = (r.moment[i], r.arc[i]);
        }
        if r.moment[i].abs() > abs.0.abs() {
            abs = (r.moment[i], r.arc[i]);
        }
    }
    // The tangent at the top points down the line; its angle from the downward vertical.
    let th = r.theta[0];
    let (tx, tz) = (th.cos(), th.sin());
    let from_vertical = (tx.abs()).atan2(-tz);
    StaticSummary {
        top_tension: (top_reaction.0.powi(2) + top_reaction.1.powi(2)).sqrt(),
        horizontal_tension: top_reaction.0.abs(),
        touchdown_arc,
        max_sag_moment: sag,
        max_abs_moment: abs,
        touchdown_moment,
        top_angle_from_vertical: from_vertical,
    }
}
