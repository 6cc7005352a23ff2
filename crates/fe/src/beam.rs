//! The 2D corotational Euler–Bernoulli beam element (Crisfield 1991, Battini 2002), as a pure kernel.
//!
//! Degrees of freedom of an element: `d = (x1, z1, θ1, x2, z2, θ2)`, with `θ` the absolute angle of the
//! tangent (counter-clockwise from the x axis) and the stress-free reference **straight** of length
//! `L0` (the catenary is only a starting guess, never a stress-free state).
//!
//! **Corotational frame.** Chord `(dx, dz) = (x2 − x1, z2 − z1)`, `L = |(dx, dz)|`, `β = atan2(dz, dx)`,
//! `c = cos β`, `s = sin β`. Local (basic) deformations:
//!
//! ```text
//! u   = L − L0                       axial extension
//! θ1l = wrap(θ1 − β),  θ2l = wrap(θ2 − β)   end rotations relative to the chord, in (−π, π]
//! ```
//!
//! **Basic response** (linear in the local frame):
//!
//! ```text
//! N  = EA/L0 · u
//! M1 = EI/L0 · (4 θ1l + 2 θ2l)
//! M2 = EI/L0 · (2 θ1l + 4 θ2l)
//! K_l = diag(EA/L0, EI/L0·[[4, 2], [2, 4]])
//! ```
//!
//! **Transformation.** With `r = (−c, −s, 0, c, s, 0)` and `q = (s, −c, 0, −s, c, 0)`,
//! `δu = r·δd`, `δβ = q·δd / L`, so `B = [r; e3 − q/L; e6 − q/L]` and
//!
//! ```text
//! f = Bᵀ (N, M1, M2)
//! K = Bᵀ K_l B + (N/L)·q qᵀ + ((M1 + M2)/L²)·(r qᵀ + q rᵀ)
//! ```
//!
//! The internal bending moment along the element (cubic Hermite interpolation of the local rotations)
//! is `M(0) = −M1` at end 1 and `M(1) = M2` at end 2, with `M = EI·dθ/ds`. With the nodes numbered from
//! the top of a riser, a sag bend (concave up) has `dθ/ds < 0`, so its moment is negative, the paper's
//! convention.
//!
//! **Lanes.** [`corotational_forces_lanes`] and [`corotational_tangent_lanes`] evaluate
//! [`ELEMENT_LANES`] elements at once (the assembly's path), in loops over the lanes that the
//! compiler turns into vector instructions: the same operations in the same order as
//! [`corotational_beam_chord`], so the same values to the bit (tested), with the arctangent's
//! reductions and the angle wrap chosen by selects instead of branches. Both kernels write the
//! tangent's upper triangle from 4 sums of [`tangent_entry`] and the bending rows (the second
//! node's translations are the first's negated, a rotation's terms add zeros: [`fold_tangent`]).

/// Section properties of an element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Axial stiffness EA, N.
    pub ea: f64,
    /// Bending stiffness EI, N·m².
    pub ei: f64,
}

/// What the element kernel returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamResponse {
    /// Internal force vector in global coordinates `(fx1, fz1, m1, fx2, fz2, m2)` (N, N·m).
    pub force: [f64; 6],
    /// Tangent stiffness, 6×6, row-major.
    pub stiffness: [[f64; 6]; 6],
    /// Axial force N (positive in tension), N.
    pub axial: f64,
    /// Internal bending moment at end 1, `−M1`, N·m.
    pub moment1: f64,
    /// Internal bending moment at end 2, `M2`, N·m.
    pub moment2: f64,
    /// Current chord angle β, rad.
    pub chord_angle: f64,
}

/// The corotational transformation of a chord `(dx, dz)`: its length, `r`, `q` and the rows
/// `b1 = e3 − q/L`, `b2 = e6 − q/L` of `B` (the module docs).
struct Basis {
    l: f64,
    r: [f64; 6],
    q: [f64; 6],
    b1: [f64; 6],
    b2: [f64; 6],
}

#[inline]
fn basis(dx: f64, dz: f64) -> Basis {
    let l = (dx * dx + dz * dz).sqrt();
    let c = dx / l;
    let s = dz / l;
    let r = [-c, -s, 0.0, c, s, 0.0];
    let q = [s, -c, 0.0, -s, c, 0.0];
    let mut b1 = [0.0; 6];
    let mut b2 = [0.0; 6];
    for i in 0..6 {
        b1[i] = -q[i] / l;
        b2[i] = -q[i] / l;
    }
    b1[2] += 1.0;
    b2[5] += 1.0;
    Basis { l, r, q, b1, b2 }
}

impl Basis {
    /// Entry `(i, j)` of the tangent ([`tangent_entry`]) with `(ka, kb)` and `(gq, gm)`.
    #[inline(always)]
    fn tangent_entry(&self, (ka, kb): (f64, f64), (gq, gm): (f64, f64), i: usize, j: usize) -> f64 {
        let Basis { r, q, b1, b2, .. } = self;
        tangent_entry(
            ka,
            kb,
            (r[i], r[j]),
            (q[i], q[j]),
            (b1[i], b1[j]),
            (b2[i], b2[j]),
            gq,
            gm,
        )
    }
}

/// The basic response `(N, M1, M2) = K_l·(u, θ1l, θ2l)` with `K_l = diag(ka, kb·[[4, 2], [2, 4]])`
/// (`ka = EA/L0`, `kb = EI/L0`; for the damping, `β` times them on the deformation rates): the one
/// place the element's material law is written. Every kernel (element by element, in lanes, the
/// damping) calls it.
#[inline(always)]
fn basic_response(ka: f64, kb: f64, u: f64, t1: f64, t2: f64) -> (f64, f64, f64) {
    (
        ka * u,
        kb * (4.0 * t1 + 2.0 * t2),
        kb * (2.0 * t1 + 4.0 * t2),
    )
}

/// Entry `i` of the end forces `f = Bᵀ (N, M1, M2) = r·N + b1·M1 + b2·M2` from the rows' entries.
#[inline(always)]
fn end_force(r: f64, b1: f64, b2: f64, (n, m1, m2): (f64, f64, f64)) -> f64 {
    r * n + b1 * m1 + b2 * m2
}

/// Entry `(i, j)` of the material stiffness `Bᵀ K_l B = ka·r rᵀ + [b1 b2]·kb[[4, 2], [2, 4]]·[b1 b2]ᵀ`
/// from the rows' entries `(r_i, r_j)`, `(b1_i, b1_j)`, `(b2_i, b2_j)`.
#[inline(always)]
fn material_entry(ka: f64, kb: f64, r: (f64, f64), b1: (f64, f64), b2: (f64, f64)) -> f64 {
    let (a1, a2) = bending_row(kb, b1.0, b2.0);
    ka * r.0 * r.1 + a1 * b1.1 + a2 * b2.1
}

/// Row `i` of the bending part `kb[[4, 2], [2, 4]]·[b1 b2]ᵀ` of the material stiffness, from
/// `(b1_i, b2_i)`: `(a1, a2)` with the material entry `(i, j)` `ka·r_i·r_j + a1·b1_j + a2·b2_j`.
#[inline(always)]
fn bending_row(kb: f64, b1: f64, b2: f64) -> (f64, f64) {
    let (k11, k12, k22) = (4.0 * kb, 2.0 * kb, 4.0 * kb);
    (k11 * b1 + k12 * b2, k12 * b1 + k22 * b2)
}

/// Entry `(i, j)` of the tangent `K = Bᵀ K_l B + gq·q qᵀ + gm·(r qᵀ + q rᵀ)`, `gq = N/L`,
/// `gm = (M1 + M2)/L²`: the material entry and the geometric terms, in that order (the one place
/// the tangent is written; the element-by-element kernel and the lanes call it through
/// [`fold_tangent`], which takes the entries with a rotation's index from [`bending_row`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn tangent_entry(
    ka: f64,
    kb: f64,
    r: (f64, f64),
    q: (f64, f64),
    b1: (f64, f64),
    b2: (f64, f64),
    gq: f64,
    gm: f64,
) -> f64 {
    material_entry(ka, kb, r, b1, b2) + gq * q.0 * q.1 + gm * (r.0 * q.1 + q.0 * r.1)
}

/// Stiffness-proportional (Rayleigh) structural damping of an element, on its basic (material)
/// deformation rates only: with `ḋ_b = B·v` (extension rate and end-rotation rates relative to the
/// chord, `B` as above),
///
/// ```text
/// f_d = β·Bᵀ K_l B·v,     C = ∂f_d/∂v = β·Bᵀ K_l B
/// ```
///
/// A rigid-body motion of the element (translation or rotation) has `B·v = 0` and is not damped;
/// the geometric stiffness is left out for that reason. `β = ζ·T/π` damps a mode of period `T` at
/// the fraction `ζ` of critical (and a mode of period T' at `ζ·T/T'`). Pure; allocates nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampingResponse {
    /// Damping force in global coordinates, N and N·m.
    pub force: [f64; 6],
    /// `C = ∂f/∂v`, 6×6, row-major (zero unless asked for).
    pub damping: [[f64; 6]; 6],
}

/// See [`DampingResponse`]: the element's chord `(dx, dz)`, `L0`, section, `β` (s) and nodal
/// velocities `v = (ẋ1, ż1, θ̇1, ẋ2, ż2, θ̇2)`.
#[inline]
pub fn structural_damping(
    dx: f64,
    dz: f64,
    l0: f64,
    sec: &Section,
    beta: f64,
    v: &[f64; 6],
    with_damping: bool,
) -> DampingResponse {
    let Basis { r, b1, b2, .. } = basis(dx, dz);
    let dot = |a: &[f64; 6]| a.iter().zip(v).map(|(x, y)| x * y).sum::<f64>();
    let (e0, e1, e2) = (dot(&r), dot(&b1), dot(&b2));
    let ka = beta * sec.ea / l0;
    let kb = beta * sec.ei / l0;
    let (n, m1, m2) = basic_response(ka, kb, e0, e1, e2);
    let mut force = [0.0; 6];
    for i in 0..6 {
        force[i] = end_force(r[i], b1[i], b2[i], (n, m1, m2));
    }
    let mut damping = [[0.0; 6]; 6];
    if with_damping {
        for i in 0..6 {
            for j in 0..6 {
                damping[i][j] =
                    material_entry(ka, kb, (r[i], r[j]), (b1[i], b1[j]), (b2[i], b2[j]));
            }
        }
    }
    DampingResponse { force, damping }
}

/// Wraps an angle to (−π, π].
#[inline]
pub fn wrap(a: f64) -> f64 {
    if a > -std::f64::consts::PI && a <= std::f64::consts::PI {
        return a; // the usual case, without the remainder (identical result)
    }
    let two_pi = std::f64::consts::TAU;
    let mut w = a % two_pi;
    if w > std::f64::consts::PI {
        w -= two_pi;
    } else if w <= -std::f64::consts::PI {
        w += two_pi;
    }
    w
}

/// [`wrap`] without branches for `|a| < 4π` (the caller checks): `a mod 2π` is then `a` or
/// `a ∓ 2π`, and `a ∓ 2π` is exact for `2π ≤ |a| < 4π` (Sterbenz), as the remainder is; the
/// same value as [`wrap`] to the bit.
#[inline(always)]
fn wrap_near(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let w = if a.abs() >= TAU {
        a - TAU.copysign(a)
    } else {
        a
    };
    if w > PI {
        w - TAU
    } else if w <= -PI {
        w + TAU
    } else {
        w
    }
}

/// The element response at the nodal values `d = (x1, z1, θ1, x2, z2, θ2)`. Pure; allocates nothing.
/// `with_stiffness = false` skips the 6×6 tangent (it is then zero).
#[inline]
pub fn corotational_beam(
    d: &[f64; 6],
    l0: f64,
    sec: &Section,
    with_stiffness: bool,
) -> BeamResponse {
    corotational_beam_chord(
        d[3] - d[0],
        d[4] - d[1],
        d[2],
        d[5],
        l0,
        sec,
        with_stiffness,
    )
}

/// The element response from the chord `(dx, dz) = (x2 − x1, z2 − z1)` and the end angles. The
/// element depends on nothing else (a rigid translation changes nothing), so a solver that keeps
/// positions as a fixed base plus a displacement can pass the chord at full precision.
#[inline]
pub fn corotational_beam_chord(
    dx: f64,
    dz: f64,
    theta1: f64,
    theta2: f64,
    l0: f64,
    sec: &Section,
    with_stiffness: bool,
) -> BeamResponse {
    corotational_beam_chord_k(
        dx,
        dz,
        theta1,
        theta2,
        l0,
        (sec.ea / l0, sec.ei / l0),
        with_stiffness,
    )
}

/// [`corotational_beam_chord`] with `(EA/L0, EI/L0)` given (as the caller may keep them).
#[inline]
pub fn corotational_beam_chord_k(
    dx: f64,
    dz: f64,
    theta1: f64,
    theta2: f64,
    l0: f64,
    (ka, kb): (f64, f64),
    with_stiffness: bool,
) -> BeamResponse {
    let bs = basis(dx, dz);
    let Basis { l, r, b1, b2, .. } = bs;
    let beta = crate::fastmath::atan2(dz, dx);
    let t1 = wrap(theta1 - beta);
    let t2 = wrap(theta2 - beta);
    let (n, m1, m2) = basic_response(ka, kb, l - l0, t1, t2);
    let mut force = [0.0; 6];
    for i in 0..6 {
        force[i] = end_force(r[i], b1[i], b2[i], (n, m1, m2));
    }
    let mut k = [[0.0; 6]; 6];
    if with_stiffness {
        let gq = n / l;
        let gm = (m1 + m2) / (l * l);
        let mut upper = [[0.0; 1]; 21];
        fold_tangent(
            |i, j, _| bs.tangent_entry((ka, kb), (gq, gm), i, j),
            |i, _| bending_row(kb, b1[i], b2[i]),
            &mut upper,
        );
        // Symmetric: the upper triangle, mirrored.
        for (&(i, j), &[v]) in UPPER_PAIRS.iter().zip(&upper) {
            k[i][j] = v;
            k[j][i] = v;
        }
    }
    BeamResponse {
        force,
        stiffness: k,
        axial: n,
        moment1: -m1,
        moment2: m2,
        chord_angle: beta,
    }
}

/// Elements of one pass of [`corotational_forces_lanes`].
pub const ELEMENT_LANES: usize = 4;

/// Inputs of [`corotational_forces_lanes`] for `L` elements: the chords, the end angles, and
/// `L0`, `EA/L0` and `EI/L0` (each the quotient [`corotational_beam_chord`] forms).
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct ChordLanes<const L: usize> {
    pub dx: [f64; L],
    pub dz: [f64; L],
    pub theta1: [f64; L],
    pub theta2: [f64; L],
    pub l0: [f64; L],
    pub ka: [f64; L],
    pub kb: [f64; L],
}

/// The forces of `L` elements from [`corotational_forces_lanes`]: `force[0..6]` of
/// [`BeamResponse`] are `(−f3, −f4, f2, f3, f4, f5)`, and `(N, −M1, M2)` its
/// `(axial, moment1, moment2)`.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct ForceLanes<const L: usize> {
    pub f2: [f64; L],
    pub f3: [f64; L],
    pub f4: [f64; L],
    pub f5: [f64; L],
    pub axial: [f64; L],
    pub m1: [f64; L],
    pub m2: [f64; L],
}

impl<const L: usize> Default for ChordLanes<L> {
    fn default() -> Self {
        Self {
            dx: [1.0; L],
            dz: [0.0; L],
            theta1: [0.0; L],
            theta2: [0.0; L],
            l0: [1.0; L],
            ka: [0.0; L],
            kb: [0.0; L],
        }
    }
}

impl<const L: usize> Default for ForceLanes<L> {
    fn default() -> Self {
        Self {
            f2: [0.0; L],
            f3: [0.0; L],
            f4: [0.0; L],
            f5: [0.0; L],
            axial: [0.0; L],
            m1: [0.0; L],
            m2: [0.0; L],
        }
    }
}

/// The forces of [`corotational_beam_chord`] (without the tangent) for `L` elements at once, in
/// loops over the lanes that the compiler vectorises: the residual-only evaluations of a Newton
/// step are two thirds of them, and element by element the kernel's divisions, square root and
/// arctangent run one at a time.
///
/// **Same values to the bit** as [`corotational_beam_chord`]: the same operations in the same
/// order. With `s_l = s/L` and `c_l = c/L` (so `b1 = (−s_l, c_l, 1, s_l, −c_l, −0)` and
/// `b2 = (−s_l, c_l, −0, s_l, −c_l, 1)`),
///
/// ```text
/// f3 = (c·N + s_l·M1) + s_l·M2      f0 = −f3   (the same sums with every term negated)
/// f4 = (s·N − c_l·M1) − c_l·M2      f1 = −f4
/// f2 = (0·N + M1) + (−0)·M2         f5 = (0·N + (−0)·M1) + M2
/// ```
///
/// A lane where the arctangent or the angle wrap leaves its common path (a vertical or
/// degenerate chord, an end rotation past ±π, a NaN) is computed again by
/// [`corotational_beam_chord`].
#[inline(always)]
pub fn corotational_forces_lanes<const L: usize>(
    inp: &ChordLanes<L>,
    out: &mut ForceLanes<L>,
) -> bool {
    let mut basis = ChordBasisLanes::default();
    let special = forces_lanes_common(inp, out, &mut basis);
    if special {
        element_by_element(inp, out, None);
    }
    special
}

/// The chord's length `L`, `c`, `s`, `s/L` and `c/L` per lane, as the forces computed them (the
/// tangent reuses them).
struct ChordBasisLanes<const L: usize> {
    l: [f64; L],
    c: [f64; L],
    s: [f64; L],
    sl: [f64; L],
    cl: [f64; L],
}

impl<const L: usize> Default for ChordBasisLanes<L> {
    fn default() -> Self {
        Self {
            l: [0.0; L],
            c: [0.0; L],
            s: [0.0; L],
            sl: [0.0; L],
            cl: [0.0; L],
        }
    }
}

/// The forces of every lane on the common path, and its basis; whether a lane left it (its
/// values are then to be recomputed by [`element_by_element`]).
#[inline(always)]
#[allow(clippy::needless_range_loop, clippy::neg_cmp_op_on_partial_ord)]
fn forces_lanes_common<const L: usize>(
    inp: &ChordLanes<L>,
    out: &mut ForceLanes<L>,
    basis: &mut ChordBasisLanes<L>,
) -> bool {
    use std::f64::consts::TAU;
    let mut beta = [0.0; L];
    let mut special = crate::fastmath::atan2_lanes(&inp.dz, &inp.dx, &mut beta);
    for k in 0..L {
        let (dx, dz) = (inp.dx[k], inp.dz[k]);
        let l = (dx * dx + dz * dz).sqrt();
        let c = dx / l;
        let s = dz / l;
        let (t1, t2) = (inp.theta1[k] - beta[k], inp.theta2[k] - beta[k]);
        special |= !(t1.abs() < 2.0 * TAU && t2.abs() < 2.0 * TAU);
        let (t1, t2) = (wrap_near(t1), wrap_near(t2));
        let (n, m1, m2) = basic_response(inp.ka[k], inp.kb[k], l - inp.l0[k], t1, t2);
        let (sl, cl) = (s / l, c / l);
        // Rows 2–5 of r, b1 and b2 (rows 0 and 1 are those of 3 and 4 negated).
        let nm = (n, m1, m2);
        out.f2[k] = end_force(0.0, 1.0, -0.0, nm);
        out.f3[k] = end_force(c, sl, sl, nm);
        out.f4[k] = end_force(s, -cl, -cl, nm);
        out.f5[k] = end_force(0.0, -0.0, 1.0, nm);
        out.axial[k] = n;
        out.m1[k] = -m1;
        out.m2[k] = m2;
        (basis.l[k], basis.c[k], basis.s[k]) = (l, c, s);
        (basis.sl[k], basis.cl[k]) = (sl, cl);
    }
    special
}

/// Every lane again by [`corotational_beam_chord_k`] (rare: a lane left the common path; a
/// common lane gives the same values), with the tangent into `kout` if given.
#[cold]
#[inline(never)]
fn element_by_element<const L: usize>(
    inp: &ChordLanes<L>,
    out: &mut ForceLanes<L>,
    mut kout: Option<&mut [[f64; L]; 21]>,
) {
    for k in 0..L {
        let r = corotational_beam_chord_k(
            inp.dx[k],
            inp.dz[k],
            inp.theta1[k],
            inp.theta2[k],
            inp.l0[k],
            (inp.ka[k], inp.kb[k]),
            kout.is_some(),
        );
        out.f2[k] = r.force[2];
        out.f3[k] = r.force[3];
        out.f4[k] = r.force[4];
        out.f5[k] = r.force[5];
        out.axial[k] = r.axial;
        out.m1[k] = r.moment1;
        out.m2[k] = r.moment2;
        if let Some(kl) = kout.as_deref_mut() {
            for (t, &(i, j)) in UPPER_PAIRS.iter().enumerate() {
                kl[t][k] = r.stiffness[i][j];
            }
        }
    }
}

/// The position of the entry `(i, j)`, `i ≤ j`, of a symmetric 6×6 matrix in its upper triangle
/// stored by rows (21 entries).
pub const fn upper_index(i: usize, j: usize) -> usize {
    6 * i - (i * i.saturating_sub(1)) / 2 + j - i
}

/// The `(i, j)` of each entry of [`upper_index`].
pub const UPPER_PAIRS: [(usize, usize); 21] = {
    let mut p = [(0, 0); 21];
    let mut i = 0;
    while i < 6 {
        let mut j = i;
        while j < 6 {
            p[upper_index(i, j)] = (i, j);
            j += 1;
        }
        i += 1;
    }
    p
};

/// [`corotational_forces_lanes`] and the tangent: `k[upper_index(i, j)]` is
/// [`BeamResponse::stiffness`]`[i][j]` (`i ≤ j`) of each element, to the bit (the same sums, from
/// `r`, `q`, `b1`, `b2` as in the module docs, with their zeros and ones).
#[inline(always)]
#[allow(clippy::needless_range_loop)]
pub fn corotational_tangent_lanes<const L: usize>(
    inp: &ChordLanes<L>,
    out: &mut ForceLanes<L>,
    kout: &mut [[f64; L]; 21],
) {
    let mut basis = ChordBasisLanes::default();
    if forces_lanes_common(inp, out, &mut basis) {
        element_by_element(inp, out, Some(kout));
        return;
    }
    let mut r = [[0.0; L]; 6];
    let mut q = [[0.0; L]; 6];
    let mut b1 = [[0.0; L]; 6];
    let mut b2 = [[0.0; L]; 6];
    let (mut gq, mut gm, mut kb) = ([0.0; L], [0.0; L], [0.0; L]);
    for k in 0..L {
        let ChordBasisLanes { l, c, s, sl, cl } = &basis;
        let (l, c, s, sl, cl) = (l[k], c[k], s[k], sl[k], cl[k]);
        let (m1, m2) = (-out.m1[k], out.m2[k]);
        [r[0][k], r[1][k], r[2][k], r[3][k], r[4][k], r[5][k]] = [-c, -s, 0.0, c, s, 0.0];
        [q[0][k], q[1][k], q[2][k], q[3][k], q[4][k], q[5][k]] = [s, -c, 0.0, -s, c, 0.0];
        // −q/L, plus e3 (b1) or e6 (b2): −0/L = −0 for L > 0, and −0 + 1 = 1.
        [b1[0][k], b1[1][k], b1[2][k], b1[3][k], b1[4][k], b1[5][k]] =
            [-sl, cl, 1.0, sl, -cl, -0.0];
        [b2[0][k], b2[1][k], b2[2][k], b2[3][k], b2[4][k], b2[5][k]] =
            [-sl, cl, -0.0, sl, -cl, 1.0];
        gq[k] = out.axial[k] / l;
        gm[k] = (m1 + m2) / (l * l);
        kb[k] = inp.kb[k];
    }
    let entry = |i: usize, j: usize, k: usize| {
        tangent_entry(
            inp.ka[k],
            kb[k],
            (r[i][k], r[j][k]),
            (q[i][k], q[j][k]),
            (b1[i][k], b1[j][k]),
            (b2[i][k], b2[j][k]),
            gq[k],
            gm[k],
        )
    };
    let row = |i: usize, k: usize| bending_row(kb[k], b1[i][k], b2[i][k]);
    fold_tangent(entry, row, kout);
}

/// The tangent's upper triangle ([`upper_index`]) of `L` elements, from [`tangent_entry`]
/// (`entry(i, j, lane)`) for the four entries of the first node's translations and from the
/// bending rows ([`bending_row`], `row(i, lane)`) for the rest; each entry the value the sum of
/// [`tangent_entry`] gives for it:
///
/// - The second node's translations have `r`, `q`, `b1` and `b2` the first node's negated
///   (`r = (−c, −s, 0, c, s, 0)`, `q = (s, −c, 0, −s, c, 0)`, `b1` and `b2`
///   `(−s/L, c/L, ·, s/L, −c/L, ·)`), so each product in an entry's sum, and the sum, changes its
///   sign and nothing else: `K[i][j+3] = −K[i][j]`, `K[i+3][j+3] = K[i][j]` (`i, j ∈ {0, 1}`), and
///   likewise with one index a rotation's.
/// - A rotation's `r` and `q` are zero and its `b1`, `b2` are `(1, −0)` (θ1) or `(−0, 1)` (θ2):
///   its terms in `r`, `q` add zeros, and the entry is the bending row's `a1` or `a2`:
///   `K[i][2] = K[2][i] = a1_i`, `K[i][5] = a2_i`, `K[2][2] = a1_2 = 4kb`, `K[2][5] = a2_2 = 2kb`,
///   `K[5][5] = a2_5 = 4kb`.
///
/// The same values as computing each entry; an entry that is zero may change its zero's sign,
/// which no sum it is added to can see (tested: `folded_tangent_is_every_entry_computed`).
#[inline(always)]
#[allow(clippy::needless_range_loop)]
fn fold_tangent<const L: usize>(
    entry: impl Fn(usize, usize, usize) -> f64,
    row: impl Fn(usize, usize) -> (f64, f64),
    kout: &mut [[f64; L]; 21],
) {
    for k in 0..L {
        let (e00, e01, e10, e11) = (
            entry(0, 0, k),
            entry(0, 1, k),
            entry(1, 0, k),
            entry(1, 1, k),
        );
        let ((a1_0, a2_0), (a1_1, a2_1)) = (row(0, k), row(1, k));
        let ((a1_2, a2_2), (_, a2_5)) = (row(2, k), row(5, k));
        // By upper_index: (0,0) 0, (0,3) 3, (3,3) 15; (0,1) 1, (0,4) 4, (3,4) 16; (1,3) 8;
        // (1,1) 6, (1,4) 9, (4,4) 18.
        (kout[0][k], kout[3][k], kout[15][k]) = (e00, -e00, e00);
        (kout[1][k], kout[4][k], kout[16][k]) = (e01, -e01, e01);
        kout[8][k] = -e10;
        (kout[6][k], kout[9][k], kout[18][k]) = (e11, -e11, e11);
        // (0,2) 2, (2,3) 12; (0,5) 5, (3,5) 17; (1,2) 7, (2,4) 13; (1,5) 10, (4,5) 19.
        (kout[2][k], kout[12][k]) = (a1_0, -a1_0);
        (kout[5][k], kout[17][k]) = (a2_0, -a2_0);
        (kout[7][k], kout[13][k]) = (a1_1, -a1_1);
        (kout[10][k], kout[19][k]) = (a2_1, -a2_1);
        // (2,2) 11, (2,5) 14, (5,5) 20.
        (kout[11][k], kout[14][k], kout[20][k]) = (a1_2, a2_2, a2_5);
    }
}

#[cfg(test)]
mod tests;
