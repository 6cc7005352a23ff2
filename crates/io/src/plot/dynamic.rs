//! A run in time: the envelopes and the top tension history (`dynamic.png`) and the gauges
//! (`gauges.png`).

use std::path::Path;

use plotters::prelude::*;

use catena::run::DynamicRun;
use catena::AppError;

use super::line::{touchdown_marks, whole_line_marks};
use super::*;

/// Envelopes and ranges along the line, and the top tension history.
pub fn dynamic(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    dynamic_on(path, r, None)
}

/// [`dynamic`] drawn on `canvas` (made ahead, see [`Canvas`]).
pub fn dynamic_on(path: &Path, r: &DynamicRun, canvas: Option<Canvas>) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let size = DYNAMIC_SIZE;
    let mut rgb = pixels(size, canvas);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let title = format!(
            "{} — dynamics, envelopes over t ≥ {} s",
            r.statics.scene.title, r.spec.envelope_start
        );
        let root = root.titled(&title, ("sans-serif", 22)).map_err(&err)?;
        let areas = root.split_evenly((3, 2));
        let arc = &r.model.line.arc;
        let e = &r.envelopes;
        let line = |v: &[f64], s: f64| -> Vec<(f64, f64)> {
            arc.iter()
                .zip(v)
                .filter(|(_, y)| y.is_finite())
                .map(|(a, y)| (*a, y * s))
                .collect()
        };
        let red = RGBColor(180, 30, 30);
        let blue = RGBColor(20, 90, 200);
        let grey = RGBColor(120, 120, 120);
        let lab = |points, colour, label| Labelled {
            points,
            colour,
            label,
        };
        let (markers, zoom) = touchdown_marks(r);
        let moments = || {
            vec![
                lab(line(&e.moment.max, 1e-3), blue, "maximum"),
                lab(line(&e.moment.min, 1e-3), red, "minimum"),
                lab(line(&r.statics.results.moment, 1e-3), grey, "static"),
            ]
        };
        let xs = "arc length from the top (m)";
        legend_panel(
            &areas[0],
            "bending moment envelope",
            (xs, "M (kN·m), negative = sag"),
            &moments(),
            &whole_line_marks(&markers),
            None,
        )
        .map_err(&perr)?;
        legend_panel(
            &areas[1],
            "touchdown zone: bending moment envelope (zoomed)",
            (xs, "M (kN·m), negative = sag"),
            &moments(),
            &markers,
            zoom,
        )
        .map_err(&perr)?;
        legend_panel(
            &areas[2],
            "bending moment range (max − min)",
            (xs, "ΔM (kN·m)"),
            &[lab(line(&e.moment.range(), 1e-3), red, "range")],
            &whole_line_marks(&markers),
            None,
        )
        .map_err(&perr)?;
        // Clear of the seabed by more than two diameters is drawn at −2D, so that the penetration
        // (millimetres to decimetres) stays readable.
        let od = r.model.line.node_od[r.model.line.nodes() - 1];
        let pen = |v: &[f64]| -> Vec<(f64, f64)> {
            line(v, 1.0)
                .into_iter()
                .map(|(a, y)| (a, y.max(-2.0 * od)))
                .collect()
        };
        legend_panel(
        &areas[3],
        "touchdown zone: penetration of the invert (zoomed; clear by more than 2D drawn at −2D)",
        (xs, "penetration (m), positive down"),
        &[
            lab(pen(&e.penetration.max), blue, "maximum"),
            lab(pen(&e.penetration.min), red, "minimum"),
            lab(pen(&r.statics.results.penetration), grey, "static"),
        ],
        &markers,
        zoom,
    )
    .map_err(&perr)?;
        legend_panel(
            &areas[4],
            "effective tension envelope",
            (xs, "T_e (kN)"),
            &[
                lab(line(&e.tension.max, 1e-3), blue, "maximum"),
                lab(line(&e.tension.min, 1e-3), red, "minimum"),
                lab(line(&r.statics.results.tension, 1e-3), grey, "static"),
            ],
            &whole_line_marks(&markers),
            None,
        )
        .map_err(&perr)?;
        let th: Vec<(f64, f64)> = r
            .top
            .t
            .iter()
            .zip(&r.top.top_tension)
            .map(|(t, v)| (*t, v * 1e-3))
            .collect();
        // A long record (over 200 s): the whole (a band per pixel column) and beside it the 100 s
        // around its largest value; a short one across the panel.
        let (whole, window) = if wants_window(&th) {
            let (w, n) = areas[5].split_horizontally(areas[5].dim_in_pixel().0 * 3 / 5);
            (w, Some(n))
        } else {
            (areas[5].clone(), None)
        };
        legend_panel(
            &whole,
            "top tension",
            ("time (s)", "T_top (kN)"),
            &[lab(th.clone(), blue, "top effective tension")],
            &[(r.spec.envelope_start, "envelopes start", grey)],
            None,
        )
        .map_err(&perr)?;
        if let Some(window) = window {
            let (near, _) = window_around_peak(&th, WINDOW);
            lines_panel(
                &window,
                "100 s around the largest top tension",
                ("time (s)", "T_top (kN)"),
                &[lab(near, blue, "")],
                &[],
                None,
                false,
            )
            .map_err(&perr)?;
        }
    }
    write_image(path, &rgb, size)
}

/// The gauges' plot. For a pull-up and lay-down (staged top motion): bending moment against the
/// top height, rising top (pull-up) red, falling (lay-down) blue, still grey — the manner of the
/// paper's Figures 7 and 8. For any other motion: each gauge's moment time history, with the
/// envelopes' start marked.
pub fn gauges(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    let staged = matches!(r.spec.motion, Some(catena_fe::motion::TopMotion::Staged(_)));
    if staged {
        gauges_pull_up(path, r)
    } else {
        gauges_history(path, r)
    }
}

/// Each gauge's bending moment against time (up to three gauges, one panel each).
fn gauges_history(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    init_fonts();
    let perr = plot_err::<String>(path);
    let ng = r.spec.gauges.len().min(3);
    let size = (1600, 380 * ng.max(1) as u32);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let areas = root.split_evenly((ng.max(1), 1));
        for (k, g) in r.spec.gauges.iter().enumerate().take(3) {
            let pts: Vec<(f64, f64)> = r
                .top
                .t
                .iter()
                .zip(&r.gauges.traces[k].moment)
                .map(|(t, m)| (*t, m * 1e-3))
                .collect();
            let caption = format!(
                "{}: gauge {} at arc length {:.2} m from the top",
                r.statics.scene.title, g.name, g.arc
            );
            legend_panel(
                &areas[k],
                &caption,
                ("time (s)", "bending moment (kN·m), negative = sag"),
                &[Labelled {
                    points: pts,
                    colour: RGBColor(20, 90, 200),
                    label: "bending moment",
                }],
                &[(
                    r.spec.envelope_start,
                    "envelopes start",
                    RGBColor(120, 120, 120),
                )],
                None,
            )
            .map_err(&perr)?;
        }
    }
    write_image(path, &rgb, size)
}

#[allow(clippy::needless_range_loop)]
fn gauges_pull_up(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    init_fonts();
    let perr = plot_err::<String>(path);
    let ng = r.spec.gauges.len();
    let size = (900 * ng.min(3) as u32, 750);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let areas = root.split_evenly((1, ng.min(3)));
        let h = &r.top;
        for (k, g) in r.spec.gauges.iter().enumerate().take(3) {
            let gm = &r.gauges.traces[k].moment;
            let mut up = Vec::new();
            let mut down = Vec::new();
            let mut still = Vec::new();
            for i in 1..h.t.len() {
                let dz = h.top_z[i] - h.top_z[i - 1];
                let p = (h.top_z[i], gm[i] * 1e-3);
                if dz > 1e-9 {
                    up.push(p);
                } else if dz < -1e-9 {
                    down.push(p);
                } else {
                    still.push(p);
                }
            }
            let mut series = vec![(up, RGBColor(200, 30, 30)), (down, RGBColor(20, 90, 200))];
            let at_rest = !still.is_empty();
            if at_rest {
                series.push((still, RGBColor(140, 140, 140)));
            }
            let caption = format!(
                "{}: gauge {} (arc {:.2} m): red pull-up, blue lay-down{}",
                r.statics.scene.title,
                g.name,
                g.arc,
                if at_rest { ", grey top at rest" } else { "" }
            );
            marked_panel(
                &areas[k],
                &caption,
                "top height above the mudline (m)",
                "bending moment (kN·m)",
                &series,
                Marks::Points,
            )
            .map_err(&perr)?;
        }
    }
    write_image(path, &rgb, size)
}
