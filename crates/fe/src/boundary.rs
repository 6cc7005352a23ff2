//! Boundary conditions of the dynamics: every prescribed degree of freedom and what prescribes it,
//! as a list built once from the line's supports, so that the stepper never names a node.
//!
//! The line's node 0 is its top end (arc length from the top). A support's prescribed translations
//! at the top follow the top end's motion ([`crate::dynamics::DynamicModel::top_at`]: the
//! prescribed motion plus the vessel's) when there is one, exactly at `t_{n+1}`: displacement,
//! velocity and acceleration (only the forces are α-weighted, [`crate::integrator`]). Every other
//! prescribed dof is held where the statics left it, at rest.

use crate::model::LineModel;

/// What prescribes a degree of freedom.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Prescribed {
    /// Held where it is, at rest.
    Held,
    /// The top end's motion, component `k` (0: x, 1: z); held when the top does not move.
    TopMotion(usize),
}

/// One prescribed degree of freedom.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Constraint {
    /// The global dof (3 per node: x, z, θ).
    pub dof: usize,
    /// What prescribes it.
    pub by: Prescribed,
}

/// The line's prescribed dofs, in dof order.
pub fn constraints(line: &LineModel) -> Vec<Constraint> {
    const TOP: usize = 0;
    line.equation
        .iter()
        .enumerate()
        .filter(|(_, e)| e.is_none())
        .map(|(dof, _)| Constraint {
            dof,
            by: match (dof / 3, dof % 3) {
                (TOP, k @ (0 | 1)) => Prescribed::TopMotion(k),
                _ => Prescribed::Held,
            },
        })
        .collect()
}

/// The prescribed dofs' displacement, velocity and acceleration at the iterate: the top's motion
/// `(d, v, a)` at `t_{n+1}` for [`Prescribed::TopMotion`], the step's start `u0` at rest otherwise.
#[inline]
pub fn apply(
    constraints: &[Constraint],
    top: Option<&([f64; 2], [f64; 2], [f64; 2])>,
    u0: &[f64],
    (u, v, a): (&mut [f64], &mut [f64], &mut [f64]),
) {
    for c in constraints {
        let g = c.dof;
        match (c.by, top) {
            (Prescribed::TopMotion(k), Some((d, vt, at))) => {
                u[g] = d[k];
                v[g] = vt[k];
                a[g] = at[k];
            }
            _ => {
                u[g] = u0[g];
                v[g] = 0.0;
                a[g] = 0.0;
            }
        }
    }
}
