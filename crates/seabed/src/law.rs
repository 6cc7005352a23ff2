//! One interface to the seabed a scene chose: a contact law plus optional soil buoyancy.
//!
//! The total upward force per unit length on a node is
//!
//! ```text
//! F = P(z; history) + F_b(z) + F_d(z, ż)
//! ```
//!
//! (resistance, soil buoyancy, damping) with the tangents `∂F/∂z = dP/dz + dF_b/dz` and
//! `∂F/∂ż` (the damping coefficient). Static analysis uses [`Seabed::backbone`] (initial penetration
//! only, as the paper prescribes); dynamics use [`Seabed::evaluate`] from each node's committed
//! history, with the penetration rate ż and the step Δt.
//!
//! **Each law owns its history type** ([`LinearHistory`], [`RqHistory`]); [`SeabedHistory`] is the
//! tagged union the FE code stores, one per node, without knowing what is inside. Adding a law
//! means: its own module (parameters, history, `evaluate`), a variant in [`Law`] and in
//! [`SeabedHistory`] here, and its scene table; nothing in the FE code or the output code.

use serde::{Deserialize, Serialize};

use crate::linear::LinearHistory;
use crate::rq::{Branch, Mode, RandolphQuiggin, RqHistory};
use crate::{LinearSeabed, SoilBuoyancy};

/// The committed history of one node, of whichever law the seabed has.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "kebab-case")]
pub enum SeabedHistory {
    /// The linear law's history.
    Linear(LinearHistory),
    /// The Randolph–Quiggin history.
    RandolphQuiggin(RqHistory),
}

impl SeabedHistory {
    /// The contact mode after the last converged step (for output: the linear law is in
    /// `InitialPenetration` while in contact and `NotInContact` otherwise).
    pub fn mode(&self) -> Mode {
        match self {
            SeabedHistory::Linear(h) => h.mode(),
            SeabedHistory::RandolphQuiggin(h) => h.mode,
        }
    }

    /// The penetration at the last converged step, m.
    pub fn z_prev(&self) -> f64 {
        match self {
            SeabedHistory::Linear(h) => h.z_prev,
            SeabedHistory::RandolphQuiggin(h) => h.z_prev,
        }
    }

    /// The Randolph–Quiggin history, if it is one.
    pub fn as_rq(&self) -> Option<&RqHistory> {
        match self {
            SeabedHistory::RandolphQuiggin(h) => Some(h),
            SeabedHistory::Linear(_) => None,
        }
    }
}

/// The contact law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "kebab-case")]
pub enum Law {
    /// `P = k·D·z`.
    Linear(LinearSeabed),
    /// Randolph & Quiggin (2009).
    RandolphQuiggin(RandolphQuiggin),
}

/// A seabed: a law and, optionally, soil buoyancy.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Seabed {
    /// The contact law.
    pub law: Law,
    /// Soil buoyancy (eq. 15), if the scene asks for it.
    pub buoyancy: Option<SoilBuoyancy>,
}

/// A trial of the whole seabed at one node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeabedTrial {
    /// Soil resistance `P`, N/m.
    pub resistance: f64,
    /// Soil buoyancy `F_b`, N/m.
    pub buoyancy: f64,
    /// Seabed damping `F_d`, N/m (0 for laws without damping).
    pub damping: f64,
    /// `∂(P + F_b + F_d)/∂z`, N/m².
    pub tangent: f64,
    /// `∂F_d/∂ż`, N·s/m² (the damping coefficient per unit length).
    pub damping_coefficient: f64,
    /// The formula `P` came from.
    pub branch: Branch,
    /// The history to commit if the step converges.
    pub next: SeabedHistory,
}

impl SeabedTrial {
    /// `P + F_b + F_d`, N/m (upward).
    pub fn total(&self) -> f64 {
        self.resistance + self.buoyancy + self.damping
    }
}

impl Seabed {
    /// The contact diameter of the law, m.
    pub fn diameter(&self) -> f64 {
        match &self.law {
            Law::Linear(l) => l.diameter,
            Law::RandolphQuiggin(r) => r.params().diameter,
        }
    }

    /// The history of a node that has never touched the seabed, for this law.
    pub fn untouched(&self) -> SeabedHistory {
        match &self.law {
            Law::Linear(_) => SeabedHistory::Linear(LinearHistory::default()),
            Law::RandolphQuiggin(_) => SeabedHistory::RandolphQuiggin(RqHistory::untouched(0.0)),
        }
    }

    /// A trial at penetration `z` moving at the rate `z_rate = ż` (m/s, positive down) over a step of
    /// `dt` (s), from the committed history `h` (pure). A history of another law than this one (which
    /// a checked scene and checkpoint never give) is read as an untouched node.
    pub fn evaluate(&self, h: &SeabedHistory, z: f64, z_rate: f64, dt: f64) -> SeabedTrial {
        let _ = dt; // No law of catena's is rate-dependent beyond linear damping yet.
        let (resistance, tangent, branch, next, damping, c) = match (&self.law, h) {
            (Law::RandolphQuiggin(rq), SeabedHistory::RandolphQuiggin(h)) => {
                let t = rq.evaluate(h, z);
                (
                    t.p,
                    t.tangent,
                    t.branch,
                    SeabedHistory::RandolphQuiggin(t.next),
                    0.0,
                    0.0,
                )
            }
            (Law::RandolphQuiggin(_), _) => return self.evaluate(&self.untouched(), z, z_rate, dt),
            (Law::Linear(l), SeabedHistory::Linear(h)) => {
                let (p, dp) = l.force(z);
                let (fd, dfd) = l.damping_force(z, z_rate);
                (
                    p,
                    dp,
                    linear_branch(z),
                    SeabedHistory::Linear(h.next(z)),
                    fd,
                    dfd,
                )
            }
            (Law::Linear(_), _) => return self.evaluate(&self.untouched(), z, z_rate, dt),
        };
        let (buoyancy, db) = self.buoyancy.map_or((0.0, 0.0), |b| b.force(z));
        SeabedTrial {
            resistance,
            buoyancy,
            damping,
            tangent: tangent + db,
            damping_coefficient: c,
            branch,
            next,
        }
    }

    /// The static (initial-penetration-only) response at `z`: the backbone for Randolph–Quiggin, at
    /// rest.
    pub fn backbone(&self, z: f64) -> SeabedTrial {
        self.evaluate(&self.untouched(), z, 0.0, 0.0)
    }

    /// The history of a node at the start of a dynamic run, from its static penetration `z_s`.
    pub fn start_of_dynamics(&self, z_s: f64) -> SeabedHistory {
        match &self.law {
            Law::RandolphQuiggin(rq) => SeabedHistory::RandolphQuiggin(rq.start_of_dynamics(z_s)),
            Law::Linear(_) => SeabedHistory::Linear(LinearHistory::default().next(z_s)),
        }
    }
}

fn linear_branch(z: f64) -> Branch {
    if z > 0.0 {
        Branch::Backbone
    } else {
        Branch::NoContact
    }
}
