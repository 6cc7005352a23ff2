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
//! The pattern (upper triangle, compressed sparse columns) is built once from the element
//! connectivity; the symbolic factorisation (AMD ordering, elimination tree) is done once per run in
//! [`LdltSolver::new`]; every Newton iteration refills the values in place and refactors numerically
//! into preallocated buffers ([`LdltSolver::factor`]), then solves in place. Nothing here allocates
//! after construction.
//!
//! **Where each algorithm lives.** This file holds the matrix ([`SparseSym`]), the choice of
//! solver ([`LinearSolver`]) and the band solver's layout ([`BandLdlt`]: the band, its skyline,
//! which order it is factorised in); each algorithm has a file of its own:
//!
//! - `top_down.rs`: the band LDLᵀ top-down, its general loops and their unrolled twin for
//!   half-width 5;
//! - `twisted.rs`: the band factorised and solved from both ends at once (the "twisted" order);
//! - `split.rs`: the twisted order on two threads (the bottom end on a partner thread, or each
//!   thread its own end, issue 48);
//! - `general.rs`: faer's general sparse LDLᵀ ([`LdltSolver`]) for patterns wider than a band.
//!
//! `tests.rs` holds each against the others: the unrolled band against the general loops to the
//! bit, the twisted order against the top-down one to rounding, the two-thread split against the
//! twisted order to the bit, the band against faer to rounding.

use faer::sparse::SymbolicSparseColMatRef;

mod general;
mod split;
mod top_down;
mod twisted;

pub use general::LdltSolver;
use top_down::{factor_dispatch, solve_dispatch};
use twisted::{factor_twisted_dispatch, solve_twisted_dispatch};

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

#[cfg(test)]
mod tests;
