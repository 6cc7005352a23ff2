//! Short-term extremes (`[extremes]`) through a run: each channel's record is what the run's other
//! outputs saw (the sample extremes equal the range graphs' and the design check's, every step), and
//! the analysis of a record is `extremes::analyse` of it.

use std::path::{Path, PathBuf};

use catena::design_observer::DesignCheck;
use catena::extremes::{analyse, Tail};
use catena::extremes_observer::ExtremesObserver;
use catena::run::{self, RunOptions};
use catena::scene::riser::RiserScene;
use catena::scene::NoFiles;
use catena::statics;

mod common;
use common::Edit;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The heave benchmark (2 m, 10 s) for 100 s with its wall and contents, a design check, a gauge at
/// the static touchdown zone and `[extremes]` of every channel, everything from t = 0, target
/// 1 hour, 20 s blocks: the sample extreme of `top_tension` is the greatest top tension of
/// the range graphs, `least_tension` the least tension of any node, `sag_moment` the least moment
/// of any node, `utilisation` the design check's largest, `gauge:tdz` the gauge's least moment
/// (all the same steps, to the bit); each channel's analysis is `analyse` of its record; the most
/// probable extremes of an hour lie beyond the 100 s sample's; 2001 records a channel.
#[test]
fn each_channel_records_what_the_run_saw() {
    let text = std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml"))
        .expect("test data")
        .edit(
            "mass = 145.06 ",
            "wall = 0.0254\ncontents_density = 726.0\nmass = 145.06 ",
        )
        .edit("[dynamic]", "[[gauge]]\nname = \"tdz\"\narc = 1170.0\n\n[dynamic]")
        .edit("envelope_start = 50.0", "envelope_start = 0.0")
        + "\n[design_check]\ncode = \"dnv-st-f201\"\nsmys = 448e6\nsmts = 531e6\n\n[extremes]\nchannels = [\"top_tension\", \"least_tension\", \"sag_moment\", \"utilisation\", \"gauge:tdz\"]\ntarget_duration = 3600.0\nblock = 20.0\n";
    let scene = RiserScene::parse("heave.toml", &text, &NoFiles).expect("scene");
    let st = statics::solve(scene).expect("statics");
    let r = run::run(st, &mut [], RunOptions::default()).expect("run");
    let x = r.output::<ExtremesObserver>().expect("extremes");
    let e = &r.envelopes;
    let d = r.output::<DesignCheck>().expect("check");
    let least = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    let want = [
        e.tension.max[0],
        least(&e.tension.min),
        least(&e.moment.min),
        d.worst().expect("checked").1,
        r.gauges.traces[0].moment_extremes.0.expect("gauge minimum"),
    ];
    assert_eq!(x.results.len(), 5);
    for (k, res) in x.results.iter().enumerate() {
        println!(
            "{}: sample {:.6e} (the run's {:.6e}); MPM 1 h Rayleigh {:.6e}, Weibull {:?}, Gumbel {:?}",
            res.channel,
            res.sample_extreme,
            want[k],
            res.rayleigh[0],
            res.weibull.map(|w| w.1[0]),
            res.gumbel.map(|g| g.2[0])
        );
        assert_eq!(x.records[k].len(), 2001, "{}", res.channel);
        assert_eq!(res.sample_extreme, want[k], "{}", res.channel);
        let again = analyse(
            &res.channel,
            res.tail,
            &x.records[k],
            x.dt,
            &x.spec.settings,
        )
        .expect("analysed");
        assert_eq!(&again, res);
        let beyond = match res.tail {
            Tail::Max => res.rayleigh[0] > res.sample_extreme,
            Tail::Min => res.rayleigh[0] < res.sample_extreme,
        };
        assert!(beyond, "{}", res.channel);
    }
}
