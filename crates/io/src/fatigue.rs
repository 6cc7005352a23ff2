//! The fatigue study's outputs: `fatigue.h5` (each storm's damage per node and fibre, the annual
//! damage and the life), `life.csv` (arc, life per fibre, minimum life), `summary.json` (minimum
//! life, where, each storm's share there), `life.png` (life along the arc, log scale, with the
//! static touchdown point and the zone the touchdown point visits) and `storms.png` (the shares).

use std::fmt::Write as _;
use std::path::Path;

use catena::studies::fatigue_study::{annual_damage, shares, StormResult, Study};
use catena::AppError;
use serde_json::{json, Value};

use crate::h5::{attr, h5err, vector};

/// The study's numbers, per fibre: annual damage and life at every node.
#[derive(Debug, Clone)]
pub struct Lives {
    /// Arc length from the top, m.
    pub arc: Vec<f64>,
    /// Per fibre: name, annual damage, life (years).
    pub fibres: Vec<(String, Vec<f64>, Vec<f64>)>,
}

/// The lives of a study's results.
pub fn lives(study: &Study, results: &[StormResult]) -> Lives {
    let arc = study.base.model.arc.clone();
    let fibres = study
        .fibres()
        .iter()
        .map(|f| {
            let d = annual_damage(results, f.name());
            let life = d
                .iter()
                .map(|x| if *x > 0.0 { 1.0 / x } else { f64::INFINITY })
                .collect();
            (f.name().to_string(), d, life)
        })
        .collect();
    Lives { arc, fibres }
}

/// `(node, life)` of the smallest life over the fibres.
pub fn minimum(l: &Lives) -> Option<(usize, f64, String)> {
    let mut best: Option<(usize, f64, String)> = None;
    for (name, _, life) in &l.fibres {
        for (i, v) in life.iter().enumerate() {
            if best.as_ref().is_none_or(|b| *v < b.1) {
                best = Some((i, *v, name.clone()));
            }
        }
    }
    best
}

/// `life.csv`: `arc`, one `life_<fibre>` per fibre, `life_min` (years).
pub fn life_csv(l: &Lives) -> String {
    let mut s = String::from("arc");
    for (n, _, _) in &l.fibres {
        let _ = write!(s, ",life_{n}");
    }
    s.push_str(",life_min\n");
    for i in 0..l.arc.len() {
        let _ = write!(s, "{}", l.arc[i]);
        let mut m = f64::INFINITY;
        for (_, _, life) in &l.fibres {
            let _ = write!(s, ",{}", life[i]);
            m = m.min(life[i]);
        }
        let _ = writeln!(s, ",{m}");
    }
    s
}

/// `summary.json`.
pub fn summary_json(
    study: &Study,
    results: &[StormResult],
    l: &Lives,
    touchdown: Option<f64>,
    wall: f64,
) -> Value {
    let num = crate::report::num;
    let min = minimum(l);
    let (i, life, fibre) = min.clone().unwrap_or((0, f64::NAN, String::new()));
    let share: Vec<Value> = shares(results, &fibre, i)
        .into_iter()
        .map(|(id, s)| json!({ "id": id, "share": s }))
        .collect();
    let design = study
        .storms
        .first()
        .and_then(|(_, s)| s.dynamic.as_ref())
        .and_then(|d| d.fatigue.as_ref())
        .and_then(|f| f.design_factor);
    json!({
        "catena_version": catena::run::checkpoint::VERSION,
        "study": study.file,
        "scene": study.base.file,
        "storms": results.len(),
        "failed_storms": results.iter().filter(|r| r.error.is_some()).map(|r| r.storm.id).collect::<Vec<_>>(),
        "record": study.record,
        "transient": study.transient,
        "min_life_years": num(life),
        "min_life_years_with_design_factor": design.map(|d| num(life / d)),
        "min_life_arc": l.arc.get(i).copied(),
        "min_life_fibre": fibre,
        "static_touchdown_arc": touchdown,
        "storm_shares": share,
        "wall_seconds": wall,
        "storm_wall_seconds": results.iter().map(|r| r.wall_seconds).sum::<f64>(),
    })
}

/// `fatigue.h5`.
pub fn write_h5(path: &Path, results: &[StormResult], l: &Lives) -> Result<(), AppError> {
    let err = h5err(path);
    let f = hdf5::File::create(path).map_err(&err)?;
    attr(&f, "catena_version", catena::run::checkpoint::VERSION).map_err(&err)?;
    vector(&f, "arc", &l.arc, "m").map_err(&err)?;
    for (name, d, life) in &l.fibres {
        vector(&f, &format!("annual_damage_{name}"), d, "1/year").map_err(&err)?;
        vector(&f, &format!("life_{name}"), life, "year").map_err(&err)?;
    }
    let g = f.create_group("storms").map_err(&err)?;
    for r in results {
        let s = g.create_group(&r.storm.id.to_string()).map_err(&err)?;
        for (k, v) in [
            ("hs", r.storm.hs),
            ("tp", r.storm.tp),
            ("probability", r.storm.probability),
            ("counted_seconds", r.counted_seconds),
        ] {
            crate::h5::num_attr(&s, k, v).map_err(&err)?;
        }
        for (name, d) in &r.damage {
            vector(
                &s,
                &format!("damage_{name}"),
                d,
                "1 (over the counted record)",
            )
            .map_err(&err)?;
        }
    }
    f.flush().map_err(&err)?;
    Ok(())
}
