//! `catena sequence SEQUENCE.toml --out DIR`: storms in sequence ([`catena::studies::sequence`]).
//!
//! The sequence is serial by nature: one thread runs it, visit after visit, each from the state the
//! last left; the as-laid visits (the study as today) run alongside on the other threads. Each
//! finished visit leaves `DIR/visits/visit-NNNN.json` (its damage, trench and strength) and
//! `DIR/visits/carry-NNNN.json` (the state the next visit starts from), written atomically, the
//! carry first: a sequence killed at any point resumes after its last finished visit and gives the
//! same bits. Then `summary.json`, `trench.csv` (penetration at rest after each visit), `life.csv`
//! (life along the arc with memory and as laid), `visits.csv` (each visit's damage at the critical
//! node, with memory and as laid) and `sequence.png`.

use std::path::Path;
use std::time::Instant;

use catena::run::statics;
use catena::studies::schedule::threads_per_run;
use catena::studies::sequence::{annual_damage, run_as_laid, run_visit, Sequence, VisitResult};
use catena::AppError;
use catena_fe::dynamics::Carry;
use serde_json::json;

use super::{resumable, write_json};

fn write_atomic<T: serde::Serialize>(path: &Path, v: &T) -> Result<(), AppError> {
    let tmp = path.with_extension("json.tmp");
    let text = serde_json::to_string(v).map_err(|e| AppError::Output {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    std::fs::write(&tmp, text).map_err(|e| AppError::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| AppError::io(path, e))
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Option<T> {
    serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()
}

/// The sequence with memory: resumes after the last finished visit whose scene is unchanged.
fn chain(
    seq: &Sequence,
    dir: &Path,
    (threads, progress): (usize, bool),
    t0: Instant,
) -> Result<(Vec<VisitResult>, usize), AppError> {
    let n = seq.visits.len();
    let paths = |k: usize| {
        (
            dir.join(format!("visit-{k:04}.json")),
            dir.join(format!("carry-{k:04}.json")),
        )
    };
    let mut results = Vec::new();
    let mut carry: Option<Carry> = None;
    while results.len() < n {
        let k = results.len();
        let (vp, cp) = paths(k);
        match (read_json::<VisitResult>(&vp), read_json::<Carry>(&cp)) {
            (Some(r), Some(c))
                if r.scene_hash == seq.hash_of(k)
                    && r.error.is_none()
                    && r.visit == seq.visits[k].0 =>
            {
                results.push(r);
                carry = Some(c);
            }
            _ => break,
        }
    }
    let resumed = results.len();
    for k in resumed..n {
        let (vp, cp) = paths(k);
        let (r, next) = run_visit(seq, k, carry.take(), Some(threads))?;
        if let Some(c) = &next {
            write_atomic(&cp, c)?;
        }
        write_atomic(&vp, &r)?;
        if progress {
            let deepest = r.trench.iter().copied().fold(0.0f64, f64::max);
            let weakest = r.strength.iter().copied().fold(1.0f64, f64::min);
            eprintln!(
                "  visit {}/{n}: storm {} (Hs {} m, Tp {} s, seed {}): {:.1} s; deepest {:.3} m, least strength {:.3}{}; {:.0} s elapsed",
                k + 1,
                r.visit.storm.id,
                r.visit.storm.hs,
                r.visit.storm.tp,
                r.visit.storm.seed.unwrap_or_default(),
                r.wall_seconds,
                deepest,
                weakest,
                match (&r.error, r.calm_retries) {
                    (Some(e), _) => format!(", STOPPED EARLY: {e}"),
                    (None, 0) => String::new(),
                    (None, n) => format!(", the calm retried {n} time(s) at a smaller step"),
                },
                t0.elapsed().as_secs_f64()
            );
        }
        let stopped = next.is_none();
        results.push(r);
        if stopped {
            break;
        }
        carry = next;
    }
    Ok((results, resumed))
}

/// The as-laid visits (resumable, on `threads` threads).
fn as_laid(
    seq: &Sequence,
    dir: &Path,
    (threads, per_run): (usize, usize),
    progress: bool,
) -> Result<Vec<VisitResult>, AppError> {
    let ks: Vec<usize> = (0..seq.visits.len()).collect();
    let n = ks.len();
    let (rs, _) = resumable(
        &ks,
        // The visits are the storms' of the table at the same record: their order is kept.
        (threads, |_: &usize| 1.0),
        |k| dir.join(format!("visit-{k:04}.json")),
        |&k, r: &VisitResult| {
            r.scene_hash == seq.hash_of(k) && r.error.is_none() && r.visit == seq.visits[k].0
        },
        |&k| run_as_laid(seq, k, Some(per_run)),
        |_, r, done| {
            if progress {
                eprintln!(
                    "  as laid: storm {} (visit {}): {:.1} s; {done}/{n} done",
                    r.visit.storm.id,
                    r.visit.index + 1,
                    r.wall_seconds
                );
            }
        },
    )?;
    Ok(rs)
}

fn lives(d: &[f64]) -> Vec<f64> {
    d.iter()
        .map(|&x| if x > 0.0 { 1.0 / x } else { f64::INFINITY })
        .collect()
}

fn finite(x: f64) -> serde_json::Value {
    if x.is_finite() {
        json!(x)
    } else {
        serde_json::Value::Null
    }
}

/// `catena sequence SEQUENCE.toml --out DIR` (see the module docs).
pub fn run(path: &Path, out: &Path, jobs: usize, progress: bool) -> Result<String, AppError> {
    let t0 = Instant::now();
    let seq = Sequence::read(path)?;
    let n = seq.visits.len();
    let st = statics::solve(seq.base.clone())?;
    let touchdown = st.summary.touchdown_arc;
    let arc = seq.base.model.arc.clone();
    let (vdir, ldir) = (out.join("visits"), out.join("as-laid"));
    for d in [&vdir, &ldir] {
        std::fs::create_dir_all(d).map_err(|e| AppError::io(d, e))?;
    }
    let (memory, resumed, laid) = both_chains(&seq, (&vdir, &ldir), jobs, progress, t0)?;
    let fibre = memory
        .first()
        .and_then(|r| r.damage.first())
        .map(|(f, _)| f.clone())
        .unwrap_or_else(|| "outer".into());
    // Compare over the visits the sequence finished.
    let done = memory.iter().take_while(|r| r.error.is_none()).count();
    let laid_same: Vec<VisitResult> = laid.iter().take(done).cloned().collect();
    let d_mem = annual_damage(&memory[..done], &fibre);
    let d_laid = annual_damage(&laid_same, &fibre);
    let (l_mem, l_laid) = (lives(&d_mem), lives(&d_laid));
    let argmin = |l: &[f64]| {
        l.iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .map(|(i, &v)| (i, v))
    };
    let (i_mem, life_mem) = argmin(&l_mem).unwrap_or((0, f64::NAN));
    let (i_laid, life_laid) = argmin(&l_laid).unwrap_or((0, f64::NAN));
    let i_crit = if l_laid.is_empty() { i_mem } else { i_laid };
    // Accumulated annual damage at the critical node, visit by visit.
    let accumulate = |rs: &[VisitResult]| -> Vec<f64> {
        (1..=rs.len())
            .map(|k| {
                annual_damage(&rs[..k], &fibre)
                    .get(i_crit)
                    .copied()
                    .unwrap_or(0.0)
            })
            .collect()
    };
    let (acc_mem, acc_laid) = (accumulate(&memory[..done]), accumulate(&laid_same));
    let trenches: Vec<Vec<f64>> = memory[..done].iter().map(|r| r.trench.clone()).collect();
    let strength = memory[..done]
        .last()
        .map(|r| r.strength.clone())
        .unwrap_or_default();
    write_trench_and_life(
        out,
        &arc,
        &st.results.penetration,
        &trenches,
        (&l_mem, &l_laid),
        &strength,
    )?;
    write_visits(out, &memory, &laid, &fibre, i_crit)?;
    let window = match touchdown {
        Some(t) => (t - 30.0, t + 120.0),
        None => (arc[0], *arc.last().unwrap_or(&1.0)),
    };
    catena_io::plot::sequence(
        &out.join("sequence.png"),
        &catena_io::plot::SequencePlot {
            title: &format!(
                "{} — {done} visits in sequence: the seabed's memory",
                seq.base.title
            ),
            arc: &arc,
            as_laid: &st.results.penetration,
            trenches: &trenches,
            window,
            life_memory: &l_mem,
            life_as_laid: &l_laid,
            accumulated: (&acc_mem, &acc_laid),
            strength: &strength,
        },
    )?;
    let wall = t0.elapsed().as_secs_f64();
    let memory_seconds: f64 = memory.iter().map(|r| r.wall_seconds).sum();
    let stopped = memory.iter().find_map(|r| r.error.clone());
    let deepest_first = trenches
        .first()
        .map_or(0.0, |t| t.iter().copied().fold(0.0f64, f64::max));
    let deepest_last = trenches
        .last()
        .map_or(0.0, |t| t.iter().copied().fold(0.0f64, f64::max));
    let ratio = life_mem / life_laid;
    let js = json!({
        "sequence": seq.file,
        "visits": n,
        "visits_done": done,
        "resumed_after": resumed,
        "coverage": seq.coverage,
        "calm_s": seq.calm,
        "fibre": fibre,
        "memory": {
            "minimum_life_years": finite(life_mem),
            "at_arc_m": arc.get(i_mem),
            "life_at_as_laid_critical_years": finite(l_mem.get(i_crit).copied().unwrap_or(f64::NAN)),
        },
        "as_laid": {
            "minimum_life_years": finite(life_laid),
            "at_arc_m": if l_laid.is_empty() { None } else { arc.get(i_laid) },
        },
        "life_ratio_memory_over_as_laid": finite(ratio),
        "deepest_trench_m": {"after_first_visit": deepest_first, "after_last_visit": deepest_last},
        "least_strength_factor": strength.iter().copied().fold(1.0f64, f64::min),
        "touchdown_arc_m": touchdown,
        "stopped": stopped,
        "wall_seconds": wall,
        "sequence_wall_seconds": memory_seconds,
    });
    write_json(&out.join("summary.json"), &js)?;
    let mut t = format!(
        "sequence {}: {done}/{n} visits ({} resumed), {:.1} % of the year's sea states covered\n",
        seq.file,
        resumed,
        100.0 * seq.coverage
    );
    t.push_str(&format!(
        "  minimum life with memory {life_mem:.4e} years at {:.1} m; as laid {life_laid:.4e} years at {:.1} m (memory/as laid {ratio:.3})\n",
        arc.get(i_mem).copied().unwrap_or(f64::NAN),
        arc.get(i_laid).copied().unwrap_or(f64::NAN),
    ));
    t.push_str(&format!(
        "  deepest trench {deepest_first:.4} m after the first visit, {deepest_last:.4} m after the last\n"
    ));
    if let Some(e) = stopped {
        t.push_str(&format!("  STOPPED EARLY: {e}\n"));
    }
    t.push_str(&format!(
        "  {wall:.1} s ({memory_seconds:.1} s in the sequence); wrote {}\n",
        out.display()
    ));
    Ok(t)
}

/// `trench.csv` (the as-laid penetration and each visit's trench along the arc) and `life.csv`
/// (the life with memory and as laid, the strength factor after the last visit).
fn write_trench_and_life(
    out: &Path,
    arc: &[f64],
    as_laid: &[f64],
    trenches: &[Vec<f64>],
    (l_mem, l_laid): (&[f64], &[f64]),
    strength: &[f64],
) -> Result<(), AppError> {
    let mut csv = String::from("arc,as_laid");
    for k in 0..trenches.len() {
        csv.push_str(&format!(",after_visit_{}", k + 1));
    }
    csv.push('\n');
    for (i, a) in arc.iter().enumerate() {
        csv.push_str(&format!("{a},{}", as_laid[i]));
        for t in trenches {
            csv.push_str(&format!(",{}", t[i]));
        }
        csv.push('\n');
    }
    let p = out.join("trench.csv");
    std::fs::write(&p, csv).map_err(|e| AppError::io(&p, e))?;
    let mut csv = String::from("arc,life_memory,life_as_laid,strength_after\n");
    for (i, a) in arc.iter().enumerate() {
        let get = |v: &[f64]| v.get(i).map_or(String::new(), |x| format!("{x}"));
        csv.push_str(&format!(
            "{a},{},{},{}\n",
            get(l_mem),
            get(l_laid),
            get(strength)
        ));
    }
    let p = out.join("life.csv");
    std::fs::write(&p, csv).map_err(|e| AppError::io(&p, e))?;
    Ok(())
}

/// `visits.csv`: each visit's storm, weight, damage at the critical node with memory and as laid,
/// deepest trench and wall time.
fn write_visits(
    out: &Path,
    memory: &[VisitResult],
    laid: &[VisitResult],
    fibre: &str,
    i_crit: usize,
) -> Result<(), AppError> {
    let mut csv = String::from(
        "visit,storm,hs,tp,seed,weight,damage_memory,damage_as_laid,deepest_trench,wall_seconds\n",
    );
    for (k, r) in memory.iter().enumerate() {
        let dm = r
            .damage
            .iter()
            .find(|(f, _)| *f == fibre)
            .and_then(|(_, d)| d.get(i_crit))
            .copied()
            .unwrap_or(f64::NAN);
        let dl = laid
            .get(k)
            .and_then(|l| l.damage.iter().find(|(f, _)| *f == fibre))
            .and_then(|(_, d)| d.get(i_crit))
            .map_or(String::new(), |x| format!("{x}"));
        csv.push_str(&format!(
            "{},{},{},{},{},{},{dm},{dl},{},{}\n",
            k + 1,
            r.visit.storm.id,
            r.visit.storm.hs,
            r.visit.storm.tp,
            r.visit.storm.seed.unwrap_or_default(),
            r.visit.weight,
            r.trench.iter().copied().fold(0.0f64, f64::max),
            r.wall_seconds
        ));
    }
    let p = out.join("visits.csv");
    std::fs::write(&p, csv).map_err(|e| AppError::io(&p, e))?;
    Ok(())
}

/// The visits with memory (the serial chain) and, where the scene asks for them, the as-laid
/// visits: on the other threads alongside the chain when `jobs` is 2 or more, after it otherwise.
/// Returns the chain's results, how many of them were resumed, and the as-laid results.
fn both_chains(
    seq: &Sequence,
    (vdir, ldir): (&Path, &Path),
    jobs: usize,
    progress: bool,
    t0: Instant,
) -> Result<(Vec<VisitResult>, usize, Vec<VisitResult>), AppError> {
    let alongside = seq.as_laid && jobs >= 2;
    // Alongside, the chain and the as-laid runs share the cores ([`catena::studies::schedule`]).
    let per_run = threads_per_run(if alongside { jobs } else { 1 });
    let (memory, laid) = std::thread::scope(|sc| {
        let laid =
            alongside.then(|| sc.spawn(|| as_laid(seq, ldir, (jobs - 1, per_run), progress)));
        let memory = chain(seq, vdir, (per_run, progress), t0);
        let laid = laid.map(|h| {
            h.join().unwrap_or_else(|_| {
                Err(AppError::Run {
                    file: seq.file.clone(),
                    message: "the as-laid runs' thread failed".into(),
                })
            })
        });
        (memory, laid)
    });
    let (memory, resumed) = memory?;
    let laid = match laid {
        Some(r) => r?,
        None if seq.as_laid => as_laid(seq, ldir, (1, threads_per_run(1)), progress)?,
        None => Vec::new(),
    };
    Ok((memory, resumed, laid))
}
