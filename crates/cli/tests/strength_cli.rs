//! `catena strength`: a short study (one storm, three seeds of 60 s) through the command: each
//! run's check and extremes, the envelope and the Gumbel fit across the seeds, resume, and bad
//! study input named.

use std::path::{Path, PathBuf};

use catena_cli::commands;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("strength_cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

/// The 100-year scene (linear seabed) with three seeds of a 6 m, 10 s sea, 60 s checked after a
/// 20 s transient; the study's own `[extremes]` (30 s blocks, target 60 s).
fn short_study(d: &Path, storms: &str) -> PathBuf {
    for f in ["design-100yr-linear.toml", "semi-rao.csv"] {
        std::fs::copy(root().join("cases/scr1000").join(f), d.join(f)).expect("copy");
    }
    std::fs::write(d.join("storms.toml"), storms).expect("storms");
    let study = d.join("study.toml");
    std::fs::write(
        &study,
        "[study]\nscene = \"design-100yr-linear.toml\"\nstorms = \"storms.toml\"\nrecord = 60.0\ntransient = 20.0\n\n\
         [extremes]\nchannels = [\"top_tension\", \"sag_moment\", \"utilisation\"]\nblock = 30.0\ntarget_duration = 60.0\nquantile = 0.8\n",
    )
    .expect("study");
    study
}

const STORMS: &str = "[[storm]]\nid = 7\nhs = 6.0\ntp = 10.0\nseeds = [11, 12, 13]\n";

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("json")).expect("json")
}

/// Three seeds of one storm: each run's largest utilisation is the largest of its per-node
/// utilisations, and the storm's envelope the largest over the seeds at every node; the seeds differ
/// (different seas); the Gumbel fit across the three largest utilisations is
/// `extremes::across_realisations` of them (most probable = μ for n = 1), and the channels of the
/// study's `[extremes]` follow; a rerun takes every run from its file, with the same summary; the
/// plot and CSV are written.
#[test]
fn three_seeds_of_a_storm_give_the_envelope_and_the_fit_across_them() {
    let d = dir("three");
    let study = short_study(&d, STORMS);
    let out = d.join("out");
    let text = commands::strength(&study, &out, 2, false).expect("study");
    println!("{text}");
    let s = json(&out.join("summary.json"));
    let storm = &s["storms"][0];
    assert_eq!(storm["seeds"].as_array().map(Vec::len), Some(3));
    let runs: Vec<serde_json::Value> = [11, 12, 13]
        .iter()
        .map(|seed| json(&out.join(format!("runs/7-{seed}.json"))))
        .collect();
    let per_seed: Vec<f64> = storm["across_seeds"][0]["per_seed"]
        .as_array()
        .expect("per seed")
        .iter()
        .map(|v| v.as_f64().expect("number"))
        .collect();
    let env: Vec<f64> = storm["utilisation_envelope"]
        .as_array()
        .expect("envelope")
        .iter()
        .map(|v| v.as_f64().expect("number"))
        .collect();
    let mut by_node = vec![0.0f64; env.len()];
    for (k, r) in runs.iter().enumerate() {
        let u: Vec<f64> = r["utilisation_max"]
            .as_array()
            .expect("u")
            .iter()
            .map(|v| v.as_f64().expect("number"))
            .collect();
        let largest = u.iter().copied().fold(0.0, f64::max);
        assert_eq!(per_seed[k], largest, "seed {k}");
        assert_eq!(r["worst"][1].as_f64(), Some(largest));
        for (b, x) in by_node.iter_mut().zip(&u) {
            *b = b.max(*x);
        }
    }
    assert_eq!(by_node, env);
    assert!(per_seed[0] != per_seed[1] && per_seed[1] != per_seed[2]);
    let settings = catena::extremes::Settings {
        target: 60.0,
        quantile: 0.8,
        block: 60.0,
    };
    let (g, v) = catena::extremes::across_realisations(
        &per_seed,
        catena::extremes::Tail::Max,
        60.0,
        &settings,
    )
    .expect("fit");
    let fit = &storm["across_seeds"][0]["gumbel"];
    assert_eq!(fit[0]["location"].as_f64(), Some(g.location));
    assert_eq!(fit[1][0].as_f64(), Some(v[0]));
    assert_eq!(v[0], g.location);
    assert!(v[1] > v[0]);
    let channels: Vec<&str> = storm["across_seeds"]
        .as_array()
        .expect("channels")
        .iter()
        .map(|c| c["channel"].as_str().expect("name"))
        .collect();
    assert_eq!(
        channels,
        [
            "utilisation_max",
            "top_tension",
            "sag_moment",
            "utilisation"
        ]
    );
    // The extremes' `utilisation` channel samples the same steps as the check: the same largest.
    let ch_u: Vec<f64> = storm["across_seeds"][3]["per_seed"]
        .as_array()
        .expect("u")
        .iter()
        .map(|v| v.as_f64().expect("number"))
        .collect();
    assert_eq!(ch_u, per_seed);
    for f in ["strength.png", "utilisation.csv"] {
        assert!(out.join(f).exists(), "{f}");
    }
    let again = commands::strength(&study, &out, 1, false).expect("resumed");
    assert!(again.contains("3 runs (3 from an earlier run)"), "{again}");
    let s2 = json(&out.join("summary.json"));
    assert_eq!(s2["storms"], s["storms"]);
}

/// Bad study input is named: a study without a design check anywhere, two equal seeds.
#[test]
fn bad_strength_input_is_named() {
    let d = dir("bad");
    let study = short_study(
        &d,
        "[[storm]]\nid = 7\nhs = 6.0\ntp = 10.0\nseeds = [11, 11]\n",
    );
    let e = commands::strength(&study, &d.join("out"), 1, false)
        .expect_err("equal seeds")
        .to_string();
    assert!(
        e.contains("storms.toml") && e.contains("storm[0].seeds[1]"),
        "{e}"
    );
    let scene = d.join("design-100yr-linear.toml");
    let text = std::fs::read_to_string(&scene).expect("scene");
    let a = text.find("[design_check]").expect("check");
    let b = text.find("[extremes]").expect("extremes");
    std::fs::write(
        &scene,
        format!("{}{}", &text[..a], &text[b..])
            .replace("\"sag_moment\", \"utilisation\"]", "\"sag_moment\"]"),
    )
    .expect("scene");
    std::fs::write(d.join("storms.toml"), STORMS).expect("storms");
    std::fs::write(
        &study,
        "[study]\nscene = \"design-100yr-linear.toml\"\nstorms = \"storms.toml\"\nrecord = 60.0\ntransient = 20.0\n",
    )
    .expect("study");
    let e = commands::strength(&study, &d.join("out"), 1, false)
        .expect_err("no check")
        .to_string();
    assert!(
        e.contains("study.toml") && e.contains("`design_check`"),
        "{e}"
    );
}
