//! The assembly that statics and dynamics share: the structural residual and tangent of a line (the
//! corotational elements, the submerged weight and the flexjoint), the sparse pattern with its
//! precomputed slots, the factorisation, and the nodal results.
//!
//! With `q = q_b + u` (the placement's base plus displacements), the structural residual on every
//! global dof is
//!
//! ```text
//! R_s(q) = Σ_e f_e(q) + k_θ (θ_fj − θ_n) e_fj − F_dead
//! ```
//!
//! and its tangent `K_s = ∂R_s/∂q` is symmetric. Statics add the seabed backbone
//! ([`crate::statics`]); dynamics add the seabed from each node's history, Morison loads and inertia
//! ([`crate::dynamics`], [`crate::environment`]). Nothing here allocates after [`Assembler::new`].
//!
//! **Nodal results.** Tension and moment at an interior node are the means of the two adjacent
//! elements' values there; at a supported end node the tension is the magnitude of the support
//! reaction, which the caller gives (statics: the residual there; dynamics: the residual plus the
//! node's inertia). [`Assembler::fill_results`] is the one place that fills [`LineResults`].

use crate::beam::{
    corotational_forces_lanes, corotational_tangent_lanes, upper_index, ChordLanes, ForceLanes,
    ELEMENT_LANES, UPPER_PAIRS,
};
use std::ops::Range;

use crate::model::LineModel;
use crate::sparse::{LinearSolver, SolveError, SparseSym};

const NONE: usize = usize::MAX;

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

/// [`Assembler::assemble_element_forces`] for the processor it runs on: the lanes' loops become
/// AVX2 or AVX-512 instructions where there are (no fused multiply-adds: the same values to the
/// bit on every processor).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn element_forces_dispatch(asm: &mut Assembler, pl: &Placement, u: &[f64], elements: Range<usize>) {
    asm.element_forces_lanes(pl, u, elements);
}

/// [`Assembler::assemble_elements_with_tangent`] for the processor it runs on (as
/// [`element_forces_dispatch`]).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn element_tangents_dispatch(
    asm: &mut Assembler,
    pl: &Placement,
    u: &[f64],
    elements: Range<usize>,
) {
    asm.element_tangents_lanes(pl, u, elements);
}

/// A thread's part of a line (issue 48, two threads in one run): the elements it computes and the
/// nodes it owns. Element `e` joins nodes `e` and `e + 1`, so a part that owns nodes `a..b`
/// computes the elements `a − 1 ..= b − 1` that touch them (within the line): the element across
/// a boundary between two parts is computed by both, and each part's own nodes get their sums
/// whole, in the whole line's order ([`Assembler::assemble_structure_part`],
/// [`crate::loads::assemble_part`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Part {
    /// The elements it computes.
    pub elements: Range<usize>,
    /// The nodes it owns.
    pub nodes: Range<usize>,
}

impl Part {
    /// The whole line.
    pub fn whole(model: &LineModel) -> Self {
        Self {
            elements: 0..model.elements.len(),
            nodes: 0..model.nodes(),
        }
    }

    /// The line in two parts, the first owning the nodes `0..=k` (`k` below the last node).
    pub fn halves(model: &LineModel, k: usize) -> [Self; 2] {
        let (ne, n) = (model.elements.len(), model.nodes());
        [
            Self {
                elements: 0..k + 1,
                nodes: 0..k + 1,
            },
            Self {
                elements: k..ne,
                nodes: k + 1..n,
            },
        ]
    }
}

/// An element's stored tangent entries: `(entry of the element's upper triangle (see
/// [`upper_index`]), value slot)` for its pairs `(i ≤ j)` of free equations (at most 21), and how
/// many there are.
type ElemPairs = ([(u8, usize); 21], u8);

/// The structural assembly of one line: pattern, slots, factorisation and element results. Part of
/// a Workspace: never saved, rebuilt from the Model.
#[derive(Debug)]
pub struct Assembler {
    /// The tangent (free equations), upper triangle.
    pub k: SparseSym,
    solver: LinearSolver,
    /// For element `e`, the value slot of local pair `(a, b)` (`usize::MAX` if not stored).
    elem_pairs: Vec<ElemPairs>,
    /// For an element whose 21 entries are all stored at the common offsets
    /// (`regular_offsets`) from its first slot (an interior element: nearly all of them), that
    /// slot; `NONE` for the others, which scatter through `elem_pairs`.
    elem_base: Vec<usize>,
    /// The slots of a regular element's entries (in [`upper_index`] order) from its first slot.
    regular_offsets: [usize; 21],
    /// The diagonal slot of each equation.
    diag_slots: Vec<usize>,
    /// Each node's slots `[xx, xz, zz]` (`NONE` where a dof is prescribed).
    node_slots: Vec<[usize; 3]>,
    /// Global residual `R(q)`, 3 per node.
    pub residual: Vec<f64>,
    /// Element axial forces, N.
    pub axial: Vec<f64>,
    /// Element internal end moments `(M(0), M(1))`, N·m.
    pub moments: Vec<(f64, f64)>,
    /// The tangent values of the last factorisation (kept so that a checkpoint can restore the
    /// factorisation bit for bit).
    factored: Vec<f64>,
    /// Per element `(L0, EA/L0, EI/L0)`, the quotients the element kernel forms.
    stiffness_per_length: Vec<(f64, f64, f64)>,
}

impl Assembler {
    /// Takes element `e`'s rest length and stiffness from the Model again (after
    /// [`LineModel::set_top_rest_length`]).
    pub fn element_changed(&mut self, model: &LineModel, e: usize) {
        let el = &model.elements[e];
        self.stiffness_per_length[e] = (el.l0, el.section.ea / el.l0, el.section.ei / el.l0);
    }

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
        let mut elem_pairs = vec![([(0u8, 0usize); 21], 0u8); ne];
        for (e, (pairs, len)) in elem_pairs.iter_mut().enumerate() {
            for a in 0..6 {
                for b in 0..6 {
                    if let (Some(i), Some(j)) = (eq(3 * e + a), eq(3 * e + b)) {
                        if i <= j {
                            if let Some(s) = k.slot(i, j) {
                                // Equations are numbered in dof order, so a ≤ b.
                                debug_assert!(a <= b);
                                pairs[*len as usize] = (upper_index(a, b) as u8, s);
                                *len += 1;
                            }
                        }
                    }
                }
            }
        }
        // The offsets most elements with all 21 entries stored share (the interior ones'), and
        // every element that has them.
        let offsets = |(pairs, len): &ElemPairs| {
            let base = pairs[..*len as usize].iter().map(|p| p.1).min()?;
            let mut off = [0; 21];
            for (o, p) in off.iter_mut().zip(&pairs[..*len as usize]) {
                *o = p.1 - base;
            }
            (*len == 21 && pairs.iter().enumerate().all(|(t, p)| p.0 as usize == t))
                .then_some((base, off))
        };
        let mut counts: Vec<([usize; 21], usize)> = Vec::new();
        for (_, off) in elem_pairs.iter().filter_map(offsets) {
            match counts.iter_mut().find(|(o, _)| *o == off) {
                Some((_, c)) => *c += 1,
                None => counts.push((off, 1)),
            }
        }
        let regular_offsets = counts
            .iter()
            .max_by_key(|(_, c)| *c)
            .map_or([0; 21], |(off, _)| *off);
        let elem_base = elem_pairs
            .iter()
            .map(|p| match offsets(p) {
                Some((base, off)) if off == regular_offsets => base,
                _ => NONE,
            })
            .collect();
        let diag_slots = (0..model.n_eq)
            .map(|i| k.slot(i, i).unwrap_or(NONE))
            .collect();
        let diag = |g: usize| eq(g).and_then(|a| k.slot(a, a)).unwrap_or(NONE);
        let node_slots = (0..model.nodes())
            .map(|i| {
                let xz = match (eq(3 * i), eq(3 * i + 1)) {
                    (Some(a), Some(b)) => k.slot(a, b).unwrap_or(NONE),
                    _ => NONE,
                };
                [diag(3 * i), xz, diag(3 * i + 1)]
            })
            .collect();
        let solver = LinearSolver::new(&k)?;
        // A line: element e joins nodes e and e + 1 (the element passes write the residual node
        // by node from that).
        assert_eq!(
            model.nodes(),
            ne + 1,
            "a line has one node more than elements"
        );
        let n3 = 3 * model.nodes();
        let nnz = k.values.len();
        Ok(Self {
            k,
            solver,
            elem_pairs,
            elem_base,
            regular_offsets,
            diag_slots,
            node_slots,
            residual: vec![0.0; n3],
            axial: vec![0.0; ne],
            moments: vec![(0.0, 0.0); ne],
            factored: vec![0.0; nnz],
            stiffness_per_length: model
                .elements
                .iter()
                .map(|el| (el.l0, el.section.ea / el.l0, el.section.ei / el.l0))
                .collect(),
        })
    }

    /// The structural part of the residual and tangent: elements, submerged weight and flexjoint
    /// (no seabed, no fluid). Overwrites the residual (and the tangent, with `with_k`). The
    /// flexjoint's vessel-side reference is turned by `fj_rotation` (rad, counter-clockwise in the
    /// x–z plane: the vessel's rotation; 0 in statics): its moment is
    /// `−k_θ(θ − θ_neutral − fj_rotation)`. Allocates nothing.
    pub fn assemble_structure(
        &mut self,
        model: &LineModel,
        pl: &Placement,
        u: &[f64],
        fj_rotation: f64,
        with_k: bool,
    ) {
        let ne = self.axial.len();
        self.assemble_structure_part(model, pl, u, (fj_rotation, with_k), 0..ne);
    }

    /// [`Assembler::assemble_structure`] over the elements `elements` only (a thread's part of the
    /// line, issue 48): the residual of the nodes strictly inside the range (`start + 1 ..
    /// end`) and of the line's end nodes the range holds, and the tangent's columns of those
    /// nodes' equations, are those of the whole line to the bit; the two nodes at a range's inner
    /// ends hold a part of their sums only (each element's forces are computed whole, so the
    /// element across a boundary is computed by both parts). With the tangent, the columns the
    /// range touches are cleared first and no others.
    pub fn assemble_structure_part(
        &mut self,
        model: &LineModel,
        pl: &Placement,
        u: &[f64],
        (fj_rotation, with_k): (f64, bool),
        elements: Range<usize>,
    ) {
        let dofs = 3 * elements.start..3 * (elements.end + 1);
        // The element passes write every entry of the part's residual (no fill needed).
        if with_k {
            self.clear_columns(model, dofs.clone());
            self.assemble_elements_with_tangent(pl, u, elements);
        } else {
            self.assemble_element_forces(pl, u, elements);
        }
        // Zipped, not indexed: the indexed loop reloaded the residual's pointer and checked its
        // bound at every entry and ran scalar (2.3 % of the 3-hour storm's samples).
        for (r, f) in self.residual[dofs.clone()]
            .iter_mut()
            .zip(&model.dead_load[dofs.clone()])
        {
            *r -= f;
        }
        if let Some(fj) = &model.flexjoint {
            let g = 3 * fj.node + 2;
            if dofs.contains(&g) {
                let q = &pl.base;
                self.residual[g] += fj.stiffness * (q[g] + u[g] - fj.neutral - fj_rotation);
                if with_k {
                    if let Some(eq) = model.equation[g] {
                        self.k.values[self.diag_slots[eq]] += fj.stiffness;
                    }
                }
            }
        }
    }

    /// Zeroes the tangent's columns of the free equations among `dofs`.
    fn clear_columns(&mut self, model: &LineModel, dofs: Range<usize>) {
        let eqs = &model.equation[dofs];
        let (Some(lo), Some(hi)) = (
            eqs.iter().find_map(|e| *e),
            eqs.iter().rev().find_map(|e| *e),
        ) else {
            return;
        };
        self.k.clear_columns(lo..hi + 1);
    }

    /// The elements' forces, [`ELEMENT_LANES`] elements at a time
    /// ([`corotational_forces_lanes`]: the same values as element by element), added to the
    /// residual in element order. Compiled for the baseline processor and for AVX2 and AVX-512,
    /// chosen at run time ([`element_forces_dispatch`]).
    fn assemble_element_forces(&mut self, pl: &Placement, u: &[f64], elements: Range<usize>) {
        element_forces_dispatch(self, pl, u, elements);
    }

    #[inline(always)]
    fn element_forces_lanes(&mut self, pl: &Placement, u: &[f64], elements: Range<usize>) {
        const L: usize = ELEMENT_LANES;
        let ne = elements.end;
        let mut inp = ChordLanes::<L>::default();
        let mut out = ForceLanes::<L>::default();
        let mut carry = [0.0; 3];
        for e0 in elements.step_by(L) {
            let m = self.gather_chords(pl, u, (e0, ne), &mut inp);
            corotational_forces_lanes(&inp, &mut out);
            for k in 0..m {
                self.put_element_forces(e0 + k, k, &out, &mut carry);
            }
        }
        self.residual[3 * ne..3 * ne + 3].copy_from_slice(&carry);
    }

    /// The elements' forces and tangents, [`ELEMENT_LANES`] elements at a time
    /// ([`corotational_tangent_lanes`]), added in element order; compiled as
    /// [`Assembler::assemble_element_forces`] is ([`element_tangents_dispatch`]).
    fn assemble_elements_with_tangent(
        &mut self,
        pl: &Placement,
        u: &[f64],
        elements: Range<usize>,
    ) {
        element_tangents_dispatch(self, pl, u, elements);
    }

    #[inline(always)]
    #[allow(clippy::needless_range_loop)]
    fn element_tangents_lanes(&mut self, pl: &Placement, u: &[f64], elements: Range<usize>) {
        const L: usize = ELEMENT_LANES;
        let ne = elements.end;
        let mut inp = ChordLanes::<L>::default();
        let mut out = ForceLanes::<L>::default();
        let mut kl = [[0.0; L]; 21];
        let mut carry = [0.0; 3];
        for e0 in elements.step_by(L) {
            let m = self.gather_chords(pl, u, (e0, ne), &mut inp);
            corotational_tangent_lanes(&inp, &mut out, &mut kl);
            for k in 0..m {
                let e = e0 + k;
                self.put_element_forces(e, k, &out, &mut carry);
                // The stored (upper-triangle) entries only: at the common offsets from the
                // element's first slot, or from its own list.
                let base = self.elem_base[e];
                if base != NONE {
                    let values = &mut self.k.values[base..];
                    for (t, &o) in self.regular_offsets.iter().enumerate() {
                        values[o] += kl[t][k];
                    }
                } else {
                    let (pairs, len) = &self.elem_pairs[e];
                    for &(t, s) in &pairs[..*len as usize] {
                        self.k.values[s] += kl[t as usize][k];
                    }
                }
            }
        }
        self.residual[3 * ne..3 * ne + 3].copy_from_slice(&carry);
    }

    /// Elements `e0..end` (up to [`ELEMENT_LANES`] of them) into `inp`; returns how many there
    /// are (lanes past the last element get a harmless unit element, never added).
    #[inline(always)]
    fn gather_chords<const L: usize>(
        &self,
        pl: &Placement,
        u: &[f64],
        (e0, end): (usize, usize),
        inp: &mut ChordLanes<L>,
    ) -> usize {
        let q = &pl.base;
        let m = L.min(end - e0);
        for k in 0..L {
            let e = e0 + k.min(m - 1);
            let b = 3 * e;
            let [cx, cz] = pl.chords[e];
            (inp.l0[k], inp.ka[k], inp.kb[k]) = self.stiffness_per_length[e];
            if k < m {
                inp.dx[k] = cx + (u[b + 3] - u[b]);
                inp.dz[k] = cz + (u[b + 4] - u[b + 1]);
                inp.theta1[k] = q[b + 2] + u[b + 2];
                inp.theta2[k] = q[b + 5] + u[b + 5];
            } else {
                (inp.dx[k], inp.dz[k], inp.theta1[k], inp.theta2[k]) = (inp.l0[k], 0.0, 0.0, 0.0);
            }
        }
        m
    }

    /// Element `e`'s forces (lane `k` of `out`) into the residual, and its axial force and end
    /// moments. Elements come in order from a residual of zeros, so node `e`'s entries are
    /// `(0 + end forces of element e−1) + start forces of element e` — the sums an add into a
    /// zeroed residual makes, in their order (the `0 +` keeps a −0 as +0) — written once, with
    /// element `e`'s end forces carried in `carry` to the next element (the node after the last
    /// one takes the last `carry`). A read-modify-write of the residual instead loads, as one
    /// vector, entries the previous element has just stored as two: the store cannot be forwarded
    /// and the load waits for it.
    #[inline(always)]
    fn put_element_forces<const L: usize>(
        &mut self,
        e: usize,
        k: usize,
        out: &ForceLanes<L>,
        carry: &mut [f64; 3],
    ) {
        let b = 3 * e;
        let r = &mut self.residual[b..b + 3];
        r[0] = carry[0] + -out.f3[k];
        r[1] = carry[1] + -out.f4[k];
        r[2] = carry[2] + out.f2[k];
        *carry = [0.0 + out.f3[k], 0.0 + out.f4[k], 0.0 + out.f5[k]];
        self.axial[e] = out.axial[k];
        self.moments[e] = (out.m1[k], out.m2[k]);
    }

    /// Adds stiffness-proportional structural damping `β·Bᵀ K_l B·v` of every element
    /// ([`crate::beam::structural_damping`]) at the configuration `u` and velocities `v` to the
    /// residual and, with `with_c`, `c_scale` times its velocity derivative to the tangent. Allocates
    /// nothing.
    #[allow(clippy::too_many_arguments)]
    pub fn add_structural_damping(
        &mut self,
        model: &LineModel,
        pl: &Placement,
        u: &[f64],
        v: &[f64],
        beta: f64,
        (c_scale, with_c): (f64, bool),
        elements: Range<usize>,
    ) {
        for (e, el) in model
            .elements
            .iter()
            .enumerate()
            .take(elements.end)
            .skip(elements.start)
        {
            let b = 3 * e;
            let [cx, cz] = pl.chords[e];
            let ve = [v[b], v[b + 1], v[b + 2], v[b + 3], v[b + 4], v[b + 5]];
            let d = crate::beam::structural_damping(
                cx + (u[b + 3] - u[b]),
                cz + (u[b + 4] - u[b + 1]),
                el.l0,
                &el.section,
                beta,
                &ve,
                with_c,
            );
            for a in 0..6 {
                self.residual[b + a] += d.force[a];
            }
            if with_c {
                let (pairs, len) = &self.elem_pairs[e];
                for &(t, s) in &pairs[..*len as usize] {
                    let (a, c) = UPPER_PAIRS[t as usize];
                    self.k.values[s] += c_scale * d.damping[a][c];
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
    pub fn add_node_block(&mut self, i: usize, xx: f64, xz: f64, zz: f64) {
        for (s, v) in self.node_slots[i].into_iter().zip([xx, xz, zz]) {
            if s != NONE {
                self.k.values[s] += v;
            }
        }
    }

    /// Multiplies every assembled tangent value by `f`.
    pub fn scale_tangent(&mut self, f: f64) {
        for v in &mut self.k.values {
            *v *= f;
        }
    }

    /// Numeric factorisation of the tangent last assembled (its values are kept, see
    /// [`Assembler::factored_values`]).
    pub fn factor_tangent(&mut self) -> Result<(), SolveError> {
        let factored = self.solver.factor(&self.k);
        // Kept by exchange, not copied: every factorisation follows an assembly of the tangent,
        // which starts by clearing the values (after this, `k` holds stale values until then).
        std::mem::swap(&mut self.factored, &mut self.k.values);
        factored
    }

    /// The tangent values of the last factorisation.
    pub fn factored_values(&self) -> &[f64] {
        &self.factored
    }

    /// Factorises the tangent with the given values (a checkpoint's
    /// [`Assembler::factored_values`]): the same factorisation, bit for bit. The values must have
    /// the pattern's length.
    pub fn refactor_from(&mut self, values: &[f64]) -> Result<(), SolveError> {
        self.k.values.copy_from_slice(values);
        self.factor_tangent()
    }

    /// The number of stored tangent values (the pattern's length).
    pub fn pattern_len(&self) -> usize {
        self.k.values.len()
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
        // An interior node's mean is a halving: multiplied by ½, exactly the division's value,
        // without two divisions on the chain of every node of every converged step.
        if c == 2.0 {
            (t * 0.5, m * 0.5)
        } else {
            (t / c, m / c)
        }
    }

    /// Fills `out` at the configuration `u` just assembled: positions, angles, tension and moment
    /// (see the module docs), penetration (0 without a seabed) and, from the callers, each node's
    /// seabed force and contact mode, and the support reactions `(Rx, Rz)` at the two end nodes.
    /// Allocates nothing.
    #[allow(clippy::too_many_arguments)]
    pub fn fill_results(
        &self,
        model: &LineModel,
        pl: &Placement,
        u: &[f64],
        seabed_force: impl Fn(usize) -> f64,
        mode: impl Fn(usize) -> u8,
        end_reaction: impl Fn(usize) -> (f64, f64),
        out: &mut LineResults,
    ) {
        let n = model.nodes();
        for i in 0..n {
            let q = [
                pl.base[3 * i] + u[3 * i],
                pl.base[3 * i + 1] + u[3 * i + 1],
                pl.base[3 * i + 2] + u[3 * i + 2],
            ];
            out.x[i] = q[0];
            out.z[i] = q[1];
            out.theta[i] = q[2];
            (out.tension[i], out.moment[i]) = self.nodal_tension_moment(i);
            out.penetration[i] = model.penetration(i, q[0], q[1]).unwrap_or(0.0);
            out.seabed_force[i] = if model.seabed.is_some() {
                seabed_force(i)
            } else {
                0.0
            };
            out.mode[i] = mode(i);
        }
        for i in [0, n - 1] {
            let (rx, rz) = end_reaction(i);
            out.tension[i] = (rx * rx + rz * rz).sqrt();
        }
    }
}

/// Results along the line, one value per node (node 0 at the top; the arc lengths are the Model's).
/// The one nodal result type of statics and dynamics.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LineResults {
    /// x, m.
    pub x: Vec<f64>,
    /// z, m.
    pub z: Vec<f64>,
    /// Tangent angle θ, rad.
    pub theta: Vec<f64>,
    /// Effective tension, N (end nodes: the support reaction's magnitude, inertia included).
    pub tension: Vec<f64>,
    /// Bending moment, N·m (negative = sag).
    pub moment: Vec<f64>,
    /// Invert penetration below the mudline, m (positive down, ≤ 0 clear; 0 without a seabed).
    pub penetration: Vec<f64>,
    /// Seabed force (resistance, buoyancy and damping) per unit length, N/m.
    pub seabed_force: Vec<f64>,
    /// Contact mode code (0 not in contact, 1 initial penetration, 2 uplift, 3 repenetration).
    pub mode: Vec<u8>,
}

/// The first value of a converged step that is not a finite number, as `(quantity, node)`: the
/// nodal results and the State's displacements, velocities and accelerations, node by node. A run
/// stops there (`Stop::NonFinite` in the `catena` crate) before any observer sees the step, so no non-finite value is
/// ever recorded. (Inputs are checked for finiteness and range when the scene is read; this is the
/// guard for what the inputs did not show.)
pub fn first_non_finite(
    res: &LineResults,
    u: &[f64],
    v: &[f64],
    a: &[f64],
) -> Option<(&'static str, usize)> {
    let fields: [(&'static str, &[f64], usize); 10] = [
        ("x", &res.x, 1),
        ("z", &res.z, 1),
        ("rotation", &res.theta, 1),
        ("tension", &res.tension, 1),
        ("moment", &res.moment, 1),
        ("penetration", &res.penetration, 1),
        ("seabed force", &res.seabed_force, 1),
        ("displacement", u, 3),
        ("velocity", v, 3),
        ("acceleration", a, 3),
    ];
    // Nearly always every value is finite: check that first, eight values at a time (branch-free
    // within each eight, so the check vectorises), and look for the first one only if not.
    let finite = |xs: &[f64]| {
        let chunks = xs.chunks_exact(8);
        let rest = chunks.remainder();
        chunks
            .into_iter()
            .all(|c| c.iter().fold(true, |ok, x| ok & x.is_finite()))
            && rest.iter().all(|x| x.is_finite())
    };
    if fields.iter().all(|(_, vals, _)| finite(vals)) {
        return None;
    }
    let n = res.x.len();
    (0..n).find_map(|i| {
        fields.iter().find_map(|(name, vals, per)| {
            vals[per * i..per * (i + 1)]
                .iter()
                .any(|x| !x.is_finite())
                .then_some((*name, i))
        })
    })
}

impl LineResults {
    /// Results for `n` nodes, zeroed.
    pub fn new(n: usize) -> Self {
        Self {
            x: vec![0.0; n],
            z: vec![0.0; n],
            theta: vec![0.0; n],
            tension: vec![0.0; n],
            moment: vec![0.0; n],
            penetration: vec![0.0; n],
            seabed_force: vec![0.0; n],
            mode: vec![0; n],
        }
    }
}

#[cfg(test)]
mod non_finite_tests {
    use super::*;

    #[test]
    fn the_first_non_finite_value_is_named_with_its_node() {
        let n = 5;
        let mut res = LineResults::new(n);
        let (mut u, v, mut a) = (vec![0.0; 3 * n], vec![0.0; 3 * n], vec![0.0; 3 * n]);
        assert_eq!(first_non_finite(&res, &u, &v, &a), None);
        res.moment[3] = f64::NAN;
        assert_eq!(first_non_finite(&res, &u, &v, &a), Some(("moment", 3)));
        // An earlier node comes first, whatever the quantity.
        a[3 * 2 + 1] = f64::INFINITY;
        assert_eq!(
            first_non_finite(&res, &u, &v, &a),
            Some(("acceleration", 2))
        );
        u[3 * 2 + 2] = f64::NEG_INFINITY;
        assert_eq!(
            first_non_finite(&res, &u, &v, &a),
            Some(("displacement", 2))
        );
        res.seabed_force[0] = f64::NAN;
        assert_eq!(
            first_non_finite(&res, &u, &v, &a),
            Some(("seabed force", 0))
        );
    }
}

#[cfg(test)]
mod tests;

mod sides;
