//! HDF5 results. Layout (other programs read it; names are stable):
//!
//! - root attributes: `catena_version`, `case`, `scene` (the case file's text), `units`;
//! - `/static/arc` (m, arc length from the top), `/static/x`, `/static/z` (m),
//!   `/static/effective_tension` (N), `/static/bending_moment` (N·m, negative = sag),
//!   `/static/penetration` (m, positive down, ≤ 0 clear), `/static/seabed_force` (N/m), one value per
//!   node, node 0 at the top; each dataset has a `units` attribute.

use std::path::Path;
use std::str::FromStr;

use hdf5::types::VarLenUnicode;

use crate::error::AppError;
use crate::statics_cmd::StaticRun;

fn h5err(path: &Path) -> impl Fn(hdf5::Error) -> AppError + '_ {
    move |e| AppError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::other(e.to_string()),
    }
}

fn text(s: &str) -> VarLenUnicode {
    // Strings with interior NULs cannot be stored; drop them.
    VarLenUnicode::from_str(&s.replace('\0', "")).unwrap_or_default()
}

/// Writes a string attribute on a location.
pub fn attr(loc: &hdf5::Location, name: &str, value: &str) -> hdf5::Result<()> {
    loc.new_attr::<VarLenUnicode>()
        .shape(())
        .create(name)?
        .write_scalar(&text(value))
}

/// Writes a 1-D dataset with a `units` attribute.
pub fn vector(g: &hdf5::Group, name: &str, data: &[f64], units: &str) -> hdf5::Result<()> {
    let ds = g.new_dataset_builder().with_data(data).create(name)?;
    attr(&ds, "units", units)
}

/// Writes `results.h5` for a static run (created anew).
pub fn write_static(path: &Path, run: &StaticRun) -> Result<(), AppError> {
    let err = h5err(path);
    let f = hdf5::File::create(path).map_err(&err)?;
    attr(&f, "catena_version", env!("CARGO_PKG_VERSION")).map_err(&err)?;
    attr(&f, "case", &run.scene.file).map_err(&err)?;
    attr(&f, "scene", &run.scene.text).map_err(&err)?;
    attr(&f, "units", "SI: m, N, N·m, N/m, s, rad").map_err(&err)?;
    let g = f.create_group("static").map_err(&err)?;
    let r = &run.results;
    for (name, data, units) in [
        ("arc", &r.arc, "m"),
        ("x", &r.x, "m"),
        ("z", &r.z, "m"),
        ("effective_tension", &r.tension, "N"),
        ("bending_moment", &r.moment, "N*m"),
        ("penetration", &r.penetration, "m"),
        ("seabed_force", &r.seabed_force, "N/m"),
        ("theta", &r.theta, "rad"),
    ] {
        vector(&g, name, data, units).map_err(&err)?;
    }
    Ok(())
}
