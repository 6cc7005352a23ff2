//! The HDF5 recorder, an observer of the run: records taken at the output interval, handed to
//! the writer thread ([`super::sink`]) in batches; on restart the file is reopened and truncated to
//! the checkpoint's record count.

use super::*;

/// Streams dynamic records into `/dynamic` as an observer of the run: a record at every output
/// interval, handed to a writer thread in batches of 64 records or every second of wall time,
/// whichever comes first. The writer compresses, writes and flushes while the run steps on; the run
/// waits only when it is two batches ahead. A checkpoint, the end of the run and dropping the
/// recorder wait until every batch is in the file.
pub struct Recorder {
    pub(super) path: PathBuf,
    /// The file's datasets: `None` until the writer thread has created the file.
    pub(super) sink: Arc<Mutex<Option<Sink>>>,
    pub(super) jobs: Option<mpsc::SyncSender<Job>>,
    pub(super) writer: Option<std::thread::JoinHandle<()>>,
    /// The writer's first error, if any.
    pub(super) failed: Arc<Mutex<Option<String>>>,
    /// Set (and waiters woken) when the writer thread has created the file, or failed to.
    pub(super) created: Arc<(Mutex<bool>, std::sync::Condvar)>,
    pub(super) n: usize,
    pub(super) chunk: usize,
    /// Records handed to the writer.
    pub(super) queued: usize,
    pub(super) rows: usize,
    pub(super) series: Vec<Vec<f64>>,
    pub(super) fields: Vec<Vec<f64>>,
    pub(super) modes: Vec<u8>,
    pub(super) gauge_arcs: Vec<f64>,
    /// With waves: `(x where the elevation is recorded, static top (x, z), (sin θ_top, cos θ_top))`.
    pub(super) sea: Option<(f64, [f64; 2], [f64; 2])>,
    pub(super) has_sea: bool,
    /// With a design check: its evaluator (set when the run starts) and the step's utilisation.
    pub(super) design: Option<(catena::checks::design::Evaluator, Vec<f64>)>,
    pub(super) has_design: bool,
    pub(super) last_flush: Instant,
    /// Time the run's thread spent recording (buffering, handing over, waiting), s.
    pub(super) busy: f64,
    /// Whether the float fields are stored deflated, and the steps between records
    /// (`output_every`): whether the writer keeps a core busy ([`writer_keeps_core`]).
    pub(super) writes: (bool, usize),
}

/// Whether a writer keeps a core busy: it deflates the records, or it writes one at every step
/// (`output_every` 1). Measured on two cores (`benches/README.md`, issue 48): storm 23 (a record
/// every 10 steps) steps on two threads beside an uncompressed writer in 10.1–12.2 s against
/// 13.9–15.0 s on one beside a compressing one, and loses to the one thread when its writer
/// compresses; the heave benchmark (a record every step, 100 s) loses 10–20 % on two threads
/// beside its writer.
pub fn writer_keeps_core(compressed: bool, output_every: usize) -> bool {
    compressed || output_every <= 1
}

/// The deflate level of the `/dynamic` fields (byte shuffle first). Level 1: the higher levels
/// shrink full-precision floats little more for much more time (`benches/README.md`). The writer
/// thread does it, off the run's critical path.
pub(super) const DEFLATE: u8 = 1;

pub(super) const SEA: [(&str, &str); 3] = [
    ("wave_elevation", "m"),
    ("top_pitch", "rad"),
    ("top_axial_motion", "m"),
];

pub(super) const FLUSH_EVERY: Duration = Duration::from_secs(1);

/// The sign and axis conventions, written as attributes of `/dynamic`.
pub(super) const CONVENTIONS: [(&str, &str); 5] = [
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
        let every = dynamic.map_or(1, |d| d.output_every);
        let (path_buf, statics, gauges) = (path.to_path_buf(), statics.clone(), gauges.to_vec());
        let init: Init = Box::new(move || Self::build_sink(&path_buf, &statics, &gauges, compress));
        let (sink, writes) = (Arc::new(Mutex::new(None)), (compress, every));
        Self::with_writer(path, (shape, writes), sink, Some(init))
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

    /// Opens an existing results file of `statics`' scene to continue its `/dynamic` records (a
    /// restart), compressed as the file's fields are. Its state is restored from the checkpoint
    /// before the run goes on ([`Observer::restore`]).
    pub fn open(path: &Path, statics: &StaticRun, gauges: &[String]) -> Result<Self, AppError> {
        let file = hdf5::File::open_rw(path).map_err(h5err(path))?;
        let (sink, shape) = Self::sink_of(path, file, statics.model.nodes(), gauges)?;
        let compressed = sink.fields.iter().any(|f| !f.filters().is_empty());
        let every = statics.scene.dynamic.as_ref().map_or(1, |d| d.output_every);
        let sink = Arc::new(Mutex::new(Some(sink)));
        Self::with_writer(path, (shape, (compressed, every)), sink, None)
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

    /// The recorder of a file of this shape, written as `writes` says (compressed, the steps
    /// between records), its writer thread started: the thread first builds the datasets with
    /// `init` when they are not there yet (a new file), then takes the jobs in order.
    fn with_writer(
        path: &Path,
        (shape, writes): (Shape, (bool, usize)),
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
            writes,
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

    /// Whether the float fields are stored deflated (asked, or `catena run`'s default).
    pub fn compressed(&self) -> bool {
        self.writes.0
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

    fn busy_threads(&self) -> usize {
        usize::from(self.writer.is_some() && writer_keeps_core(self.writes.0, self.writes.1))
    }

    fn start(
        &mut self,
        ctx: &RunContext<'_>,
        first: &StepView<'_>,
        restarted: bool,
    ) -> Result<(), AppError> {
        self.gauge_arcs = ctx.spec.gauges.iter().map(|g| g.arc).collect();
        if self.has_design {
            self.design = catena::run::observers::design::evaluator_of(ctx)
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
        _: Option<&catena::run::observe::Stop>,
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
