//! The fatigue study's outputs: `fatigue.h5` (each storm's damage per node and fibre, the annual
//! damage and the life), `life.csv` (arc, life per fibre, minimum life), `summary.json` (minimum
//! life, where, each storm's share there), `life.png` (life along the arc, log scale, with the
//! static touchdown point and the zone the touchdown point visits) and `storms.png` (the shares).

use std::fmt::Write as _;
use std::path::Path;

use catena::studies::fatigue_study::{annual_damage, shares, StormResult, Study};
use catena::AppError;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde_json::{json, Value};

use crate::h5::{attr, h5err, vector};
use crate::plot::{init_fonts, pixels, plot_err, write_image, OpaqueGrid};

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

/// `life.png`: life along the arc (log scale), the whole line and the touchdown zone, with the
/// static touchdown point marked.
pub fn life_png(
    path: &Path,
    l: &Lives,
    touchdown: Option<f64>,
    title: &str,
) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let size = (1600, 900);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root.titled(title, ("sans-serif", 24)).map_err(&err)?;
        let areas = root.split_evenly((1, 2));
        let colours = [RGBColor(20, 90, 200), RGBColor(200, 30, 30)];
        let finite: Vec<f64> = l
            .fibres
            .iter()
            .flat_map(|(_, _, life)| life.iter().copied())
            .filter(|v| v.is_finite() && *v > 0.0)
            .collect();
        let lo = finite.iter().copied().fold(f64::INFINITY, f64::min);
        let (i_min, _, _) = minimum(l).unwrap_or((0, 1.0, String::new()));
        let centre = l.arc[i_min];
        for (k, (a0, a1, caption)) in [
            (
                0.0,
                *l.arc.last().unwrap_or(&1.0),
                "life along the line (log scale)".to_string(),
            ),
            (
                centre - 100.0,
                centre + 100.0,
                format!("touchdown zone (±100 m about the minimum at {centre:.1} m)"),
            ),
        ]
        .into_iter()
        .enumerate()
        {
            let sel: Vec<usize> = (0..l.arc.len())
                .filter(|&i| l.arc[i] >= a0 && l.arc[i] <= a1)
                .collect();
            let ymin = lo.max(1e-6) * 0.5;
            let ymax = sel
                .iter()
                .flat_map(|&i| l.fibres.iter().map(move |(_, _, life)| life[i]))
                .filter(|v| v.is_finite())
                .fold(ymin * 10.0, f64::max)
                .min(ymin * 1e8);
            let mut chart = ChartBuilder::on(&areas[k])
                .caption(&caption, ("sans-serif", 20))
                .margin(15)
                .x_label_area_size(45)
                .y_label_area_size(80)
                .build_cartesian_2d(a0..a1, (ymin..ymax).log_scale())
                .map_err(|e| perr(e.to_string()))?;
            chart
                .configure_mesh()
                .opaque_grid()
                .x_desc("arc length from the top (m)")
                .y_desc("fatigue life (years)")
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .draw()
                .map_err(|e| perr(e.to_string()))?;
            for (j, (name, _, life)) in l.fibres.iter().enumerate() {
                let pts: Vec<(f64, f64)> =
                    sel.iter().map(|&i| (l.arc[i], life[i].min(ymax))).collect();
                let c = colours[j % 2];
                chart
                    .draw_series(LineSeries::new(pts, c.stroke_width(2)))
                    .map_err(|e| perr(e.to_string()))?
                    .label(format!("{name} fibre"))
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                    });
            }
            if let Some(td) = touchdown.filter(|t| *t >= a0 && *t <= a1) {
                chart
                    .draw_series(LineSeries::new(
                        vec![(td, ymin), (td, ymax)],
                        BLACK.stroke_width(1),
                    ))
                    .map_err(|e| perr(e.to_string()))?
                    .label("static touchdown point")
                    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()
                .map_err(|e| perr(e.to_string()))?;
        }
    }
    write_image(path, &rgb, size)
}

/// `storms.png`: each storm's share of the damage at the critical point.
pub fn storms_png(path: &Path, shares: &[(i64, f64)], title: &str) -> Result<(), AppError> {
    init_fonts();
    let perr = plot_err::<String>(path);
    let size = (1400, 700);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let n = shares.len().max(1) as i64;
        let top = shares.iter().map(|s| s.1).fold(0.0, f64::max).max(1e-3) * 1.15 * 100.0;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d((0i64..n - 1).into_segmented(), 0.0..top)
            .map_err(|e| perr(e.to_string()))?;
        chart
            .configure_mesh()
            .opaque_grid()
            .disable_x_mesh()
            .x_desc("storm id (in the table's order)")
            .y_desc("share of the damage at the critical point (%)")
            .x_labels(shares.len().max(1))
            .x_label_formatter(&|v| match v {
                SegmentValue::CenterOf(i) => shares
                    .get(*i as usize)
                    .map_or(String::new(), |s| s.0.to_string()),
                _ => String::new(),
            })
            .label_style(("sans-serif", 15))
            .draw()
            .map_err(|e| perr(e.to_string()))?;
        let blue = RGBColor(20, 90, 200);
        chart
            .draw_series(shares.iter().enumerate().map(|(i, s)| {
                let mut bar = Rectangle::new(
                    [
                        (SegmentValue::Exact(i as i64), 0.0),
                        (SegmentValue::Exact(i as i64 + 1), s.1 * 100.0),
                    ],
                    blue.filled(),
                );
                bar.set_margin(0, 0, 10, 10);
                bar
            }))
            .map_err(|e| perr(e.to_string()))?;
        // Each bar's share written above it.
        chart
            .draw_series(shares.iter().enumerate().map(|(i, s)| {
                Text::new(
                    format!("{:.1} %", s.1 * 100.0),
                    (SegmentValue::CenterOf(i as i64), s.1 * 100.0 + 0.02 * top),
                    ("sans-serif", 15)
                        .into_font()
                        .into_text_style(&root)
                        .pos(Pos::new(HPos::Center, VPos::Bottom)),
                )
            }))
            .map_err(|e| perr(e.to_string()))?;
    }
    write_image(path, &rgb, size)
}
