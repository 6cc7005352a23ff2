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
