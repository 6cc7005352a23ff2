//! The heave benchmark (`cases/benchmarks/scr-heave.toml`: 400 elements, 2000 steps of 0.05 s),
//! statics included, without file output: the target is 1 s of wall time on one core.
//! Also one dynamic step on its own, and the 2000 steps bare against the run with its outputs.
//!
//! Run: `cargo bench -p catena-benches --bench dynamics`.

use std::path::Path;

use catena_fe::dynamics::{self, DynWorkspace, Pair, Samples};
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/benchmarks/scr-heave.toml");
    let scene = catena::run::statics::read_scene(&case).expect("case");
    let mut g = c.benchmark_group("heave");
    g.sample_size(10);
    g.bench_function("heave_benchmark_full", |b| {
        b.iter(|| {
            let st = catena::run::statics::solve(scene.clone()).expect("statics");
            catena::run::run(st, &mut [], catena::run::RunOptions::default()).expect("run")
        })
    });
    // The same on one thread (`--threads 1`): the run above steps on two where it may (issue 48).
    g.bench_function("heave_benchmark_full_1t", |b| {
        b.iter(|| {
            let st = catena::run::statics::solve(scene.clone()).expect("statics");
            let opts = catena::run::RunOptions::with_threads(Some(1));
            catena::run::run(st, &mut [], opts).expect("run")
        })
    });
    // What the outputs cost (issue 31: at most 10 % over the bare stepper): the same 2000 steps
    // from the same statics, (a) the bare stepper (the dynamic model prepared, then `advance`
    // 2000 times, nothing observed), (b) `run::run` with its built-in outputs (range graphs,
    // gauges, touchdown, top history) and the command line's HDF5 recorder writing every record
    // to a file, as `catena run` does.
    let st = catena::run::statics::solve(scene.clone()).expect("statics");
    g.bench_function("heave_bare_stepper", |b| {
        b.iter(|| {
            let (spec, dm) = catena::run::prepare(&st).expect("dynamic model");
            let mut ws = DynWorkspace::new(&dm.line).expect("ws");
            let mut s = dynamics::initial_state(&dm, &st.u, &mut ws);
            let steps = (spec.duration / spec.dt).round() as usize;
            for _ in 0..steps {
                dynamics::advance(&dm, &mut s, &mut ws, spec.dt).expect("step");
            }
            s
        })
    });
    // The same on two threads (issue 48): the line stepped in two parts by a [`Pair`], the second
    // part's State handed over after every step; the same States to the bit.
    g.bench_function("heave_bare_stepper_2t", |b| {
        b.iter(|| {
            let (spec, dm) = catena::run::prepare(&st).expect("dynamic model");
            // Shared with the second thread during each step.
            let dm = std::sync::Arc::new(dm);
            let mut ws = DynWorkspace::new(&dm.line).expect("ws");
            let mut s = dynamics::initial_state(&dm, &st.u, &mut ws);
            let mut pair = Pair::start(&dm, &s, &mut ws)
                .expect("a thread")
                .expect("a line in two parts");
            let steps = (spec.duration / spec.dt).round() as usize;
            for _ in 0..steps {
                pair.advance(&dm, &mut s, &mut ws, spec.dt).expect("step");
            }
            s
        })
    });
    let dir = std::env::temp_dir().join(format!("catena-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let h5 = dir.join("results.h5");
    let spec = st.scene.dynamic.as_ref().expect("a dynamic table");
    let gauges: Vec<String> = spec.gauges.iter().map(|g| g.name.clone()).collect();
    // Compressed as `catena run` does it (when records are decimated).
    let compress = spec.output_every > 1;
    g.bench_function("heave_run_with_outputs", |b| {
        // The last iteration's file is deleted outside the timing (as `catena run` moves it aside).
        b.iter_batched(
            || {
                let _ = std::fs::remove_file(&h5);
            },
            |()| {
                let mut rec =
                    catena_io::h5::Recorder::create(&h5, &st, &gauges, compress).expect("recorder");
                let r = catena::run::run(
                    st.clone(),
                    &mut [&mut rec],
                    catena::run::RunOptions::default(),
                )
                .expect("run");
                drop(rec);
                r
            },
            criterion::BatchSize::PerIteration,
        )
    });
    let (spec, dm) = catena::run::prepare(&st).expect("dynamic model");
    let mut ws = DynWorkspace::new(&dm.line).expect("ws");
    let state0 = dynamics::initial_state(&dm, &st.u, &mut ws);
    g.bench_function("heave_one_step", |b| {
        b.iter(|| {
            let mut s = state0.clone();
            dynamics::advance(&dm, &mut s, &mut ws, spec.dt).expect("step")
        })
    });
    g.finish();
}

/// What waves cost per step, measured on real storm steps: 20 consecutive steps from a developed
/// sea (t = 120 s, after the ramp), against the parts waves add for the same 20 times: the water
/// kinematics at every node and the vessel's motion. Two lines: the 1000 m SCR on 400 elements of
/// 4 m hung from the semi in a JONSWAP sea of 400 components (Hs 5 m, Tp 9.9 s), and the paper's
/// fatigue case as it runs (`cases/scr1000/storm23.toml`: 860 elements, 5 m near the surface,
/// 0.5 m in the touchdown zone).
///
/// Each line twice: as the scene runs by default, the kinematics sampled every `Tp/40` = 0.2475 s
/// and interpolated ([`catena_fe::wave_sampling`]), and with `kinematics_interval = 0` (exact at
/// every node at every step, `_exact`). Waves add `waves_20_steps` to `20_steps`; their share is
/// `waves / (steps − waves)`. (One step repeated from the same state would reuse the very step's
/// factorisation and converge sooner than in a storm, making the waves' share look larger.)
fn waves(c: &mut Criterion) {
    use catena::scene::edit::Edit;
    use catena::scene::DirResolver;
    use catena_fe::wave_sampling::{fill_interval, grid_index, interpolate, KinematicsGrid};
    let case =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/benchmarks/scr-regular-wave.toml");
    let files = DirResolver::beside(&case);
    let base = catena::run::statics::read_scene(&case).expect("case");
    let storm = [
        Edit::set("waves.kind", "jonswap"),
        Edit::set("waves.hs", 5.0),
        Edit::set("waves.tp", 9.9),
        Edit::set("waves.seed", 23i64),
        Edit::set("waves.components", 400i64),
        Edit::remove("waves.height"),
        Edit::remove("waves.period"),
        Edit::set("waves.ramp", 100.0),
    ];
    let exact = [Edit::set("waves.kinematics_interval", 0.0)];
    let line400 = base.edited(&storm, &files).expect("storm scene");
    let line400_exact = line400.edited(&exact, &files).expect("exact");
    let storm23_case = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/scr1000/storm23.toml");
    let storm23 = catena::run::statics::read_scene(&storm23_case).expect("storm 23");
    two_threads_in_a_storm(c, storm23.clone());
    storm_phases(c, storm23.clone());
    let storm23_exact = storm23
        .edited(&exact, &DirResolver::beside(&storm23_case))
        .expect("exact");
    let mut g = c.benchmark_group("waves");
    g.sample_size(20);
    for (name, scene) in [
        ("line400", line400),
        ("line400_exact", line400_exact),
        ("storm23_fatigue_mesh", storm23),
        ("storm23_fatigue_mesh_exact", storm23_exact),
    ] {
        let (spec, dm, mut ws, state) = storm_at_120_s(scene);
        g.bench_function(format!("{name}_20_steps"), |b| {
            b.iter(|| storm_steps(&dm, &state, &mut ws, spec.dt))
        });
        // The parts waves add, alone, at the same times and the nodes' positions at the start:
        // what `dynamics` does for the kinematics (sampled on the grid and interpolated, or
        // exact at every node) and the vessel's motion.
        let waves = dm.environment.waves.as_ref().expect("waves");
        let level = dm.environment.water_level;
        let nodes: Vec<(f64, f64)> = (0..dm.line.nodes())
            .map(|i| {
                (
                    dm.placement.base[3 * i] + state.u[3 * i],
                    dm.placement.base[3 * i + 1] + state.u[3 * i + 1] - level,
                )
            })
            .collect();
        let mut sc = waves.scratch();
        let h = waves.kinematics_interval;
        let mut grid = KinematicsGrid::default();
        for s in &mut grid.samples {
            s.resize(nodes.len(), None);
        }
        let at = |_: f64, i: usize| nodes[i];
        let all = 0..nodes.len();
        // The samples around the first step's end are the previous steps' (as in a run): taken
        // before the timing; within it, a new sample every `h`, as a run takes them.
        if h > 0.0 {
            let first = grid_index(state.t + spec.dt, h);
            fill_interval(
                waves,
                (h, first),
                None,
                at,
                (&mut grid, all.clone()),
                &mut sc,
            );
        }
        let start = grid.clone();
        let mut next = grid.clone();
        g.bench_function(format!("{name}_waves_20_steps"), |b| {
            b.iter(|| {
                let mut acc = 0.0;
                grid.index = start.index;
                for (s, s0) in grid.samples.iter_mut().zip(&start.samples) {
                    s.copy_from_slice(s0);
                }
                for j in 1..=STEPS {
                    let t = state.t + j as f64 * spec.dt;
                    if h > 0.0 {
                        let m = grid_index(t, h);
                        if grid.index != m {
                            let to = (&mut next, all.clone());
                            fill_interval(waves, (h, m), Some(&grid), at, to, &mut sc);
                            std::mem::swap(&mut grid, &mut next);
                        }
                        let s = (t - (m - 1) as f64 * h) / h;
                        for (k0, k1) in grid.samples[0].iter().zip(&grid.samples[1]) {
                            if let (Some(k0), Some(k1)) = (k0, k1) {
                                acc += interpolate(k0, k1, s, h).velocity[0];
                            }
                        }
                    } else {
                        for &(x, z) in &nodes {
                            if let Some(k) = waves.kinematics_with(x, z, t, &mut sc) {
                                acc += k.velocity[0];
                            }
                        }
                    }
                    acc += dm.top_at(t).map_or(0.0, |s| s.d[0]);
                }
                acc
            })
        });
    }
    g.finish();
}

/// Storm 23 on its fatigue mesh, 200 steps from 120 s on one thread and on two (a [`Pair`], each
/// thread sampling the waves at its own nodes, or the samples shared; started for each round, as
/// the partner's State must start from the same State).
fn two_threads_in_a_storm(c: &mut Criterion, scene: catena::scene::riser::RiserScene) {
    const N: usize = 200;
    let (spec, dm, mut ws, state) = storm_at_120_s(scene);
    // Shared with the second thread during each step.
    let dm = std::sync::Arc::new(dm);
    let mut g = c.benchmark_group("storm_two_threads");
    g.sample_size(10);
    g.bench_function("storm23_200_steps_1t", |b| {
        b.iter(|| {
            let mut s = state.clone();
            for _ in 0..N {
                dynamics::advance(&dm, &mut s, &mut ws, spec.dt).expect("step");
            }
            s
        })
    });
    // Each thread sampling its own nodes, and the second also sampling the first part's nodes
    // next to the cut (`Pair::start`'s).
    for (name, samples) in [
        ("storm23_200_steps_2t", Samples::Own),
        ("storm23_200_steps_2t_shared", Samples::Shared),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut s = state.clone();
                let mut pair = Pair::start_with(&dm, &s, &mut ws, samples)
                    .expect("a thread")
                    .expect("a line in two parts");
                for _ in 0..N {
                    pair.advance(&dm, &mut s, &mut ws, spec.dt).expect("step");
                }
                pair.stop(&dm, &mut ws);
                s
            })
        });
    }
    g.finish();
}

/// What one thread computes of a storm step's phase, on the line or on one part of it (see
/// [`storm_phases`]): its own Model, State and arrays, as a pair's thread has.
struct PhaseWork {
    dm: catena_fe::dynamics::DynamicModel,
    state: catena_fe::dynamics::DynState,
    kin: Vec<Option<catena_fe::waves::Kinematics>>,
    asm: catena_fe::assembly::Assembler,
    loads: catena_fe::loads::LoadScratch,
    grid: catena_fe::wave_sampling::KinematicsGrid,
    prev: catena_fe::wave_sampling::KinematicsGrid,
    sc: catena_fe::waves::WaveScratch,
    part: catena_fe::assembly::Part,
}

/// The phase coded `code` on `w`'s part: 0, the forces and the tangent (the structure, then the
/// loads: seabed, drag and wave inertia, the wave kinematics given); 1, the wave samples of a grid
/// time (the earlier one copied from the interval before, as in a run).
fn phase(w: &mut PhaseWork, code: u8) {
    use catena_fe::loads::{self, Iterate, SeabedPass, TangentScale};
    use catena_fe::waves::WaveKinematics;
    let (dm, st) = (&w.dm, &w.state);
    if code == 0 {
        let elements = w.part.elements.clone();
        w.asm
            .assemble_structure_part(&dm.line, &dm.placement, &st.u, (0.0, true), elements);
        let seabed = SeabedPass::Trial {
            committed: &st.history,
            anchors: &st.friction_anchor,
            dt: 0.05,
            memo: &mut [],
            keep: None,
        };
        let at = Iterate {
            u: &st.u,
            v: &st.v,
            wave_kin: &w.kin,
        };
        let scale = TangentScale {
            with_k: true,
            k: 0.9,
            c_v: 40.0,
        };
        let to = (&mut w.asm, &mut w.loads);
        loads::assemble_part(&dm.loads(), &at, seabed, scale, to, &w.part);
    } else if let Some(waves) = &dm.environment.waves {
        let (pl, level) = (&dm.placement, dm.environment.water_level);
        let h = waves.sampling_interval();
        let m = catena_fe::wave_sampling::grid_index(st.t, h) + 1;
        let at = |_: f64, i: usize| {
            (
                pl.base[3 * i] + st.u[3 * i],
                pl.base[3 * i + 1] + st.u[3 * i + 1] - level,
            )
        };
        let to = (&mut w.grid, w.part.nodes.clone());
        catena_fe::wave_sampling::fill_interval(waves, (h, m), Some(&w.prev), at, to, &mut w.sc);
    }
}

/// A storm step's phases on one thread and on two (issue 48: "the speed-up of each phase"), storm
/// 23 on its fatigue mesh at 120 s: the forces and the tangent (`forces_{1,2}t`) and the wave
/// samples of a grid time (`samples_{1,2}t`), each part alone on one thread too
/// (`{forces,samples}_{first,second}_part`), on two threads the caller taking the first part and a
/// [`catena_fe::partner::Partner`] the second, cut where the pair cuts the line
/// ([`catena_fe::assembly::Assembler::split_at_node`]). The band's factorisation and solve on one
/// and two threads are `scr1000_factor_{1,2}t` and `scr1000_solve_{1,2}t` (the `statics` bench).
fn storm_phases(c: &mut Criterion, scene: catena::scene::riser::RiserScene) {
    use catena_fe::assembly::{Assembler, Part};
    use catena_fe::partner::Partner;
    use catena_fe::wave_sampling::KinematicsGrid;
    use catena_fe::waves::WaveKinematics;
    let (_, dm, _, state) = storm_at_120_s(scene);
    let n = dm.line.nodes();
    let waves = dm.environment.waves.clone().expect("waves");
    let mut sc = waves.scratch();
    let (pl, level) = (&dm.placement, dm.environment.water_level);
    let kin = (0..n)
        .map(|i| {
            let (x, z) = (
                pl.base[3 * i] + state.u[3 * i],
                pl.base[3 * i + 1] + state.u[3 * i + 1],
            );
            waves.water_at(x, z - level, state.t, &mut sc)
        })
        .collect();
    let grid = KinematicsGrid {
        index: 0,
        samples: [vec![None; n], vec![None; n]],
    };
    let mut asm = Assembler::new(&dm.line).expect("assembler");
    let k = asm.split_at_node(&dm.line).expect("a band cut in two");
    let work = |part: Part| PhaseWork {
        dm: dm.clone(),
        state: state.clone(),
        kin: Vec::clone(&kin),
        asm: Assembler::new(&dm.line).expect("assembler"),
        loads: catena_fe::loads::LoadScratch::new(n),
        grid: grid.clone(),
        prev: KinematicsGrid {
            index: catena_fe::wave_sampling::grid_index(state.t, waves.sampling_interval()),
            ..grid.clone()
        },
        sc: waves.scratch(),
        part,
    };
    let [first, second] = Part::halves(&dm.line, k);
    let mut whole = work(Part::whole(&dm.line));
    let mut parts = [work(first.clone()), work(second.clone())];
    let mut mine = work(first);
    let partner = Partner::start(work(second), phase).expect("a thread");
    let mut g = c.benchmark_group("storm_phases");
    g.sample_size(20);
    for (name, code) in [("forces", 0), ("samples", 1)] {
        g.bench_function(format!("{name}_1t"), |b| b.iter(|| phase(&mut whole, code)));
        // Each part alone on one thread: how evenly the cut shares the phase.
        for (w, part) in parts.iter_mut().zip(["first", "second"]) {
            g.bench_function(format!("{name}_{part}_part"), |b| b.iter(|| phase(w, code)));
        }
        g.bench_function(format!("{name}_2t"), |b| {
            b.iter(|| {
                partner.ask(code);
                phase(&mut mine, code);
                drop(partner.wait());
            })
        });
    }
    g.finish();
}

/// A storm scene's dynamic Model, Workspace and State after 120 s (the ramp over).
fn storm_at_120_s(
    scene: catena::scene::riser::RiserScene,
) -> (
    catena::scene::riser::DynamicSpec,
    catena_fe::dynamics::DynamicModel,
    DynWorkspace,
    catena_fe::dynamics::DynState,
) {
    let st = catena::run::statics::solve(scene).expect("statics");
    let (spec, dm) = catena::run::prepare(&st).expect("dynamic model");
    let mut ws = DynWorkspace::new(&dm.line).expect("ws");
    let mut state = dynamics::initial_state(&dm, &st.u, &mut ws);
    while state.t < 120.0 - 0.5 * spec.dt {
        dynamics::advance(&dm, &mut state, &mut ws, spec.dt).expect("step");
    }
    (spec, dm, ws, state)
}

/// [`STEPS`] steps of `dt` from a copy of `state`.
fn storm_steps(
    dm: &catena_fe::dynamics::DynamicModel,
    state: &catena_fe::dynamics::DynState,
    ws: &mut DynWorkspace,
    dt: f64,
) -> catena_fe::dynamics::DynState {
    let mut s = state.clone();
    for _ in 0..STEPS {
        dynamics::advance(dm, &mut s, ws, dt).expect("step");
    }
    s
}

/// What axial seabed friction costs a storm step: storm 23 (the fatigue mesh, 400 wave components)
/// without and with `[seabed.friction]` (μ 0.5, δ 5 mm), 20 steps from the state at 120 s.
fn friction(c: &mut Criterion) {
    use catena::scene::riser::RiserScene;
    use catena::scene::DirResolver;
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/scr1000/storm23.toml");
    let files = DirResolver::beside(&case);
    let text = std::fs::read_to_string(&case).expect("case");
    let with_friction = format!("{text}\n[seabed.friction]\naxial = 0.5\nmobilisation = 0.005\n");
    let mut g = c.benchmark_group("friction");
    g.sample_size(20);
    for (name, text) in [("storm23", &text), ("storm23_friction", &with_friction)] {
        let scene = RiserScene::parse("storm23", text, &files).expect("scene");
        let (spec, dm, mut ws, state) = storm_at_120_s(scene);
        g.bench_function(format!("{name}_20_steps"), |b| {
            b.iter(|| storm_steps(&dm, &state, &mut ws, spec.dt))
        });
    }
    g.finish();
}

/// Steps of a storm benchmark.
const STEPS: usize = 20;

/// What a line of sections costs per step: the steel lazy wave of `cases/lazy-wave/cabledyn-heave.toml`
/// (770 elements of three sections, a linear seabed like the heave benchmark's, 2000 steps of the
/// heave benchmark's motion), the dynamics alone (from a solved statics: the lazy wave's statics
/// take longer, for its seed), no output; and the heave benchmark the same way. Its cost per element-step and per
/// element-iteration against `heave/heave_benchmark_full` (400 elements of one section) is in
/// `benches/README.md`; the Newton iterations of both are printed once.
fn sections(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut g = c.benchmark_group("sections");
    g.sample_size(10);
    for (name, case) in [
        (
            "lazy_wave_heave_full",
            "cases/lazy-wave/cabledyn-heave.toml",
        ),
        ("scr_heave_full", "cases/benchmarks/scr-heave.toml"),
    ] {
        let scene = catena::run::statics::read_scene(&root.join(case)).expect("case");
        let st = catena::run::statics::solve(scene).expect("statics");
        let run = |st: &catena::run::statics::StaticRun| {
            catena::run::run(st.clone(), &mut [], catena::run::RunOptions::default()).expect("run")
        };
        let r = run(&st);
        println!(
            "{name}: {} elements, {} steps, {} Newton iterations",
            r.model.line.elements.len(),
            r.steps,
            r.iterations
        );
        g.bench_function(name, |b| b.iter(|| run(&st)));
    }
    g.finish();
}

/// Storm 23 (`cases/scr1000/storm23.toml`: the fatigue mesh, 400 wave components) cut to 30 s,
/// its ramp to 10 s and its envelopes and fatigue counted from 10 s; its case text and where its
/// files are read from.
fn storm23_30s() -> (String, catena::scene::DirResolver) {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/scr1000/storm23.toml");
    let files = catena::scene::DirResolver::beside(&case);
    let text = std::fs::read_to_string(&case)
        .expect("case")
        .replace("duration = 1800.0", "duration = 30.0")
        .replace("envelope_start = 200.0", "envelope_start = 10.0")
        .replace("start = 200.0", "start = 10.0")
        .replace("ramp = 100.0", "ramp = 10.0");
    (text, files)
}

/// What the strength check costs a storm run: storm 23 on the fatigue mesh (861 nodes, 400 wave
/// components, its fatigue counting on) for 30 s (600 steps, the 10 s ramp shortened to fit), run
/// through `run::run` with its built-in outputs, without and with a DNV `[design_check]` from t = 0
/// (every node, every step). The statics are solved once, outside the timing.
fn design_check(c: &mut Criterion) {
    use catena::scene::riser::RiserScene;
    let (text, files) = storm23_30s();
    let with_check = format!(
        "{text}\n[design_check]\ncode = \"dnv-st-f201\"\nsmys = 448e6\nsmts = 531e6\ninternal_pressure = 15e6\nstart = 0.0\n"
    );
    let mut g = c.benchmark_group("design_check");
    g.sample_size(10);
    for (name, text) in [
        ("storm23_30s", &text),
        ("storm23_30s_design_check", &with_check),
    ] {
        let scene = RiserScene::parse("storm23", text, &files).expect("scene");
        let st = catena::run::statics::solve(scene).expect("statics");
        g.bench_function(name, |b| {
            b.iter(|| {
                catena::run::run(st.clone(), &mut [], catena::run::RunOptions::default())
                    .expect("run")
            })
        });
    }
    g.finish();
}

/// A run's threads (`RunOptions::threads`, `catena run --threads`): storm 23 on the fatigue mesh
/// (861 nodes, 400 wave components) for 30 s (600 steps, the ramp shortened to 10 s, its fatigue
/// counted from 10 s), through `run::run` with its built-in outputs, on one thread (the fatigue
/// counting on the stepping thread) and on two (the counting on a thread of its own). The phase
/// the second thread takes is the counting; the stepping is one thread either way. The statics are
/// solved once, outside the timing; the damage is the same to the bit (`tests/sea.rs`).
fn threads(c: &mut Criterion) {
    use catena::scene::riser::RiserScene;
    let (text, files) = storm23_30s();
    let scene = RiserScene::parse("storm23", &text, &files).expect("scene");
    let st = catena::run::statics::solve(scene).expect("statics");
    let mut g = c.benchmark_group("threads");
    g.sample_size(10);
    for threads in [1, 2] {
        g.bench_function(format!("storm23_30s_fatigue_{threads}_thread"), |b| {
            b.iter(|| {
                let opts = catena::run::RunOptions {
                    threads: Some(threads),
                    ..catena::run::RunOptions::default()
                };
                let r = catena::run::run(st.clone(), &mut [], opts).expect("run");
                assert!(r.fatigue.is_some(), "counted");
                r
            })
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    bench,
    waves,
    friction,
    sections,
    design_check,
    threads
);
criterion_main!(benches);
