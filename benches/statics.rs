//! The static solve of the 1000 m SCR (`cases/scr1000/static-linear-k100.toml`: 860 elements,
//! 0.5 m in the touchdown zone), and the cost of one Newton iteration split into its parts:
//!
//! - `scr1000_static_solve`: the whole solve from the catenary seed (seed, workspace with symbolic
//!   factorisation, Newton);
//! - `scr1000_assemble`: one assembly of residual and tangent;
//! - `scr1000_factor_solve`: one numeric LDLᵀ factorisation and solve;
//! - `scr1000_factor_{1,2}t`, `scr1000_solve_{1,2}t`: the factorisation and the solve apart, on one
//!   thread and on two ([`catena_fe::assembly::Assembler::use_partner`]);
//! - `scr1000_symbolic`: building the workspace (pattern and symbolic factorisation, once per run).
//!
//! Run: `cargo bench -p catena-benches --bench statics`.

use std::path::Path;

use catena_fe::statics::{self, Placement, StaticOptions, StaticWorkspace};
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    let case =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/scr1000/static-linear-k100.toml");
    let scene = catena::run::statics::read_scene(&case).expect("case");
    let model = scene.model.clone();
    c.bench_function("scr1000_static_solve", |b| {
        b.iter(|| {
            let q = statics::catenary_seed(&model, &scene.ends.positions(&model)).expect("seed");
            let pl = Placement::new(&q);
            let mut u = vec![0.0; q.len()];
            let mut ws = StaticWorkspace::new(&model).expect("ws");
            statics::solve(&model, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("solve")
        })
    });
    let q = statics::catenary_seed(&model, &scene.ends.positions(&model)).expect("seed");
    let pl = Placement::new(&q);
    let mut u = vec![0.0; q.len()];
    let mut ws = StaticWorkspace::new(&model).expect("ws");
    statics::solve(&model, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("solve");
    c.bench_function("scr1000_assemble", |b| {
        b.iter(|| ws.assemble(&model, &pl, &u, true))
    });
    // The same right-hand side every time (solved in place over and over, it decayed to zeros
    // after about 65 solves, and the benchmark measured solves of zeros).
    let b0: Vec<f64> = (0..model.n_eq)
        .map(|i| 1e3 * (0.37 * i as f64).cos())
        .collect();
    let mut rhs = b0.clone();
    c.bench_function("scr1000_factor_solve", |b| {
        b.iter(|| {
            rhs.copy_from_slice(&b0);
            ws.asm.factor_tangent().expect("factor");
            ws.asm.solve_tangent(&mut rhs);
        })
    });
    // The same factorisation and solve apart, on one thread and on two (the bottom end on a
    // partner thread: the same values to the bit).
    for threads in [1, 2] {
        if threads == 2 {
            assert!(ws.asm.use_partner().expect("thread"), "a twisted band");
        }
        c.bench_function(&format!("scr1000_factor_{threads}t"), |b| {
            b.iter(|| ws.asm.factor_tangent().expect("factor"))
        });
        c.bench_function(&format!("scr1000_solve_{threads}t"), |b| {
            b.iter(|| {
                rhs.copy_from_slice(&b0);
                ws.asm.solve_tangent(&mut rhs);
            })
        });
    }
    c.bench_function("scr1000_symbolic", |b| {
        b.iter(|| StaticWorkspace::new(&model).expect("ws"))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = bench
}
criterion_main!(benches);
