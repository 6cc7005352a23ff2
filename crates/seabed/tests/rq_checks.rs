//! The public checks of `docs/seabed-model.md` ("Checks any implementation must pass") and
//! the numbers the paper states, each with its tolerance.

use catena_seabed::element_test::{self, Control, Leg, Target};
use catena_seabed::law::{Law, Seabed};
use catena_seabed::rq::{Branch, Mode, RandolphQuiggin, RqHistory, RqParams};

fn law(p: RqParams) -> RandolphQuiggin {
    RandolphQuiggin::new(p).expect("valid parameters")
}

fn walk(l: &RandolphQuiggin, h: &mut RqHistory, to: f64, step: f64) {
    let from = h.z_prev;
    let n = ((to - from).abs() / step).ceil().max(1.0) as usize;
    for k in 1..=n {
        let z = if k == n {
            to
        } else {
            from + (to - from) * k as f64 / n as f64
        };
        *h = l.evaluate(h, z).next;
    }
}

/// Table 2, monotonic penetration to z = 2D: P/D = 24.49 kPa (paper: 24.5 kPa). Tolerance 0.005 kPa.
#[test]
fn table2_pressure_at_two_diameters() {
    let l = law(RqParams::table2());
    let d = 0.025;
    let p = l.p_ip(2.0 * d).0;
    let p_over_d_kpa = p / d / 1000.0;
    assert!((p_over_d_kpa - 24.49).abs() < 0.005, "P/D = {p_over_d_kpa}");
}

/// Kmax = 200: secant stiffness (P/z)·D/Pu = 166.7, 100, 40 at z/D = 0.001, 0.005, 0.02 (to 0.05).
#[test]
fn secant_stiffness_kmax_200() {
    let l = law(RqParams::table1());
    let d = 0.35;
    for (zd, expect) in [(0.001, 166.667), (0.005, 100.0), (0.02, 40.0)] {
        let z = zd * d;
        let secant = l.p_ip(z).0 / z * d / l.pu(z).0;
        assert!((secant - expect).abs() < 0.05, "z/D {zd}: {secant}");
    }
}

/// Uplift stiffness at reversal = Kmax·Pu(z0)/D, analytically and by a one-sided difference
/// (relative tolerance 1e-9 analytic, 1e-4 difference).
#[test]
fn uplift_stiffness_at_reversal() {
    for p in [RqParams::table1(), RqParams::table2()] {
        let l = law(p);
        let d = p.diameter;
        let mut h = RqHistory::untouched(0.0);
        walk(&l, &mut h, 0.5 * d, d / 1000.0);
        let expect = p.k_max * l.pu(0.5 * d).0 / d;
        let dz = 1e-7 * d;
        let t = l.evaluate(&h, 0.5 * d - dz);
        assert_eq!(t.next.mode, Mode::Uplift);
        let t0 = l.evaluate(&h, 0.5 * d - 1e-15);
        assert!(
            (t0.tangent / expect - 1.0).abs() < 1e-6,
            "{} vs {expect}",
            t0.tangent
        );
        let fd = (h.p_prev - t.p) / dz;
        assert!((fd / expect - 1.0).abs() < 1e-4, "{fd} vs {expect}");
    }
}

/// Reload stiffness after an uplift that ended in suction (P0 ≤ 0) = Kmax·Pu(z)/D (relative 1e-6).
#[test]
fn reload_stiffness_after_suction() {
    let p = RqParams::table1();
    let l = law(p);
    let d = p.diameter;
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.5 * d, d / 1000.0);
    walk(&l, &mut h, 0.4 * d, d / 1000.0);
    assert!(
        h.p_prev < 0.0,
        "the uplift must reach suction: P = {}",
        h.p_prev
    );
    let z = h.z_prev + 1e-15;
    let t = l.evaluate(&h, z);
    assert_eq!(t.next.mode, Mode::Repenetration);
    let expect = p.k_max * l.pu(z).0 / d;
    assert!(
        (t.tangent / expect - 1.0).abs() < 1e-6,
        "{} vs {expect}",
        t.tangent
    );
}

/// Reload stiffness after an uplift still in compression (P0 > 0) = Kmax·Pu(z*)/D (relative 1e-6).
#[test]
fn reload_stiffness_after_partial_uplift() {
    let p = RqParams::table1();
    let l = law(p);
    let d = p.diameter;
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.5 * d, d / 1000.0);
    let z_star = h.z_prev;
    walk(&l, &mut h, 0.499 * d, d / 10000.0);
    assert!(h.p_prev > 0.0);
    let t = l.evaluate(&h, h.z_prev + 1e-15);
    let expect = p.k_max * l.pu(z_star).0 / d;
    assert!(
        (t.tangent / expect - 1.0).abs() < 1e-6,
        "{} vs {expect}",
        t.tangent
    );
}

fn figure3_path(d: f64) -> Vec<f64> {
    vec![
        0.5 * d,
        0.45 * d,
        0.55 * d,
        0.3 * d,
        0.6 * d,
        -0.05 * d,
        0.62 * d,
        0.5 * d,
        0.66 * d,
    ]
}

/// Step-size independence: the same path with steps D/50000 and D/500 gives the same P at the
/// waypoints (relative 1e-6 of Pu at the waypoint, the spec's tolerance).
#[test]
fn step_size_independence() {
    for p in [RqParams::table1(), RqParams::table2()] {
        let l = law(p);
        let d = p.diameter;
        let path = figure3_path(d);
        let mut fine = RqHistory::untouched(0.0);
        let mut coarse = RqHistory::untouched(0.0);
        for &w in &path {
            walk(&l, &mut fine, w, d / 50000.0);
            walk(&l, &mut coarse, w, d / 500.0);
            let scale = l.pu(w.max(0.01 * d)).0;
            assert!(
                (fine.p_prev - coarse.p_prev).abs() <= 1e-6 * scale,
                "at z = {w}: fine {} coarse {}",
                fine.p_prev,
                coarse.p_prev
            );
            assert_eq!(fine.mode, coarse.mode);
        }
    }
}

/// The path above visits every mode and every transition, including lift-off and re-contact.
#[test]
fn figure3_path_visits_every_mode_and_branch() {
    let p = RqParams::table1();
    let l = law(p);
    let d = p.diameter;
    let mut h = RqHistory::untouched(0.0);
    let mut modes = std::collections::HashSet::new();
    let mut branches = std::collections::HashSet::new();
    for &w in &figure3_path(d) {
        let from = h.z_prev;
        let n = ((w - from).abs() / (d / 2000.0)).ceil() as usize;
        for k in 1..=n {
            let z = from + (w - from) * k as f64 / n as f64;
            let t = l.evaluate(&h, z);
            modes.insert(t.next.mode);
            branches.insert(t.branch);
            h = t.next;
        }
    }
    for m in [
        Mode::NotInContact,
        Mode::InitialPenetration,
        Mode::Uplift,
        Mode::Repenetration,
    ] {
        assert!(modes.contains(&m), "mode {m:?} not visited");
    }
    for b in [
        Branch::NoContact,
        Branch::Backbone,
        Branch::Uplift,
        Branch::SuctionFloor,
        Branch::Repenetration,
        Branch::RepenetrationCap,
    ] {
        assert!(branches.contains(&b), "branch {b:?} not visited");
    }
    assert!(h.z_p0 > 0.0, "suction must have started: z_P0 = {}", h.z_p0);
}

/// After lift-off, re-contact follows `P = E_RP·P_IP(z)` and rejoins the backbone where the
/// exponent of `E_RP` reaches zero: `z = z_P0 + λrep·λsuc·z_max` if that is within `z_max`, else (the
/// denominator then being `λsuc·z`) `z = z_P0/(1 − λrep·λsuc)`. Relative 1e-12 on P; the rejoin point
/// to the scan's resolution, 0.6D/20000.
#[test]
fn recontact_is_concave_and_rejoins_backbone() {
    let p = RqParams::table1();
    let l = law(p);
    let d = p.diameter;
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, 0.5 * d, d / 2000.0);
    walk(&l, &mut h, -0.01 * d, d / 2000.0);
    assert_eq!(h.mode, Mode::NotInContact);
    let (z_p0, z_max) = (h.z_p0, h.z_max);
    assert!(z_p0 > 0.0 && z_p0 < z_max);
    let ll = p.lambda_rep * p.lambda_suc;
    let rejoin = if z_p0 + ll * z_max <= z_max {
        z_p0 + ll * z_max
    } else {
        z_p0 / (1.0 - ll)
    };
    for zf in [0.05, 0.2, 0.4] {
        let z = zf * d;
        let t = l.evaluate(&h, z);
        let e = ((z - z_p0) / (p.lambda_suc * z_max) - p.lambda_rep)
            .min(0.0)
            .exp();
        let expect = e * l.p_ip(z).0;
        assert!(
            (t.p / expect - 1.0).abs() < 1e-12,
            "z/D {zf}: {} vs {expect}",
            t.p
        );
    }
    // Walk down and find where the response meets the backbone.
    let mut met = None;
    let n = 20000;
    for k in 1..=n {
        let z = 0.6 * d * k as f64 / n as f64;
        let t = l.evaluate(&h, z);
        if (t.p - l.p_ip(z).0).abs() <= 1e-12 * l.pu(z).0 {
            met = Some(z);
            break;
        }
    }
    let met = met.expect("re-contact curve rejoins the backbone");
    assert!(
        (met - rejoin).abs() < 0.6 * d / n as f64 + 1e-12,
        "{met} vs {rejoin}"
    );
}

/// z_c is where eq. 5 crosses zero: P just below z_c is negative, just above it positive.
#[test]
fn suction_onset_is_the_first_root() {
    let p = RqParams::table1();
    let l = law(p);
    let d = p.diameter;
    let z0 = 0.5 * d;
    let p0 = l.p_ip(z0).0;
    let zc = l.suction_onset(z0, p0).expect("f_suc > 0 gives suction");
    assert!(zc < z0 && zc > 0.0);
    let mut h = RqHistory::untouched(0.0);
    walk(&l, &mut h, z0, d / 1000.0);
    let above = l.evaluate(&h, zc + 1e-9 * d);
    let below = l.evaluate(&h, zc - 1e-9 * d);
    assert!(above.p > 0.0 && below.p <= 0.0, "{} {}", above.p, below.p);
    // No suction at all with f_suc = 0.
    let l0 = law(RqParams { f_suc: 0.0, ..p });
    assert_eq!(l0.suction_onset(z0, p0), None);
}

/// Figure 4: monotonic penetration to 2.5D under displacement control follows the backbone exactly.
#[test]
fn figure4_monotonic_follows_backbone() {
    let rq = law(RqParams::table2());
    let d = 0.025;
    let seabed = Seabed {
        law: Law::RandolphQuiggin(rq),
        buoyancy: None,
    };
    let legs = element_test::legs_through(Control::Displacement, &[0.0, 2.5 * d], d / 1000.0);
    let r = element_test::run(&seabed, &legs).expect("runs");
    assert_eq!(r.rows.len(), 2501);
    for row in &r.rows[1..] {
        assert_eq!(row.mode, Mode::InitialPenetration);
        assert!((row.p - rq.p_ip(row.z).0).abs() <= 1e-12 * row.p.abs());
    }
}

/// Load control reaches each target force to 1e-9 N/m and commits one row per increment.
#[test]
fn load_control_hits_targets() {
    let d = 0.025;
    let seabed = Seabed {
        law: Law::RandolphQuiggin(law(RqParams::table2())),
        buoyancy: None,
    };
    let legs = vec![
        Leg {
            control: Control::Load,
            target: Target::To(24.49e3 * d),
            step: 5.0,
        },
        Leg {
            control: Control::Load,
            target: Target::To(2e3 * d),
            step: 5.0,
        },
        Leg {
            control: Control::Load,
            target: Target::To(21e3 * d),
            step: 5.0,
        },
    ];
    let r = element_test::run(&seabed, &legs).expect("runs");
    for &i in &r.leg_ends {
        let row = &r.rows[i];
        let target = match legs[row.leg - 1].target {
            Target::To(t) => t,
            Target::By(_) => unreachable!(),
        };
        assert!(
            (row.total - target).abs() < 1e-9,
            "{} vs {target}",
            row.total
        );
    }
    let z2d = r.rows[r.leg_ends[0]].z;
    assert!(
        (z2d / d - 2.0).abs() < 2e-3,
        "z/D at 24.49 kPa = {}",
        z2d / d
    );
}

/// A suction the soil cannot give is reported, not looped on or panicked over.
#[test]
fn load_beyond_capacity_is_an_error() {
    let d = 0.025;
    let seabed = Seabed {
        law: Law::RandolphQuiggin(law(RqParams::table2())),
        buoyancy: None,
    };
    let legs = vec![
        Leg {
            control: Control::Displacement,
            target: Target::To(d),
            step: d / 100.0,
        },
        Leg {
            control: Control::Load,
            target: Target::To(-1e6),
            step: 1e6,
        },
    ];
    let e = element_test::run(&seabed, &legs).expect_err("cannot carry 1 MN/m of suction");
    assert!(matches!(
        e,
        element_test::TestError::LoadNotCarried { leg: 2, .. }
    ));
}

/// The root finder behind `suction_onset`: the bracket closes on two neighbouring numbers with
/// `f ≤ 0` below and `f > 0` at the answer, for smooth and for awkward functions, in a few
/// evaluations where Newton applies.
#[test]
fn bracketed_root_closes_on_neighbours() {
    use catena_seabed::rq::bracketed_root;
    use std::cell::Cell;
    let calls = Cell::new(0);
    let cube = |x: f64| {
        calls.set(calls.get() + 1);
        (x * x * x - 2.0, 3.0 * x * x)
    };
    let r = bracketed_root(cube, 0.0, 4.0);
    assert!(cube(r).0 > 0.0 && cube(r.next_down()).0 <= 0.0);
    assert!((r - 2f64.cbrt()).abs() <= 2.0 * f64::EPSILON * r);
    assert!(
        calls.get() < 24,
        "{} evaluations (bisection: about 55)",
        calls.get()
    );
    // A zero derivative and a step function: bisection carries it.
    let step = |x: f64| (if x < 0.3 { -1.0 } else { 1.0 }, 0.0);
    let r = bracketed_root(step, 0.0, 1.0);
    assert!(r >= 0.3 && r.next_down() < 0.3);
    // Decreasing in x, as P5 is towards the mudline: the same rule.
    let dec = |x: f64| (0.5 - x, -1.0);
    let r = bracketed_root(|x| dec(1.0 - x), 0.0, 1.0);
    assert!(dec(1.0 - r).0 > 0.0);
}

/// `suction_onset` ends whatever `Kmax` (issue 14: with `Kmax` of 1e17 its scan step fell below
/// half an ulp and it never returned) and agrees with a plain scan-and-bisect for Table 1.
#[test]
fn suction_onset_ends_for_any_kmax() {
    // Ends, and returns a root inside (0, z0] if any, for an uplift from z0 on the backbone.
    let ends = |p: RqParams, z0: f64, what: String| {
        let l = law(p);
        let p0 = l.p_ip(z0).0;
        let t = std::time::Instant::now();
        let zc = l.suction_onset(z0, p0);
        assert!(t.elapsed().as_secs_f64() < 1.0, "{what}");
        if let Some(zc) = zc {
            assert!(zc > 0.0 && zc <= z0, "{what}: {zc}");
        }
    };
    for k_max in [200.0, 1e6, 1e17, 1e300] {
        let p = RqParams {
            k_max,
            ..RqParams::table1()
        };
        ends(p, 0.05, format!("k_max {k_max}"));
    }
    // … and whatever the diameter (the fuzz target hung on an outer diameter of 1e-300 m, which
    // scenes now refuse).
    for diameter in [1e-300, 1e-12, 1e-6] {
        let p = RqParams {
            diameter,
            ..RqParams::table1()
        };
        ends(p, 0.5 * diameter, format!("D {diameter}"));
    }
    // … and when D/Kmax underflows to zero (D 1e-300 m, Kmax 1e300): the scan's first step was
    // 10⁻³·D/Kmax = 0, and `hi − 0 = hi` for ever.
    let p = RqParams {
        diameter: 1e-300,
        k_max: 1e300,
        ..RqParams::table1()
    };
    ends(p, 0.5e-300, "D/Kmax = 0".into());
    // Against a plain bisection of P5 on the same bracket (Table 1, an uplift from 5 cm).
    let l = law(RqParams::table1());
    let (z0, p0) = (0.05, l.p_ip(0.05).0);
    let zc = l.suction_onset(z0, p0).expect("suction for f_suc 0.6");
    // P5 changes sign across zc: just above (smaller z) it is ≤ 0... evaluated through the law's
    // uplift from (z0, p0): the force at zc is ≥ 0 and at the next number below it is the floor.
    let h = RqHistory {
        mode: Mode::Uplift,
        z_prev: z0,
        p_prev: p0,
        z0,
        p0,
        z_c: Some(zc),
        ..RqHistory::untouched(0.0)
    };
    let above = l.evaluate(&h, zc * (1.0 + 1e-9)).p;
    let below = l.evaluate(&h, zc * (1.0 - 1e-9)).p;
    assert!(above > below, "{above} {below}");
}

/// Load control (issue 14): a leg starts at the previous leg's target, not at the force the
/// previous solve reached, so a leg of a whole number of steps has exactly that many increments
/// (Figure 5's 365 → 525 N/m at 2 N/m: 80, not 81).
#[test]
fn load_legs_start_at_their_waypoint() {
    let seabed = Seabed {
        law: Law::RandolphQuiggin(law(RqParams::table2())),
        buoyancy: None,
    };
    let leg = |to: f64| Leg {
        control: Control::Load,
        target: Target::To(to),
        step: 2.0,
    };
    let legs = [leg(612.25), leg(365.0), leg(525.0), leg(365.0), leg(525.0)];
    let r = element_test::run(&seabed, &legs).expect("runs");
    let counts: Vec<usize> = r.leg_ends.windows(2).map(|w| w[1] - w[0]).collect();
    assert_eq!(counts, vec![124, 80, 80, 80], "increments per leg");
}
