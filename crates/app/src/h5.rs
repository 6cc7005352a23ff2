//! HDF5 results. Layout (other programs read it; names are stable):
//!
//! - root attributes: `catena_version`, `case`, `scene` (the case file's text), `units`;
//! - `/static/arc` (m, arc length from the top), `/static/x`, `/static/z` (m),
//!   `/static/effective_tension` (N), `/static/bending_moment` (N·m, negative = sag),
//!   `/static/penetration` (m, positive down, ≤ 0 clear), `/static/seabed_force` (N/m), one value per
//!   node, node 0 at the top; each dataset has a `units` attribute;
//! - `/dynamic/time`, `/dynamic/top_x`, `/dynamic/top_z`, `/dynamic/top_tension` (n_t);
//!   `/dynamic/x`, `z`, `effective_tension`, `bending_moment`, `penetration`, `seabed_force` (n_t ×
//!   n_nodes, f64) and `seabed_mode` (n_t × n_nodes, u8: 0 not in contact, 1 initial penetration,
//!   2 uplift, 3 repenetration); `/dynamic/gauges/NAME/bending_moment` and `effective_tension` (n_t).
//!   Written in chunks of 64 records as the run goes, so a run that stops keeps every record up to its
//!   last converged step.

use std::path::Path;
use std::str::FromStr;

use hdf5::types::VarLenUnicode;

use crate::error::AppError;
use crate::statics_cmd::StaticRun;

/// Maps an HDF5 error to an I/O error naming the file.
pub fn h5err(path: &Path) -> impl Fn(hdf5::Error) -> AppError + '_ {
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

/// Streams dynamic records into `/dynamic`, 64 records per chunk.
pub struct Recorder {
    path: std::path::PathBuf,
    file: hdf5::File,
    n: usize,
    chunk: usize,
    written: usize,
    rows: usize,
    series: Vec<(hdf5::Dataset, Vec<f64>)>,
    fields: Vec<(hdf5::Dataset, Vec<f64>)>,
    modes: (hdf5::Dataset, Vec<u8>),
}

/// One record.
pub struct Record<'a> {
    /// Time, s.
    pub t: f64,
    /// Top position, m.
    pub top: [f64; 2],
    /// Top tension, N.
    pub top_tension: f64,
    /// The nodal snapshot.
    pub snap: &'a catena_fe::dynamics::Snapshot,
    /// Gauge values `(moment, tension)`.
    pub gauges: &'a [(f64, f64)],
}

impl Recorder {
    /// Creates the `/dynamic` datasets for `n` nodes and the named gauges.
    pub fn new(
        path: &Path,
        file: &hdf5::File,
        n: usize,
        gauges: &[String],
    ) -> Result<Self, AppError> {
        let err = h5err(path);
        let chunk = 64;
        let g = file.create_group("dynamic").map_err(&err)?;
        let mk1 = |grp: &hdf5::Group, name: &str, units: &str| -> hdf5::Result<hdf5::Dataset> {
            let ds = grp
                .new_dataset::<f64>()
                .chunk(chunk)
                .shape(0..)
                .create(name)?;
            attr(&ds, "units", units)?;
            Ok(ds)
        };
        let mut series = Vec::new();
        for (name, units) in [
            ("time", "s"),
            ("top_x", "m"),
            ("top_z", "m"),
            ("top_tension", "N"),
        ] {
            series.push((
                mk1(&g, name, units).map_err(&err)?,
                Vec::with_capacity(chunk),
            ));
        }
        if !gauges.is_empty() {
            let gg = g.create_group("gauges").map_err(&err)?;
            for name in gauges {
                let one = gg.create_group(name).map_err(&err)?;
                series.push((
                    mk1(&one, "bending_moment", "N*m").map_err(&err)?,
                    Vec::with_capacity(chunk),
                ));
                series.push((
                    mk1(&one, "effective_tension", "N").map_err(&err)?,
                    Vec::with_capacity(chunk),
                ));
            }
        }
        let mut fields = Vec::new();
        for (name, units) in [
            ("x", "m"),
            ("z", "m"),
            ("effective_tension", "N"),
            ("bending_moment", "N*m"),
            ("penetration", "m"),
            ("seabed_force", "N/m"),
        ] {
            let ds = g
                .new_dataset::<f64>()
                .chunk((chunk, n))
                .shape((0.., n))
                .create(name)
                .map_err(&err)?;
            attr(&ds, "units", units).map_err(&err)?;
            fields.push((ds, Vec::with_capacity(chunk * n)));
        }
        let md = g
            .new_dataset::<u8>()
            .chunk((chunk, n))
            .shape((0.., n))
            .create("seabed_mode")
            .map_err(&err)?;
        attr(
            &md,
            "units",
            "0 not_in_contact, 1 initial_penetration, 2 uplift, 3 repenetration",
        )
        .map_err(&err)?;
        Ok(Self {
            path: path.to_path_buf(),
            file: file.clone(),
            n,
            chunk,
            written: 0,
            rows: 0,
            series,
            fields,
            modes: (md, Vec::with_capacity(chunk * n)),
        })
    }

    /// Buffers a record; writes a chunk when the buffer is full.
    pub fn push(&mut self, r: &Record<'_>) -> Result<(), AppError> {
        let mut vals = vec![r.t, r.top[0], r.top[1], r.top_tension];
        for (m, t) in r.gauges {
            vals.push(*m);
            vals.push(*t);
        }
        for ((_, buf), v) in self.series.iter_mut().zip(vals) {
            buf.push(v);
        }
        let s = r.snap;
        for ((_, buf), src) in self.fields.iter_mut().zip([
            &s.x,
            &s.z,
            &s.tension,
            &s.moment,
            &s.penetration,
            &s.seabed_force,
        ]) {
            buf.extend_from_slice(src);
        }
        self.modes.1.extend_from_slice(&s.mode);
        self.rows += 1;
        if self.rows == self.chunk {
            self.flush()?;
        }
        Ok(())
    }

    /// Writes what is buffered and flushes the file.
    pub fn flush(&mut self) -> Result<(), AppError> {
        if self.rows == 0 {
            return Ok(());
        }
        let err = h5err(&self.path);
        let (k, m, n) = (self.written, self.rows, self.n);
        for (ds, buf) in &mut self.series {
            ds.resize(k + m).map_err(&err)?;
            ds.write_slice(&buf[..], k..k + m).map_err(&err)?;
            buf.clear();
        }
        for (ds, buf) in &mut self.fields {
            ds.resize((k + m, n)).map_err(&err)?;
            let view =
                ndarray::ArrayView2::from_shape((m, n), &buf[..]).map_err(|e| AppError::Io {
                    path: self.path.clone(),
                    source: std::io::Error::other(e.to_string()),
                })?;
            ds.write_slice(&view, (k..k + m, ..)).map_err(&err)?;
            buf.clear();
        }
        let (ds, buf) = &mut self.modes;
        ds.resize((k + m, n)).map_err(&err)?;
        let view = ndarray::ArrayView2::from_shape((m, n), &buf[..]).map_err(|e| AppError::Io {
            path: self.path.clone(),
            source: std::io::Error::other(e.to_string()),
        })?;
        ds.write_slice(&view, (k..k + m, ..)).map_err(&err)?;
        buf.clear();
        self.written += m;
        self.rows = 0;
        self.file.flush().map_err(&err)?;
        Ok(())
    }

    /// Records written so far (flushed or not).
    pub fn records(&self) -> usize {
        self.written + self.rows
    }
}
