//! Newton's method for one time step, apart from the integrator ([`crate::integrator`]) and the
//! stepping ([`crate::dynamics`]): what each iteration evaluates (the lazy tangent with the reuse
//! of the last factorisation), backtracking, the divergence and convergence tests, the rounding
//! floor of the residual and the worst node of a failed attempt. [`Newton`] is the attempt's
//! bookkeeping; the caller evaluates the forces and solves.
//!
//! **Lazy tangent, factorisation reuse.** The first iteration of a step reuses the Jacobian
//! factorised last when it was for the same Δt (a modified-Newton start: one factorisation per step
//! instead of two). After a correction with a fresh factorisation Newton is quadratic and the next
//! residual nearly always converges: it is evaluated without the tangent (keeping each node's trial
//! seabed history for the commit, [`Pass::KeepingHistories`]), and the tangent is assembled at that
//! iterate only if it does not converge. The converged answer is the same to the bit: the residual
//! and the tangent do not depend on each other.
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

/// One attempt's Newton bookkeeping.
#[derive(Debug, Clone, Copy)]
pub struct Newton {
    /// The last factorisation is for this attempt's Δt (the first iteration may reuse it).
    reusable: bool,
    after_fresh: bool,
    r_prev: f64,
    lambda: f64,
    backtracks: u32,
    first: f64,
    last: (usize, f64),
}

impl Newton {
    /// A new attempt; `reusable` when the last factorisation is for its Δt.
    pub fn new(reusable: bool) -> Self {
        Self {
            reusable,
            after_fresh: false,
            r_prev: f64::INFINITY,
            lambda: 1.0,
            backtracks: 0,
            first: f64::INFINITY,
            last: (0, f64::INFINITY),
        }
    }

    /// Whether iteration `it` reuses the last factorisation.
    fn reuse(&self, it: usize) -> bool {
        it == 0 && self.reusable
    }

    /// What iteration `it` evaluates.
    pub fn pass(&self, it: usize) -> Pass {
        let lazy = self.reuse(it) || self.after_fresh;
        match (lazy, self.after_fresh) {
            (false, _) => Pass::Tangent,
            (true, true) => Pass::KeepingHistories,
            (true, false) => Pass::Forces,
        }
    }

    /// Judges iteration `it`'s relative residual `r` against the tolerance `tol` (the floor
    /// included).
    pub fn judge(&mut self, it: usize, r: f64, tol: f64) -> Verdict {
        if r.is_finite() && r > self.r_prev && self.backtracks < MAX_BACKTRACKS {
            // u = u₀ − λ·dq → u₀ − (λ/2)·dq: add back λ/2 of it.
            self.lambda *= 0.5;
            self.backtracks += 1;
            return Verdict::Backtrack { back: self.lambda };
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
        if r <= tol {
            return Verdict::Accepted(Accepted::Converged);
        }
        let reuse = self.reuse(it);
        let correct = Accepted::Correct {
            refresh_tangent: self.after_fresh && !reuse,
            factor: !reuse,
        };
        self.after_fresh = !reuse;
        Verdict::Accepted(correct)
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

/// `(iteration, residual)` of the last accepted iterate and the node of the largest entry of its
/// residual on the free equations, `g` (the first of equal ones).
pub fn worst_node(model: &LineModel, (it, r): (usize, f64), g: &[f64]) -> (usize, f64, usize) {
    let mut eq = 0;
    let mut big = 0.0;
    for (e, x) in g.iter().enumerate() {
        if x.abs() > big {
            (big, eq) = (x.abs(), e);
        }
    }
    let node = model
        .equation
        .iter()
        .position(|e| *e == Some(eq))
        .map_or(0, |g| g / 3);
    (it, r, node)
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
    // The largest |x| and |z| in eight partial maxima, four nodes at a time (the same value as
    // one running maximum, without its chain of dependent comparisons).
    let mut acc = [0.0f64; 8];
    let nodes = u.chunks_exact(12);
    let rest = nodes.remainder();
    for c in nodes {
        for k in 0..4 {
            acc[2 * k] = acc[2 * k].max(c[3 * k].abs());
            acc[2 * k + 1] = acc[2 * k + 1].max(c[3 * k + 1].abs());
        }
    }
    let big = rest
        .chunks_exact(3)
        .fold(max_abs(&acc), |m, c| m.max(c[0].abs()).max(c[1].abs()));
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
    /// for no factorisation; after a fresh one the next pass keeps histories; a rising residual is
    /// backtracked three times at most (½, ¼, ⅛ of the correction added back), then accepted; a
    /// residual 10⁴ times the first from the third iteration diverges.
    #[test]
    fn the_bookkeeping_of_an_attempt() {
        let mut n = Newton::new(true);
        assert_eq!(n.pass(0), Pass::Forces);
        let v = n.judge(0, 1.0, 1e-9);
        assert_eq!(
            v,
            Verdict::Accepted(Accepted::Correct {
                refresh_tangent: false,
                factor: false
            })
        );
        assert_eq!(n.pass(1), Pass::Tangent);
        assert!(matches!(
            n.judge(1, 0.5, 1e-9),
            Verdict::Accepted(Accepted::Correct { factor: true, .. })
        ));
        assert_eq!(n.pass(2), Pass::KeepingHistories);
        for back in [0.5, 0.25, 0.125] {
            assert_eq!(n.judge(2, 0.9, 1e-9), Verdict::Backtrack { back });
        }
        assert!(matches!(
            n.judge(2, 0.9, 1e-9),
            Verdict::Accepted(Accepted::Correct {
                refresh_tangent: true,
                factor: true
            })
        ));
        assert_eq!(n.last(), (2, 0.9));
        let mut d = Newton::new(false);
        d.judge(0, 1.0, 1e-9);
        d.judge(1, 0.5, 1e-9);
        assert_eq!(
            d.judge(2, f64::NAN, 1e-9),
            Verdict::Accepted(Accepted::Diverged)
        );
        assert_eq!(
            Newton::new(false).judge(0, 1e-10, 1e-9),
            Verdict::Accepted(Accepted::Converged)
        );
    }
}
