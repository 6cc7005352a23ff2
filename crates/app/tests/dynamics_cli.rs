#![allow(clippy::needless_range_loop)]
//! Dynamics through the scene files: HHT against Newmark, the prescribed-motion consistency (top
//! tension independent of Δt), the seabed history committed only at converged steps, the start of a
//! dynamic run, and streamed output.

mod common;
use common::Edit;

use std::path::{Path, PathBuf};

use catena::checkpoint::Checkpoint;
use catena::observe::{Checkpointer, Stop};
use catena::run::{self as run_cmd, DynamicRun, RunOptions};
use catena::scene::riser::RiserScene;
use catena::scene::DirResolver;
use catena::statics as statics_cmd;
use catena_fe::dynamics::{self, DynWorkspace};
use catena_seabed::law::Law;
use catena_seabed::rq::Mode;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn heave_text() -> String {
    std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml")).expect("case")
}

fn run_text(name: &str, text: &str) -> run_cmd::DynamicRun {
    let scene = RiserScene::parse(
        name,
        text,
        &DirResolver {
            dir: root().join("cases"),
        },
    )
    .expect("scene");
    let st = statics_cmd::solve(scene).expect("statics");
    run_cmd::run(st, &mut [], RunOptions::default()).expect("runs")
}

/// The heave benchmark with HHT (α = −0.1) and with Newmark (β = 1/4, γ = 1/2): over t ∈ [50, 100] s
/// the top tension range agrees within 1 % and the largest moment range within 2 %.
#[test]
fn hht_and_newmark_agree_on_the_heave_benchmark() {
    let text = heave_text();
    let hht = run_text("hht", &text);
    let nm = run_text(
        "newmark",
        &text.edit(
            "scheme = \"hht\"\nalpha = -0.1 ",
            "scheme = \"newmark\"\nbeta = 0.25\ngamma = 0.5 ",
        ),
    );
    assert!(matches!(
        nm.spec.settings.scheme,
        catena_fe::dynamics::Scheme::Newmark { .. }
    ));
    let (m1, _, tmin1, tmax1) = run_cmd::key_numbers(&hht);
    let (m2, _, tmin2, tmax2) = run_cmd::key_numbers(&nm);
    println!(
        "HHT: top tension range {:.1} kN, moment range {:.2} kN·m; Newmark: {:.1} kN, {:.2} kN·m",
        (tmax1 - tmin1) / 1e3,
        m1 / 1e3,
        (tmax2 - tmin2) / 1e3,
        m2 / 1e3
    );
    assert!(((tmax1 - tmin1) / (tmax2 - tmin2) - 1.0).abs() < 0.01);
    assert!((m1 / m2 - 1.0).abs() < 0.02);
    assert!(hht.completed() && nm.completed());
}

/// Prescribed heave imposed consistently: halving Δt changes the top tension extremes by less than
/// 0.3 % (a node lagged by (1−α)·Δt·v would add an axial force of order EA·Δt·v/L ≈ ±60 MN here).
#[test]
fn top_tension_does_not_depend_on_the_time_step() {
    let text = heave_text()
        .edit("duration = 100.0", "duration = 30.0")
        .edit("envelope_start = 50.0", "envelope_start = 15.0");
    let a = run_text("dt", &text);
    let b = run_text("dt2", &text.edit("time_step = 0.05 ", "time_step = 0.025 "));
    assert_eq!(b.spec.dt, 0.025);
    let (_, _, min_a, max_a) = run_cmd::key_numbers(&a);
    let (_, _, min_b, max_b) = run_cmd::key_numbers(&b);
    println!(
        "Δt 0.05: {:.2}..{:.2} kN; Δt 0.025: {:.2}..{:.2} kN",
        min_a / 1e3,
        max_a / 1e3,
        min_b / 1e3,
        max_b / 1e3
    );
    assert!((max_a / max_b - 1.0).abs() < 3e-3 && (min_a / min_b - 1.0).abs() < 3e-3);
}

fn rq_heave_text() -> String {
    heave_text().edit(
        "model = \"linear\"\nstiffness = 100.0e3           # N/m/m², no friction, no damping",
        "model = \"randolph-quiggin\"\nsu0 = 1000.0\nsu_gradient = 1300.0\na = 6.0\nb = 0.25\nk_max = 200.0\nf_suc = 0.6\nlambda_suc = 1.0\nlambda_rep = 0.3",
    )
}

/// The seabed history is committed only at converged steps: after every step, each node's committed
/// history equals the law evaluated once from the previous committed history at the converged
/// penetration. Committing every Newton iterate would chain evaluations through the iterates and
/// break this (the test also checks that the run had reversals inside multi-iteration steps).
/// Also: the run starts with each contact node in Initial Penetration at its static penetration.
#[test]
fn seabed_history_is_committed_only_at_converged_steps() {
    let text = rq_heave_text()
        .edit("duration = 100.0", "duration = 15.0")
        .edit("envelope_start = 50.0", "envelope_start = 0.0");
    let scene = RiserScene::parse(
        "rq-heave",
        &text,
        &DirResolver {
            dir: root().join("cases"),
        },
    )
    .expect("scene");
    assert!(matches!(
        scene.model.seabed.expect("seabed").seabed.law,
        Law::RandolphQuiggin(_)
    ));
    let st = statics_cmd::solve(scene).expect("statics");
    let (spec, dm) = run_cmd::prepare(&st).expect("dynamic model");
    let (model, pl) = (&dm.line, &dm.placement);
    let sb = model.seabed.expect("seabed").seabed;
    let mut ws = DynWorkspace::new(model).expect("ws");
    let mut state = dynamics::initial_state(&dm, &st.u, &mut ws);
    for (i, h) in state.history.iter().enumerate() {
        let p = st.results.penetration[i];
        if p > 0.0 {
            assert_eq!(h.mode(), Mode::InitialPenetration);
            assert_eq!(h.z_prev(), p);
            assert_eq!(h.as_rq().expect("an RQ history").z_max, p);
        } else {
            assert_eq!(h.mode(), Mode::NotInContact);
        }
    }
    let mut reversals_in_multi_iteration_steps = 0;
    let steps = (spec.duration / spec.dt).round() as usize;
    for _ in 0..steps {
        let prev = state.history.clone();
        let info = dynamics::advance(&dm, &mut state, &mut ws, spec.dt).expect("step");
        assert_eq!(info.cuts, 0);
        for i in 0..model.nodes() {
            let z = model
                .penetration(
                    i,
                    pl.base[3 * i] + state.u[3 * i],
                    pl.base[3 * i + 1] + state.u[3 * i + 1],
                )
                .expect("seabed");
            let once = sb.evaluate(&prev[i], z, -state.v[3 * i + 1], spec.dt).next;
            assert_eq!(state.history[i], once, "node {i}");
            if info.iterations >= 2 && once.mode() != prev[i].mode() {
                reversals_in_multi_iteration_steps += 1;
            }
        }
    }
    assert!(
        reversals_in_multi_iteration_steps > 10,
        "{reversals_in_multi_iteration_steps}"
    );
}

/// cases.md / issue: the 1000 m SCR under slow heave (2 m, 300 s, k = 100 kN/m/m²) is quasi-static:
/// at every node the dynamic moment range over t ∈ [300, 900] s matches the range spanned by static
/// solves with the top 2 m up, at rest and 2 m down, within 2 % of the largest range.
#[test]
fn slow_heave_is_quasi_static() {
    let text =
        std::fs::read_to_string(root().join("cases/scr1000/slow-heave-k100.toml")).expect("case");
    let scene = RiserScene::parse(
        "slow-heave-k100",
        &text,
        &DirResolver {
            dir: root().join("cases"),
        },
    )
    .expect("scene");
    // The flexjoint keeps the baseline's neutral angle (zero moment at rest), as in the dynamics.
    let base = statics_cmd::solve(scene.clone()).expect("statics");
    let neutral = base.summary.top_angle_from_vertical;
    let mut moments = Vec::new();
    for dz in [-2.0, 0.0, 2.0] {
        let mut s = scene.clone();
        s.flexjoint_neutral_from_vertical = Some(neutral);
        s.ends.top.1 += dz;
        moments.push(statics_cmd::solve(s).expect("statics").results.moment);
    }
    let r = run_cmd::run(
        statics_cmd::solve(scene).expect("statics"),
        &mut [],
        RunOptions::default(),
    )
    .expect("runs");
    let dyn_range = r.envelopes.moment.range();
    let n = dyn_range.len();
    let stat_range: Vec<f64> = (0..n)
        .map(|i| {
            let v = [moments[0][i], moments[1][i], moments[2][i]];
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                - v.iter().copied().fold(f64::INFINITY, f64::min)
        })
        .collect();
    let big = stat_range.iter().copied().fold(0.0, f64::max);
    let (mut worst, mut at) = (0.0f64, 0);
    for i in 0..n {
        let d = (dyn_range[i] - stat_range[i]).abs();
        if d > worst {
            worst = d;
            at = i;
        }
    }
    println!("largest static range {:.3} kN·m; largest difference {:.3} kN·m at node {at} (arc {:.1} m): dynamic {:.3}, static {:.3}",
        big / 1e3, worst / 1e3, r.statics.model.arc[at], dyn_range[at] / 1e3, stat_range[at] / 1e3);
    assert!(worst < 0.02 * big, "{worst} vs {big}");
}

/// cases.md §4, Watchet: the sag moment at gauge D dips during pull-up as touchdown passes the gauge
/// and recovers; suction (f_suc 1 vs 0) deepens the pull-up dip; without suction pull-up and
/// lay-down reach the same minimum (the difference is the soil's suction, not the dynamics); and the
/// static embedment away from touchdown equals the law's own static solution (2e-4 at arc 100 m: the
/// grounded length is short compared with the decay of the touchdown boundary layer).
#[test]
fn watchet_suction_deepens_the_pull_up_dip() {
    let run = |name: &str| {
        let text = std::fs::read_to_string(root().join(format!("cases/watchet/{name}.toml")))
            .expect("case");
        let st = statics_cmd::solve(
            RiserScene::parse(
                name,
                &text,
                &DirResolver {
                    dir: root().join("cases"),
                },
            )
            .expect("scene"),
        )
        .expect("statics");
        run_cmd::run(st, &mut [], RunOptions::default()).expect("runs")
    };
    let with = run("pull-up-lay-down");
    let without = run("pull-up-lay-down-no-suction");
    let dir = |r: &DynamicRun| {
        let [(rmin, rmax), (fmin, _)] = r.gauges.traces[0].by_direction;
        (
            rmin.expect("rising"),
            rmax.expect("rising"),
            fmin.expect("falling"),
        )
    };
    let (up_w, up_w_max, down_w) = dir(&with);
    let (up_n, _, down_n) = dir(&without);
    println!(
        "gauge D pull-up minimum: {:.3} kN·m with suction, {:.3} without; lay-down: {:.3} / {:.3}",
        up_w / 1e3,
        up_n / 1e3,
        down_w / 1e3,
        down_n / 1e3
    );
    assert!(
        up_w < up_n - 0.3e3,
        "suction must deepen the dip: {up_w} vs {up_n}"
    );
    assert!(
        (up_n - down_n).abs() < 0.05e3,
        "no suction: pull-up {up_n} vs lay-down {down_n}"
    );
    assert!(
        up_w < down_w,
        "with suction the pull-up dip is deeper than the lay-down one"
    );
    // The moment recovers after touchdown has passed the gauge (its maximum while rising is near 0,
    // far above the dip), and the gauge sits between the two static touchdown points.
    assert!(up_w_max > up_w + 5e3);
    let g = with.spec.gauges[0].arc;
    assert!(g > with.statics.summary.touchdown_arc.expect("touchdown") && g < 110.0);
    // Far-field static embedment: backbone plus buoyancy carries the submerged weight.
    let sb = with.statics.model.seabed.expect("seabed").seabed;
    let r = &with.statics.results;
    let w = with.statics.scene.line.2;
    for s in [70.0, 80.0, 90.0, 100.0, 105.0] {
        let i = with
            .model
            .line
            .arc
            .iter()
            .position(|a| *a >= s)
            .expect("node");
        println!(
            "arc {s}: F/w − 1 = {:.3e}",
            sb.backbone(r.penetration[i]).total() / w - 1.0
        );
    }
    // The grounded part is only 65 m and the contact boundary layer decays over ~(4EI/k)^¼ ≈ 7 m,
    // oscillating: 55 m past touchdown (arc 100 m) it has decayed to ~1e-4.
    let i = with
        .model
        .line
        .arc
        .iter()
        .position(|a| *a >= 100.0)
        .expect("node");
    assert!((sb.backbone(r.penetration[i]).total() / w - 1.0).abs() < 2e-4);
}

/// A top motion given as a CSV series (beside the case file) drives the top exactly as written, and
/// seabed damping on the linear seabed is built and acts (the law's damping force itself is tested in
/// `catena-seabed`). Here the dashpot stiffens the seabed dynamically, and the touchdown moment range
/// grows, as it does with a stiffer seabed.
#[test]
fn series_motion_and_seabed_damping_through_a_case() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("series_case");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut csv = String::from("t,dx,dz\n");
    for i in 0..=200 {
        let t = i as f64 * 0.1;
        csv.push_str(&format!(
            "{t},0.0,{}\n",
            1.5 * (std::f64::consts::TAU * t / 10.0).sin() * (t / 20.0)
        ));
    }
    std::fs::write(dir.join("heave.csv"), csv).expect("csv");
    let base = heave_text()
        .edit("duration = 100.0", "duration = 20.0")
        .edit("envelope_start = 50.0", "envelope_start = 10.0");
    let text = base.edit(
        "[motion.harmonic]             # z = 2·r(t)·sin(2πt/10), quintic ramp over the first 10 s\nheave = 2.0                   # m\nperiod = 10.0                 # s\nramp = 10.0                   # s",
        "[motion.series]\nfile = \"heave.csv\"",
    );
    assert!(text.contains("[motion.series]"));
    let case = dir.join("series.toml");
    std::fs::write(&case, &text).expect("case");
    let scene = statics_cmd::read_scene(&case).expect("scene");
    let r = run_cmd::run(
        statics_cmd::solve(scene).expect("statics"),
        &mut [],
        RunOptions::default(),
    )
    .expect("runs");
    let i = r
        .top
        .t
        .iter()
        .position(|t| (*t - 12.5).abs() < 1e-9)
        .expect("t = 12.5");
    let expect = 1000.0 + 1.5 * (std::f64::consts::TAU * 12.5 / 10.0).sin() * (12.5 / 20.0);
    assert!(
        (r.top.top_z[i] - expect).abs() < 2e-3,
        "{} vs {expect}",
        r.top.top_z[i]
    );
    // Seabed damping (per unit contact area): the same run with a damped seabed.
    let damped_text = text.edit(
        "stiffness = 100.0e3           # N/m/m², no friction, no damping",
        "stiffness = 100.0e3\ndamping = 50.0e3",
    );
    assert!(damped_text.contains("damping = 50.0e3"));
    let case2 = dir.join("damped.toml");
    std::fs::write(&case2, &damped_text).expect("case");
    let r2 = run_cmd::run(
        statics_cmd::solve(statics_cmd::read_scene(&case2).expect("scene")).expect("statics"),
        &mut [],
        RunOptions::default(),
    )
    .expect("runs");
    let (m1, ..) = run_cmd::key_numbers(&r);
    let (m2, ..) = run_cmd::key_numbers(&r2);
    println!(
        "moment range without seabed damping {:.3} kN·m, with {:.3} kN·m",
        m1 / 1e3,
        m2 / 1e3
    );
    assert!(
        (m2 - m1).abs() > 1e-3 * m1,
        "the damping must change the response"
    );
}

/// Determinism: the same scene gives bit-identical envelopes and histories when run again, inside a
/// 1-thread and a 4-thread rayon pool, and as two runs at once on two threads (the solver is
/// sequential: faer runs with `Par::Seq`, and nothing depends on hashing, timing or thread count).
#[test]
fn repeated_runs_are_bit_identical_whatever_the_threads() {
    let text = rq_heave_text()
        .edit("duration = 100.0", "duration = 10.0")
        .edit("envelope_start = 50.0", "envelope_start = 0.0");
    let pool = |n| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .expect("pool")
    };
    let a = pool(1).install(|| run_text("det-a", &text));
    let b = pool(4).install(|| run_text("det-b", &text));
    let (c, d) = pool(2).join(|| run_text("det-c", &text), || run_text("det-d", &text));
    for other in [&b, &c, &d] {
        assert_eq!(a.top, other.top);
        assert_eq!(a.envelopes.moment.min, other.envelopes.moment.min);
        assert_eq!(a.envelopes.moment.max, other.envelopes.moment.max);
        assert_eq!(a.envelopes.penetration.max, other.envelopes.penetration.max);
        assert_eq!(a.iterations, other.iterations);
    }
}

/// Checkpoint and restart (rapier's snapshot round trip): a run on the hysteretic seabed stopped at
/// a checkpoint (State, solver memory and observers written to JSON and read back) and restarted
/// with a freshly rebuilt Model and Workspace is **bit-for-bit** the uninterrupted run, whatever the
/// checkpoint interval of either: the uninterrupted run here writes no checkpoint at all, the
/// interrupted one checkpoints every 37 steps and stops at step 111, and the restarted one
/// checkpoints every 50. Its envelopes, gauges and top history cover the whole run and equal the
/// uninterrupted run's; so does the final State (with the seabed's friction anchors).
#[test]
fn restart_from_checkpoint_is_bit_for_bit() {
    // With axial seabed friction too: its anchors are State and travel with the checkpoint.
    let text = rq_heave_text()
        .edit("duration = 100.0", "duration = 10.0")
        .edit("envelope_start = 50.0", "envelope_start = 0.0")
        + "\n[seabed.friction]\naxial = 0.5\nmobilisation = 0.005\n";
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("restart");
    std::fs::create_dir_all(&dir).expect("dir");
    let solve = |text: &str| {
        statics_cmd::solve(
            RiserScene::parse(
                "restart",
                text,
                &DirResolver {
                    dir: root().join("cases"),
                },
            )
            .expect("scene"),
        )
        .expect("statics")
    };
    // Uninterrupted, no checkpoints; its final State through a checkpointer at the last step.
    let mut end = Checkpointer::new(&dir.join("full.json"), 200);
    let full = run_cmd::run(solve(&text), &mut [&mut end], RunOptions::default()).expect("runs");
    // Checkpoints every 37 steps, stopped after step 111 (the last checkpoint is at 111).
    let mut cp37 = Checkpointer::new(&dir.join("cut.json"), 37);
    let first = run_cmd::run(
        solve(&text),
        &mut [&mut cp37],
        RunOptions {
            stop_after: Some(111),
            ..RunOptions::default()
        },
    )
    .expect("runs");
    assert_eq!(first.steps, 111);
    assert!(matches!(first.stop, Some(Stop::StoppedAfter(111))));
    let cp = Checkpoint::read(&dir.join("cut.json")).expect("checkpoint");
    assert_eq!(cp.step, 111);
    assert!(
        cp.solver.is_some(),
        "the solver memory travels with the checkpoint"
    );
    let mut cp50 = Checkpointer::new(&dir.join("after.json"), 50);
    let second = run_cmd::run(
        solve(&text),
        &mut [&mut cp50],
        RunOptions {
            restart: Some(cp.clone()),
            restart_file: "cut.json".into(),
            stop_after: None,
            start: None,
            threads: None,
        },
    )
    .expect("runs");
    assert!(second.completed());
    assert_eq!(second.steps, 200);
    assert_eq!(full.top, second.top, "top history over the whole run");
    assert_eq!(
        full.envelopes, second.envelopes,
        "envelopes over the whole run"
    );
    assert_eq!(full.gauges.traces, second.gauges.traces);
    let end_full = Checkpoint::read(&dir.join("full.json")).expect("cp");
    let end_restarted = Checkpoint::read(&dir.join("after.json")).expect("cp");
    assert_eq!(end_full.step, 200);
    assert_eq!(
        end_full.state, end_restarted.state,
        "final State bit for bit"
    );
    assert_eq!(
        end_full.state.friction_anchor.len(),
        full.model.line.nodes()
    );
    // A checkpoint of another scene is refused, naming what differs.
    let err = run_cmd::run(
        solve(&text.edit("f_suc = 0.6", "f_suc = 0.5")),
        &mut [],
        RunOptions {
            restart: Some(cp),
            restart_file: "cut.json".into(),
            stop_after: None,
            start: None,
            threads: None,
        },
    )
    .expect_err("another scene");
    assert!(err.to_string().contains("another scene"), "{err}");
}

/// A checkpoint that parses but does not fit the run is a clear error naming the file and what
/// differs, never a panic: arrays one entry short, empty or one entry long (the three inputs that
/// panicked before), a history of another length, a non-finite value, a time that is not
/// `step·Δt`, a step beyond the run, another version, a solver memory of the wrong size.
#[test]
fn malformed_checkpoints_are_refused_with_the_reason() {
    let text = rq_heave_text()
        .edit("duration = 100.0", "duration = 2.0")
        .edit("envelope_start = 50.0", "envelope_start = 0.0");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bad_checkpoints");
    std::fs::create_dir_all(&dir).expect("dir");
    let solve = || {
        statics_cmd::solve(
            RiserScene::parse(
                "bad-cp",
                &text,
                &DirResolver {
                    dir: root().join("cases"),
                },
            )
            .expect("scene"),
        )
        .expect("statics")
    };
    let mut c = Checkpointer::new(&dir.join("good.json"), 10);
    run_cmd::run(
        solve(),
        &mut [&mut c],
        RunOptions {
            stop_after: Some(10),
            ..RunOptions::default()
        },
    )
    .expect("runs");
    let good = Checkpoint::read(&dir.join("good.json")).expect("checkpoint");
    type Mutation = Box<dyn Fn(&mut Checkpoint)>;
    let cases: Vec<(&str, Mutation, &str)> = vec![
        (
            "v short",
            Box::new(|c| {
                c.state.v.pop();
            }),
            "state.v",
        ),
        ("a empty", Box::new(|c| c.state.a.clear()), "state.a"),
        (
            "f_prev long",
            Box::new(|c| c.state.f_prev.push(0.0)),
            "state.f_prev",
        ),
        (
            "history short",
            Box::new(|c| {
                c.state.history.pop();
            }),
            "state.history",
        ),
        ("u nan", Box::new(|c| c.state.u[7] = f64::NAN), "state.u[7]"),
        ("t off", Box::new(|c| c.state.t += 0.013), "state.t"),
        (
            "step beyond",
            Box::new(|c| c.step = 1_000_000),
            "step 1000000",
        ),
        (
            "version",
            Box::new(|c| c.catena_version = "0.0.1".into()),
            "0.0.1",
        ),
        (
            "solver",
            Box::new(|c| {
                if let Some(m) = &mut c.solver {
                    m.values.pop();
                }
            }),
            "solver memory",
        ),
        (
            "observers",
            Box::new(|c| {
                c.observers.remove("envelopes");
            }),
            "envelopes",
        ),
    ];
    for (label, mutate, needle) in cases {
        let mut cp = good.clone();
        mutate(&mut cp);
        let err = run_cmd::run(
            solve(),
            &mut [],
            RunOptions {
                restart: Some(cp),
                restart_file: "bad.json".into(),
                stop_after: None,
                start: None,
                threads: None,
            },
        )
        .expect_err(label)
        .to_string();
        println!("{label}: {err}");
        assert!(
            err.contains("bad.json") && err.contains(needle),
            "{label}: {err}"
        );
    }
}

/// Without `output_interval` a run records every step up to 10 000 steps, and beyond that the
/// smallest multiple of the time step that keeps it within 10 000 records: the heave benchmark
/// stretched to a 3-hour storm's 216 000 steps records every 22nd step (1.1 s); an explicit
/// interval is kept as given.
#[test]
fn long_runs_record_at_a_bounded_default_interval() {
    let parse = |text: &str| {
        RiserScene::parse(
            "heave.toml",
            text,
            &DirResolver::beside(&root().join("cases/benchmarks/scr-heave.toml")),
        )
        .expect("scene")
        .dynamic
        .expect("dynamic")
    };
    assert_eq!(parse(&heave_text()).output_every, 1);
    let long = heave_text().replace("duration = 100.0", "duration = 10800.0");
    assert_ne!(long, heave_text());
    assert_eq!(parse(&long).output_every, 22);
    let explicit = long.replace(
        "time_step = 0.05              # s (2000 steps)",
        "time_step = 0.05\noutput_interval = 0.05",
    );
    assert_ne!(explicit, long);
    assert_eq!(parse(&explicit).output_every, 1);
}

/// `[[attachment]]` through a scene: a 5 kN buoyancy module on the heave benchmark's riser at
/// 601 m is carried by the nearest node (arc 600 m), its lift enters that node's dead load, it
/// lightens the line (the static top tension falls: 1221.6 → 1216.0 kN), and the run completes.
#[test]
fn an_attached_buoyancy_module_lightens_the_riser() {
    let base = heave_text()
        .edit("duration = 100.0", "duration = 5.0")
        .edit("envelope_start = 50.0", "envelope_start = 0.0");
    let with = base.edit(
        "[dynamic]",
        "[[attachment]]\nname = \"module\"\narc = 601.0\nmass = 800.0\nsubmerged_weight = -5000.0\ndrag_area = 1.2\nadded_mass = 600.0\n\n[dynamic]",
    );
    let a = run_text("attachment-none", &base);
    let b = run_text("attachment-module", &with);
    let att = &b.model.line.attachments;
    assert_eq!(att.len(), 1);
    assert!(
        (b.model.line.arc[att[0].node] - 600.0).abs() < 1e-9,
        "{}",
        att[0].node
    );
    let (ta, tb) = (a.statics.summary.top_tension, b.statics.summary.top_tension);
    println!(
        "top tension {:.1} kN without, {:.1} kN with a 5 kN module",
        ta / 1e3,
        tb / 1e3
    );
    assert!(tb < ta, "{ta} {tb}");
    // Its lift is in the node's dead load (the weight as a downward force: −W = +5 kN here).
    let (n, lines) = (att[0].node, (&a.model.line, &b.model.line));
    assert_eq!(
        lines.1.dead_load[3 * n + 1] - lines.0.dead_load[3 * n + 1],
        5000.0
    );
    assert!(b.completed());
}
