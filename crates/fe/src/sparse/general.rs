//! faer's general sparse LDLᵀ, for a tangent whose pattern is not a narrow band (a future branched
//! or multi-line model): the symbolic factorisation (AMD ordering, elimination tree) once per run
//! in [`LdltSolver::new`], then each factorisation numeric only, into preallocated buffers, and
//! each solve in place. Held to the band solver to rounding (`band_and_sparse_agree`).
//!
//! Only the upper triangle is stored and passed with `Side::Upper`: faer reads the triangle the side
//! names, and this is the combination tested to give the right answer for every ordering.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::SparseColMatRef;
use faer::{Conj, MatMut, Par, Side};

use super::{SolveError, SparseSym};

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
