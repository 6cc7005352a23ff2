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
//!   (shuffle + deflate 1) when asked, by default when the records are decimated.

use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

use catena::observe::{
    at_arc, record_fields, record_series, Control, Observer, RunContext, StepView,
    RECORD_FIELDS as FIELDS, RECORD_SERIES as SERIES,
};
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
    f.flush().map_err(&err)?;
    Ok(())
}

/// The datasets of `/dynamic` and the file, as the writer thread writes them.
struct Sink {
    path: PathBuf,
    file: hdf5::File,
    n: usize,
    series: Vec<hdf5::Dataset>,
    fields: Vec<hdf5::Dataset>,
    modes: hdf5::Dataset,
    /// Records in the file.
    written: usize,
    /// Seconds spent writing (compressing, writing, flushing).
    seconds: f64,
}

/// Records handed from the run to the writer: `rows` records of every series, field and the modes.
struct Batch {
    rows: usize,
    series: Vec<Vec<f64>>,
    fields: Vec<Vec<f64>>,
    modes: Vec<u8>,
}

/// What the writer thread is asked to do.
enum Job {
    /// Write `/dynamic`'s self-description (the run's start, [`Describe`]).
    Describe(Describe),
    /// Append a batch and flush the file.
    Write(Batch),
    /// Answer once every earlier job is done, with the first write error if there was one.
    Sync(mpsc::SyncSender<Option<String>>),
}

/// Batches the run may queue ahead of the writer (then it waits): at most this many × 64 records in
/// memory.
const QUEUE: usize = 2;

/// What a recorder needs to know of its file's `/dynamic` before the file is there: the nodes,
/// the series and fields it records, whether it has the sea's series and the design check's
/// utilisation, and the records already written (a restart).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Shape {
    n: usize,
    ns: usize,
    nf: usize,
    has_sea: bool,
    has_design: bool,
    written: usize,
}

/// Builds a new file's datasets (on the writer thread), and says what shape they have.
type Init = Box<dyn FnOnce() -> Result<(Sink, Shape), AppError> + Send>;

/// An output error's message alone (the recorder names the file when it reports it).
fn output_message(e: AppError) -> String {
    match e {
        AppError::Output { message, .. } => message,
        e => e.to_string(),
    }
}

/// `/dynamic`'s self-description, written when the run starts: each gauge's arc length, the arc
/// axis of the fields, the conventions and the dimension scales.
struct Describe {
    /// Each gauge's name and arc length, m.
    gauges: Vec<(String, f64)>,
    /// Each node's arc length, m.
    arc: Vec<f64>,
    has_design: bool,
    has_sea: bool,
}

impl Describe {
    fn write(&self, sink: &Sink) -> Result<(), AppError> {
        let err = h5err(&sink.path);
        let g = sink.file.group("dynamic").map_err(&err)?;
        for (name, arc) in &self.gauges {
            let one = g.group(&format!("gauges/{name}")).map_err(&err)?;
            num_attr(&one, "arc", *arc).map_err(&err)?;
            attr(&one, "arc_units", "m, from the top").map_err(&err)?;
        }
        vector(&g, "arc", &self.arc, "m").map_err(&err)?;
        for (k, v) in CONVENTIONS {
            attr(&g, k, v).map_err(&err)?;
        }
        let mut dims: Vec<(String, Vec<Option<&str>>)> = Vec::new();
        for (name, _) in FIELDS {
            dims.push((
                format!("dynamic/{name}"),
                vec![Some("dynamic/time"), Some("dynamic/arc")],
            ));
        }
        dims.push((
            "dynamic/seabed_mode".into(),
            vec![Some("dynamic/time"), Some("dynamic/arc")],
        ));
        if self.has_design {
            dims.push((
                "design_check/utilisation".into(),
                vec![Some("dynamic/time"), Some("dynamic/arc")],
            ));
        }
        let mut one_d: Vec<String> = SERIES[1..]
            .iter()
            .map(|(name, _)| format!("dynamic/{name}"))
            .collect();
        for (name, _) in &self.gauges {
            for what in ["bending_moment", "effective_tension"] {
                one_d.push(format!("dynamic/gauges/{name}/{what}"));
            }
        }
        if self.has_sea {
            one_d.extend(SEA.iter().map(|(name, _)| format!("dynamic/{name}")));
        }
        dims.extend(one_d.into_iter().map(|d| (d, vec![Some("dynamic/time")])));
        dimension_scales(&sink.file, &dims).map_err(&err)?;
        sink.file.flush().map_err(&err)
    }
}

impl Sink {
    fn write(&mut self, b: &Batch) -> Result<(), String> {
        let t0 = Instant::now();
        let e = |e: hdf5::Error| format!("HDF5: {e}");
        let (k, m, n) = (self.written, b.rows, self.n);
        for (ds, buf) in self.series.iter().zip(&b.series) {
            ds.resize(k + m).map_err(e)?;
            ds.write_slice(&buf[..], k..k + m).map_err(e)?;
        }
        for (ds, buf) in self.fields.iter().zip(&b.fields) {
            ds.resize((k + m, n)).map_err(e)?;
            let view =
                ndarray::ArrayView2::from_shape((m, n), &buf[..]).map_err(|x| x.to_string())?;
            ds.write_slice(&view, (k..k + m, ..)).map_err(e)?;
        }
        self.modes.resize((k + m, n)).map_err(e)?;
        let view =
            ndarray::ArrayView2::from_shape((m, n), &b.modes[..]).map_err(|x| x.to_string())?;
        self.modes.write_slice(&view, (k..k + m, ..)).map_err(e)?;
        self.written += m;
        self.file.flush().map_err(e)?;
        self.seconds += t0.elapsed().as_secs_f64();
        Ok(())
    }

    /// Cuts every `/dynamic` dataset back to `records` records.
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
        for ds in &self.series {
            ds.resize(records).map_err(&err)?;
        }
        for ds in &self.fields {
            ds.resize((records, self.n)).map_err(&err)?;
        }
        self.modes.resize((records, self.n)).map_err(&err)?;
        self.written = records;
        self.file.flush().map_err(&err)?;
        Ok(())
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    // A panic on the writer thread cannot leave a half-updated Sink that matters: the file is what
    // it wrote, and `written` is updated after the writes.
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Streams dynamic records into `/dynamic` as an observer of the run: a record at every output
/// interval, handed to a writer thread in batches of 64 records or every second of wall time,
/// whichever comes first. The writer compresses, writes and flushes while the run steps on; the run
/// waits only when it is two batches ahead. A checkpoint, the end of the run and dropping the
/// recorder wait until every batch is in the file.
pub struct Recorder {
    path: PathBuf,
    /// The file's datasets: `None` until the writer thread has created the file.
    sink: Arc<Mutex<Option<Sink>>>,
    jobs: Option<mpsc::SyncSender<Job>>,
    writer: Option<std::thread::JoinHandle<()>>,
    /// The writer's first error, if any.
    failed: Arc<Mutex<Option<String>>>,
    /// Set (and waiters woken) when the writer thread has created the file, or failed to.
    created: Arc<(Mutex<bool>, std::sync::Condvar)>,
    n: usize,
    chunk: usize,
    /// Records handed to the writer.
    queued: usize,
    rows: usize,
    series: Vec<Vec<f64>>,
    fields: Vec<Vec<f64>>,
    modes: Vec<u8>,
    gauge_arcs: Vec<f64>,
    /// With waves: `(x where the elevation is recorded, static top (x, z), (sin θ_top, cos θ_top))`.
    sea: Option<(f64, [f64; 2], [f64; 2])>,
    has_sea: bool,
    /// With a design check: its evaluator (set when the run starts) and the step's utilisation.
    design: Option<(catena::design::Evaluator, Vec<f64>)>,
    has_design: bool,
    last_flush: Instant,
    /// Time the run's thread spent recording (buffering, handing over, waiting), s.
    busy: f64,
}

/// The deflate level of the `/dynamic` fields (byte shuffle first). Level 1: the higher levels
/// shrink full-precision floats little more for much more time (`benches/README.md`). The writer
/// thread does it, off the run's critical path.
const DEFLATE: u8 = 1;

const SEA: [(&str, &str); 3] = [
    ("wave_elevation", "m"),
    ("top_pitch", "rad"),
    ("top_axial_motion", "m"),
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
    /// `/dynamic` datasets for the run's nodes and gauges; with `compress`, the float fields are
    /// stored shuffled and deflated (level 1; `seabed_mode` always is). The writer thread does it
    /// (4 ms for the heave benchmark) while the run steps: the first records wait in memory, and an
    /// error stops the run at the next hand-over of records, naming the file.
    pub fn create(
        path: &Path,
        statics: &StaticRun,
        gauges: &[String],
        compress: bool,
    ) -> Result<Self, AppError> {
        let dynamic = statics.scene.dynamic.as_ref();
        let has_sea = dynamic.is_some_and(|d| d.environment.waves.is_some());
        let has_design = dynamic.is_some_and(|d| d.design_check.is_some());
        let ns = SERIES.len() + 2 * gauges.len() + if has_sea { SEA.len() } else { 0 };
        let nf = FIELDS.len() + usize::from(has_design);
        let shape = Shape {
            n: statics.model.nodes(),
            ns,
            nf,
            has_sea,
            has_design,
            written: 0,
        };
        let (path_buf, statics, gauges) = (path.to_path_buf(), statics.clone(), gauges.to_vec());
        let init: Init = Box::new(move || Self::build_sink(&path_buf, &statics, &gauges, compress));
        Self::with_writer(path, shape, Arc::new(Mutex::new(None)), Some(init))
    }

    fn build_sink(
        path: &Path,
        statics: &StaticRun,
        gauges: &[String],
        compress: bool,
    ) -> Result<(Sink, Shape), AppError> {
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
        let deflate = hdf5::filters::deflate_available();
        for (name, units) in FIELDS {
            let ds = g.new_dataset::<f64>().chunk((chunk, n));
            let ds = if deflate && compress {
                ds.shuffle().deflate(DEFLATE)
            } else {
                ds
            };
            let ds = ds.shape((0.., n)).create(name).map_err(&err)?;
            attr(&ds, "units", units).map_err(&err)?;
        }
        let md = g.new_dataset::<u8>().chunk((chunk, n));
        let md = if deflate {
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
        if let Some(c) = statics
            .scene
            .dynamic
            .as_ref()
            .and_then(|d| d.design_check.as_ref())
        {
            let dg = file.create_group("design_check").map_err(&err)?;
            let ds = dg.new_dataset::<f64>().chunk((chunk, n));
            let ds = if deflate && compress {
                ds.shuffle().deflate(DEFLATE)
            } else {
                ds
            };
            let ds = ds.shape((0.., n)).create("utilisation").map_err(&err)?;
            attr(&ds, "units", "1 (the criterion's left side; above 1 fails)").map_err(&err)?;
            attr(&ds, "code", c.code.name()).map_err(&err)?;
            attr(
                &ds,
                "convention",
                "one row per record of /dynamic/time, one column per node of /dynamic/arc",
            )
            .map_err(&err)?;
        }
        file.flush().map_err(&err)?;
        drop((g, md));
        Self::sink_of(path, file, n, gauges)
    }

    /// Opens an existing results file to continue its `/dynamic` records (a restart). Its state is
    /// restored from the checkpoint before the run goes on ([`Observer::restore`]).
    pub fn open(path: &Path, n: usize, gauges: &[String]) -> Result<Self, AppError> {
        let file = hdf5::File::open_rw(path).map_err(h5err(path))?;
        let (sink, shape) = Self::sink_of(path, file, n, gauges)?;
        Self::with_writer(path, shape, Arc::new(Mutex::new(Some(sink))), None)
    }

    /// The datasets of a results file's `/dynamic` for `n` nodes and these gauges, and their shape.
    fn sink_of(
        path: &Path,
        file: hdf5::File,
        n: usize,
        gauges: &[String],
    ) -> Result<(Sink, Shape), AppError> {
        let err = h5err(path);
        let g = file.group("dynamic").map_err(&err)?;
        let mut series = Vec::new();
        for (name, _) in SERIES {
            series.push(g.dataset(name).map_err(&err)?);
        }
        for name in gauges {
            for what in ["bending_moment", "effective_tension"] {
                series.push(g.dataset(&format!("gauges/{name}/{what}")).map_err(&err)?);
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
            fields.push(ds);
        }
        let has_design = file.link_exists("design_check");
        if has_design {
            fields.push(file.dataset("design_check/utilisation").map_err(&err)?);
        }
        let has_sea = g.link_exists("wave_elevation");
        if has_sea {
            for (name, _) in SEA {
                series.push(g.dataset(name).map_err(&err)?);
            }
        }
        let modes = g.dataset("seabed_mode").map_err(&err)?;
        let written = series[0].shape().first().copied().unwrap_or(0);
        let shape = Shape {
            n,
            ns: series.len(),
            nf: fields.len(),
            has_sea,
            has_design,
            written,
        };
        let sink = Sink {
            path: path.to_path_buf(),
            file,
            n,
            series,
            fields,
            modes,
            written,
            seconds: 0.0,
        };
        Ok((sink, shape))
    }

    /// The recorder of a file of this shape, its writer thread started: the thread first builds the
    /// datasets with `init` when they are not there yet (a new file), then takes the jobs in order.
    fn with_writer(
        path: &Path,
        shape: Shape,
        sink: Arc<Mutex<Option<Sink>>>,
        init: Option<Init>,
    ) -> Result<Self, AppError> {
        let Shape {
            n,
            ns,
            nf,
            has_sea,
            has_design,
            written,
        } = shape;
        let chunk = 64;
        let failed = Arc::new(Mutex::new(None));
        let created = Arc::new((Mutex::new(false), std::sync::Condvar::new()));
        let (jobs, rx) = mpsc::sync_channel::<Job>(QUEUE);
        let writer = {
            let (sink, failed) = (Arc::clone(&sink), Arc::clone(&failed));
            let done = Arc::clone(&created);
            std::thread::Builder::new()
                .name("catena-hdf5".into())
                .spawn(move || {
                    let first = || lock(&failed);
                    if let Some(init) = init {
                        // The recorder's buffers were sized from the scene before the file
                        // existed: the file must have that shape (else records would be lost).
                        match init() {
                            Ok((s, built)) if built == shape => *lock(&sink) = Some(s),
                            Ok((_, built)) => {
                                *first() = Some(format!(
                                    "the file's /dynamic ({built:?}) is not what the run records \
                                     ({shape:?})"
                                ));
                            }
                            Err(e) => *first() = Some(output_message(e)),
                        }
                    }
                    *lock(&done.0) = true;
                    done.1.notify_all();
                    for job in rx {
                        // After a failure, jobs are dropped: the file keeps what was written.
                        // (The error lock is not held while writing: the run checks it.)
                        let done = match job {
                            Job::Sync(reply) => {
                                let _ = reply.send(first().clone());
                                continue;
                            }
                            _ if first().is_some() => continue,
                            Job::Write(b) => lock(&sink).as_mut().map_or(Ok(()), |s| s.write(&b)),
                            Job::Describe(d) => lock(&sink)
                                .as_ref()
                                .map_or(Ok(()), |s| d.write(s).map_err(output_message)),
                        };
                        if let Err(e) = done {
                            *first() = Some(e);
                        }
                    }
                })
                .map_err(|e| AppError::Output {
                    path: path.to_path_buf(),
                    message: format!("cannot start the writer thread: {e}"),
                })?
        };
        Ok(Self {
            path: path.to_path_buf(),
            sink,
            jobs: Some(jobs),
            writer: Some(writer),
            failed,
            created,
            n,
            chunk,
            queued: written,
            rows: 0,
            series: (0..ns).map(|_| Vec::with_capacity(chunk)).collect(),
            fields: (0..nf).map(|_| Vec::with_capacity(chunk * n)).collect(),
            modes: Vec::with_capacity(chunk * n),
            gauge_arcs: Vec::new(),
            sea: None,
            has_sea,
            design: None,
            has_design,
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
        for v in record_series(t, arc, r) {
            self.series[k].push(v);
            k += 1;
        }
        for &s in &self.gauge_arcs {
            self.series[k].push(at_arc(arc, &r.moment, s));
            self.series[k + 1].push(at_arc(arc, &r.tension, s));
            k += 2;
        }
        if let Some(v) = sea {
            for x in v {
                self.series[k].push(x);
                k += 1;
            }
        }
        for (buf, src) in self.fields.iter_mut().zip(record_fields(r)) {
            buf.extend_from_slice(src);
        }
        if self.has_design {
            let buf = self.fields.last_mut().expect("the utilisation's buffer");
            match &mut self.design {
                Some((ev, u)) => {
                    ev.along(r, u);
                    buf.extend_from_slice(u);
                }
                None => buf.extend(std::iter::repeat_n(f64::NAN, self.n)),
            }
        }
        self.modes.extend_from_slice(&r.mode);
        self.rows += 1;
        if self.rows == self.chunk || self.last_flush.elapsed() >= FLUSH_EVERY {
            self.flush()?;
        }
        Ok(())
    }

    /// A call that returns once the writer thread has created the file (or failed to), at most
    /// after `limit`: work that would compete with the file's creation for the cores waits on it.
    pub fn when_created(&self, limit: Duration) -> impl FnOnce() + Send + 'static {
        let created = Arc::clone(&self.created);
        move || {
            let (flag, cv) = &*created;
            let _ = cv.wait_timeout_while(lock(flag), limit, |done| !*done);
        }
    }

    /// The writer's first error, as an output error naming the file.
    fn check(&self) -> Result<(), AppError> {
        match lock(&self.failed).as_ref() {
            Some(message) => Err(AppError::Output {
                path: self.path.clone(),
                message: message.clone(),
            }),
            None => Ok(()),
        }
    }

    /// Hands what is buffered to the writer (which writes it and flushes the file).
    pub fn flush(&mut self) -> Result<(), AppError> {
        self.last_flush = Instant::now();
        self.check()?;
        if self.rows == 0 {
            return Ok(());
        }
        let (chunk, n) = (self.chunk, self.n);
        let batch = Batch {
            rows: self.rows,
            series: self
                .series
                .iter_mut()
                .map(|b| std::mem::replace(b, Vec::with_capacity(chunk)))
                .collect(),
            fields: self
                .fields
                .iter_mut()
                .map(|b| std::mem::replace(b, Vec::with_capacity(chunk * n)))
                .collect(),
            modes: std::mem::replace(&mut self.modes, Vec::with_capacity(chunk * n)),
        };
        self.send(Job::Write(batch))?;
        self.queued += self.rows;
        self.rows = 0;
        Ok(())
    }

    fn send(&self, job: Job) -> Result<(), AppError> {
        let gone = || AppError::Output {
            path: self.path.clone(),
            message: "the writer thread has stopped".into(),
        };
        self.jobs
            .as_ref()
            .ok_or_else(gone)?
            .send(job)
            .map_err(|_| gone())
    }

    /// Hands over what is buffered and waits until every record is in the file.
    pub fn sync(&mut self) -> Result<(), AppError> {
        self.flush()?;
        let (tx, rx) = mpsc::sync_channel(1);
        self.send(Job::Sync(tx))?;
        match rx.recv() {
            Ok(None) => Ok(()),
            Ok(Some(message)) => Err(AppError::Output {
                path: self.path.clone(),
                message,
            }),
            Err(_) => Err(AppError::Output {
                path: self.path.clone(),
                message: "the writer thread has stopped".into(),
            }),
        }
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

    /// Seconds the run's thread spent recording so far (buffering, handing over, waiting for the
    /// writer when it was two batches behind).
    pub fn busy_seconds(&self) -> f64 {
        self.busy
    }

    /// Seconds the writer thread spent compressing, writing and flushing so far (alongside the run).
    pub fn writer_seconds(&self) -> f64 {
        lock(&self.sink).as_ref().map_or(0.0, |s| s.seconds)
    }

    /// Records recorded so far (written, queued or buffered).
    pub fn records(&self) -> usize {
        self.queued + self.rows
    }

    /// Cuts every `/dynamic` dataset back to `records` records (a restart drops what the
    /// interrupted run wrote after its checkpoint).
    fn truncate(&mut self, records: usize) -> Result<(), AppError> {
        self.sync()?;
        if let Some(s) = lock(&self.sink).as_mut() {
            s.truncate(records)?;
        }
        self.queued = records;
        Ok(())
    }
}

impl Drop for Recorder {
    /// Every queued batch reaches the file before the recorder is gone.
    fn drop(&mut self) {
        drop(self.jobs.take());
        if let Some(w) = self.writer.take() {
            let _ = w.join();
        }
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
        if self.has_design {
            self.design = catena::design_observer::evaluator_of(ctx)
                .map(|ev| (ev, vec![0.0; ctx.model.line.nodes()]));
        }
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
            // Self-description, by the writer thread (after it has created the file).
            self.send(Job::Describe(Describe {
                gauges: ctx
                    .spec
                    .gauges
                    .iter()
                    .zip(&self.gauge_arcs)
                    .map(|(g, a)| (g.name.clone(), *a))
                    .collect(),
                arc: ctx.model.line.arc.clone(),
                has_design: self.has_design,
                has_sea: self.has_sea,
            }))?;
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
        let r = self.sync();
        self.busy += t0.elapsed().as_secs_f64();
        r
    }

    fn save(&mut self) -> Result<serde_json::Value, AppError> {
        self.sync()?;
        Ok(serde_json::json!({ "records": self.queued }))
    }

    fn restore(&mut self, v: &serde_json::Value) -> Result<(), String> {
        let records = v["records"].as_u64().ok_or_else(|| {
            "it holds no record count for results.h5 (was it written with an HDF5 recorder?)"
                .to_string()
        })?;
        self.truncate(records as usize).map_err(|e| e.to_string())
    }
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

/// Writes the design check's per-node results into `/design_check` (beside the per-record
/// `utilisation` the recorder wrote): `utilisation_max`, `time_of_max`, `term_of_max` (an index
/// into the attribute `terms`), `least_effective_tension`, `time_of_least` and `euler_load`, with
/// units and the code's name and conventions as attributes. Nothing without a check.
pub fn write_design_check(path: &Path, r: &catena::run::DynamicRun) -> Result<(), AppError> {
    let Some(d) = r.output::<catena::design_observer::DesignCheck>() else {
        return Ok(());
    };
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    let g = if file.link_exists("design_check") {
        file.group("design_check").map_err(&err)?
    } else {
        file.create_group("design_check").map_err(&err)?
    };
    for name in [
        "utilisation_max",
        "time_of_max",
        "term_of_max",
        "least_effective_tension",
        "time_of_least",
        "euler_load",
    ] {
        if g.link_exists(name) {
            g.unlink(name).map_err(&err)?;
        }
    }
    // A restart into the same directory rewrites them.
    for name in g.attr_names().map_err(&err)? {
        g.delete_attr(&name).map_err(&err)?;
    }
    attr(&g, "code", d.spec.code.name()).map_err(&err)?;
    num_attr(&g, "start", d.spec.start).map_err(&err)?;
    attr(
        &g,
        "convention",
        "utilisation: the code's criterion (DNV-ST-F201 combined loading with functional = the static state, environmental = the increment over it; API STD 2RD von Mises over C*SMYS); above 1 fails",
    )
    .map_err(&err)?;
    vector(&g, "utilisation_max", &d.max, "1").map_err(&err)?;
    vector(&g, "time_of_max", &d.time_of_max, "s").map_err(&err)?;
    let terms: Vec<u8> = d.term_of_max.iter().map(|t| t.index()).collect();
    let ds = g
        .new_dataset_builder()
        .with_data(&terms)
        .create("term_of_max")
        .map_err(&err)?;
    let names: Vec<String> = catena::design::Term::ALL
        .iter()
        .enumerate()
        .map(|(i, t)| format!("{i} {}", t.name()))
        .collect();
    attr(&ds, "terms", &names.join(", ")).map_err(&err)?;
    let least: Vec<f64> = d
        .least_tension
        .iter()
        .map(|t| if *t == f64::MAX { f64::NAN } else { *t })
        .collect();
    vector(&g, "least_effective_tension", &least, "N").map_err(&err)?;
    vector(&g, "time_of_least", &d.time_of_least, "s").map_err(&err)?;
    vector(
        &g,
        "euler_load",
        &d.euler,
        "N (pi^2 EI / L^2, the smaller of the adjacent elements')",
    )
    .map_err(&err)?;
    let dims: Vec<(String, Vec<Option<&str>>)> = [
        "utilisation_max",
        "time_of_max",
        "term_of_max",
        "least_effective_tension",
        "time_of_least",
        "euler_load",
    ]
    .iter()
    .map(|n| (format!("design_check/{n}"), vec![Some("dynamic/arc")]))
    .collect();
    dimension_scales(&file, &dims).map_err(&err)?;
    file.flush().map_err(&err)?;
    Ok(())
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
            dimension_scales(
                &file,
                &[(
                    format!("fatigue/damage_{}", fib.name()),
                    vec![Some("dynamic/arc")],
                )],
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
    let mut dims: Vec<(String, Vec<Option<&str>>)> = Vec::new();
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
        dims.extend(
            ["min", "max", "mean"]
                .iter()
                .map(|w| (format!("ranges/{name}/{w}"), vec![Some("dynamic/arc")])),
        );
    }
    // Attached in one pass: `/dynamic/arc`'s list of uses rewritten once, not once per quantity.
    dimension_scales(&file, &dims).map_err(&err)?;
    file.flush().map_err(&err)?;
    Ok(())
}

/// A channel's name, design end and record.
pub type Channel = (String, catena::extremes::Tail, Vec<f64>);

/// The channels of `catena extremes` from a results file's records: `/dynamic/time` and, for each
/// name, its record: `top_tension`, `least_tension` (the least of each record's effective
/// tensions), `sag_moment` (the least moment), `utilisation` (the largest of
/// `/design_check/utilisation`'s row), `utilisation_at_critical` and `moment_at_critical` (at the
/// node of the largest utilisation over the run; the moment's least where the static moment is a
/// sag, else its greatest), `gauge:NAME[:max|:min]` (the gauge's moment). Each with its
/// design end; no names: the first three and, with a design check, `utilisation`. A name the file
/// cannot give is an error naming the file and the channel.
pub fn read_extreme_channels(
    path: &Path,
    names: &[String],
) -> Result<(Vec<f64>, Vec<Channel>), AppError> {
    use catena::extremes::Tail;
    let err = h5err(path);
    let file = hdf5::File::open(path).map_err(&err)?;
    let read = |name: &str| -> Result<Vec<f64>, AppError> {
        file.dataset(name)
            .and_then(|d| d.read_raw::<f64>())
            .map_err(&err)
    };
    let time = read("dynamic/time")?;
    let nt = time.len();
    let mut defaults: Vec<String> = ["top_tension", "least_tension", "sag_moment"]
        .map(String::from)
        .to_vec();
    if file.link_exists("design_check") {
        defaults.push("utilisation".into());
    }
    let names = if names.is_empty() {
        &defaults[..]
    } else {
        names
    };
    let rows = |name: &str, pick: fn(&[f64]) -> f64| -> Result<Vec<f64>, AppError> {
        let v = read(name)?;
        let n = v.len() / nt.max(1);
        Ok(v.chunks_exact(n.max(1)).map(pick).collect())
    };
    let least = |r: &[f64]| r.iter().copied().fold(f64::INFINITY, f64::min);
    let most = |r: &[f64]| r.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mut out = Vec::new();
    for name in names {
        let missing = |what: &str| AppError::Run {
            file: path.display().to_string(),
            message: format!("--channel {name}: {what}"),
        };
        let (tail, v) = match name.as_str() {
            "top_tension" => (Tail::Max, read("dynamic/top_tension")?),
            "least_tension" => (Tail::Min, rows("dynamic/effective_tension", least)?),
            "sag_moment" => (Tail::Min, rows("dynamic/bending_moment", least)?),
            "utilisation" => {
                if !file.link_exists("design_check") {
                    return Err(missing(
                        "the file has no /design_check (the run had no [design_check])",
                    ));
                }
                (Tail::Max, rows("design_check/utilisation", most)?)
            }
            "utilisation_at_critical" | "moment_at_critical" => {
                // The critical node: the largest utilisation over the run (every step).
                if !file.link_exists("design_check/utilisation_max") {
                    return Err(missing(
                        "the file has no /design_check/utilisation_max (the run had no [design_check])",
                    ));
                }
                let umax = read("design_check/utilisation_max")?;
                let i = umax
                    .iter()
                    .enumerate()
                    .fold(0, |b, (i, v)| if *v > umax[b] { i } else { b });
                let column = |name: &str| -> Result<Vec<f64>, AppError> {
                    let v = read(name)?;
                    let n = v.len() / nt.max(1);
                    Ok(v.chunks_exact(n.max(1)).map(|r| r[i]).collect())
                };
                if name == "utilisation_at_critical" {
                    (Tail::Max, column("design_check/utilisation")?)
                } else {
                    // A sag (negative static moment) is a least extreme, a hog a greatest.
                    let m0 = read("static/bending_moment")?;
                    let tail = if m0.get(i).is_some_and(|m| *m < 0.0) {
                        Tail::Min
                    } else {
                        Tail::Max
                    };
                    (tail, column("dynamic/bending_moment")?)
                }
            }
            other => {
                let g = other.strip_prefix("gauge:").ok_or_else(|| {
                    missing("not a channel: top_tension, least_tension, sag_moment, utilisation, utilisation_at_critical, moment_at_critical or gauge:NAME[:max]")
                })?;
                let (g, tail) = match g.strip_suffix(":max") {
                    Some(g) => (g, Tail::Max),
                    None => (g.strip_suffix(":min").unwrap_or(g), Tail::Min),
                };
                let ds = format!("dynamic/gauges/{g}/bending_moment");
                if !file.link_exists(&format!("dynamic/gauges/{g}")) {
                    return Err(missing(&format!("the file has no gauge `{g}`")));
                }
                (tail, read(&ds)?)
            }
        };
        if v.len() != nt {
            return Err(missing("its record is not as long as /dynamic/time"));
        }
        out.push((name.clone(), tail, v));
    }
    Ok((time, out))
}

/// A run's records for the animation ([`crate::animate`]): `/dynamic`'s fields and each node's
/// outer diameter, `/line/contact_od` (in a file written before `/line` existed: from the scene
/// the file carries, [`crate::animate::diameters`]).
pub fn read_animation(path: &Path) -> Result<crate::animate::Records, AppError> {
    let err = h5err(path);
    let file = hdf5::File::open(path).map_err(&err)?;
    let bad = |m: String| AppError::Run {
        file: path.display().to_string(),
        message: m,
    };
    if !file.link_exists("dynamic") {
        return Err(bad(
            "no /dynamic group: a dynamic run's results.h5 is needed (`catena run` with a \
             [dynamic] table)"
                .into(),
        ));
    }
    let read = |name: &str| -> Result<Vec<f64>, AppError> {
        file.dataset(name)
            .and_then(|d| d.read_raw::<f64>())
            .map_err(&err)
    };
    let scene: VarLenUnicode = file
        .attr("scene")
        .and_then(|a| a.read_scalar())
        .map_err(&err)?;
    let case: VarLenUnicode = file
        .attr("case")
        .and_then(|a| a.read_scalar())
        .map_err(&err)?;
    crate::animate::Records::from_named(
        |name| read(&format!("dynamic/{name}")),
        |arc| {
            // Each node's diameter as the run used it (`/line/contact_od`); a file written before
            // `/line` existed: from the scene it carries.
            if file.link_exists("line/contact_od") {
                let od = read("line/contact_od")?;
                if od.len() == arc.len() {
                    return Ok(od);
                }
            }
            crate::animate::diameters(scene.as_str(), case.as_str(), arc.len()).ok_or_else(|| {
                bad(
                    "the scene in the `scene` attribute gives no pipe diameter (line.od or line \
                     types)"
                        .into(),
                )
            })
        },
    )
}
