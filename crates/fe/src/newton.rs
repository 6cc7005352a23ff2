//! Newton's method for one time step, apart from the integrator ([`crate::integrator`]) and the
//! stepping ([`crate::dynamics`]): what each iteration evaluates (the lazy tangent with the reuse
//! of the last factorisation), backtracking, the divergence and convergence tests, the rounding
//! floor of the residual and the worst node of a failed attempt. [`Newton`] is the attempt's
//! bookkeeping; the caller evaluates the forces and solves.
//!
//! **Lazy tangent, factorisation reuse.** The first iteration of a step reuses the Jacobian
//! factorised last when it was for the same Δt (a modified-Newton start: one factorisation per step
//! instead of two). It goes on reusing it while that pays (a modified-Newton chain, at most
//! [`MAX_REUSES`] corrections): a correction with the old factorisation contracts the residual
//! linearly, `r_{k+1} ≈ q·r_k`, with a rate `q` measured at each such correction and carried from
//! step to step. After a correction from `r` the next iteration evaluates
//! - the residual keeping histories when `r·q ≤ tol` (expected to converge);
//! - the residual only when `r·q² ≤ tol` and `q ≤` [`MAX_REUSE_RATE`] (one more reused correction
//!   expected to converge);
//! - else the tangent at once (Newton's quadratic path, as without a chain).
//!
//! A residual that did not converge is corrected with the old factorisation again only when its
//! measured `r·q ≤ tol`; otherwise the tangent is assembled at its iterate and factorised. Each
//! residual-only iteration costs a residual pass and a solve, against the tangent pass (twice a
//! residual's work) and a factorisation it replaces (`benches/README.md` has the numbers). The
//! converged answer meets the same tolerance either way, but it is not the same to the bit as full
//! Newton's: a chain stops at a different iterate.
//!
//! After a correction with a fresh factorisation Newton is quadratic and the next residual nearly
//! always converges: it is evaluated without the tangent (keeping each node's trial seabed history
//! for the commit, [`Pass::KeepingHistories`]), and the tangent is assembled at that iterate only
//! if it does not converge (the residual and the tangent do not depend on each other, so this
//! laziness changes no bit).
//!
//! **Backtracking.** A correction after which the residual norm is larger than before it is halved
//! (the iterate moved back halfway), up to [`MAX_BACKTRACKS`] times, before the next correction is
//! computed from wherever that leaves it (see [`crate::dynamics`] for why: the seabed at lift-off).
//!
//! **Divergence and convergence.** An attempt diverges when the residual is not finite, or, from
//! the third iteration, 10⁴ times the first's. It converges when `r ≤ tol + floor/‖F_weight‖`
//! ([`residual_floor`]), or when `r ≤ 1e-6` with a correction below `1e-10` (machine-precision
//! stagnation).

use crate::model::LineModel;

/// Halvings of one Newton correction that raised the residual, before it is taken as it is.
pub const MAX_BACKTRACKS: u32 = 3;

/// What an evaluation of the forces at an iterate assembles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    /// The residual only.
    Forces,
    /// The residual, keeping each node's trial seabed history for the commit (the iterate is
    /// expected to converge).
    KeepingHistories,
    /// The residual and the tangent.
    Tangent,
}

/// The judgement of an iterate's relative residual.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Verdict {
    /// The last correction raised the residual: move the iterate by `back` times the correction
    /// (towards where it came from) and evaluate again.
    Backtrack {
        /// The fraction of the correction to add back.
        back: f64,
    },
    /// Accepted (its free equations are to be kept for a failure's report): diverged, converged,
    /// or on to a correction.
    Accepted(Accepted),
}

/// What an accepted iterate calls for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Accepted {
    /// Diverging: give up the attempt at once.
    Diverged,
    /// Converged: commit.
    Converged,
    /// A correction: assemble the tangent at this iterate first (`refresh_tangent`, after a lazy
    /// residual that did not converge), and factorise it (`factor`; else the last factorisation is
    /// reused).
    Correct {
        /// Assemble the tangent at this iterate first.
        refresh_tangent: bool,
        /// Factorise the tangent.
        factor: bool,
    },
}

/// Corrections with a reused factorisation in one attempt, at most.
pub const MAX_REUSES: u32 = 4;

/// The largest contraction rate (`r_k / r_{k−1}`) of a correction with a reused factorisation for
/// which another one is taken.
pub const MAX_REUSE_RATE: f64 = 0.1;

/// One attempt's Newton bookkeeping.
#[derive(Debug, Clone, Copy)]
pub struct Newton {
    /// The tolerance on the relative residual (the floor included).
    tol: f64,
    /// The factorisation in hand is the one reused from an earlier step (none fresh yet).
    old_factor: bool,
    /// The contraction rate of a correction with the reused factorisation: measured in this
    /// attempt, or carried from the steps before.
    rate: Option<f64>,
    /// Corrections made with the reused factorisation (the last one was, while `old_factor`).
    reuses: u32,
    /// What the next iteration evaluates.
    next: Pass,
    r_prev: f64,
    lambda: f64,
    backtracks: u32,
    first: f64,
    last: (usize, f64),
}

impl Newton {
    /// A new attempt to the relative tolerance `tol`; `reusable` when the last factorisation is
    /// for its Δt, and `rate` the contraction rate its corrections had (if measured).
    pub fn new(reusable: bool, rate: Option<f64>, tol: f64) -> Self {
        Self {
            tol,
            old_factor: reusable,
            rate: rate.filter(|_| reusable),
            reuses: 0,
            next: if reusable {
                Pass::Forces
            } else {
                Pass::Tangent
            },
            r_prev: f64::INFINITY,
            lambda: 1.0,
            backtracks: 0,
            first: f64::INFINITY,
            last: (0, f64::INFINITY),
        }
    }

    /// What the next iteration evaluates.
    pub fn pass(&self) -> Pass {
        self.next
    }

    /// The contraction rate of the reused factorisation's corrections, as last measured.
    pub fn rate(&self) -> Option<f64> {
        self.rate
    }

    /// Judges the relative residual `r` of iteration `it` (evaluated with [`Self::pass`]).
    pub fn judge(&mut self, it: usize, r: f64) -> Verdict {
        if r.is_finite() && r > self.r_prev && self.backtracks < MAX_BACKTRACKS {
            // u = u₀ − λ·dq → u₀ − (λ/2)·dq: add back λ/2 of it.
            self.lambda *= 0.5;
            self.backtracks += 1;
            return Verdict::Backtrack { back: self.lambda };
        }
        // The rate of a whole correction with the reused factorisation (a backtracked one says
        // the factorisation is no longer good enough).
        if self.old_factor && self.reuses > 0 {
            self.rate = Some(if self.backtracks == 0 {
                r / self.r_prev
            } else {
                1.0
            });
        }
        self.r_prev = r;
        self.lambda = 1.0;
        self.backtracks = 0;
        self.last = (it, r);
        if it == 0 {
            self.first = r;
        }
        // Diverging (the residual 10⁴ times its start): give up at once, retry or cut.
        if !r.is_finite() || (it >= 2 && r > 1e4 * self.first) {
            return Verdict::Accepted(Accepted::Diverged);
        }
        if r <= self.tol {
            return Verdict::Accepted(Accepted::Converged);
        }
        let evaluated = self.next;
        // Reuse the old factorisation at the start, and again while its corrections contract
        // fast enough for the next one to converge; never after a tangent was assembled here.
        let reuse = self.old_factor
            && evaluated != Pass::Tangent
            && self.reuses < MAX_REUSES
            && (it == 0
                || self
                    .rate
                    .is_some_and(|q| q <= MAX_REUSE_RATE && r * q <= self.tol));
        if !reuse {
            self.old_factor = false;
            self.next = Pass::KeepingHistories;
            return Verdict::Accepted(Accepted::Correct {
                refresh_tangent: evaluated != Pass::Tangent,
                factor: true,
            });
        }
        self.reuses += 1;
        // After this correction: converged (predicted), one more reused correction, or the
        // tangent (Newton's, quadratic from there).
        self.next = match self.rate {
            Some(q) if r * q <= self.tol => Pass::KeepingHistories,
            Some(q) if q <= MAX_REUSE_RATE && r * q * q <= self.tol => Pass::Forces,
            _ => Pass::Tangent,
        };
        Verdict::Accepted(Accepted::Correct {
            refresh_tangent: false,
            factor: false,
        })
    }

    /// `(iteration, relative residual)` of the last accepted iterate.
    pub fn last(&self) -> (usize, f64) {
        self.last
    }

    /// Whether a correction of largest entry `step` from a residual `r` is machine-precision
    /// stagnation (converged as far as the state resolves).
    pub fn stagnated(r: f64, step: f64) -> bool {
        r <= 1e-6 && step <= 1e-10
    }
}

/// The largest `|g_e|` over the equations `eqs` and the first equation where it is (`0` and
/// `eqs.start` when every entry is zero).
pub fn largest_entry(g: &[f64], eqs: std::ops::Range<usize>) -> (f64, usize) {
    let (mut big, mut eq) = (0.0, eqs.start);
    for (e, x) in g.iter().enumerate().take(eqs.end).skip(eqs.start) {
        if x.abs() > big {
            (big, eq) = (x.abs(), e);
        }
    }
    (big, eq)
}

/// The node whose dof is free equation `eq` (0 when none is).
pub fn node_of_equation(model: &LineModel, eq: usize) -> usize {
    model
        .equation
        .iter()
        .position(|e| *e == Some(eq))
        .map_or(0, |g| g / 3)
}

/// `max |x|` (0 for none; a NaN is passed over, as `f64::max` does), in eight partial maxima: the
/// same value as one running maximum, without its chain of dependent comparisons.
pub fn max_abs(xs: &[f64]) -> f64 {
    let mut acc = [0.0f64; 8];
    let chunks = xs.chunks_exact(8);
    let rest = chunks.remainder();
    for c in chunks {
        for (a, x) in acc.iter_mut().zip(c) {
            *a = a.max(x.abs());
        }
    }
    rest.iter()
        .fold(acc.iter().fold(0.0, |m, a| m.max(*a)), |m, x| {
            m.max(x.abs())
        })
}

/// The rounding floor of the residual (N): `10·ε·√(Σₑ (EAₑ·(1 + U/L0ₑ))²)` with `U` the largest
/// translational displacement from the base configuration. An element's axial force is EA times a
/// strain computed from a chord `base + (uⱼ − uᵢ)` whose rounding is about `ε·U`, so the force is
/// known to about `EA·ε·(1 + U/L0)`, and no iteration can bring the residual below that. The step
/// converges when `‖G‖ ≤ tol·‖F_weight‖ + floor`. (Without the `U/L0` term the floor was too low
/// for short elements far from the base: Watchet with 0.0625 m elements stalled at a relative
/// residual of 1.05e-6 with the worst node wandering along the line.)
pub fn residual_floor(model: &LineModel, u: &[f64]) -> f64 {
    residual_floor_at(model, largest_translation(u))
}

/// The largest translational displacement `U = max |x|, |z|` of `u` (3 per node), in eight
/// partial maxima, four nodes at a time (the same value as one running maximum, without its chain
/// of dependent comparisons; a maximum is exact, so over parts of the line it is the largest of
/// theirs).
pub fn largest_translation(u: &[f64]) -> f64 {
    let mut acc = [0.0f64; 8];
    let nodes = u.chunks_exact(12);
    let rest = nodes.remainder();
    for c in nodes {
        for k in 0..4 {
            acc[2 * k] = acc[2 * k].max(c[3 * k].abs());
            acc[2 * k + 1] = acc[2 * k + 1].max(c[3 * k + 1].abs());
        }
    }
    rest.chunks_exact(3)
        .fold(max_abs(&acc), |m, c| m.max(c[0].abs()).max(c[1].abs()))
}

/// [`residual_floor`] for the largest translational displacement `big`
/// ([`largest_translation`]).
pub fn residual_floor_at(model: &LineModel, big: f64) -> f64 {
    10.0 * f64::EPSILON
        * model
            .elements
            .iter()
            .map(|e| (e.section.ea * (1.0 + big / e.l0)).powi(2))
            .sum::<f64>()
            .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values of every size and sign, with NaNs, ±0 and a length that is not a multiple of eight.
    fn values(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| match i % 37 {
                5 => f64::NAN,
                11 => -0.0,
                _ => {
                    ((i * 7919) % 1013) as f64
                        * 10f64.powi((i % 13) as i32 - 6)
                        * (-1f64).powi(i as i32)
                }
            })
            .collect()
    }

    #[test]
    fn the_partial_maxima_are_the_running_maximum() {
        for n in [0, 1, 7, 8, 9, 100, 1203] {
            let x = values(n);
            let running = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert_eq!(max_abs(&x).to_bits(), running.to_bits(), "n = {n}");
        }
    }

    #[test]
    fn the_partial_sums_of_squares_are_the_running_sum_to_rounding() {
        for n in [0, 1, 7, 8, 9, 100, 1203] {
            let x: Vec<f64> = values(n).into_iter().filter(|v| !v.is_nan()).collect();
            let running = x.iter().fold(0.0, |s, v| s + v * v);
            let s = crate::fastmath::lane_dot(&x, &x);
            assert!(
                (s - running).abs() <= 1e-15 * running,
                "n = {n}: {s} vs {running}"
            );
        }
    }

    /// The bookkeeping of an attempt: a reusable factorisation makes the first pass lazy and asks
    /// for no factorisation; without a measured rate the next pass assembles the tangent; after a
    /// fresh factorisation the next pass keeps histories; a rising residual is backtracked three
    /// times at most (½, ¼, ⅛ of the correction added back), then accepted; a residual 10⁴ times
    /// the first from the third iteration diverges.
    #[test]
    fn the_bookkeeping_of_an_attempt() {
        let mut n = Newton::new(true, None, 1e-9);
        assert_eq!(n.pass(), Pass::Forces);
        let v = n.judge(0, 1.0);
        assert_eq!(
            v,
            Verdict::Accepted(Accepted::Correct {
                refresh_tangent: false,
                factor: false
            })
        );
        assert_eq!(n.pass(), Pass::Tangent);
        assert_eq!(
            n.judge(1, 0.5),
            Verdict::Accepted(Accepted::Correct {
                refresh_tangent: false,
                factor: true
            })
        );
        // The reused correction's rate was measured on the way.
        assert_eq!(n.rate(), Some(0.5));
        assert_eq!(n.pass(), Pass::KeepingHistories);
        for back in [0.5, 0.25, 0.125] {
            assert_eq!(n.judge(2, 0.9), Verdict::Backtrack { back });
        }
        assert_eq!(
            n.judge(2, 0.9),
            Verdict::Accepted(Accepted::Correct {
                refresh_tangent: true,
                factor: true
            })
        );
        assert_eq!(n.last(), (2, 0.9));
        let mut d = Newton::new(false, Some(1e-3), 1e-9);
        assert_eq!(d.pass(), Pass::Tangent);
        d.judge(0, 1.0);
        d.judge(1, 0.5);
        assert_eq!(d.judge(2, f64::NAN), Verdict::Accepted(Accepted::Diverged));
        assert_eq!(
            Newton::new(false, None, 1e-9).judge(0, 1e-10),
            Verdict::Accepted(Accepted::Converged)
        );
    }

    /// The reused factorisation's chain: with a carried rate q, a start residual r0 with
    /// r0·q² ≤ tol is corrected twice with it (residuals only, the last keeping histories); one
    /// whose measured rate is too slow for the next correction to converge gets the tangent
    /// assembled at its iterate and factorised; with r0·q² > tol the tangent is assembled at once
    /// after the first correction (Newton's quadratic path).
    #[test]
    fn the_reused_factorisation_is_kept_while_it_contracts_fast_enough() {
        let tol = 1e-8;
        // r0 = 1e-3, q = 1e-3: r1 ≈ 1e-6, r2 ≈ 1e-9.
        let mut n = Newton::new(true, Some(1e-3), tol);
        let reuse = Verdict::Accepted(Accepted::Correct {
            refresh_tangent: false,
            factor: false,
        });
        assert_eq!(n.judge(0, 1e-3), reuse);
        assert_eq!(n.pass(), Pass::Forces);
        assert_eq!(n.judge(1, 2e-6), reuse);
        assert_eq!(n.rate(), Some(2e-6 / 1e-3));
        assert_eq!(n.pass(), Pass::KeepingHistories);
        assert_eq!(n.judge(2, 5e-9), Verdict::Accepted(Accepted::Converged));
        assert_eq!(n.rate(), Some(5e-9 / 2e-6));

        // The second correction contracts by 0.05 only: 1e-6·0.05 > tol, so the tangent.
        let mut s = Newton::new(true, Some(1e-3), tol);
        s.judge(0, 1e-3);
        assert_eq!(
            s.judge(1, 5e-5),
            Verdict::Accepted(Accepted::Correct {
                refresh_tangent: true,
                factor: true
            })
        );
        assert_eq!(s.pass(), Pass::KeepingHistories);
        // A fresh factorisation is never given up for the old one.
        assert!(matches!(
            s.judge(2, 1e-7),
            Verdict::Accepted(Accepted::Correct { factor: true, .. })
        ));

        // r0 = 0.1: 0.1·(1e-3)² = 1e-7 > tol, so the tangent at the first corrected iterate.
        let mut f = Newton::new(true, Some(1e-3), tol);
        assert_eq!(f.judge(0, 0.1), reuse);
        assert_eq!(f.pass(), Pass::Tangent);

        // A carried rate above MAX_REUSE_RATE never continues a chain; at most MAX_REUSES
        // corrections with the old factorisation.
        let mut m = Newton::new(true, Some(0.5), 1.0);
        m.judge(0, 4.0);
        assert_eq!(m.pass(), Pass::Tangent);
        // Residuals 1e16, 1e8, 1e4, 100, 10 to a tolerance of 1: each rate ≤ 0.1 and each
        // r·rate ≤ 1, so only the count stops the chain.
        let mut k = Newton::new(true, Some(1e-8), 1.0);
        for (it, r) in [1e16, 1e8, 1e4, 100.0].into_iter().enumerate() {
            assert_eq!(k.judge(it, r), reuse, "iteration {it}");
        }
        assert_eq!(MAX_REUSES, 4);
        assert!(matches!(
            k.judge(4, 10.0),
            Verdict::Accepted(Accepted::Correct { factor: true, .. })
        ));
    }
}
