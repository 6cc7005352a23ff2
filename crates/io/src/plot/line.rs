//! The line along its arc: the static configuration (`static.png`) and the range graphs
//! (`ranges.png`), with their markers (touchdown, sections).

use std::path::Path;

use plotters::prelude::*;

use catena::run::DynamicRun;
use catena::AppError;

use super::*;

/// The static configuration: shape (to scale), bending moment, effective tension and penetration
/// along the arc length, the touchdown point marked, and the touchdown zone (±30 m) zoomed.
pub fn static_line(
    path: &Path,
    title: &str,
    model: &catena_fe::model::LineModel,
    r: &catena_fe::statics::LineResults,
) -> Result<(), AppError> {
    let arc = &model.arc;
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let size = (1600, 1500);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root.titled(title, ("sans-serif", 24)).map_err(&err)?;
        let areas = root.split_evenly((3, 2));
        let blue = RGBColor(20, 90, 200);
        let n = arc.len();
        let shape: Vec<(f64, f64)> = (0..n).map(|i| (r.x[i], r.z[i])).collect();
        // The mudline under the line: flat, or the scene's profile (its points within the line's span).
        let (x0, x1) = (
            r.x.iter().copied().fold(f64::INFINITY, f64::min),
            r.x.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let mut mudline = vec![(x0, model.mudline_at(x0).0)];
        mudline.extend(
            model
                .mudline_profile
                .iter()
                .filter(|p| p.0 > x0 && p.0 < x1)
                .copied(),
        );
        mudline.push((x1, model.mudline_at(x1).0));
        let by_arc = |v: &[f64], scale: f64| -> Vec<(f64, f64)> {
            (0..n).map(|i| (arc[i], v[i] * scale)).collect()
        };
        scaled_panel(
            &areas[0],
            "configuration, to scale",
            "x from the anchor (m)",
            "z above the mudline datum (m)",
            &[(mudline, RGBColor(140, 100, 40)), (shape, blue)],
        )
        .map_err(&perr)?;
        let tdp = catena_fe::statics::touchdown_arc(arc, &r.penetration);
        let mut markers: Vec<Marker> = tdp
            .map(|a| (a, "touchdown point", RGBColor(20, 140, 60)))
            .into_iter()
            .collect();
        markers.extend(section_marks(model));
        let zoom = tdp.map(|a| (a - 30.0, a + 30.0));
        let xs = "arc length from the top (m)";
        let one = |points, colour, label| {
            [Labelled {
                points,
                colour,
                label,
            }]
        };
        let red = RGBColor(180, 30, 30);
        let green = RGBColor(20, 150, 40);
        let moment = one(by_arc(&r.moment, 1e-3), red, "static bending moment");
        let pen: Vec<f64> = r.penetration.iter().map(|p| p.max(0.0)).collect();
        let pen = one(
            by_arc(&pen, 1e3),
            green,
            "invert penetration (clear drawn at 0)",
        );
        legend_panel(
            &areas[1],
            "bending moment (negative = sag)",
            (xs, "M (kN·m)"),
            &moment,
            &markers,
            None,
        )
        .map_err(&perr)?;
        legend_panel(
            &areas[2],
            "effective tension",
            (xs, "T (kN)"),
            &one(by_arc(&r.tension, 1e-3), blue, "effective tension"),
            &markers,
            None,
        )
        .map_err(&perr)?;
        legend_panel(
            &areas[3],
            "invert penetration (positive down)",
            (xs, "z_pen (mm)"),
            &pen,
            &markers,
            None,
        )
        .map_err(&perr)?;
        if zoom.is_some() {
            legend_panel(
                &areas[4],
                "touchdown zone (±30 m): bending moment",
                (xs, "M (kN·m)"),
                &moment,
                &markers,
                zoom,
            )
            .map_err(&perr)?;
            legend_panel(
                &areas[5],
                "touchdown zone (±30 m): invert penetration",
                (xs, "z_pen (mm)"),
                &pen,
                &markers,
                zoom,
            )
            .map_err(&perr)?;
        }
    }
    write_image(path, &rgb, size)
}

/// A vertical marker: `(x, label, colour)`.
pub(super) type Marker = (f64, &'static str, RGBColor);

/// The markers of a whole-line panel: the static touchdown point (the first) and the section
/// boundaries (the touchdown zone's other markers crowd only the zoomed panels).
pub(super) fn whole_line_marks(markers: &[Marker]) -> Vec<Marker> {
    markers
        .iter()
        .enumerate()
        .filter(|(k, m)| *k == 0 || m.1 == "section boundary" || m.1.is_empty())
        .map(|(_, m)| *m)
        .collect()
}

/// The boundaries between a line's sections (none for one type), grey, the first labelled.
pub(super) fn section_marks(model: &catena_fe::model::LineModel) -> Vec<Marker> {
    model
        .section_boundaries()
        .into_iter()
        .enumerate()
        .map(|(k, a)| {
            let label = if k == 0 { "section boundary" } else { "" };
            (a, label, RGBColor(130, 130, 130))
        })
        .collect()
}

/// The touchdown point's markers — static, and the least and greatest arc length it reached — and
/// the zoom on the zone it visits, with a margin of half its width or 20 m (±30 m about the static
/// point if it never touched down in the window).
pub(super) fn touchdown_marks(r: &DynamicRun) -> (Vec<Marker>, Option<(f64, f64)>) {
    let green = RGBColor(20, 140, 60);
    let tdp_static = r.statics.summary.touchdown_arc.unwrap_or(f64::NAN);
    let (td0, td1) = r.envelopes.touchdown;
    let mut markers = vec![(tdp_static, "static touchdown point", green)];
    if td0.is_finite() {
        markers.push((
            td0,
            "touchdown point nearest the top",
            RGBColor(230, 140, 20),
        ));
        markers.push((
            td1,
            "touchdown point nearest the anchor",
            RGBColor(150, 80, 10),
        ));
    }
    let zoom = if td0.is_finite() {
        let m = (0.5 * (td1 - td0)).max(20.0);
        Some((td0 - m, td1 + m))
    } else if tdp_static.is_finite() {
        Some((tdp_static - 30.0, tdp_static + 30.0))
    } else {
        None
    };
    markers.extend(section_marks(&r.model.line));
    (markers, zoom)
}

/// Range graphs (`ranges.png`): for every quantity of [`catena::run::observe::RANGE_QUANTITIES`] the
/// run has, its least, greatest and mean value along the arc over the envelope window, on the whole
/// line and zoomed on the touchdown zone.
pub fn ranges(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    ranges_on(path, r, None)
}

/// [`ranges`] drawn on `canvas` (made ahead, see [`Canvas`]).
pub fn ranges_on(path: &Path, r: &DynamicRun, canvas: Option<Canvas>) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let e = &r.envelopes;
    let all = e.ranges();
    let rows = all.len().div_ceil(2) as u32;
    let size = ranges_size(all.len());
    let mut rgb = pixels(size, canvas);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let title = format!(
            "{} — range graphs over t ≥ {} s ({} steps): least, greatest and mean at each node",
            r.statics.scene.title, r.spec.envelope_start, e.samples
        );
        let root = root.titled(&title, ("sans-serif", 24)).map_err(&err)?;
        let (strip, body) = root.split_vertically(50);
        let areas = body.split_evenly((rows as usize, 4));
        let arc = &r.model.line.arc;
        let (markers, zoom) = touchdown_marks(r);
        let (blue, dark, red) = (
            RGBColor(20, 90, 200),
            RGBColor(60, 60, 60),
            RGBColor(180, 30, 30),
        );
        let mut entries = vec![
            ("greatest", blue, false),
            ("mean", dark, false),
            ("least", red, false),
        ];
        entries.extend(
            markers
                .iter()
                .filter(|(_, l, _)| !l.is_empty())
                .map(|(_, l, c)| (*l, *c, true)),
        );
        legend_strip(&strip, &entries).map_err(&perr)?;
        let od = r.model.line.node_od[r.model.line.nodes() - 1];
        let xs = "arc length from the top (m)";
        for (k, (name, range)) in all.iter().enumerate() {
            let (scale, axis, floor, caption) = match *name {
                "bending_moment" => (1e-3, "M (kN·m)", None, "bending moment (negative = sag)"),
                "effective_tension" => (1e-3, "T_e (kN)", None, "effective tension"),
                "curvature" => (1e3, "κ (1/km)", None, "curvature M/EI (negative = sag)"),
                "penetration" => (
                    1.0,
                    "z (m)",
                    Some(-2.0 * od),
                    "invert penetration (positive down; clear by > 2D drawn at −2D)",
                ),
                "seabed_force" => (
                    1e-3,
                    "F (kN/m)",
                    None,
                    "seabed force per metre (positive up)",
                ),
                "wall_tension" => (1e-3, "T_w (kN)", None, "wall tension"),
                "stress_top" => (
                    1e-6,
                    "σ (MPa)",
                    None,
                    "outer-fibre axial stress, top of the section (no SCF)",
                ),
                _ => (
                    1e-6,
                    "σ (MPa)",
                    None,
                    "outer-fibre axial stress, bottom of the section (no SCF)",
                ),
            };
            let line = |v: &[f64]| -> Vec<(f64, f64)> {
                arc.iter()
                    .zip(v)
                    .filter(|(_, y)| y.is_finite())
                    .map(|(a, y)| (*a, floor.map_or(y * scale, |f| (y * scale).max(f))))
                    .collect()
            };
            let series = [
                Labelled {
                    points: line(&range.max),
                    colour: blue,
                    label: "greatest",
                },
                Labelled {
                    points: line(&range.mean(e.samples)),
                    colour: dark,
                    label: "mean",
                },
                Labelled {
                    points: line(&range.min),
                    colour: red,
                    label: "least",
                },
            ];
            lines_panel(
                &areas[2 * k],
                caption,
                (xs, axis),
                &series,
                &whole_line_marks(&markers),
                None,
                false,
            )
            .map_err(&perr)?;
            lines_panel(
                &areas[2 * k + 1],
                &format!(
                    "touchdown zone (zoomed): {}",
                    caption.split(" (").next().unwrap_or(caption)
                ),
                (xs, axis),
                &series,
                &markers,
                zoom,
                false,
            )
            .map_err(&perr)?;
        }
    }
    write_image(path, &rgb, size)
}
