//! Every branch's analytic tangent against a central finite difference, and the zero-motion checks.
//!
//! Tolerance: |analytic − FD| ≤ 1e-5·|analytic| + 1e-6·Kmax·Pu(z)/D·1e-3, with the difference step
//! 1e-7·D, at points chosen away from branch switches (a switch within ±step would be a kink).

use catena_seabed::buoyancy::SoilBuoyancy;
use catena_seabed::law::{Law, Seabed};
use catena_seabed::linear::LinearSeabed;
use catena_seabed::rq::{Branch, RandolphQuiggin, RqHistory, RqParams};

fn walk(l: &RandolphQuiggin, h: &mut RqHistory, to: f64, step: f64) {
    let from = h.z_prev;
    let n = ((to - from).abs() / step).ceil().max(1.0) as usize;
    for k in 1..=n {
        let z = from + (to - from) * k as f64 / n as f64;
        *h = l.evaluate(h, z).next;
    }
}

fn check_fd(l: &RandolphQuiggin, h: &RqHistory, z: f64, want: Branch) {
    let d = l.params().diameter;
    let step = 1e-7 * d;
    let t = l.evaluate(h, z);
    assert_eq!(t.branch, want, "at z = {z}");
    let tp = l.evaluate(h, z + step);
    let tm = l.evaluate(h, z - step);
    assert_eq!(tp.branch, want, "z+ at {z}");
    assert_eq!(tm.branch, want, "z- at {z}");
    let fd = (tp.p - tm.p) / (2.0 * step);
    let scale = l.params().k_max * l.pu(z).0 / d;
    assert!(
        (fd - t.tangent).abs() <= 1e-5 * t.tangent.abs() + 1e-9 * scale,
        "{want:?} at z = {z}: analytic {} FD {fd}",
        t.tangent
    );
}

#[test]
fn tangent_backbone_both_nc_branches() {
    let l = RandolphQuiggin::new(RqParams::table1()).expect("valid");
    let h = RqHistory::untouched(0.0);
    for zd in [0.003, 0.05, 0.09, 0.11, 0.5, 1.5] {
        check_fd(&l, &h, zd * 0.35, Branch::Backbone);
    }
}

#[test]
fn tangent_uplift_floor_repenetration_cap() {
    let p = RqParams::table1();
    let l = RandolphQuiggin::new(p).expect("valid");
    let d = p.diameter;
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.5 * d, d / 1000.0);
    // Uplift (eq. 5), on both sides of z_c.
    check_fd(&l, &h, 0.49 * d, Branch::Uplift);
    check_fd(&l, &h, 0.45 * d, Branch::Uplift);
    // Walk deep into suction, past z_c, to the decaying floor.
    walk(&l, &mut h, 0.2 * d, d / 1000.0);
    check_fd(&l, &h, 0.15 * d, Branch::SuctionFloor);
    // Repenetration (eq. 10) from the suction state, just after the reversal.
    check_fd(&l, &h, h.z_prev + 1e-4 * d, Branch::Repenetration);
    // Lift off, then re-contact: the cap E_RP·P_IP.
    walk(&l, &mut h, -0.01 * d, d / 1000.0);
    check_fd(&l, &h, 0.12 * d, Branch::RepenetrationCap);
    check_fd(&l, &h, 0.05 * d, Branch::RepenetrationCap);
    check_fd(&l, &h, 0.3 * d, Branch::RepenetrationCap);
    // Past the old z_max (the exponent's denominator then moves with z).
    walk(&l, &mut h, 0.52 * d, d / 1000.0);
    let b = branch_at(&l, &h, 0.6 * d);
    assert!(
        matches!(b, Branch::Repenetration | Branch::RepenetrationCap),
        "{b:?}"
    );
    check_fd(&l, &h, 0.6 * d, b);
}

fn branch_at(l: &RandolphQuiggin, h: &RqHistory, z: f64) -> Branch {
    l.evaluate(h, z).branch
}

#[test]
fn tangent_continuity_guard_hold() {
    // λrep·λsuc > 1 reaches the guard: P is held at P0 with zero tangent.
    let p = RqParams {
        lambda_suc: 4.0,
        lambda_rep: 0.5,
        ..RqParams::table1()
    };
    let l = RandolphQuiggin::new(p).expect("valid");
    let d = p.diameter;
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.5 * d, d / 1000.0);
    // A small uplift that stays in compression (so z_P0 stays 0), then repenetration.
    walk(&l, &mut h, 0.499 * d, d / 10000.0);
    walk(&l, &mut h, 0.4995 * d, d / 10000.0);
    assert_eq!(h.z_p0, 0.0);
    let t = l.evaluate(&h, 0.4997 * d);
    assert_eq!(t.branch, Branch::RepenetrationHold);
    assert_eq!(t.tangent, 0.0);
    assert_eq!(t.p, h.p0);
}

#[test]
fn tangent_liftoff_smoothing() {
    let p = RqParams {
        liftoff_smoothing: true,
        f_suc: 0.0,
        ..RqParams::table1()
    };
    let l = RandolphQuiggin::new(p).expect("valid");
    let d = p.diameter;
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.05 * d, d / 1000.0);
    walk(&l, &mut h, 0.01 * d, d / 1000.0);
    check_fd(&l, &h, 0.0003 * d, Branch::LiftoffSmoothing);
    // With smoothing, P tends to zero at the mudline (no jump at lift-off).
    let t = l.evaluate(&h, 1e-9 * d);
    assert!(
        t.p.abs() < 1e-6 * l.pu(0.05 * d).0,
        "P at the mudline {}",
        t.p
    );
    // Without it, the literal eq. 5 leaves a small positive force there.
    let l0 = RandolphQuiggin::new(RqParams {
        liftoff_smoothing: false,
        ..p
    })
    .expect("valid");
    let mut h0 = RqHistory::untouched(0.0);
    walk(&l0, &mut h0, 0.05 * d, d / 1000.0);
    walk(&l0, &mut h0, 0.01 * d, d / 1000.0);
    // Just above the lift-off band, the literal eq. 5 leaves a clear positive force …
    let band = catena_seabed::rq::LIFTOFF_BAND * d / p.k_max;
    let jump = l0.evaluate(&h0, 2.0 * band).p / l0.pu(0.05 * d).0;
    assert!(
        jump > 0.005,
        "the literal eq. 5 force near lift-off: {jump}"
    );
    // … which the band takes linearly to zero at the mudline (continuous, tangent exact inside).
    let inside = l0.evaluate(&h0, 1e-3 * band).p / l0.pu(0.05 * d).0;
    assert!(
        inside.abs() < 1e-3 * jump + 1e-12,
        "P inside the band {inside}"
    );
    check_fd(&l0, &h0, 0.5 * band, Branch::Uplift);
    let near = l0.evaluate(&h0, band * (1.0 + 1e-9)).p;
    let at = l0.evaluate(&h0, band * (1.0 - 1e-9)).p;
    assert!(
        (near - at).abs() < 1e-6 * near.abs(),
        "{near} vs {at} across the band's edge"
    );
}

#[test]
fn linear_and_buoyancy_tangents_and_zero_motion() {
    let lin = LinearSeabed::new(0.228, 100e3, 0.0).expect("valid");
    let b = SoilBuoyancy::new(0.228, 1.5, 1500.0, 1025.0).expect("valid");
    let s = Seabed {
        law: Law::Linear(lin),
        buoyancy: Some(b),
    };
    for z in [0.01, 0.05, 0.11, 0.2, 0.3] {
        let h = 1e-7;
        let t = s.backbone(z);
        let fd = (s.backbone(z + h).total() - s.backbone(z - h).total()) / (2.0 * h);
        assert!(
            (fd - t.tangent).abs() < 1e-5 * t.tangent.abs(),
            "{z}: {fd} {}",
            t.tangent
        );
    }
    // Zero motion: no penetration, no force, no tangent.
    for z in [0.0, -0.1] {
        let t = s.backbone(z);
        assert_eq!((t.resistance, t.buoyancy, t.tangent), (0.0, 0.0, 0.0));
    }
    // Full immersion: the displaced area is the whole circle.
    let (a, da) = b.displaced_area(0.5);
    assert!((a - std::f64::consts::PI * 0.228 * 0.228 / 4.0).abs() < 1e-15);
    assert_eq!(da, 0.0);
    // Half immersion: half the circle.
    let (a, _) = b.displaced_area(0.114);
    assert!((a - std::f64::consts::PI * 0.228 * 0.228 / 8.0).abs() < 1e-15);
}

/// Zero motion for the Randolph–Quiggin law: repeating the committed z returns the committed force,
/// mode and history, in every mode.
#[test]
fn rq_zero_motion_keeps_state() {
    let p = RqParams::table1();
    let l = RandolphQuiggin::new(p).expect("valid");
    let d = p.diameter;
    let mut h = RqHistory::untouched(0.0);
    for w in [0.3 * d, 0.2 * d, 0.25 * d, -0.1 * d, 0.1 * d] {
        walk(&l, &mut h, w, d / 500.0);
        let t = l.evaluate(&h, h.z_prev);
        assert_eq!(t.p, h.p_prev, "at {w}");
        assert_eq!(t.next.mode, h.mode, "at {w}");
        assert_eq!(t.next, h, "at {w}");
    }
}

/// Linear seabed damping: `c·D·ż` in contact, nothing out of contact; its derivative is `c·D`.
#[test]
fn linear_damping_force_and_derivative() {
    let lin = LinearSeabed::new(0.228, 100e3, 2e3).expect("valid");
    let (f, df) = lin.damping_force(0.01, 0.3);
    assert!((f - 2e3 * 0.228 * 0.3).abs() < 1e-12 && (df - 2e3 * 0.228).abs() < 1e-12);
    assert_eq!(lin.damping_force(-0.01, 0.3), (0.0, 0.0));
    assert_eq!(
        LinearSeabed::new(0.228, 100e3, 0.0)
            .expect("valid")
            .damping_force(0.01, 0.3),
        (0.0, 0.0)
    );
    assert!(LinearSeabed::new(0.228, 100e3, -1.0).is_err());
}
