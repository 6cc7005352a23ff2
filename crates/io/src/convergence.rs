//! The convergence study's outputs: `convergence.csv` (a row per run: its settings, cost, and each
//! key output with its error), `convergence.json`, the text summary and `convergence.png` (|error|
//! against wall time, log–log).

use std::fmt::Write as _;
use std::path::Path;

use catena::studies::convergence::{error_of, Series, SeriesAnalysis, Study, VariantRun};
use catena::AppError;
use plotters::prelude::*;
use serde_json::json;

use crate::plot::{init_fonts, pixels, plot_err, write_image, OpaqueGrid};

/// The table as CSV: a row per run; per output its value and its error (mesh series or Δt series).
pub fn csv(st: &Study) -> String {
    let mut s = String::from(
        "series,mesh_factor,dt_factor,elements,min_element_length_m,time_step_s,steps,newton_iterations,step_cuts,wall_s",
    );
    for o in &st.outputs {
        let unit = o.unit.replace('·', "");
        let _ = write!(s, ",{}_{unit},{}_error_percent", o.id, o.id);
    }
    s.push('\n');
    let mut rows: Vec<(Series, &VariantRun)> = Vec::new();
    for ser in [Series::Mesh, Series::TimeStep] {
        rows.extend(st.series(ser).into_iter().map(|r| (ser, r)));
    }
    for (ser, r) in rows {
        let _ = write!(
            s,
            "{},{},{},{},{},{},{},{},{},{:.4}",
            ser.name(),
            r.mesh_factor,
            r.dt_factor,
            r.elements,
            r.min_element_length,
            r.dt,
            r.steps,
            r.newton_iterations,
            r.step_cuts,
            r.wall_seconds
        );
        for (k, v) in r.values.iter().enumerate() {
            let (em, ed) = error_of(st, k, r);
            let e = if ser == Series::Mesh { em } else { ed };
            // An unknown value or error (a failed run, a series of one factor) is an empty cell,
            // never `NaN`.
            let cell = |x: f64| {
                if x.is_finite() {
                    x.to_string()
                } else {
                    String::new()
                }
            };
            let _ = write!(s, ",{},{}", cell(*v), cell(e));
        }
        s.push('\n');
    }
    s
}

/// The study as JSON.
pub fn to_json(st: &Study) -> serde_json::Value {
    let num = |v: f64| {
        if v.is_finite() {
            json!(v)
        } else {
            serde_json::Value::Null
        }
    };
    let an = |a: &SeriesAnalysis| {
        json!({
            "factors": a.factors,
            "values": a.values.iter().map(|v| num(*v)).collect::<Vec<_>>(),
            "observed_order": a.order,
            "richardson": a.extrapolated,
            "gci_percent": a.gci_percent,
            "reference": num(a.reference),
            "reference_kind": a.reference_kind,
            "errors_percent": a.errors_percent.iter().map(|v| num(*v)).collect::<Vec<_>>(),
        })
    };
    json!({
        "case": st.file,
        "title": st.title,
        "catena_version": env!("CARGO_PKG_VERSION"),
        "runs": st.runs.iter().map(|r| json!({
            "mesh_factor": r.mesh_factor, "dt_factor": r.dt_factor, "elements": r.elements,
            "min_element_length": r.min_element_length, "time_step": r.dt, "steps": r.steps,
            "newton_iterations": r.newton_iterations, "step_cuts": r.step_cuts,
            "wall_seconds": r.wall_seconds,
            "values": r.values.iter().map(|v| num(*v)).collect::<Vec<_>>(),
            "error": r.error.as_ref().map(ToString::to_string),
        })).collect::<Vec<_>>(),
        "outputs": st.outputs.iter().zip(&st.analyses).map(|(o, (m, d))| json!({
            "id": o.id, "label": o.label, "unit": o.unit,
            "mesh": an(m), "time_step": an(d),
        })).collect::<Vec<_>>(),
    })
}

/// The study as text.
pub fn summary_text(st: &Study) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "{} — convergence study ({})", st.title, st.file);
    for ser in [Series::Mesh, Series::TimeStep] {
        let runs = st.series(ser);
        let _ = writeln!(
            t,
            "\n{}:",
            match ser {
                Series::Mesh => "element length refined (time step as written)",
                Series::TimeStep => "time step refined (mesh as written)",
            }
        );
        let _ = write!(
            t,
            "  {:>7} {:>8} {:>9} {:>8} {:>5} {:>8}",
            "factor", "elements", "min el m", "dt s", "cuts", "wall s"
        );
        for o in &st.outputs {
            let _ = write!(t, " | {:>24}", format!("{} ({})", o.id, o.unit));
        }
        t.push('\n');
        for r in &runs {
            let f = if ser == Series::Mesh {
                r.mesh_factor
            } else {
                r.dt_factor
            };
            let _ = write!(
                t,
                "  {:>7} {:>8} {:>9.4} {:>8.4} {:>5} {:>8.2}",
                format!("x{f}"),
                r.elements,
                r.min_element_length,
                r.dt,
                r.step_cuts,
                r.wall_seconds
            );
            for k in 0..st.outputs.len() {
                let (em, ed) = error_of(st, k, r);
                let e = if ser == Series::Mesh { em } else { ed };
                if e.is_finite() {
                    let _ = write!(t, " | {:>12.4} {:>+10.4}%", r.values[k], e);
                } else {
                    let _ = write!(t, " | {:>12.4} {:>11}", r.values[k], "unknown");
                }
            }
            if r.error.is_some() {
                t.push_str("  STOPPED EARLY");
            }
            t.push('\n');
        }
        let _ = write!(t, "  {:>58}", "reference (order p, GCI)");
        for (m, d) in &st.analyses {
            let a = if ser == Series::Mesh { m } else { d };
            let tag = match (a.order, a.gci_percent) {
                (Some(p), Some(g)) => format!("R p={p:.2} GCI {g:.3}%"),
                (Some(p), None) => format!("R p={p:.2}"),
                _ => a.reference_kind.into(),
            };
            let _ = write!(t, " | {:>12.4} {:>11}", a.reference, tag);
        }
        t.push('\n');
    }
    if let Some(b) = st.base() {
        let _ = writeln!(
            t,
            "\nthe scene as written ({} elements, dt {} s, {:.2} s): estimated error = |mesh| + |time step|:",
            b.elements, b.dt, b.wall_seconds
        );
        for (k, o) in st.outputs.iter().enumerate() {
            let (em, ed) = error_of(st, k, b);
            let pct = |e: f64| {
                if e.is_finite() {
                    format!("{e:+.4} %")
                } else {
                    "unknown".into()
                }
            };
            let together = if em.is_finite() && ed.is_finite() {
                format!("together ≤ {:.4} %", em.abs() + ed.abs())
            } else {
                "together unknown (refine the unknown one below the scene's own level)".into()
            };
            let _ = writeln!(
                t,
                "  {:<34} {:>12.4} {:<5} mesh {}, time step {}, {together}",
                o.label,
                b.values[k],
                o.unit,
                pct(em),
                pct(ed),
            );
        }
    }
    for r in &st.runs {
        if let Some(e) = &r.error {
            let _ = writeln!(
                t,
                "run x{} mesh, x{} dt stopped early: {e}",
                r.mesh_factor, r.dt_factor
            );
        }
    }
    t
}

/// The plot: per output, |error| (log) against wall time (log), the mesh series and the Δt series.
pub fn plot(path: &Path, st: &Study) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let n = st.outputs.len();
    let cols = n.clamp(1, 3);
    let rows = n.div_ceil(cols).max(1);
    let size = (680 * cols as u32, 480 * rows as u32 + 50);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root
        .titled(
            &format!(
                "{}: error against wall time (blue: element length, orange: time step; labels: factor)",
                st.title
            ),
            ("sans-serif", 22),
        )
        .map_err(&err)?;
        let areas = root.split_evenly((rows, cols));
        let blue = RGBColor(20, 90, 200);
        let orange = RGBColor(230, 120, 20);
        for (k, o) in st.outputs.iter().enumerate() {
            // Per series: (wall time, |error|, factor) points and a colour.
            let mut series: Vec<(Vec<Pt>, RGBColor)> = Vec::new();
            for (ser, c) in [(Series::Mesh, blue), (Series::TimeStep, orange)] {
                let pts: Vec<(f64, f64, f64)> = st
                    .series(ser)
                    .iter()
                    .filter_map(|r| {
                        let (em, ed) = error_of(st, k, r);
                        let (e, f) = if ser == Series::Mesh {
                            (em, r.mesh_factor)
                        } else {
                            (ed, r.dt_factor)
                        };
                        (e.is_finite() && e.abs() > 0.0 && r.wall_seconds > 0.0).then_some((
                            r.wall_seconds,
                            e.abs(),
                            f,
                        ))
                    })
                    .collect();
                series.push((pts, c));
            }
            let all = series.iter().flat_map(|(v, _)| v.iter());
            let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
            for &(x, y, _) in all {
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
            if !x0.is_finite() {
                (x0, x1, y0, y1) = (0.1, 1.0, 1e-3, 1.0);
            }
            let a = (a_or(&st.analyses[k].0), a_or(&st.analyses[k].1));
            let caption = format!("{} ({}); ref.: mesh {}, dt {}", o.label, o.unit, a.0, a.1);
            let mut chart = ChartBuilder::on(&areas[k])
                .caption(caption, ("sans-serif", 15))
                .margin(12)
                .x_label_area_size(45)
                .y_label_area_size(75)
                .build_cartesian_2d(
                    (x0 / 1.5..x1 * 1.5)
                        .log_scale()
                        .with_key_points(one_two_five(x0 / 1.5, x1 * 1.5)),
                    (y0 / 3.0..y1 * 3.0)
                        .log_scale()
                        .with_key_points(one_two_five(y0 / 3.0, y1 * 3.0)),
                )
                .map_err(&err)?;
            chart
                .configure_mesh()
                .opaque_grid()
                .x_desc("wall time of the run (s)")
                .y_desc("|error| (%)")
                .x_labels(6)
                .y_labels(6)
                .x_label_formatter(&|v| short(*v))
                .y_label_formatter(&|v| short(*v))
                .max_light_lines(1)
                .label_style(("sans-serif", 13))
                .draw()
                .map_err(&err)?;
            for (pts, c) in &series {
                chart
                    .draw_series(LineSeries::new(
                        pts.iter().map(|p| (p.0, p.1)),
                        c.stroke_width(2),
                    ))
                    .map_err(&err)?;
                chart
                    .draw_series(pts.iter().map(|p| {
                        EmptyElement::at((p.0, p.1))
                            + Circle::new((0, 0), 4, c.filled())
                            + Text::new(
                                format!("x{}", p.2),
                                (7, -16),
                                ("sans-serif", 14).into_font().color(c),
                            )
                    }))
                    .map_err(&err)?;
            }
        }
    }
    write_image(path, &rgb, size)
}

/// Axis key points 1, 2, 5 × 10ᵏ within `[lo, hi]`.
fn one_two_five(lo: f64, hi: f64) -> Vec<f64> {
    let mut v = Vec::new();
    let mut k = lo.log10().floor() as i32;
    while 10f64.powi(k) <= hi && k < 300 {
        for m in [1.0, 2.0, 5.0] {
            let x = m * 10f64.powi(k);
            if x >= lo && x <= hi {
                v.push(x);
            }
        }
        k += 1;
    }
    v
}

/// A short axis label: `0.001`, `0.5`, `2`, `30`.
fn short(v: f64) -> String {
    if v <= 0.0 || !v.is_finite() {
        return String::new();
    }
    let decimals = (-v.log10()).ceil().max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A plotted point: (wall time s, |error| %, factor).
type Pt = (f64, f64, f64);

fn a_or(a: &SeriesAnalysis) -> String {
    match (a.order, a.reference_kind) {
        (Some(p), _) => format!("Richardson p={p:.1}"),
        (None, "finest") => "finest".into(),
        _ => "none".into(),
    }
}
