//! The animated touchdown zone (`catena_io::animate`): a real run's records drawn within the frame
//! budget, to a GIF that decodes frame by frame, small enough to e-mail; the frame choice; bad
//! shapes refused with the source named.

use std::path::Path;

use catena::observe::Observer;
use catena::run::records::Records as RunRecords;
use catena::run::RunOptions;
use catena_io::animate::{animate, diameters, frame_records, Colour, Options, Records};

mod common;

fn heave_records(duration: f64) -> Records {
    let scene = common::heave_scene(&[
        ("dynamic.duration", duration),
        ("dynamic.output_interval", 0.5),
        ("dynamic.envelope_start", 0.0),
    ]);
    let od = scene.model.node_od.clone();
    let mut rec = RunRecords::new();
    {
        let mut extra: [&mut dyn Observer; 1] = [&mut rec];
        catena::run::simulate(scene, &mut extra, RunOptions::default()).expect("the run completes");
    }
    let series = |n: &str| rec.series.iter().find(|s| s.0 == n).expect(n).1.clone();
    let field = |n: &str| rec.fields.iter().find(|s| s.0 == n).expect(n).1.clone();
    Records {
        arc: rec.arc.clone(),
        time: series("time"),
        x: field("x"),
        z: field("z"),
        penetration: field("penetration"),
        seabed_force: field("seabed_force"),
        bending_moment: field("bending_moment"),
        top_x: series("top_x"),
        top_z: series("top_z"),
        od,
        follow_touchdown: false,
    }
}

#[test]
fn the_frames_are_chosen_evenly_within_the_budget_first_and_last_always() {
    assert_eq!(frame_records(5, 120), vec![0, 1, 2, 3, 4]);
    let f = frame_records(2001, 120);
    assert_eq!(f.len(), 120);
    assert_eq!((f[0], f[119]), (0, 2000));
    let gaps: Vec<usize> = f.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(gaps.iter().all(|&g| g == 16 || g == 17), "{gaps:?}");
}

#[test]
fn a_heave_run_animates_to_a_small_gif_that_decodes_frame_by_frame() {
    let rec = heave_records(20.0);
    let dir = std::env::temp_dir().join(format!("catena-animate-{}", std::process::id()));
    for (colour, budget) in [(Colour::Penetration, 30), (Colour::SeabedForce, 12)] {
        let path = dir.join(format!("tdz-{budget}.gif"));
        let opts = Options {
            frames: budget,
            colour,
            ..Options::default()
        };
        let r = animate(&path, &rec, &opts).expect("animates");
        // 41 records (0 to 20 s every 0.5 s): `budget` of them drawn.
        assert_eq!(r.frames, budget);
        assert_eq!(r.seconds, 20.0);
        let bytes = std::fs::read(&path).expect("written");
        assert_eq!(bytes.len() as u64, r.bytes);
        assert!(r.bytes < 400_000, "{} bytes for {budget} frames", r.bytes);
        let mut d = gif::DecodeOptions::new();
        d.set_color_output(gif::ColorOutput::Indexed);
        let mut d = d.read_info(bytes.as_slice()).expect("a GIF");
        assert_eq!((d.width(), d.height()), (800, 760));
        let mut frames = 0;
        let mut changed = 0usize;
        while let Some(f) = d.read_next_frame().expect("a frame decodes") {
            if frames > 0 {
                // After the first, each frame holds only what changed (and some of it does: the
                // line moves).
                assert_eq!(f.transparent, Some(255));
                changed += f.buffer.iter().filter(|&&p| p != 255).count();
            }
            frames += 1;
        }
        assert_eq!(frames, budget);
        assert!(
            changed > 1000,
            "the frames after the first change {changed} pixels"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn records_of_the_wrong_shape_are_refused_naming_the_source() {
    let mut rec = heave_records(1.0);
    rec.od.pop();
    let e = animate(Path::new("/tmp/never.gif"), &rec, &Options::default())
        .expect_err("a diameter short");
    let m = e.to_string();
    assert!(
        m.contains("never.gif") && m.contains("outer diameter"),
        "{m}"
    );
    let e = animate(
        Path::new("/tmp/never.gif"),
        &Records::default(),
        &Options::default(),
    )
    .expect_err("no records");
    assert!(e.to_string().contains("nothing to animate"), "{e}");
}

#[test]
fn the_diameters_come_from_the_scene_or_line_od() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let case = root.join("cases/lazy-wave/static.toml");
    let text = std::fs::read_to_string(&case).expect("the lazy wave reads");
    let scene = catena::statics::read_scene(&case).expect("the lazy wave parses");
    let n = scene.model.node_od.len();
    let od = diameters(&text, &case.display().to_string(), n).expect("its diameters");
    // A line of sections: the buoyancy modules' diameter differs from the pipe's.
    assert_eq!(od, scene.model.node_od);
    assert!(od.iter().any(|&d| d != od[0]));
    // The short form, the case file gone: `line.od` for every node.
    let heave = std::fs::read_to_string(root.join("cases/benchmarks/scr-heave.toml"))
        .expect("the heave benchmark reads");
    let od = diameters(&heave, "/nowhere/scr-heave.toml", 7).expect("line.od");
    assert_eq!(od.len(), 7);
    assert!(od.iter().all(|&d| d == od[0] && d > 0.1));
    assert!(diameters("[line]\nlength = 3.0\n", "x.toml", 3).is_none());
}

/// A lay animates following its touchdown (`/lay/frames` of `results.h5`, every material point of
/// the pipe a node): 1500 s of the calm 12-inch lay, its frames read back from the file it wrote, a
/// GIF of every frame whose touchdown-zone window keeps its width and moves with the touchdown
/// point from the first frame to the last (to within the window's placement by node, 1 m).
#[test]
fn a_lay_animates_following_its_touchdown() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = std::fs::read_to_string(root.join("cases/lay/jlay-12in-steady.toml"))
        .expect("case")
        .replace("duration = 6100.0", "duration = 1500.0");
    let scene = catena::scene::riser::RiserScene::parse("lay.toml", &text, &catena::scene::NoFiles)
        .expect("scene");
    // On one thread: the tests run side by side (a pair each would oversubscribe the cores).
    let st = catena::run::statics::solve(catena::run::lay::statics_scene(scene)).expect("statics");
    let one = catena::run::lay::LayOptions {
        threads: Some(1),
        ..Default::default()
    };
    let lay = catena::run::lay::lay_with(st, one, &mut |_| true).expect("lay");
    let dir = std::env::temp_dir().join(format!("catena-animate-lay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let h5 = dir.join("results.h5");
    catena_io::h5::write_lay(&h5, &lay).expect("results.h5");
    let rec = catena_io::h5::read_animation(&h5).expect("a lay's frames");
    assert!(rec.follow_touchdown);
    assert_eq!(rec.arc.len(), lay.full.nodes());
    assert_eq!(rec.time, lay.frames.time);
    let frames = rec.time.len();
    let r = animate(
        &dir.join("lay.gif"),
        &rec,
        &Options {
            frames,
            ..Options::default()
        },
    )
    .expect("animates");
    assert_eq!(r.frames, frames);
    let td = |k: usize| {
        let n = rec.arc.len();
        let i = (0..n)
            .find(|&i| rec.penetration[k * n + i] > 0.0)
            .expect("a touchdown");
        rec.x[k * n + i]
    };
    let travel = td(frames - 1) - td(0);
    let [(a0, b0), (a1, b1)] = r.windows;
    println!("touchdown travel {travel:.2} m; window {a0:.2}–{b0:.2} m to {a1:.2}–{b1:.2} m");
    assert!(travel > 50.0, "the touchdown moved {travel} m");
    assert!(((b1 - a1) - (b0 - a0)).abs() < 1e-9);
    assert!(((a1 - a0) - travel).abs() < 1.0);
    let _ = std::fs::remove_dir_all(&dir);
}
