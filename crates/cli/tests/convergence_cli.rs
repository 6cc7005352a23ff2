//! `catena convergence`: the study on a shortened heave benchmark. The Richardson estimate from the
//! mesh series must predict a finer run it did not see; the errors must shrink with refinement; the
//! values must not depend on how many runs go at once; and the files must be written.

#[path = "../../app/tests/common/mod.rs"]
mod common;
use common::Edit;

use std::path::{Path, PathBuf};

use catena::convergence::{self, ConvergenceOptions, Series};
use catena::scene::riser::RiserScene;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The heave benchmark cut to 30 s (ranges from 15 s) with Δt = 0.1 s (4 m elements as written: 8 m
/// and coarser are outside the asymptotic range, the touchdown boundary layer √(EI/H) being 9 m).
fn short_heave(dir: &Path) -> PathBuf {
    let text =
        std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml")).expect("case");
    let text = text
        .edit("duration = 100.0 ", "duration = 30.0 ")
        .edit("time_step = 0.05 ", "time_step = 0.1 ")
        .edit("envelope_start = 50.0 ", "envelope_start = 15.0 ");
    assert!(text.contains("time_step = 0.1 ") && text.contains("duration = 30.0"));
    std::fs::create_dir_all(dir).expect("dir");
    let p = dir.join("short-heave.toml");
    std::fs::write(&p, text).expect("write");
    p
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("catena-conv-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn richardson_predicts_a_finer_mesh_and_errors_shrink() {
    let dir = tmp("richardson");
    let case = short_heave(&dir);
    let opts = ConvergenceOptions {
        mesh_factors: vec![2.0, 1.0, 0.5],
        dt_factors: vec![2.0, 1.0, 0.5],
        jobs: 1,
        progress: false,
    };
    let st = convergence::study(&case, &opts).expect("study");
    assert_eq!(st.runs.len(), 5, "base + 2 mesh + 2 dt runs");
    assert!(st.runs.iter().all(|r| r.error.is_none()));
    assert_eq!(st.outputs[0].id, "tdz_moment_range");
    let (mesh, dt) = &st.analyses[0];
    println!("mesh: {mesh:?}\ndt: {dt:?}");
    // Errors shrink as the mesh is refined.
    let e = &mesh.errors_percent;
    assert!(e[0].abs() > e[1].abs() && e[1].abs() > e[2].abs(), "{e:?}");
    let p = mesh.order.expect("monotone mesh convergence");
    assert!((1.0..=6.0).contains(&p), "observed order {p}");
    // A finer run the study did not see (1 m elements) lands within 0.2 % of the estimate from the
    // 8, 4 and 2 m runs (the 4 m run itself is 1 % off on the full benchmark).
    let f = mesh.extrapolated.expect("Richardson");
    let finer = convergence::study(
        &case,
        &ConvergenceOptions {
            mesh_factors: vec![0.25],
            dt_factors: vec![1.0],
            ..opts.clone()
        },
    )
    .expect("finer");
    let v = finer
        .series(Series::Mesh)
        .iter()
        .find(|r| r.mesh_factor == 0.25)
        .expect("x0.25")
        .values[0];
    println!("Richardson {f:.4} kN·m, 1 m elements {v:.4} kN·m");
    assert!((v / f - 1.0).abs() < 0.002, "{v} vs {f}");
    // And the Δt series' errors are smaller than the coarsest mesh's (Δt 0.1 s resolves a 10 s heave).
    assert!(dt.errors_percent[0].abs() < e[0].abs());
}

#[test]
fn values_do_not_depend_on_the_number_of_jobs_and_files_are_written() {
    let dir = tmp("jobs");
    let case = short_heave(&dir);
    let one = ConvergenceOptions {
        mesh_factors: vec![2.0, 1.0],
        dt_factors: vec![2.0, 1.0],
        jobs: 1,
        progress: false,
    };
    let two = ConvergenceOptions {
        jobs: 2,
        ..one.clone()
    };
    let a = convergence::study(&case, &one).expect("one job");
    let b = convergence::study(&case, &two).expect("two jobs");
    for (x, y) in a.runs.iter().zip(&b.runs) {
        assert_eq!((x.mesh_factor, x.dt_factor), (y.mesh_factor, y.dt_factor));
        assert_eq!(x.newton_iterations, y.newton_iterations);
        for (u, v) in x.values.iter().zip(&y.values) {
            assert_eq!(u.to_bits(), v.to_bits(), "bit-identical with 1 and 2 jobs");
        }
    }
    let out = dir.join("out");
    let text = catena_cli::commands::convergence(&case, &out, &one).expect("command");
    assert!(text.contains("touchdown-zone moment range"), "{text}");
    let csv = std::fs::read_to_string(out.join("convergence.csv")).expect("csv");
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 1 + 4, "header + mesh x2, x1 + dt x2, x1");
    assert!(lines[0].starts_with("series,mesh_factor,dt_factor,elements"));
    assert!(lines[0].contains("tdz_moment_range_kNm,tdz_moment_range_error_percent"));
    let js: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("convergence.json")).expect("json"))
            .expect("valid json");
    assert_eq!(js["runs"].as_array().map(Vec::len), Some(3));
    let png = std::fs::metadata(out.join("convergence.png")).expect("png");
    assert!(png.len() > 10_000);
    // The variant scenes are real scenes: each parses and has the scaled settings.
    let scene =
        std::fs::read_to_string(out.join("scenes/short-heave-mesh2-dt1.toml")).expect("variant");
    let s = RiserScene::parse("variant", &scene, &catena::scene::NoFiles).expect("parses");
    assert_eq!(s.model.elements.len(), 200);
    assert_eq!(s.dynamic.expect("dynamic").output_every, 1);
}

#[test]
fn bad_requests_are_named() {
    let dir = tmp("bad");
    let case = short_heave(&dir);
    let e = convergence::study(
        &case,
        &ConvergenceOptions {
            mesh_factors: vec![-1.0],
            ..ConvergenceOptions::default()
        },
    )
    .expect_err("negative factor");
    assert!(e.to_string().contains("--mesh-factors"), "{e}");
    let e = convergence::study(
        &root().join("cases/scr1000/static-linear-k100.toml"),
        &ConvergenceOptions::default(),
    )
    .expect_err("no dynamics");
    assert!(e.to_string().contains("`dynamic`"), "{e}");
}

/// Fatigue damage is one of the study's key outputs when the scene counts it: a 30 s storm on the
/// 1000 m SCR with `[fatigue]`, at two time steps, reports `fatigue_damage_outer` for each run (a
/// positive number), and the values appear in the CSV.
#[test]
fn fatigue_damage_is_a_key_output() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("convergence_fatigue");
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::copy(
        root().join("cases/scr1000/semi-rao.csv"),
        dir.join("semi-rao.csv"),
    )
    .expect("rao");
    let text = common::short_storm23(&root());
    let case = dir.join("storm.toml");
    std::fs::write(&case, text).expect("case");
    let st = convergence::study(
        &case,
        &ConvergenceOptions {
            mesh_factors: vec![1.0],
            dt_factors: vec![1.0, 0.5],
            jobs: 2,
            progress: false,
        },
    )
    .expect("study");
    let k = st
        .outputs
        .iter()
        .position(|o| o.id == "fatigue_damage_outer")
        .expect("a fatigue output");
    for r in &st.runs {
        println!("dt {}: damage {:.4e}", r.dt, r.values[k]);
        assert!(r.values[k] > 0.0 && r.values[k].is_finite());
    }
    let out = dir.join("out");
    catena_cli::commands::convergence(
        &case,
        &out,
        &ConvergenceOptions {
            mesh_factors: vec![1.0],
            dt_factors: vec![1.0],
            jobs: 1,
            progress: false,
        },
    )
    .expect("command");
    let csv = std::fs::read_to_string(out.join("convergence.csv")).expect("csv");
    assert!(csv
        .lines()
        .next()
        .expect("header")
        .contains("fatigue_damage_outer_1"));
}
