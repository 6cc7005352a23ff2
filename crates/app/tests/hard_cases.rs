#![allow(clippy::needless_range_loop)]
//! The stability suite (issue 5): hard cases under `cases/hard/` run to the end (or stop with a clear
//! error), never with NaN or a hang, and each has a check that a broken solver would fail.
//! `validation/hard-cases.md` records what each tests, its step cuts and its cost.

mod common;
use common::Edit;

use std::path::{Path, PathBuf};

use catena::run::{self as run_cmd, DynamicRun, RunOptions};
use catena::scene::riser::RiserScene;
use catena::scene::DirResolver;
use catena::statics as statics_cmd;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run_case(name: &str, edit: impl Fn(String) -> String) -> DynamicRun {
    let text =
        edit(std::fs::read_to_string(root().join(format!("cases/{name}.toml"))).expect("case"));
    let st = statics_cmd::solve(
        RiserScene::parse(
            name,
            &text,
            &DirResolver::beside(&root().join(format!("cases/{name}.toml"))),
        )
        .expect("scene"),
    )
    .expect("statics");
    let r = run_cmd::run(st, &mut [], RunOptions::default()).expect("runs");
    assert!(r.completed(), "{name}: {:?}", r.stop);
    let e = &r.envelopes;
    for v in [
        &e.moment.min,
        &e.moment.max,
        &e.tension.min,
        &e.tension.max,
        &e.penetration.max,
    ] {
        assert!(
            v.iter().all(|x| x.is_finite()),
            "{name}: non-finite envelope"
        );
    }
    assert!(
        r.top.top_tension.iter().all(|t| t.is_finite() && *t < 20e6),
        "{name}: top tension"
    );
    println!(
        "{name}: {} converged steps, {} Newton iterations ({:.2} per step), {} step cuts, {} predictor retries, {:.2} s",
        r.steps,
        r.iterations,
        r.iterations as f64 / r.steps.max(1) as f64,
        r.cuts,
        r.retries,
        r.wall_seconds
    );
    r
}

/// Stiff, sticky soil (Kmax 1000, f_suc 1, λsuc 2) under a 5 m, 6 s heave: repeated lift-off and
/// re-contact. Nodes that rest on the seabed in the statics lift off; the resting far field (arc ≥
/// 1300 m) stays within 1.5 times its static penetration plus 0.1D (a solver that ratchets the soil,
/// e.g. by committing Newton iterates or chattering, drives it down), and the slammed touchdown zone
/// stays above 3 m. The whole 60 s: with backtracking Newton it needs 263 step cuts (2022 without,
/// when full Newton steps cycled at the lift-off snap-through: `catena_fe::dynamics`); fewer than
/// 600 are allowed.
#[test]
fn sticky_soil_lift_off_and_recontact() {
    let r = run_case("hard/sticky-soil", |t| {
        t.edit("envelope_start = 30.0", "envelope_start = 0.0")
    });
    assert!(r.completed(), "{:?}", r.stop);
    assert!(r.cuts < 600, "{} step cuts", r.cuts);
    let stat = &r.statics.results.penetration;
    let e = &r.envelopes;
    let lifted = (0..stat.len())
        .filter(|&i| stat[i] > 0.0 && e.penetration.min[i] < 0.0)
        .count();
    assert!(lifted > 10, "lift-off at {lifted} nodes");
    for i in 0..stat.len() {
        // The touchdown zone is lifted clear and slammed back each cycle (to ~2.5 m here, bounded
        // from cycle to cycle: validation/hard-cases.md); the resting far field must not ratchet.
        let bound = if r.statics.model.arc[i] >= 1300.0 {
            1.5 * stat[i] + 0.1 * 0.2286
        } else {
            3.0
        };
        assert!(
            e.penetration.max[i] <= bound,
            "node {i}: {} (static {})",
            e.penetration.max[i],
            stat[i]
        );
    }
}

/// The heave benchmark with Δt = 0.2 s: still converges, and its ranges over t ∈ [50, 100] s stay
/// within 1 % (top tension) and 2 % (moment) of the Δt = 0.05 s run.
#[test]
fn large_time_step() {
    let big = run_case("hard/large-step", |t| t);
    let small = run_case("benchmarks/scr-heave", |t| t);
    let (m1, _, a1, b1) = run_cmd::key_numbers(&big);
    let (m2, _, a2, b2) = run_cmd::key_numbers(&small);
    assert!(
        ((b1 - a1) / (b2 - a2) - 1.0).abs() < 0.01,
        "{} vs {}",
        b1 - a1,
        b2 - a2
    );
    assert!((m1 / m2 - 1.0).abs() < 0.02, "{m1} vs {m2}");
}

/// Violent heave (8 m, 8 s): the riser near touchdown goes into compression (negative effective
/// tension), and the run still completes.
#[test]
fn violent_heave_into_compression() {
    let r = run_case("hard/violent-heave", |t| t);
    let min_t = r
        .envelopes
        .tension
        .min
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    println!(
        "violent heave: minimum effective tension {:.1} kN",
        min_t / 1e3
    );
    assert!(min_t < 0.0, "compression expected: {min_t}");
}

/// A near-vertical riser (2° top angle) heaved: it converges without cuts at a normal cost.
#[test]
fn near_vertical_riser() {
    let r = run_case("hard/near-vertical", |t| t);
    assert!(r.statics.summary.top_angle_from_vertical.to_degrees() < 2.5);
    assert!(r.iterations as f64 / r.steps as f64 <= 4.0);
}

/// A riser hanging clear of the seabed (touching it only at its anchor) is lowered by 120 m and lands:
/// nodes 100 m from the anchor penetrate the seabed during the run.
#[test]
fn riser_lands_on_the_seabed() {
    let r = run_case("hard/landing", |t| t);
    assert!(r.statics.summary.touchdown_arc.expect("anchor contact") > 1390.0);
    let i = r
        .statics
        .model
        .arc
        .iter()
        .position(|a| *a >= 1300.0)
        .expect("node");
    assert!(r.statics.results.penetration[i] < 0.0, "clear at the start");
    assert!(
        r.envelopes.penetration.max[i] > 0.0,
        "landed: {}",
        r.envelopes.penetration.max[i]
    );
}

/// Very short elements (0.0625 m, 1760 of them, shorter than the diameter) next to steps in the top
/// velocity (Watchet's line and soil). The run completes, and it agrees with the same scene on
/// 0.25 m elements: the sag-bend moment extremes within 0.5 %, the top tension maximum within 1 %.
#[test]
fn short_elements_next_to_velocity_steps() {
    let fine = run_case("hard/short-elements", |t| t);
    let coarse = run_case("hard/short-elements", |t| {
        t.edit("element_length = 0.0625", "element_length = 0.25")
    });
    let ext = |r: &DynamicRun| {
        let m = &r.gauges.traces[0].moment;
        (
            m.iter().copied().fold(f64::INFINITY, f64::min),
            m.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            r.top.top_tension.iter().copied().fold(0.0, f64::max),
        )
    };
    let (a, b) = (ext(&fine), ext(&coarse));
    println!("0.0625 m: {a:?}; 0.25 m: {b:?}");
    assert!((a.0 / b.0 - 1.0).abs() < 0.005);
    assert!((a.1 / b.1 - 1.0).abs() < 0.005);
    assert!((a.2 / b.2 - 1.0).abs() < 0.01);
    assert_eq!(fine.statics.model.elements.len(), 1760);
}

/// Steps in the top velocity (0 → +1 → −1 → 0 m/s): the run completes, the top ends where it started,
/// and the line responds as it must: while the top rises at 1 m/s the mean top tension is above its
/// static value (drag and inertia resist the lift), while it falls it is below, and 15 s after the
/// motion stopped the top tension has come back to the static value within 3 % (the mean over the
/// last 5 s).
#[test]
fn velocity_steps() {
    let r = run_case("hard/velocity-step", |t| t);
    let z = *r.top.top_z.last().expect("records");
    assert!((z - 1000.0).abs() < 1e-9, "{z}");
    let h = &r.top;
    let mean = |a: f64, b: f64| {
        let v: Vec<f64> =
            h.t.iter()
                .zip(&h.top_tension)
                .filter(|(t, _)| **t >= a && **t <= b)
                .map(|(_, v)| *v)
                .collect();
        v.iter().sum::<f64>() / v.len() as f64
    };
    let t0 = r.statics.summary.top_tension;
    let (up, down, end) = (mean(6.0, 10.0), mean(11.0, 15.0), mean(25.0, 30.0));
    println!(
        "velocity steps: static {:.1} kN; rising {:.1} kN, falling {:.1} kN, last 5 s {:.1} kN",
        t0 / 1e3,
        up / 1e3,
        down / 1e3,
        end / 1e3
    );
    assert!(up > t0 && down < t0, "{up} / {down} vs {t0}");
    assert!((end / t0 - 1.0).abs() < 0.03, "{end} vs {t0}");
}

/// Three hours of the heave benchmark (216 000 steps, about 2 minutes): the top tension's mean and
/// range in the last 100 s equal those of t ∈ [50, 150] s (drift-free, to 0.5 %), and the
/// penetration stays within 10 % of its envelope after 150 s. Ignored in CI (long); run with
/// `cargo test --release -p catena --test hard_cases -- --ignored`.
#[test]
#[ignore]
fn three_hour_heave_benchmark() {
    let r = run_case("benchmarks/scr-heave", |t| {
        t.edit("duration = 100.0", "duration = 10800.0")
            .edit("envelope_start = 50.0", "envelope_start = 0.0")
    });
    let h = &r.top;
    let window = |a: f64, b: f64| {
        let v: Vec<f64> =
            h.t.iter()
                .zip(&h.top_tension)
                .filter(|(t, _)| **t >= a && **t < b)
                .map(|(_, v)| *v)
                .collect();
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let range = v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - v.iter().copied().fold(f64::INFINITY, f64::min);
        (mean, range)
    };
    let (m0, r0) = window(50.0, 150.0);
    let (m1, r1) = window(10700.0, 10800.0);
    println!(
        "3 h: top tension mean {:.2} → {:.2} kN, range {:.2} → {:.2} kN",
        m0 / 1e3,
        m1 / 1e3,
        r0 / 1e3,
        r1 / 1e3
    );
    assert!((m1 / m0 - 1.0).abs() < 5e-3 && (r1 / r0 - 1.0).abs() < 5e-3);
    let pmax = r
        .envelopes
        .penetration
        .max
        .iter()
        .copied()
        .fold(0.0, f64::max);
    let pstat = r
        .statics
        .results
        .penetration
        .iter()
        .copied()
        .fold(0.0, f64::max);
    println!("3 h: max penetration {:.5} m (static {:.5} m)", pmax, pstat);
    assert!(pmax < 1.5 * pstat);
}

/// A very stiff clay (su0 30 kPa, Kmax 1000, f_suc 0.6) under a 3 m, 10 s heave of the 1000 m SCR
/// (issue 14). Without the lift-off band the run stopped at t = 2.25 s after 8 cuts (at Δt 0.05 and
/// 0.1 s alike). It must now complete at Δt and Δt/2, and the two must agree on the largest moment
/// range within 1 % and the top tension range within 2 %. Shortened to 40 s in CI.
#[test]
fn stiff_clay_completes_and_halving_the_step_agrees() {
    let shorten = |t: String| t.edit("duration = 100.0", "duration = 40.0");
    let a = run_case("hard/stiff-clay", shorten);
    let b = run_case("hard/stiff-clay", |t| {
        shorten(t).edit("time_step = 0.05", "time_step = 0.025")
    });
    let (m1, at1, t1a, t1b) = run_cmd::key_numbers(&a);
    let (m2, at2, t2a, t2b) = run_cmd::key_numbers(&b);
    println!(
        "stiff clay: moment range {m1:.1} N·m at {at1} m (Δt/2: {m2:.1} at {at2}); top tension range {:.1} N (Δt/2: {:.1})",
        t1b - t1a,
        t2b - t2a
    );
    assert!(a.cuts < 100, "{} cuts", a.cuts);
    // The cut steps are reported where they happen: the touchdown zone.
    assert!(!a.cut_log.is_empty() && a.cut_log.len() <= a.cuts as usize);
    for c in &a.cut_log {
        assert!(
            (1100.0..1250.0).contains(&c.arc) && c.t >= 0.0 && c.dt <= 0.05 + 1e-12,
            "{c:?}"
        );
    }
    assert!((m1 / m2 - 1.0).abs() < 0.01, "{m1} vs {m2}");
    assert!(((t1b - t1a) / (t2b - t2a) - 1.0).abs() < 0.02);
    // The touchdown zone does lift to the mudline (the case tests lift-off, not resting contact).
    let lifted = (0..a.model.line.nodes())
        .filter(|&i| {
            a.statics.results.penetration[i] > 0.0 && a.envelopes.penetration.min[i] <= 0.0
        })
        .count();
    assert!(lifted > 0, "no node lifted off");
}

/// The run of the reduced Figure 10 sweep that stopped (su0 2 kPa, f_suc 0.6, storm 8): a touchdown
/// node reaches the mudline while the literal eq. 5 still gives 28 N/m. It must complete.
#[test]
fn suction_at_lift_off_in_a_storm_completes() {
    let r = run_case("hard/suction-liftoff", |t| t);
    assert!(r.cuts < 20, "{} cuts", r.cuts);
}

/// Axial friction in stick–slip (issue 28): the heave benchmark's riser on a seabed with friction
/// μ = 0.5 and a mobilisation of only 1 mm, in a slow 5 m surge (`cases/hard/friction-stick-slip`).
/// It completes, and friction does what it must: the seabed section carries the axial load
/// variation, so the effective tension's range at the anchor falls to under half of the
/// frictionless run's (a friction that never acts, or acts the wrong way, fails).
#[test]
fn friction_stick_slip_on_a_slow_surge() {
    let with = run_case("hard/friction-stick-slip", |t| t);
    let without = run_case("hard/friction-stick-slip", |t| {
        t.edit(
            "[seabed.friction]\naxial = 0.5 ",
            "[seabed.friction]\naxial = 0.0 ",
        )
    });
    let (a, b) = (anchor_tension_range(&with), anchor_tension_range(&without));
    println!(
        "friction stick-slip: anchor tension range {:.2} kN with friction, {:.2} kN without; {} cuts",
        a / 1e3,
        b / 1e3,
        with.cuts
    );
    assert!(a < 0.5 * b, "{a} vs {b}");
}

/// The effective tension's range at the anchor over the envelope window, N.
fn anchor_tension_range(r: &DynamicRun) -> f64 {
    let e = &r.envelopes.tension;
    let n = e.max.len() - 1;
    e.max[n] - e.min[n]
}

/// The same stick–slip on a seabed rising 2° towards the anchor (friction along the local mudline,
/// its anchors points on the slope): it completes, and the seabed section still carries the axial
/// load variation (anchor tension range under half of the frictionless run's on the same slope).
#[test]
fn friction_stick_slip_on_a_sloping_seabed() {
    let slope = |t: String| {
        t.edit(
            "[seabed]\n",
            "[seabed]\nprofile = [[0.0, 0.0], [2000.0, -69.84]]\n",
        )
    };
    let with = run_case("hard/friction-stick-slip", slope);
    let without = run_case("hard/friction-stick-slip", |t| {
        slope(t).edit(
            "[seabed.friction]\naxial = 0.5 ",
            "[seabed.friction]\naxial = 0.0 ",
        )
    });
    let (a, b) = (anchor_tension_range(&with), anchor_tension_range(&without));
    println!(
        "friction stick-slip on a 2° slope: anchor tension range {:.2} kN with friction, {:.2} kN without; {} cuts",
        a / 1e3,
        b / 1e3,
        with.cuts
    );
    assert!(a < 0.5 * b, "{a} vs {b}");
}

/// A touchdown crossing a soil zone boundary (issue 28): the heave benchmark's riser with a soft
/// zone (20 kN/m/m² against 100) under its resting part, up to x = 400 m, about where its touchdown
/// point rests, in a 2 m heave (`cases/hard/zone-boundary`). It completes; the resting pipe sinks
/// to the soft soil's embedment `w/(kD)` = 0.221 m (the default's would be 0.044 m), to 2 %; and
/// the touchdown point moves across the boundary (its range of arc lengths spans the arc where
/// x = 400 m).
#[test]
fn touchdown_crossing_a_zone_boundary() {
    let r = run_case("hard/zone-boundary", |t| t);
    let st = &r.statics;
    let (x, pen) = (&st.results.x, &st.results.penetration);
    let at = |x0: f64| {
        let i = x.iter().position(|x| (x - x0).abs() < 2.5).expect("node");
        pen[i]
    };
    let (w, d) = (1010.0, 0.2286);
    let (a, b) = (at(100.0), at(300.0));
    println!(
        "zone boundary: static penetration {a:.4} m at x 100 m, {b:.4} m at 300 m (soft zone; w/kD {:.4} m); touchdown arc {:?}; {} cuts",
        w / (2e4 * d),
        r.envelopes.touchdown,
        r.cuts
    );
    for p in [a, b] {
        assert!((p / (w / (2e4 * d)) - 1.0).abs() < 0.02, "{p}");
    }
    let boundary_arc = {
        let i = x.iter().position(|x| *x < 400.0).expect("node");
        r.model.line.arc[i]
    };
    let (lo, hi) = r.envelopes.touchdown;
    assert!(
        lo < boundary_arc && boundary_arc < hi,
        "{lo} {hi} {boundary_arc}"
    );
}

/// The steel lazy wave in a violent heave (8 m, 8 s; `cases/hard/lazy-wave-violent-heave`): the
/// hanging line above the buoyancy goes slack as the top falls (least effective tension −26.7 kN at
/// 940 m measured, compressed between 810 and 1045 m), and the run completes without a cut.
#[test]
fn lazy_wave_violent_heave_goes_slack_above_the_buoyancy() {
    let r = run_case("hard/lazy-wave-violent-heave", |t| t);
    let mins = &r.envelopes.tension.min;
    let (i, min_t) =
        mins.iter().copied().enumerate().fold(
            (0, f64::INFINITY),
            |a, (i, t)| if t < a.1 { (i, t) } else { a },
        );
    let arc = r.model.line.arc[i];
    println!(
        "lazy wave violent heave: least effective tension {:.1} kN at {arc:.1} m, {} cuts",
        min_t / 1e3,
        r.cuts
    );
    assert!(min_t < 0.0, "compression expected: {min_t}");
    assert!(
        arc < r.model.line.section_boundaries()[0],
        "slack at {arc} m"
    );
}
