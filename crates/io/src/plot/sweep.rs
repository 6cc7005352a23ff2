//! The sweep's figure (`sweep.png`), in the manner of the paper's Figures 9–11: the minimum fatigue
//! life (log scale) against the first parameter that takes more than one value (the first, if none
//! does), one line per value of the others, and beside it the touchdown-zone moment range and the
//! largest penetration against the same parameter. Failed points
//! are left out (and named in `sweep.csv`).

use std::path::Path;

use catena::studies::sweep::{Parameter, Plan, PointSummary};
use catena::AppError;
use plotters::prelude::*;

use super::{init_fonts, pixels, plot_err, write_image, OpaqueGrid};

/// The number a parameter value stands for, if it is one.
fn number(v: &toml::Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

/// A tick label: plain for moderate numbers, `1e5`-style beyond.
fn short(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-2..1e4).contains(&a) {
        let e = a.log10().floor();
        let m = v / 10f64.powf(e);
        if (m - m.round()).abs() < 1e-9 {
            format!("{}e{}", m.round(), e)
        } else {
            format!("{m:.1}e{e}")
        }
    } else {
        format!("{}", (v * 1e3).round() / 1e3)
    }
}

/// A key path with its SI unit, for an axis (the keys the paper's figures sweep; others as they are).
pub fn key_label(key: &str) -> String {
    let unit = match key.rsplit('.').next().unwrap_or(key) {
        "stiffness" => " (N/m/m²)",
        "su0" => " (Pa)",
        "su_gradient" => " (Pa/m)",
        "k_max" | "f_suc" | "lambda_suc" | "lambda_rep" | "a" | "b" => " (—)",
        "time_step" | "duration" => " (s)",
        "element_length" | "od" | "wall" | "hs" => " (m)",
        "tp" => " (s)",
        _ => "",
    };
    format!("{key}{unit}")
}

/// The parameter on the x axis: the first that takes more than one value (a parameter held at one
/// value, such as Figure 11's su0 = 0, would put every point on one vertical), else the first.
fn x_parameter(parameters: &[Parameter]) -> usize {
    parameters
        .iter()
        .position(|p| p.values.len() > 1)
        .unwrap_or(0)
}

/// The sweep's points as series: one per combination of the parameters other than the x axis's
/// (`ix`), in the plan's order, labelled `key = value, …`.
fn series_by_the_others<'p>(
    plan: &Plan,
    points: &'p [PointSummary],
    ix: usize,
) -> Vec<(String, Vec<&'p PointSummary>)> {
    let mut series: Vec<(String, Vec<&PointSummary>)> = Vec::new();
    for p in points {
        let label = plan
            .parameters
            .iter()
            .zip(&p.values)
            .enumerate()
            .filter(|&(i, _)| i != ix)
            .map(|(_, pv)| pv)
            .map(|(par, v)| format!("{} = {v}", par.key))
            .collect::<Vec<_>>()
            .join(", ");
        match series.iter_mut().find(|(l, _)| *l == label) {
            Some((_, v)) => v.push(p),
            None => series.push((label, vec![p])),
        }
    }
    series
}

/// The least and the greatest of some values.
fn least_and_greatest(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(*x), b.max(*x))
        })
}

/// Writes `sweep.png` (nothing to draw when the x axis's parameter is not numeric or no point has
/// a life).
pub fn figure(
    path: &Path,
    plan: &Plan,
    points: &[PointSummary],
    title: &str,
) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let ix = x_parameter(&plan.parameters);
    let series = series_by_the_others(plan, points, ix);
    let xs: Vec<f64> = points
        .iter()
        .filter(|p| p.failed.is_none())
        .filter_map(|p| number(&p.values[ix]))
        .collect();
    if xs.is_empty() {
        return Ok(());
    }
    let (x0, x1) = least_and_greatest(&xs);
    let log_x = x0 > 0.0 && x1 / x0 >= 10.0;
    let colours = [
        RGBColor(20, 90, 200),
        RGBColor(200, 30, 30),
        RGBColor(30, 150, 60),
        RGBColor(150, 80, 180),
        RGBColor(220, 140, 0),
    ];
    let size = (1600, 700);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root.titled(title, ("sans-serif", 24)).map_err(&err)?;
        let areas = root.split_evenly((1, 3));
        let key = &plan.parameters[ix].key;
        type Pick = fn(&PointSummary) -> f64;
        let panels: [(&str, &str, Pick, bool); 3] = [
            (
                "minimum fatigue life",
                "life (years, log scale)",
                |p| p.min_life_years,
                true,
            ),
            (
                "touchdown-zone moment range",
                "largest moment range (kN·m)",
                |p| p.tdz_moment_range / 1e3,
                false,
            ),
            (
                "largest penetration",
                "penetration of the invert (m, positive down)",
                |p| p.max_penetration,
                false,
            ),
        ];
        for (k, (caption, ydesc, pick, log_y)) in panels.into_iter().enumerate() {
            let vals: Vec<f64> = points
                .iter()
                .filter(|p| p.failed.is_none())
                .map(pick)
                .filter(|v| v.is_finite() && (!log_y || *v > 0.0))
                .collect();
            if vals.is_empty() {
                continue;
            }
            let (lo, hi) = least_and_greatest(&vals);
            let pad = if log_y {
                0.0
            } else {
                0.08 * (hi - lo).max(hi.abs() * 0.05 + 1e-12)
            };
            let (xa, xb) = if log_x {
                (x0 / 1.5, x1 * 1.5)
            } else {
                (x0 - 0.05 * (x1 - x0 + 1.0), x1 + 0.05 * (x1 - x0 + 1.0))
            };
            let mut b = ChartBuilder::on(&areas[k]);
            b.caption(caption, ("sans-serif", 20))
                .margin(15)
                .x_label_area_size(45)
                .y_label_area_size(80);
            let points_of = |pts: &Vec<&PointSummary>| -> Vec<(f64, f64)> {
                pts.iter()
                    .filter(|p| p.failed.is_none())
                    .filter_map(|p| Some((number(&p.values[ix])?, pick(p))))
                    .filter(|(_, y)| y.is_finite() && (!log_y || *y > 0.0))
                    .collect()
            };
            macro_rules! draw {
                ($chart:expr) => {{
                    let mut chart = $chart;
                    chart
                        .configure_mesh()
                        .x_desc(key_label(key))
                        .y_desc(ydesc)
                        .x_label_formatter(&|v| short(*v))
                        .y_label_formatter(&|v| short(*v))
                        .opaque_grid()
                        .light_line_style(WHITE)
                        .draw()
                        .map_err(|e| perr(e.to_string()))?;
                    for (j, (label, pts)) in series.iter().enumerate() {
                        let c = colours[j % colours.len()];
                        let xy = points_of(pts);
                        chart
                            .draw_series(super::segments(xy.clone(), c.stroke_width(2)))
                            .map_err(|e| perr(e.to_string()))?
                            .label(if label.is_empty() {
                                "catena".to_string()
                            } else {
                                label.clone()
                            })
                            .legend(move |(x, y)| {
                                PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                            });
                        chart
                            .draw_series(
                                xy.iter().map(|&(x, y)| Circle::new((x, y), 4, c.filled())),
                            )
                            .map_err(|e| perr(e.to_string()))?;
                    }
                    chart
                        .configure_series_labels()
                        .background_style(WHITE.mix(0.85))
                        .border_style(BLACK)
                        .position(SeriesLabelPosition::UpperRight)
                        .draw()
                        .map_err(|e| perr(e.to_string()))?;
                }};
            }
            match (log_x, log_y) {
                (true, true) => draw!(b
                    .build_cartesian_2d((xa..xb).log_scale(), (lo / 2.0..hi * 2.0).log_scale())
                    .map_err(|e| perr(e.to_string()))?),
                (true, false) => draw!(b
                    .build_cartesian_2d((xa..xb).log_scale(), lo - pad..hi + pad)
                    .map_err(|e| perr(e.to_string()))?),
                (false, true) => draw!(b
                    .build_cartesian_2d(xa..xb, (lo / 2.0..hi * 2.0).log_scale())
                    .map_err(|e| perr(e.to_string()))?),
                (false, false) => draw!(b
                    .build_cartesian_2d(xa..xb, lo - pad..hi + pad)
                    .map_err(|e| perr(e.to_string()))?),
            }
        }
    }
    write_image(path, &rgb, size)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parameter(key: &str, values: &[f64]) -> Parameter {
        Parameter {
            key: key.into(),
            values: values.iter().map(|&v| toml::Value::Float(v)).collect(),
        }
    }

    /// Figure 11's full points hold su0 at 0 and vary the gradient: the gradient is the x axis
    /// (with su0 first it put the three points on one vertical); a sweep varying its first
    /// parameter keeps it there, and one varying none draws against the first.
    #[test]
    fn the_x_axis_is_the_first_parameter_that_varies() {
        let su0 = parameter("seabed.su0", &[0.0]);
        let grad = parameter("seabed.su_gradient", &[650.0, 1300.0, 5000.0]);
        assert_eq!(x_parameter(&[su0.clone(), grad.clone()]), 1);
        assert_eq!(x_parameter(&[grad.clone(), su0.clone()]), 0);
        assert_eq!(x_parameter(&[su0.clone(), su0]), 0);
    }
}
