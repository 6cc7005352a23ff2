//! The soil element test (`soil-test`) and the calibration's figure (`catena calibrate`).

use std::path::Path;

use catena_seabed::element_test::TestResult;
use catena_seabed::law::Law;
use catena_seabed::rq::Mode;
use plotters::prelude::*;

use catena::studies::soil_test::SoilTestCase;
use catena::AppError;

use super::*;

/// The soil test plot: P/D against z/D (penetration down), coloured by mode, with the `Pu` and
/// `−fsuc·Pu` asymptotes dashed; and, if the test has cycles, the cumulative penetration per cycle.
pub fn soil_test(
    path: &Path,
    case: &SoilTestCase,
    r: &TestResult,
    cycles: &[(usize, f64)],
    z_start: f64,
) -> Result<(), AppError> {
    init_fonts();
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| AppError::io(dir, e))?;
    }
    let err = plot_err(path);
    let d = case.seabed.diameter();
    let width = if cycles.is_empty() { 900 } else { 1600 };
    let size = (width, 800);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let (left, right) = if cycles.is_empty() {
            (root.clone(), None)
        } else {
            let (l, r) = root.split_horizontally(900);
            (l, Some(r))
        };

        let z_lo = r.rows.iter().map(|row| row.z).fold(0.0f64, f64::min);
        let z_hi = r
            .rows
            .iter()
            .map(|row| row.z)
            .fold(0.0f64, f64::max)
            .max(1e-9);
        let mut asym: Vec<(Vec<(f64, f64)>, &str)> = Vec::new();
        if let Law::RandolphQuiggin(rq) = &case.seabed.law {
            let n = 400;
            let zs: Vec<f64> = (0..=n).map(|i| z_hi * i as f64 / n as f64).collect();
            let pu: Vec<(f64, f64)> = zs.iter().map(|&z| (rq.pu(z).0 / d / 1e3, -z / d)).collect();
            let fsuc = rq.params().f_suc;
            let psuc: Vec<(f64, f64)> = pu.iter().map(|&(p, y)| (-fsuc * p, y)).collect();
            asym.push((pu, "Pu (bearing capacity)"));
            asym.push((psuc, "-f_suc Pu (suction limit)"));
        }
        let p_lo = r
            .rows
            .iter()
            .map(|row| row.p / d / 1e3)
            .chain(asym.iter().flat_map(|(v, _)| v.iter().map(|p| p.0)))
            .fold(0.0f64, f64::min);
        let p_hi = r
            .rows
            .iter()
            .map(|row| row.p / d / 1e3)
            .chain(asym.iter().flat_map(|(v, _)| v.iter().map(|p| p.0)))
            .fold(0.0f64, f64::max);
        let (x0, x1) = padded(p_lo, p_hi);
        let (y0, y1) = padded(-z_hi / d, -z_lo / d);
        let title = Path::new(&case.file)
            .file_stem()
            .map_or_else(|| case.file.clone(), |s| s.to_string_lossy().into_owned());
        let mut chart = ChartBuilder::on(&left)
            .caption(
                format!("{title}: soil resistance P/D against penetration"),
                ("sans-serif", 22),
            )
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(&err)?;
        chart
            .configure_mesh()
            .opaque_grid()
            .x_desc("P/D (kPa)  (positive: resistance, negative: suction)")
            .y_desc("penetration z/D (down)")
            .x_label_formatter(&ticks(x0, x1))
            .y_label_formatter(&|v| format!("{:.2}", -v + 0.0))
            .label_style(("sans-serif", 16))
            .draw()
            .map_err(&err)?;
        // The two bounds in two styles: Pu long dashes in dark grey, the suction limit short dashes in
        // brown (each legend entry drawn dashed like its line).
        for ((pts, label), (colour, dash, gap)) in asym.iter().zip([
            (RGBColor(70, 70, 70), 10u32, 5u32),
            (RGBColor(160, 100, 30), 3, 4),
        ]) {
            chart
                .draw_series(DashedLineSeries::new(
                    pts.iter().copied(),
                    dash,
                    gap,
                    colour.stroke_width(2),
                ))
                .map_err(&err)?
                .label(*label)
                .legend(move |(x, y)| {
                    let seg = (dash + gap) as i32;
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (dash as i32, 0)], colour.stroke_width(2))
                        + PathElement::new(
                            vec![(seg, 0), ((seg + dash as i32).min(20), 0)],
                            colour.stroke_width(2),
                        )
                });
        }
        let segments = mode_segments(case, r, d);
        let grey = RGBColor(205, 205, 205);
        let mut grey_labelled = false;
        for (pts, _, _) in segments.iter().filter(|s| s.2) {
            let series = chart
                .draw_series(LineSeries::new(pts.iter().copied(), grey.stroke_width(1)))
                .map_err(&err)?;
            if !grey_labelled {
                grey_labelled = true;
                series
                    .label("other cycles (in colour: 1-3, every 10th, the last)")
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], grey.stroke_width(2))
                    });
            }
        }
        let mut labelled = [false; 4];
        for (pts, mode, _) in segments.into_iter().filter(|s| !s.2) {
            let colour = mode_colour(mode);
            let series = chart
                .draw_series(super::segments(pts, colour.stroke_width(2)))
                .map_err(&err)?;
            let k = mode.code() as usize;
            if !labelled[k] {
                labelled[k] = true;
                series.label(mode.name()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 15))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(&err)?;

        if let Some(right) = right {
            cycles_panel(&right, cycles, z_start, d).map_err(plot_err(path))?;
        }
    }
    write_image(path, &rgb, size)
}

/// The cumulative penetration at the end of each cycle (the soil test's right panel).
fn cycles_panel<DB: DrawingBackend>(
    right: &DrawingArea<DB, plotters::coord::Shift>,
    cycles: &[(usize, f64)],
    z_start: f64,
    d: f64,
) -> Result<(), String> {
    let pts: Vec<(f64, f64)> = cycles
        .iter()
        .map(|&(c, z)| (c as f64, (z - z_start) / d))
        .collect();
    let n = cycles.len() as f64;
    let y_hi = pts.iter().map(|p| p.1).fold(0.0f64, f64::max);
    let y_lo = pts.iter().map(|p| p.1).fold(0.0f64, f64::min);
    let (ya, yb) = padded(y_lo, y_hi);
    let mut c2 = ChartBuilder::on(right)
        .caption("penetration at the end of each cycle", ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..n + 1.0, ya..yb)
        .map_err(|e| e.to_string())?;
    let (fx, fy) = (ticks(0.0, n + 1.0), ticks(ya, yb));
    c2.configure_mesh()
        .opaque_grid()
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .x_desc("cycle")
        .y_desc("cumulative penetration since the first cycle, Δz/D")
        .label_style(("sans-serif", 16))
        .draw()
        .map_err(|e| e.to_string())?;
    c2.draw_series(super::segments(
        pts.iter().copied(),
        mode_colour(Mode::Repenetration).stroke_width(2),
    ))
    .map_err(|e| e.to_string())?;
    c2.draw_series(
        pts.iter()
            .map(|&p| Circle::new(p, 3, mode_colour(Mode::Repenetration).filled())),
    )
    .map_err(|e| e.to_string())?;
    Ok(())
}

/// The test's path cut into segments of one mode within one cycle, as `(P/D in kPa, −z/D)`
/// points, each with its mode and whether it is drawn grey. Many cycles merge into a block: then
/// only the first three, every tenth and the last are drawn in the modes' colours.
fn mode_segments(case: &SoilTestCase, r: &TestResult, d: f64) -> Vec<(Points, Mode, bool)> {
    // Many cycles merge into a block: then only the first three, every tenth and the last are
    // drawn in the modes' colours, the others thin and light grey.
    let n_cycles = case.cycle_of_leg.iter().copied().max().unwrap_or(0);
    let shown = |c: usize| n_cycles <= 10 || c <= 3 || c % 10 == 0 || c == n_cycles;
    let cycle_of_row = |i: usize| {
        let leg = r.rows[i].leg;
        if leg == 0 {
            0
        } else {
            case.cycle_of_leg[leg - 1]
        }
    };
    // Segments of one mode within one cycle; the grey ones first, so that colour stays on top.
    let mut segments = Vec::new();
    let mut start = 0;
    while start + 1 < r.rows.len() {
        let mode = r.rows[start + 1].mode;
        let cycle = cycle_of_row(start + 1);
        let mut end = start + 1;
        while end + 1 < r.rows.len()
            && r.rows[end + 1].mode == mode
            && cycle_of_row(end + 1) == cycle
        {
            end += 1;
        }
        let pts: Vec<(f64, f64)> = r.rows[start..=end]
            .iter()
            .map(|row| (row.p / d / 1e3, -row.z / d))
            .collect();
        segments.push((pts, mode, cycle > 0 && !shown(cycle)));
        start = end;
    }
    segments
}

/// The calibration's figure (`catena calibrate`): the test's force against penetration with the
/// law at the start and fitted parameters (left), and each point's misfit at the fit (right).
pub fn calibration(
    path: &Path,
    title: &str,
    z: &[f64],
    (test, start, fit): (&[f64], &[f64], &[f64]),
) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let size = (1600, 700);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root.titled(title, ("sans-serif", 20)).map_err(&err)?;
        let areas = root.split_evenly((1, 2));
        let curve =
            |p: &[f64]| -> Vec<(f64, f64)> { z.iter().copied().zip(p.iter().copied()).collect() };
        legend_panel(
            &areas[0],
            "soil resistance against penetration",
            ("penetration of the invert z (m)", "P (N/m)"),
            &[
                Labelled {
                    points: curve(start),
                    colour: RGBColor(150, 150, 150),
                    label: "law, start parameters",
                },
                Labelled {
                    points: curve(test),
                    colour: RGBColor(20, 20, 20),
                    label: "test",
                },
                Labelled {
                    points: curve(fit),
                    colour: RGBColor(200, 30, 30),
                    label: "law, fitted parameters",
                },
            ],
            &[],
            None,
        )
        .map_err(&perr)?;
        lines_panel(
            &areas[1],
            "misfit at the fit, point by point",
            ("point of the test", "P_fit − P_test (N/m)"),
            &[Labelled {
                points: fit
                    .iter()
                    .zip(test)
                    .enumerate()
                    .map(|(i, (a, b))| (i as f64, a - b))
                    .collect(),
                colour: RGBColor(200, 30, 30),
                label: "",
            }],
            &[],
            None,
            false,
        )
        .map_err(&perr)?;
    }
    write_image(path, &rgb, size)
}
