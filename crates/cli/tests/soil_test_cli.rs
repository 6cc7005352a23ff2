//! `catena soil-test`: the paper's Figures 3–6 as cases, the CSV interface, and bad input.

#[path = "../../app/tests/common/mod.rs"]
mod common;
use common::Edit;

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("soil_test_cli");
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}

struct Csv {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Csv {
    fn read(p: &Path) -> Self {
        let text = std::fs::read_to_string(p).expect("csv written");
        let mut lines = text.lines();
        let header = lines
            .next()
            .expect("header")
            .split(',')
            .map(str::to_string)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect();
        Self { header, rows }
    }
    fn col(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("column {name}"))
    }
    fn f(&self, row: usize, name: &str) -> f64 {
        self.rows[row][self.col(name)].parse().expect("number")
    }
}

fn run_case(name: &str) -> (String, Csv) {
    let case = root().join(format!("cases/soil/{name}.toml"));
    let out = tmp(&format!("{name}.csv"));
    let png = tmp(&format!("{name}.png"));
    let r = catena_cli::commands::soil_test(&case, &out, Some(&png)).expect("case runs");
    assert!(std::fs::metadata(&png).expect("plot written").len() > 10_000);
    (r, Csv::read(&out))
}

/// The interface's required columns, the initial-state row, and one row per increment.
#[test]
fn figure3_csv_interface_and_every_mode() {
    let (_, csv) = run_case("figure3");
    for c in ["step", "z", "P", "buoyancy", "mode"] {
        csv.col(c);
    }
    assert_eq!(csv.f(0, "step"), 0.0);
    assert_eq!(csv.f(0, "z"), 0.0);
    assert_eq!(csv.rows[0][csv.col("mode")], "not_in_contact");
    for (i, r) in csv.rows.iter().enumerate() {
        assert_eq!(r[csv.col("step")], i.to_string());
    }
    let modes: std::collections::HashSet<&str> = csv
        .rows
        .iter()
        .map(|r| r[csv.col("mode")].as_str())
        .collect();
    for m in [
        "not_in_contact",
        "initial_penetration",
        "uplift",
        "repenetration",
    ] {
        assert!(modes.contains(m), "{m}");
    }
    // Each leg is split in ceil(|dz|/step) increments: the first leg (0 -> 0.175 m, step 8.75e-5)
    // has 2000.
    let first_leg_rows = csv.rows.iter().filter(|r| r[csv.col("leg")] == "2").count();
    assert_eq!(first_leg_rows, 2000);
}

/// Figure 4: P/D at 2D = 24.49 kPa (to 0.005 kPa).
#[test]
fn figure4_pressure_at_2d() {
    let (_, csv) = run_case("figure4");
    let i = (0..csv.rows.len())
        .find(|&i| (csv.f(i, "z") - 0.05).abs() < 1e-12)
        .expect("a row at z = 2D");
    let p_over_d = csv.f(i, "P") / 0.025 / 1000.0;
    assert!((p_over_d - 24.49).abs() < 0.005, "{p_over_d}");
}

/// Figure 5: the penetration per cycle grows with the cycle amplitude (mean per-cycle increment of
/// each block larger than the previous block's).
#[test]
fn figure5_penetration_grows_with_amplitude() {
    let case = catena::soil_test::SoilTestCase::read(&root().join("cases/soil/figure5.toml"))
        .expect("reads");
    let r = case.run().expect("runs");
    let ends = case.cycle_ends(&r);
    assert_eq!(ends.len(), 120);
    let z0 = case.start_of_cycles(&r);
    let z = |c: usize| ends[c - 1].1;
    let block1 = (z(10) - z0) / 10.0;
    let block2 = (z(20) - z(10)) / 10.0;
    let block3 = (z(120) - z(20)) / 100.0;
    assert!(
        block1 > 0.0 && block2 > 1.5 * block1 && block3 > block2,
        "{block1} {block2} {block3}"
    );
    // Every cycle ends at the 21 kPa target.
    for &i in &r.leg_ends[2..] {
        let t = r.rows[i].total / 0.025 / 1000.0;
        assert!(
            [14.6, 8.2, 2.0, 21.0].iter().any(|v| (t - v).abs() < 1e-9),
            "{t}"
        );
    }
}

/// Figure 6: the penetration at 20 kPa grows each cycle, by less each time.
#[test]
fn figure6_penetration_grows_by_less_each_cycle() {
    let case = catena::soil_test::SoilTestCase::read(&root().join("cases/soil/figure6.toml"))
        .expect("reads");
    let r = case.run().expect("runs");
    let ends = case.cycle_ends(&r);
    assert_eq!(ends.len(), 30);
    let mut prev = case.start_of_cycles(&r);
    let mut prev_inc = f64::INFINITY;
    for &(c, z) in &ends {
        let inc = z - prev;
        assert!(inc > 0.0, "cycle {c}: {inc}");
        assert!(
            inc < prev_inc * (1.0 + 1e-9),
            "cycle {c}: {inc} after {prev_inc}"
        );
        prev = z;
        prev_inc = inc;
    }
}

fn run_bad(name: &str, text: &str) -> String {
    let path = tmp(name);
    std::fs::write(&path, text).expect("write case");
    let out = Command::new(env!("CARGO_BIN_EXE_catena"))
        .args(["soil-test"])
        .arg(&path)
        .arg("--out")
        .arg(tmp(&format!("{name}.csv")))
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "{name} must fail");
    assert!(!err.contains("panicked"), "{name} panicked: {err}");
    assert!(
        err.contains(name),
        "{name}: the message must name the file: {err}"
    );
    err
}

const GOOD_SEABED: &str = r#"
[seabed]
model = "randolph-quiggin"
diameter = 0.35
su0 = 5000.0
su_gradient = 1500.0
a = 6.0
b = 0.25
k_max = 200.0
f_suc = 0.6
lambda_suc = 0.4
lambda_rep = 0.2
"#;

const GOOD_TEST: &str = r#"
[test]
control = "displacement"
waypoints = [0.0, 0.1]
step = 0.001
"#;

/// Bad input: each message names the file and the key, and says what was expected.
#[test]
fn bad_input_names_file_and_key() {
    let cases: Vec<(&str, String, &[&str])> = vec![
        ("unknown_key.toml", format!("{GOOD_SEABED}kmax = 3.0\n{GOOD_TEST}"), &["kmax", "k_max"]),
        ("missing_key.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("a = 6.0\n", "")), &["seabed.a"]),
        ("bad_b.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("b = 0.25", "b = 1.5")), &["seabed.b", "0 < b < 1"]),
        ("bad_fsuc.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("f_suc = 0.6", "f_suc = 1.2")), &["seabed.f_suc"]),
        ("bad_kmax.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("k_max = 200.0", "k_max = 0.0")), &["seabed.k_max"]),
        ("bad_d.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("diameter = 0.35", "diameter = -1.0")), &["seabed.diameter"]),
        ("bad_lsuc.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("lambda_suc = 0.4", "lambda_suc = 0.0")), &["seabed.lambda_suc"]),
        ("bad_lrep.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("lambda_rep = 0.2", "lambda_rep = -0.1")), &["seabed.lambda_rep"]),
        ("no_strength.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("su0 = 5000.0", "su0 = 0.0").edit("su_gradient = 1500.0", "su_gradient = 0.0")), &["seabed.su0"]),
        ("neg_strength.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("su0 = 5000.0", "su0 = -5.0")), &["seabed.su0"]),
        ("bad_fb.toml", format!("{GOOD_SEABED}f_b = 0.5\nsoil_density = 1500.0\nwater_density = 1025.0\n{GOOD_TEST}"), &["seabed.f_b"]),
        ("partial_buoyancy.toml", format!("{GOOD_SEABED}f_b = 1.5\n{GOOD_TEST}"), &["seabed.soil_density"]),
        ("wrong_model_key.toml", format!("{GOOD_SEABED}stiffness = 1.0\n{GOOD_TEST}"), &["seabed.stiffness"]),
        ("unknown_model.toml", format!("{}{GOOD_TEST}", GOOD_SEABED.edit("randolph-quiggin", "rq")), &["rq", "randolph-quiggin"]),
        ("empty_waypoints.toml", format!("{GOOD_SEABED}{}", GOOD_TEST.edit("[0.0, 0.1]", "[]")), &["test.waypoints"]),
        ("zero_step.toml", format!("{GOOD_SEABED}{}", GOOD_TEST.edit("step = 0.001", "step = 0.0")), &["test.step"]),
        ("bad_control.toml", format!("{GOOD_SEABED}{}", GOOD_TEST.edit("\"displacement\"", "\"force\"")), &["force", "displacement"]),
        ("missing_test.toml", GOOD_SEABED.to_string(), &["test"]),
        ("not_carried.toml", format!("{GOOD_SEABED}[test]\ncontrol = \"load\"\nwaypoints = [5000.0, -1.0e7]\nstep = 1.0e6\n"), &["test.waypoints[1]", "cannot carry"]),
        ("syntax.toml", "[seabed\nmodel = 1".to_string(), &["line"]),
    ];
    for (name, text, needles) in cases {
        let err = run_bad(name, &text);
        for n in needles {
            assert!(err.contains(n), "{name}: expected `{n}` in: {err}");
        }
    }
}

/// A missing case file is an error that names it, not a panic.
#[test]
fn missing_file_is_reported() {
    let out = Command::new(env!("CARGO_BIN_EXE_catena"))
        .args(["soil-test", "no/such/case.toml", "--out", "x.csv"])
        .output()
        .expect("runs");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no/such/case.toml") && !err.contains("panicked"),
        "{err}"
    );
}
