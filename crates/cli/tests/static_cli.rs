//! `catena static`: output files, the HDF5 layout other programs read, and bad input.

#[path = "../../app/tests/common/mod.rs"]
mod common;
use common::Edit;

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("static_cli");
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}

/// The heave benchmark's statics: results.h5 with the /static layout and units, summary.json,
/// static.png; the numbers in the file agree with the summary.
#[test]
fn heave_benchmark_static_outputs() {
    let out = tmp("scr-heave");
    let text = catena_cli::commands::static_(&root().join("cases/benchmarks/scr-heave.toml"), &out)
        .expect("runs");
    assert!(text.contains("top tension"));
    let f = hdf5::File::open(out.join("results.h5")).expect("h5");
    let n = 401;
    let read = |name: &str| -> Vec<f64> {
        let ds = f.dataset(&format!("static/{name}")).expect(name);
        let units: hdf5::types::VarLenUnicode = ds
            .attr("units")
            .expect("units")
            .read_scalar()
            .expect("units");
        assert!(!units.as_str().is_empty());
        ds.read_raw::<f64>().expect("data")
    };
    let arc = read("arc");
    assert_eq!(arc.len(), n);
    assert_eq!(arc[0], 0.0);
    assert!((arc[n - 1] - 1600.0).abs() < 1e-9);
    for name in [
        "x",
        "z",
        "effective_tension",
        "bending_moment",
        "penetration",
        "seabed_force",
    ] {
        assert_eq!(read(name).len(), n, "{name}");
    }
    let z = read("z");
    assert!((z[0] - 1000.0).abs() < 1e-9, "top at the still water line");
    let pen = read("penetration");
    let sbf = read("seabed_force");
    for i in 0..n {
        if pen[i] <= 0.0 {
            assert_eq!(sbf[i], 0.0);
        } else {
            // Linear seabed: F = k·D·z.
            assert!((sbf[i] - 100e3 * 0.2286 * pen[i]).abs() < 1e-6 * sbf[i].max(1.0));
        }
    }
    let m = read("bending_moment");
    let min = m.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(min < -70e3 && min > -90e3, "sag moment {min}");
    let scene: hdf5::types::VarLenUnicode =
        f.attr("scene").expect("scene").read_scalar().expect("text");
    assert!(scene.as_str().contains("[line]"));
    let js: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("json"))
            .expect("json");
    let t = js["static"]["top_tension"].as_f64().expect("top tension");
    assert!(t > 1.2e6 && t < 1.25e6, "{t}");
    assert!(
        js["static"]["relative_residual"]
            .as_f64()
            .expect("residual")
            <= 1e-8
    );
    assert!(
        std::fs::metadata(out.join("static.png"))
            .expect("png")
            .len()
            > 10_000
    );
}

fn run_bad(name: &str, text: &str) -> String {
    let path = tmp(name);
    std::fs::write(&path, text).expect("write");
    let out = Command::new(env!("CARGO_BIN_EXE_catena"))
        .arg("static")
        .arg(&path)
        .arg("--out")
        .arg(tmp(&format!("{name}.out")))
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "{name} must fail");
    assert!(!err.contains("panicked"), "{name} panicked: {err}");
    assert!(err.contains(name), "{name}: must name the file: {err}");
    err
}

/// Bad scenes: each message names the file and the key.
#[test]
fn bad_scenes_name_file_and_key() {
    let good =
        std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml")).expect("case");
    let cases: Vec<(&str, String, &[&str])> = vec![
        (
            "short_line.toml",
            good.edit("length = 1600.0", "length = 1000.0")
                .edit("to = 1600.0", "to = 1000.0"),
            &["line.length", "distance between the ends"],
        ),
        (
            "mesh_short.toml",
            good.edit("to = 1600.0", "to = 1500.0"),
            &["mesh[0].to", "1600"],
        ),
        (
            "unknown_key.toml",
            good.edit("[line]", "[line]\ncolour = 1.0"),
            &["colour"],
        ),
        (
            "neg_ei.toml",
            good.edit("ei = 17.59e6", "ei = -1.0"),
            &["line.ei"],
        ),
        (
            "missing_weight.toml",
            good.edit("submerged_weight = 1010.0", ""),
            &["line.submerged_weight"],
        ),
        (
            "bad_seabed.toml",
            good.edit("stiffness = 100.0e3", "stiffness = 100.0e3\nk_max = 3.0"),
            &["seabed.k_max"],
        ),
        (
            "bad_support.toml",
            good.edit("anchor_x = 0.0", "anchor_x = 0.0\ntop = \"glued\""),
            &["glued", "pinned"],
        ),
        (
            "no_env.toml",
            good.edit("[environment]", "[environmnt]"),
            &["environmnt"],
        ),
        (
            "bad_flexjoint.toml",
            format!("{good}\n[flexjoint]\nstiffness = -5.0\n"),
            &["flexjoint.stiffness"],
        ),
    ];
    for (name, text, needles) in cases {
        let err = run_bad(name, &text);
        for n in needles {
            assert!(err.contains(n), "{name}: expected `{n}` in: {err}");
        }
    }
}

/// A static solve that cannot converge (one Newton iteration allowed) cuts its load increments and
/// then reports the load factor, iteration, residual, node and arc length, naming the file.
#[test]
fn static_non_convergence_is_reported_with_context() {
    let good =
        std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml")).expect("case");
    let text = format!("{good}\n[static]\nmax_iterations = 1\n");
    let err = run_bad("no_converge.toml", &text);
    for needle in [
        "did not converge",
        "load factor",
        "iteration",
        "relative residual",
        "node",
        "arc length",
    ] {
        assert!(err.contains(needle), "`{needle}` missing from: {err}");
    }
}
