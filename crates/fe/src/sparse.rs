//! Symmetric sparse matrices and their LDLᵀ solve: a dedicated band solver for a line's tangent,
//! faer's general sparse solver for anything wider.
//!
//! **Which solver.** A line's equations numbered node by node couple only within a band of
//! half-width 5 (two nodes of three unknowns). For such a band, [`BandLdlt`] factors in place
//! with no permutation, no elimination tree and no index arithmetic in the inner loops, each
//! column from its first stored row (its skyline: a node's x, z and θ columns reach 3, 4 and 5 rows
//! up, not 5 each), about `n·w²/3` multiply-adds (2577 equations: ~21 000). [`LinearSolver::new`] takes it when the
//! half-width is at most [`BAND_LIMIT`], and faer's simplicial/supernodal LDLᵀ ([`LdltSolver`])
//! otherwise — for a pattern that is not a narrow band (a future branched or multi-line model),
//! which is what faer is for. Both give the same solution to rounding (`band_and_sparse_agree`).
//!
//! **Band LDLᵀ** (no pivoting, like faer's; the tangent is symmetric and, at a converged state,
//! positive definite; an indefinite but nonsingular matrix factors too):
//!
//! ```text
//! for j = 0..n:  t_i = A_ij − Σ_{k<i} L_ik t_k   (i = j−w..j−1;  t_i = L_ji D_i)
//!                L_ji = t_i / D_i,   D_j = A_jj − Σ_i L_ji t_i
//! L z = b,  z ← D⁻¹ z,  Lᵀ x = z
//! ```
//!
//! The pattern (upper triangle, compressed sparse columns) is built once from the element
//! connectivity; the symbolic factorisation (AMD ordering, elimination tree) is done once per run in
//! [`LdltSolver::new`]; every Newton iteration refills the values in place and refactors numerically
//! into preallocated buffers ([`LdltSolver::factor`]), then solves in place. Nothing here allocates
//! after construction.
//!
//! **Why more than one path, and what each buys.** The band's general loops (any half-width up to
//! [`BAND_LIMIT`]) are the reference; for a line's half-width 5 the same operations in the same
//! order are unrolled over five fixed rows (`factor_band5`, `solve_band5`: the unknowns in
//! registers, the backward sweep gathering instead of scattering), kept for the speed they were
//! measured to buy — the heave benchmark's dynamics 0.230 → 0.188 s (−18 %), the factorisation's
//! share of the run 13 % → 8 % and the solves' 14 % → 7 % (`benches/README.md`) — and held to the
//! general loops to the bit by `unrolled_band_is_the_general_band_to_the_bit`. faer's LDLᵀ serves
//! patterns wider than a band (held to the band to rounding by `band_and_sparse_agree`).
//!
//! **From both ends.** A line of at least [`TWIST_MIN`] equations is factorised from both ends at
//! once ([`factor_twisted5`], the "twisted" or "burn at both ends" order of tridiagonal solvers):
//! the equations `0..m` top-down as above, `m+5..n` bottom-up by the same recurrence on the
//! reversed order, and the five in the middle from their Schur complement; the solve sweeps from
//! both ends to the middle and back. Each column's recurrence is a chain of dependent operations
//! (the division by the last pivot, then the next pivot's update; each unknown of a sweep from
//! the one before it) that leaves the processor waiting; two independent chains in one loop
//! overlap. The same operations, another order: the solution agrees with the top-down one to
//! rounding (`twisted_band_is_the_band_to_rounding`), not to the bit. Measured on 2577 equations:
//! the factorisation 27.0 → 24.5 µs, a solve 10.1 → 7.6 µs (`benches/README.md`).
//!
//! Only the upper triangle is stored and passed with `Side::Upper`: faer reads the triangle the side
//! names, and this is the combination tested to give the right answer for every ordering.
//!
//! One algorithm: the LDLᵀ factorisation and solve of the line's symmetric tangent, kept whole in
//! one file because its three forms (the general band, its unrolled twin for half-width 5, and the
//! band from both ends) share their kernels and are each tested against the others.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// Why a linear solve failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// The symbolic analysis failed (out of memory or an invalid pattern).
    #[error("symbolic factorisation failed: {0}")]
    Symbolic(String),
    /// A zero pivot: the tangent is singular (a mechanism, or an unsupported rigid-body mode).
    #[error("the tangent matrix is singular (zero pivot at equation {equation})")]
    Singular {
        /// The equation (free degree of freedom) where the pivot vanished, in the solver's order.
        equation: usize,
    },
}

/// A symmetric sparse matrix: its upper triangle in compressed sparse columns.
#[derive(Debug, Clone, PartialEq)]
pub struct SparseSym {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// The values, in the order of the pattern (refilled each iteration).
    pub values: Vec<f64>,
}

impl SparseSym {
    /// Builds the pattern of an `n × n` symmetric matrix from the coupled pairs `(i, j)` (either
    /// order; duplicates allowed). The diagonal is always included.
    pub fn from_couplings(n: usize, pairs: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let mut cols: Vec<Vec<usize>> = (0..n).map(|j| vec![j]).collect();
        for (i, j) in pairs {
            let (r, c) = if i <= j { (i, j) } else { (j, i) };
            cols[c].push(r);
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for mut c in cols {
            c.sort_unstable();
            c.dedup();
            row_idx.extend(c);
            col_ptr.push(row_idx.len());
        }
        let nnz = row_idx.len();
        Self {
            n,
            col_ptr,
            row_idx,
            values: vec![0.0; nnz],
        }
    }

    /// The order of the matrix.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The index into [`SparseSym::values`] of entry `(i, j)` (either order), if it is in the pattern.
    pub fn slot(&self, i: usize, j: usize) -> Option<usize> {
        let (r, c) = if i <= j { (i, j) } else { (j, i) };
        let lo = self.col_ptr[c];
        let hi = self.col_ptr[c + 1];
        self.row_idx[lo..hi].binary_search(&r).ok().map(|k| lo + k)
    }

    /// Sets every value to zero.
    pub fn clear(&mut self) {
        self.values.fill(0.0);
    }

    /// Sets the values of the columns `columns` to zero (a part of the line's tangent, each
    /// column's rows above its diagonal included).
    pub fn clear_columns(&mut self, columns: std::ops::Range<usize>) {
        let slots = self.column_slots(columns);
        self.values[slots].fill(0.0);
    }

    /// The places in `values` of the columns `columns`.
    pub fn column_slots(&self, columns: std::ops::Range<usize>) -> std::ops::Range<usize> {
        self.col_ptr[columns.start]..self.col_ptr[columns.end]
    }

    /// `y = A·x` (for tests and residual checks).
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for c in 0..self.n {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                let r = self.row_idx[k];
                let v = self.values[k];
                y[r] += v * x[c];
                if r != c {
                    y[c] += v * x[r];
                }
            }
        }
    }

    /// The half-bandwidth: the largest `j − i` over the stored entries `(i, j)`, `i ≤ j`.
    pub fn half_bandwidth(&self) -> usize {
        (0..self.n)
            .filter(|&c| self.col_ptr[c + 1] > self.col_ptr[c])
            .map(|c| c - self.row_idx[self.col_ptr[c]])
            .max()
            .unwrap_or(0)
    }

    fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        SymbolicSparseColMatRef::new_checked(self.n, self.n, &self.col_ptr, None, &self.row_idx)
    }
}

/// The widest band [`LinearSolver`] gives to [`BandLdlt`] (half-width, equations).
pub const BAND_LIMIT: usize = 32;

/// The linear solver of a tangent: the band solver for a narrow band, faer's otherwise (see the
/// module docs).
#[derive(Debug)]
pub enum LinearSolver {
    /// Band LDLᵀ.
    Band(BandLdlt),
    /// faer's sparse LDLᵀ in the natural order.
    Sparse(Box<LdltSolver>),
}

impl LinearSolver {
    /// The solver for `a`'s pattern.
    pub fn new(a: &SparseSym) -> Result<Self, SolveError> {
        if a.half_bandwidth() <= BAND_LIMIT {
            Ok(Self::Band(BandLdlt::new(a)))
        } else {
            Ok(Self::Sparse(Box::new(LdltSolver::with_ordering(a, true)?)))
        }
    }

    /// The numeric factorisation of `a` (same pattern as at construction).
    pub fn factor(&mut self, a: &SparseSym) -> Result<(), SolveError> {
        match self {
            Self::Band(b) => b.factor(a),
            Self::Sparse(s) => s.factor(a),
        }
    }

    /// Factorises and solves on two threads from now on where the band allows it
    /// ([`BandLdlt::use_partner`]; faer's solver stays on one): the same values to the bit.
    /// Returns whether it does.
    pub fn use_partner(&mut self) -> std::io::Result<bool> {
        match self {
            Self::Band(b) => b.use_partner(),
            Self::Sparse(_) => Ok(false),
        }
    }

    /// One side of the factorisation by two threads ([`BandLdlt::factor_side`]).
    ///
    /// # Panics
    /// For faer's solver (only a band factorised from both ends has sides).
    pub fn factor_side(
        &mut self,
        a: &SparseSym,
        side: usize,
        seat: &mut crate::partner::Seat,
    ) -> Result<(), SolveError> {
        match self {
            Self::Band(b) => b.factor_side(a, side, seat),
            Self::Sparse(_) => panic!("only a band factorised from both ends has sides"),
        }
    }

    /// One side of the solve by two threads ([`BandLdlt::solve_side`]).
    ///
    /// # Panics
    /// For faer's solver.
    pub fn solve_side(&self, side: usize, seat: &mut crate::partner::Seat, x: &mut [f64]) {
        match self {
            Self::Band(b) => b.solve_side(side, seat, x),
            Self::Sparse(_) => panic!("only a band factorised from both ends has sides"),
        }
    }

    /// The first of the band's five middle equations when it is factorised from both ends
    /// ([`BandLdlt::twist`]).
    pub fn twist(&self) -> Option<usize> {
        match self {
            Self::Band(b) => b.twist(),
            Self::Sparse(_) => None,
        }
    }

    /// Moves the band's middle five to `m..m+5` ([`BandLdlt::set_twist`]); returns whether it did.
    pub fn set_twist(&mut self, m: usize) -> bool {
        match self {
            Self::Band(b) => b.set_twist(m),
            Self::Sparse(_) => false,
        }
    }

    /// Solves `A x = b` in place with the last factorisation.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        match self {
            Self::Band(b) => b.solve_in_place(rhs),
            Self::Sparse(s) => s.solve_in_place(rhs),
        }
    }
}

/// LDLᵀ of a symmetric band matrix, in place (see the module docs). Column `j` of the band holds
/// rows `j − w ..= j` (the upper triangle): `L_ji` for `i < j`, `D_j` on the diagonal. The loops
/// start at each column's first stored row (its skyline), not at `j − w`.
#[derive(Debug, Clone)]
pub struct BandLdlt {
    w: usize,
    band: Vec<f64>,
    /// For each value of the sparse pattern, its place in `band`.
    map: Vec<usize>,
    /// Each column's first row in the pattern (`j − w ≤ first[j] ≤ j`).
    first: Vec<usize>,
    /// The places in `band` within a column's skyline that the pattern does not fill (the
    /// factor's fill-in: zeroed before each factorisation; a line's pattern has none). Places above
    /// the skyline are never written by the scatter, so they stay zero.
    holes: Vec<usize>,
    /// A half-width of 5 whose every column holds exactly its skyline rows (a line's pattern): then
    /// [`BandLdlt::factor`] copies the six values ending at each diagonal (where each column's
    /// values end in the pattern, `col_ptr[c + 1]`) as one block into the
    /// column, instead of scattering value by value through `map` (a third of the time of a
    /// factorisation: the map is one more array as large as the values). The places above a
    /// column's skyline then hold the previous column's last values, which the top-down
    /// half-width-5 kernels never read: they select by the skyline (`first`), never by a stored
    /// zero (the twisted solve reads zeros there: `above`).
    blocks: bool,
    /// Factorised from both ends ([`factor_twisted5`]): `Some(m)`, the first of the five middle
    /// equations `m..m+5`, for a line's pattern (`blocks`, each column's first row nondecreasing)
    /// of at least [`TWIST_MIN`] equations; `None`: top-down.
    twist: Option<usize>,
    /// The places in `band` above each column's skyline from column 5 on (twisted only): zeroed
    /// after the block copy (which leaves the previous column's values there), so that the twisted
    /// solve multiplies by zero where the top-down one selects; the factorisation's kernels select
    /// and write back what they read there, so the zeros stay.
    above: Vec<usize>,
    /// The twisted factorisation's middle block `m..m+5`, densely: `L_ca` at `[5a + c]` (`a < c`),
    /// `D_c` at `[6c]`.
    middle: Box<[f64; 25]>,
    /// The thread that factorises and solves the bottom end, when the band uses one
    /// ([`BandLdlt::use_partner`], [`split`]).
    partner: split::Slot,
}

/// The fewest equations of a line's band factorised from both ends ([`factor_twisted5`]).
pub const TWIST_MIN: usize = 40;

impl BandLdlt {
    /// The band layout of `a`'s pattern.
    pub fn new(a: &SparseSym) -> Self {
        let (n, w) = (a.n, a.half_bandwidth());
        let mut map = vec![0; a.values.len()];
        let mut first = vec![0; n];
        for (c, f) in first.iter_mut().enumerate() {
            let (lo, hi) = (a.col_ptr[c], a.col_ptr[c + 1]);
            for (m, r) in map[lo..hi].iter_mut().zip(&a.row_idx[lo..hi]) {
                *m = c * (w + 1) + (r + w - c);
            }
            *f = a.row_idx[lo..hi].iter().copied().min().unwrap_or(c).min(c);
        }
        let mut filled = vec![false; n * (w + 1)];
        for &m in &map {
            filled[m] = true;
        }
        let holes = (0..n)
            .flat_map(|c| (first[c]..=c).map(move |r| c * (w + 1) + (r + w - c)))
            .filter(|&m| !filled[m])
            .collect();
        // Column c's values are rows first[c] ..= c in order, nothing missing: its place in the
        // pattern ends at col_ptr[c + 1], its block in the band at c·(w+1) + w.
        let skyline_only = (0..n).all(|c| {
            let rows = &a.row_idx[a.col_ptr[c]..a.col_ptr[c + 1]];
            rows.iter().copied().eq(first[c]..=c)
        });
        let blocks = w == 5 && n > w && skyline_only;
        let nondecreasing = first.windows(2).all(|p| p[0] <= p[1]);
        let twist = (blocks && nondecreasing && n >= TWIST_MIN).then_some((n - 5) / 2);
        let above = if twist.is_some() {
            (w..n)
                .flat_map(|c| (c - w..first[c]).map(move |r| c * (w + 1) + (r + w - c)))
                .collect()
        } else {
            Vec::new()
        };
        Self {
            w,
            band: vec![0.0; n * (w + 1)],
            map,
            first,
            holes,
            blocks,
            twist,
            above,
            middle: Box::new([0.0; 25]),
            partner: split::Slot::default(),
        }
    }

    /// The first of the five middle equations `m..m+5` when the band is factorised from both ends
    /// ([`factor_twisted5`]); `None` when it is factorised top-down.
    pub fn twist(&self) -> Option<usize> {
        self.twist
    }

    /// Moves the middle five of a band factorised from both ends to `m..m+5` (at least five
    /// equations above them and five below): the ends then meet there. Another `m` is the same
    /// factorisation in another order, so its values agree to rounding, not to the bit. Returns
    /// whether it moved (`false`: a band factorised top-down, or `m` out of range).
    pub fn set_twist(&mut self, m: usize) -> bool {
        let n = self.first.len();
        let fits = self.twist.is_some() && m >= 5 && m + 10 <= n;
        if fits {
            self.twist = Some(m);
        }
        fits
    }

    /// The numeric factorisation of `a` (the pattern given to [`BandLdlt::new`]).
    pub fn factor(&mut self, a: &SparseSym) -> Result<(), SolveError> {
        if let (Some(m), true) = (self.twist, self.has_partner()) {
            return self.factor_split(a, m);
        }
        for &h in &self.holes {
            self.band[h] = 0.0;
        }
        if self.blocks {
            const W: usize = 5;
            // Where each column's values end in the pattern (one past its diagonal).
            let ends = &a.col_ptr[1..];
            // The first W columns by the map (their places above the skyline stay zero: the
            // general loops of the factorisation's head read them), the others in blocks.
            let head = ends[W - 1];
            for (v, &m) in a.values[..head].iter().zip(&self.map[..head]) {
                self.band[m] = *v;
            }
            for (col, &end) in self.band.chunks_exact_mut(W + 1).zip(ends).skip(W) {
                let block: &[f64; W + 1] =
                    a.values[end - (W + 1)..end].try_into().expect("a block");
                col.copy_from_slice(block);
            }
        } else {
            for (v, &m) in a.values.iter().zip(&self.map) {
                self.band[m] = *v;
            }
        }
        for &h in &self.above {
            self.band[h] = 0.0;
        }
        match self.twist {
            Some(m) => factor_twisted_dispatch(&self.first, &mut self.band, m, &mut self.middle),
            None => factor_dispatch(self.w, &self.first, &mut self.band),
        }
    }

    /// Solves `A x = b` in place with the last factorisation.
    pub fn solve_in_place(&self, x: &mut [f64]) {
        match self.twist {
            Some(m) if self.has_partner() => self.solve_split(m, x),
            Some(m) => solve_twisted_dispatch(&self.first, &self.band, m, &self.middle, x),
            None => solve_dispatch(self.w, &self.first, &self.band, x),
        }
    }
}

/// [`BandLdlt::factor`] compiled for the baseline processor and for AVX2 and AVX-512, chosen at
/// run time (no fused multiply-adds: the same values to the bit).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn factor_dispatch(w: usize, first: &[usize], band: &mut [f64]) -> Result<(), SolveError> {
    // A beam line's half-width (5) as a constant: the column's slices have a known bound.
    // The same arithmetic in the same order as the general path.
    match w {
        5 => factor_band::<5>(first, band),
        w => factor_band_dyn(first, w, band),
    }
}

/// [`BandLdlt::solve_in_place`] compiled as [`factor_dispatch`] is.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn solve_dispatch(w: usize, first: &[usize], band: &[f64], x: &mut [f64]) {
    match w {
        5 => solve_band::<5>(first, band, x),
        w => solve_band_dyn(first, w, band, x),
    }
}

/// [`BandLdlt::factor`] for a half-width known at compile time: a beam line's 5 unrolled
/// ([`factor_band5`]), any other through the general loops.
#[inline(always)]
fn factor_band<const W: usize>(first: &[usize], band: &mut [f64]) -> Result<(), SolveError> {
    if W == 5 {
        factor_band5(first, band)
    } else {
        factor_band_dyn(first, W, band)
    }
}

/// [`BandLdlt::solve_in_place`] for a half-width known at compile time, as [`factor_band`].
#[inline(always)]
fn solve_band<const W: usize>(first: &[usize], band: &[f64], x: &mut [f64]) {
    if W == 5 {
        solve_band5(first, band, x)
    } else {
        solve_band_dyn(first, W, band, x)
    }
}

/// [`factor_band_dyn`] for half-width 5, each column's loops unrolled over the five rows above
/// the diagonal: a row or a product outside the skyline is not taken (a select, not a branch on
/// data), every kept operation is the general loop's, in its order, so the factor is the same to
/// the bit (`unrolled_band_is_the_general_band_to_the_bit`). The general loops' trip counts vary
/// with each column's skyline (3, 4 or 5 rows up) and their bookkeeping, not the arithmetic,
/// was most of the factorisation's time.
#[inline(always)]
fn factor_band5(first: &[usize], band: &mut [f64]) -> Result<(), SolveError> {
    const W: usize = 5;
    let n = first.len();
    let head = n.min(W);
    factor_columns_dyn(first, W, band, 0..head)?;
    for j in head..n {
        top_column5(first, band, j)?;
    }
    Ok(())
}

/// Column `j ≥ 5` of [`factor_band5`]: `L_ji` for the rows `i` of its skyline and `D_j`, from
/// the five columns before it.
#[inline(always)]
fn top_column5(first: &[usize], band: &mut [f64], j: usize) -> Result<(), SolveError> {
    const W: usize = 5;
    let lo = first[j];
    let (before, rest) = band.split_at_mut(j * (W + 1));
    let col: &mut [f64; W + 1] = (&mut rest[..W + 1]).try_into().expect("column");
    // Columns j−5..j−1; row k = j−5+b of column i = j−5+a is cols[6a + 5 + b − a].
    let cols: &[f64; W * (W + 1)] = before[(j - W) * (W + 1)..].try_into().expect("columns");
    let fi: &[usize; W] = first[j - W..j].try_into().expect("firsts");
    let mut c = *col;
    for a in 0..W {
        let i = j - W + a;
        let klo = lo.max(fi[a]);
        let mut t = c[a];
        for b in 0..a {
            // A product outside the skyline subtracts +0: exactly nothing.
            t -= if j - W + b >= klo {
                cols[a * (W + 1) + W + b - a] * c[b]
            } else {
                0.0
            };
        }
        c[a] = if i >= lo { t } else { c[a] };
    }
    let mut d = c[W];
    for a in 0..W {
        let t = c[a];
        let l = t / cols[a * (W + 1) + W];
        let keep = j - W + a >= lo; // row i = j−5+a is in the skyline
        d -= if keep { l * t } else { 0.0 };
        c[a] = if keep { l } else { t };
    }
    if d == 0.0 || !d.is_finite() {
        return Err(SolveError::Singular { equation: j });
    }
    c[W] = d;
    *col = c;
    Ok(())
}

/// [`solve_band_dyn`] for half-width 5, unrolled as [`factor_band5`]: the forward sweep keeps the
/// last five unknowns in registers; the backward sweep gathers each unknown's terms from the
/// columns below it (`x_i ← x_i/D_i − Σ_{j=i+5..i+1} L_ji x_j`, j descending) instead of
/// scattering each column into the unknowns above it: the same operations in the same order, the
/// same values to the bit, and no store of a vector overlapping the next column's load.
#[inline(always)]
fn solve_band5(first: &[usize], band: &[f64], x: &mut [f64]) {
    const W: usize = 5;
    let n = first.len();
    if n <= W {
        return solve_band_dyn(first, W, band, x);
    }
    // Forward: z_j = b_j − Σ_{i=lo..j−1} L_ji z_i, the first five rows by the general loop.
    forward_rows_dyn(first, W, band, x, 0..W);
    // The last five unknowns, x_{j−5} .. x_{j−1}, in registers (a window array would go through
    // the stack, each row's scalar store then read back as a vector).
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; W] = x[..W].try_into().expect("window");
    for j in W..n {
        let lo = first[j];
        let l: &[f64; W + 1] = band[j * (W + 1)..][..W + 1].try_into().expect("column");
        // A row outside the skyline subtracts +0 (exactly nothing), the select off the chain.
        let term = |a: usize, xi: f64| if j - W + a >= lo { l[a] * xi } else { 0.0 };
        let s = x[j] - term(0, w0) - term(1, w1) - term(2, w2) - term(3, w3) - term(4, w4);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (w1, w2, w3, w4, s);
    }
    // Backward: x_i = z_i/D_i − Σ_j L_ji x_j over the columns j > i whose skyline reaches row i,
    // in descending j (the order in which the column-oriented sweep subtracts them).
    let tail = n - W;
    for i in (tail..n).rev() {
        let mut s = x[i] / band[i * (W + 1) + W];
        for j in (i + 1..n).rev() {
            if first[j] <= i {
                s -= band[j * (W + 1) + W + i - j] * x[j];
            }
        }
        x[i] = s;
    }
    // x_{i+1} .. x_{i+5} in registers.
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; W] = x[tail..].try_into().expect("window");
    for i in (0..tail).rev() {
        let f: &[usize; W] = first[i + 1..][..W].try_into().expect("firsts");
        let below = &band[(i + 1) * (W + 1)..][..W * (W + 1)];
        // Column j = i+1+b, row i: below[6b + 5 + i − j] = below[6b + 4 − b].
        let term = |b: usize, xj: f64| {
            if f[b] <= i {
                below[b * (W + 1) + W - 1 - b] * xj
            } else {
                0.0
            }
        };
        let s = x[i] / band[i * (W + 1) + W]
            - term(4, w4)
            - term(3, w3)
            - term(2, w2)
            - term(1, w1)
            - term(0, w0);
        x[i] = s;
        (w0, w1, w2, w3, w4) = (s, w0, w1, w2, w3);
    }
}

/// [`factor_twisted5`], compiled for the baseline processor only: compiled for AVX2 or AVX-512
/// the compiler packs the two ends' scalar recurrences into vectors, and the shuffles between them
/// lengthen the very chains that the two ends are there to overlap (2577 equations, the copy into
/// the band included: 24.5 µs for the baseline, 29.8 µs for AVX-512, against 27.0 µs top-down;
/// `benches/README.md`). The values are the same either way: no fused multiply-adds.
fn factor_twisted_dispatch(
    first: &[usize],
    band: &mut [f64],
    m: usize,
    middle: &mut [f64; 25],
) -> Result<(), SolveError> {
    factor_twisted5(first, band, m, middle)
}

/// [`solve_twisted5`] compiled as [`factor_dispatch`] is.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn solve_twisted_dispatch(
    first: &[usize],
    band: &[f64],
    m: usize,
    middle: &[f64; 25],
    x: &mut [f64],
) {
    solve_twisted5(first, band, m, middle, x)
}

/// Row `i` of column `l` (`l − 5 ≤ i ≤ l`) in the band.
#[inline(always)]
fn at(i: usize, l: usize) -> usize {
    l * 6 + 5 + i - l
}

/// The twisted ("burn at both ends") LDLᵀ of a line's half-width-5 band, `P A Pᵀ = L D Lᵀ` in the
/// elimination order `0, 1, …, m−1`, then `n−1, n−2, …, m+5`, then the middle `m, …, m+4`:
///
/// - the top equations `j < m` as [`factor_band5`] does (`L_ji` in column `j`, `i < j`);
/// - the bottom equations `i ≥ m+5` from the last one up, the same recurrence on the reversed
///   order: `t_l = A_il − Σ_{k>l} U_lk t_k` for the equations `l = i+5 … i+1` eliminated before
///   `i`, `U_il = t_l / D_l`, `D_i = A_ii − Σ_l U_il t_l`, `U_il` in place of `A_il` (row `i` of
///   column `l`);
/// - the middle five from their Schur complement `S = A_MM − Σ_top L D Lᵀ − Σ_bottom U D Uᵀ`,
///   densely (`middle`).
///
/// The two ends are independent until the middle, and their columns are computed in the same loop:
/// each column's recurrence is a chain of dependent operations (the division by the last pivot,
/// then the pivot's update) that one end alone leaves the processor waiting on, and two ends
/// overlap. The same operations' count as top-down, a different order: the factor, and the
/// solution, agree with [`factor_band5`]'s to rounding (`twisted_band_is_the_band_to_rounding`).
/// The band's rows are the line's skyline (each column's `first` nondecreasing: the rows of row
/// `i`'s band beyond the diagonal are then `i+1 ..= last` with no gap, and neither end fills in
/// outside them); a place above the skyline is zero (`BandLdlt::above`) and stays zero: the
/// kernels select by `first` and write back what they read there.
#[inline(always)]
fn factor_twisted5(
    first: &[usize],
    band: &mut [f64],
    m: usize,
    middle: &mut [f64; 25],
) -> Result<(), SolveError> {
    const W: usize = 5;
    let n = first.len();
    let p = m + W;
    // The first five columns and the last five rows by the general loops.
    factor_columns_dyn(first, W, band, 0..W)?;
    factor_bottom_tail(first, band)?;
    let (mut j, mut i) = (W, n - W - 1);
    while j < m && i >= p {
        top_column5(first, band, j)?;
        bottom_row5(first, band, i)?;
        j += 1;
        i -= 1;
    }
    while j < m {
        top_column5(first, band, j)?;
        j += 1;
    }
    while i >= p {
        bottom_row5(first, band, i)?;
        i -= 1;
    }
    factor_middle5(first, band, m, middle)
}

/// The top end of [`factor_twisted5`] alone: the columns `0..m`, top-down (the partner of a split
/// factorisation does the bottom end at the same time, [`factor_bottom5`]). They read and write
/// the band's columns `0..m` only.
#[inline(always)]
fn factor_top5(first: &[usize], band: &mut [f64], m: usize) -> Result<(), SolveError> {
    factor_columns_dyn(first, 5, band, 0..5)?;
    for j in 5..m {
        top_column5(first, band, j)?;
    }
    Ok(())
}

/// The bottom end of [`factor_twisted5`] alone: the rows `n−1` down to `m+5`. They read and write
/// the band's columns `m+5..n` only.
#[inline(always)]
fn factor_bottom5(first: &[usize], band: &mut [f64], m: usize) -> Result<(), SolveError> {
    factor_bottom_tail(first, band)?;
    for i in (m + 5..first.len() - 5).rev() {
        bottom_row5(first, band, i)?;
    }
    Ok(())
}

/// The last five rows of the bottom end, by the general loops.
#[inline(always)]
fn factor_bottom_tail(first: &[usize], band: &mut [f64]) -> Result<(), SolveError> {
    let n = first.len();
    for i in (n - 5..n).rev() {
        bottom_row(first, band, i, i + 1, true)?;
    }
    Ok(())
}

/// The middle five of [`factor_twisted5`] once both ends are factorised: their couplings with
/// either end and the dense LDLᵀ of their Schur complement. They read the band's columns
/// `first[m]..m+10` and write columns `m..m+10`.
#[inline(always)]
fn factor_middle5(
    first: &[usize],
    band: &mut [f64],
    m: usize,
    middle: &mut [f64; 25],
) -> Result<(), SolveError> {
    const W: usize = 5;
    let n = first.len();
    let p = m + W;
    // The middle's couplings with either end, t = L·D in place of A: top rows q < m of
    // columns m..m+4, bottom columns l ≥ m+5 of rows m..m+4.
    for c in m..p {
        let lo = first[c];
        for q in lo..m {
            let mut t = band[at(q, c)];
            for k in lo.max(first[q])..q {
                t -= band[at(k, q)] * band[at(k, c)];
            }
            band[at(q, c)] = t;
        }
        bottom_row(first, band, c, p, false)?;
    }
    // S = A_MM − C_top − C_bottom (upper triangle; outside the skyline, zero).
    let mut s = [0.0; 25];
    for a in 0..W {
        let ja = m + a;
        for c in a..W {
            let jc = m + c;
            let mut v = if first[jc] <= ja {
                band[at(ja, jc)]
            } else {
                0.0
            };
            for q in first[jc].max(first[ja])..m {
                v -= band[at(q, ja)] * band[at(q, jc)] / band[at(q, q)];
            }
            for l in p..(ja + W + 1).min(n) {
                if first[l] <= ja {
                    v -= band[at(ja, l)] * band[at(jc, l)] / band[at(l, l)];
                }
            }
            s[5 * a + c] = v;
        }
    }
    // The middle's couplings as L and U.
    for c in m..p {
        for q in first[c]..m {
            band[at(q, c)] /= band[at(q, q)];
        }
        for l in p..(c + W + 1).min(n) {
            if first[l] <= c {
                band[at(c, l)] /= band[at(l, l)];
            }
        }
    }
    // The dense LDLᵀ of S, left-looking as the band's columns.
    for c in 0..W {
        for a in 0..c {
            let mut t = s[5 * a + c];
            for k in 0..a {
                t -= s[5 * k + a] * s[5 * k + c];
            }
            s[5 * a + c] = t;
        }
        let mut d = s[6 * c];
        for a in 0..c {
            let t = s[5 * a + c];
            let l = t / s[6 * a];
            d -= l * t;
            s[5 * a + c] = l;
        }
        if d == 0.0 || !d.is_finite() {
            return Err(SolveError::Singular { equation: m + c });
        }
        s[6 * c] = d;
    }
    *middle = s;
    Ok(())
}

/// Row `i` of the bottom end ([`factor_twisted5`]), general: `t_l` for the columns `l` from
/// `from` to `i+5` (and below `n`) whose skyline holds row `i`, from the last down, in place of
/// `A_il`; with `full`, then `U_il = t_l/D_l` and `D_i`, else the `t_l` are left (the middle's).
#[inline(always)]
fn bottom_row(
    first: &[usize],
    band: &mut [f64],
    i: usize,
    from: usize,
    full: bool,
) -> Result<(), SolveError> {
    let hi = (i + 5).min(first.len() - 1);
    for l in (from..=hi).rev().filter(|&l| first[l] <= i) {
        let mut t = band[at(i, l)];
        for k in (l + 1..=hi.min(l + 5)).rev().filter(|&k| first[k] <= i) {
            t -= band[at(l, k)] * band[at(i, k)];
        }
        band[at(i, l)] = t;
    }
    if full {
        let mut d = band[at(i, i)];
        for l in (from..=hi).rev().filter(|&l| first[l] <= i) {
            let t = band[at(i, l)];
            let u = t / band[at(l, l)];
            d -= u * t;
            band[at(i, l)] = u;
        }
        if d == 0.0 || !d.is_finite() {
            return Err(SolveError::Singular { equation: i });
        }
        band[at(i, i)] = d;
    }
    Ok(())
}

/// Row `i` of the bottom end (`i + 5 < n`), unrolled as [`top_column5`]: the columns `l = i+5−a`
/// (`a = 0..5`) after it, `U_il` at row `i` of column `l` (held when `first[l] ≤ i`).
#[inline(always)]
fn bottom_row5(first: &[usize], band: &mut [f64], i: usize) -> Result<(), SolveError> {
    const W: usize = 5;
    let (head, rest) = band.split_at_mut((i + 1) * (W + 1));
    // Columns i+1..i+5: column l = i+5−a at win[6(4−a)..]; its row r at win[6(4−a) + 5 + r − l].
    let win: &mut [f64; W * (W + 1)] = (&mut rest[..W * (W + 1)]).try_into().expect("window");
    let fl: &[usize; W] = first[i + 1..i + 1 + W].try_into().expect("firsts");
    let keep = |a: usize| fl[4 - a] <= i;
    let mut c = [0.0; W];
    for (a, ca) in c.iter_mut().enumerate() {
        *ca = win[6 * (4 - a) + a]; // A_il, l = i+5−a
    }
    for a in 0..W {
        let mut t = c[a];
        for b in 0..a {
            // U_{l_a l_b} (l_b = i+5−b > l_a): row l_a of column l_b.
            t -= if keep(b) {
                win[6 * (4 - b) + 5 - (a - b)] * c[b]
            } else {
                0.0
            };
        }
        c[a] = if keep(a) { t } else { c[a] };
    }
    let mut d = head[i * (W + 1) + W];
    for a in 0..W {
        let t = c[a];
        let u = t / win[6 * (4 - a) + 5];
        d -= if keep(a) { u * t } else { 0.0 };
        c[a] = if keep(a) { u } else { t };
    }
    if d == 0.0 || !d.is_finite() {
        return Err(SolveError::Singular { equation: i });
    }
    for (a, ca) in c.iter().enumerate() {
        win[6 * (4 - a) + a] = *ca;
    }
    head[i * (W + 1) + W] = d;
    Ok(())
}

/// The solve with [`factor_twisted5`]'s factor: forward from both ends to the middle, the
/// middle's five densely, backward from the middle to both ends; the two ends' sweeps in the same
/// loops (each a chain of dependent operations; together they overlap), each keeping its last
/// five unknowns in registers as [`solve_band5`] does.
#[inline(always)]
fn solve_twisted5(first: &[usize], band: &[f64], m: usize, middle: &[f64; 25], x: &mut [f64]) {
    const W: usize = 5;
    let n = first.len();
    let p = m + W;
    // Forward: z_j = b_j − Σ_i L_ji z_i (top), z_i = b_i − Σ_l U_il z_l (bottom).
    forward_rows_dyn(first, W, band, x, 0..W);
    forward_bottom_tail(first, band, x);
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; W] = x[..W].try_into().expect("window");
    // v0..v4 = x_{i+5} .. x_{i+1}.
    let [mut v4, mut v3, mut v2, mut v1, mut v0]: [f64; W] = x[n - W..].try_into().expect("window");
    let (top, bottom) = (forward_top5, forward_bottom5);
    let (mut j, mut i) = (W, n - W - 1);
    while j < m && i >= p {
        let s = top(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (w1, w2, w3, w4, s);
        let r = bottom(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
        j += 1;
        i -= 1;
    }
    while j < m {
        let s = top(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (w1, w2, w3, w4, s);
        j += 1;
    }
    while i >= p {
        let r = bottom(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
        i -= 1;
    }
    let z = solve_middle5(first, band, m, middle, x);
    // Backward: x_j = z_j/D_j − Σ_{q>j} L_qj x_q (top, j descending), x_i = z_i/D_i −
    // Σ_{q<i} U_qi x_q (bottom, i ascending); each from the middle's five.
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; W] = z; // x_{j+1} .. x_{j+5}
    let [mut v0, mut v1, mut v2, mut v3, mut v4]: [f64; W] = z; // x_{i−5} .. x_{i−1}
    let (top, bottom) = (backward_top5, backward_bottom5);
    let (mut j, mut i) = (m, p);
    while j > 0 && i < n {
        j -= 1;
        let s = top(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (s, w0, w1, w2, w3);
        let r = bottom(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
        i += 1;
    }
    while j > 0 {
        j -= 1;
        let s = top(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (s, w0, w1, w2, w3);
    }
    while i < n {
        let r = bottom(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
        i += 1;
    }
}

/// The forward sweep of the last five rows (the bottom end's general start).
#[inline(always)]
fn forward_bottom_tail(first: &[usize], band: &[f64], x: &mut [f64]) {
    let n = first.len();
    for i in (n - 5..n).rev() {
        let mut s = x[i];
        for l in (i + 1..n).rev().filter(|&l| first[l] <= i) {
            s -= band[at(i, l)] * x[l];
        }
        x[i] = s;
    }
}

/// The forward sweep of [`solve_twisted5`]'s top end alone (rows `0..m`; reads the band's columns
/// `0..m`), the same operations in the same order.
#[inline(always)]
fn forward_top_end5(first: &[usize], band: &[f64], m: usize, x: &mut [f64]) {
    forward_rows_dyn(first, 5, band, x, 0..5);
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; 5] = x[..5].try_into().expect("window");
    for j in 5..m {
        let s = forward_top5(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (w1, w2, w3, w4, s);
    }
}

/// The forward sweep of [`solve_twisted5`]'s bottom end alone (rows `n−1` down to `m+5`; reads
/// the band's columns `m+6..n`).
#[inline(always)]
fn forward_bottom_end5(first: &[usize], band: &[f64], m: usize, x: &mut [f64]) {
    let n = first.len();
    forward_bottom_tail(first, band, x);
    let [mut v4, mut v3, mut v2, mut v1, mut v0]: [f64; 5] = x[n - 5..].try_into().expect("window");
    for i in (m + 5..n - 5).rev() {
        let r = forward_bottom5(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
    }
}

/// The middle five of [`solve_twisted5`] once both forward sweeps are done: their right-hand side
/// less both ends' couplings (`x[first[m]..m]` and `x[m+5..m+10]`), then `L z = r`, `z/D`,
/// `Lᵀ x = z` densely; written into `x[m..m+5]` and returned.
#[inline(always)]
fn solve_middle5(
    first: &[usize],
    band: &[f64],
    m: usize,
    middle: &[f64; 25],
    x: &mut [f64],
) -> [f64; 5] {
    const W: usize = 5;
    let n = first.len();
    let p = m + W;
    let mut z = [0.0; W];
    for (a, za) in z.iter_mut().enumerate() {
        let c = m + a;
        let mut s = x[c];
        for q in first[c]..m {
            s -= band[at(q, c)] * x[q];
        }
        for l in p..(c + W + 1).min(n) {
            if first[l] <= c {
                s -= band[at(c, l)] * x[l];
            }
        }
        *za = s;
    }
    for c in 0..W {
        for a in 0..c {
            z[c] -= middle[5 * a + c] * z[a];
        }
    }
    for (c, zc) in z.iter_mut().enumerate() {
        *zc /= middle[6 * c];
    }
    for a in (0..W).rev() {
        for c in a + 1..W {
            z[a] -= middle[5 * a + c] * z[c];
        }
    }
    x[m..p].copy_from_slice(&z);
    z
}

/// The backward sweep of [`solve_twisted5`]'s top end alone, from the middle's five `z` (rows
/// `m−1` down to 0; reads the band's columns `0..m+5`).
#[inline(always)]
fn backward_top_end5(band: &[f64], m: usize, z: [f64; 5], x: &mut [f64]) {
    let [mut w0, mut w1, mut w2, mut w3, mut w4] = z;
    for j in (0..m).rev() {
        let s = backward_top5(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (s, w0, w1, w2, w3);
    }
}

/// The backward sweep of [`solve_twisted5`]'s bottom end alone, from the middle's five `z` (rows
/// `m+5..n`; reads the band's columns `m+5..n`).
#[inline(always)]
fn backward_bottom_end5(band: &[f64], m: usize, z: [f64; 5], x: &mut [f64]) {
    let [mut v0, mut v1, mut v2, mut v3, mut v4] = z;
    for i in m + 5..x.len() {
        let r = backward_bottom5(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
    }
}

/// Forward row `j ≥ 5` of the top end: `z_j = b_j − Σ_i L_ji z_i`, `w` = `z_{j−5} .. z_{j−1}`
/// (zeros above the skyline).
#[inline(always)]
fn forward_top5(band: &[f64], j: usize, x: &[f64], w: [f64; 5]) -> f64 {
    let l: &[f64; 6] = band[j * 6..][..6].try_into().expect("column");
    x[j] - l[0] * w[0] - l[1] * w[1] - l[2] * w[2] - l[3] * w[3] - l[4] * w[4]
}

/// Forward row `i` (`i + 5 < n`) of the bottom end: `z_i = b_i − Σ_l U_il z_l`, `v` =
/// `z_{i+5} .. z_{i+1}`.
#[inline(always)]
fn forward_bottom5(band: &[f64], i: usize, x: &[f64], v: [f64; 5]) -> f64 {
    // U_il, l = i+5−a: row i of column l, u[6(4−a) + a].
    let u: &[f64; 30] = band[(i + 1) * 6..][..30].try_into().expect("columns");
    x[i] - u[24] * v[0] - u[19] * v[1] - u[14] * v[2] - u[9] * v[3] - u[4] * v[4]
}

/// Backward row `j` (`j + 5 < n`) of the top end: `x_j = z_j/D_j − Σ_{q>j} L_qj x_q`, `w` =
/// `x_{j+1} .. x_{j+5}`.
#[inline(always)]
fn backward_top5(band: &[f64], j: usize, x: &[f64], w: [f64; 5]) -> f64 {
    // Column q = j+1+b, row j: below[6b + 4 − b].
    let below: &[f64; 30] = band[(j + 1) * 6..][..30].try_into().expect("columns");
    x[j] / band[j * 6 + 5]
        - below[24] * w[4]
        - below[18 + 1] * w[3]
        - below[12 + 2] * w[2]
        - below[6 + 3] * w[1]
        - below[4] * w[0]
}

/// Backward row `i ≥ 5` of the bottom end: `x_i = z_i/D_i − Σ_{q<i} U_qi x_q`, `v` =
/// `x_{i−5} .. x_{i−1}`.
#[inline(always)]
fn backward_bottom5(band: &[f64], i: usize, x: &[f64], v: [f64; 5]) -> f64 {
    // Row q = i−5+a of column i: col[a].
    let col: &[f64; 6] = band[i * 6..][..6].try_into().expect("column");
    x[i] / col[5] - col[0] * v[0] - col[1] * v[1] - col[2] * v[2] - col[3] * v[3] - col[4] * v[4]
}

/// The general band factorisation over all columns.
#[inline(always)]
fn factor_band_dyn(first: &[usize], w: usize, band: &mut [f64]) -> Result<(), SolveError> {
    factor_columns_dyn(first, w, band, 0..first.len())
}

/// The band factorisation (see the module docs) over each column's skyline: a row above a
/// column's first stored row stays zero in the factor (no fill above the first nonzero), so
/// leaving it out changes no value; `#[inline(always)]` so that a constant `w` from
/// [`factor_band`] specialises it.
#[inline(always)]
fn factor_columns_dyn(
    first: &[usize],
    w: usize,
    band: &mut [f64],
    columns: std::ops::Range<usize>,
) -> Result<(), SolveError> {
    for j in columns {
        let lo = first[j];
        // Column j holds rows j−w..=j at band[cj ..= cj + w]; its skyline starts at row lo.
        let cj = j * (w + 1);
        let (before, col_j) = band.split_at_mut(cj);
        let col_j = &mut col_j[..w + 1];
        let off_j = w - j; // row r of column j is col_j[r + off_j] (r ≥ lo)
                           // t_i = A_ij − Σ_{k = max(lo, first_i)}^{i−1} L_ik t_k, in place of A_ij.
        for i in lo..j {
            let klo = lo.max(first[i]);
            let off_i = i * (w + 1) + w - i; // row r of column i is before[r + off_i]
            let l_i = &before[klo + off_i..i + off_i];
            let t_k = &col_j[klo + off_j..i + off_j];
            let mut t = col_j[i + off_j];
            for (l, tk) in l_i.iter().zip(t_k) {
                t -= l * tk;
            }
            col_j[i + off_j] = t;
        }
        let mut d = col_j[w];
        for i in lo..j {
            let t = col_j[i + off_j];
            let l = t / before[i * (w + 1) + w];
            d -= l * t;
            col_j[i + off_j] = l;
        }
        if d == 0.0 || !d.is_finite() {
            return Err(SolveError::Singular { equation: j });
        }
        col_j[w] = d;
    }
    Ok(())
}

/// The forward sweep `z_j = b_j − Σ_{i=lo..j−1} L_ji z_i` over the rows `rows`, in place.
#[inline(always)]
fn forward_rows_dyn(
    first: &[usize],
    w: usize,
    band: &[f64],
    x: &mut [f64],
    rows: std::ops::Range<usize>,
) {
    for j in rows {
        let lo = first[j];
        let cj = j * (w + 1) + w - j;
        let mut s = x[j];
        for (li, xi) in band[lo + cj..j + cj].iter().zip(&x[lo..j]) {
            s -= li * xi;
        }
        x[j] = s;
    }
}

/// The band solve over each column's skyline; `#[inline(always)]` for the same reason as
/// [`factor_band_dyn`].
#[inline(always)]
fn solve_band_dyn(first: &[usize], w: usize, band: &[f64], x: &mut [f64]) {
    let n = first.len();
    forward_rows_dyn(first, w, band, x, 0..n);
    for (j, xj) in x.iter_mut().enumerate().take(n) {
        *xj /= band[j * (w + 1) + w];
    }
    for (j, &lo) in first.iter().enumerate().rev() {
        let cj = j * (w + 1) + w - j;
        let l = &band[lo + cj..j + cj];
        let xj = x[j];
        for (xi, li) in x[lo..j].iter_mut().zip(l) {
            *xi -= li * xj;
        }
    }
}

/// faer's sparse LDLᵀ with the symbolic factorisation done once and every buffer preallocated.
pub struct LdltSolver {
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    buf: MemBuffer,
}

impl std::fmt::Debug for LdltSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LdltSolver")
            .field("n", &self.symbolic.nrows())
            .field("len_val", &self.l_values.len())
            .finish()
    }
}

impl LdltSolver {
    /// The symbolic factorisation of `a`'s pattern (once per run), with a fill-reducing AMD ordering.
    pub fn new(a: &SparseSym) -> Result<Self, SolveError> {
        Self::with_ordering(a, false)
    }

    /// The symbolic factorisation in the matrix's own order (`natural = true`) or with AMD. A line's
    /// equations numbered node by node form a band with no fill outside it, so the natural order is
    /// optimal and skips the permutation that AMD needs at every numeric factorisation.
    pub fn with_ordering(a: &SparseSym, natural: bool) -> Result<Self, SolveError> {
        let ordering = if natural {
            SymmetricOrdering::Identity
        } else {
            SymmetricOrdering::Amd
        };
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Upper,
            ordering,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| SolveError::Symbolic(format!("{e:?}")))?;
        let req = StackReq::or(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        );
        let l_values = vec![0.0; symbolic.len_val()];
        Ok(Self {
            symbolic,
            l_values,
            buf: MemBuffer::new(req),
        })
    }

    /// The numeric factorisation of `a` (same pattern as at construction).
    pub fn factor(&mut self, a: &SparseSym) -> Result<(), SolveError> {
        let mat = SparseColMatRef::new(a.symbolic(), &a.values);
        self.symbolic
            .factorize_numeric_ldlt(
                &mut self.l_values,
                mat,
                Side::Upper,
                LdltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut self.buf),
                Default::default(),
            )
            .map(|_| ())
            .map_err(|e| match e {
                faer::linalg::cholesky::ldlt::factor::LdltError::ZeroPivot { index } => {
                    SolveError::Singular { equation: index }
                }
            })
    }

    /// Solves `A x = b` in place with the last factorisation (`rhs` holds `b`, then `x`).
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let n = rhs.len();
        let ldlt = LdltRef::new(&self.symbolic, &self.l_values);
        ldlt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, n, 1),
            Par::Seq,
            MemStack::new(&mut self.buf),
        );
    }
}

mod split;

#[cfg(test)]
mod tests;
