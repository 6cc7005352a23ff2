//! The fatigue study's figures: the life along the line (`life.png`) and each storm's share of
//! the damage (`storms.png`).

use std::path::Path;

use catena::AppError;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{init_fonts, pixels, plot_err, ticks, write_image, OpaqueGrid};
use crate::fatigue::{minimum, Lives};

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
                .x_label_formatter(&ticks(a0, a1))
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .draw()
                .map_err(|e| perr(e.to_string()))?;
            for (j, (name, _, life)) in l.fibres.iter().enumerate() {
                let pts: Vec<(f64, f64)> =
                    sel.iter().map(|&i| (l.arc[i], life[i].min(ymax))).collect();
                let c = colours[j % 2];
                chart
                    .draw_series(super::segments(pts, c.stroke_width(2)))
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
