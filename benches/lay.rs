//! What a second of lay costs with 100 m and with 2 km of pipe laid (`[lay]`): the 12-inch J-lay in
//! calm water (`cases/lay/jlay-12in-steady.toml`) at 0.025 m/s, stepped on in 20 s pieces from the
//! moment 100 m and 2 km have been paid out (the setup lays them; not timed). The pipe far behind the
//! touchdown is frozen, so the two must be within 20 % (`benches/README.md`). The lay goes on
//! while criterion measures: the bench prints the length paid out when it ends.
//!
//! Run: `cargo bench -p catena-benches --bench lay`.

use std::path::Path;
use std::time::{Duration, Instant};

use catena::run::lay::{self, Lay};
use catena::scene::riser::RiserScene;
use catena::scene::NoFiles;
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/lay/jlay-12in-steady.toml");
    let text = std::fs::read_to_string(path)
        .expect("case")
        .replace(
            "speed = 0.05                  # m/s",
            "speed = 0.025\npipe_length = 4000.0 # m/s",
        )
        .replace("length = 300.0", "# length = 300.0")
        .replace("duration = 6100.0", "duration = 1.2e5");
    let scene = RiserScene::parse("lay.toml", &text, &NoFiles).expect("scene");
    let st = catena::run::statics::solve(lay::statics_scene(scene)).expect("statics");
    let mut g = c.benchmark_group("lay");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for laid in [100.0, 2000.0] {
        let mut l = Lay::start(&st).expect("lay");
        let mut go = |_: &lay::LayProgress| true;
        l.run_until(laid / 0.025, &mut go)
            .expect("lay to the start");
        let from = l.paid_out();
        g.bench_function(format!("lay_20s_after_{laid}m"), |b| {
            b.iter_custom(|iters| {
                let t0 = Instant::now();
                for _ in 0..iters {
                    let t = l.time() + 20.0;
                    let stop = l.run_until(t, &mut |_| true).expect("lay");
                    assert!(stop.is_none());
                }
                t0.elapsed()
            })
        });
        println!(
            "lay_20s_after_{laid}m: measured from {from:.0} m to {:.0} m paid out, {} nodes in the solve",
            l.paid_out(),
            l.window_nodes()
        );
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
