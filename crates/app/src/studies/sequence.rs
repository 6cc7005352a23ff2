//! Storms in sequence (`catena sequence SEQUENCE.toml`): the seabed's memory across storms.
//!
//! A fatigue study ([`crate::studies::fatigue_study`]) starts every storm from the same as-laid static state. A
//! sequence runs the storms one after another, each from the state the previous one left: every
//! node's seabed history (the trench it dug, its degraded strength) and friction anchors, the line
//! brought to rest by a calm interval.
//!
//! **Sequence file** (every key in `docs/sequence.md`):
//!
//! ```toml
//! [sequence]
//! scene = "../fatigue/scr1000-rq-fsuc0.2.toml"   # the base scene (with [waves], [vessel])
//! storms = "../fatigue/gom-30-storms.toml"       # the storm table of the fatigue study
//! order = [23, 24, 20]          # storm ids in order; or `random` (below)
//! record = 600.0                # s counted per visit, after the transient
//! transient = 200.0             # s discarded at the start of each visit
//! calm = 86400.0                # s of rest between visits (strength regain, if the soil has it)
//! settle = 200.0                # s of calm dynamics that bring the line to rest (default 200)
//! settle_time_step = 0.05       # s (default: the scene's time step)
//! as_laid = true                # also run every visit from the as-laid state (default true)
//! [sequence.random]             # instead of `order`:
//! seed = 1                      # the order's seed
//! visits = 60                   # visits in all: one per storm, the rest by probability
//! every_storm = true            # one visit to every storm first (default true)
//! [fatigue]                     # as in a fatigue study
//! ```
//!
//! **A visit** is one storm of the table run for `transient + record` seconds with the fatigue
//! observer. With `random`, every storm is visited once (`every_storm`, default: the rare storms
//! make the touchdown zone's damage) and the other visits are shared among the storms by their
//! probabilities (largest remainders; with `every_storm = false` all of them are, and a storm whose
//! share rounds to nothing is not visited: its probability is reported as not covered) and put in a random order drawn from the seed (ChaCha8, Fisher–Yates). Storm
//! `i`'s `k`-th visit uses the wave seed `seed_i + 1000·k` (the study's seed for the first).
//!
//! **The cut.** Storm `i` fills `p_i·Y` seconds of a year; its `n_i` visits, each counting `T`
//! seconds, stand for it, so each counted second stands for `p_i·Y/(n_i·T)` seconds of the year,
//! and the annual damage is
//!
//! ```text
//! D = Σ_visits p_i·D_v·Y/(n_i·T_v).
//! ```
//!
//! The trench a visit digs is that of `T_v` seconds of the storm, not of the `p_i·Y/n_i` seconds it
//! stands for: the cut's accuracy is measured by running the sequence with longer records (see
//! `validation/seabed-memory.md`).
//!
//! **Between visits** the line is brought to rest: the base scene without waves, vessel motion or
//! outputs, run for `settle` seconds with steps of `settle_time_step` from the visit's last state
//! with its velocities set to zero; the hang-off returns from where the storm left it to its mean
//! position over the first half of the settling (the quintic ramp), and the line settles under its
//! drag and the scheme's damping; velocities are then set to zero again. Each node's seabed history then rests for `calm` seconds (the law's regain of
//! degraded strength: [`catena_seabed::degradation`]). The next visit starts from that state
//! ([`crate::run::RunOptions::start`]). The *trench* after a visit is each node's penetration in
//! the settled state (m, positive down).
//!
//! **As laid.** The same visits, each from the as-laid statics (the study as today), give the
//! damage without memory: the difference is the memory alone (the same seas, the same seeds). The
//! first visit with memory is the first as laid, to the bit.

use std::path::{Path, PathBuf};

use catena_fe::dynamics::Carry;
use catena_seabed::law::Law;
use catena_seabed::SeabedHistory;
use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::error::AppError;
use crate::run::{self, RunOptions};
use crate::scene::edit::Edit;
use crate::scene::riser::RiserScene;
use crate::scene::{invalid, parse, DirResolver};
use crate::studies::fatigue_study::{
    check_sea, damage_of, read_base_as, read_storm_table_as, weighted_damage, Sea, Storm,
    StormsFile, YEAR,
};

/// `[sequence.random]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct RandomTable {
    pub seed: u64,
    pub visits: usize,
    pub every_storm: Option<bool>,
}

/// `[sequence]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SequenceTable {
    pub scene: String,
    pub storms: String,
    pub order: Option<Vec<i64>>,
    pub random: Option<RandomTable>,
    pub record: f64,
    pub transient: f64,
    pub calm: f64,
    pub settle: Option<f64>,
    pub settle_time_step: Option<f64>,
    pub as_laid: Option<bool>,
}

/// A sequence file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SequenceFile {
    pub sequence: SequenceTable,
    pub fatigue: toml::Table,
}

/// One visit of a storm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Visit {
    /// Its place in the sequence, from 0.
    pub index: usize,
    /// The storm (its `seed` the visit's wave seed).
    pub storm: Storm,
    /// The storm's visits in the sequence, `n_i`.
    pub visits_of_storm: usize,
    /// Seconds of the year each counted second stands for, `p_i·Y/(n_i·T)`.
    pub weight: f64,
}

/// A sequence, read and checked: every visit's scene built.
#[derive(Debug, Clone)]
pub struct Sequence {
    /// The sequence file.
    pub file: String,
    /// The base scene.
    pub base: RiserScene,
    /// The visits in order, each with its scene.
    pub visits: Vec<(Visit, RiserScene)>,
    /// The calm scene that brings the line to rest.
    pub calm_scene: RiserScene,
    /// Rest between visits, s.
    pub calm: f64,
    /// Whether the visits are also run from the as-laid state.
    pub as_laid: bool,
    /// The share of the year's sea states the visits cover (Σ p of the storms visited / Σ p).
    pub coverage: f64,
}

/// One visit's result (one JSON per visit, so a sequence resumes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VisitResult {
    /// The visit.
    pub visit: Visit,
    /// The hash of its scene's text and of the calm scene's (a changed scene is run again).
    pub scene_hash: String,
    /// Seconds counted.
    pub counted_seconds: f64,
    /// Per fibre (by name), the damage at every node over the counted record.
    pub damage: Vec<(String, Vec<f64>)>,
    /// Each node's penetration after the visit, at rest, m (with memory; empty as laid).
    pub trench: Vec<f64>,
    /// Each node's strength factor `δ` for its next episode (1: intact; empty as laid).
    pub strength: Vec<f64>,
    /// Wall time, s.
    pub wall_seconds: f64,
    /// How many times the calm after the visit was retried with a smaller step (0 usually).
    #[serde(default)]
    pub calm_retries: usize,
    /// Why the run stopped early, if it did (its damage is then not used, and the sequence stops).
    pub error: Option<String>,
}

fn positive_time(file: &str, key: &str, v: f64, allow_zero: bool) -> Result<(), AppError> {
    if !(v.is_finite() && (v > 0.0 || (allow_zero && v == 0.0))) {
        let what = if allow_zero {
            format!("a time >= 0 s (got {v})")
        } else {
            format!("a time > 0 s (got {v})")
        };
        return Err(invalid(file, key, what).into());
    }
    Ok(())
}

/// The visits of storm indices `order`: each with its count, seed and weight.
fn visits_of(storms: &[Storm], order: &[usize], record: f64) -> Vec<Visit> {
    let mut seen = vec![0usize; storms.len()];
    let counts: Vec<usize> = (0..storms.len())
        .map(|i| order.iter().filter(|&&j| j == i).count())
        .collect();
    order
        .iter()
        .enumerate()
        .map(|(index, &i)| {
            let st = &storms[i];
            let k = seen[i];
            seen[i] += 1;
            let base_seed = st.seed.map_or(st.id, |s| s as i64);
            let n = counts[i];
            let t = st.duration.unwrap_or(record);
            Visit {
                index,
                storm: Storm {
                    seed: Some((base_seed + 1000 * k as i64) as u64),
                    duration: Some(t),
                    ..st.clone()
                },
                visits_of_storm: n,
                weight: st.probability * YEAR / (n as f64 * t),
            }
        })
        .collect()
}

/// `visits` shared among the storms by probability (largest remainders; with `every_storm`, one
/// visit to each storm first and the rest by probability), shuffled by `seed` (ChaCha8,
/// Fisher–Yates). `visits` must be at least the storms' count with `every_storm`.
pub fn random_order(
    probabilities: &[f64],
    visits: usize,
    seed: u64,
    every_storm: bool,
) -> Vec<usize> {
    let total: f64 = probabilities.iter().sum();
    let first = usize::from(every_storm);
    let shared = visits - first * probabilities.len();
    let exact: Vec<f64> = probabilities
        .iter()
        .map(|p| p / total * shared as f64)
        .collect();
    let mut counts: Vec<usize> = exact.iter().map(|x| first + x.floor() as usize).collect();
    let mut left = visits - counts.iter().sum::<usize>();
    let mut by_remainder: Vec<usize> = (0..exact.len()).collect();
    by_remainder.sort_by(|&a, &b| {
        let (ra, rb) = (exact[a] - exact[a].floor(), exact[b] - exact[b].floor());
        rb.total_cmp(&ra).then(a.cmp(&b))
    });
    for i in by_remainder {
        if left == 0 {
            break;
        }
        counts[i] += 1;
        left -= 1;
    }
    let mut order: Vec<usize> = counts
        .iter()
        .enumerate()
        .flat_map(|(i, &n)| std::iter::repeat_n(i, n))
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for i in (1..order.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        order.swap(i, j);
    }
    order
}

impl Sequence {
    /// Reads a sequence file and builds every visit's scene and the calm scene.
    pub fn read(path: &Path) -> Result<Self, AppError> {
        let file = path.display().to_string();
        let text = crate::scene::read_text(path)?;
        let raw: SequenceFile = parse(&file, &text)?;
        let dir = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let s = &raw.sequence;
        positive_time(&file, "sequence.record", s.record, false)?;
        positive_time(&file, "sequence.transient", s.transient, true)?;
        positive_time(&file, "sequence.calm", s.calm, true)?;
        let settle = s.settle.unwrap_or(200.0);
        positive_time(&file, "sequence.settle", settle, false)?;
        let (scene_path, base) = read_base_as(&file, "sequence", &dir, &s.scene)?;
        let settle_dt = s
            .settle_time_step
            .unwrap_or_else(|| base.dynamic.as_ref().map_or(0.05, |d| d.dt));
        positive_time(&file, "sequence.settle_time_step", settle_dt, false)?;
        if settle_dt > settle {
            return Err(invalid(
                &file,
                "sequence.settle_time_step",
                format!("a step no longer than sequence.settle ({settle} s), got {settle_dt} s"),
            )
            .into());
        }
        let (sfile, table): (String, StormsFile) =
            read_storm_table_as(&file, "sequence", &dir, &s.storms)?;
        if table.storm.is_empty() {
            return Err(invalid(&file, "sequence.storms", "at least one [[storm]]").into());
        }
        check_storms(&sfile, &table)?;
        let order = storm_order(&file, &sfile, s, &table)?;
        for (k, &i) in order.iter().enumerate() {
            let t = table.storm[i].duration.unwrap_or(s.record);
            if !(t.is_finite() && t > 0.0) {
                return Err(invalid(
                    &sfile,
                    format!("storm[{i}].duration"),
                    format!("a counted record > 0 s (visit {k})"),
                )
                .into());
            }
        }
        let files = DirResolver::beside(&scene_path);
        let mut visits = Vec::new();
        for v in visits_of(&table.storm, &order, s.record) {
            let st = &v.storm;
            let sea = Sea {
                hs: st.hs,
                tp: st.tp,
                gamma: st.gamma,
                seed: st.seed.map_or(st.id, |x| x as i64),
            };
            let mut edits = sea.edits(s.transient, st.duration.unwrap_or(s.record));
            edits.push(Edit::set(
                "fatigue",
                toml::Value::Table(raw.fatigue.clone()),
            ));
            edits.push(Edit::set("fatigue.start", s.transient));
            // The [fatigue] table is the study's own: its errors name the study's file.
            let scene = base
                .edited(&edits, &files)
                .map_err(|e| e.in_table_of("fatigue", &file))?;
            visits.push((v, scene));
        }
        let mut calm_edits = vec![
            Edit::set("dynamic.duration", settle),
            Edit::set("dynamic.time_step", settle_dt),
            Edit::set("dynamic.envelope_start", 0.0),
            Edit::set("dynamic.output_interval", settle),
        ];
        for key in [
            "waves",
            "vessel",
            "motion",
            "fatigue",
            "design_check",
            "extremes",
            "gauge",
        ] {
            if base.doc.get(key).is_some() {
                calm_edits.push(Edit::remove(key));
            }
        }
        let calm_scene = base.edited(&calm_edits, &files)?;
        let visited: f64 = (0..table.storm.len())
            .filter(|i| order.contains(i))
            .map(|i| table.storm[i].probability)
            .sum();
        let all: f64 = table.storm.iter().map(|st| st.probability).sum();
        Ok(Self {
            file,
            base,
            visits,
            calm_scene,
            calm: s.calm,
            as_laid: s.as_laid.unwrap_or(true),
            coverage: if all > 0.0 { visited / all } else { 0.0 },
        })
    }

    /// The calm scene after `storm`: the hang-off returns from where the storm left it to its
    /// mean position over the first half of the settling, on the quintic ramp (sampled every
    /// `settle/100`: a smooth path with a velocity that starts and ends near zero).
    fn returning(&self, storm: &run::DynamicRun) -> RiserScene {
        let mut scene = self.calm_scene.clone();
        let top = |u: &[f64]| (u[0], u[1]);
        let (ex, ez) = top(&storm.carry.u);
        let (sx, sz) = top(&storm.statics.u);
        let (dx, dz) = (ex - sx, ez - sz);
        if let Some(d) = scene.dynamic.as_mut() {
            let settle = d.duration;
            let t_return = 0.5 * settle;
            let points = (0..=50)
                .map(|k| {
                    let t = t_return * k as f64 / 50.0;
                    let (r, _, _) = catena_fe::motion::quintic_ramp(t, t_return);
                    (t, dx * (1.0 - r), dz * (1.0 - r))
                })
                .collect();
            d.motion = Some(catena_fe::motion::TopMotion::Series(points));
        }
        scene
    }

    /// The hash of visit `k`'s scene and the calm scene (what a resumed sequence checks).
    pub fn hash_of(&self, k: usize) -> String {
        crate::scene::text_hash(&format!(
            "{}\n{}\n{}",
            self.visits[k].1.text, self.calm_scene.text, self.calm
        ))
    }
}

/// Runs visit `k` from `start` (the as-laid statics when `None`): the storm, then the calm (the
/// line brought to rest, each node's history rested for `calm` seconds), keeping `threads`
/// threads busy (`None`: the machine's cores; [`crate::run::RunOptions::threads`]). Returns the
/// result and what it leaves for the next visit (`None` if the storm stopped early).
pub fn run_visit(
    seq: &Sequence,
    k: usize,
    start: Option<Carry>,
    threads: Option<usize>,
) -> Result<(VisitResult, Option<Carry>), AppError> {
    let t0 = std::time::Instant::now();
    let (visit, scene) = &seq.visits[k];
    let storm = run::simulate(
        scene.clone(),
        &mut [],
        RunOptions {
            start,
            threads,
            ..RunOptions::default()
        },
    )?;
    let damage = damage_of(&storm, scene)?;
    let counted_seconds = storm.fatigue.as_ref().map_or(0.0, |f| f.counted_seconds());
    let mut result = VisitResult {
        visit: visit.clone(),
        scene_hash: seq.hash_of(k),
        counted_seconds,
        damage,
        trench: Vec::new(),
        strength: Vec::new(),
        wall_seconds: 0.0,
        calm_retries: 0,
        error: storm.stop.as_ref().map(ToString::to_string),
    };
    if result.error.is_some() {
        result.wall_seconds = t0.elapsed().as_secs_f64();
        return Ok((result, None));
    }
    // The settling from a line stopped mid-storm can fail to converge at the storm's step where a
    // smaller one goes through (seen once in thirty 1800 s visits): it is retried at 2/5 and 4/25 of
    // the step. The settling is not counted; only its end state is kept.
    let mut calm = None;
    let mut failures = Vec::new();
    for factor in [1.0, 0.4, 0.16] {
        let mut scene = seq.returning(&storm);
        if let Some(d) = scene.dynamic.as_mut() {
            d.dt *= factor;
        }
        let r = run::simulate(
            scene,
            &mut [],
            RunOptions {
                start: Some(storm.carry.clone()),
                threads,
                ..RunOptions::default()
            },
        )?;
        match &r.stop {
            None => {
                calm = Some(r);
                break;
            }
            Some(stop) => failures.push(format!("at {factor} of the step: {stop}")),
        }
    }
    result.calm_retries = failures.len();
    let Some(calm) = calm else {
        result.error = Some(format!(
            "the calm after the visit stopped: {}",
            failures.join("; ")
        ));
        result.wall_seconds = t0.elapsed().as_secs_f64();
        return Ok((result, None));
    };
    let mut carry = calm.carry;
    let line = &calm.model.line;
    let base = &calm.model.placement.base;
    let law_of = |i: usize| {
        line.seabed_law(i)
            .or_else(|| line.seabed.as_ref().map(|s| &s.seabed))
    };
    for (i, h) in carry.history.iter_mut().enumerate() {
        if let Some(law) = law_of(i) {
            *h = law.rest(h, seq.calm);
        }
    }
    result.trench = (0..line.nodes())
        .map(|i| {
            let (x, z) = (
                base[3 * i] + carry.u[3 * i],
                base[3 * i + 1] + carry.u[3 * i + 1],
            );
            line.penetration(i, x, z).unwrap_or(0.0)
        })
        .collect();
    result.strength = carry
        .history
        .iter()
        .enumerate()
        .map(|(i, h)| match (law_of(i).map(|s| &s.law), h) {
            (Some(Law::RandolphQuiggin(l)), SeabedHistory::RandolphQuiggin(r)) => l
                .params()
                .degradation
                .map_or(1.0, |d| d.strength(r.wear.xi)),
            _ => 1.0,
        })
        .collect();
    result.wall_seconds = t0.elapsed().as_secs_f64();
    Ok((result, Some(carry)))
}

/// Visit `k` from the as-laid statics, without the calm (the study as today), keeping `threads`
/// threads busy (`None`: the machine's cores).
pub fn run_as_laid(
    seq: &Sequence,
    k: usize,
    threads: Option<usize>,
) -> Result<VisitResult, AppError> {
    let t0 = std::time::Instant::now();
    let (visit, scene) = &seq.visits[k];
    let opts = RunOptions::with_threads(threads);
    let r = run::simulate(scene.clone(), &mut [], opts)?;
    Ok(VisitResult {
        visit: visit.clone(),
        scene_hash: seq.hash_of(k),
        counted_seconds: r.fatigue.as_ref().map_or(0.0, |f| f.counted_seconds()),
        damage: damage_of(&r, scene)?,
        trench: Vec::new(),
        strength: Vec::new(),
        wall_seconds: t0.elapsed().as_secs_f64(),
        calm_retries: 0,
        error: r.stop.as_ref().map(ToString::to_string),
    })
}

/// The annual damage along the arc for one fibre over visits `results`:
/// `D = Σ p_i·D_v·Y/(n_i·T_v)` (visits that stopped early are left out).
pub fn annual_damage(results: &[VisitResult], fibre: &str) -> Vec<f64> {
    weighted_damage(
        results
            .iter()
            .filter(|r| r.error.is_none() && r.counted_seconds > 0.0)
            .map(|r| {
                (
                    r.damage.as_slice(),
                    r.visit.storm.probability * YEAR
                        / (r.visit.visits_of_storm as f64 * r.counted_seconds),
                )
            }),
        fibre,
    )
}

/// Each storm of the table checked: its sea state, a probability in [0, 1] and a unique id.
fn check_storms(sfile: &str, table: &StormsFile) -> Result<(), AppError> {
    for (i, st) in table.storm.iter().enumerate() {
        check_sea(sfile, i, st.hs, st.tp)?;
        if !(st.probability.is_finite() && (0.0..=1.0).contains(&st.probability)) {
            return Err(invalid(
                sfile,
                format!("storm[{i}].probability"),
                "a fraction of the year in [0, 1]",
            )
            .into());
        }
        if table.storm[..i].iter().any(|o| o.id == st.id) {
            return Err(invalid(sfile, format!("storm[{i}].id"), "a unique id").into());
        }
    }
    Ok(())
}

/// The visits' order: the storms named in `order`, or drawn by their probabilities
/// (`[sequence.random]`), as indices into the table.
fn storm_order(
    file: &str,
    sfile: &str,
    s: &SequenceTable,
    table: &StormsFile,
) -> Result<Vec<usize>, AppError> {
    Ok(match (&s.order, &s.random) {
        (Some(ids), None) => {
            if ids.is_empty() {
                return Err(invalid(file, "sequence.order", "at least one storm id").into());
            }
            ids.iter()
                .enumerate()
                .map(|(k, id)| {
                    table
                        .storm
                        .iter()
                        .position(|st| st.id == *id)
                        .ok_or_else(|| {
                            AppError::from(invalid(
                                file,
                                format!("sequence.order[{k}]"),
                                format!("the id of a storm in {sfile} (there is no storm {id})"),
                            ))
                        })
                })
                .collect::<Result<_, _>>()?
        }
        (None, Some(r)) => {
            let every = r.every_storm.unwrap_or(true);
            let least = if every { table.storm.len() } else { 1 };
            if r.visits < least {
                return Err(invalid(
                    file,
                    "sequence.random.visits",
                    format!(
                        "at least {least} visits ({})",
                        if every {
                            "one per storm of the table: every_storm = true"
                        } else {
                            "one"
                        }
                    ),
                )
                .into());
            }
            let p: Vec<f64> = table.storm.iter().map(|st| st.probability).collect();
            if p.iter().sum::<f64>() <= 0.0 {
                return Err(invalid(
                    sfile,
                    "storm[*].probability",
                    "probabilities that are not all zero (a random order draws by them)",
                )
                .into());
            }
            random_order(&p, r.visits, r.seed, every)
        }
        _ => {
            return Err(invalid(
                file,
                "sequence.order",
                "either `order = [storm ids]` or a [sequence.random] table, not both or neither",
            )
            .into())
        }
    })
}
