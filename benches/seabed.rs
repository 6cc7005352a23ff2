//! Seabed law throughput: 100 000 evaluations of each law.
//!
//! - `rq_cyclic_100k`: the Randolph–Quiggin law walked along 100 000 committed steps of a cyclic path
//!   (0.5D ± 0.05D, 50 cycles: every step a trial and a commit, with 100 reversals, each computing z_c);
//! - `rq_backbone_100k`: the static backbone (initial penetration) at 100 000 penetrations;
//! - `linear_100k`: the linear seabed with soil buoyancy at 100 000 penetrations.
//!
//! Run: `cargo bench -p catena-benches --bench seabed`.

use std::hint::black_box;

use catena_seabed::law::{Law, Seabed};
use catena_seabed::{LinearSeabed, RandolphQuiggin, RqHistory, RqParams, SoilBuoyancy};
use criterion::{criterion_group, criterion_main, Criterion};

const N: usize = 100_000;

fn bench(c: &mut Criterion) {
    let p = RqParams::table1();
    let rq = RandolphQuiggin::new(p).expect("valid");
    let d = p.diameter;
    let path: Vec<f64> = (0..N)
        .map(|i| {
            let t = i as f64 / N as f64;
            0.5 * d + 0.05 * d * (2.0 * std::f64::consts::PI * 50.0 * t).sin()
        })
        .collect();
    let mut start = RqHistory::untouched(0.0);
    start = rq.evaluate(&start, 0.5 * d).next;
    c.bench_function("rq_cyclic_100k", |b| {
        b.iter(|| {
            let mut h = start;
            let mut sum = 0.0;
            for &z in &path {
                let t = rq.evaluate(&h, black_box(z));
                sum += t.p;
                h = t.next;
            }
            black_box(sum)
        })
    });
    let zs: Vec<f64> = (0..N).map(|i| d * i as f64 / N as f64).collect();
    c.bench_function("rq_backbone_100k", |b| {
        b.iter(|| zs.iter().map(|&z| rq.p_ip(black_box(z)).0).sum::<f64>())
    });
    let lin = Seabed {
        law: Law::Linear(LinearSeabed::new(d, 100e3, 0.0).expect("valid")),
        buoyancy: Some(SoilBuoyancy::new(d, 1.5, 1500.0, 1025.0).expect("valid")),
    };
    let h0 = lin.untouched();
    c.bench_function("linear_100k", |b| {
        b.iter(|| {
            zs.iter()
                .map(|&z| lin.evaluate(&h0, black_box(z), 0.0, 0.0).total())
                .sum::<f64>()
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
