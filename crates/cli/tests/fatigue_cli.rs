//! `catena fatigue`: a short study (three storms of 30 s) through the command: the outputs, the
//! annual-damage bookkeeping, resume, a changed storm run again, and bad study input named.

use std::path::{Path, PathBuf};

use catena_cli::commands;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("fatigue_cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

const STORMS: &str = "[[storm]]\nid = 22\nhs = 5.0\ntp = 8.4\nprobability = 0.002\n\n\
[[storm]]\nid = 23\nhs = 5.0\ntp = 9.9\nprobability = 0.004\n\n\
[[storm]]\nid = 24\nhs = 5.0\ntp = 11.9\ngamma = 1.0\nprobability = 0.002\nseed = 99\n";

/// A study of the paper's base scene over three storms, 30 s counted after a 20 s transient, two at
/// once.
fn short_study(d: &Path, storms: &str) -> PathBuf {
    for f in ["scr1000-linear-k100.toml", "semi-rao.csv"] {
        std::fs::copy(root().join("cases/scr1000/fatigue").join(f), d.join(f)).expect("copy");
    }
    std::fs::write(d.join("storms.toml"), storms).expect("storms");
    let study = d.join("study.toml");
    std::fs::write(
        &study,
        "[study]\nscene = \"scr1000-linear-k100.toml\"\nstorms = \"storms.toml\"\nrecord = 30.0\ntransient = 20.0\n\n\
         [fatigue]\nsn_curve = \"dnv-e-seawater-cp\"\nscf = 1.2\nfibres = [\"outer\", \"inner\"]\ndesign_factor = 3.0\n",
    )
    .expect("study");
    study
}

fn json(p: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(p).expect("json")).expect("json")
}

/// The outputs, and the bookkeeping: the annual damage at the critical point is `Σ p_i D_i Y/T_i`
/// over the storms' own results (`storms/<id>.json`), the minimum life its inverse, and the shares
/// add up to 1. A rerun takes every storm from the first run and gives the same numbers; a storm
/// whose sea state changes is run again, alone.
#[test]
fn short_study_bookkeeping_and_resume() {
    let d = dir("short");
    let study = short_study(&d, STORMS);
    let out = d.join("out");
    let text = commands::fatigue(&study, &out, 2, false).expect("study runs");
    println!("{text}");
    for f in [
        "fatigue.h5",
        "life.csv",
        "summary.json",
        "life.png",
        "storms.png",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    let s = json(&out.join("summary.json"));
    let life = s["min_life_years"].as_f64().expect("life");
    let arc = s["min_life_arc"].as_f64().expect("arc");
    let fibre = s["min_life_fibre"].as_str().expect("fibre").to_string();
    let arcs: Vec<f64> = std::fs::read_to_string(out.join("life.csv"))
        .expect("csv")
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().expect("arc").parse().expect("number"))
        .collect();
    let i = arcs.iter().position(|a| *a == arc).expect("node");
    let year = 365.25 * 86400.0;
    let mut total = 0.0;
    for id in [22, 23, 24] {
        let r = json(&out.join("storms").join(format!("{id}.json")));
        let p = r["storm"]["probability"].as_f64().expect("p");
        let t = r["counted_seconds"].as_f64().expect("T");
        assert!((t - 30.0).abs() < 1e-9);
        let dmg = r["damage"]
            .as_array()
            .expect("damage")
            .iter()
            .find(|x| x[0] == fibre.as_str())
            .expect("fibre")[1][i]
            .as_f64()
            .expect("d");
        total += p * dmg * year / t;
    }
    assert!((life * total - 1.0).abs() < 1e-9, "{life} vs 1/{total}");
    let shares: f64 = s["storm_shares"]
        .as_array()
        .expect("shares")
        .iter()
        .map(|x| x["share"].as_f64().expect("share"))
        .sum();
    assert!((shares - 1.0).abs() < 1e-9);
    assert!(
        (s["min_life_years_with_design_factor"].as_f64().expect("df") * 3.0 / life - 1.0).abs()
            < 1e-12
    );
    assert!(
        arc > 1100.0 && arc < 1250.0,
        "the minimum is in the touchdown zone: {arc}"
    );
    // Resume: everything taken from the first run.
    let again = commands::fatigue(&study, &out, 1, false).expect("rerun");
    assert!(again.contains("3 from an earlier run"), "{again}");
    assert_eq!(
        json(&out.join("summary.json"))["min_life_years"],
        s["min_life_years"]
    );
    // A changed storm runs again, alone.
    let changed = STORMS.replace("hs = 5.0\ntp = 11.9", "hs = 4.5\ntp = 11.9");
    short_study(&d, &changed);
    let third = commands::fatigue(&study, &out, 1, false).expect("changed");
    assert!(third.contains("2 from an earlier run"), "{third}");
}

/// Bad study input: a missing scene, a storm with a negative Hs, a duplicate id, an unknown key,
/// a bad S-N curve, SCF or fibre in the study's own `[fatigue]`; each names the file the key is
/// in and the key.
#[test]
fn bad_study_input_is_named() {
    let d = dir("bad");
    let study = short_study(&d, STORMS);
    let text = std::fs::read_to_string(&study).expect("study");
    for (name, study_text, storms, needle) in [
        (
            "scene",
            text.replace("scr1000-linear-k100.toml", "nope.toml"),
            STORMS.to_string(),
            "study.scene".to_string(),
        ),
        (
            "hs",
            text.clone(),
            STORMS.replace("hs = 5.0\ntp = 8.4", "hs = -1.0\ntp = 8.4"),
            "storm[0].hs".to_string(),
        ),
        (
            "id",
            text.clone(),
            STORMS.replace("id = 24", "id = 23"),
            "storm[2].id".to_string(),
        ),
        (
            "key",
            text.replace("transient = 20.0", "transient = 20.0\ncolour = 1"),
            STORMS.to_string(),
            "colour".to_string(),
        ),
        // The study's own [fatigue] table: its errors name the study's file, not the scene's.
        (
            "sn_curve",
            text.replace("\"dnv-e-seawater-cp\"", "\"dnv-z\""),
            STORMS.to_string(),
            format!("{}: key `fatigue.sn_curve`", study.display()),
        ),
        (
            "scf",
            text.replace("scf = 1.2", "scf = -1.0"),
            STORMS.to_string(),
            format!("{}: key `fatigue.scf`", study.display()),
        ),
        (
            "fibres",
            text.replace("[\"outer\", \"inner\"]", "[\"middle\"]"),
            STORMS.to_string(),
            format!("{}: key `fatigue.fibres", study.display()),
        ),
    ] {
        std::fs::write(&study, &study_text).expect("study");
        std::fs::write(d.join("storms.toml"), &storms).expect("storms");
        let err = commands::fatigue(&study, &d.join("out"), 1, false)
            .expect_err(name)
            .to_string();
        println!("{name}: {err}");
        assert!(err.contains(&needle), "{name}: {err}");
    }
}
