//! The fatigue study (`catena fatigue STUDY.toml`): a base scene run once per storm of a storm table,
//! each storm a full dynamic run with its own JONSWAP sea and the fatigue observer, then the annual
//! damage and the life along the arc.
//!
//! **Study file** (every key in `docs/study.md`):
//!
//! ```toml
//! [study]
//! scene = "scr1000-linear-k100.toml"   # the base scene (with [waves], [vessel]), relative to this file
//! storms = "gom-30-storms.toml"        # [[storm]] id, hs, tp, probability; optional gamma, seed, duration
//! record = 10800.0                     # s counted per storm, after the transient
//! transient = 200.0                    # s discarded: the ramp and the settling
//! [fatigue]                            # the same table a scene may hold
//! sn_curve = "dnv-e-seawater-cp"
//! scf = 1.2
//! ```
//!
//! Each storm's scene is the base scene edited by key path: `waves.hs`, `waves.tp`, `waves.gamma`
//! (when the storm gives it), `waves.seed` (the storm's `seed`, else its id), `dynamic.duration`
//! (transient + record, or the storm's own duration), `dynamic.envelope_start` and `fatigue.start`
//! (the transient), and the study's `[fatigue]` table.
//!
//! **Bookkeeping.** Storm i, counted over `T_i` seconds, gives the damage `D_i` at every node and
//! fibre; with its probability `p_i` (fraction of the year) the annual damage is
//!
//! ```text
//! D = Σ_i p_i · D_i · Y / T_i,     Y = 365.25·86400 s,     life = 1/D years,
//! ```
//!
//! and storm i's share at a point is `p_i D_i Y/T_i / D`. With a design factor the life divided by
//! it is reported as well.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::checks::fatigue::stress::Fibre;
use crate::error::AppError;
use crate::run::{self, RunOptions};
use crate::scene::edit::Edit;
use crate::scene::riser::RiserScene;
use crate::scene::{invalid, parse, DirResolver};

/// Seconds in a year.
pub const YEAR: f64 = 365.25 * 86400.0;

/// `[study]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct StudyTable {
    pub scene: String,
    pub storms: String,
    pub record: f64,
    pub transient: f64,
}

/// A study file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct StudyFile {
    pub study: StudyTable,
    pub fatigue: toml::Table,
}

/// One storm of the table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Storm {
    /// Its id.
    pub id: i64,
    /// Significant wave height, m.
    pub hs: f64,
    /// Peak period, s.
    pub tp: f64,
    /// Peak enhancement (the DNV rule when absent).
    pub gamma: Option<f64>,
    /// Fraction of the year.
    pub probability: f64,
    /// Seed (the id when absent).
    pub seed: Option<u64>,
    /// Counted record length for this storm, s (the study's `record` when absent).
    pub duration: Option<f64>,
}

/// A storm table file: `[[storm]]` rows.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct StormsFile {
    pub(crate) storm: Vec<Storm>,
}

/// A study, read and checked: the storms' scenes built.
#[derive(Debug, Clone)]
pub struct Study {
    /// The study file.
    pub file: String,
    /// The base scene.
    pub base: RiserScene,
    /// The storms, in the table's order, each with its scene.
    pub storms: Vec<(Storm, RiserScene)>,
    /// The counted record per storm, s.
    pub record: f64,
    /// The discarded transient, s.
    pub transient: f64,
}

/// One storm's result (written as JSON, one file per storm, so a study resumes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StormResult {
    /// The storm.
    pub storm: Storm,
    /// The hash of its scene's text (a changed scene is run again).
    pub scene_hash: String,
    /// Seconds counted.
    pub counted_seconds: f64,
    /// Per fibre (by name), the damage at every node over the counted record.
    pub damage: Vec<(String, Vec<f64>)>,
    /// Wall time of the run, s.
    pub wall_seconds: f64,
    /// Why the run stopped early, if it did (its damage is then not used).
    pub error: Option<String>,
}

impl Study {
    /// Reads a study file and builds every storm's scene.
    pub fn read(path: &Path) -> Result<Self, AppError> {
        let file = path.display().to_string();
        let text = crate::scene::read_text(path)?;
        let raw: StudyFile = parse(&file, &text)?;
        let dir = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let s = &raw.study;
        for (k, v) in [("study.record", s.record), ("study.transient", s.transient)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(invalid(&file, k, "a time >= 0 s").into());
            }
        }
        if s.record <= 0.0 {
            return Err(invalid(&file, "study.record", "a counted record > 0 s").into());
        }
        let (scene_path, base) = read_base(&file, &dir, &s.scene)?;
        let (sfile, table): (String, StormsFile) = read_storm_table(&file, &dir, &s.storms)?;
        if table.storm.is_empty() {
            return Err(invalid(&file, "study.storms", "at least one [[storm]]").into());
        }
        let files = DirResolver::beside(&scene_path);
        let mut storms = Vec::new();
        for (i, st) in table.storm.iter().enumerate() {
            let key = |k: &str| format!("storm[{i}].{k}");
            check_sea(&sfile, i, st.hs, st.tp)?;
            if !(st.probability.is_finite() && (0.0..=1.0).contains(&st.probability)) {
                return Err(invalid(
                    &sfile,
                    key("probability"),
                    "a fraction of the year in [0, 1]",
                )
                .into());
            }
            if storms
                .iter()
                .any(|(o, _): &(Storm, RiserScene)| o.id == st.id)
            {
                return Err(invalid(&sfile, key("id"), "a unique id").into());
            }
            let record = st.duration.unwrap_or(s.record);
            if !(record.is_finite() && record > 0.0) {
                return Err(invalid(&sfile, key("duration"), "a counted record > 0 s").into());
            }
            let sea = Sea {
                hs: st.hs,
                tp: st.tp,
                gamma: st.gamma,
                seed: st.seed.map_or(st.id, |x| x as i64),
            };
            let mut edits = sea.edits(s.transient, record);
            edits.push(Edit::set(
                "fatigue",
                toml::Value::Table(raw.fatigue.clone()),
            ));
            edits.push(Edit::set("fatigue.start", s.transient));
            // The [fatigue] table is the study's own: its errors name the study's file.
            let scene = base
                .edited(&edits, &files)
                .map_err(|e| e.in_table_of("fatigue", &file))?;
            storms.push((st.clone(), scene));
        }
        Ok(Self {
            file,
            base,
            storms,
            record: s.record,
            transient: s.transient,
        })
    }

    /// The fibres the study counts.
    pub fn fibres(&self) -> Vec<Fibre> {
        self.storms
            .first()
            .and_then(|(_, s)| s.dynamic.as_ref())
            .and_then(|d| d.fatigue.as_ref())
            .map(|f| f.fibres.clone())
            .unwrap_or_default()
    }
}

/// A storm's sea: what a study sets in its base scene's `[waves]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sea {
    /// Significant wave height, m.
    pub hs: f64,
    /// Peak period, s.
    pub tp: f64,
    /// Peak enhancement (the DNV rule when `None`).
    pub gamma: Option<f64>,
    /// Seed.
    pub seed: i64,
}

impl Sea {
    /// The edits of a storm's scene: `waves.kind = "jonswap"`, `hs`, `tp`, `seed`, `gamma` (or
    /// removed), `dynamic.duration = transient + record`, `dynamic.envelope_start = transient`.
    pub fn edits(&self, transient: f64, record: f64) -> Vec<Edit> {
        vec![
            Edit::set("waves.kind", "jonswap"),
            Edit::set("waves.hs", self.hs),
            Edit::set("waves.tp", self.tp),
            Edit::set("waves.seed", self.seed),
            Edit::set("dynamic.duration", transient + record),
            Edit::set("dynamic.envelope_start", transient),
            match self.gamma {
                Some(g) => Edit::set("waves.gamma", g),
                None => Edit::remove("waves.gamma"),
            },
        ]
    }
}

/// A study's base scene (`study.scene`, relative to the study file's directory `dir`): read, and
/// checked to be a dynamic scene with `[waves]`. Returns its path too.
pub(crate) fn read_base(
    file: &str,
    dir: &Path,
    scene: &str,
) -> Result<(PathBuf, RiserScene), AppError> {
    read_base_as(file, "study", dir, scene)
}

/// [`read_base`] for a file whose table is `table` (`study`, `sequence`): errors name
/// `table.scene`.
pub(crate) fn read_base_as(
    file: &str,
    table: &str,
    dir: &Path,
    scene: &str,
) -> Result<(PathBuf, RiserScene), AppError> {
    let key = format!("{table}.scene");
    let scene_path = dir.join(scene);
    let base = crate::run::statics::read_scene(&scene_path).map_err(|e| match e {
        AppError::Io { .. } => invalid(file, &key, format!("a readable scene file ({e})")).into(),
        other => other,
    })?;
    let dynamic = base
        .dynamic
        .as_ref()
        .ok_or_else(|| AppError::from(invalid(file, &key, "a scene with a [dynamic] table")))?;
    if dynamic.environment.waves.is_none() || base.doc.get("waves").is_none() {
        return Err(invalid(file, &key, "a scene with a [waves] table (jonswap)").into());
    }
    Ok((scene_path, base))
}

/// A study's storm table (`study.storms`, relative to `dir`), parsed; with its path as a name for
/// errors. At least one storm is checked by the caller.
pub(crate) fn read_storm_table<T: serde::de::DeserializeOwned>(
    file: &str,
    dir: &Path,
    storms: &str,
) -> Result<(String, T), AppError> {
    read_storm_table_as(file, "study", dir, storms)
}

/// [`read_storm_table`] for a file whose table is `table`: errors name `table.storms`.
pub(crate) fn read_storm_table_as<T: serde::de::DeserializeOwned>(
    file: &str,
    table: &str,
    dir: &Path,
    storms: &str,
) -> Result<(String, T), AppError> {
    let key = format!("{table}.storms");
    let storms_path = dir.join(storms);
    let text = std::fs::read_to_string(&storms_path).map_err(|e| {
        AppError::from(invalid(
            file,
            &key,
            format!("a readable storm table ({}: {e})", storms_path.display()),
        ))
    })?;
    let sfile = storms_path.display().to_string();
    let table = parse(&sfile, &text)?;
    Ok((sfile, table))
}

/// Storm `i` of the table `sfile`: a wave height and a peak period > 0.
pub(crate) fn check_sea(sfile: &str, i: usize, hs: f64, tp: f64) -> Result<(), AppError> {
    if !(hs.is_finite() && hs > 0.0) {
        return Err(invalid(
            sfile,
            format!("storm[{i}].hs"),
            "a significant wave height > 0 m",
        )
        .into());
    }
    if !(tp.is_finite() && tp > 0.0) {
        return Err(invalid(sfile, format!("storm[{i}].tp"), "a peak period > 0 s").into());
    }
    Ok(())
}

/// Runs one storm, keeping `threads` threads busy (`None`: the machine's cores; a study running
/// storms side by side passes [`crate::studies::schedule::threads_per_run`]).
pub fn run_storm(
    storm: &Storm,
    scene: &RiserScene,
    threads: Option<usize>,
) -> Result<StormResult, AppError> {
    let t0 = std::time::Instant::now();
    let hash = crate::scene::text_hash(&scene.text);
    let opts = RunOptions::with_threads(threads);
    let r = run::simulate(scene.clone(), &mut [], opts)?;
    let damage = damage_of(&r, scene)?;
    Ok(StormResult {
        storm: storm.clone(),
        scene_hash: hash,
        counted_seconds: r.fatigue.as_ref().map_or(0.0, |f| f.counted_seconds()),
        damage,
        wall_seconds: t0.elapsed().as_secs_f64(),
        error: r.stop.as_ref().map(ToString::to_string),
    })
}

/// A run's damage per fibre over its counted record (an error if its scene has no `[fatigue]`).
pub(crate) fn damage_of(
    r: &run::DynamicRun,
    scene: &RiserScene,
) -> Result<Vec<(String, Vec<f64>)>, AppError> {
    let f = r.fatigue.as_ref().ok_or_else(|| AppError::Run {
        file: scene.file.clone(),
        message: "the run's scene has no [fatigue] table".into(),
    })?;
    Ok(f.spec
        .fibres
        .iter()
        .filter_map(|fib| f.damage_of(*fib).map(|d| (fib.name().to_string(), d)))
        .collect())
}

/// Annual damage along the arc for one fibre: `D = Σ p_i D_i Y/T_i` over the storms that completed.
pub fn annual_damage(results: &[StormResult], fibre: &str) -> Vec<f64> {
    weighted_damage(
        results
            .iter()
            .filter(|r| r.error.is_none() && r.counted_seconds > 0.0)
            .map(|r| {
                (
                    r.damage.as_slice(),
                    r.storm.probability * YEAR / r.counted_seconds,
                )
            }),
        fibre,
    )
}

/// `Σ w·D` along the arc for one fibre over `(damage per fibre, weight)` pairs (a pair without the
/// fibre adds nothing): the sum behind a study's and a sequence's annual damage.
pub(crate) fn weighted_damage<'a>(
    items: impl Iterator<Item = (&'a [(String, Vec<f64>)], f64)>,
    fibre: &str,
) -> Vec<f64> {
    let mut total: Vec<f64> = Vec::new();
    for (damage, w) in items {
        if let Some((_, d)) = damage.iter().find(|(n, _)| n == fibre) {
            if total.is_empty() {
                total = vec![0.0; d.len()];
            }
            for (t, x) in total.iter_mut().zip(d) {
                *t += w * x;
            }
        }
    }
    total
}

/// Each storm's share of the annual damage at node `i` of a fibre, `(id, share)`.
pub fn shares(results: &[StormResult], fibre: &str, i: usize) -> Vec<(i64, f64)> {
    let total = annual_damage(results, fibre).get(i).copied().unwrap_or(0.0);
    results
        .iter()
        .map(|r| {
            let d = r
                .damage
                .iter()
                .find(|(n, _)| n == fibre)
                .and_then(|(_, d)| d.get(i))
                .copied()
                .unwrap_or(0.0);
            let part = if r.error.is_none() && r.counted_seconds > 0.0 {
                r.storm.probability * d * YEAR / r.counted_seconds
            } else {
                0.0
            };
            (r.storm.id, if total > 0.0 { part / total } else { 0.0 })
        })
        .collect()
}
