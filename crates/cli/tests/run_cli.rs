//! `catena run` through the command layer: the /dynamic layout in results.h5, a failed run that
//! keeps its results, restart into the same directory continuing results.h5, SIGTERM and SIGKILL.

mod common;
use common::Edit;

use std::path::{Path, PathBuf};

use catena_cli::commands::{self, RunCommandOptions};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn heave_text() -> String {
    std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml")).expect("case")
}

/// `catena run` writes the /dynamic layout: time series of n_t and fields of n_t × n_nodes.
#[test]
fn run_writes_dynamic_layout() {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("dyn_layout");
    let case = Path::new(env!("CARGO_TARGET_TMPDIR")).join("dyn_layout.toml");
    std::fs::write(
        &case,
        heave_text()
            .edit("duration = 100.0", "duration = 5.0")
            .edit(
                "envelope_start = 50.0",
                "envelope_start = 0.0\noutput_interval = 0.1",
            ),
    )
    .expect("case");
    commands::run(&case, &out, &RunCommandOptions::default()).expect("runs");
    let f = hdf5::File::open(out.join("results.h5")).expect("h5");
    let t = f
        .dataset("dynamic/time")
        .expect("time")
        .read_raw::<f64>()
        .expect("t");
    assert_eq!(t.len(), 51);
    assert!((t[50] - 5.0).abs() < 1e-9);
    for name in [
        "x",
        "z",
        "effective_tension",
        "bending_moment",
        "penetration",
        "seabed_force",
        "seabed_mode",
    ] {
        let ds = f.dataset(&format!("dynamic/{name}")).expect(name);
        assert_eq!(ds.shape(), vec![51, 401], "{name}");
    }
    let top_z = f
        .dataset("dynamic/top_z")
        .expect("top_z")
        .read_raw::<f64>()
        .expect("z");
    // z = 1000 + 2·r(t)·sin(2πt/10) at t = 5 s (r(0.5) = 0.5): sin(π) = 0.
    assert!((top_z[50] - 1000.0).abs() < 1e-9);
    assert!((top_z[25] - (1000.0 + 2.0 * 0.5f64.powi(3) * (10.0 - 7.5 + 1.5) * 0.0)).abs() < 1.0);
    let js: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("json"))
            .expect("json");
    assert_eq!(js["dynamic"]["completed"], true);
    for key in [
        "moment_min",
        "moment_max",
        "moment_range",
        "tension_min",
        "tension_max",
        "tension_range",
    ] {
        let v = js["dynamic"]["envelopes"][key].as_array().expect(key);
        assert_eq!(v.len(), 401, "{key}");
    }
    for png in ["static.png", "dynamic.png"] {
        assert!(std::fs::metadata(out.join(png)).expect(png).len() > 10_000);
    }
}

/// A run whose steps cannot converge (one Newton iteration allowed) cuts the step, then stops with
/// an error that says when (t, step, iteration), where (node, arc length) and by how much (the
/// residual), and keeps its results: the file has the statics and every record up to the last
/// converged step, and summary.json says the run did not complete.
#[test]
fn failed_run_reports_context_and_keeps_results() {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("dyn_fail");
    let case = Path::new(env!("CARGO_TARGET_TMPDIR")).join("dyn_fail.toml");
    let text = heave_text()
        .edit("duration = 100.0", "duration = 5.0")
        .edit(
            "envelope_start = 50.0",
            "envelope_start = 0.0\nmax_iterations = 1\nmax_step_cuts = 2",
        );
    std::fs::write(&case, text).expect("case");
    let err = commands::run(&case, &out, &RunCommandOptions::default())
        .expect_err("cannot converge")
        .to_string();
    println!("{err}");
    for needle in [
        "dyn_fail.toml",
        "did not converge after 2 step cuts",
        "t = ",
        "step 1",
        "iteration",
        "relative residual",
        "node",
        "arc length",
        "results up to the last converged step",
    ] {
        assert!(err.contains(needle), "`{needle}` missing from: {err}");
    }
    let f = hdf5::File::open(out.join("results.h5")).expect("h5 kept");
    assert_eq!(f.dataset("static/arc").expect("static").shape(), vec![401]);
    assert_eq!(f.dataset("dynamic/time").expect("time").shape(), vec![1]);
    let js: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("json"))
            .expect("json");
    assert_eq!(js["dynamic"]["completed"], false);
}
