//! `catena animate`: bad options and a results file without dynamics are refused with the file
//! and the option named, never a panic.

use std::path::Path;

use catena_cli::commands;

#[test]
fn bad_animations_are_refused_naming_the_file_and_the_option() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = std::env::temp_dir().join(format!("catena-animate-cli-{}", std::process::id()));
    commands::static_(&root.join("cases/benchmarks/scr-heave.toml"), &out).expect("statics run");
    let h5 = out.join("results.h5");
    let gif = out.join("tdz.gif");
    for (frames, fps, colour, target, key) in [
        (120, 12.0, "tension", &gif, "--colour"),
        (1, 12.0, "penetration", &gif, "--frames"),
        (120, 0.0, "penetration", &gif, "--fps"),
        (120, 12.0, "penetration", &out.join("tdz.png"), "--out"),
        (120, 12.0, "penetration", &gif, "no /dynamic group"),
    ] {
        let e = commands::animate(&h5, target, frames, fps, colour).expect_err(key);
        let m = e.to_string();
        assert!(m.contains("results.h5") && m.contains(key), "{key}: {m}");
    }
    let e = commands::animate(&out.join("missing.h5"), &gif, 120, 12.0, "penetration")
        .expect_err("no file");
    assert!(e.to_string().contains("missing.h5"), "{e}");
    let _ = std::fs::remove_dir_all(&out);
}

/// A results file animates with each node's own diameter after the files its scene names have
/// gone (the diameters are read from `/line`, not from the scene again): a lazy wave's buoyancy
/// section stays wider than its pipe, as in the run. Reading them from the scene (which no longer
/// reads) gave `line.od` everywhere.
#[test]
fn an_animation_keeps_each_nodes_diameter_when_the_scenes_files_are_gone() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = std::env::temp_dir().join(format!("catena-animate-od-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let text = std::fs::read_to_string(root.join("cases/lazy-wave/storm23.toml"))
        .expect("the lazy wave reads")
        .replace("duration = 1800.0", "duration = 1.0")
        .replace("start = 200.0", "start = 0.0");
    let case = dir.join("short.toml");
    std::fs::write(&case, text).expect("case written");
    std::fs::copy(
        root.join("cases/lazy-wave/semi-rao.csv"),
        dir.join("semi-rao.csv"),
    )
    .expect("RAO table copied");
    let model_od = catena::statics::read_scene(&case)
        .expect("the short lazy wave reads")
        .model
        .node_od;
    let out = dir.join("out");
    let opts = commands::RunCommandOptions::default();
    commands::run(&case, &out, &opts).expect("the short run completes");
    std::fs::remove_file(dir.join("semi-rao.csv")).expect("RAO table removed");
    assert!(
        catena::statics::read_scene(&case).is_err(),
        "the scene no longer reads"
    );
    let rec = catena_io::h5::read_animation(&out.join("results.h5")).expect("animation records");
    assert_eq!(rec.od, model_od);
    assert!(rec.od.iter().any(|&d| d > 1.5 * rec.od[0]), "{:?}", rec.od);
    let _ = std::fs::remove_dir_all(&dir);
}
