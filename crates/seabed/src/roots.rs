//! The root finders every scan and bisection of catena shares (issue 14: a hand-written bisection
//! that could stop making progress hung a run). Each one ends: [`bisect`] stops after 200 halvings
//! or when the midpoint is one of the ends (the bracket is two neighbouring numbers);
//! [`bracketed_root`] shrinks its bracket at every iteration.

/// Bisects `[lo, hi]`, where `upper(lo)` is false and `upper(hi)` is true (`upper(x)`: "the root
/// is at or below `x`"), to two neighbouring numbers or 200 halvings; returns the final bracket.
pub fn bisect(mut lo: f64, mut hi: f64, mut upper: impl FnMut(f64) -> bool) -> (f64, f64) {
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if m <= lo || m >= hi {
            break;
        }
        if upper(m) {
            hi = m;
        } else {
            lo = m;
        }
    }
    (lo, hi)
}

/// The root of `f` in `[lo, hi]` given `f(lo) ≤ 0 < f(hi)`, to machine precision: the smallest
/// `x` found with `f(x) > 0` whose lower neighbour in the bracket has `f ≤ 0`. `f` returns the value
/// and its derivative. Newton's step is taken when it stays inside the bracket and at least halves
/// it, else bisection; a converged iterate is nudged by one unit in the last place towards the other
/// end, so the bracket closes on two neighbouring numbers in a few evaluations (about 6 against
/// bisection's 50). Every iteration shrinks the bracket, so it always ends.
pub fn bracketed_root(f: impl Fn(f64) -> (f64, f64), lo: f64, hi: f64) -> f64 {
    let (mut a, mut b) = (lo, hi);
    let mut x = 0.5 * (a + b);
    for _ in 0..400 {
        if x <= a || x >= b {
            break;
        }
        let (fx, dfx) = f(x);
        if fx <= 0.0 {
            a = x;
        } else {
            b = x;
        }
        let newton = x - fx / dfx;
        x = if newton > a && newton < b && (newton - x).abs() <= 0.5 * (b - a) {
            newton
        } else {
            0.5 * (a + b)
        };
        if x <= a {
            x = a.next_up();
        } else if x >= b {
            x = b.next_down();
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisect_ends_on_neighbours_and_on_flat_functions() {
        let (lo, hi) = bisect(0.0, 2.0, |x| x * x >= 2.0);
        assert!(lo * lo < 2.0 && hi * hi >= 2.0 && hi - lo <= 2.0 * f64::EPSILON * 2.0);
        // A predicate that never changes still ends (at the bracket's end).
        let (lo, hi) = bisect(0.0, 1.0, |_| false);
        assert!(hi == 1.0 && lo < 1.0);
    }
}
