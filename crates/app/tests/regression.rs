//! Pinned numbers: the results the validation pages publish, recomputed from the case files and held
//! to 1e-9 relative. Moving one of these is a decision, stated in the CHANGELOG with the old and the
//! new value; a refactoring must leave them all in place.
//!
//! The published values are the rounded ones in `validation/` (heave benchmark 72.24 kN·m and
//! 303.52 kN, Watchet gauge D −6.28 / −5.44 kN·m, the slow-heave ranges, the static SCR); the pins
//! carry their full digits as first computed.

use std::path::{Path, PathBuf};

use catena::run::{self, DynamicRun, RunOptions};
use catena::statics::{self, StaticRun};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn statics(case: &str) -> StaticRun {
    let scene = statics::read_scene(&root().join(case)).expect("scene");
    statics::solve(scene).expect("statics")
}

fn dynamics(case: &str) -> DynamicRun {
    let r = run::run(statics(case), &mut [], RunOptions::default()).expect("run");
    assert!(r.completed(), "{case}: {:?}", r.stop);
    r
}

/// Checks `got` against the pinned value to 1e-9 relative, naming what it is.
fn pin(what: &str, got: f64, pinned: f64) {
    let rel = (got / pinned - 1.0).abs();
    println!("{what}: {got:.10e} (pinned {pinned:.10e}, rel. diff {rel:.2e})");
    assert!(
        rel <= 1e-9,
        "{what}: {got} moved from the pinned {pinned} (rel. {rel:.3e})"
    );
}

/// Top tension, horizontal tension, touchdown arc length and largest sag moment of each static case.
#[test]
fn static_cases_hold_their_numbers() {
    for (case, tt, h, td, sag) in [
        (
            "cases/scr1000/static-linear-k100.toml",
            1196513.4612135587,
            207272.82298733274,
            1168.2422527863937,
            -82792.95785766437,
        ),
        (
            "cases/scr1000/static-linear-k1000.toml",
            1196470.3568540686,
            207249.74625050643,
            1171.944661287799,
            -82877.47998119594,
        ),
        (
            "cases/scr1000/static-linear-k10000.toml",
            1196465.8376712666,
            207247.29820383553,
            1173.8840995684782,
            -82892.26565538853,
        ),
        (
            "cases/scr1000/static-rq.toml",
            1196498.6175611278,
            207265.3069781715,
            1168.2017678396244,
            -82751.19738462503,
        ),
        (
            "cases/watchet/static.toml",
            55448.16586482093,
            54097.39941691175,
            44.96982193710941,
            -12361.667970709426,
        ),
        (
            "cases/benchmarks/scr-heave.toml",
            1221555.599548865,
            211858.7472988595,
            1191.947991404193,
            -80757.62911176775,
        ),
    ] {
        let s = statics(case).summary;
        pin(&format!("{case}: top tension"), s.top_tension, tt);
        pin(
            &format!("{case}: horizontal tension"),
            s.horizontal_tension,
            h,
        );
        pin(
            &format!("{case}: touchdown arc"),
            s.touchdown_arc.expect("touchdown"),
            td,
        );
        pin(&format!("{case}: max sag moment"), s.max_sag_moment.0, sag);
    }
}

/// The heave benchmark (validation/heave-benchmark.md): largest moment range 72.24 kN·m (at 1192 m,
/// in the touchdown zone) and top tension range 303.52 kN over t ∈ [50, 100] s.
#[test]
fn heave_benchmark_holds_its_numbers() {
    let r = dynamics("cases/benchmarks/scr-heave.toml");
    let (mr, at, tmin, tmax) = run::key_numbers(&r);
    assert_eq!(at, 1192.0);
    pin("heave: largest moment range", mr, 72243.96882039313);
    pin("heave: top tension range", tmax - tmin, 303516.0436136981);
}

/// The slow heave of the 1000 m SCR on k = 100, 1000, 10000 kN/m/m² (validation/dynamics.md):
/// largest moment range 32.20 / 39.31 / 43.37 kN·m, top tension range 8.13 kN.
#[test]
fn slow_heave_cases_hold_their_numbers() {
    for (case, m, t) in [
        (
            "cases/scr1000/slow-heave-k100.toml",
            32199.504631778538,
            8125.214635347715,
        ),
        (
            "cases/scr1000/slow-heave-k1000.toml",
            39313.33425446856,
            8125.715889881365,
        ),
        (
            "cases/scr1000/slow-heave-k10000.toml",
            43372.91966287929,
            8125.978754619136,
        ),
    ] {
        let r = dynamics(case);
        let (mr, _, tmin, tmax) = run::key_numbers(&r);
        pin(&format!("{case}: largest moment range"), mr, m);
        pin(&format!("{case}: top tension range"), tmax - tmin, t);
    }
}

/// Watchet (validation/watchet.md): the pull-up minimum of the moment at gauge D, −6.28 kN·m with
/// suction (f_suc = 1) and −5.44 kN·m without (from every step since 0.2.0; from the 0.1 s records
/// before: −6.2792 and −5.4358 kN·m).
#[test]
fn watchet_gauge_d_holds_its_numbers() {
    for (case, pull_up_min) in [
        ("cases/watchet/pull-up-lay-down.toml", -6280.839030001626),
        (
            "cases/watchet/pull-up-lay-down-no-suction.toml",
            -5436.105728385792,
        ),
    ] {
        let r = dynamics(case);
        let k = r
            .spec
            .gauges
            .iter()
            .position(|g| g.name == "D")
            .expect("gauge D");
        let rising_min = r.gauges.traces[k].by_direction[0].0.expect("the top rose");
        // Extremes come from every step: the top tension maximum is the envelope's at the top node
        // (they disagreed when the summary read the 0.1 s records).
        let (_, _, _, tmax) = run::key_numbers(&r);
        assert_eq!(tmax, r.envelopes.tension.max[0]);
        pin(
            &format!("{case}: gauge D pull-up minimum"),
            rising_min,
            pull_up_min,
        );
    }
}
