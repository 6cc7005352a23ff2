//! HDF5 results. Layout (other programs read it; names are stable):
//!
//! - root attributes: `catena_version`, `case`, `scene` (the case file's text), `units`;
//! - `/static/arc` (m, arc length from the top), `/static/x`, `/static/z` (m),
//!   `/static/effective_tension` (N), `/static/bending_moment` (N·m, negative = sag),
//!   `/static/penetration` (m, positive down, ≤ 0 clear), `/static/seabed_force` (N/m), one value per
//!   node, node 0 at the top; each dataset has a `units` attribute;
//! - `/line/section` (each node's line type, an index into the attribute `names`, comma-separated),
//!   `/line/od`, `/line/wall` (NaN if not given), `/line/hydrodynamic_od`, `/line/contact_od` (m),
//!   one value per node;
//! - `/dynamic/time`, `/dynamic/top_x`, `/dynamic/top_z`, `/dynamic/top_tension`,
//!   `/dynamic/touchdown_arc` (n_t); `/dynamic/arc` (n_nodes); the conventions as attributes of
//!   `/dynamic`; each gauge group's arc length as its attribute `arc`;
//!   `/dynamic/x`, `z`, `effective_tension`, `bending_moment`, `penetration`, `seabed_force` (n_t ×
//!   n_nodes, f64) and `seabed_mode` (n_t × n_nodes, u8: 0 not in contact, 1 initial penetration,
//!   2 uplift, 3 repenetration); `/dynamic/gauges/NAME/bending_moment` and `effective_tension` (n_t).
//! - `/ranges/<quantity>/min`, `max`, `mean` (one per node): range graphs over every step from the
//!   envelope start ([`write_ranges`], after the run);
//! - with `[waves]`: `/dynamic/wave_elevation` (m, at the RAO origin, or at the top end's x without a
//!   vessel), `/dynamic/top_pitch` (rad, the vessel's pitch, positive bow down; 0 without a vessel)
//!   and `/dynamic/top_axial_motion` (m, the hang-off's displacement along the riser's static top
//!   tangent, `u_a = ΔX sin θ_top + ΔZ cos θ_top`, θ_top from the vertical, positive up the riser),
//!   each n_t; `/waves/omega` (rad/s), `/waves/wavenumber` (rad/m), `/waves/amplitude` (m) and
//!   `/waves/phase` (rad), one value per component, with the attributes `direction` (`+x`/`-x`),
//!   `depth` (m) and `ramp` (s): `η(x, t) = r(t)·Σ a cos(ωt − s k x + ε)` re-synthesises the record.
//!   The writer thread creates the file (while the run's first steps are taken) and is handed the
//!   records in batches of 64, or every second of wall time if sooner; it writes each batch and
//!   flushes the file while the run steps on: a run that stops keeps
//!   every record up to its last converged step, and a run killed outright keeps `/static` and every
//!   record up to about a second (or two batches) before the kill. The recorder is an observer of
//!   the run ([`Recorder`]); on restart it reopens the file, truncates the records written after the
//!   checkpoint and continues it.
//! - `/dynamic/time`, `/dynamic/arc` and `/static/arc` are HDF5 dimension scales attached to every
//!   field, series and per-node result ([`dimension_scales`]). The float fields are compressed
//!   (shuffle + deflate 1) when asked (`catena run` by default when the records are decimated and
//!   the run has three threads or more). The writer keeps a core busy only when it compresses or
//!   records every step ([`recorder::writer_keeps_core`]): else the run may step on two threads
//!   beside it.

use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

use catena::run::observe::{at_arc, Control, Observer, RunContext, StepView};
use catena::run::records::{
    record_fields, record_series, RECORD_FIELDS as FIELDS, RECORD_SERIES as SERIES,
};
use catena::run::statics::StaticRun;
use catena::AppError;
use catena_fe::assembly::LineResults;
use hdf5::types::VarLenUnicode;

mod after;
mod lay;
mod read;
mod recorder;
mod sink;

pub use after::{write_design_check, write_fatigue, write_ranges};
pub use lay::write_lay;
pub use read::{read_animation, read_extreme_channels, Channel};
use recorder::*;
pub use recorder::{writer_keeps_core, Recorder};
use sink::*;

/// Maps an HDF5 error to an output error naming the file.
pub fn h5err(path: &Path) -> impl Fn(hdf5::Error) -> AppError + '_ {
    move |e| AppError::Output {
        path: path.to_path_buf(),
        message: format!("HDF5: {e}"),
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

/// Writes a number attribute on a location.
pub fn num_attr(loc: &hdf5::Location, name: &str, value: f64) -> hdf5::Result<()> {
    loc.new_attr::<f64>()
        .shape(())
        .create(name)?
        .write_scalar(&value)
}

/// Writes a 1-D dataset with a `units` attribute.
pub fn vector(g: &hdf5::Group, name: &str, data: &[f64], units: &str) -> hdf5::Result<()> {
    let ds = g.new_dataset_builder().with_data(data).create(name)?;
    attr(&ds, "units", units)
}

/// Writes `results.h5` for a static run (created anew).
pub fn write_static(path: &Path, run: &StaticRun) -> Result<(), AppError> {
    let f = hdf5::File::create(path).map_err(h5err(path))?;
    write_static_into(path, &f, run)
}

/// Writes the root attributes and the `/static` group into an open file.
pub fn write_static_into(path: &Path, f: &hdf5::File, run: &StaticRun) -> Result<(), AppError> {
    let err = h5err(path);
    attr(f, "catena_version", env!("CARGO_PKG_VERSION")).map_err(&err)?;
    attr(f, "case", &run.scene.file).map_err(&err)?;
    attr(f, "scene", &run.scene.text).map_err(&err)?;
    attr(f, "units", "SI: m, N, N·m, N/m, s, rad").map_err(&err)?;
    let g = f.create_group("static").map_err(&err)?;
    let r = &run.results;
    let mut dims: Vec<(String, Vec<Option<&str>>)> = Vec::new();
    for (name, data, units) in [
        ("arc", &run.model.arc, "m"),
        ("x", &r.x, "m"),
        ("z", &r.z, "m"),
        ("effective_tension", &r.tension, "N"),
        ("bending_moment", &r.moment, "N*m"),
        ("penetration", &r.penetration, "m"),
        ("seabed_force", &r.seabed_force, "N/m"),
        ("theta", &r.theta, "rad"),
    ] {
        vector(&g, name, data, units).map_err(&err)?;
        if name != "arc" {
            dims.push((format!("static/{name}"), vec![Some("static/arc")]));
        }
    }
    // What each node is made of (`/line`): its section's type and its diameters and wall.
    let l = f.create_group("line").map_err(&err)?;
    let p = catena::scene::sections::node_properties(&run.model);
    let kind: Vec<u32> = p.kind.iter().map(|&k| k as u32).collect();
    let ds = l
        .new_dataset_builder()
        .with_data(&kind)
        .create("section")
        .map_err(&err)?;
    attr(&ds, "units", "1").map_err(&err)?;
    attr(&ds, "names", &run.scene.line_type_names().join(",")).map_err(&err)?;
    attr(
        &ds,
        "description",
        "each node's line type, an index into the comma-separated names (at a change of section, the weaker element's)",
    )
    .map_err(&err)?;
    for (name, data) in [
        ("od", &p.od),
        ("wall", &p.wall),
        ("hydrodynamic_od", &p.hydrodynamic_od),
        ("contact_od", &p.contact_od),
    ] {
        vector(&l, name, data, "m").map_err(&err)?;
    }
    for name in ["section", "od", "wall", "hydrodynamic_od", "contact_od"] {
        dims.push((format!("line/{name}"), vec![Some("static/arc")]));
    }
    dimension_scales(f, &dims).map_err(&err)?;
    link_scales(f, "line", "static", &["arc"]).map_err(&err)?;
    f.flush().map_err(&err)?;
    Ok(())
}

/// A fixed-length, null-terminated ASCII string type of `n` bytes. `H5DSis_scale` (which h5py,
/// netCDF and xarray call) accepts a `CLASS` attribute only of this kind, and the crate's fixed
/// strings are null-padded; the crate offers no way to set the padding, hence the one unsafe call.
#[allow(unsafe_code)]
fn nullterm_string(n: usize) -> hdf5::Result<hdf5::Datatype> {
    let dt = hdf5::Datatype::from_descriptor(&hdf5::types::TypeDescriptor::FixedAscii(n))?;
    let id = dt.id();
    // SAFETY: `id` is a valid, transient (not committed, not shared) string datatype that `dt`
    // owns and keeps alive across the call; `H5Tset_strpad` changes only its padding. The call
    // runs under the crate's global HDF5 lock, as every call of the crate does.
    let status = hdf5::sync::sync(|| unsafe {
        hdf5_sys::h5t::H5Tset_strpad(id, hdf5_sys::h5t::H5T_str_t::H5T_STR_NULLTERM)
    });
    if status < 0 {
        return Err("H5Tset_strpad failed".into());
    }
    Ok(dt)
}

/// Hard links in `group` to the dimension scales `scales` of the group `from` (the same datasets,
/// not copies), unless the group has them already: a group whose datasets use another group's
/// scales then opens on its own with its dimensions and coordinates (netCDF readers and xarray
/// find a dimension in the group or its parents only).
pub fn link_scales(
    file: &hdf5::File,
    group: &str,
    from: &str,
    scales: &[&str],
) -> hdf5::Result<()> {
    let g = file.group(group)?;
    for s in scales {
        if !g.link_exists(s) {
            g.link_hard(&format!("/{from}/{s}"), s)?;
        }
    }
    Ok(())
}

/// A reference from a dimension scale back to a dataset dimension it is attached to: an element
/// of the scale's `REFERENCE_LIST` (HDF5 Dimension Scale specification, 1.0).
#[derive(hdf5::H5Type, Clone, Copy)]
#[repr(C)]
struct ScaleUse {
    dataset: hdf5::ObjectReference1,
    dimension: i32,
}

/// Attaches HDF5 dimension scales, as the HDF5 high-level library's `H5DSset_scale` and
/// `H5DSattach_scale` would (the Rust crate does not bind that library; this writes the same
/// attributes, HDF5 Dimension Scale specification 1.0): each scale gets `CLASS =
/// "DIMENSION_SCALE"`, `NAME` (its last path part) and `REFERENCE_LIST`; each dataset
/// `DIMENSION_LIST`, one list of scale references per dimension. `datasets` pairs a dataset's path
/// with the scale of each dimension (`None`: no scale). h5py reads them as `ds.dims[k][0]`.
pub fn dimension_scales(
    file: &hdf5::File,
    datasets: &[(String, Vec<Option<&str>>)],
) -> hdf5::Result<()> {
    use hdf5::types::{FixedAscii, VarLenArray};
    use hdf5::ObjectReference1;
    let mut uses: Vec<(&str, Vec<ScaleUse>)> = Vec::new();
    for (path, dims) in datasets {
        let ds = file.dataset(path)?;
        let me: ObjectReference1 = file.reference(path)?;
        let mut list = Vec::with_capacity(dims.len());
        for (k, scale) in dims.iter().enumerate() {
            match scale {
                Some(sc) => {
                    let r: ObjectReference1 = file.reference(sc)?;
                    list.push(VarLenArray::from_slice(&[r]));
                    let u = ScaleUse {
                        dataset: me,
                        dimension: k as i32,
                    };
                    match uses.iter_mut().find(|(s, _)| s == sc) {
                        Some((_, v)) => v.push(u),
                        None => uses.push((sc, vec![u])),
                    }
                }
                None => list.push(VarLenArray::from_slice(&[])),
            }
        }
        if ds.attr("DIMENSION_LIST").is_ok() {
            ds.delete_attr("DIMENSION_LIST")?;
        }
        ds.new_attr::<VarLenArray<ObjectReference1>>()
            .shape(list.len())
            .create("DIMENSION_LIST")?
            .write(&list)?;
    }
    let fixed = |s: &str| FixedAscii::<32>::from_ascii(s).unwrap_or_default();
    let (class_type, name_type) = (nullterm_string(16)?, nullterm_string(32)?);
    for (sc, mut v) in uses {
        let ds = file.dataset(sc)?;
        // Keep the uses attached before (another call, e.g. `/ranges` after `/dynamic`).
        if let Ok(a) = ds.attr("REFERENCE_LIST") {
            let before: Vec<ScaleUse> = a.read_raw()?;
            v.splice(0..0, before);
        }
        for name in ["CLASS", "NAME", "REFERENCE_LIST"] {
            if ds.attr(name).is_ok() {
                ds.delete_attr(name)?;
            }
        }
        ds.new_attr_builder()
            .empty_as(class_type.clone())
            .shape(())
            .create("CLASS")?
            .write_scalar(&FixedAscii::<16>::from_ascii("DIMENSION_SCALE").unwrap_or_default())?;
        let short = sc.rsplit('/').next().unwrap_or(sc);
        ds.new_attr_builder()
            .empty_as(name_type.clone())
            .shape(())
            .create("NAME")?
            .write_scalar(&fixed(short))?;
        ds.new_attr::<ScaleUse>()
            .shape(v.len())
            .create("REFERENCE_LIST")?
            .write(&v)?;
    }
    Ok(())
}
