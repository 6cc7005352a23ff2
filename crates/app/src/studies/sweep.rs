//! Parameter sweeps: a plan varies key paths of a base scene or fatigue study, and expands into a
//! deterministic, sorted list of independent runs (parameter point × storm), each of which writes
//! its own result; a merge reads the results only.
//!
//! **Plan** (`docs/sweep.md`):
//!
//! ```toml
//! [sweep]
//! base = "study-linear.toml"   # a fatigue study ([study]) or a scene, relative to the plan
//! combine = "product"          # or "zip"
//! [[sweep.parameter]]
//! key = "seabed.stiffness"     # a key path into the base scene (scene::edit)
//! values = [50e3, 100e3, 300e3]
//! ```
//!
//! **Points.** `product`: every combination, the last parameter varying fastest; `zip`: the i-th
//! value of every parameter (all lists the same length). **Runs**: for a study, each point × each
//! storm in the table's order, id `p<point>-s<storm id>`; for a scene, one run per point, id
//! `p<point>`. Run `k` of the list belongs to shard `k mod N`.
//!
//! **Merge**, per point: with a study, the annual damage `D = Σ p_i D_i Y/T_i` over its storms
//! ([`crate::studies::fatigue_study::annual_damage`]) and the minimum life `1/D` over nodes and fibres; with a scene
//! that counts fatigue, the life were its counted record repeated, `T/(Y·D)`. Also the largest
//! per-node bending-moment range (the touchdown zone's, on a riser) and the largest penetration, over
//! its runs. A point with a failed run is marked failed with that run's error; the others are
//! unaffected. The merge sums storms in plan order, so it is the same to the bit whatever the shards
//! or threads that ran the runs.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::AppError;
use crate::run::{self, RunOptions};
use crate::scene::edit::Edit;
use crate::scene::riser::RiserScene;
use crate::scene::{invalid, parse, DirResolver};
use crate::studies::fatigue_study::{annual_damage, Storm, StormResult, Study, YEAR};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PlanFile {
    sweep: SweepTable,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SweepTable {
    base: String,
    #[serde(default)]
    combine: Option<String>,
    parameter: Vec<Parameter>,
}

/// One varied key.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Parameter {
    /// The key path into the base scene.
    pub key: String,
    /// Its values.
    pub values: Vec<toml::Value>,
}

/// What a plan varies.
#[derive(Debug, Clone)]
pub enum Base {
    /// A fatigue study: each point runs every storm.
    Study(Box<Study>),
    /// A scene: each point is one run.
    Scene(Box<RiserScene>),
}

/// A read plan.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The plan file.
    pub file: String,
    /// The base.
    pub base: Base,
    /// The parameters, in the plan's order.
    pub parameters: Vec<Parameter>,
    /// The parameter points: one value per parameter.
    pub points: Vec<Vec<toml::Value>>,
}

/// One run of the expanded plan.
#[derive(Debug, Clone)]
pub struct RunSpec {
    /// Its place in the sorted list.
    pub index: usize,
    /// `p<point>` or `p<point>-s<storm>`.
    pub id: String,
    /// Its parameter point.
    pub point: usize,
    /// Its storm (study bases).
    pub storm: Option<Storm>,
    /// Its scene, edited; or why the edit failed (the run then fails with it).
    pub scene: Result<RiserScene, String>,
}

/// A run's result (one JSON file per run).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    /// The run's id.
    pub id: String,
    /// Its parameter point.
    pub point: usize,
    /// Its storm, for a study.
    pub storm: Option<Storm>,
    /// The hash of its scene's text (a changed run is run again).
    pub scene_hash: String,
    /// Arc length of each node from the top, m.
    pub arc: Vec<f64>,
    /// Seconds of fatigue counted (0 without `[fatigue]`).
    pub counted_seconds: f64,
    /// Per fibre, the damage at every node.
    pub damage: Vec<(String, Vec<f64>)>,
    /// The largest per-node bending-moment range, N·m (`None` if not measured).
    pub moment_range: Option<f64>,
    /// The largest penetration, m.
    pub max_penetration: Option<f64>,
    /// Wall time, s.
    pub wall_seconds: f64,
    /// Why the run failed, if it did.
    pub error: Option<String>,
}

/// A merged parameter point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointSummary {
    /// The parameter values, in the plan's order.
    pub values: Vec<toml::Value>,
    /// Minimum life, years (NaN without fatigue or on failure).
    pub min_life_years: f64,
    /// Its arc length from the top, m.
    pub min_life_arc: f64,
    /// The largest moment range over the point's runs, N·m.
    pub tdz_moment_range: f64,
    /// The largest penetration over the point's runs, m.
    pub max_penetration: f64,
    /// The error of a failed run, if any.
    pub failed: Option<String>,
}

impl Plan {
    /// Reads a plan and its base.
    pub fn read(path: &Path) -> Result<Self, AppError> {
        let file = path.display().to_string();
        let text = crate::scene::read_text(path)?;
        let raw: PlanFile = parse(&file, &text)?;
        let s = raw.sweep;
        if s.parameter.is_empty() {
            return Err(
                invalid(&file, "sweep.parameter", "at least one [[sweep.parameter]]").into(),
            );
        }
        for (i, p) in s.parameter.iter().enumerate() {
            if p.values.is_empty() {
                return Err(invalid(
                    &file,
                    format!("sweep.parameter[{i}].values"),
                    "at least one value",
                )
                .into());
            }
        }
        let points = match s.combine.as_deref().unwrap_or("product") {
            "product" => {
                let mut pts: Vec<Vec<toml::Value>> = vec![vec![]];
                for p in &s.parameter {
                    pts = pts
                        .into_iter()
                        .flat_map(|pt| {
                            p.values.iter().map(move |v| {
                                let mut q = pt.clone();
                                q.push(v.clone());
                                q
                            })
                        })
                        .collect();
                }
                pts
            }
            "zip" => {
                let n = s.parameter[0].values.len();
                if s.parameter.iter().any(|p| p.values.len() != n) {
                    return Err(invalid(
                        &file,
                        "sweep.combine",
                        "\"zip\" with value lists of one length (or \"product\")",
                    )
                    .into());
                }
                (0..n)
                    .map(|i| s.parameter.iter().map(|p| p.values[i].clone()).collect())
                    .collect()
            }
            other => {
                return Err(invalid(
                    &file,
                    "sweep.combine",
                    format!("\"product\" or \"zip\", got {other:?}"),
                )
                .into())
            }
        };
        let dir = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let base_path = dir.join(&s.base);
        let base_text = crate::scene::read_text(&base_path).map_err(|e| {
            AppError::from(invalid(
                &file,
                "sweep.base",
                format!("a readable file ({e})"),
            ))
        })?;
        let is_study = base_text
            .parse::<toml::Table>()
            .map(|t| t.contains_key("study"))
            .unwrap_or(false);
        let base = if is_study {
            Base::Study(Box::new(Study::read(&base_path)?))
        } else {
            Base::Scene(Box::new(crate::run::statics::read_scene(&base_path)?))
        };
        Ok(Self {
            file,
            base,
            parameters: s.parameter,
            points,
        })
    }

    /// The edits of point `p`.
    fn edits(&self, p: usize) -> Vec<Edit> {
        self.parameters
            .iter()
            .zip(&self.points[p])
            .map(|(par, v)| Edit::set(&par.key, v.clone()))
            .collect()
    }

    /// The sorted list of runs (point, then storm in the table's order).
    pub fn runs(&self) -> Vec<RunSpec> {
        let edit = |scene: &RiserScene, p: usize| {
            let files = DirResolver::beside(Path::new(&scene.file));
            scene
                .edited(&self.edits(p), &files)
                .map_err(|e| e.to_string())
        };
        let mut out = Vec::new();
        for p in 0..self.points.len() {
            match &self.base {
                Base::Study(study) => {
                    for (storm, scene) in &study.storms {
                        out.push(RunSpec {
                            index: out.len(),
                            id: format!("p{p:03}-s{:03}", storm.id),
                            point: p,
                            storm: Some(storm.clone()),
                            scene: edit(scene, p),
                        });
                    }
                }
                Base::Scene(scene) => out.push(RunSpec {
                    index: out.len(),
                    id: format!("p{p:03}"),
                    point: p,
                    storm: None,
                    scene: edit(scene, p),
                }),
            }
        }
        out
    }

    /// A point's parameters as text, `key = value, …`.
    pub fn describe(&self, p: usize) -> String {
        self.parameters
            .iter()
            .zip(&self.points[p])
            .map(|(par, v)| format!("{} = {v}", par.key))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The hash a run's result is keyed on: its scene's text, or its id and the edit error (two runs
/// whose edits fail alike must not share a result file).
pub fn run_hash(spec: &RunSpec) -> String {
    match &spec.scene {
        Ok(s) => crate::scene::text_hash(&s.text),
        Err(e) => crate::scene::text_hash(&format!("{}\n{e}", spec.id)),
    }
}

/// Runs one run, keeping `threads` threads busy (`None`: the machine's cores). Never fails: an
/// error is recorded in the result.
pub fn run_one(spec: &RunSpec, threads: Option<usize>) -> RunResult {
    let t0 = std::time::Instant::now();
    let mut res = RunResult {
        id: spec.id.clone(),
        point: spec.point,
        storm: spec.storm.clone(),
        scene_hash: run_hash(spec),
        arc: vec![],
        counted_seconds: 0.0,
        damage: vec![],
        moment_range: None,
        max_penetration: None,
        wall_seconds: 0.0,
        error: None,
    };
    let scene = match &spec.scene {
        Ok(s) => s.clone(),
        Err(e) => {
            res.error = Some(e.clone());
            return res;
        }
    };
    let opts = RunOptions::with_threads(threads);
    match run::simulate(scene, &mut [], opts) {
        Ok(r) => {
            res.arc = r.model.line.arc.clone();
            let finite = |x: f64| x.is_finite().then_some(x);
            res.moment_range = finite(run::key_numbers(&r).0);
            res.max_penetration = finite(
                r.envelopes
                    .penetration
                    .max
                    .iter()
                    .copied()
                    .filter(|x| x.is_finite())
                    .fold(f64::NAN, f64::max),
            );
            if let Some(f) = &r.fatigue {
                res.counted_seconds = f.counted_seconds();
                res.damage = f
                    .spec
                    .fibres
                    .iter()
                    .filter_map(|fib| f.damage_of(*fib).map(|d| (fib.name().to_string(), d)))
                    .collect();
            }
            res.error = r.stop.as_ref().map(ToString::to_string);
        }
        Err(e) => res.error = Some(e.to_string()),
    }
    res.wall_seconds = t0.elapsed().as_secs_f64();
    res
}

/// Merges the results of every run of `runs` (the plan's [`Plan::runs`]; `results[k]` is run `k`'s,
/// `None` when missing) into one summary per point.
pub fn merge(plan: &Plan, runs: &[RunSpec], results: &[Option<RunResult>]) -> Vec<PointSummary> {
    (0..plan.points.len())
        .map(|p| {
            let mine: Vec<(&RunSpec, Option<&RunResult>)> = runs
                .iter()
                .filter(|r| r.point == p)
                .map(|r| (r, results.get(r.index).and_then(Option::as_ref)))
                .collect();
            let mut s = PointSummary {
                values: plan.points[p].clone(),
                min_life_years: f64::NAN,
                min_life_arc: f64::NAN,
                tdz_moment_range: f64::NAN,
                max_penetration: f64::NAN,
                failed: None,
            };
            for (spec, r) in &mine {
                match r {
                    None => {
                        s.failed
                            .get_or_insert_with(|| format!("run {} has no result", spec.id));
                    }
                    Some(r) => {
                        if let Some(e) = &r.error {
                            s.failed.get_or_insert_with(|| format!("run {}: {e}", r.id));
                        }
                        if let Some(m) = r.moment_range {
                            s.tdz_moment_range = s.tdz_moment_range.max(m);
                        }
                        if let Some(p) = r.max_penetration {
                            s.max_penetration = s.max_penetration.max(p);
                        }
                    }
                }
            }
            if s.failed.is_some() {
                return s;
            }
            let done: Vec<&RunResult> = mine.iter().filter_map(|(_, r)| *r).collect();
            let Some(first) = done.first() else {
                return s;
            };
            let fibres: Vec<String> = first.damage.iter().map(|(n, _)| n.clone()).collect();
            let annual: Vec<(String, Vec<f64>)> = match &plan.base {
                Base::Study(_) => {
                    let storms: Vec<StormResult> = done
                        .iter()
                        .filter_map(|r| {
                            Some(StormResult {
                                storm: r.storm.clone()?,
                                scene_hash: r.scene_hash.clone(),
                                counted_seconds: r.counted_seconds,
                                damage: r.damage.clone(),
                                wall_seconds: r.wall_seconds,
                                error: r.error.clone(),
                            })
                        })
                        .collect();
                    fibres
                        .iter()
                        .map(|f| (f.clone(), annual_damage(&storms, f)))
                        .collect()
                }
                Base::Scene(_) if first.counted_seconds > 0.0 => first
                    .damage
                    .iter()
                    .map(|(n, d)| {
                        let w = YEAR / first.counted_seconds;
                        (n.clone(), d.iter().map(|x| x * w).collect())
                    })
                    .collect(),
                Base::Scene(_) => vec![],
            };
            for (_, d) in &annual {
                for (i, x) in d.iter().enumerate() {
                    let life = 1.0 / x;
                    if *x > 0.0 && (s.min_life_years.is_nan() || life < s.min_life_years) {
                        s.min_life_years = life;
                        s.min_life_arc = first.arc.get(i).copied().unwrap_or(f64::NAN);
                    }
                }
            }
            s
        })
        .collect()
}

/// The merged table as CSV: the parameters by their key paths, then `min_life_years`,
/// `min_life_arc`, `tdz_moment_range`, `max_penetration`, `status` (empty cells for unmeasured
/// values).
pub fn csv(plan: &Plan, points: &[PointSummary]) -> String {
    let num = |x: f64| {
        if x.is_finite() {
            format!("{x}")
        } else {
            String::new()
        }
    };
    let mut out = plan
        .parameters
        .iter()
        .map(|p| p.key.clone())
        .chain(
            [
                "min_life_years",
                "min_life_arc",
                "tdz_moment_range",
                "max_penetration",
                "status",
            ]
            .map(String::from),
        )
        .collect::<Vec<_>>()
        .join(",");
    out.push('\n');
    for s in points {
        let mut row: Vec<String> = s.values.iter().map(|v| v.to_string()).collect();
        row.extend([
            num(s.min_life_years),
            num(s.min_life_arc),
            num(s.tdz_moment_range),
            num(s.max_penetration),
            s.failed.as_ref().map_or("ok".into(), |e| {
                format!("\"failed: {}\"", e.replace('"', "'"))
            }),
        ]);
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}
