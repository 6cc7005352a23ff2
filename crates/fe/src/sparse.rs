//! Symmetric sparse matrices and their LDLᵀ solve with faer.
//!
//! The pattern (upper triangle, compressed sparse columns) is built once from the element
//! connectivity; the symbolic factorisation (AMD ordering, elimination tree) is done once per run in
//! [`LdltSolver::new`]; every Newton iteration refills the values in place and refactors numerically
//! into preallocated buffers ([`LdltSolver::factor`]), then solves in place. Nothing here allocates
//! after construction.
//!
//! Only the upper triangle is stored and passed with `Side::Upper`: faer reads the triangle the side
//! names, and this is the combination tested to give the right answer for every ordering.

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

    fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        SymbolicSparseColMatRef::new_checked(self.n, self.n, &self.col_ptr, None, &self.row_idx)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A block-tridiagonal SPD system like a beam's (3 dof per node): the sparse LDLᵀ solution matches
    /// the product check `A x = b` to 1e-10, refactoring twice with new values, with the AMD and the
    /// natural (identity) ordering, both from the upper triangle.
    #[test]
    fn ldlt_solves_banded_spd_system() {
        let nodes = 50;
        let n = 3 * nodes;
        let pairs = (0..nodes - 1)
            .flat_map(|e| (0..6).flat_map(move |a| (0..6).map(move |b| (3 * e + a, 3 * e + b))));
        let mut a = SparseSym::from_couplings(n, pairs);
        for natural in [false, true] {
            let mut solver = LdltSolver::with_ordering(&a, natural).expect("symbolic");
            for round in 0..2 {
                a.clear();
                for e in 0..nodes - 1 {
                    for i in 0..6 {
                        for j in i..6 {
                            let (r, c) = (3 * e + i, 3 * e + j);
                            let v = if i == j {
                                10.0 + round as f64
                            } else {
                                0.5 / (1 + i + j) as f64
                            };
                            let s = a.slot(r, c).expect("in pattern");
                            a.values[s] += v;
                        }
                    }
                }
                solver.factor(&a).expect("factor");
                let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
                let mut x = b.clone();
                solver.solve_in_place(&mut x);
                let mut ax = vec![0.0; n];
                a.mul(&x, &mut ax);
                let err = ax
                    .iter()
                    .zip(&b)
                    .map(|(p, q)| (p - q).abs())
                    .fold(0.0, f64::max);
                assert!(err < 1e-10, "natural order {natural}, round {round}: {err}");
            }
        }
    }

    /// An indefinite (but nonsingular) matrix still factors: LDLᵀ takes negative pivots.
    #[test]
    fn ldlt_handles_negative_pivots() {
        let mut a = SparseSym::from_couplings(3, [(0, 1), (1, 2)]);
        let vals = [
            (0, 0, 2.0),
            (0, 1, 1.0),
            (1, 1, -3.0),
            (1, 2, 1.0),
            (2, 2, 4.0),
        ];
        for (i, j, v) in vals {
            let s = a.slot(i, j).expect("slot");
            a.values[s] = v;
        }
        let mut solver = LdltSolver::new(&a).expect("symbolic");
        solver.factor(&a).expect("factor");
        let b = [1.0, 2.0, 3.0];
        let mut x = b;
        solver.solve_in_place(&mut x);
        let mut ax = [0.0; 3];
        a.mul(&x, &mut ax);
        for i in 0..3 {
            assert!((ax[i] - b[i]).abs() < 1e-12);
        }
    }
}
