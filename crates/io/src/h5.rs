//! HDF5 results. Layout (other programs read it; names are stable):
//!
//! - root attributes: `catena_version`, `case`, `scene` (the case file's text), `units`;
//! - `/static/arc` (m, arc length from the top), `/static/x`, `/static/z` (m),
//!   `/static/effective_tension` (N), `/static/bending_moment` (N·m, negative = sag),
//!   `/static/penetration` (m, positive down, ≤ 0 clear), `/static/seabed_force` (N/m), one value per
//!   node, node 0 at the top; each dataset has a `units` attribute;
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
//!   Written in chunks of 64 records, or every second of wall time if sooner, as the run goes, and
//!   the file flushed each time: a run that stops keeps every record up to its last converged step,
//!   and a run killed outright keeps `/static` and every record up to about a second before the
//!   kill. The recorder is an observer of the run ([`Recorder`]); on restart it reopens the file,
//!   truncates the records written after the checkpoint and continues it.

use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::time::{Duration, Instant};

use catena::observe::{at_arc, Control, Observer, RunContext, StepView};
use catena::statics::StaticRun;
use catena::AppError;
use catena_fe::assembly::LineResults;
use hdf5::types::VarLenUnicode;

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
    }
    f.flush().map_err(&err)?;
    Ok(())
}

/// Streams dynamic records into `/dynamic` as an observer of the run: a record at every output
/// interval, written in chunks of 64 records or every second of wall time, whichever comes first.
pub struct Recorder {
    path: PathBuf,
    file: hdf5::File,
    n: usize,
    chunk: usize,
    written: usize,
    rows: usize,
    series: Vec<(hdf5::Dataset, Vec<f64>)>,
    fields: Vec<(hdf5::Dataset, Vec<f64>)>,
    modes: (hdf5::Dataset, Vec<u8>),
    gauge_arcs: Vec<f64>,
    /// With waves: `(x where the elevation is recorded, static top (x, z), (sin θ_top, cos θ_top))`.
    sea: Option<(f64, [f64; 2], [f64; 2])>,
    has_sea: bool,
    last_flush: Instant,
    /// Time spent recording (buffering and writing), s.
    busy: f64,
}

/// The deflate level of `/dynamic/seabed_mode` (byte shuffle first; mostly zeros, it compresses
/// for nothing).
const DEFLATE: u8 = 1;

const SEA: [(&str, &str); 3] = [
    ("wave_elevation", "m"),
    ("top_pitch", "rad"),
    ("top_axial_motion", "m"),
];

const SERIES: [(&str, &str); 5] = [
    ("time", "s"),
    ("top_x", "m"),
    ("top_z", "m"),
    ("top_tension", "N"),
    // The touchdown point's arc length from the top, interpolated where the invert's penetration is
    // zero (`catena_fe::statics::touchdown_arc`); the anchor's arc length when no node touches down
    // after a clear one.
    ("touchdown_arc", "m"),
];
const FIELDS: [(&str, &str); 6] = [
    ("x", "m"),
    ("z", "m"),
    ("effective_tension", "N"),
    ("bending_moment", "N*m"),
    ("penetration", "m"),
    ("seabed_force", "N/m"),
];
const FLUSH_EVERY: Duration = Duration::from_secs(1);

/// The sign and axis conventions, written as attributes of `/dynamic`.
const CONVENTIONS: [(&str, &str); 5] = [
    ("units", "SI: m, s, N, N*m, N/m, rad"),
    (
        "arc",
        "arc length from the top end (node 0), m; `arc` gives each node's, columns of every field",
    ),
    ("bending_moment", "negative in a sag bend"),
    (
        "penetration",
        "of the pipe invert below the mudline, positive down",
    ),
    (
        "effective_tension",
        "effective tension (wall tension minus the hydrostatic term), N",
    ),
];

impl Recorder {
    /// Creates `path` anew with the root attributes and `/static` (flushed at once), and the empty
    /// `/dynamic` datasets for the run's nodes and gauges.
    pub fn create(path: &Path, statics: &StaticRun, gauges: &[String]) -> Result<Self, AppError> {
        let err = h5err(path);
        let file = hdf5::File::create(path).map_err(&err)?;
        write_static_into(path, &file, statics)?;
        let n = statics.model.nodes();
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
        for (name, units) in SERIES {
            mk1(&g, name, units).map_err(&err)?;
        }
        let waves = statics
            .scene
            .dynamic
            .as_ref()
            .and_then(|d| d.environment.waves.as_ref());
        if let Some(w) = waves {
            for (name, units) in SEA {
                mk1(&g, name, units).map_err(&err)?;
            }
            let wg = file.create_group("waves").map_err(&err)?;
            let col = |f: fn(&catena_fe::waves::Component) -> f64| -> Vec<f64> {
                w.components.iter().map(f).collect()
            };
            vector(&wg, "omega", &col(|c| c.omega), "rad/s").map_err(&err)?;
            vector(&wg, "wavenumber", &col(|c| c.k), "rad/m").map_err(&err)?;
            vector(&wg, "amplitude", &col(|c| c.amplitude), "m").map_err(&err)?;
            vector(&wg, "phase", &col(|c| c.phase), "rad").map_err(&err)?;
            let dir = match w.direction {
                catena_fe::waves::Direction::PlusX => "+x",
                catena_fe::waves::Direction::MinusX => "-x",
            };
            attr(&wg, "direction", dir).map_err(&err)?;
            num_attr(&wg, "depth", w.depth).map_err(&err)?;
            num_attr(&wg, "ramp", w.ramp).map_err(&err)?;
            attr(
                &wg,
                "phase_convention",
                "eta(x, t) = r(t) * sum(a * cos(omega t - s k x + phase)), s = +1 for +x; r the quintic ramp",
            )
            .map_err(&err)?;
        }
        if !gauges.is_empty() {
            let gg = g.create_group("gauges").map_err(&err)?;
            for name in gauges {
                let one = gg.create_group(name).map_err(&err)?;
                mk1(&one, "bending_moment", "N*m").map_err(&err)?;
                mk1(&one, "effective_tension", "N").map_err(&err)?;
            }
        }
        for (name, units) in FIELDS {
            // Not compressed: the low bytes of full-precision values are noise. Shuffle + deflate
            // level 1 took the heave benchmark's file from 40 to 25 MB (all fields) or 32 MB (the
            // seabed fields alone) for 4 to 16 times the recording time (benches/README.md).
            let ds = g
                .new_dataset::<f64>()
                .chunk((chunk, n))
                .shape((0.., n))
                .create(name)
                .map_err(&err)?;
            attr(&ds, "units", units).map_err(&err)?;
        }
        let md = g.new_dataset::<u8>().chunk((chunk, n));
        let md = if hdf5::filters::deflate_available() {
            md.shuffle().deflate(DEFLATE)
        } else {
            md
        };
        let md = md.shape((0.., n)).create("seabed_mode").map_err(&err)?;
        attr(
            &md,
            "units",
            "0 not_in_contact, 1 initial_penetration, 2 uplift, 3 repenetration",
        )
        .map_err(&err)?;
        file.flush().map_err(&err)?;
        drop((g, md));
        Self::from_file(path, file, n, gauges)
    }

    /// Opens an existing results file to continue its `/dynamic` records (a restart). Its state is
    /// restored from the checkpoint before the run goes on ([`Observer::restore`]).
    pub fn open(path: &Path, n: usize, gauges: &[String]) -> Result<Self, AppError> {
        let file = hdf5::File::open_rw(path).map_err(h5err(path))?;
        Self::from_file(path, file, n, gauges)
    }

    fn from_file(
        path: &Path,
        file: hdf5::File,
        n: usize,
        gauges: &[String],
    ) -> Result<Self, AppError> {
        let err = h5err(path);
        let chunk = 64;
        let g = file.group("dynamic").map_err(&err)?;
        let mut series = Vec::new();
        for (name, _) in SERIES {
            series.push((g.dataset(name).map_err(&err)?, Vec::with_capacity(chunk)));
        }
        for name in gauges {
            for what in ["bending_moment", "effective_tension"] {
                let ds = g.dataset(&format!("gauges/{name}/{what}")).map_err(&err)?;
                series.push((ds, Vec::with_capacity(chunk)));
            }
        }
        let mut fields = Vec::new();
        for (name, _) in FIELDS {
            let ds = g.dataset(name).map_err(&err)?;
            if ds.shape().get(1) != Some(&n) {
                return Err(AppError::Output {
                    path: path.to_path_buf(),
                    message: format!("/dynamic/{name} is not for {n} nodes"),
                });
            }
            fields.push((ds, Vec::with_capacity(chunk * n)));
        }
        let has_sea = g.link_exists("wave_elevation");
        if has_sea {
            for (name, _) in SEA {
                series.push((g.dataset(name).map_err(&err)?, Vec::with_capacity(chunk)));
            }
        }
        let md = g.dataset("seabed_mode").map_err(&err)?;
        let written = series[0].0.shape().first().copied().unwrap_or(0);
        Ok(Self {
            path: path.to_path_buf(),
            file,
            n,
            chunk,
            written,
            rows: 0,
            series,
            fields,
            modes: (md, Vec::with_capacity(chunk * n)),
            gauge_arcs: Vec::new(),
            sea: None,
            has_sea,
            last_flush: Instant::now(),
            busy: 0.0,
        })
    }

    fn push(
        &mut self,
        t: f64,
        r: &LineResults,
        arc: &[f64],
        sea: Option<[f64; 3]>,
    ) -> Result<(), AppError> {
        let mut k = 0;
        let tdp =
            catena_fe::statics::touchdown_arc(arc, &r.penetration).unwrap_or(arc[arc.len() - 1]);
        for v in [t, r.x[0], r.z[0], r.tension[0], tdp] {
            self.series[k].1.push(v);
            k += 1;
        }
        for &s in &self.gauge_arcs {
            self.series[k].1.push(at_arc(arc, &r.moment, s));
            self.series[k + 1].1.push(at_arc(arc, &r.tension, s));
            k += 2;
        }
        if let Some(v) = sea {
            for x in v {
                self.series[k].1.push(x);
                k += 1;
            }
        }
        for ((_, buf), src) in self.fields.iter_mut().zip([
            &r.x,
            &r.z,
            &r.tension,
            &r.moment,
            &r.penetration,
            &r.seabed_force,
        ]) {
            buf.extend_from_slice(src);
        }
        self.modes.1.extend_from_slice(&r.mode);
        self.rows += 1;
        if self.rows == self.chunk || self.last_flush.elapsed() >= FLUSH_EVERY {
            self.flush()?;
        }
        Ok(())
    }

    /// Writes what is buffered and flushes the file.
    pub fn flush(&mut self) -> Result<(), AppError> {
        self.last_flush = Instant::now();
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
        let shape_err = |e: ndarray::ShapeError| AppError::Output {
            path: self.path.clone(),
            message: e.to_string(),
        };
        for (ds, buf) in &mut self.fields {
            ds.resize((k + m, n)).map_err(&err)?;
            let view = ndarray::ArrayView2::from_shape((m, n), &buf[..]).map_err(shape_err)?;
            ds.write_slice(&view, (k..k + m, ..)).map_err(&err)?;
            buf.clear();
        }
        let (ds, buf) = &mut self.modes;
        ds.resize((k + m, n)).map_err(&err)?;
        let view = ndarray::ArrayView2::from_shape((m, n), &buf[..]).map_err(shape_err)?;
        ds.write_slice(&view, (k..k + m, ..)).map_err(&err)?;
        buf.clear();
        self.written += m;
        self.rows = 0;
        self.file.flush().map_err(&err)?;
        Ok(())
    }

    /// `(wave elevation, pitch, axial hang-off motion)` of a step, with waves.
    fn sea_values(&self, ctx: &RunContext<'_>, s: &StepView<'_>) -> Option<[f64; 3]> {
        let (x_ref, top0, axis) = self.sea?;
        let waves = ctx.model.environment.waves.as_ref()?;
        let pitch = ctx.model.top_at(s.t).map_or(0.0, |t| t.pitch);
        let (dx, dz) = (s.results.x[0] - top0[0], s.results.z[0] - top0[1]);
        Some([
            waves.elevation(x_ref, s.t),
            pitch,
            dx * axis[0] + dz * axis[1],
        ])
    }

    /// Seconds spent recording so far (buffering, writing, flushing).
    pub fn busy_seconds(&self) -> f64 {
        self.busy
    }

    /// Records written so far (flushed or not).
    pub fn records(&self) -> usize {
        self.written + self.rows
    }

    /// Cuts every `/dynamic` dataset back to `records` records (a restart drops what the
    /// interrupted run wrote after its checkpoint).
    fn truncate(&mut self, records: usize) -> Result<(), AppError> {
        let err = h5err(&self.path);
        if records > self.written {
            return Err(AppError::Output {
                path: self.path.clone(),
                message: format!(
                    "the file holds {} records, the checkpoint expects {records}",
                    self.written
                ),
            });
        }
        for (ds, _) in &self.series {
            ds.resize(records).map_err(&err)?;
        }
        for (ds, _) in &self.fields {
            ds.resize((records, self.n)).map_err(&err)?;
        }
        self.modes.0.resize((records, self.n)).map_err(&err)?;
        self.written = records;
        self.file.flush().map_err(&err)?;
        Ok(())
    }
}

impl Observer for Recorder {
    fn name(&self) -> &'static str {
        "hdf5"
    }

    fn start(
        &mut self,
        ctx: &RunContext<'_>,
        first: &StepView<'_>,
        restarted: bool,
    ) -> Result<(), AppError> {
        self.gauge_arcs = ctx.spec.gauges.iter().map(|g| g.arc).collect();
        if self.has_sea {
            let st = &ctx.statics;
            let x_ref = ctx
                .model
                .vessel
                .as_ref()
                .map_or(st.results.x[0], |v| v.origin_x);
            let th = st.summary.top_angle_from_vertical;
            self.sea = Some((
                x_ref,
                [st.results.x[0], st.results.z[0]],
                [th.sin(), th.cos()],
            ));
        }
        if !restarted {
            // Self-description: each gauge's arc length, the arc axis of the fields, the conventions.
            let path = self.path.clone();
            let err = h5err(&path);
            let g = self.file.group("dynamic").map_err(&err)?;
            for (gauge, arc) in ctx.spec.gauges.iter().zip(&self.gauge_arcs) {
                let one = g.group(&format!("gauges/{}", gauge.name)).map_err(&err)?;
                num_attr(&one, "arc", *arc).map_err(&err)?;
                attr(&one, "arc_units", "m, from the top").map_err(&err)?;
            }
            vector(&g, "arc", &ctx.model.line.arc, "m").map_err(&err)?;
            for (k, v) in CONVENTIONS {
                attr(&g, k, v).map_err(&err)?;
            }
            drop(g);
            let sea = self.sea_values(ctx, first);
            self.push(first.t, first.results, &ctx.model.line.arc, sea)?;
        }
        Ok(())
    }

    fn step(&mut self, ctx: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        if s.record {
            let t0 = Instant::now();
            let sea = self.sea_values(ctx, s);
            self.push(s.t, s.results, &ctx.model.line.arc, sea)?;
            self.busy += t0.elapsed().as_secs_f64();
        }
        Ok(Control::Continue)
    }

    fn finish(
        &mut self,
        _: &RunContext<'_>,
        _: Option<&catena::observe::Stop>,
    ) -> Result<(), AppError> {
        let t0 = Instant::now();
        let r = self.flush();
        self.busy += t0.elapsed().as_secs_f64();
        r
    }

    fn save(&mut self) -> Result<serde_json::Value, AppError> {
        self.flush()?;
        Ok(serde_json::json!({ "records": self.written }))
    }

    fn restore(&mut self, v: &serde_json::Value) -> Result<(), String> {
        let records = v["records"].as_u64().ok_or_else(|| {
            "it holds no record count for results.h5 (was it written with an HDF5 recorder?)"
                .to_string()
        })?;
        self.truncate(records as usize).map_err(|e| e.to_string())
    }
}

/// Writes `/fatigue/damage_<fibre>` (one value per node, the larger of top and bottom; attributes
/// `sn_curve`, `scf`, `counted_seconds`) into a results file after the run.
pub fn write_fatigue(path: &Path, r: &catena::run::DynamicRun) -> Result<(), AppError> {
    let Some(f) = &r.fatigue else {
        return Ok(());
    };
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    if file.link_exists("fatigue") {
        file.unlink("fatigue").map_err(&err)?;
    }
    let g = file.create_group("fatigue").map_err(&err)?;
    attr(&g, "sn_curve", &f.spec.curve_name).map_err(&err)?;
    num_attr(&g, "scf", f.spec.scf).map_err(&err)?;
    num_attr(&g, "counted_seconds", f.counted_seconds()).map_err(&err)?;
    for fib in &f.spec.fibres {
        if let Some(d) = f.damage_of(*fib) {
            vector(
                &g,
                &format!("damage_{}", fib.name()),
                &d,
                "1 (Miner damage of the counted record)",
            )
            .map_err(&err)?;
        }
    }
    file.flush().map_err(&err)?;
    Ok(())
}

/// Writes `/ranges/<quantity>/min`, `max` and `mean` (one value per node, node order as in
/// `/dynamic/arc`; every quantity of [`catena::observe::RANGE_QUANTITIES`] the run has) into a
/// results file after the run. The group's attributes `start` (s) and `steps` say what they were
/// taken over (every step from the envelope start, not only the recorded ones); each quantity's
/// group has `units` and `description`.
pub fn write_ranges(path: &Path, r: &catena::run::DynamicRun) -> Result<(), AppError> {
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    if file.link_exists("ranges") {
        file.unlink("ranges").map_err(&err)?;
    }
    let g = file.create_group("ranges").map_err(&err)?;
    let e = &r.envelopes;
    num_attr(&g, "start", r.spec.envelope_start).map_err(&err)?;
    num_attr(&g, "steps", e.samples as f64).map_err(&err)?;
    attr(
        &g,
        "description",
        "least, greatest and mean of each quantity at each node over every step from `start`",
    )
    .map_err(&err)?;
    for (name, range) in e.ranges() {
        let (units, what) = catena::observe::RANGE_QUANTITIES
            .iter()
            .find(|q| q.0 == name)
            .map_or(("", ""), |q| (q.1, q.2));
        let q = g.create_group(name).map_err(&err)?;
        attr(&q, "units", units).map_err(&err)?;
        attr(&q, "description", what).map_err(&err)?;
        vector(&q, "min", &range.min, units).map_err(&err)?;
        vector(&q, "max", &range.max, units).map_err(&err)?;
        vector(&q, "mean", &range.mean(e.samples), units).map_err(&err)?;
    }
    file.flush().map_err(&err)?;
    Ok(())
}
