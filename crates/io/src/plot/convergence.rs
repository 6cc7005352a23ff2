//! The convergence study's figure (`convergence.png`): each key output's error against the wall
//! time of its variant, on log axes.

use std::path::Path;

use catena::studies::convergence::{error_of, Series, Study};
use catena::AppError;
use plotters::prelude::*;

use super::{init_fonts, pixels, plot_err, write_image, OpaqueGrid};
use crate::convergence::a_or;

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
                    .draw_series(super::segments(
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
