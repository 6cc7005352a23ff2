//! catena from Python: the native module `catena._catena`, wrapped by the `catena` package in
//! `python/catena/` (built with maturin: `pip install ./python`).
//!
//! Everything runs through the library crate (`catena`): the same scene reader, checks, statics,
//! dynamics, fatigue study and sweep as the command line, so a result is the same to the bit.
//! Results come back in memory, never through HDF5 (a wheel needs no libhdf5): arrays as
//! little-endian `f64` bytes with their shape, which the Python side turns into numpy arrays, and
//! summaries as JSON text. Names and units are those of `results.h5` (see `docs/results.md`).
//! Errors are `catena.CatenaError` with the command line's message (file, key, what was expected).

use std::path::PathBuf;

use catena::run::observe::{Control, Observer, RunContext, StepView};
use catena::run::records::Records;
use catena::run::RunOptions;
use catena::scene::edit::Edit;
use catena::scene::riser::RiserScene;
use catena::scene::DirResolver;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

pyo3::create_exception!(
    _catena,
    CatenaError,
    PyException,
    "An error from catena: a bad input (naming the file, the key and what was expected), a solve \
     that failed, or a run that stopped."
);

fn err(e: impl std::fmt::Display) -> PyErr {
    CatenaError::new_err(e.to_string())
}

/// A scene: a case file read and checked, and the folder its relative paths are resolved from.
#[pyclass(name = "Scene", module = "catena._catena", from_py_object)]
#[derive(Clone)]
struct PyScene {
    scene: RiserScene,
    files: DirResolver,
}

#[pymethods]
impl PyScene {
    /// Reads and checks a case file.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let scene = catena::run::statics::read_scene(&path).map_err(err)?;
        Ok(Self {
            scene,
            files: DirResolver::beside(&path),
        })
    }

    /// Reads and checks a scene given as TOML text; `base_dir` resolves its relative paths (RAO
    /// tables, motion series), `name` is what error messages call it.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir = None, name = "<text>"))]
    fn from_text(text: &str, base_dir: Option<PathBuf>, name: &str) -> PyResult<Self> {
        let dir = base_dir.unwrap_or_else(|| PathBuf::from("."));
        let files = DirResolver::beside(&dir.join(name));
        let scene = RiserScene::parse(name, text, &files).map_err(err)?;
        Ok(Self { scene, files })
    }

    /// A copy with keys set (`{"seabed.k": 1000.0, "dynamic.duration": 20.0}`); a value of `None`
    /// removes the key. The edited scene is checked like a file.
    fn edited(&self, edits: &Bound<'_, PyDict>) -> PyResult<Self> {
        let mut list = Vec::new();
        for (k, v) in edits.iter() {
            let key: String = k.extract()?;
            if v.is_none() {
                list.push(Edit::remove(&key));
            } else {
                list.push(Edit::set(&key, to_toml(&key, &v)?));
            }
        }
        let scene = self.scene.edited(&list, &self.files).map_err(err)?;
        Ok(Self {
            scene,
            files: self.files.clone(),
        })
    }

    /// The scene as TOML text (after any edits).
    #[getter]
    fn text(&self) -> String {
        self.scene.text.clone()
    }

    /// The file name error messages use.
    #[getter]
    fn file(&self) -> String {
        self.scene.file.clone()
    }

    fn __repr__(&self) -> String {
        format!("Scene({:?})", self.scene.file)
    }
}

/// A Python value as a TOML value (bool, int, float, str, or a list of them).
fn to_toml(key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if let Ok(b) = v.extract::<bool>() {
        return Ok(toml::Value::Boolean(b));
    }
    if let Ok(i) = v.extract::<i64>() {
        return Ok(toml::Value::Integer(i));
    }
    if let Ok(x) = v.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    if let Ok(s) = v.extract::<String>() {
        return Ok(toml::Value::String(s));
    }
    if let Ok(list) = v.cast::<PyList>() {
        return list
            .iter()
            .map(|x| to_toml(key, &x))
            .collect::<PyResult<Vec<_>>>()
            .map(toml::Value::Array);
    }
    Err(CatenaError::new_err(format!(
        "key `{key}`: expected a bool, a number, a string or a list of them"
    )))
}

/// `(bytes, shape)` of a vector of f64, little-endian.
fn array<'py>(py: Python<'py>, v: &[f64], shape: Vec<usize>) -> (Bound<'py, PyBytes>, Vec<usize>) {
    let mut b = Vec::with_capacity(8 * v.len());
    for x in v {
        b.extend_from_slice(&x.to_le_bytes());
    }
    (PyBytes::new(py, &b), shape)
}

/// The static solution: `{"arrays": {name: (bytes, shape)}, "summary": json}`.
#[pyfunction]
fn statics<'py>(py: Python<'py>, scene: &PyScene) -> PyResult<Bound<'py, PyDict>> {
    let st = catena::run::statics::solve(scene.scene.clone()).map_err(err)?;
    let out = PyDict::new(py);
    let arrays = PyDict::new(py);
    let r = &st.results;
    let n = r.x.len();
    for (name, v) in [
        ("arc", &st.model.arc),
        ("x", &r.x),
        ("z", &r.z),
        ("theta", &r.theta),
        ("effective_tension", &r.tension),
        ("bending_moment", &r.moment),
        ("penetration", &r.penetration),
        ("seabed_force", &r.seabed_force),
    ] {
        arrays.set_item(name, array(py, v, vec![n]))?;
    }
    out.set_item("arrays", arrays)?;
    let s = &st.summary;
    let summary = serde_json::json!({
        "top_tension": s.top_tension,
        "horizontal_tension": s.horizontal_tension,
        "anchor_horizontal_tension": s.anchor_horizontal_tension,
        "touchdown_arc": s.touchdown_arc,
        "max_sag_moment": s.max_sag_moment.0, "max_sag_moment_arc": s.max_sag_moment.1,
        "top_angle_from_vertical": s.top_angle_from_vertical,
        "newton_iterations": st.report.iterations,
        "wall_seconds": st.wall_seconds,
    });
    out.set_item("summary", summary.to_string())?;
    Ok(out)
}

/// Calls a Python progress function every `every` steps, at most [`PROGRESS_PERIOD`] apart, and
/// stops the run on Ctrl-C. It runs with the interpreter released and takes it only for that call
/// (a few times a second at most), so other Python threads run while catena steps.
struct Progress {
    callback: Option<Py<PyAny>>,
    every: u64,
    last: Option<std::time::Instant>,
    error: Option<PyErr>,
}

/// The shortest interval between two calls of a progress function (and two Ctrl-C checks).
const PROGRESS_PERIOD: std::time::Duration = std::time::Duration::from_millis(200);

impl Observer for Progress {
    fn name(&self) -> &'static str {
        "python-progress"
    }

    fn step(
        &mut self,
        ctx: &RunContext<'_>,
        s: &StepView<'_>,
    ) -> Result<Control, catena::error::AppError> {
        let last_step = s.t >= ctx.spec.duration - 0.5 * ctx.spec.dt;
        if s.step % self.every != 0 && !last_step {
            return Ok(Control::Continue);
        }
        let now = std::time::Instant::now();
        if !last_step && self.last.is_some_and(|l| now - l < PROGRESS_PERIOD) {
            return Ok(Control::Continue);
        }
        self.last = Some(now);
        let stop = Python::attach(|py| {
            if let Err(e) = py.check_signals() {
                return Some((e, "interrupted from Python"));
            }
            if let Some(cb) = &self.callback {
                if let Err(e) = cb.call1(py, (s.t, ctx.spec.duration)) {
                    return Some((e, "the progress function raised"));
                }
            }
            None
        });
        if let Some((e, why)) = stop {
            self.error = Some(e);
            return Ok(Control::Stop(why.into()));
        }
        Ok(Control::Continue)
    }
}

/// A dynamic run (statics first): `{"arrays": …, "summary": json}`. The arrays are the
/// `results.h5` `/dynamic` series and fields (one row per record), the envelopes (`*_min`,
/// `*_max`, from `envelope_start`) and each gauge's moment and tension at every step. The
/// interpreter is released while catena steps. `threads`: the threads the run may keep busy
/// ([`RunOptions::threads`]; 0: [`run_threads`]).
#[pyfunction]
#[pyo3(signature = (scene, progress = None, every = 100, threads = 0))]
fn run<'py>(
    py: Python<'py>,
    scene: &PyScene,
    progress: Option<Py<PyAny>>,
    every: u64,
    threads: usize,
) -> PyResult<Bound<'py, PyDict>> {
    if scene.scene.lay.is_some() {
        return run_lay(py, scene, threads);
    }
    let mut records = Records::new();
    let mut prog = Progress {
        callback: progress,
        every: every.max(1),
        last: None,
        error: None,
    };
    let input = scene.scene.clone();
    let threads = run_threads(py, threads);
    let r = py
        .detach(|| {
            let mut extra: [&mut dyn Observer; 2] = [&mut records, &mut prog];
            let opts = RunOptions::with_threads(threads);
            catena::run::simulate(input, &mut extra, opts)
        })
        .map_err(err)?;
    if let Some(e) = prog.error.take() {
        return Err(e);
    }
    let out = PyDict::new(py);
    let arrays = PyDict::new(py);
    let (nr, n) = (records.len(), records.arc.len());
    arrays.set_item(
        "arc",
        array(py, &r.model.line.arc, vec![r.model.line.arc.len()]),
    )?;
    arrays.set_item(
        "outer_diameter",
        array(py, &r.model.line.node_od, vec![r.model.line.node_od.len()]),
    )?;
    for (name, v) in &records.series {
        arrays.set_item(*name, array(py, v, vec![nr]))?;
    }
    for (name, v) in &records.fields {
        arrays.set_item(*name, array(py, v, vec![nr, n]))?;
    }
    let e = &r.envelopes;
    for (name, range) in e.ranges() {
        let m = range.min.len();
        for (what, v) in [
            ("min", range.min.clone()),
            ("max", range.max.clone()),
            ("mean", range.mean(e.samples)),
        ] {
            arrays.set_item(format!("ranges/{name}/{what}"), array(py, &v, vec![m]))?;
        }
    }
    for (g, tr) in r.gauges.gauges.iter().zip(&r.gauges.traces) {
        arrays.set_item(
            format!("gauges/{}/bending_moment", g.name),
            array(py, &tr.moment, vec![tr.moment.len()]),
        )?;
        arrays.set_item(
            format!("gauges/{}/effective_tension", g.name),
            array(py, &tr.tension, vec![tr.tension.len()]),
        )?;
    }
    if let Some(f) = &r.fatigue {
        for fib in &f.spec.fibres {
            if let Some(d) = f.damage_of(*fib) {
                arrays.set_item(
                    format!("fatigue/damage_{}", fib.name()),
                    array(py, &d, vec![d.len()]),
                )?;
            }
        }
    }
    out.set_item("arrays", arrays)?;
    let (tdp_min, tdp_max) = e.touchdown;
    let gauges: Vec<_> = r
        .gauges
        .gauges
        .iter()
        .map(|g| serde_json::json!({"name": g.name, "arc": g.arc}))
        .collect();
    let summary = serde_json::json!({
        "completed": r.completed(),
        "stop_reason": r.stop.as_ref().map(ToString::to_string),
        "t_reached": r.t_reached,
        "steps": r.steps,
        "newton_iterations": r.iterations,
        "step_cuts": r.cuts,
        "predictor_retries": r.retries,
        "wall_seconds": r.wall_seconds,
        "stepping_threads": r.stepping_threads,
        "steps_on_two_threads": r.steps_on_two,
        "records": nr,
        "time_step": r.spec.dt,
        "envelope_start": r.spec.envelope_start,
        "touchdown_arc_min": tdp_min.is_finite().then_some(tdp_min),
        "touchdown_arc_max": tdp_max.is_finite().then_some(tdp_max),
        "gauges": gauges,
        "fatigue_counted_seconds": r.fatigue.as_ref().map(|f| f.counted_seconds()),
    });
    out.set_item("summary", summary.to_string())?;
    Ok(out)
}

/// A lay (a scene with `[lay]`): `results.h5`'s `/lay` arrays under the same names (`lay/time`,
/// `lay/as_laid_embedment`, …) and `summary.json` (with its `lay`). The interpreter is released
/// while catena lays the pipe. `threads`: as [`run`]'s
/// ([`catena::run::lay::LayOptions::threads`]: from two, each window is stepped on two threads,
/// the same bits).
fn run_lay<'py>(py: Python<'py>, scene: &PyScene, threads: usize) -> PyResult<Bound<'py, PyDict>> {
    let input = scene.scene.clone();
    let threads = run_threads(py, threads);
    let r = py
        .detach(|| {
            let st = catena::statics::solve(catena::run::lay::statics_scene(input))?;
            let opts = catena::run::lay::LayOptions {
                threads,
                ..catena::run::lay::LayOptions::default()
            };
            catena::run::lay::lay_with(st, opts, &mut |_| true)
        })
        .map_err(err)?;
    let arrays = PyDict::new(py);
    let rec = &r.records;
    let nr = rec.time.len();
    for (name, v) in [
        ("time", &rec.time),
        ("paid_out", &rec.paid_out),
        ("vessel_x", &rec.vessel_x),
        ("top_tension", &rec.top_tension),
        ("payout_rate", &rec.payout_rate),
        ("touchdown_x", &rec.touchdown_x),
        ("touchdown_arc", &rec.touchdown_arc),
        ("window_nodes", &rec.window_nodes),
        ("sag_moment", &rec.sag_moment),
    ] {
        arrays.set_item(format!("lay/{name}"), array(py, v, vec![nr]))?;
    }
    let n = &r.nodes;
    let nn = n.kp.len();
    let episodes: Vec<f64> = n.episodes.iter().map(|&e| f64::from(e)).collect();
    let landed: Vec<f64> = n.landed.iter().map(|&b| f64::from(u8::from(b))).collect();
    let x: Vec<f64> = r.positions.iter().map(|p| p[0]).collect();
    let z: Vec<f64> = r.positions.iter().map(|p| p[1]).collect();
    for (name, v) in [
        ("kp", &n.kp),
        ("arc", &n.arc),
        ("as_laid_embedment", &n.as_laid),
        ("laid_x", &n.laid_x),
        ("max_contact_force", &n.max_contact),
        ("episodes", &episodes),
        ("strength_factor", &n.strength),
        ("landed_during_lay", &landed),
        ("x", &x),
        ("z", &z),
    ] {
        arrays.set_item(format!("lay/{name}"), array(py, v, vec![nn]))?;
    }
    if let Some(c) = &r.installation {
        arrays.set_item("lay/lcc_utilisation", array(py, &c.lcc_of_node, vec![nn]))?;
    }
    // The animation's frames, as `/lay/frames` (single precision there, the same values here).
    let f = &r.frames;
    let nf = f.len();
    let top_x: Vec<f64> = f.exit.iter().map(|p| p[0]).collect();
    let top_z: Vec<f64> = f.exit.iter().map(|p| p[1]).collect();
    let od: Vec<f64> = (0..nn)
        .map(|k| catena::run::lay::frames::contact_od(&r.full, k))
        .collect();
    arrays.set_item("lay/frames/time", array(py, &f.time, vec![nf]))?;
    arrays.set_item("lay/frames/top_x", array(py, &top_x, vec![nf]))?;
    arrays.set_item("lay/frames/top_z", array(py, &top_z, vec![nf]))?;
    arrays.set_item("lay/frames/contact_od", array(py, &od, vec![nn]))?;
    for (name, v) in [
        ("x", &f.x),
        ("z", &f.z),
        ("penetration", &f.penetration),
        ("seabed_force", &f.seabed_force),
        ("bending_moment", &f.moment),
    ] {
        let wide: Vec<f64> = v.iter().map(|&x| f64::from(x)).collect();
        arrays.set_item(format!("lay/frames/{name}"), array(py, &wide, vec![nf, nn]))?;
    }
    let out = PyDict::new(py);
    out.set_item("arrays", arrays)?;
    out.set_item("summary", catena_io::lay::json(&r).to_string())?;
    Ok(out)
}

/// The threads a run may keep busy, as Python gives them, as [`RunOptions::threads`] takes them.
/// 0, the default: one thread where the caller shares the cores with other callers
/// ([`shared_caller`]: a Python thread other than the main one — a `threading.Thread`, an
/// executor's worker, a Dask worker's task — or a process pool's worker), else the cores no other
/// run of this process holds ([`catena::run::cores`]). Two runs started from two Python threads
/// then step on one core each instead of four threads on two cores (1.98× one run, measured on
/// two cores, before this default); the results are the same to the bit whatever the number.
fn run_threads(py: Python<'_>, threads: usize) -> Option<usize> {
    if threads > 0 {
        return Some(threads);
    }
    shared_caller(py).then_some(1)
}

/// Whether this call comes from a Python thread other than the main one, or from a child process
/// (`multiprocessing.parent_process()`: a process pool's worker). Where Python cannot say, no.
fn shared_caller(py: Python<'_>) -> bool {
    let other_thread = || -> PyResult<bool> {
        let threading = py.import("threading")?;
        let current = threading.call_method0("current_thread")?;
        let main = threading.call_method0("main_thread")?;
        Ok(!current.is(&main))
    };
    let child_process = || -> PyResult<bool> {
        let parent = py
            .import("multiprocessing")?
            .call_method0("parent_process")?;
        Ok(!parent.is_none())
    };
    other_thread().unwrap_or(false) || child_process().unwrap_or(false)
}

/// Runs `f` on `jobs` threads (0: all cores) with the interpreter released.
fn on_threads<T: Send>(
    py: Python<'_>,
    jobs: usize,
    f: impl FnOnce() -> Result<T, String> + Send,
) -> PyResult<T> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(err)?;
    py.detach(|| pool.install(f)).map_err(err)
}

/// The threads each of `n` runs may keep busy when `jobs` run side by side (0: the machine's
/// cores, as [`on_threads`]' pool): the cores shared between them
/// ([`catena::studies::schedule::threads_per_run`]).
fn per_run(jobs: usize, n: usize) -> usize {
    let jobs = if jobs == 0 {
        catena::run::default_threads()
    } else {
        jobs
    };
    catena::studies::schedule::threads_per_run(jobs.min(n))
}

/// A result or a carry as JSON text (exact: serde_json round-trips every f64).
fn to_json<T: serde::Serialize>(v: &T) -> PyResult<String> {
    serde_json::to_string(v).map_err(err)
}

/// A task's JSON text back (`what` names it in the error).
fn from_json<T: serde::de::DeserializeOwned>(what: &str, text: &str) -> PyResult<T> {
    serde_json::from_str(text).map_err(|e| err(format!("{what}: not a catena result ({e})")))
}

/// A task index checked against the number of tasks.
fn task(what: &str, k: usize, n: usize) -> PyResult<usize> {
    if k < n {
        Ok(k)
    } else {
        Err(err(format!(
            "{what} {k}: there are {n} (0 to {})",
            n.max(1) - 1
        )))
    }
}

/// A fatigue study (a study file: base scene, storm table, fatigue table), every storm run in
/// parallel: `{"arrays": {"arc", "damage_<fibre>" (annual), "life_<fibre>" (years)}, "summary"}`.
#[pyfunction]
#[pyo3(signature = (path, jobs = 0))]
fn fatigue_study<'py>(py: Python<'py>, path: PathBuf, jobs: usize) -> PyResult<Bound<'py, PyDict>> {
    use rayon::prelude::*;
    let study = catena::studies::fatigue_study::Study::read(&path).map_err(err)?;
    let threads = Some(per_run(jobs, study.storms.len()));
    let results = on_threads(py, jobs, || {
        study
            .storms
            .par_iter()
            .map(|(storm, scene)| {
                catena::studies::fatigue_study::run_storm(storm, scene, threads)
                    .map_err(|e| e.to_string())
            })
            .collect::<Result<Vec<_>, _>>()
    })?;
    study_dict(py, &study, &results)
}

/// A study's tasks, one per storm in the table's order: JSON `[{"index", "id", "scene_hash"}]`.
#[pyfunction]
fn study_tasks(path: PathBuf) -> PyResult<String> {
    let study = catena::studies::fatigue_study::Study::read(&path).map_err(err)?;
    let tasks: Vec<_> = study
        .storms
        .iter()
        .enumerate()
        .map(|(i, (storm, scene))| {
            serde_json::json!({"index": i, "id": storm.id,
                               "scene_hash": catena::scene::text_hash(&scene.text)})
        })
        .collect();
    Ok(serde_json::Value::Array(tasks).to_string())
}

/// One storm of a study (the `index`-th of its table), run with the interpreter released: the
/// storm's result as JSON text (its damage per fibre along the arc, exact). `threads`: the threads
/// the run may keep busy ([`run_threads`]).
#[pyfunction]
#[pyo3(signature = (path, index, threads = 1))]
fn study_storm(py: Python<'_>, path: PathBuf, index: usize, threads: usize) -> PyResult<String> {
    let study = catena::studies::fatigue_study::Study::read(&path).map_err(err)?;
    let (storm, scene) = &study.storms[task("storm", index, study.storms.len())?];
    let threads = run_threads(py, threads);
    let r = py
        .detach(|| catena::studies::fatigue_study::run_storm(storm, scene, threads))
        .map_err(err)?;
    to_json(&r)
}

/// A study from its storms' results (JSON texts, one per storm in the table's order), the same
/// dictionary as [`fatigue_study`].
#[pyfunction]
fn study_merge<'py>(
    py: Python<'py>,
    path: PathBuf,
    results: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let study = catena::studies::fatigue_study::Study::read(&path).map_err(err)?;
    if results.len() != study.storms.len() {
        return Err(err(format!(
            "{}: {} storm results for {} storms",
            study.file,
            results.len(),
            study.storms.len()
        )));
    }
    let results: Vec<catena::studies::fatigue_study::StormResult> = results
        .iter()
        .zip(&study.storms)
        .map(|(t, (storm, _))| from_json(&format!("storm {}", storm.id), t))
        .collect::<PyResult<_>>()?;
    for (r, (storm, scene)) in results.iter().zip(&study.storms) {
        if r.storm.id != storm.id || r.scene_hash != catena::scene::text_hash(&scene.text) {
            return Err(err(format!(
                "{}: the result given for storm {} is of another storm or an older scene",
                study.file, storm.id
            )));
        }
    }
    study_dict(py, &study, &results)
}

fn study_dict<'py>(
    py: Python<'py>,
    study: &catena::studies::fatigue_study::Study,
    results: &[catena::studies::fatigue_study::StormResult],
) -> PyResult<Bound<'py, PyDict>> {
    let arc = study
        .storms
        .first()
        .map(|(_, s)| catena::run::statics::solve(s.clone()).map(|st| st.model.arc.clone()))
        .transpose()
        .map_err(err)?
        .unwrap_or_default();
    let out = PyDict::new(py);
    let arrays = PyDict::new(py);
    arrays.set_item("arc", array(py, &arc, vec![arc.len()]))?;
    let mut lives = serde_json::Map::new();
    for fib in study.fibres() {
        let d = catena::studies::fatigue_study::annual_damage(results, fib.name());
        let life: Vec<f64> = d.iter().map(|x| 1.0 / x).collect();
        let (i, min) =
            life.iter().enumerate().fold(
                (0, f64::INFINITY),
                |b, (i, x)| if *x < b.1 { (i, *x) } else { b },
            );
        lives.insert(
            fib.name().to_string(),
            serde_json::json!({"min_life_years": min.is_finite().then_some(min),
                               "arc": arc.get(i)}),
        );
        arrays.set_item(
            format!("damage_{}", fib.name()),
            array(py, &d, vec![d.len()]),
        )?;
        arrays.set_item(
            format!("life_{}", fib.name()),
            array(py, &life, vec![life.len()]),
        )?;
    }
    out.set_item("arrays", arrays)?;
    let storms: Vec<_> = results
        .iter()
        .map(|r| {
            serde_json::json!({"id": r.storm.id, "hs": r.storm.hs, "tp": r.storm.tp,
             "probability": r.storm.probability, "wall_seconds": r.wall_seconds,
             "stopped": r.error})
        })
        .collect();
    let summary = serde_json::json!({"file": study.file, "lives": lives, "storms": storms});
    out.set_item("summary", summary.to_string())?;
    Ok(out)
}

/// Storms in sequence (a sequence file: base scene, storm table, order or random order, calm,
/// fatigue table), each visit from the state the last left, the as-laid visits alongside on the
/// other threads: `{"arrays": {"arc", "trench" (visits × nodes, m), "as_laid_penetration" (m),
/// "life_memory", "life_as_laid" (years, of the first fibre), "strength" (after the last visit)},
/// "summary"}`. In memory: no files, no resume (the command line keeps both).
#[pyfunction]
#[pyo3(signature = (path, jobs = 0))]
fn sequence<'py>(py: Python<'py>, path: PathBuf, jobs: usize) -> PyResult<Bound<'py, PyDict>> {
    use catena::studies::sequence::{run_as_laid, run_visit, Sequence};
    use rayon::prelude::*;
    let seq = Sequence::read(&path).map_err(err)?;
    let n = seq.visits.len();
    // The chain and the as-laid visits side by side share the cores; a chain alone has them all
    // (as `catena sequence`).
    let side_by_side = if seq.as_laid { jobs.max(2) } else { 1 };
    let threads = Some(per_run(side_by_side, usize::MAX));
    let (memory, laid) = on_threads(py, jobs.max(2), || {
        let ks: Vec<usize> = (0..n).collect();
        let (memory, laid) = rayon::join(
            || -> Result<Vec<_>, String> {
                let mut out = Vec::new();
                let mut carry = None;
                for k in 0..n {
                    let (r, next) =
                        run_visit(&seq, k, carry.take(), threads).map_err(|e| e.to_string())?;
                    let stop = next.is_none();
                    out.push(r);
                    if stop {
                        break;
                    }
                    carry = next;
                }
                Ok(out)
            },
            || -> Result<Vec<_>, String> {
                if !seq.as_laid {
                    return Ok(Vec::new());
                }
                ks.par_iter()
                    .map(|&k| run_as_laid(&seq, k, threads).map_err(|e| e.to_string()))
                    .collect()
            },
        );
        Ok((memory?, laid?))
    })?;
    sequence_dict(py, &seq, &memory, &laid)
}

/// A sequence's tasks: JSON `{"visits": [{"index", "storm", "scene_hash"}], "as_laid": bool}`.
/// The visits with memory are a chain (each needs the carry of the one before); the as-laid
/// visits are independent.
#[pyfunction]
fn sequence_tasks(path: PathBuf) -> PyResult<String> {
    let seq = catena::studies::sequence::Sequence::read(&path).map_err(err)?;
    let visits: Vec<_> = seq
        .visits
        .iter()
        .enumerate()
        .map(|(k, (v, _))| {
            serde_json::json!({"index": k, "storm": v.storm.id, "scene_hash": seq.hash_of(k)})
        })
        .collect();
    Ok(serde_json::json!({"visits": visits, "as_laid": seq.as_laid}).to_string())
}

/// One visit with memory, from the carry the previous visit left (`None` for the first: the
/// as-laid state): `(result, carry)` as JSON texts, the carry `None` when the sequence stops here
/// (the visit's run stopped early).
#[pyfunction]
#[pyo3(signature = (path, index, carry = None, threads = 1))]
fn sequence_visit(
    py: Python<'_>,
    path: PathBuf,
    index: usize,
    carry: Option<String>,
    threads: usize,
) -> PyResult<(String, Option<String>)> {
    let seq = catena::studies::sequence::Sequence::read(&path).map_err(err)?;
    let k = task("visit", index, seq.visits.len())?;
    let start: Option<catena_fe::dynamics::Carry> = carry
        .as_deref()
        .map(|t| from_json(&format!("the carry into visit {k}"), t))
        .transpose()?;
    if (k == 0) != start.is_none() {
        return Err(err(format!(
            "visit {k}: {}",
            if k == 0 {
                "the first visit starts as laid (no carry)"
            } else {
                "needs the carry the visit before it left"
            }
        )));
    }
    let threads = run_threads(py, threads);
    let (r, next) = py
        .detach(|| catena::studies::sequence::run_visit(&seq, k, start, threads))
        .map_err(err)?;
    Ok((to_json(&r)?, next.as_ref().map(to_json).transpose()?))
}

/// One visit from the as-laid state: its result as JSON text.
#[pyfunction]
#[pyo3(signature = (path, index, threads = 1))]
fn sequence_as_laid(
    py: Python<'_>,
    path: PathBuf,
    index: usize,
    threads: usize,
) -> PyResult<String> {
    let seq = catena::studies::sequence::Sequence::read(&path).map_err(err)?;
    let k = task("visit", index, seq.visits.len())?;
    let threads = run_threads(py, threads);
    let r = py
        .detach(|| catena::studies::sequence::run_as_laid(&seq, k, threads))
        .map_err(err)?;
    to_json(&r)
}

/// A sequence from its visits' results (JSON texts: the visits with memory in order, as far as
/// they went, and the as-laid visits), the same dictionary as [`sequence`].
#[pyfunction]
fn sequence_merge<'py>(
    py: Python<'py>,
    path: PathBuf,
    memory: Vec<String>,
    as_laid: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    use catena::studies::sequence::VisitResult;
    let seq = catena::studies::sequence::Sequence::read(&path).map_err(err)?;
    let parse = |texts: &[String], what: &str| -> PyResult<Vec<VisitResult>> {
        texts
            .iter()
            .enumerate()
            .map(|(k, t)| {
                let r: VisitResult = from_json(&format!("{what} visit {k}"), t)?;
                if k >= seq.visits.len() || r.visit.index != k || r.scene_hash != seq.hash_of(k) {
                    return Err(err(format!(
                        "{}: the {what} result given for visit {k} is of another visit or an \
                         older scene",
                        seq.file
                    )));
                }
                Ok(r)
            })
            .collect()
    };
    let memory = parse(&memory, "memory")?;
    let laid = parse(&as_laid, "as-laid")?;
    sequence_dict(py, &seq, &memory, &laid)
}

fn sequence_dict<'py>(
    py: Python<'py>,
    seq: &catena::studies::sequence::Sequence,
    memory: &[catena::studies::sequence::VisitResult],
    laid: &[catena::studies::sequence::VisitResult],
) -> PyResult<Bound<'py, PyDict>> {
    use catena::studies::sequence::annual_damage;
    let st = catena::run::statics::solve(seq.base.clone()).map_err(err)?;
    let arc = st.model.arc.clone();
    let fibre = memory
        .first()
        .and_then(|r| r.damage.first())
        .map(|(f, _)| f.clone())
        .unwrap_or_else(|| "outer".into());
    let done = memory.iter().take_while(|r| r.error.is_none()).count();
    let lives = |d: Vec<f64>| -> Vec<f64> { d.iter().map(|x| 1.0 / x).collect() };
    let life_memory = lives(annual_damage(&memory[..done], &fibre));
    let life_laid = lives(annual_damage(&laid[..done.min(laid.len())], &fibre));
    let trench: Vec<f64> = memory[..done]
        .iter()
        .flat_map(|r| r.trench.iter().copied())
        .collect();
    let strength = memory[..done]
        .last()
        .map(|r| r.strength.clone())
        .unwrap_or_default();
    let out = PyDict::new(py);
    let arrays = PyDict::new(py);
    arrays.set_item("arc", array(py, &arc, vec![arc.len()]))?;
    arrays.set_item("trench", array(py, &trench, vec![done, arc.len()]))?;
    arrays.set_item(
        "as_laid_penetration",
        array(py, &st.results.penetration, vec![arc.len()]),
    )?;
    arrays.set_item(
        "life_memory",
        array(py, &life_memory, vec![life_memory.len()]),
    )?;
    arrays.set_item("life_as_laid", array(py, &life_laid, vec![life_laid.len()]))?;
    arrays.set_item("strength", array(py, &strength, vec![strength.len()]))?;
    out.set_item("arrays", arrays)?;
    let visits: Vec<_> = memory
        .iter()
        .map(|r| {
            serde_json::json!({"storm": r.visit.storm.id, "seed": r.visit.storm.seed,
             "weight": r.visit.weight, "wall_seconds": r.wall_seconds, "stopped": r.error})
        })
        .collect();
    let summary = serde_json::json!({"file": seq.file, "fibre": fibre, "visits": visits,
        "visits_done": done, "coverage": seq.coverage, "calm_s": seq.calm});
    out.set_item("summary", summary.to_string())?;
    Ok(out)
}

/// A parameter sweep (a plan file), every run in parallel: the merged table as JSON text, one row
/// per parameter point (`values`, `min_life_years`, `min_life_arc`, `tdz_moment_range`,
/// `max_penetration`, `failed`).
#[pyfunction]
#[pyo3(signature = (path, jobs = 0))]
fn sweep(py: Python<'_>, path: PathBuf, jobs: usize) -> PyResult<String> {
    use rayon::prelude::*;
    let plan = catena::studies::sweep::Plan::read(&path).map_err(err)?;
    let runs = plan.runs();
    let threads = Some(per_run(jobs, runs.len()));
    let results = on_threads(py, jobs, || {
        Ok(runs
            .par_iter()
            .map(|r| Some(catena::studies::sweep::run_one(r, threads)))
            .collect::<Vec<_>>())
    })?;
    sweep_table(&plan, &runs, &results)
}

/// A sweep's tasks, one per run (a parameter point, times each storm for a study base): JSON
/// `[{"index", "id", "point", "scene_hash"}]`.
#[pyfunction]
fn sweep_tasks(path: PathBuf) -> PyResult<String> {
    let plan = catena::studies::sweep::Plan::read(&path).map_err(err)?;
    let tasks: Vec<_> = plan
        .runs()
        .iter()
        .map(|r| {
            serde_json::json!({"index": r.index, "id": r.id, "point": r.point,
                               "scene_hash": catena::studies::sweep::run_hash(r)})
        })
        .collect();
    Ok(serde_json::Value::Array(tasks).to_string())
}

/// One run of a sweep, with the interpreter released: its result as JSON text (a run that fails
/// says why in its `error`, as on the command line).
#[pyfunction]
#[pyo3(signature = (path, index, threads = 1))]
fn sweep_run(py: Python<'_>, path: PathBuf, index: usize, threads: usize) -> PyResult<String> {
    let plan = catena::studies::sweep::Plan::read(&path).map_err(err)?;
    let runs = plan.runs();
    let spec = &runs[task("run", index, runs.len())?];
    let threads = run_threads(py, threads);
    to_json(&py.detach(|| catena::studies::sweep::run_one(spec, threads)))
}

/// A sweep's table from its runs' results (JSON texts, or `None` for a run without one, which
/// marks its point failed), the same as [`sweep`].
#[pyfunction]
fn sweep_merge(path: PathBuf, results: Vec<Option<String>>) -> PyResult<String> {
    let plan = catena::studies::sweep::Plan::read(&path).map_err(err)?;
    let runs = plan.runs();
    if results.len() != runs.len() {
        return Err(err(format!(
            "{}: {} run results for {} runs",
            plan.file,
            results.len(),
            runs.len()
        )));
    }
    let results: Vec<Option<catena::studies::sweep::RunResult>> = results
        .iter()
        .zip(&runs)
        .map(|(t, spec)| {
            t.as_deref()
                .map(|t| {
                    let r: catena::studies::sweep::RunResult =
                        from_json(&format!("run {}", spec.id), t)?;
                    if r.id != spec.id || r.scene_hash != catena::studies::sweep::run_hash(spec) {
                        return Err(err(format!(
                            "{}: the result given for run {} is of another run or an older scene",
                            plan.file, spec.id
                        )));
                    }
                    Ok(r)
                })
                .transpose()
        })
        .collect::<PyResult<_>>()?;
    sweep_table(&plan, &runs, &results)
}

fn sweep_table(
    plan: &catena::studies::sweep::Plan,
    runs: &[catena::studies::sweep::RunSpec],
    results: &[Option<catena::studies::sweep::RunResult>],
) -> PyResult<String> {
    let points = catena::studies::sweep::merge(plan, runs, results);
    let names: Vec<String> = plan.parameters.iter().map(|p| p.key.clone()).collect();
    let rows: Vec<_> = points
        .iter()
        .map(|p| {
            let values: serde_json::Map<String, serde_json::Value> = names
                .iter()
                .cloned()
                .zip(
                    p.values
                        .iter()
                        .map(|v| serde_json::to_value(v).unwrap_or(serde_json::Value::Null)),
                )
                .collect();
            serde_json::json!({
                "values": values,
                "min_life_years": p.min_life_years.is_finite().then_some(p.min_life_years),
                "min_life_arc": p.min_life_arc.is_finite().then_some(p.min_life_arc),
                "tdz_moment_range": p.tdz_moment_range.is_finite().then_some(p.tdz_moment_range),
                "max_penetration": p.max_penetration.is_finite().then_some(p.max_penetration),
                "failed": p.failed,
            })
        })
        .collect();
    Ok(serde_json::Value::Array(rows).to_string())
}

/// The animated touchdown zone (`catena animate`) from a run's arrays (`{name: (bytes, shape)}`:
/// `arc`, `time`, `x`, `z`, `penetration`, `seabed_force`, `bending_moment`, `top_x`, `top_z`,
/// `outer_diameter`): `{"frames", "bytes", "seconds"}` as JSON text; `follow`: the touchdown
/// zone follows the touchdown (a lay's frames).
#[pyfunction]
#[pyo3(signature = (arrays, out, frames, fps, colour, follow = false))]
fn animate_arrays(
    py: Python<'_>,
    arrays: &Bound<'_, PyDict>,
    out: PathBuf,
    frames: usize,
    fps: f64,
    colour: &str,
    follow: bool,
) -> PyResult<String> {
    let get = |name: &str| -> PyResult<Vec<f64>> {
        let item = arrays
            .get_item(name)?
            .ok_or_else(|| err(format!("animate: the results have no `{name}`")))?;
        let (bytes, _shape): (Vec<u8>, Vec<usize>) = item.extract()?;
        Ok(bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
            .collect())
    };
    let colour = catena_io::animate::Colour::parse(colour).ok_or_else(|| {
        err(format!(
            "animate: colour: expected \"penetration\" or \"seabed_force\", got {colour:?}"
        ))
    })?;
    if frames < 2 || !(fps.is_finite() && fps > 0.0 && fps <= 50.0) {
        return Err(err(format!(
            "animate: expected frames >= 2 and 0 < fps <= 50, got {frames} and {fps}"
        )));
    }
    let mut rec =
        catena_io::animate::Records::from_named(|name| get(name), |_| get("outer_diameter"))?;
    rec.follow_touchdown = follow;
    let opts = catena_io::animate::Options {
        frames,
        fps,
        colour,
        ..Default::default()
    };
    let r = py
        .detach(|| catena_io::animate::animate(&out, &rec, &opts))
        .map_err(err)?;
    Ok(serde_json::json!({"frames": r.frames, "bytes": r.bytes, "seconds": r.seconds}).to_string())
}

/// Each node's outer diameter, m, from a scene's text and its case file's path (the `scene` and
/// `case` attributes of `results.h5`), as the command line's `catena animate` finds them.
#[pyfunction]
fn node_diameters(text: &str, case: &str, nodes: usize) -> PyResult<Vec<f64>> {
    catena_io::animate::diameters(text, case, nodes)
        .ok_or_else(|| err("the scene gives no pipe diameter (line.od or line types)"))
}

/// The version of the catena library inside.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

#[pymodule]
fn _catena(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_function(wrap_pyfunction!(statics, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(fatigue_study, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(sequence, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    m.add_function(wrap_pyfunction!(study_tasks, m)?)?;
    m.add_function(wrap_pyfunction!(study_storm, m)?)?;
    m.add_function(wrap_pyfunction!(study_merge, m)?)?;
    m.add_function(wrap_pyfunction!(sequence_tasks, m)?)?;
    m.add_function(wrap_pyfunction!(sequence_visit, m)?)?;
    m.add_function(wrap_pyfunction!(sequence_as_laid, m)?)?;
    m.add_function(wrap_pyfunction!(sequence_merge, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_tasks, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_run, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_merge, m)?)?;
    m.add_function(wrap_pyfunction!(animate_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(node_diameters, m)?)?;
    m.add("CatenaError", m.py().get_type::<CatenaError>())?;
    Ok(())
}
