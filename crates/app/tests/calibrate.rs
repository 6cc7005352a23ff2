//! Soil parameters fitted to element tests (`catena::calibrate`): a round trip through a synthetic
//! test (known parameters recovered, without and with noise), the determination of parameters a
//! test does not exercise, and bad test files named.

use catena::calibrate::{calibrate, forward, read_test, TestData};
use catena_seabed::RqParams;
use rand_chacha::rand_core::{RngCore, SeedableRng};

/// A displacement-controlled test in the spirit of the paper's Figure 6 (Table 1 soil, D = 0.35
/// m): penetration to one diameter, then five cycles of uplift by 1.2 D (lifting off) and
/// repenetration to 1.1 D, one point every D/100.
fn figure6_like() -> Vec<f64> {
    let d = RqParams::table1().diameter;
    let mut z = Vec::new();
    let mut walk = |from: f64, to: f64| {
        let n = ((to - from).abs() / (0.01 * d)).ceil() as usize;
        for k in 1..=n {
            z.push(from + (to - from) * k as f64 / n as f64);
        }
    };
    walk(0.0, d);
    let mut at = d;
    for _ in 0..5 {
        walk(at, at - 1.2 * d);
        walk(at - 1.2 * d, 1.1 * d);
        at = 1.1 * d;
    }
    z
}

const FIT: [&str; 5] = ["su0", "k_max", "f_suc", "lambda_suc", "lambda_rep"];

fn start() -> RqParams {
    let t = RqParams::table1();
    RqParams {
        su0: 1.3 * t.su0,
        k_max: 0.6 * t.k_max,
        f_suc: 0.4,
        lambda_suc: 0.7,
        lambda_rep: 0.35,
        ..t
    }
}

fn keys() -> Vec<String> {
    FIT.iter().map(|s| s.to_string()).collect()
}

fn value(p: &RqParams, k: &str) -> f64 {
    match k {
        "su0" => p.su0,
        "k_max" => p.k_max,
        "f_suc" => p.f_suc,
        "lambda_suc" => p.lambda_suc,
        _ => p.lambda_rep,
    }
}

/// A noiseless synthetic test with Table 1's parameters, fitted from a start 30–60 % off in five
/// parameters: every one recovered to 1e-4 relative, the misfit below 1e-6 of the peak force, and
/// each one well determined (the test lifts off and re-contacts, so the suction and repenetration
/// parameters are exercised).
#[test]
fn a_synthetic_test_gives_back_its_parameters() {
    let truth = RqParams::table1();
    let z = figure6_like();
    let p = forward(&truth, &z).expect("valid");
    let data = TestData {
        file: "synthetic".into(),
        z,
        p,
    };
    let c = calibrate(&data, start(), &keys(), "test").expect("fits");
    assert!(c.rms_relative < 1e-6, "misfit {}", c.rms_relative);
    for k in FIT {
        let (got, want) = (value(&c.params, k), value(&truth, k));
        assert!(
            ((got - want) / want).abs() < 1e-4,
            "{k}: fitted {got}, true {want}"
        );
    }
    for d in &c.determination {
        assert_eq!(d.verdict, "well determined", "{}: {d:?}", d.name);
    }
}

/// The same test with Gaussian noise of 1 % of the peak force on every point (seeded): the fit is
/// within 5 % of the truth for every parameter, within four of its reported standard errors, and
/// the misfit is the noise's (1 % of the peak, to 10 %).
#[test]
fn a_noisy_synthetic_test_gives_its_parameters_within_their_errors() {
    let truth = RqParams::table1();
    let z = figure6_like();
    let clean = forward(&truth, &z).expect("valid");
    let peak = clean.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let mut unit = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    let p: Vec<f64> = clean
        .iter()
        .map(|x| {
            // Box–Muller.
            let (u1, u2) = (unit().max(1e-300), unit());
            x + 0.01 * peak * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
        })
        .collect();
    let data = TestData {
        file: "noisy".into(),
        z,
        p,
    };
    let c = calibrate(&data, start(), &keys(), "test").expect("fits");
    assert!(
        (c.rms_relative - 0.01).abs() < 0.001,
        "misfit {} of the peak",
        c.rms_relative
    );
    for d in &c.determination {
        let want = value(&truth, &d.name);
        let err = (d.value - want) / want;
        assert!(err.abs() < 0.05, "{}: {} vs {want}", d.name, d.value);
        assert!(
            err.abs() < 4.0 * d.relative_standard_error,
            "{}: error {err}, standard error {}",
            d.name,
            d.relative_standard_error
        );
    }
}

/// A test that never lifts off (penetration and small reversals in compression) cannot determine
/// the suction decay: `lambda_suc` is reported as not determined while `su0` is well determined.
#[test]
fn a_parameter_the_test_does_not_exercise_is_not_determined() {
    let truth = RqParams::table1();
    let d = truth.diameter;
    let mut z: Vec<f64> = (1..=100).map(|k| d * k as f64 / 100.0).collect();
    for _ in 0..5 {
        z.extend((1..=10).map(|k| d * (1.0 - 0.001 * k as f64)));
        z.extend((1..=10).map(|k| d * (0.99 + 0.001 * k as f64)));
    }
    let p = forward(&truth, &z).expect("valid");
    let data = TestData {
        file: "compression".into(),
        z,
        p,
    };
    let keys = vec!["su0".to_string(), "lambda_suc".to_string()];
    let c = calibrate(&data, start(), &keys, "test").expect("fits");
    assert_eq!(c.determination[0].verdict, "well determined");
    assert_eq!(c.determination[1].verdict, "not determined");
}

/// Bad test files and fits: too few points, a leg that reverses, a missing column, an unknown
/// key: each error names the file and what is wrong.
#[test]
fn bad_tests_are_named() {
    let rows = |n: usize| -> String {
        (0..n)
            .map(|k| format!("1,{},{}\n", 0.001 * k as f64, 10.0 * k as f64))
            .collect()
    };
    for (text, key) in [
        (format!("leg,z,P\n{}", rows(5)), "rows"),
        (
            format!("leg,z,P\n{}1,0.002,3.0\n", rows(12)),
            "leg 1 (rows 1 to 13)",
        ),
        ("leg,depth,P\n1,0.0,0.0\n".to_string(), "`z`"),
        (format!("leg,z,P\n{}1,x,3\n", rows(12)), "row 13, column z"),
    ] {
        let e = read_test("t.csv", &text).expect_err("bad").to_string();
        assert!(e.contains("t.csv") && e.contains(key), "{e}");
    }
    let data = read_test("t.csv", &format!("z,P\n{}", rows(12))).expect("good");
    let e = calibrate(&data, start(), &["k_mix".to_string()], "--fit")
        .expect_err("unknown key")
        .to_string();
    assert!(e.contains("fit[0]") && e.contains("k_mix"), "{e}");
}
