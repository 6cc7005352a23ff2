//! The assembler's pieces for two threads that each step a part of the line (issue 48): where the
//! line is cut, the two sides of the factorisation and the solve, and what one side takes from the
//! other's assembly.

use std::ops::Range;

use crate::model::LineModel;
use crate::partner::Seat;
use crate::sparse::SolveError;

use super::Assembler;

impl Assembler {
    /// Factorises and solves the tangent on two threads from now on where its band allows it
    /// ([`crate::sparse::LinearSolver::use_partner`]): the same values to the bit. Returns whether it does.
    pub fn use_partner(&mut self) -> std::io::Result<bool> {
        self.solver.use_partner()
    }

    /// One side of [`Assembler::factor_tangent`] by two threads that each assembled their part of
    /// the line ([`crate::sparse::LinearSolver::factor_side`]): this side's columns of the factor are those of one
    /// thread to the bit. The tangent values kept are this side's columns'.
    pub fn factor_tangent_side(&mut self, side: usize, seat: &mut Seat) -> Result<(), SolveError> {
        let factored = self.solver.factor_side(&self.k, side, seat);
        std::mem::swap(&mut self.factored, &mut self.k.values);
        factored
    }

    /// One side of [`Assembler::solve_tangent`] ([`crate::sparse::LinearSolver::solve_side`]).
    pub fn solve_tangent_side(&self, side: usize, seat: &mut Seat, rhs: &mut [f64]) {
        self.solver.solve_side(side, seat, rhs);
    }

    /// Takes the tangent values last factorised in the columns `columns` from `other` (the other
    /// side's, [`Assembler::factor_tangent_side`]), so that [`Assembler::factored_values`] is the
    /// whole tangent's.
    pub fn take_factored_columns(&mut self, other: &Assembler, columns: Range<usize>) {
        let r = self.k.column_slots(columns);
        self.factored[r.clone()].copy_from_slice(&other.factored[r]);
    }

    /// Takes the elements' results (axial forces and end moments) of `elements` from `other`'s
    /// last assembly (the other part's, [`Assembler::assemble_structure_part`]).
    pub fn take_element_results(&mut self, other: &Assembler, elements: Range<usize>) {
        self.axial[elements.clone()].copy_from_slice(&other.axial[elements.clone()]);
        self.moments[elements.clone()].copy_from_slice(&other.moments[elements]);
    }

    /// Moves the band's middle (where its two ends meet, [`crate::sparse::LinearSolver::set_twist`]) to the node
    /// boundary nearest the middle of the line, so that its bottom end starts at a node's first
    /// equation, and returns the last node `k` above it: the top end and the middle then hold
    /// the equations of the nodes `0..=k` and the bottom end those of the nodes `k + 1..`, the
    /// [`super::Part::halves`] at `k` (issue 48). `None` for a tangent factorised top-down.
    pub fn split_at_node(&mut self, model: &LineModel) -> Option<usize> {
        let m0 = self.solver.twist()?;
        let first_equation = |i: usize| (3 * i..3 * i + 3).find_map(|g| model.equation[g]);
        let (k, m) = (1..model.nodes())
            .filter_map(|i| {
                first_equation(i)
                    .filter(|&p| p >= 5)
                    .map(|p| (i - 1, p - 5))
            })
            .min_by_key(|&(_, m)| m.abs_diff(m0))?;
        self.solver.set_twist(m).then_some(k)
    }
}
