//! Suction that depends on the uplift's rate (`RqParams::rate_suction`): the limits (very slow,
//! very fast) are the drained and undrained laws, half-way at V50; the tangent of a rate-dependent
//! uplift matches a finite difference.

use catena_seabed::rq::{Branch, RandolphQuiggin, RqHistory, RqParams};
use catena_seabed::{OnsetMemo, RateSuction};

const RATE: RateSuction = RateSuction {
    drained_ratio: 0.1,
    cv: 1e-7,
    v50: 10.0,
    exponent: 1.5,
};

/// Penetration to 0.5 D, then an uplift at a steady velocity `v` (m/s) to `to`, each step's trial
/// given its rate; returns the history.
fn cycle(l: &RandolphQuiggin, v: f64, to: f64) -> RqHistory {
    let d = l.params().diameter;
    let mut memo = OnsetMemo::default();
    let mut h = RqHistory::untouched(0.0);
    let n = 500;
    for k in 1..=n {
        h = l
            .evaluate_rate(&h, 0.5 * d * k as f64 / n as f64, 1e-3, &mut memo)
            .next;
    }
    for k in 1..=n {
        let z = 0.5 * d + (to - 0.5 * d) * k as f64 / n as f64;
        h = l.evaluate_rate(&h, z, -v, &mut memo).next;
    }
    h
}

/// The same path on the law with a fixed suction ratio `f`.
fn fixed(p: RqParams, f: f64, to: f64) -> RqHistory {
    let l = RandolphQuiggin::new(RqParams {
        f_suc: f,
        rate_suction: None,
        ..p
    })
    .expect("valid");
    cycle(&l, 0.0, to)
}

/// Very slow uplift (V = 10⁻⁶ V50) is the drained law, very fast (V = 10⁶ V50) the undrained one,
/// and V = V50 the law half-way between, to 1e-6 of Pu (the ratio's distance from its limit at
/// those rates is below 1e-9), deep in suction (0.2 D, past the onset and onto the decaying floor)
/// and through lift-off to a re-contact.
#[test]
fn the_limits_are_the_drained_and_undrained_laws() {
    let p = RqParams {
        rate_suction: Some(RATE),
        ..RqParams::table1()
    };
    let l = RandolphQuiggin::new(p).expect("valid");
    let d = p.diameter;
    let v_of = |big_v: f64| big_v * RATE.cv / d;
    let pu = l.pu(0.2 * d).0;
    for (big_v, f) in [
        (1e-6 * RATE.v50, RATE.drained_ratio),
        (1e6 * RATE.v50, p.f_suc),
        (RATE.v50, 0.5 * (RATE.drained_ratio + p.f_suc)),
    ] {
        let got = cycle(&l, v_of(big_v), 0.2 * d);
        let want = fixed(p, f, 0.2 * d);
        assert!(
            (got.p_prev - want.p_prev).abs() < 1e-6 * pu,
            "V/V50 = {}: P {} against {} (f = {f})",
            big_v / RATE.v50,
            got.p_prev,
            want.p_prev
        );
        assert!(got.p_prev < 0.0, "in suction: {}", got.p_prev);
        // Lifted off: the suction onset recorded is the same law's.
        let (got, want) = (cycle(&l, v_of(big_v), -0.01 * d), fixed(p, f, -0.01 * d));
        assert!(
            (got.z_p0 - want.z_p0).abs() < 1e-9 * d,
            "{} {}",
            got.z_p0,
            want.z_p0
        );
    }
    // And the fast law's suction is the deeper one.
    assert!(
        cycle(&l, v_of(1e6 * RATE.v50), 0.2 * d).p_prev
            < cycle(&l, v_of(1e-6 * RATE.v50), 0.2 * d).p_prev
    );
}

/// Within a step the suction ratio is the committed velocity's, so a rate-dependent uplift's
/// tangent is the law's: against a central difference on the uplift and suction-floor branches.
#[test]
fn a_rate_dependent_uplift_has_the_laws_tangent() {
    let p = RqParams {
        rate_suction: Some(RATE),
        ..RqParams::table1()
    };
    let l = RandolphQuiggin::new(p).expect("valid");
    let d = p.diameter;
    let v = RATE.v50 * RATE.cv / d;
    for (to, at, want) in [
        (0.49 * d, 0.485 * d, Branch::Uplift),
        (0.2 * d, 0.19 * d, Branch::SuctionFloor),
    ] {
        let h = cycle(&l, v, to);
        let step = 1e-7 * d;
        let mut memo = OnsetMemo::default();
        let t = l.evaluate_rate(&h, at, -v, &mut memo);
        assert_eq!(t.branch, want);
        let tp = l.evaluate_rate(&h, at + step, -v, &mut memo);
        let tm = l.evaluate_rate(&h, at - step, -v, &mut memo);
        let fd = (tp.p - tm.p) / (2.0 * step);
        let scale = p.k_max * l.pu(at).0 / d;
        assert!(
            (fd - t.tangent).abs() <= 1e-5 * t.tangent.abs() + 1e-9 * scale,
            "{want:?}: analytic {} FD {fd}",
            t.tangent
        );
    }
}

/// A drained ratio above the undrained one is refused, naming the key.
#[test]
fn a_drained_ratio_above_the_undrained_is_refused() {
    let p = RqParams {
        rate_suction: Some(RateSuction {
            drained_ratio: 0.9,
            ..RATE
        }),
        ..RqParams::table1()
    };
    assert_eq!(
        RandolphQuiggin::new(p).expect_err("f_dr > f_suc").key,
        "rate_suction.drained_ratio"
    );
}
