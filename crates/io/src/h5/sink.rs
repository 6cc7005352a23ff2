//! The writer thread's side of the recorder: the `/dynamic` datasets and the file, created while
//! the run starts, each batch written and flushed as it comes.

use super::*;

/// The datasets of `/dynamic` and the file, as the writer thread writes them.
pub(super) struct Sink {
    pub(super) path: PathBuf,
    pub(super) file: hdf5::File,
    pub(super) n: usize,
    pub(super) series: Vec<hdf5::Dataset>,
    pub(super) fields: Vec<hdf5::Dataset>,
    pub(super) modes: hdf5::Dataset,
    /// Records in the file.
    pub(super) written: usize,
    /// Seconds spent writing (compressing, writing, flushing).
    pub(super) seconds: f64,
}

/// Records handed from the run to the writer: `rows` records of every series, field and the modes.
pub(super) struct Batch {
    pub(super) rows: usize,
    pub(super) series: Vec<Vec<f64>>,
    pub(super) fields: Vec<Vec<f64>>,
    pub(super) modes: Vec<u8>,
}

/// What the writer thread is asked to do.
pub(super) enum Job {
    /// Write `/dynamic`'s self-description (the run's start, [`Describe`]).
    Describe(Describe),
    /// Append a batch and flush the file.
    Write(Batch),
    /// Answer once every earlier job is done, with the first write error if there was one.
    Sync(mpsc::SyncSender<Option<String>>),
}

/// Batches the run may queue ahead of the writer (then it waits): at most this many × 64 records in
/// memory.
pub(super) const QUEUE: usize = 2;

/// What a recorder needs to know of its file's `/dynamic` before the file is there: the nodes,
/// the series and fields it records, whether it has the sea's series and the design check's
/// utilisation, and the records already written (a restart).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Shape {
    pub(super) n: usize,
    pub(super) ns: usize,
    pub(super) nf: usize,
    pub(super) has_sea: bool,
    pub(super) has_design: bool,
    pub(super) written: usize,
}

/// Builds a new file's datasets (on the writer thread), and says what shape they have.
pub(super) type Init = Box<dyn FnOnce() -> Result<(Sink, Shape), AppError> + Send>;

/// An output error's message alone (the recorder names the file when it reports it).
pub(super) fn output_message(e: AppError) -> String {
    match e {
        AppError::Output { message, .. } => message,
        e => e.to_string(),
    }
}

/// `/dynamic`'s self-description, written when the run starts: each gauge's arc length, the arc
/// axis of the fields, the conventions and the dimension scales.
pub(super) struct Describe {
    /// Each gauge's name and arc length, m.
    pub(super) gauges: Vec<(String, f64)>,
    /// Each node's arc length, m.
    pub(super) arc: Vec<f64>,
    pub(super) has_design: bool,
    pub(super) has_sea: bool,
}

impl Describe {
    pub(super) fn write(&self, sink: &Sink) -> Result<(), AppError> {
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
            // The components' arrays along their frequency.
            for name in ["wavenumber", "amplitude", "phase"] {
                dims.push((format!("waves/{name}"), vec![Some("waves/omega")]));
            }
        }
        dims.extend(one_d.into_iter().map(|d| (d, vec![Some("dynamic/time")])));
        dimension_scales(&sink.file, &dims).map_err(&err)?;
        // Each group that uses `/dynamic`'s scales holds them too (hard links: the same datasets),
        // so that it opens on its own with its dimensions and coordinates (netCDF readers, xarray).
        let mut groups: Vec<(String, &[&str])> = self
            .gauges
            .iter()
            .map(|(name, _)| (format!("dynamic/gauges/{name}"), &["time"][..]))
            .collect();
        if self.has_design {
            groups.push(("design_check".into(), &["time", "arc"][..]));
        }
        for (group, scales) in groups {
            link_scales(&sink.file, &group, "dynamic", scales).map_err(&err)?;
        }
        sink.file.flush().map_err(&err)
    }
}

impl Sink {
    pub(super) fn write(&mut self, b: &Batch) -> Result<(), String> {
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
    pub(super) fn truncate(&mut self, records: usize) -> Result<(), AppError> {
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

pub(super) fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    // A panic on the writer thread cannot leave a half-updated Sink that matters: the file is what
    // it wrote, and `written` is updated after the writes.
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}
