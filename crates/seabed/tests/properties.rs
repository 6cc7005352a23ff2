//! Property tests over random displacement histories (proptest; failing seeds are kept in
//! `proptest-regressions/`):
//! - no NaN or infinity, ever;
//! - `P` within `[−fsuc·Pu(z), Pu(z_max)]` (1e-9 relative slack for rounding);
//! - a trial never changes committed state, and the same trial twice gives the same answer;
//! - the same path walked with coarse (D/200) and fine (D/20000) steps gives the same `P` at the
//!   waypoints (relative 1e-6 of `Pu(z_max)`).

use catena_seabed::rq::{RandolphQuiggin, RqHistory, RqParams};
use proptest::prelude::*;

fn params() -> impl Strategy<Value = RqParams> {
    (
        0.0f64..5000.0,
        0.0f64..6000.0,
        0.15f64..0.35,
        100.0f64..400.0,
        0.0f64..=1.0,
        0.2f64..2.0,
        0.0f64..0.5,
        any::<bool>(),
    )
        .prop_map(
            |(su0, grad, b, k_max, f_suc, lambda_suc, lambda_rep, smooth)| RqParams {
                diameter: 0.2,
                su0: su0 + 100.0,
                su_gradient: grad,
                a: 6.0,
                b,
                k_max,
                f_suc,
                lambda_suc,
                lambda_rep,
                liftoff_smoothing: smooth,
                degradation: None,
                rate_suction: None,
            },
        )
}

/// Waypoints as fractions of D, in [−0.2, 1.5].
fn path() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-0.2f64..1.5, 2..8)
}

fn walk(
    l: &RandolphQuiggin,
    h: &mut RqHistory,
    to: f64,
    step: f64,
    mut each: impl FnMut(&RqHistory, f64),
) {
    let from = h.z_prev;
    let n = ((to - from).abs() / step).ceil().max(1.0) as usize;
    for k in 1..=n {
        let z = if k == n {
            to
        } else {
            from + (to - from) * k as f64 / n as f64
        };
        each(h, z);
        *h = l.evaluate(h, z).next;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn bounded_pure_and_finite(p in params(), fracs in path()) {
        let l = RandolphQuiggin::new(p).expect("valid");
        let d = p.diameter;
        let mut h = RqHistory::untouched(0.0);
        let mut failure: Option<String> = None;
        for f in fracs {
            walk(&l, &mut h, f * d, d / 300.0, |h, z| {
                if failure.is_some() {
                    return;
                }
                let before = *h;
                let t = l.evaluate(h, z);
                let again = l.evaluate(h, z);
                let z_max = h.z_max.max(z);
                let lo = -p.f_suc * l.pu(z).0;
                let hi = l.pu(z_max).0;
                let slack = 1e-9 * hi.max(1.0);
                if !(t.p.is_finite() && t.tangent.is_finite()) {
                    failure = Some(format!("non-finite at z = {z}: {t:?}"));
                } else if t.p < lo - slack || t.p > hi + slack {
                    failure = Some(format!("P = {} outside [{lo}, {hi}] at z = {z}", t.p));
                } else if *h != before || t != again {
                    failure = Some(format!("trial not pure at z = {z}"));
                }
            });
        }
        prop_assert!(failure.is_none(), "{}", failure.unwrap_or_default());
    }

    #[test]
    fn coarse_and_fine_steps_agree_at_waypoints(p in params(), fracs in path()) {
        let l = RandolphQuiggin::new(p).expect("valid");
        let d = p.diameter;
        let mut fine = RqHistory::untouched(0.0);
        let mut coarse = RqHistory::untouched(0.0);
        for f in fracs {
            walk(&l, &mut fine, f * d, d / 20000.0, |_, _| {});
            walk(&l, &mut coarse, f * d, d / 200.0, |_, _| {});
            let scale = l.pu(fine.z_max.max(0.01 * d)).0;
            prop_assert!(
                (fine.p_prev - coarse.p_prev).abs() <= 1e-6 * scale,
                "at z = {}: fine {} coarse {}", f * d, fine.p_prev, coarse.p_prev
            );
            prop_assert_eq!(fine.mode, coarse.mode);
        }
    }
}
