//! Cyclic degradation and regain at rest, options of the Randolph–Quiggin law
//! (`catena_seabed::degradation`): an element test against the published form's closed solution,
//! regain after a rest, finite-difference tangents on every branch of degraded soil, and the
//! zero-motion check.

use catena_seabed::rq::{Branch, Mode, RandolphQuiggin, RqHistory, RqParams};
use catena_seabed::{Degradation, Regain};

const SOIL: Degradation = Degradation {
    sensitivity: 3.0,
    ductility: 8.0,
    regain: Some(Regain {
        t50: 7200.0,
        exponent: 1.0,
    }),
};

fn walk(l: &RandolphQuiggin, h: &mut RqHistory, to: f64, steps: usize) {
    let from = h.z_prev;
    for k in 1..=steps {
        *h = l
            .evaluate(h, from + (to - from) * k as f64 / steps as f64)
            .next;
    }
}

/// A displacement-controlled cyclic test between `z_b` = 0.5 D and `z_t` = 0.3 D on a very stiff
/// soil (Kmax = 10⁵, λrep = 0), where nearly all travel is plastic: the resistance at the bottom
/// of repenetration n is `δ(ξ_n)·Pu(z_b)` with `ξ_n = (z_b + (2n − 1)(z_b − z_t))/D` the travel so
/// far, the closed solution of Einav & Randolph's form (tolerance 2e-3 of Pu: the hyperbolae's
/// approach to Pu at Kmax = 10⁵ and the elastic part of each reversal). Without the option the same
/// test keeps the intact resistance.
#[test]
fn cyclic_test_follows_the_closed_solution() {
    let p = RqParams {
        k_max: 1e5,
        lambda_rep: 0.0,
        degradation: Some(SOIL),
        ..RqParams::table1()
    };
    let d = p.diameter;
    let (zb, zt) = (0.5 * d, 0.3 * d);
    for degrading in [true, false] {
        let l = RandolphQuiggin::new(RqParams {
            degradation: degrading.then_some(SOIL),
            ..p
        })
        .expect("valid");
        let pu = l.pu(zb).0;
        let mut h = RqHistory::untouched(0.0);
        walk(&l, &mut h, zb, 400);
        let mut checked = 0;
        for n in 1..=12 {
            walk(&l, &mut h, zt, 200);
            walk(&l, &mut h, zb, 200);
            let xi = (zb + (2 * n - 1) as f64 * (zb - zt)) / d;
            let want = if degrading { SOIL.strength(xi) } else { 1.0 };
            let got = h.p_prev / pu;
            assert!(
                (got - want).abs() < 2e-3,
                "cycle {n}: P/Pu = {got}, δ(ξ = {xi}) = {want}"
            );
            checked += 1;
        }
        assert_eq!(checked, 12);
        if degrading {
            // Twelve cycles take the soil most of the way to remoulded (δ_rem = 1/3).
            assert!(h.p_prev / pu < 0.45, "{}", h.p_prev / pu);
        }
    }
}

/// A rest of t50 after the uplift of the sixth cycle: the next repenetration finds half the lost
/// strength regained (`δ' = 1 − (1 − δ)/2`), to the same tolerance; a rest without the regain
/// option changes nothing.
#[test]
fn a_rest_regains_half_the_loss_at_t50() {
    let p = RqParams {
        k_max: 1e5,
        lambda_rep: 0.0,
        degradation: Some(SOIL),
        ..RqParams::table1()
    };
    let d = p.diameter;
    let (zb, zt) = (0.5 * d, 0.3 * d);
    let l = RandolphQuiggin::new(p).expect("valid");
    let pu = l.pu(zb).0;
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, zb, 400);
    for _ in 0..5 {
        walk(&l, &mut h, zt, 200);
        walk(&l, &mut h, zb, 200);
    }
    walk(&l, &mut h, zt, 200);
    let xi = (zb + 11.0 * (zb - zt)) / d;
    let rested = l.rest(&h, 7200.0);
    assert!(rested.wear.xi < h.wear.xi);
    let mut after = rested;
    walk(&l, &mut after, zb, 200);
    let want = 1.0 - 0.5 * (1.0 - SOIL.strength(xi));
    assert!(
        (after.p_prev / pu - want).abs() < 2e-3,
        "after the rest P/Pu = {}, want {want}",
        after.p_prev / pu
    );
    let unrested = RandolphQuiggin::new(RqParams {
        degradation: Some(Degradation {
            regain: None,
            ..SOIL
        }),
        ..p
    })
    .expect("valid");
    assert_eq!(unrested.rest(&h, 7200.0), h);
}

/// Every branch of degraded soil (strength factor about 0.6) against a central finite difference,
/// to the tolerance of `tangents.rs`: within an episode the strength is fixed, so the law's
/// tangent is exact.
#[test]
fn degraded_tangents_match_finite_differences() {
    let p = RqParams {
        degradation: Some(SOIL),
        ..RqParams::table1()
    };
    let d = p.diameter;
    let l = RandolphQuiggin::new(p).expect("valid");
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.5 * d, 500);
    for _ in 0..4 {
        walk(&l, &mut h, 0.2 * d, 300);
        walk(&l, &mut h, 0.5 * d, 300);
    }
    // The next episode's strength.
    let delta = SOIL.strength(h.wear.xi);
    assert!(delta < 0.8, "δ = {delta}");
    let check = |h: &RqHistory, z: f64, want: Branch| {
        let step = 1e-7 * d;
        let t = l.evaluate(h, z);
        assert_eq!(t.branch, want, "at z = {z}");
        let (tp, tm) = (l.evaluate(h, z + step), l.evaluate(h, z - step));
        assert_eq!((tp.branch, tm.branch), (want, want), "at z = {z}");
        let fd = (tp.p - tm.p) / (2.0 * step);
        let scale = p.k_max * l.pu(z).0 / d;
        assert!(
            (fd - t.tangent).abs() <= 1e-5 * t.tangent.abs() + 1e-9 * scale,
            "{want:?} at {z}: analytic {} FD {fd}",
            t.tangent
        );
    };
    // Uplift from the bottom of the cycle: the new episode takes the degraded strength.
    walk(&l, &mut h, 0.499 * d, 2);
    assert_eq!(h.mode, Mode::Uplift);
    assert!((h.wear.strength - delta).abs() < 1e-15);
    check(&h, 0.49 * d, Branch::Uplift);
    walk(&l, &mut h, 0.15 * d, 300);
    check(&h, 0.12 * d, Branch::SuctionFloor);
    check(&h, h.z_prev + 1e-4 * d, Branch::Repenetration);
    walk(&l, &mut h, -0.01 * d, 100);
    check(&h, 0.05 * d, Branch::RepenetrationCap);
    walk(&l, &mut h, 0.6 * d, 600);
    let b = l.evaluate(&h, 0.7 * d).branch;
    assert!(
        matches!(b, Branch::Repenetration | Branch::RepenetrationCap),
        "{b:?}"
    );
    check(&h, 0.7 * d, b);
}

/// Zero motion: a node held at its penetration accumulates no plastic displacement and keeps its
/// force, step after step, on degraded soil.
#[test]
fn zero_motion_changes_nothing() {
    let p = RqParams {
        degradation: Some(SOIL),
        ..RqParams::table1()
    };
    let d = p.diameter;
    let l = RandolphQuiggin::new(p).expect("valid");
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.4 * d, 400);
    walk(&l, &mut h, 0.3 * d, 100);
    let before = h;
    for _ in 0..50 {
        h = l.evaluate(&h, h.z_prev).next;
    }
    assert_eq!(h.wear, before.wear);
    assert_eq!(h.p_prev.to_bits(), before.p_prev.to_bits());
}

/// Reversals much smaller than the law's elastic length `D/Kmax` (1.75 mm for Table 1) are nearly
/// elastic: a thousand cycles of ±3.5 µm at half a diameter add less than 5 % of their travel to the
/// accumulated plastic displacement, while travel on the backbone counts nearly in full (within 5 %).
#[test]
fn small_reversals_are_elastic_and_the_backbone_is_plastic() {
    let p = RqParams {
        degradation: Some(SOIL),
        ..RqParams::table1()
    };
    let d = p.diameter;
    let l = RandolphQuiggin::new(p).expect("valid");
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.5 * d, 500);
    // The backbone's travel: 0.5 D less its elastic part (the increments of P over the reversal
    // stiffness Kmax·Pu/D: about 3 D/Kmax here).
    assert!(
        h.wear.xi < 0.5 && h.wear.xi > 0.95 * 0.5,
        "ξ on the backbone {}",
        h.wear.xi
    );
    let xi0 = h.wear.xi;
    let a = 1e-5 * d;
    for _ in 0..1000 {
        walk(&l, &mut h, 0.5 * d - a, 1);
        walk(&l, &mut h, 0.5 * d, 1);
    }
    let travel = 2000.0 * a / d;
    assert!(
        h.wear.xi - xi0 < 0.05 * travel,
        "ξ grew by {} over a travel of {travel} D",
        h.wear.xi - xi0
    );
}
