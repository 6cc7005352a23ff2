//! `catena rainflow`: the ASTM E1049-85 example through the command line, the cycles file, Miner's
//! damage, and bad input named.

use std::path::{Path, PathBuf};
use std::process::Command;

fn tmp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rainflow_cli");
    std::fs::create_dir_all(&dir).expect("dir");
    dir.join(name)
}

fn catena(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_catena"))
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The ASTM example as a two-column CSV: the cycles file has `range,mean,count` rows in the order
/// found, and the damage on DNV E in seawater (SCF 1.2) is `Σ n/N(1.2·Δσ)` computed by hand from
/// the curve's upper slope (every range is far below the knee, so the lower slope, m = 5).
#[test]
fn astm_example_through_the_command() {
    let csv = tmp("astm.csv");
    std::fs::write(
        &csv,
        "t,stress\n0,-2\n1,1\n2,-3\n3,5\n4,-1\n5,3\n6,-4\n7,4\n8,-2\n",
    )
    .expect("csv");
    let out = tmp("astm-cycles.csv");
    let (ok, stdout, stderr) = catena(&[
        "rainflow",
        csv.to_str().expect("path"),
        "--out",
        out.to_str().expect("path"),
        "--column",
        "stress",
        "--sn",
        "dnv-e-seawater-cp",
        "--scf",
        "1.2",
    ]);
    assert!(ok, "{stderr}");
    let cycles = std::fs::read_to_string(&out).expect("cycles");
    assert_eq!(
        cycles,
        "range,mean,count\n3,-0.5,0.5\n4,-1,0.5\n4,1,1\n8,1,0.5\n9,0.5,0.5\n8,0,0.5\n6,1,0.5\n"
    );
    let n = |ds: f64| 10f64.powf(15.350 - 5.0 * (1.2 * ds).log10());
    let want = 0.5 / n(3.0) + 1.5 / n(4.0) + 0.5 / n(6.0) + 1.0 / n(8.0) + 0.5 / n(9.0);
    let got: f64 = stdout
        .lines()
        .find(|l| l.contains("Miner damage"))
        .and_then(|l| l.rsplit(' ').next())
        .and_then(|v| v.parse().ok())
        .expect("damage printed");
    println!("{stdout}damage {got:.6e}, by hand {want:.6e}");
    assert!((got / want - 1.0).abs() < 1e-6);
}

/// Bad input: several columns without `--column`, an unknown column, a non-number, an unknown curve,
/// a bad SCF, a missing file: each a clear error naming the file and what is wrong, never a panic.
#[test]
fn bad_input_is_named() {
    let two = tmp("two.csv");
    std::fs::write(&two, "a,b\n1,2\n3,4\n").expect("csv");
    let word = tmp("word.csv");
    std::fs::write(&word, "s\n1\nabc\n").expect("csv");
    let out = tmp("bad-out.csv");
    let o = out.to_str().expect("path");
    for (args, needle) in [
        (vec![two.to_str().expect("p")], "--column"),
        (
            vec![two.to_str().expect("p"), "--column", "c"],
            "no such column",
        ),
        (vec![word.to_str().expect("p")], "line 3"),
        (
            vec![word.to_str().expect("p"), "--sn", "dnv-x"],
            "dnv-e-seawater-cp",
        ),
        (vec![word.to_str().expect("p"), "--scf=-1"], "--scf"),
        (vec!["/nonexistent/series.csv"], "series.csv"),
    ] {
        let mut a = vec!["rainflow"];
        a.extend(args);
        a.extend(["--out", o]);
        let (ok, _, stderr) = catena(&a);
        assert!(!ok && !stderr.contains("panicked"), "{a:?}: {stderr}");
        assert!(stderr.contains(needle), "{a:?}: `{needle}` not in {stderr}");
    }
}
