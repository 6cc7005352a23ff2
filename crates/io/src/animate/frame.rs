//! Drawing one frame of the animation: the whole line, the touchdown zone and the moment.

use super::*;

pub(super) type Envelope<'a> = (&'a [f64], &'a [f64]);

#[allow(clippy::too_many_arguments)]
pub(super) fn draw_frame(
    rgb: &mut [u8],
    (w, h): (u32, u32),
    rec: &Records,
    geo: &Geometry,
    opts: &Options,
    k: usize,
    trench: &[f64],
    (m_lo, m_hi): Envelope<'_>,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    let n = rec.n();
    let (x, z) = (rec.row(&rec.x, k), rec.row(&rec.z, k));
    let (x0, z0) = (rec.row(&rec.x, 0), rec.row(&rec.z, 0));
    let moment = rec.row(&rec.bending_moment, k);
    let root = BitMapBackend::with_buffer(rgb, (w, h)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let caption = format!(
        "t = {:7.2} s    top: heave {:+.2} m, surge {:+.2} m",
        rec.time[k],
        rec.top_z[k] - rec.top_z[0],
        rec.top_x[k] - rec.top_x[0]
    );
    let root = root.titled(&caption, ("sans-serif", 20)).map_err(e)?;
    let (top, rest) = root.split_vertically((h as f64 * 0.30) as u32);
    let (mid, bottom) = rest.split_vertically((h as f64 * 0.36) as u32);

    // The whole line.
    let ((wx0, wx1), (wz0, wz1)) = geo.whole;
    let mut c = ChartBuilder::on(&top)
        .margin(6)
        .x_label_area_size(24)
        .y_label_area_size(50)
        .build_cartesian_2d(wx0..wx1, wz0..wz1)
        .map_err(e)?;
    axes(&mut c, "x (m)", "z (m)").map_err(e)?;
    let light = RGBColor(190, 190, 190);
    let pipe = RGBColor(30, 60, 140);
    c.draw_series(LineSeries::new(
        (0..n).map(|i| (x0[i], z0[i])),
        light.stroke_width(1),
    ))
    .map_err(e)?;
    c.draw_series(LineSeries::new(
        (0..n).map(|i| (x[i], z[i])),
        pipe.stroke_width(2),
    ))
    .map_err(e)?;
    let mud_all = geo.mud[n - 1];
    c.draw_series(LineSeries::new(
        [(wx0, mud_all), (wx1, mud_all)],
        RGBColor(140, 100, 60).stroke_width(1),
    ))
    .map_err(e)?;
    let (a, b) = geo.window;
    c.draw_series(std::iter::once(Rectangle::new(
        [
            (a, mud_all - 0.03 * (wz1 - wz0)),
            (b, mud_all + 0.05 * (wz1 - wz0)),
        ],
        RED.stroke_width(1),
    )))
    .map_err(e)?;

    // The touchdown zone: heights in true metres, exaggerated by `geo.exaggeration`.
    touchdown_panel(&mid, rec, geo, opts, k, trench)?;

    // The bending moment along the touchdown zone's arc.
    moment_panel(&bottom, rec, geo, moment, (m_lo, m_hi))?;
    root.present().map_err(e)?;
    Ok(())
}

/// The animation's middle panel: the touchdown zone, heights exaggerated by
/// `geo.exaggeration`, the soil less its trench, the pipe as a band of its diameter coloured by
/// penetration or seabed force.
pub(super) fn touchdown_panel<DB: DrawingBackend>(
    mid: &DrawingArea<DB, plotters::coord::Shift>,
    rec: &Records,
    geo: &Geometry,
    opts: &Options,
    k: usize,
    trench: &[f64],
) -> Result<(), String> {
    let n = rec.n();
    let (x, z) = (rec.row(&rec.x, k), rec.row(&rec.z, k));
    let x0 = rec.row(&rec.x, 0);
    let pen = rec.row(&rec.penetration, k);
    let force = rec.row(&rec.seabed_force, k);
    let (a, b) = geo.window;
    let (za, zb) = geo.z_window;
    let (lo, hi) = geo.colour(opts.colour);
    let what = match opts.colour {
        Colour::Penetration => format!(
            "nodes by penetration: 0 (blue) to {:.3} m (yellow), grey clear",
            hi
        ),
        Colour::SeabedForce => format!(
            "nodes by seabed force: {:.2} (blue) to {:.2} kN/m (yellow)",
            lo / 1e3,
            hi / 1e3
        ),
    };
    let mut c = ChartBuilder::on(mid)
        .margin(6)
        .caption(
            format!(
                "touchdown zone, vertical scale x{:.0}; {what}",
                geo.exaggeration
            ),
            ("sans-serif", 14),
        )
        .x_label_area_size(34)
        .y_label_area_size(50)
        .build_cartesian_2d(a..b, za..zb)
        .map_err(|e| e.to_string())?;
    axes(&mut c, "x (m)", "z (m)").map_err(|e| e.to_string())?;
    // The soil: the mudline less the trench under the nodes' present places, filled down.
    let near: Vec<usize> = (0..n)
        .filter(|&i| x[i] >= a - 5.0 && x[i] <= b + 5.0)
        .collect();
    let mut soil: Vec<(f64, f64)> = near
        .iter()
        .map(|&i| (x[i], geo.mud[i] - trench[i].max(0.0)))
        .collect();
    soil.sort_by(|p, q| p.0.total_cmp(&q.0));
    if let (Some(&first), Some(&last)) = (soil.first(), soil.last()) {
        let mut poly = vec![(a - 5.0, za), (a - 5.0, first.1)];
        poly.extend(soil.iter().copied());
        poly.extend([(b + 5.0, last.1), (b + 5.0, za)]);
        c.draw_series(std::iter::once(Polygon::new(
            poly,
            RGBColor(205, 180, 140).filled(),
        )))
        .map_err(|e| e.to_string())?;
        // The original mudline, dashed.
        let mut mud0: Vec<(f64, f64)> = near.iter().map(|&i| (x0[i], geo.mud[i])).collect();
        mud0.sort_by(|p, q| p.0.total_cmp(&q.0));
        c.draw_series(
            mud0.windows(2)
                .step_by(2)
                .map(|w| PathElement::new(vec![w[0], w[1]], RGBColor(110, 80, 50).stroke_width(1))),
        )
        .map_err(|e| e.to_string())?;
    }
    // The pipe: a band of its diameter between consecutive nodes, coloured by the two nodes'
    // mean value; its invert the lower edge.
    let value = |i: usize| match opts.colour {
        Colour::Penetration => pen[i],
        Colour::SeabedForce => force[i],
    };
    let shade = |i: usize, j: usize| {
        let v = 0.5 * (value(i) + value(j));
        if matches!(opts.colour, Colour::Penetration) && pen[i] <= 0.0 && pen[j] <= 0.0 {
            RGBColor(150, 150, 150)
        } else {
            ramp((v - lo) / (hi - lo))
        }
    };
    c.draw_series(
        (0..n - 1)
            .filter(|&i| x[i].max(x[i + 1]) >= a && x[i].min(x[i + 1]) <= b)
            .map(|i| {
                let j = i + 1;
                let (ri, rj) = (0.5 * rec.od[i], 0.5 * rec.od[j]);
                Polygon::new(
                    vec![
                        (x[i], z[i] - ri),
                        (x[j], z[j] - rj),
                        (x[j], z[j] + rj),
                        (x[i], z[i] + ri),
                    ],
                    shade(i, j).filled(),
                )
            }),
    )
    .map_err(|e| e.to_string())?;
    c.draw_series([-1.0, 1.0].into_iter().flat_map(|side| {
        LineSeries::new(
            (0..n)
                .filter(|&i| x[i] >= a - 5.0 && x[i] <= b + 5.0)
                .map(move |i| (x[i], z[i] + side * 0.5 * rec.od[i])),
            RGBColor(20, 20, 40).stroke_width(1),
        )
    }))
    .map_err(|e| e.to_string())?;

    Ok(())
}

/// The animation's bottom panel: the bending moment along the touchdown zone's arc now (line)
/// and its least and greatest so far (band).
pub(super) fn moment_panel<DB: DrawingBackend>(
    bottom: &DrawingArea<DB, plotters::coord::Shift>,
    rec: &Records,
    geo: &Geometry,
    moment: &[f64],
    (m_lo, m_hi): Envelope<'_>,
) -> Result<(), String> {
    let (s0, s1) = geo.arc_window;
    let span: Vec<usize> = (0..rec.n())
        .filter(|&i| rec.arc[i] >= s0 && rec.arc[i] <= s1)
        .collect();
    let (mlo, mhi) = geo.moment_range;
    let mut c = ChartBuilder::on(bottom)
        .margin(6)
        .caption(
            "bending moment: now (line), least and greatest so far (band); negative = sag",
            ("sans-serif", 14),
        )
        .x_label_area_size(34)
        .y_label_area_size(50)
        .build_cartesian_2d(s0..s1, mlo..mhi)
        .map_err(|e| e.to_string())?;
    axes(&mut c, "arc length from the top (m)", "moment (kN·m)").map_err(|e| e.to_string())?;
    let band: Vec<(f64, f64)> = span
        .iter()
        .map(|&i| (rec.arc[i], m_hi[i] / 1e3))
        .chain(span.iter().rev().map(|&i| (rec.arc[i], m_lo[i] / 1e3)))
        .collect();
    c.draw_series(std::iter::once(Polygon::new(
        band,
        RGBColor(215, 225, 240).filled(),
    )))
    .map_err(|e| e.to_string())?;
    c.draw_series(LineSeries::new(
        span.iter().map(|&i| (rec.arc[i], moment[i] / 1e3)),
        RGBColor(30, 60, 140).stroke_width(2),
    ))
    .map_err(|e| e.to_string())?;
    c.draw_series(LineSeries::new(
        [(s0, 0.0), (s1, 0.0)],
        RGBColor(120, 120, 120).stroke_width(1),
    ))
    .map_err(|e| e.to_string())?;
    Ok(())
}

/// A panel's axes: no grid, the two labels, small tick labels.
pub(super) fn axes<DB: DrawingBackend>(
    c: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    x: &str,
    y: &str,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (xr, yr) = (c.x_range(), c.y_range());
    let (fx, fy) = (
        crate::plot::ticks(xr.start, xr.end),
        crate::plot::ticks(yr.start, yr.end),
    );
    c.configure_mesh()
        .disable_mesh()
        .x_desc(x)
        .y_desc(y)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style(("sans-serif", 12))
        .draw()
}

/// The moment axis over the whole run (so the axis does not jump between frames), kN·m.
pub(super) fn envelope_limits(rec: &Records, (s0, s1): (f64, f64)) -> Option<(f64, f64)> {
    let n = rec.n();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..rec.records() {
        for i in 0..n {
            if rec.arc[i] >= s0 && rec.arc[i] <= s1 {
                let m = rec.bending_moment[k * n + i] / 1e3;
                lo = lo.min(m);
                hi = hi.max(m);
            }
        }
    }
    lo.is_finite().then(|| padded(lo.min(0.0), hi.max(0.0)))
}
