//! The command links HDF5's static library where the system has one (`crates/cli/build.rs`): it
//! then loads no shared libhdf5 (nor the 36 libraries that one brings), and still writes and reads
//! `results.h5` (the other tests).

use std::process::Command;

/// The system's `libhdf5.a`, found as the build script finds it; `None` where there is none.
fn static_archive() -> Option<std::path::PathBuf> {
    let out = Command::new("pkg-config")
        .args(["--libs-only-L", "hdf5"])
        .output()
        .ok()
        .filter(|o| o.status.success())?;
    let flags = String::from_utf8(out.stdout).ok()?;
    let dir = flags
        .split_whitespace()
        .find_map(|f| f.strip_prefix("-L"))?;
    let archive = std::fs::canonicalize(std::path::Path::new(dir).join("libhdf5.a")).ok()?;
    let libs = archive.parent()?;
    (libs.join("libsz.so").exists() && libs.join("libz.so").exists()).then_some(archive)
}

#[test]
#[cfg(target_os = "linux")]
fn the_command_loads_no_shared_hdf5_where_the_static_library_is_there() {
    if std::env::var_os("CATENA_HDF5_SHARED").is_some_and(|v| v == "1") {
        eprintln!("CATENA_HDF5_SHARED=1: the shared library was asked for");
        return;
    }
    let Some(archive) = static_archive() else {
        eprintln!(
            "no static HDF5 library on this system: the shared one is linked, nothing to check"
        );
        return;
    };
    // The dynamic loader lists what it would load and runs nothing (what `ldd` does).
    let out = Command::new(env!("CARGO_BIN_EXE_catena"))
        .env("LD_TRACE_LOADED_OBJECTS", "1")
        .output()
        .expect("the loader lists the command's libraries");
    let list = String::from_utf8_lossy(&out.stdout);
    assert!(list.contains("libc.so"), "not the loader's list: {list}");
    assert!(
        !list.contains("libhdf5"),
        "{} is there, but the command loads a shared HDF5:\n{list}",
        archive.display()
    );
    assert!(!list.contains("libcurl"), "{list}");
    let version = Command::new(env!("CARGO_BIN_EXE_catena"))
        .arg("--version")
        .output()
        .expect("catena --version");
    assert!(version.status.success());
}
