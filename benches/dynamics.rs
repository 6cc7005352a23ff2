//! The heave benchmark (`cases/benchmarks/scr-heave.toml`: 400 elements, 2000 steps of 0.05 s),
//! statics included, without file output: the target is 1 s of wall time on one core.
//! Also one dynamic step on its own.
//!
//! Run: `cargo bench -p catena-benches --bench dynamics`.

use std::path::Path;

use catena_fe::dynamics::{self, DynWorkspace};
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/benchmarks/scr-heave.toml");
    let scene = catena::statics::read_scene(&case).expect("case");
    let mut g = c.benchmark_group("heave");
    g.sample_size(10);
    g.bench_function("heave_benchmark_full", |b| {
        b.iter(|| {
            let st = catena::statics::solve(scene.clone()).expect("statics");
            catena::run::run(st, &mut [], catena::run::RunOptions::default()).expect("run")
        })
    });
    let st = catena::statics::solve(scene.clone()).expect("statics");
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

/// What waves cost per step: the 1000 m SCR on 400 elements of 4 m hung from the semi, one step at
/// t = 20 s (after the ramp), in a JONSWAP sea of 400 components (Hs 5 m, Tp 9.9 s) with the vessel,
/// against the same line with its top held still and no waves.
fn waves(c: &mut Criterion) {
    use catena::scene::edit::Edit;
    use catena::scene::DirResolver;
    let case =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/benchmarks/scr-regular-wave.toml");
    let files = DirResolver::beside(&case);
    let base = catena::statics::read_scene(&case).expect("case");
    let storm = base
        .edited(
            &[
                Edit::set("waves.kind", "jonswap"),
                Edit::set("waves.hs", 5.0),
                Edit::set("waves.tp", 9.9),
                Edit::set("waves.seed", 23i64),
                Edit::set("waves.components", 400i64),
                Edit::remove("waves.height"),
                Edit::remove("waves.period"),
                Edit::set("waves.ramp", 10.0),
            ],
            &files,
        )
        .expect("storm scene");
    let calm = base
        .edited(&[Edit::remove("waves"), Edit::remove("vessel")], &files)
        .expect("calm scene");
    // The paper's fatigue case as it runs: storm 23 on the fatigue mesh (860 elements, 5 m near the
    // surface, 0.5 m in the touchdown zone), the semi, 400 components.
    let storm23_case = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/scr1000/storm23.toml");
    let storm23 = catena::statics::read_scene(&storm23_case).expect("storm 23");
    let mut g = c.benchmark_group("waves");
    g.sample_size(20);
    for (name, scene) in [
        ("step_400_components", storm),
        ("step_no_waves", calm),
        ("storm23_fatigue_mesh_step", storm23),
    ] {
        let st = catena::statics::solve(scene).expect("statics");
        let (spec, dm) = catena::run::prepare(&st).expect("dynamic model");
        let mut ws = DynWorkspace::new(&dm.line).expect("ws");
        let mut state = dynamics::initial_state(&dm, &st.u, &mut ws);
        for _ in 0..400 {
            dynamics::advance(&dm, &mut state, &mut ws, spec.dt).expect("step");
        }
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut s = state.clone();
                dynamics::advance(&dm, &mut s, &mut ws, spec.dt).expect("step")
            })
        });
        // The parts waves add to a step, alone: the kinematics at every node (once per attempt)
        // and the vessel's motion (once per step).
        if let Some(waves) = &dm.environment.waves {
            let level = dm.environment.water_level;
            let nodes: Vec<(f64, f64)> = st
                .results
                .x
                .iter()
                .zip(&st.results.z)
                .map(|(x, z)| (*x, *z - level))
                .collect();
            let mut sc = waves.scratch();
            let mut t = 20.0;
            let kin_name = if name == "step_400_components" {
                "kinematics_at_every_node".to_string()
            } else {
                format!("{name}_kinematics")
            };
            g.bench_function(kin_name, |b| {
                b.iter(|| {
                    t += spec.dt;
                    let mut acc = 0.0;
                    for &(x, z) in &nodes {
                        if let Some(k) = waves.kinematics_with(x, z, t, &mut sc) {
                            acc += k.velocity[0];
                        }
                    }
                    acc
                })
            });
            if name == "step_400_components" {
                g.bench_function("vessel_motion", |b| {
                    b.iter(|| {
                        t += spec.dt;
                        dm.top_at(t)
                    })
                });
            }
        }
    }
    g.finish();
}

criterion_group!(benches, bench, waves);
criterion_main!(benches);
