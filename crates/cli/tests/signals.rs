//! `catena run` under signals: SIGTERM (and SIGINT) end the run at the next step with everything
//! kept; SIGKILL leaves a readable results file. In a test binary of their own: the child processes
//! they spawn would otherwise inherit (and keep locked) the HDF5 files other tests of the same
//! process have open.

#[path = "../../app/tests/common/mod.rs"]
mod common;
use common::Edit;

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn heave_text() -> String {
    std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml")).expect("case")
}

fn tmp(name: &str) -> PathBuf {
    let p = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("signals")
        .join(name);
    let _ = std::fs::remove_dir_all(&p);
    std::fs::create_dir_all(&p).expect("dir");
    p
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).expect("json"))
        .expect("json")
}

/// Waits (up to 60 s) until the run has written records to `h5` (the file passes 2 MB).
fn wait_for_records(h5: &Path) {
    let t0 = std::time::Instant::now();
    while !(h5.exists() && std::fs::metadata(h5).map(|m| m.len()).unwrap_or(0) > 2_000_000) {
        assert!(t0.elapsed().as_secs() < 60, "no records after 60 s");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// Waits until the results file, read while the run writes it, holds more than `n` records (its
/// last flushed state: the writer flushes each batch); returns how many. The file is read without
/// HDF5's file lock (the writer holds it), and a read that meets the file between flushes is tried
/// again.
fn wait_for_readable_records(h5: &Path, n: usize) -> usize {
    let t0 = std::time::Instant::now();
    loop {
        assert!(t0.elapsed().as_secs() < 120, "no {n} records after 120 s");
        let read = hdf5::File::open(h5).ok().and_then(|f| {
            f.dataset("dynamic/time")
                .ok()
                .map(|d| d.shape().first().copied().unwrap_or(0))
        });
        match read {
            Some(k) if k > n => return k,
            _ => std::thread::sleep(std::time::Duration::from_millis(20)),
        }
    }
}

/// The two cases run one after the other (one test), so that neither child inherits the other's
/// open files. The results files are read while their runs write them: without HDF5's file locks.
#[test]
fn signals() {
    // Read at the first open of a file; set before any (the only thread of this test program).
    std::env::set_var("HDF5_USE_FILE_LOCKING", "FALSE");
    sigterm_stops_at_the_next_step_and_keeps_everything();
    sigkill_leaves_a_readable_results_file();
}

/// SIGTERM ends the run at the next step: the process exits with an error that says so, the
/// records are flushed (every one up to the time reached), and summary.json says
/// `"completed": false`, the reason, and the time actually reached; values the run never measured
/// (here its envelope window starts after the stop) are null, not 0.
fn sigterm_stops_at_the_next_step_and_keeps_everything() {
    let dir = tmp("sigterm");
    let case = dir.join("long.toml");
    std::fs::write(
        &case,
        heave_text()
            .edit("duration = 100.0", "duration = 3000.0")
            // every step recorded (a 60 000-step run would otherwise record every 0.3 s)
            .edit(
                "envelope_start = 50.0",
                "output_interval = 0.05\nenvelope_start = 2900.0",
            ),
    )
    .expect("case");
    let out = dir.join("out");
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_catena"))
        .args(["run", "--quiet", "--out"])
        .arg(&out)
        .arg(&case)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spawn");
    // Wait until the dynamics have written records, then send SIGTERM.
    let h5 = out.join("results.h5");
    wait_for_records(&h5);
    let status = std::process::Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(status.success());
    let res = child.wait_with_output().expect("exits");
    let err = String::from_utf8_lossy(&res.stderr);
    println!("{err}");
    assert!(!res.status.success());
    assert!(
        err.contains("SIGINT or SIGTERM") && !err.contains("panicked"),
        "{err}"
    );
    let js = summary(&out);
    let d = &js["dynamic"];
    assert_eq!(d["completed"], false);
    assert!(d["stop_reason"]
        .as_str()
        .expect("reason")
        .contains("SIGTERM"));
    let reached = d["time_reached"].as_f64().expect("time reached");
    assert!(reached > 0.0 && reached < 3000.0, "{reached}");
    assert!(d["top_tension_max"].is_null() && d["max_moment_range"].is_null());
    let t = hdf5::File::open(&h5)
        .expect("h5")
        .dataset("dynamic/time")
        .expect("time")
        .read_raw::<f64>()
        .expect("t");
    assert!(
        (t[t.len() - 1] - reached).abs() < 1e-9,
        "last record at the time reached"
    );
    assert_eq!(t.len() as f64, (reached / 0.05).round() + 1.0);
}

/// A run killed outright (SIGKILL) leaves a readable results.h5: `/static` complete and the
/// records written up to shortly before the kill, in order, without gaps.
fn sigkill_leaves_a_readable_results_file() {
    let dir = tmp("sigkill");
    let case = dir.join("long.toml");
    std::fs::write(
        &case,
        heave_text()
            .edit("duration = 100.0", "duration = 3000.0")
            .edit(
                "envelope_start = 50.0",
                "output_interval = 0.05\nenvelope_start = 50.0",
            ),
    )
    .expect("case");
    let out = dir.join("out");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_catena"))
        .args(["run", "--quiet", "--out"])
        .arg(&out)
        .arg(&case)
        .spawn()
        .expect("spawn");
    let h5 = out.join("results.h5");
    // Killed once more than 100 records can be read back from the file as the writer left it
    // (however fast the machine steps), so the file must hold at least those after the kill.
    let before = wait_for_readable_records(&h5, 100);
    child.kill().expect("SIGKILL");
    let _ = child.wait();
    let f = hdf5::File::open(&h5).expect("readable after SIGKILL");
    assert_eq!(
        f.dataset("static/arc")
            .expect("static")
            .read_raw::<f64>()
            .expect("arc")
            .len(),
        401
    );
    let t = f
        .dataset("dynamic/time")
        .expect("time")
        .read_raw::<f64>()
        .expect("t");
    let x = f.dataset("dynamic/x").expect("x");
    assert!(
        t.len() >= before,
        "{} records, {before} before the kill",
        t.len()
    );
    assert_eq!(x.shape()[0], t.len());
    for (k, w) in t.windows(2).enumerate() {
        assert!((w[1] - w[0] - 0.05).abs() < 1e-9, "gap after record {k}");
    }
    println!(
        "killed at t = {} s of simulated time, {} records",
        t[t.len() - 1],
        t.len()
    );
}
