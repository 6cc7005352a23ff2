//! Boundary conditions of the dynamics: every prescribed degree of freedom and what prescribes it,
//! as a list built once from the line's supports, so that the stepper never names a node.
//!
//! The line's node 0 is its top end (arc length from the top). A support's prescribed translations
//! at the top follow the top end's motion ([`crate::dynamics::DynamicModel::top_at`]: the
//! prescribed motion plus the vessel's) when there is one, exactly at `t_{n+1}`: displacement,
//! velocity and acceleration (only the forces are α-weighted, [`crate::integrator`]). A top that
//! also holds the rotation (`"fixed"`, or a lay's clamped tower) turns with the vessel, rigidly:
//! its counter-clockwise rotation is `−pitch` (pitch positive bow down), so over a step from `t_n`
//! to `t_{n+1}`
//!
//! ```text
//! θ_{n+1} = θ_n − (β_{n+1} − β_n),   θ̇_{n+1} = −β̇_{n+1},   θ̈_{n+1} = −β̈_{n+1}
//! ```
//!
//! (`β` the vessel's ramped pitch, zero at the start: `θ = θ_static − β(t)`, taken step by step so
//! that a lay's new top node, placed on the pitched tower, turns from where it is placed). Every
//! other prescribed dof is held where the statics left it, at rest.

use crate::model::LineModel;
use crate::motion::TopState;

/// What prescribes a degree of freedom.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Prescribed {
    /// Held where it is, at rest.
    Held,
    /// The top end's motion, component `k` (0: x, 1: z); held when the top does not move.
    TopMotion(usize),
    /// The top end's rotation: turned by the vessel's pitch; held without a vessel.
    TopRotation,
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
                (TOP, _) => Prescribed::TopRotation,
                _ => Prescribed::Held,
            },
        })
        .collect()
}

/// The top end's prescribed motion over a step: its displacement, velocity and acceleration at
/// `t_{n+1}` (`[x, z]` each), and, with a vessel, its turn: the rotation's change over the step,
/// its rate and its acceleration at `t_{n+1}` (`−(β_{n+1} − β_n)`, `−β̇`, `−β̈`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TopPrescribed {
    /// Displacement, m.
    pub d: [f64; 2],
    /// Velocity, m/s.
    pub v: [f64; 2],
    /// Acceleration, m/s².
    pub a: [f64; 2],
    /// The turn with the vessel (`None` without one: the rotation is held).
    pub turn: Option<[f64; 3]>,
}

impl TopPrescribed {
    /// The top's state `at` the step's end; `before`, for a top that turns with the vessel, the
    /// vessel's pitch at the step's start.
    pub fn new(at: TopState, before: Option<f64>) -> Self {
        Self {
            d: at.d,
            v: at.v,
            a: at.a,
            turn: before.map(|b| [-(at.pitch - b), -at.pitch_rates[0], -at.pitch_rates[1]]),
        }
    }
}

/// The prescribed dofs' displacement, velocity and acceleration at the iterate: the top's motion
/// at `t_{n+1}` for [`Prescribed::TopMotion`], its rotation turned from the step's start by the
/// vessel for [`Prescribed::TopRotation`], the step's start `u0` at rest otherwise.
#[inline]
pub fn apply(
    constraints: &[Constraint],
    top: Option<&TopPrescribed>,
    u0: &[f64],
    (u, v, a): (&mut [f64], &mut [f64], &mut [f64]),
) {
    for c in constraints {
        let g = c.dof;
        match (c.by, top) {
            (Prescribed::TopMotion(k), Some(t)) => {
                u[g] = t.d[k];
                v[g] = t.v[k];
                a[g] = t.a[k];
            }
            (
                Prescribed::TopRotation,
                Some(TopPrescribed {
                    turn: Some([dq, w, dw]),
                    ..
                }),
            ) => {
                u[g] = u0[g] + dq;
                v[g] = *w;
                a[g] = *dw;
            }
            _ => {
                u[g] = u0[g];
                v[g] = 0.0;
                a[g] = 0.0;
            }
        }
    }
}
