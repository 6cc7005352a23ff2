//! One interface to the seabed a scene chose: a contact law plus optional soil buoyancy.
//!
//! The total upward force per unit length on a node is `F = P(z) + F_b(z)`, with tangent
//! `dF/dz = dP/dz + dF_b/dz`. Static analysis uses [`Seabed::backbone`] (initial penetration only, as
//! the paper prescribes); dynamics use [`Seabed::evaluate`] from each node's committed history.

use serde::{Deserialize, Serialize};

use crate::rq::{Branch, Mode, RandolphQuiggin, RqHistory};
use crate::{LinearSeabed, SoilBuoyancy};

/// The per-node committed history (the Randolph–Quiggin history; the linear law only tracks its
/// mode and last penetration in it).
pub type SeabedHistory = RqHistory;

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
    /// `d(P + F_b)/dz`, N/m².
    pub tangent: f64,
    /// The formula `P` came from.
    pub branch: Branch,
    /// The history to commit if the step converges.
    pub next: SeabedHistory,
}

impl SeabedTrial {
    /// `P + F_b`, N/m (upward).
    pub fn total(&self) -> f64 {
        self.resistance + self.buoyancy
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

    /// A trial at penetration `z` from the committed history `h` (pure).
    pub fn evaluate(&self, h: &SeabedHistory, z: f64) -> SeabedTrial {
        let (resistance, tangent, branch, next) = match &self.law {
            Law::RandolphQuiggin(rq) => {
                let t = rq.evaluate(h, z);
                (t.p, t.tangent, t.branch, t.next)
            }
            Law::Linear(l) => {
                let (p, dp) = l.force(z);
                (p, dp, linear_branch(z), linear_next(h, z, p))
            }
        };
        self.with_buoyancy(resistance, tangent, branch, next, z)
    }

    /// The static (initial-penetration-only) response at `z`: the backbone for Randolph–Quiggin.
    pub fn backbone(&self, z: f64) -> SeabedTrial {
        self.evaluate(&SeabedHistory::untouched(0.0), z)
    }

    /// The history of a node at the start of a dynamic run, from its static penetration `z_s`.
    pub fn start_of_dynamics(&self, z_s: f64) -> SeabedHistory {
        match &self.law {
            Law::RandolphQuiggin(rq) => rq.start_of_dynamics(z_s),
            Law::Linear(l) => linear_next(&SeabedHistory::untouched(0.0), z_s, l.force(z_s).0),
        }
    }

    fn with_buoyancy(
        &self,
        resistance: f64,
        tangent: f64,
        branch: Branch,
        next: SeabedHistory,
        z: f64,
    ) -> SeabedTrial {
        let (buoyancy, db) = self.buoyancy.map_or((0.0, 0.0), |b| b.force(z));
        SeabedTrial {
            resistance,
            buoyancy,
            tangent: tangent + db,
            branch,
            next,
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

fn linear_next(h: &SeabedHistory, z: f64, p: f64) -> SeabedHistory {
    let contact = z > 0.0;
    SeabedHistory {
        mode: if contact {
            Mode::InitialPenetration
        } else {
            Mode::NotInContact
        },
        z_prev: z,
        p_prev: p,
        z_max: h.z_max.max(z),
        contacted: h.contacted || contact,
        ..SeabedHistory::untouched(z)
    }
}
