//! `catena run` through the command layer: the /dynamic layout in results.h5, a failed run that
//! keeps its results, restart into the same directory continuing results.h5, SIGTERM and SIGKILL.

#[path = "../../app/tests/common/mod.rs"]
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
            )
            .edit(
                "[dynamic]",
                "[[gauge]]\nname = \"tdz\"\narc = 1190.0\n\n[dynamic]",
            ),
    )
    .expect("case");
    commands::run(&case, &out, &RunCommandOptions::default()).expect("runs");
    // Self-describing: the arc axis, the conventions, and each gauge's arc length.
    {
        let f = hdf5::File::open(out.join("results.h5")).expect("h5");
        let arc = f
            .dataset("dynamic/arc")
            .expect("arc")
            .read_raw::<f64>()
            .expect("arc");
        assert_eq!(arc.len(), 401);
        assert!((arc[400] - 1600.0).abs() < 1e-9);
        let g = f.group("dynamic").expect("dynamic");
        for key in [
            "units",
            "arc",
            "bending_moment",
            "penetration",
            "effective_tension",
        ] {
            let a = g.attr(key).expect(key);
            let v: hdf5::types::VarLenUnicode = a.read_scalar().expect(key);
            assert!(!v.as_str().is_empty(), "{key}");
        }
        let sag: hdf5::types::VarLenUnicode = g
            .attr("bending_moment")
            .expect("attr")
            .read_scalar()
            .expect("sag");
        assert!(sag.as_str().contains("negative in a sag bend"));
        let ga: f64 = f
            .group("dynamic/gauges/tdz")
            .expect("gauge")
            .attr("arc")
            .expect("arc attr")
            .read_scalar()
            .expect("arc");
        assert!((ga - 1190.0).abs() < 1e-9, "{ga}");
    }
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
    // The touchdown track: every record equals the interpolation of its own penetration row, and the
    // summary's range (from every step) contains the recorded one.
    let tdp = f
        .dataset("dynamic/touchdown_arc")
        .expect("touchdown_arc")
        .read_raw::<f64>()
        .expect("tdp");
    assert_eq!(tdp.len(), 51);
    let pen = f
        .dataset("dynamic/penetration")
        .expect("pen")
        .read_2d::<f64>()
        .expect("pen");
    let arc: Vec<f64> = (0..401).map(|i| 4.0 * i as f64).collect();
    for (k, row) in pen.rows().into_iter().enumerate() {
        // Written out here, independently of the library: the first node from the top that
        // penetrates after a clear one, and linear interpolation to zero penetration.
        let i = (1..401)
            .find(|&i| row[i] > 0.0 && row[i - 1] <= 0.0)
            .expect("touches down");
        let want = arc[i - 1] + (arc[i] - arc[i - 1]) * row[i - 1] / (row[i - 1] - row[i]);
        assert!(
            (tdp[k] - want).abs() < 1e-9,
            "record {k}: {} vs {want}",
            tdp[k]
        );
        assert!((1000.0..1300.0).contains(&tdp[k]), "record {k}: {}", tdp[k]);
    }
    let lo = js["dynamic"]["touchdown_arc_min"].as_f64().expect("min");
    let hi = js["dynamic"]["touchdown_arc_max"].as_f64().expect("max");
    let (rlo, rhi) = tdp
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(*x), b.max(*x))
        });
    assert!(
        lo <= rlo && hi >= rhi && hi - lo > 0.5,
        "{lo}..{hi} vs {rlo}..{rhi}"
    );
    for png in ["static.png", "dynamic.png", "ranges.png", "gauges.png"] {
        assert!(std::fs::metadata(out.join(png)).expect(png).len() > 10_000);
    }
}

/// Compression of the float fields is a choice that changes no value: recording every step, the
/// default leaves them uncompressed (the writer could not keep up); `--compress yes` deflates them,
/// and the file reads back to the bit. Time and arc are attached as dimension scales either way.
#[test]
fn compression_changes_no_value() {
    let dir = tmp("compress");
    let case = dir.join("case.toml");
    std::fs::write(
        &case,
        heave_text()
            .edit("duration = 100.0", "duration = 3.0")
            .edit("envelope_start = 50.0", "envelope_start = 0.0"),
    )
    .expect("case");
    let (plain, packed) = (dir.join("plain"), dir.join("packed"));
    commands::run(&case, &plain, &RunCommandOptions::default()).expect("runs");
    commands::run(
        &case,
        &packed,
        &RunCommandOptions {
            compress: Some(true),
            ..RunCommandOptions::default()
        },
    )
    .expect("runs");
    let fa = hdf5::File::open(plain.join("results.h5")).expect("h5");
    let fb = hdf5::File::open(packed.join("results.h5")).expect("h5");
    for (name, _) in catena::run::records::RECORD_FIELDS {
        let (a, b) = (
            fa.dataset(&format!("dynamic/{name}")).expect(name),
            fb.dataset(&format!("dynamic/{name}")).expect(name),
        );
        assert!(a.filters().is_empty(), "{name} compressed by default");
        assert!(!b.filters().is_empty(), "{name} not compressed");
        let (va, vb) = (
            a.read_raw::<f64>().expect(name),
            b.read_raw::<f64>().expect(name),
        );
        assert_eq!(va.len(), 61 * 401, "{name}");
        assert!(
            va.iter().zip(&vb).all(|(x, y)| x.to_bits() == y.to_bits()),
            "{name}"
        );
        for f in [&a, &b] {
            assert_eq!(f.attr("DIMENSION_LIST").expect("dims").shape(), vec![2]);
        }
    }
    let time = fa.dataset("dynamic/time").expect("time");
    assert!(time.attr("CLASS").is_ok() && time.attr("REFERENCE_LIST").is_ok());
}

/// A run whose steps cannot converge (one Newton iteration allowed) cuts the step, then stops with
/// an error that says when (t, step, iteration), where (node, arc length) and by how much (the
/// residual), and keeps its results: the file has the statics and every record up to the last
/// converged step, and summary.json says the run did not complete, how far it got and what the
/// failing step took.
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
    let d = &js["dynamic"];
    assert_eq!(d["completed"], false);
    // The summary of a stopped run: the time it reached, the failing step's cuts and iterations,
    // and null (not 0) for what it never measured.
    assert_eq!(d["time_reached"], 0.0);
    assert_eq!(d["steps"], 0);
    assert_eq!(d["failed_step"]["step"], 1);
    assert_eq!(d["failed_step"]["step_cuts"], 2);
    assert!(
        d["failed_step"]["newton_iterations"]
            .as_u64()
            .expect("iterations")
            >= 3
    );
    assert!(d["stop_reason"]
        .as_str()
        .expect("reason")
        .contains("did not converge"));
    assert!(d["iterations_per_step"].is_null());
    assert!(d["max_moment_range"].is_finite_or_null());
}

trait FiniteOrNull {
    fn is_finite_or_null(&self) -> bool;
}

impl FiniteOrNull for serde_json::Value {
    fn is_finite_or_null(&self) -> bool {
        self.is_null() || self.as_f64().is_some_and(f64::is_finite)
    }
}

fn rq_heave_text() -> String {
    heave_text().edit(
        "model = \"linear\"\nstiffness = 100.0e3           # N/m/m², no friction, no damping",
        "model = \"randolph-quiggin\"\nsu0 = 1000.0\nsu_gradient = 1300.0\na = 6.0\nb = 0.25\nk_max = 200.0\nf_suc = 0.6\nlambda_suc = 1.0\nlambda_rep = 0.3",
    )
}

/// Decimated records on two threads (issue 48): by default they stay uncompressed, so that the
/// writer keeps no core busy and the line steps on two threads beside it; asked to compress, the
/// writer keeps a core and the line steps on one; from three threads they are compressed and the
/// line steps on two. The records are the same to the bit in all three.
#[test]
fn decimated_records_leave_two_threads_to_the_line() {
    let dir = tmp("decimated-threads");
    let case = dir.join("case.toml");
    std::fs::write(
        &case,
        heave_text()
            .edit("duration = 100.0", "duration = 2.0")
            .edit("envelope_start = 50.0", "envelope_start = 0.0")
            .edit(
                "time_step = 0.05",
                "time_step = 0.05\noutput_interval = 0.1",
            ),
    )
    .expect("case");
    let run = |name: &str, threads: usize, compress: Option<bool>| {
        let out = dir.join(name);
        let opts = RunCommandOptions {
            threads: Some(threads),
            compress,
            ..RunCommandOptions::default()
        };
        let text = commands::run(&case, &out, &opts).expect("runs");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("json"))
                .expect("summary");
        let stepping = summary["dynamic"]["stepping_threads"]
            .as_u64()
            .expect("threads");
        // The text says on how many threads the line stepped, and whether the writer compressed.
        let plural = if stepping == 1 { "" } else { "s" };
        assert!(
            text.contains(&format!("s on {stepping} thread{plural}")),
            "{text}"
        );
        let compressing = text.contains("(writing and compressing ");
        let f = hdf5::File::open(out.join("results.h5")).expect("h5");
        let ds = f.dataset("dynamic/bending_moment").expect("moment");
        let packed = !ds.filters().is_empty();
        assert_eq!(compressing, packed, "{text}");
        let bits: Vec<u64> = ds
            .read_raw::<f64>()
            .expect("moment")
            .iter()
            .map(|x| x.to_bits())
            .collect();
        (stepping, packed, bits)
    };
    let (two, packed, bits) = run("two", 2, None);
    assert_eq!((two, packed), (2, false), "two threads, by default");
    assert_eq!(bits.len(), 21 * 401, "21 records of 401 nodes");
    let (one, packed, asked) = run("asked", 2, Some(true));
    assert_eq!((one, packed), (1, true), "two threads, compression asked");
    let (three, packed, wide) = run("three", 3, None);
    assert_eq!((three, packed), (2, true), "three threads, by default");
    assert!(bits == asked && bits == wide, "the records differ");
}

fn tmp(name: &str) -> PathBuf {
    let p = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("run_cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&p);
    std::fs::create_dir_all(&p).expect("dir");
    p
}

/// Every dataset under `/dynamic` (gauges included) of a results file, by name.
fn dynamic_datasets(path: &Path) -> Vec<(String, Vec<f64>)> {
    let f = hdf5::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut out = Vec::new();
    let g = f.group("dynamic").expect("dynamic");
    for name in g.member_names().expect("names") {
        if let Ok(ds) = g.dataset(&name) {
            let v: Vec<f64> = if name == "seabed_mode" {
                ds.read_raw::<u8>()
                    .expect("modes")
                    .into_iter()
                    .map(f64::from)
                    .collect()
            } else {
                ds.read_raw::<f64>().expect("data")
            };
            out.push((name, v));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).expect("json"))
        .expect("json")
}

/// A restart into the same `--out` continues `results.h5`: a run stopped at step 120 (checkpoints
/// every 37 steps, so the last one is at step 111 and the file holds 9 records beyond it) and then
/// restarted from its checkpoint ends with a results file whose every `/dynamic` dataset is
/// bit-identical to that of the uninterrupted run, and a summary (envelopes, gauges, extremes,
/// iteration counts since the restart aside) identical too.
#[test]
fn restart_into_the_same_directory_continues_the_results_file() {
    let dir = tmp("restart");
    let case = dir.join("rq-heave.toml");
    std::fs::write(
        &case,
        rq_heave_text()
            .edit("duration = 100.0", "duration = 10.0")
            .edit("envelope_start = 50.0", "envelope_start = 2.0"),
    )
    .expect("case");
    let (full, cut) = (dir.join("full"), dir.join("cut"));
    commands::run(&case, &full, &RunCommandOptions::default()).expect("uninterrupted");
    commands::run(
        &case,
        &cut,
        &RunCommandOptions {
            checkpoint_every: Some(37),
            stop_after: Some(120),
            ..RunCommandOptions::default()
        },
    )
    .expect("stopped at 120");
    assert_eq!(summary(&cut)["dynamic"]["completed"], false);
    assert_eq!(summary(&cut)["dynamic"]["steps"], 120);
    commands::run(
        &case,
        &cut,
        &RunCommandOptions {
            checkpoint_every: Some(37),
            restart: Some(cut.join("checkpoint.json")),
            ..RunCommandOptions::default()
        },
    )
    .expect("restarted");
    let (a, b) = (
        dynamic_datasets(&full.join("results.h5")),
        dynamic_datasets(&cut.join("results.h5")),
    );
    assert_eq!(a.len(), b.len());
    for ((na, va), (nb, vb)) in a.iter().zip(&b) {
        assert_eq!(na, nb);
        assert_eq!(va.len(), vb.len(), "{na}: length");
        assert!(va == vb, "{na}: values differ");
    }
    let time = a.iter().find(|(n, _)| n == "time").expect("time");
    assert_eq!(time.1.len(), 201, "every record of the 10 s run");
    let (sa, sb) = (summary(&full), summary(&cut));
    assert_eq!(sb["dynamic"]["completed"], true);
    for key in [
        "envelopes",
        "gauges",
        "top_tension_min",
        "top_tension_max",
        "max_moment_range",
        "steps",
        "time_reached",
        "envelope_steps",
    ] {
        assert_eq!(sa["dynamic"][key], sb["dynamic"][key], "{key}");
    }
}

/// A storm's record re-synthesises exactly from what results.h5 holds: with `/waves/omega`,
/// `wavenumber`, `amplitude`, `phase`, the ramp and the RAO table, the wave elevation at the RAO origin
/// and the hang-off's position (surge + pitch·Δz, heave − pitch·Δx, ramped) equal the recorded
/// `wave_elevation`, `top_x` and `top_z` to 1e-9 m at every record. The sea plot is drawn.
#[test]
fn a_storm_resynthesises_from_its_recorded_components() {
    let dir = tmp("storm");
    let text = common::short_storm23(&root());
    std::fs::copy(
        root().join("cases/scr1000/semi-rao.csv"),
        dir.join("semi-rao.csv"),
    )
    .expect("RAO table beside the case");
    let case = dir.join("storm.toml");
    std::fs::write(&case, text).expect("case");
    let out = dir.join("out");
    commands::run(&case, &out, &RunCommandOptions::default()).expect("runs");
    assert!(
        std::fs::metadata(out.join("sea.png"))
            .expect("sea.png")
            .len()
            > 10_000
    );
    let f = hdf5::File::open(out.join("results.h5")).expect("h5");
    let read = |name: &str| -> Vec<f64> {
        f.dataset(name)
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .read_raw::<f64>()
            .expect("data")
    };
    let (om, k, a, ph) = (
        read("waves/omega"),
        read("waves/wavenumber"),
        read("waves/amplitude"),
        read("waves/phase"),
    );
    assert_eq!(om.len(), 400);
    let ramp: f64 = f
        .group("waves")
        .expect("waves")
        .attr("ramp")
        .expect("ramp")
        .read_scalar::<f64>()
        .expect("ramp, a number");
    let table = catena_fe::vessel::RaoTable::parse_csv(
        &std::fs::read_to_string(root().join("cases/scr1000/semi-rao.csv")).expect("rao"),
    )
    .expect("table");
    let (t, eta, tx, tz) = (
        read("dynamic/time"),
        read("dynamic/wave_elevation"),
        read("dynamic/top_x"),
        read("dynamic/top_z"),
    );
    let (x0, z0) = (read("static/x")[0], read("static/z")[0]);
    let (dx, dz) = (-38.0, -20.0);
    let xo = x0 - dx;
    let raos: Vec<_> = om.iter().map(|w| table.at(*w)).collect();
    for (i, &ti) in t.iter().enumerate() {
        let (r, _, _) = catena_fe::motion::quintic_ramp(ti, ramp);
        let (mut e, mut m) = (0.0, [0.0; 3]);
        for j in 0..om.len() {
            let psi = om[j] * ti - k[j] * xo + ph[j];
            let (s, c) = psi.sin_cos();
            e += a[j] * c;
            for (q, mq) in m.iter_mut().enumerate() {
                let (re, im) = raos[j][q];
                *mq += a[j] * (re * c - im * s);
            }
        }
        let (x, z) = (r * (m[0] + m[2] * dz), r * (m[1] - m[2] * dx));
        assert!((eta[i] - r * e).abs() < 1e-9, "η at {ti}");
        assert!(
            (tx[i] - x0 - x).abs() < 1e-9,
            "top_x at {ti}: {} vs {x}",
            tx[i] - x0
        );
        assert!((tz[i] - z0 - z).abs() < 1e-9, "top_z at {ti}");
    }
    for name in ["dynamic/top_pitch", "dynamic/top_axial_motion"] {
        assert_eq!(read(name).len(), t.len(), "{name}");
    }
}

/// Fatigue as an observer equals counting afterwards: a 40 s storm with every step recorded; at the
/// node of the largest damage (and at a node 100 m away) the damage `catena run` reports in
/// `/fatigue/damage_outer` equals the damage of the stresses recomputed from the recorded tension,
/// moment and height (top and bottom fibre, ASTM counting, DNV E in seawater, SCF 1.2, thickness
/// correction 1.00318), to 1e-9.
#[test]
fn fatigue_observer_equals_counting_the_records() {
    let dir = tmp("fatigue");
    let text = std::fs::read_to_string(root().join("cases/scr1000/storm23.toml"))
        .expect("case")
        .edit("duration = 1800.0 ", "duration = 40.0 ")
        .edit("envelope_start = 200.0 ", "envelope_start = 20.0 ")
        .edit("start = 200.0 ", "start = 20.0 ")
        .edit("ramp = 100.0 ", "ramp = 10.0 ")
        .edit("output_interval = 0.5 ", "output_interval = 0.05 ");
    std::fs::copy(
        root().join("cases/scr1000/semi-rao.csv"),
        dir.join("semi-rao.csv"),
    )
    .expect("rao");
    let case = dir.join("storm.toml");
    std::fs::write(&case, text).expect("case");
    let out = dir.join("out");
    commands::run(&case, &out, &RunCommandOptions::default()).expect("runs");
    let f = hdf5::File::open(out.join("results.h5")).expect("h5");
    let damage = f
        .dataset("fatigue/damage_outer")
        .expect("damage")
        .read_raw::<f64>()
        .expect("d");
    let (te, bm, z) = (
        f.dataset("dynamic/effective_tension")
            .expect("te")
            .read_2d::<f64>()
            .expect("te"),
        f.dataset("dynamic/bending_moment")
            .expect("m")
            .read_2d::<f64>()
            .expect("m"),
        f.dataset("dynamic/z")
            .expect("z")
            .read_2d::<f64>()
            .expect("z"),
    );
    let t = f
        .dataset("dynamic/time")
        .expect("t")
        .read_raw::<f64>()
        .expect("t");
    let imax = damage
        .iter()
        .enumerate()
        .fold((0, 0.0), |b, (i, d)| if *d > b.1 { (i, *d) } else { b })
        .0;
    let (od, wall) = (0.228f64, 0.0254f64);
    let pi = std::f64::consts::PI;
    let id = od - 2.0 * wall;
    let (a, inertia) = (
        pi / 4.0 * (od * od - id * id),
        pi / 64.0 * (od.powi(4) - id.powi(4)),
    );
    let curve = catena::fatigue::sn::SnCurve::dnv("dnv-e-seawater-cp").expect("curve");
    let factor = 1.2 * (wall / 0.025f64).powf(0.2);
    for node in [imax, imax.saturating_sub(200)] {
        let mut d_side = [0.0f64; 2];
        for (side, sign) in [(0, -1.0), (1, 1.0)] {
            let sigma: Vec<f64> = (0..t.len())
                .filter(|k| t[*k] >= 20.0 - 1e-9)
                .map(|k| {
                    let head = 1000.0 - z[[k, node]];
                    let dw = 726.0 * 9.80665 * head * pi / 4.0 * id * id
                        - 1025.0 * 9.80665 * head * pi / 4.0 * od * od;
                    ((te[[k, node]] + dw) / a + sign * bm[[k, node]] * 0.5 * od / inertia) * 1e-6
                })
                .collect();
            let cycles = catena::fatigue::rainflow::count(&sigma);
            d_side[side] = catena::fatigue::sn::miner(
                cycles.iter().map(|c| (c.range, c.count)),
                &curve,
                factor,
            );
        }
        let offline = d_side[0].max(d_side[1]);
        println!(
            "node {node}: observer {:.6e}, from the records {offline:.6e}",
            damage[node]
        );
        assert!((damage[node] / offline - 1.0).abs() < 1e-9, "node {node}");
    }
}

/// The design check's outputs: `/design_check/utilisation` holds one row per record (every step
/// here) and one column per node, and each node's `utilisation_max` is its column's largest (the
/// check starts at 0); `summary.json` has the largest, where and when, and pass; `design_check.png`
/// is drawn. A run stopped at step 120 and restarted from its step-111 checkpoint into the same
/// directory ends with the same utilisation records and per-node results to the bit. With
/// `[extremes]`: the same after the restart, and `catena extremes results.h5` gives the run's own.
/// With `[fatigue]` (two fibres, from 1 s): the damage the same after the restart.
#[test]
fn design_check_is_recorded_and_restarts_bit_for_bit() {
    let dir = tmp("design");
    let case = dir.join("check.toml");
    std::fs::write(
        &case,
        rq_heave_text()
            .edit(
                "mass = 145.06 ",
                "wall = 0.0254\ncontents_density = 726.0\nmass = 145.06 ",
            )
            .edit("duration = 100.0", "duration = 10.0")
            .edit("envelope_start = 50.0", "envelope_start = 2.0")
            + "\n[design_check]\ncode = \"dnv-st-f201\"\nsmys = 448e6\nsmts = 531e6\ninternal_pressure = 15e6\nstart = 0.0\n\n[extremes]\nstart = 2.0\nblock = 1.0\ntarget_duration = 600.0\n\n[fatigue]\nsn_curve = \"dnv-e-seawater-cp\"\nscf = 1.2\nfibres = [\"outer\", \"inner\"]\nstart = 1.0\n",
    )
    .expect("case");
    let (full, cut) = (dir.join("full"), dir.join("cut"));
    commands::run(&case, &full, &RunCommandOptions::default()).expect("uninterrupted");
    commands::run(
        &case,
        &cut,
        &RunCommandOptions {
            checkpoint_every: Some(37),
            stop_after: Some(120),
            ..RunCommandOptions::default()
        },
    )
    .expect("stopped at 120");
    commands::run(
        &case,
        &cut,
        &RunCommandOptions {
            checkpoint_every: Some(37),
            restart: Some(cut.join("checkpoint.json")),
            ..RunCommandOptions::default()
        },
    )
    .expect("restarted");
    let dataset = |dir: &Path, path: &str| -> Vec<f64> {
        hdf5::File::open(dir.join("results.h5"))
            .expect("h5")
            .dataset(path)
            .unwrap_or_else(|e| panic!("{path}: {e}"))
            .read_raw::<f64>()
            .expect("data")
    };
    let read = |dir: &Path, name: &str| dataset(dir, &format!("design_check/{name}"));
    let u = read(&full, "utilisation");
    let umax = read(&full, "utilisation_max");
    let n = umax.len();
    assert_eq!(n, 401);
    assert_eq!(u.len(), 201 * n, "one row per record");
    for i in 0..n {
        let col = (0..201).map(|k| u[k * n + i]).fold(0.0, f64::max);
        assert_eq!(col, umax[i], "node {i}");
    }
    for name in [
        "utilisation",
        "utilisation_max",
        "time_of_max",
        "least_effective_tension",
    ] {
        assert!(
            read(&full, name) == read(&cut, name),
            "{name} after restart"
        );
    }
    // The fatigue damage (counted on its own thread, drained into each checkpoint and restored
    // from the one at step 111): the same to the bit.
    let fatigue = |dir: &Path, fibre: &str| dataset(dir, &format!("fatigue/damage_{fibre}"));
    for fibre in ["outer", "inner"] {
        let d = fatigue(&full, fibre);
        assert_eq!(d.len(), 401);
        assert!(d.iter().any(|x| *x > 0.0), "{fibre}: no damage counted");
        assert!(d == fatigue(&cut, fibre), "{fibre} damage after restart");
    }
    let s = summary(&full);
    let c = &s["design_check"];
    assert_eq!(c["code"], "dnv-st-f201");
    assert_eq!(c["passes"], true);
    let largest = c["max_utilisation"].as_f64().expect("largest");
    assert_eq!(largest, umax.iter().copied().fold(0.0, f64::max));
    assert_eq!(summary(&cut)["design_check"], c.clone());
    assert!(full.join("design_check.png").exists());
    // The extremes: the same after the restart (their records travel with the checkpoint), and
    // `catena extremes` of the results file (recorded every step) gives the run's own, to the bit.
    let ext = |dir: &Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(dir.join("extremes.json")).expect("json"))
            .expect("json")
    };
    let in_run = ext(&full);
    assert_eq!(in_run.as_array().map(Vec::len), Some(4));
    assert_eq!(ext(&cut), in_run);
    assert_eq!(s["extremes"], in_run);
    let post = dir.join("post");
    let text = commands::extremes(
        &full.join("results.h5"),
        &post,
        &commands::ExtremesOptions {
            channels: Vec::new(),
            start: Some(2.0),
            settings: catena::extremes::Settings {
                target: 600.0,
                quantile: 0.9,
                block: 1.0,
            },
        },
    )
    .expect("extremes of the file");
    assert!(text.contains("utilisation"), "{text}");
    // In the units of the other outputs, not raw SI: tensions in kN, moments in kN·m.
    let top = text
        .lines()
        .find(|l| l.contains("extremes of top_tension"))
        .expect("top_tension");
    assert!(top.contains(" kN;") && !top.contains("e6"), "{top}");
    let sag = text
        .lines()
        .find(|l| l.contains("extremes of sag_moment"))
        .expect("sag_moment");
    assert!(sag.contains(" kN·m;"), "{sag}");
    assert_eq!(ext(&post), in_run);
    assert!(post.join("extremes.png").exists() && full.join("extremes.png").exists());
    // At the critical node (the largest utilisation over the run): its utilisation and moment
    // columns of the records, from t = 2 s.
    let crit = dir.join("crit");
    commands::extremes(
        &full.join("results.h5"),
        &crit,
        &commands::ExtremesOptions {
            channels: vec![
                "utilisation_at_critical".into(),
                "moment_at_critical".into(),
            ],
            start: Some(2.0),
            settings: catena::extremes::Settings {
                target: 600.0,
                quantile: 0.9,
                block: 1.0,
            },
        },
    )
    .expect("critical node");
    let c = ext(&crit);
    let i = umax
        .iter()
        .enumerate()
        .fold(0, |b, (i, v)| if *v > umax[b] { i } else { b });
    let moments = hdf5::File::open(full.join("results.h5"))
        .expect("h5")
        .dataset("dynamic/bending_moment")
        .expect("moment")
        .read_raw::<f64>()
        .expect("moment");
    let col = |v: &[f64]| -> Vec<f64> { (40..201).map(|k| v[k * n + i]).collect() };
    let u_crit = col(&u).into_iter().fold(0.0, f64::max);
    let m_col = col(&moments);
    let m_least = m_col.iter().copied().fold(f64::INFINITY, f64::min);
    assert_eq!(c[0]["sample_extreme"].as_f64(), Some(u_crit));
    assert_eq!(c[1]["tail"], "min", "the critical node is in the sag bend");
    assert_eq!(c[1]["sample_extreme"].as_f64(), Some(m_least));
    // A channel the file cannot give: an error naming the file and the channel.
    let e = commands::extremes(
        &full.join("results.h5"),
        &post,
        &commands::ExtremesOptions {
            channels: vec!["gauge:nowhere".into()],
            ..commands::ExtremesOptions::default()
        },
    )
    .expect_err("no such gauge")
    .to_string();
    assert!(
        e.contains("results.h5") && e.contains("gauge:nowhere"),
        "{e}"
    );
}

/// A results file that cannot be created (its name a link into a folder that does not exist) stops
/// the run with an error naming it. The file is created on the recorder's writer thread while the
/// run steps, so the run stops at its first hand-over of records, not at step 2000.
#[test]
fn a_results_file_that_cannot_be_created_stops_the_run_naming_it() {
    let out = tmp("uncreatable");
    let h5 = out.join("results.h5");
    std::os::unix::fs::symlink("/nonexistent-catena-folder/results.h5", &h5).expect("link");
    let case = out.join("heave.toml");
    std::fs::write(&case, heave_text()).expect("case");
    let t0 = std::time::Instant::now();
    let err = commands::run(&case, &out, &RunCommandOptions::default())
        .expect_err("no results file")
        .to_string();
    println!("{err} ({:.2} s)", t0.elapsed().as_secs_f64());
    assert!(err.contains("results.h5") && err.contains("HDF5"), "{err}");
    assert!(
        t0.elapsed().as_secs_f64() < 5.0,
        "the run went on without its file"
    );
}
