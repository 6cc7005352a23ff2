//! The checks: the design check along the line (`design_check.png`), the extremes on probability
//! paper (`extremes.png`) and the strength study (`strength.png`).

use std::path::Path;

use plotters::prelude::*;

use catena::run::DynamicRun;
use catena::AppError;

use super::line::{touchdown_marks, whole_line_marks};
use super::*;

/// The design check (`design_check.png`): each node's largest utilisation over the run with the
/// static state's (functional only) and the limit 1.0, over the whole line and around the touchdown
/// zone; beneath, each node's least effective tension with the static tension (compression below 0).
pub fn design_check(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    let Some(d) = r.output::<catena::run::observers::design::DesignCheck>() else {
        return Ok(());
    };
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let size = (1800, 1100);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let worst = d
            .worst()
            .map(|(i, u)| {
                format!(
                    "largest {u:.3} at {:.1} m, t = {:.1} s",
                    d.arc[i], d.time_of_max[i]
                )
            })
            .unwrap_or_default();
        let title = format!(
            "{} — design check {} over t ≥ {} s: {worst}",
            r.statics.scene.title,
            d.spec.code.name(),
            d.spec.start
        );
        let root = root.titled(&title, ("sans-serif", 18)).map_err(&err)?;
        let areas = root.split_evenly((2, 2));
        let arc = &r.model.line.arc;
        let st = &r.statics.results;
        let line = |v: &[f64], s: f64| -> Vec<(f64, f64)> {
            arc.iter()
                .zip(v)
                .filter(|(_, y)| y.is_finite() && **y != f64::MAX)
                .map(|(a, y)| (*a, y * s))
                .collect()
        };
        let static_u: Vec<f64> = match &d.evaluator {
            Some(ev) => {
                let mut u = vec![0.0; arc.len()];
                ev.along(st, &mut u);
                u
            }
            None => Vec::new(),
        };
        let (red, blue, grey, black) = (
            RGBColor(180, 30, 30),
            RGBColor(20, 90, 200),
            RGBColor(120, 120, 120),
            RGBColor(0, 0, 0),
        );
        let level = |y: f64| vec![(arc[0], y), (arc[arc.len() - 1], y)];
        let utilisation = || {
            vec![
                Labelled {
                    points: line(&d.max, 1.0),
                    colour: blue,
                    label: "largest over the run",
                },
                Labelled {
                    points: line(&static_u, 1.0),
                    colour: grey,
                    label: "static (functional only)",
                },
                Labelled {
                    points: level(1.0),
                    colour: red,
                    label: "limit 1.0",
                },
            ]
        };
        let tension = || {
            vec![
                Labelled {
                    points: line(&d.least_tension, 1e-3),
                    colour: blue,
                    label: "least over the run",
                },
                Labelled {
                    points: line(&st.tension, 1e-3),
                    colour: grey,
                    label: "static",
                },
                Labelled {
                    points: level(0.0),
                    colour: black,
                    label: "zero",
                },
            ]
        };
        let (markers, zoom) = touchdown_marks(r);
        // The zoom takes in the node of the largest utilisation (often a little above the touchdown
        // zone, in the sag bend).
        let zoom = match (zoom, d.worst()) {
            (Some((a, b)), Some((i, _))) => Some((a.min(d.arc[i] - 10.0), b.max(d.arc[i] + 10.0))),
            (z, _) => z,
        };
        let marks: Vec<(f64, &str, RGBColor)> =
            markers.iter().map(|(x, l, c)| (*x, *l, *c)).collect();
        let whole: Vec<(f64, &str, RGBColor)> = whole_line_marks(&markers)
            .iter()
            .map(|(x, l, c)| (*x, *l, *c))
            .collect();
        let xs = "arc length from the top (m)";
        legend_panel(
            &areas[0],
            "utilisation along the line",
            (xs, "utilisation (1)"),
            &utilisation(),
            &whole,
            None,
        )
        .map_err(&perr)?;
        legend_panel(
            &areas[1],
            "utilisation around the touchdown zone and the largest",
            (xs, "utilisation (1)"),
            &utilisation(),
            &marks,
            zoom,
        )
        .map_err(&perr)?;
        legend_panel(
            &areas[2],
            "least effective tension along the line",
            (xs, "T_e (kN)"),
            &tension(),
            &whole,
            None,
        )
        .map_err(&perr)?;
        legend_panel(
            &areas[3],
            "least effective tension around the touchdown zone",
            (xs, "T_e (kN)"),
            &tension(),
            &marks,
            zoom,
        )
        .map_err(&perr)?;
    }
    write_image(path, &rgb, size)
}

/// The extremes on probability paper (`extremes.png`): a row per channel, its up-crossing peaks'
/// excesses on Weibull paper and its block maxima on Gumbel paper, each with its fitted line (a
/// fit that suits the data is a straight line through the points), and the estimates of the target
/// duration's extreme in the caption. `items`: each channel's analysis, record and time step.
pub fn extremes(
    path: &Path,
    title: &str,
    items: &[(&catena::checks::extremes::Extremes, &[f64], f64)],
) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let rows = items.len().max(1);
    let size = (1800, 60 + 420 * rows as u32);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root.titled(title, ("sans-serif", 20)).map_err(&err)?;
        let areas = root.split_evenly((rows, 2));
        let (blue, red) = (RGBColor(20, 90, 200), RGBColor(180, 30, 30));
        for (k, (e, x, dt)) in items.iter().enumerate() {
            let p = catena::checks::extremes::paper(e, x, *dt);
            let side = match e.tail {
                catena::checks::extremes::Tail::Max => "",
                catena::checks::extremes::Tail::Min => " (least, negated)",
            };
            // In the channel's units (kN, kN·m), as the other outputs give them.
            let (scale, unit) = crate::report::channel_units(&e.channel);
            let mpm = |v: Option<f64>| {
                v.map_or("—".to_string(), |v| {
                    crate::report::channel_value(&e.channel, v)
                })
            };
            let unit_of = |what: &str| {
                if unit.is_empty() {
                    what.to_string()
                } else {
                    format!("{what} ({unit})")
                }
            };
            let weibull_x = if unit.is_empty() {
                "ln(peak − mean)".to_string()
            } else {
                format!("ln((peak − mean) / {unit})")
            };
            let gumbel_x = unit_of("block maximum (negated for a least)");
            // Peaks' excesses and block maxima scaled to the units: ln x + ln(scale), x·scale.
            let weibull: (Points, Points) = (
                p.weibull
                    .0
                    .iter()
                    .map(|&(a, b)| (a + scale.ln(), b))
                    .collect(),
                p.weibull
                    .1
                    .iter()
                    .map(|&(a, b)| (a + scale.ln(), b))
                    .collect(),
            );
            let gumbel: (Points, Points) = (
                p.gumbel.0.iter().map(|&(a, b)| (a * scale, b)).collect(),
                p.gumbel.1.iter().map(|&(a, b)| (a * scale, b)).collect(),
            );
            let w_caption = format!(
                "{}{side}: peaks, Weibull paper; MPM {} h: Rayleigh {}, Weibull {}",
                e.channel,
                e.target / 3600.0,
                mpm(Some(e.rayleigh[0])),
                mpm(e.weibull.map(|w| w.1[0]))
            );
            let g_caption = format!(
                "{}{side}: {} s block maxima, Gumbel paper; MPM {}; sample {}",
                e.channel,
                e.gumbel.map_or(0.0, |g| g.0),
                mpm(e.gumbel.map(|g| g.2[0])),
                mpm(Some(e.sample_extreme))
            );
            for (area, (points, line), caption, axes) in [
                (
                    &areas[2 * k],
                    &weibull,
                    w_caption,
                    (weibull_x.as_str(), "ln(−ln(1 − F))"),
                ),
                (
                    &areas[2 * k + 1],
                    &gumbel,
                    g_caption,
                    (gumbel_x.as_str(), "−ln(−ln F)"),
                ),
            ] {
                let ((x0, x1), (y0, y1)) = data_box(points.iter().chain(line).copied(), None);
                let mut chart = framed_chart_sized(area, &caption, axes, (x0, x1), (y0, y1), 15)
                    .map_err(&perr)?;
                chart
                    .draw_series(
                        points
                            .iter()
                            .map(|&(a, b)| Circle::new((a, b), 3, blue.filled())),
                    )
                    .map_err(|e| perr(e.to_string()))?;
                chart
                    .draw_series(super::segments(line.iter().copied(), red.stroke_width(2)))
                    .map_err(|e| perr(e.to_string()))?;
            }
        }
    }
    write_image(path, &rgb, size)
}

/// The strength study (`strength.png`): per storm (a row), the largest utilisation along the line
/// of each seed (thin), their envelope and the static state's with the limit 1.0; beside it, each
/// seed's largest utilisation on Gumbel paper with the fit across the seeds (three or more).
pub fn strength(
    path: &Path,
    title: &str,
    arc: &[f64],
    static_u: &[f64],
    runs: &[catena::studies::strength::RunResult],
    storms: &[catena::studies::strength::StormSummary],
) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let rows = storms.len().max(1);
    let size = (1800, 60 + 460 * rows as u32);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root.titled(title, ("sans-serif", 20)).map_err(&err)?;
        let areas = root.split_evenly((rows, 3));
        let (blue, red, grey, light) = (
            RGBColor(20, 90, 200),
            RGBColor(180, 30, 30),
            RGBColor(90, 90, 90),
            RGBColor(150, 170, 210),
        );
        for (k, s) in storms.iter().enumerate() {
            let mut series = vec![
                Labelled {
                    points: arc
                        .iter()
                        .copied()
                        .zip(s.utilisation_envelope.iter().copied())
                        .collect(),
                    colour: blue,
                    label: "largest over the seeds",
                },
                Labelled {
                    points: arc.iter().copied().zip(static_u.iter().copied()).collect(),
                    colour: grey,
                    label: "static (functional only)",
                },
                Labelled {
                    points: vec![(arc[0], 1.0), (arc[arc.len() - 1], 1.0)],
                    colour: red,
                    label: "limit 1.0",
                },
            ];
            for (j, r) in runs
                .iter()
                .filter(|r| r.error.is_none() && r.storm.id == s.storm.id)
                .enumerate()
            {
                series.push(Labelled {
                    points: arc
                        .iter()
                        .copied()
                        .zip(r.utilisation_max.iter().copied())
                        .collect(),
                    colour: light,
                    label: if j == 0 { "each seed" } else { "" },
                });
            }
            // Each seed's line beneath the envelope.
            series.rotate_left(3);
            let caption = format!(
                "storm {} (Hs {} m, Tp {} s), {} seeds: largest utilisation along the line",
                s.storm.id,
                s.storm.hs,
                s.storm.tp,
                s.seeds.len()
            );
            legend_panel(
                &areas[3 * k],
                &caption,
                ("arc length from the top (m)", "utilisation (1)"),
                &series,
                &[],
                None,
            )
            .map_err(&perr)?;
            // Around the largest (±100 m), without the limit: the spread over the seeds.
            let (i, _) = s
                .utilisation_envelope
                .iter()
                .copied()
                .enumerate()
                .fold((0, 0.0), |b, (i, v)| if v > b.1 { (i, v) } else { b });
            let near = (arc[i] - 100.0, arc[i] + 100.0);
            let close: Vec<Labelled<'_>> = series
                .iter()
                .filter(|l| l.label != "limit 1.0")
                .map(|l| Labelled {
                    points: l.points.clone(),
                    colour: l.colour,
                    label: l.label,
                })
                .collect();
            legend_panel(
                &areas[3 * k + 1],
                &format!("within 100 m of the largest, at {:.1} m", arc[i]),
                ("arc length from the top (m)", "utilisation (1)"),
                &close,
                &[],
                Some(near),
            )
            .map_err(&perr)?;
            let u = &s.across_seeds[0];
            let (points, line) = gumbel_paper(&u.per_seed, u.gumbel.map(|g| g.0));
            let caption = format!(
                "each seed's largest, Gumbel paper: {}",
                u.gumbel
                    .map_or("fewer than 3 seeds: no fit".to_string(), |(_, v)| format!(
                        "MPM {:.4}, quantile {:.4}",
                        v[0], v[1]
                    ))
            );
            let ((x0, x1), (y0, y1)) = data_box(points.iter().chain(&line).copied(), None);
            let mut chart = framed_chart(
                &areas[3 * k + 2],
                &caption,
                ("largest utilisation of a seed", "−ln(−ln F)"),
                (x0, x1),
                (y0, y1),
            )
            .map_err(&perr)?;
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|&(a, b)| Circle::new((a, b), 5, blue.filled())),
                )
                .map_err(|e| perr(e.to_string()))?;
            chart
                .draw_series(super::segments(line.iter().copied(), red.stroke_width(2)))
                .map_err(|e| perr(e.to_string()))?;
        }
    }
    write_image(path, &rgb, size)
}

/// Values on Gumbel paper, `(v, −ln(−ln F))` at the plotting positions `F = i/(n + 1)` of the
/// sorted values, and the fitted line between the least and the greatest (none without a fit).
fn gumbel_paper(values: &[f64], fit: Option<catena::checks::extremes::Gumbel>) -> (Points, Points) {
    let mut m = values.to_vec();
    m.sort_by(f64::total_cmp);
    let n = m.len() as f64;
    let points: Vec<(f64, f64)> = m
        .iter()
        .enumerate()
        .map(|(i, v)| (*v, -(-((i as f64 + 1.0) / (n + 1.0)).ln()).ln()))
        .collect();
    let line: Vec<(f64, f64)> = match (fit, m.first(), m.last()) {
        (Some(g), Some(a), Some(b)) => [*a, *b]
            .iter()
            .map(|v| (*v, (v - g.location) / g.scale))
            .collect(),
        _ => Vec::new(),
    };
    (points, line)
}
