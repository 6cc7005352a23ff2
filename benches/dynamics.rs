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

criterion_group!(benches, bench);
criterion_main!(benches);
