//! The sea in runs: current in the statics against two independent codes, a run in current starting
//! in equilibrium, and the hang-off following the vessel's RAOs in a regular wave.

mod common;

use std::path::{Path, PathBuf};

use catena::run::{self, RunOptions};
use catena::scene::edit::Edit;
use catena::statics;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

/// The heave benchmark's riser in a uniform 0.5 m/s current along +x
/// (`cases/benchmarks/scr-current.toml`): CableDyn and OpenSees (agreeing with each other to 0.03 %)
/// give top tension 1235.7 kN, horizontal tension at the anchor 225.9 kN and touchdown 1199.3 m
/// from the top. catena, with the current's drag in its statics, agrees within 0.1 % (4 m elements).
#[test]
fn current_statics_match_two_independent_codes() {
    let scene =
        statics::read_scene(&root().join("cases/benchmarks/scr-current.toml")).expect("scene");
    let s = statics::solve(scene).expect("statics").summary;
    println!(
        "top tension {:.2} kN, anchor H {:.2} kN (top H {:.2} kN), touchdown {:.2} m",
        s.top_tension / 1e3,
        s.anchor_horizontal_tension / 1e3,
        s.horizontal_tension / 1e3,
        s.touchdown_arc.expect("touchdown")
    );
    assert!(rel(s.top_tension, 1235.7e3) < 1e-3);
    assert!(rel(s.anchor_horizontal_tension, 225.9e3) < 1e-3);
    assert!(rel(s.touchdown_arc.expect("touchdown"), 1199.3) < 1e-3);
    // The current changes the statics: without it, the heave benchmark's 1221.6 kN.
    assert!(s.top_tension > 1230e3);
}

/// A run in current starts in equilibrium with it: the same scene without top motion stays at its
/// static state for 10 s (top tension within 1e-5 of the static value, every node's speed below
/// 1 mm/s). Before the statics included the current, the drag switched on at t = 0 and the line
/// was thrown off its static shape.
#[test]
fn a_run_in_current_starts_in_equilibrium() {
    let case = root().join("cases/benchmarks/scr-current.toml");
    let scene = common::edited_case(
        &case,
        &[
            Edit::remove("motion"),
            Edit::set("dynamic.duration", 10.0),
            Edit::set("dynamic.envelope_start", 0.0),
        ],
    );
    let st = statics::solve(scene).expect("statics");
    let t0 = st.summary.top_tension;
    let r = run::run(st, &mut [], RunOptions::default()).expect("runs");
    let (_, _, lo, hi) = run::key_numbers(&r);
    println!(
        "static top tension {:.4} kN; over 10 s {:.4} … {:.4} kN",
        t0 / 1e3,
        lo / 1e3,
        hi / 1e3
    );
    assert!(rel(lo, t0) < 1e-5 && rel(hi, t0) < 1e-5);
    // Node speeds from the recorded positions' changes over the last step are tiny.
    let n = r.model.line.nodes();
    let e = &r.envelopes;
    for i in 0..n {
        assert!(
            e.tension.max[i] - e.tension.min[i] < 1e-5 * t0,
            "node {i} moved"
        );
    }
}

/// In a regular wave (H 6 m, T 12 s, `cases/benchmarks/scr-regular-wave.toml`) the hang-off moves as
/// the RAO table says once the ramp is over: its displacement is `Re(a·(R_surge + R_pitch·Δz)·e^{iψ})`
/// horizontally and `Re(a·(R_heave − R_pitch·Δx)·e^{iψ})` vertically (to 1e-9 m), and the riser
/// answers: the top tension range over the last minute exceeds 50 kN (the heave benchmark's 2 m heave
/// gives 304 kN), with the largest moment range in the touchdown zone (1100–1250 m from the top).
#[test]
fn the_hang_off_follows_the_raos_in_a_regular_wave() {
    let case = root().join("cases/benchmarks/scr-regular-wave.toml");
    let st = statics::solve(statics::read_scene(&case).expect("scene")).expect("statics");
    let (x0, z0) = (st.results.x[0], st.results.z[0]);
    let r = run::run(st, &mut [], RunOptions::default()).expect("runs");
    let vessel = r.model.vessel.as_ref().expect("vessel");
    let waves = r.model.environment.waves.as_ref().expect("waves");
    let c = waves.components[0];
    let rao = vessel.table.at(c.omega);
    let [dx, dz] = vessel.hangoff_offset;
    let mut checked = 0;
    for (k, t) in r.top.t.iter().enumerate() {
        if *t < waves.ramp {
            continue;
        }
        let psi = c.omega * t - c.k * vessel.origin_x + c.phase;
        let (s, co) = psi.sin_cos();
        let re = |z: (f64, f64)| c.amplitude * (z.0 * co - z.1 * s);
        let want_x = re(rao[0]) + re(rao[2]) * dz;
        let want_z = re(rao[1]) - re(rao[2]) * dx;
        assert!((r.top.top_x[k] - x0 - want_x).abs() < 1e-9, "x at {t}");
        assert!((r.top.top_z[k] - z0 - want_z).abs() < 1e-9, "z at {t}");
        checked += 1;
    }
    assert!(checked > 1000);
    let (mr, at, lo, hi) = run::key_numbers(&r);
    println!(
        "top tension range {:.2} kN; largest moment range {:.2} kN·m at {at:.1} m",
        (hi - lo) / 1e3,
        mr / 1e3
    );
    assert!(hi - lo > 50e3);
    assert!((1100.0..=1250.0).contains(&at));
}

/// A wave-driven case against an independent code: `cases/benchmarks/riser-airy-wave.toml` (the
/// heave benchmark's riser, top held 20 m down, Airy H 10 m, T 12 s along +x) run in CableDyn 0.3.0
/// (`validation/cabledyn/`): over t ∈ [120, 180] s its top tension range is 3.749 kN and its
/// largest touchdown-zone moment range 6.853 kN·m at 1156 m. Tolerance 5 % on the tension range,
/// 6 % on the moment range (catena: +2.8 %, +4.2 %). Without the axial Froude–Krylov force the
/// tension range is 1.63 kN (−57 %), and this test fails (checked).
#[test]
fn a_regular_wave_on_the_riser_matches_cabledyn() {
    let case = root().join("cases/benchmarks/riser-airy-wave.toml");
    let st = statics::solve(statics::read_scene(&case).expect("scene")).expect("statics");
    let r = run::run(st, &mut [], RunOptions::default()).expect("runs");
    let (mr, at, lo, hi) = run::key_numbers(&r);
    println!(
        "top tension range {:.3} kN; largest moment range {:.3} kN·m at {at:.1} m",
        (hi - lo) / 1e3,
        mr / 1e3
    );
    assert!(
        rel(hi - lo, 3.749e3) < 0.05,
        "top tension range {}",
        hi - lo
    );
    assert!(rel(mr, 6.853e3) < 0.06, "moment range {mr}");
    assert!((at - 1156.0).abs() <= 8.0, "at {at}");
}

/// Storm 23 shortened to 30 s (`common::short_storm23`), parsed as if it were in `cases/scr1000/`
/// (where its RAO table is), with the given edits of its text.
fn short_storm(edits: &[(&str, &str)]) -> catena::statics::StaticRun {
    use common::Edit;
    let mut text = common::short_storm23(&root());
    for (from, to) in edits {
        text = text.edit(from, to);
    }
    let scene = catena::scene::riser::RiserScene::parse(
        "storm23-short.toml",
        &text,
        &catena::scene::DirResolver {
            dir: root().join("cases/scr1000"),
        },
    )
    .expect("scene");
    statics::solve(scene).expect("statics")
}

/// The kinematics sampled every Tp/40 = 0.2475 s and interpolated (the default) against the
/// kinematics at every node at every step (`kinematics_interval = 0`), in 30 s of storm 23: the
/// top tension history within 3e-5 of its range, the moment range at every node within 1e-4 of
/// the largest, the largest damage within 1e-3 (measured here: 6.9e-6, 4.4e-5 and 1.3e-6;
/// `docs/accuracy.md` for 400 s). With the jerk left out of the acceleration's interpolation the
/// tension is off by 1.1e-4 of its range and the moment range by 1.75e-4, and this test fails
/// (checked).
#[test]
fn sampled_kinematics_are_the_exact_ones_within_1e_4() {
    let sampled = short_storm(&[]);
    let h = sampled
        .scene
        .dynamic
        .as_ref()
        .and_then(|d| d.environment.waves.as_ref())
        .map(|w| w.kinematics_interval)
        .expect("waves");
    assert!((h - 9.9 / 40.0).abs() < 1e-12, "default interval {h}");
    let exact = short_storm(&[("ramp = 10.0 ", "kinematics_interval = 0.0\nramp = 10.0 ")]);
    let a = run::run(sampled, &mut [], RunOptions::default()).expect("runs");
    let b = run::run(exact, &mut [], RunOptions::default()).expect("runs");
    let (ta, tb) = (&a.top.top_tension, &b.top.top_tension);
    assert_eq!(ta.len(), tb.len());
    let range =
        tb.iter().cloned().fold(f64::MIN, f64::max) - tb.iter().cloned().fold(f64::MAX, f64::min);
    let worst_t = ta
        .iter()
        .zip(tb)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    let (ma, mb) = (a.envelopes.moment.range(), b.envelopes.moment.range());
    let m_max = mb
        .iter()
        .cloned()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let worst_m = ma
        .iter()
        .zip(&mb)
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    let dmax = |r: &run::DynamicRun| {
        r.fatigue
            .as_ref()
            .expect("fatigue")
            .counting()
            .expect("counted")
            .damage
            .iter()
            .cloned()
            .fold(0.0, f64::max)
    };
    let (da, db) = (dmax(&a), dmax(&b));
    println!(
        "tension {:.2e} of its range {:.1} kN; moment range {:.2e} of {:.2} kN·m; damage {da:e} vs {db:e}",
        worst_t / range,
        range / 1e3,
        worst_m / m_max,
        m_max / 1e3
    );
    assert!(worst_t > 0.0, "sampling changes something");
    assert!(worst_t < 3e-5 * range, "tension {worst_t} of range {range}");
    assert!(worst_m < 1e-4 * m_max, "moment range {worst_m} of {m_max}");
    assert!(rel(da, db) < 1e-3, "damage {da} vs {db}");
}

/// A run's threads (`RunOptions::threads`) say where the line is stepped and the fatigue damage
/// counted, and change nothing else: 30 s of storm 23 run on one thread (counting on the stepping
/// thread), on two (the line stepped by a pair, counting in the pair's waits, each thread half the
/// nodes) and on three (a pair, counting on a thread of its own; the envelopes taken in the pair's
/// waits on both), the damage, the counters' state and the envelopes the same to the bit. (A study at `--jobs` equal to the cores gives each storm one thread:
/// `schedule::threads_per_run`.)
#[test]
fn fatigue_counts_the_same_on_one_thread_or_more() {
    let on = |threads| {
        let opts = RunOptions::with_threads(Some(threads));
        run::run(short_storm(&[]), &mut [], opts).expect("runs")
    };
    let runs = [on(1), on(2), on(3)];
    let stepping = runs.each_ref().map(|r| r.stepping_threads);
    assert_eq!(stepping, [1, 2, 2], "the threads stepping the line");
    let fatigue = runs
        .each_ref()
        .map(|r| r.fatigue.as_ref().expect("fatigue"));
    let threaded = fatigue.map(|f| f.threaded());
    assert_eq!(
        threaded,
        [false, false, true],
        "counted on a thread of its own"
    );
    let waits = fatigue.map(|f| f.in_the_pairs_waits());
    assert_eq!(waits, [false, true, false], "counted in the pair's waits");
    let bits = |d: &[f64]| d.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let c1 = fatigue[0].counting().expect("counted");
    assert!(c1.damage.iter().any(|&d| d > 0.0), "damage counted");
    for (r, f) in runs.iter().zip(fatigue).skip(1) {
        let c = f.counting().expect("counted");
        let n = r.stepping_threads;
        assert_eq!(bits(&c1.damage), bits(&c.damage), "damage ({n} stepping)");
        assert_eq!(c1, c, "counters ({n} stepping)");
        assert_eq!(runs[0].envelopes, r.envelopes, "envelopes ({n} stepping)");
    }
}

/// With sampled kinematics, a run stopped at a checkpoint in the middle of a sampling interval
/// (step 111, t = 5.55 s, between the samples at 5.445 s and 5.6925 s) and restarted is bit for bit
/// the uninterrupted run: the samples are history in the State, and travel with the checkpoint.
#[test]
fn restart_with_sampled_kinematics_is_bit_for_bit() {
    use catena::checkpoint::Checkpoint;
    use catena::observe::Checkpointer;
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("restart-sampled");
    std::fs::create_dir_all(&dir).expect("dir");
    let shorter = [
        ("duration = 30.0 ", "duration = 8.0 "),
        ("envelope_start = 20.0 ", "envelope_start = 2.0 "),
        ("\nstart = 20.0 ", "\nstart = 2.0 "),
    ];
    let mut end = Checkpointer::new(&dir.join("full.json"), 160);
    let full = run::run(
        short_storm(&shorter),
        &mut [&mut end],
        RunOptions::default(),
    )
    .expect("runs");
    let mut cut = Checkpointer::new(&dir.join("cut.json"), 37);
    run::run(
        short_storm(&shorter),
        &mut [&mut cut],
        RunOptions {
            stop_after: Some(111),
            ..RunOptions::default()
        },
    )
    .expect("runs");
    let cp = Checkpoint::read(&dir.join("cut.json")).expect("checkpoint");
    assert_eq!(cp.step, 111);
    assert!(
        cp.state.wave_grid.is_some(),
        "the samples travel with the checkpoint"
    );
    let mut after = Checkpointer::new(&dir.join("after.json"), 40);
    let second = run::run(
        short_storm(&shorter),
        &mut [&mut after],
        RunOptions {
            restart: Some(cp),
            restart_file: "cut.json".into(),
            stop_after: None,
            start: None,
            threads: None,
        },
    )
    .expect("runs");
    assert_eq!(second.steps, 160);
    assert_eq!(full.top, second.top, "top history over the whole run");
    assert_eq!(
        full.envelopes, second.envelopes,
        "envelopes over the whole run"
    );
    let (a, b) = (
        Checkpoint::read(&dir.join("full.json")).expect("cp"),
        Checkpoint::read(&dir.join("after.json")).expect("cp"),
    );
    assert_eq!(a.state, b.state, "final State bit for bit");
}

/// A kinematics interval shorter than a step, negative or not a number is refused, naming the file
/// and the key.
#[test]
fn a_bad_kinematics_interval_names_file_and_key() {
    use common::Edit;
    for bad in ["0.01", "-0.3", "nan"] {
        let text = common::short_storm23(&root()).edit(
            "ramp = 10.0 ",
            &format!("kinematics_interval = {bad}\nramp = 10.0 "),
        );
        let err = catena::scene::riser::RiserScene::parse(
            "storm23-short.toml",
            &text,
            &catena::scene::DirResolver {
                dir: root().join("cases/scr1000"),
            },
        )
        .expect_err(bad)
        .to_string();
        assert!(
            err.contains("storm23-short.toml") && err.contains("waves.kinematics_interval"),
            "{err}"
        );
        if bad != "nan" {
            assert!(err.contains(">= dynamic.time_step (0.05 s)"), "{err}");
        }
    }
}

/// The paper's SCR on a seabed sloping 2° up towards the anchor (issue 28,
/// `cases/scr1000/static-rq-slope-2deg.toml`): the statics converge from the draped seed, and the
/// frictionless seabed carries the resting pipe's down-slope weight, so the anchor's horizontal
/// tension exceeds the top's by `w·sin α·L_s·cos α` (w = 1010.08 N/m, L_s = the length past the
/// touchdown point), to 1 %; the line hangs deeper than on the flat seabed (the touchdown point
/// further along it, the top tension higher).
#[test]
fn a_seabed_sloping_up_to_the_anchor_carries_the_pipes_down_slope_weight() {
    let flat = statics::solve(
        statics::read_scene(&root().join("cases/scr1000/static-rq.toml")).expect("scene"),
    )
    .expect("statics");
    let slope = statics::solve(
        statics::read_scene(&root().join("cases/scr1000/static-rq-slope-2deg.toml"))
            .expect("scene"),
    )
    .expect("statics");
    let (sf, ss) = (&flat.summary, &slope.summary);
    let w = slope.scene.line.2;
    let td = ss.touchdown_arc.expect("touchdown");
    let alpha = 2f64.to_radians();
    let want = w * alpha.sin() * alpha.cos() * (slope.model.length() - td);
    let got = ss.anchor_horizontal_tension - ss.horizontal_tension;
    println!(
        "2° slope: top tension {:.2} kN (flat {:.2}), touchdown {td:.2} m (flat {:.2}); anchor H − top H {:.3} kN against w·sin α·cos α·L_s {:.3} kN",
        ss.top_tension / 1e3,
        sf.top_tension / 1e3,
        sf.touchdown_arc.expect("td"),
        got / 1e3,
        want / 1e3
    );
    assert!((got / want - 1.0).abs() < 0.01, "{got} vs {want}");
    assert!(ss.top_tension > sf.top_tension);
    assert!(td > sf.touchdown_arc.expect("td"));
}
