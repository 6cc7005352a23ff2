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
use crate::rq::{Branch, Mode, OnsetMemo, RandolphQuiggin, RqHistory};
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

impl Law {
    /// The law's name in scene files and outputs (`model = "…"`).
    pub fn name(&self) -> &'static str {
        match self {
            Law::Linear(_) => "linear",
            Law::RandolphQuiggin(_) => "randolph-quiggin",
        }
    }

    /// The law's name for people.
    pub fn title(&self) -> &'static str {
        match self {
            Law::Linear(_) => "linear seabed",
            Law::RandolphQuiggin(_) => "Randolph–Quiggin seabed",
        }
    }

    /// A step's cost on this law relative to the linear law's, as measured on the storm cases
    /// (`catena check`'s estimate of a run's time; 1 for a law not measured).
    pub fn relative_cost(&self) -> f64 {
        match self {
            Law::Linear(_) => 1.0,
            Law::RandolphQuiggin(_) => 1.9,
        }
    }
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

/// The seabed's total force per length `P + F_b + F_d` (N/m, upward): the one place it is summed
/// (a trial's [`SeabedTrial::total`] and the residual passes' responses, the same values to the bit;
/// a law without damping passes `F_d = 0`).
#[inline(always)]
fn total_force(resistance: f64, buoyancy: f64, damping: f64) -> f64 {
    resistance + buoyancy + damping
}

impl SeabedTrial {
    /// `P + F_b + F_d`, N/m (upward).
    pub fn total(&self) -> f64 {
        total_force(self.resistance, self.buoyancy, self.damping)
    }

    /// What a residual needs of it.
    pub fn response(&self) -> SeabedResponse {
        SeabedResponse {
            total: self.total(),
            tangent: self.tangent,
            damping_coefficient: self.damping_coefficient,
        }
    }
}

/// What a node's trials may keep between them (a pure cache, one per node, in the caller's
/// workspace: never part of the history, never changes a value): the Randolph–Quiggin law's last
/// suction onset ([`crate::rq::OnsetMemo`]), which every trial of a step that starts an uplift
/// needs from the same committed history.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TrialMemo {
    onset: OnsetMemo,
}

/// What a residual needs of a trial ([`Seabed::response`]): [`SeabedTrial`] without the branch and
/// the next history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeabedResponse {
    /// `P + F_b + F_d`, N/m (upward): [`SeabedTrial::total`].
    pub total: f64,
    /// [`SeabedTrial::tangent`], N/m².
    pub tangent: f64,
    /// [`SeabedTrial::damping_coefficient`], N·s/m².
    pub damping_coefficient: f64,
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

    /// The force of the trial [`Seabed::evaluate`] makes, without its next history: the same
    /// values, the linear law's computed in line (a residual evaluates every node; the commit takes
    /// the histories); `memo` is the node's [`TrialMemo`].
    #[inline(always)]
    pub fn response(
        &self,
        h: &SeabedHistory,
        z: f64,
        z_rate: f64,
        dt: f64,
        memo: &mut TrialMemo,
    ) -> SeabedResponse {
        match (&self.law, h) {
            (Law::Linear(l), SeabedHistory::Linear(_)) => {
                let ((p, dp), (fd, dfd)) = (l.force(z), l.damping_force(z, z_rate));
                let (buoyancy, db) = self.buoyancy.map_or((0.0, 0.0), |b| b.force(z));
                SeabedResponse {
                    total: total_force(p, buoyancy, fd),
                    tangent: dp + db,
                    damping_coefficient: dfd,
                }
            }
            (Law::RandolphQuiggin(rq), SeabedHistory::RandolphQuiggin(h)) => {
                self.rq_response(rq, h, (z, z_rate), (memo, None))
            }
            _ => self.evaluate_with(h, z, z_rate, dt, memo).response(),
        }
    }

    /// What [`Seabed::evaluate`] makes of a Randolph–Quiggin trial, without building the
    /// [`SeabedTrial`] (the same sums: no damping, `+ 0` included), and its next history into
    /// `next` if given. Not inlined: the residual loop stays as small for the linear law as
    /// without this arm.
    #[inline(never)]
    fn rq_response(
        &self,
        rq: &RandolphQuiggin,
        h: &RqHistory,
        (z, z_rate): (f64, f64),
        (memo, next): (&mut TrialMemo, Option<&mut SeabedHistory>),
    ) -> SeabedResponse {
        let t = rq.evaluate_rate(h, z, z_rate, &mut memo.onset);
        if let Some(next) = next {
            *next = SeabedHistory::RandolphQuiggin(t.next);
        }
        let (buoyancy, db) = self.buoyancy.map_or((0.0, 0.0), |b| b.force(z));
        SeabedResponse {
            // The law has no damping force.
            total: total_force(t.p, buoyancy, 0.0),
            tangent: t.tangent + db,
            damping_coefficient: 0.0,
        }
    }

    /// [`Seabed::response`], writing the trial's next history into `next` (the linear law's in
    /// line, without the copy of a whole [`SeabedTrial`]); `memo` is the node's [`TrialMemo`].
    #[inline(always)]
    pub fn response_and_next(
        &self,
        h: &SeabedHistory,
        z: f64,
        z_rate: f64,
        dt: f64,
        (memo, next): (&mut TrialMemo, &mut SeabedHistory),
    ) -> SeabedResponse {
        match (&self.law, h) {
            (Law::Linear(_), SeabedHistory::Linear(l)) => {
                *next = SeabedHistory::Linear(l.next(z));
                self.response(h, z, z_rate, dt, memo)
            }
            (Law::RandolphQuiggin(rq), SeabedHistory::RandolphQuiggin(hr)) => {
                self.rq_response(rq, hr, (z, z_rate), (memo, Some(next)))
            }
            _ => {
                let t = self.evaluate_with(h, z, z_rate, dt, memo);
                *next = t.next;
                t.response()
            }
        }
    }

    /// A trial at penetration `z` moving at the rate `z_rate = ż` (m/s, positive down) over a step of
    /// `dt` (s), from the committed history `h` (pure). A history of another law than this one (which
    /// a checked scene and checkpoint never give) is read as an untouched node.
    pub fn evaluate(&self, h: &SeabedHistory, z: f64, z_rate: f64, dt: f64) -> SeabedTrial {
        self.evaluate_with(h, z, z_rate, dt, &mut TrialMemo::default())
    }

    /// [`Seabed::evaluate`] with a node's [`TrialMemo`] (the same values to the bit).
    pub fn evaluate_with(
        &self,
        h: &SeabedHistory,
        z: f64,
        z_rate: f64,
        dt: f64,
        memo: &mut TrialMemo,
    ) -> SeabedTrial {
        let _ = dt; // The laws' rates are their own (linear damping, R–Q rate-dependent suction).
        let (resistance, tangent, branch, next, damping, c) = match (&self.law, h) {
            (Law::RandolphQuiggin(rq), SeabedHistory::RandolphQuiggin(h)) => {
                let t = rq.evaluate_rate(h, z, z_rate, &mut memo.onset);
                (
                    t.p,
                    t.tangent,
                    t.branch,
                    SeabedHistory::RandolphQuiggin(t.next),
                    0.0,
                    0.0,
                )
            }
            (Law::RandolphQuiggin(_), _) => {
                return self.evaluate_with(&self.untouched(), z, z_rate, dt, memo)
            }
            (Law::Linear(l), SeabedHistory::Linear(h)) => {
                let ((p, dp), (fd, dfd)) = (l.force(z), l.damping_force(z, z_rate));
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

    /// A node's history after a rest of `t` seconds (a calm interval between storms): the
    /// Randolph–Quiggin law's regain of degraded strength, if its scene asks for it
    /// ([`crate::degradation`]); otherwise unchanged.
    pub fn rest(&self, h: &SeabedHistory, t: f64) -> SeabedHistory {
        match (&self.law, h) {
            (Law::RandolphQuiggin(rq), SeabedHistory::RandolphQuiggin(h)) => {
                SeabedHistory::RandolphQuiggin(rq.rest(h, t))
            }
            _ => *h,
        }
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

#[cfg(test)]
mod response_tests {
    use super::*;
    use crate::rq::RqParams;
    use crate::{LinearSeabed, RandolphQuiggin, SoilBuoyancy};

    /// Along a cyclic path (penetration, uplift past lift-off, repenetration), committing each
    /// trial: `response` and `response_and_next` give `evaluate`'s values to the bit, for both laws
    /// with and without soil buoyancy and damping.
    #[test]
    fn the_response_is_the_trials_to_the_bit() {
        let d = 0.2286;
        let buoyancy = SoilBuoyancy::new(d, 1.5, 1500.0, 1025.0).expect("valid");
        let laws = [
            Law::Linear(LinearSeabed::new(d, 1.0e5, 0.0).expect("valid")),
            Law::Linear(LinearSeabed::new(d, 1.0e5, 3.0e3).expect("valid")),
            Law::RandolphQuiggin(RandolphQuiggin::new(RqParams::table1()).expect("valid")),
        ];
        for law in laws {
            for buoyancy in [None, Some(buoyancy)] {
                let sb = Seabed { law, buoyancy };
                let mut h = sb.untouched();
                let mut z_prev = 0.0;
                for k in 0..400 {
                    let z = d * (0.3 * (k as f64 * 0.07).sin() + 0.1 - 1e-3 * k as f64);
                    let rate = (z - z_prev) / 0.05;
                    let t = sb.evaluate(&h, z, rate, 0.05);
                    // Two trials of one step share the node's memo: the second, at another z
                    // from the same history, as Newton's next iterate does.
                    let mut memo = TrialMemo::default();
                    let r0 = sb.response(&h, z + 1e-4, rate, 0.05, &mut memo);
                    let t0 = sb.evaluate(&h, z + 1e-4, rate, 0.05);
                    assert_eq!(r0.total.to_bits(), t0.total().to_bits(), "{k}");
                    let r = sb.response(&h, z, rate, 0.05, &mut memo);
                    let mut next = sb.untouched();
                    let rn = sb.response_and_next(&h, z, rate, 0.05, (&mut memo, &mut next));
                    for x in [r, rn] {
                        assert_eq!(x.total.to_bits(), t.total().to_bits(), "{k}");
                        assert_eq!(x.tangent.to_bits(), t.tangent.to_bits(), "{k}");
                        assert_eq!(
                            x.damping_coefficient.to_bits(),
                            t.damping_coefficient.to_bits()
                        );
                    }
                    assert_eq!(next, t.next, "{k}");
                    (h, z_prev) = (t.next, z);
                }
            }
        }
    }

    /// One memo for trials from two histories that differ only in `P_prev`, in turn: each gets
    /// its own suction onset (the memo is keyed on both), the same trial as without the memo.
    #[test]
    fn the_onset_memo_is_keyed_on_the_history() {
        let rq = RandolphQuiggin::new(RqParams::table1()).expect("valid");
        let mut h = crate::RqHistory::untouched(0.0);
        h.mode = Mode::InitialPenetration;
        h.contacted = true;
        h.z_prev = 0.05;
        h.z_max = 0.05;
        let (mut a, mut b) = (h, h);
        a.p_prev = rq.pu(0.05).0;
        b.p_prev = 0.5 * a.p_prev;
        let mut memo = OnsetMemo::default();
        // Uplifts past the onsets (a few D/Kmax), so that every trial needs its onset.
        for (hist, z) in [(a, 0.03), (b, 0.03), (a, 0.02), (b, 0.025)] {
            let with = rq.evaluate_with(&hist, z, &mut memo);
            let fresh = rq.evaluate(&hist, z);
            assert_eq!(with.next, fresh.next);
            assert_eq!(with.p.to_bits(), fresh.p.to_bits());
            assert!(!with.next.z_c_pending && with.next.z_c.is_some());
        }
        assert_ne!(
            rq.evaluate(&a, 0.03).next.z_c,
            rq.evaluate(&b, 0.03).next.z_c
        );
    }
}
