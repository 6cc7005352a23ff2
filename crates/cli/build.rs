//! Links the `catena` command to HDF5's static library when the system has one (Debian's and
//! Ubuntu's `libhdf5-dev` do), instead of the shared one.
//!
//! Why: the shared `libhdf5` brings 36 more shared libraries (curl, GnuTLS, Kerberos, LDAP… for its
//! S3 driver, which catena does not use), and loading them is most of the command's start: 6.6 ms
//! against 1.3 ms for `catena --version` (measured 2026-11-26), on every command, in a heave
//! benchmark of 0.22 s. Linked statically, only the objects catena calls come in, and the command
//! needs `libsz`, `libz` and the C library besides.
//!
//! How: `hdf5-metno-sys` asks the linker for `-lhdf5` (always the shared library). This script puts
//! a folder holding only `libhdf5.a` (a link to the system's) first in the linker's search path, so
//! that `-lhdf5` finds the archive there first. Where there is no such archive, or with
//! `CATENA_HDF5_SHARED=1` in the environment, nothing changes: the shared library as before.

use std::path::PathBuf;
use std::process::Command;

fn main() {
    println!("cargo::rerun-if-env-changed=CATENA_HDF5_SHARED");
    println!("cargo::rerun-if-env-changed=PKG_CONFIG_PATH");
    let linux = std::env::var("CARGO_CFG_TARGET_OS").is_ok_and(|os| os == "linux");
    if !linux || std::env::var_os("CATENA_HDF5_SHARED").is_some_and(|v| v == "1") {
        return;
    }
    let Some(archive) = static_hdf5() else {
        return;
    };
    let Some(out) = std::env::var_os("OUT_DIR").map(|d| PathBuf::from(d).join("static-hdf5"))
    else {
        return;
    };
    let link = out.join("libhdf5.a");
    let made = std::fs::create_dir_all(&out).is_ok()
        && (std::fs::remove_file(&link).is_ok() || !link.exists())
        && std::os::unix::fs::symlink(&archive, &link).is_ok();
    if !made {
        return;
    }
    println!("cargo::rerun-if-changed={}", archive.display());
    println!("cargo::rustc-link-search=native={}", out.display());
    // What the archive's objects call that the C library does not have: szip and deflate. As
    // linker arguments (after the archive on the command line), so that every program of this
    // package gets them: a `rustc-link-lib` would reach only the programs that link this
    // package's library, and a test that uses HDF5 without it would find the archive but not these.
    println!("cargo::rustc-link-arg=-lsz");
    println!("cargo::rustc-link-arg=-lz");
}

/// The system's `libhdf5.a`, from the folder pkg-config gives for `hdf5`, when the shared
/// libraries its objects need (`libsz`, `libz`) are beside the system's others.
fn static_hdf5() -> Option<PathBuf> {
    let flags = Command::new("pkg-config")
        .args(["--libs-only-L", "hdf5"])
        .output()
        .ok()
        .filter(|o| o.status.success())?;
    let flags = String::from_utf8(flags.stdout).ok()?;
    let dir = flags
        .split_whitespace()
        .find_map(|f| f.strip_prefix("-L"))
        .map(PathBuf::from)?;
    let archive = std::fs::canonicalize(dir.join("libhdf5.a")).ok()?;
    // Debian: /usr/lib/<multiarch>/hdf5/serial/libhdf5.a → /usr/lib/<multiarch>/libhdf5_serial.a,
    // beside libsz.so and libz.so (what `-lsz` and `-lz` find).
    let libs = archive.parent()?;
    let beside = |name: &str| libs.join(name).exists();
    (beside("libsz.so") && beside("libz.so")).then_some(archive)
}
