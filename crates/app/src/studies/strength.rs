//! The strength study (`catena strength STUDY.toml`): a base scene with a `[design_check]` run for
//! each design storm of a storm table and each of its seeds (realisations of the same sea state),
//! then, per storm, the largest utilisation along the line over the seeds and the extremes across
//! the seeds (a Gumbel fit of one maximum per seed, [`crate::checks::extremes::across_realisations`]).
//!
//! **Study file** (every key in `docs/study.md`):
//!
//! ```toml
//! [study]
//! scene = "../design-100yr-linear.toml"  # the base scene ([waves], [design_check]; [extremes] optional)
//! storms = "design-storms.toml"          # [[storm]] id, hs, tp; optional gamma, seeds, duration
//! record = 10800.0                       # s checked per run, after the transient
//! transient = 200.0                      # s discarded: the ramp and the settling
//! # [design_check] and [extremes] here replace the scene's
//! ```
//!
//! Each run's scene is the base scene edited by key path as the fatigue study's storms
//! ([`crate::studies::fatigue_study`]): `waves.hs`, `waves.tp`, `waves.gamma`, `waves.seed` (the run's seed),
//! `dynamic.duration` (transient + record), `dynamic.envelope_start`, `design_check.start` and
//! `extremes.start` (the transient), and the study's tables.
//!
//! **Across seeds.** Storm i run with seeds `s_1 … s_m` (each a record of `T` s) gives each seed's
//! largest utilisation `u_j` (anywhere on the line) and each channel's sample extreme. With three
//! seeds or more, their Gumbel fit gives the most probable largest of a record of `T` and its
//! quantile (`n = 1`): the expected extreme of the storm, not what one seed happened to give, and
//! its spread.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::checks::extremes::{across_realisations, Extremes, Gumbel, Settings, Tail};
use crate::error::AppError;
use crate::run::observers::design::DesignCheck;
use crate::run::observers::extremes::ExtremesObserver;
use crate::run::{self, RunOptions};
use crate::scene::edit::Edit;
use crate::scene::riser::RiserScene;
use crate::scene::{invalid, parse, DirResolver};
use crate::studies::fatigue_study::{check_sea, read_base, read_storm_table, Sea};

/// `[study]` of a strength study.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct StrengthTable {
    pub scene: String,
    pub storms: String,
    pub record: f64,
    pub transient: f64,
}

/// A strength study file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct StrengthFile {
    pub study: StrengthTable,
    pub design_check: Option<toml::Table>,
    pub extremes: Option<toml::Table>,
}

/// A design storm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignStorm {
    /// Its id.
    pub id: i64,
    /// Significant wave height, m.
    pub hs: f64,
    /// Peak period, s.
    pub tp: f64,
    /// Peak enhancement (the DNV rule when absent).
    pub gamma: Option<f64>,
    /// The seeds of its realisations (the id alone when absent).
    pub seeds: Option<Vec<u64>>,
    /// Record length for this storm, s (the study's `record` when absent).
    pub duration: Option<f64>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct DesignStormsFile {
    storm: Vec<DesignStorm>,
}

/// One run of the study: a storm and one of its seeds, with its scene.
#[derive(Debug, Clone)]
pub struct StrengthRun {
    /// The storm.
    pub storm: DesignStorm,
    /// The seed.
    pub seed: u64,
    /// The run's record, s.
    pub record: f64,
    /// Its scene.
    pub scene: RiserScene,
}

/// A strength study, read and checked: every run's scene built.
#[derive(Debug, Clone)]
pub struct StrengthStudy {
    /// The study file.
    pub file: String,
    /// The base scene.
    pub base: RiserScene,
    /// The runs, storm by storm, seed by seed.
    pub runs: Vec<StrengthRun>,
    /// The discarded transient, s.
    pub transient: f64,
}

/// One run's result (one JSON file per run, so a study resumes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    /// The storm.
    pub storm: DesignStorm,
    /// The seed.
    pub seed: u64,
    /// The hash of its scene's text (a changed scene is run again).
    pub scene_hash: String,
    /// Seconds checked.
    pub record: f64,
    /// Each node's largest utilisation.
    pub utilisation_max: Vec<f64>,
    /// Each node's least effective tension, N.
    pub least_tension: Vec<f64>,
    /// The largest utilisation: `(node, value, time, term)`.
    pub worst: Option<(usize, f64, f64, String)>,
    /// Compression beyond the element Euler load: `(arc, least tension, time)` of each node.
    pub compression: Vec<(f64, f64, f64)>,
    /// The run's extremes (its `[extremes]`), if any.
    pub extremes: Vec<Extremes>,
    /// Wall time, s.
    pub wall_seconds: f64,
    /// Why the run stopped early, if it did (its results are then not used).
    pub error: Option<String>,
}

impl StrengthStudy {
    /// Reads a strength study file and builds every run's scene.
    pub fn read(path: &Path) -> Result<Self, AppError> {
        let file = path.display().to_string();
        let text = crate::scene::read_text(path)?;
        let raw: StrengthFile = parse(&file, &text)?;
        let dir = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let s = &raw.study;
        if !(s.transient.is_finite() && s.transient >= 0.0) {
            return Err(invalid(&file, "study.transient", "a time >= 0 s").into());
        }
        if !(s.record.is_finite() && s.record > 0.0) {
            return Err(invalid(&file, "study.record", "a checked record > 0 s").into());
        }
        let (scene_path, base) = read_base(&file, &dir, &s.scene)?;
        if raw.design_check.is_none() && base.doc.get("design_check").is_none() {
            return Err(invalid(
                &file,
                "design_check",
                "a [design_check] table here or in the scene",
            )
            .into());
        }
        let (sfile, table): (String, DesignStormsFile) = read_storm_table(&file, &dir, &s.storms)?;
        if table.storm.is_empty() {
            return Err(invalid(&file, "study.storms", "at least one [[storm]]").into());
        }
        let files = DirResolver::beside(&scene_path);
        let mut runs = Vec::new();
        for (i, st) in table.storm.iter().enumerate() {
            let key = |k: &str| format!("storm[{i}].{k}");
            check_sea(&sfile, i, st.hs, st.tp)?;
            if table.storm[..i].iter().any(|o| o.id == st.id) {
                return Err(invalid(&sfile, key("id"), "a unique id").into());
            }
            let record = st.duration.unwrap_or(s.record);
            if !(record.is_finite() && record > 0.0) {
                return Err(invalid(&sfile, key("duration"), "a record > 0 s").into());
            }
            let seeds = st.seeds.clone().unwrap_or_else(|| vec![st.id as u64]);
            if seeds.is_empty() {
                return Err(invalid(&sfile, key("seeds"), "at least one seed").into());
            }
            for (j, sd) in seeds.iter().enumerate() {
                if seeds[..j].contains(sd) {
                    return Err(invalid(
                        &sfile,
                        format!("storm[{i}].seeds[{j}]"),
                        "seeds that differ (the same seed is the same sea)",
                    )
                    .into());
                }
            }
            for seed in seeds {
                let sea = Sea {
                    hs: st.hs,
                    tp: st.tp,
                    gamma: st.gamma,
                    seed: seed as i64,
                };
                let mut edits = sea.edits(s.transient, record);
                if let Some(t) = &raw.design_check {
                    edits.push(Edit::set("design_check", toml::Value::Table(t.clone())));
                }
                edits.push(Edit::set("design_check.start", s.transient));
                if let Some(t) = &raw.extremes {
                    edits.push(Edit::set("extremes", toml::Value::Table(t.clone())));
                }
                if raw.extremes.is_some() || base.doc.get("extremes").is_some() {
                    edits.push(Edit::set("extremes.start", s.transient));
                }
                let scene = base.edited(&edits, &files)?;
                runs.push(StrengthRun {
                    storm: st.clone(),
                    seed,
                    record,
                    scene,
                });
            }
        }
        Ok(Self {
            file,
            base,
            runs,
            transient: s.transient,
        })
    }
}

/// Runs one storm and seed, keeping `threads` threads busy (`None`: the machine's cores).
pub fn run_one(run: &StrengthRun, threads: Option<usize>) -> Result<RunResult, AppError> {
    let t0 = std::time::Instant::now();
    let hash = crate::scene::text_hash(&run.scene.text);
    let opts = RunOptions::with_threads(threads);
    let r = run::simulate(run.scene.clone(), &mut [], opts)?;
    let d = r.output::<DesignCheck>().ok_or_else(|| AppError::Run {
        file: run.scene.file.clone(),
        message: "the run's scene has no [design_check] table".into(),
    })?;
    let worst = d
        .worst()
        .map(|(i, u)| (i, u, d.time_of_max[i], d.term_of_max[i].name().to_string()));
    Ok(RunResult {
        storm: run.storm.clone(),
        seed: run.seed,
        scene_hash: hash,
        record: run.record,
        utilisation_max: d.max.clone(),
        least_tension: d.least_tension.clone(),
        worst,
        compression: d
            .compression()
            .iter()
            .map(|c| (c.arc, c.least_tension, c.time))
            .collect(),
        extremes: r
            .output::<ExtremesObserver>()
            .map(|x| x.results.clone())
            .unwrap_or_default(),
        wall_seconds: t0.elapsed().as_secs_f64(),
        error: r.stop.as_ref().map(ToString::to_string),
    })
}

/// One channel's extremes across the seeds of a storm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AcrossSeeds {
    /// The channel (`utilisation_max` for the design check's largest anywhere).
    pub channel: String,
    /// Its design end.
    pub tail: Tail,
    /// Each seed's extreme over its record.
    pub per_seed: Vec<f64>,
    /// Their mean and standard deviation.
    pub mean: f64,
    /// Standard deviation over the seeds.
    pub std_dev: f64,
    /// The Gumbel fit across the seeds (three or more), the most probable extreme of one record
    /// and the quantile.
    pub gumbel: Option<(Gumbel, [f64; 2])>,
    /// Each seed's most probable extreme from its own record (Weibull of peaks, when fitted),
    /// for comparison.
    pub per_seed_weibull: Vec<Option<f64>>,
}

/// A storm's results over its seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StormSummary {
    /// The storm.
    pub storm: DesignStorm,
    /// The seeds that completed.
    pub seeds: Vec<u64>,
    /// The record of each run, s.
    pub record: f64,
    /// Each node's largest utilisation over every seed.
    pub utilisation_envelope: Vec<f64>,
    /// Each node's mean over the seeds of its largest utilisation.
    pub utilisation_mean: Vec<f64>,
    /// The largest utilisation, then every channel of the runs' `[extremes]`, across the seeds.
    pub across_seeds: Vec<AcrossSeeds>,
}

/// The storms' summaries (completed runs only), in the order of the table; `quantile` for the
/// Gumbel fits across seeds.
pub fn summarise(results: &[RunResult], quantile: f64) -> Vec<StormSummary> {
    let mut out: Vec<StormSummary> = Vec::new();
    for r in results.iter().filter(|r| r.error.is_none()) {
        let k = match out.iter().position(|s| s.storm.id == r.storm.id) {
            Some(k) => k,
            None => {
                out.push(StormSummary {
                    storm: r.storm.clone(),
                    seeds: Vec::new(),
                    record: r.record,
                    utilisation_envelope: vec![0.0; r.utilisation_max.len()],
                    utilisation_mean: vec![0.0; r.utilisation_max.len()],
                    across_seeds: Vec::new(),
                });
                out.len() - 1
            }
        };
        let s = &mut out[k];
        s.seeds.push(r.seed);
        for (e, u) in s.utilisation_envelope.iter_mut().zip(&r.utilisation_max) {
            *e = e.max(*u);
        }
        for (m, u) in s.utilisation_mean.iter_mut().zip(&r.utilisation_max) {
            *m += u;
        }
    }
    for s in &mut out {
        let n = s.seeds.len() as f64;
        for m in &mut s.utilisation_mean {
            *m /= n;
        }
        let runs: Vec<&RunResult> = results
            .iter()
            .filter(|r| r.error.is_none() && r.storm.id == s.storm.id)
            .collect();
        let settings = Settings {
            target: s.record,
            quantile,
            block: s.record,
        };
        // (channel, tail, each seed's extreme, each seed's own Weibull estimate)
        type PerSeed = (String, Tail, Vec<f64>, Vec<Option<f64>>);
        let mut channels: Vec<PerSeed> = vec![(
            "utilisation_max".into(),
            Tail::Max,
            runs.iter()
                .map(|r| r.worst.as_ref().map_or(0.0, |w| w.1))
                .collect(),
            vec![None; runs.len()],
        )];
        if let Some(first) = runs.first() {
            for e in &first.extremes {
                let per: Vec<(f64, Option<f64>)> = runs
                    .iter()
                    .filter_map(|r| r.extremes.iter().find(|x| x.channel == e.channel))
                    .map(|x| (x.sample_extreme, x.weibull.map(|w| w.1[0])))
                    .collect();
                if per.len() == runs.len() {
                    channels.push((
                        e.channel.clone(),
                        e.tail,
                        per.iter().map(|p| p.0).collect(),
                        per.iter().map(|p| p.1).collect(),
                    ));
                }
            }
        }
        for (channel, tail, per_seed, per_seed_weibull) in channels {
            let m = per_seed.len() as f64;
            let mean = per_seed.iter().sum::<f64>() / m;
            let sd = (per_seed.iter().map(|v| (v - mean).powi(2)).sum::<f64>()
                / (m - 1.0).max(1.0))
            .sqrt();
            s.across_seeds.push(AcrossSeeds {
                gumbel: across_realisations(&per_seed, tail, s.record, &settings),
                channel,
                tail,
                per_seed,
                mean,
                std_dev: sd,
                per_seed_weibull,
            });
        }
    }
    out
}
