//! PNG plots, drawn with plotters. The font (DejaVu Sans, Bitstream Vera licence, `assets/`) is
//! embedded in the binary, so plots need nothing from the system.

use std::path::Path;
use std::sync::Once;

use catena_seabed::element_test::TestResult;
use catena_seabed::law::Law;
use catena_seabed::rq::Mode;
use plotters::prelude::*;

use catena::run::DynamicRun;
use catena::soil_test::SoilTestCase;
use catena::AppError;

static FONT: &[u8] = include_bytes!("../../../assets/DejaVuSans.ttf");
static INIT: Once = Once::new();

/// Registers the embedded font under the name `sans-serif` (once).
pub fn init_fonts() {
    INIT.call_once(|| {
        // The font is embedded and valid; a failure would only mean text is not drawn.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// The colour of a contact mode (the paper's Figure 2: blue backbone, green uplift, purple
/// repenetration; grey out of contact).
pub fn mode_colour(m: Mode) -> RGBColor {
    match m {
        Mode::NotInContact => RGBColor(140, 140, 140),
        Mode::InitialPenetration => RGBColor(20, 90, 200),
        Mode::Uplift => RGBColor(20, 150, 40),
        Mode::Repenetration => RGBColor(150, 30, 170),
    }
}

pub(crate) fn plot_err<E: std::fmt::Display>(path: &Path) -> impl Fn(E) -> AppError + '_ {
    move |e| AppError::Plot {
        path: path.to_path_buf(),
        message: plain_message(&e.to_string()),
    }
}

/// The plotting backend's error in words: its text is Rust debug output (`ImageError(IoError(Os {
/// … message: "No such file or directory" }))`); the system's message is taken out of it, and an
/// unknown image format becomes what to do.
fn plain_message(raw: &str) -> String {
    if let Some(i) = raw.find("message: \"") {
        let rest = &raw[i + 10..];
        let text = rest.split('"').next().unwrap_or(rest);
        return format!("cannot write the image: {text}");
    }
    if raw.contains("Unsupported") {
        return "cannot write the image: the file name must end in .png".into();
    }
    raw.to_string()
}

/// A white RGB canvas (three bytes a pixel) made ahead of the plot that draws on it.
///
/// Making and whitening the pixels of a large plot (8 MB for `dynamic.png`) takes as long as
/// drawing its curves: `catena run` makes the canvases of its two large plots on another thread
/// while the dynamics step ([`Canvas::white`]), and the plots, drawn after the run, start on them.
/// A plot given no canvas, or one too small, makes its own.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Canvas(Vec<u8>);

impl Canvas {
    /// A white canvas with room for `width × height` pixels.
    pub fn white((width, height): (u32, u32)) -> Self {
        Self(vec![255; 3 * width as usize * height as usize])
    }
}

/// The grid's major lines: the grey that plotters' default for them, black at 20 % opacity,
/// blends to on white, drawn opaque.
///
/// Translucent lines are blended into the canvas pixel by pixel, and a plot's dense minor grid
/// (up to ten lines between two labels) made the blending a fifth of the drawing: about 9 ms of
/// `catena run`'s three plots of the heave benchmark, two of them after the run
/// (`benches/README.md`). Opaque lines are filled a row at a time. The grid looks the same; only
/// where two of its lines cross is the pixel no longer darker than either.
pub const GRID_BOLD: RGBColor = RGBColor(204, 204, 204);

/// The grid's minor lines: black at 10 % opacity on white, drawn opaque (see [`GRID_BOLD`]).
pub const GRID_LIGHT: RGBColor = RGBColor(230, 230, 230);

/// A chart's grid in [`GRID_BOLD`] and [`GRID_LIGHT`]: `chart.configure_mesh().opaque_grid()`.
pub trait OpaqueGrid {
    /// Sets the grid's major and minor lines to the opaque greys.
    fn opaque_grid(&mut self) -> &mut Self;
}

impl<X, Y, DB> OpaqueGrid for plotters::chart::MeshStyle<'_, '_, X, Y, DB>
where
    X: plotters::coord::ranged1d::Ranged,
    Y: plotters::coord::ranged1d::Ranged,
    DB: DrawingBackend,
{
    fn opaque_grid(&mut self) -> &mut Self {
        self.bold_line_style(GRID_BOLD).light_line_style(GRID_LIGHT)
    }
}

/// The size of [`dynamic`]'s plot.
pub const DYNAMIC_SIZE: (u32, u32) = (1800, 1500);

/// The largest size of [`ranges`]' plot: every quantity of [`catena::observe::RANGE_QUANTITIES`]
/// present.
pub const RANGES_MAX_SIZE: (u32, u32) = ranges_size(catena::observe::RANGE_QUANTITIES.len());

/// The size of [`ranges`]' plot of `quantities` range graphs (two to a row).
const fn ranges_size(quantities: usize) -> (u32, u32) {
    (2400, 50 + 420 * quantities.div_ceil(2) as u32)
}

/// The white pixels a plot of `size` draws on: the first `width × height` of `canvas` when it
/// has room for them, else new ones.
pub(crate) fn pixels((width, height): (u32, u32), canvas: Option<Canvas>) -> Vec<u8> {
    let n = 3 * width as usize * height as usize;
    match canvas {
        Some(Canvas(mut v)) if v.len() >= n => {
            v.truncate(n);
            v
        }
        _ => vec![255; n],
    }
}

/// Writes the RGB pixels `rgb` (`width × height`) to `path`, its format from its extension.
///
/// A `.png` is written with the fast deflate and the Paeth filter on every row: the same pixels
/// as the image crate's default (the fast deflate with an adaptive filter tried row by row), in
/// files 2–3 % larger, written in two thirds of the time (4.1 against 6.3 ms for the heave
/// benchmark's `dynamic.png`, measured 2026-11-26). Any other extension goes to the image crate's
/// encoder for it, as plotters would.
pub(crate) fn write_image(
    path: &Path,
    rgb: &[u8],
    (width, height): (u32, u32),
) -> Result<(), AppError> {
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    use image::ImageEncoder;
    // The error's debug text, as plotters gives it (see `plain_message`).
    let err = |e: &dyn std::fmt::Debug| AppError::Plot {
        path: path.to_path_buf(),
        message: plain_message(&format!("{e:?}")),
    };
    let rgb = &rgb[..3 * width as usize * height as usize];
    let is_png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return image::save_buffer(path, rgb, width, height, image::ColorType::Rgb8)
            .map_err(|e| err(&e));
    }
    let file = std::fs::File::create(path).map_err(|e| err(&e))?;
    let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
    PngEncoder::new_with_quality(&mut w, CompressionType::Fast, FilterType::Paeth)
        .write_image(rgb, width, height, image::ColorType::Rgb8)
        .map_err(|e| err(&e))?;
    std::io::Write::flush(&mut w).map_err(|e| err(&e))
}

#[cfg(test)]
mod message_tests {
    #[test]
    fn backend_errors_are_put_in_words() {
        let io = r#"backend error: Drawing backend error: ImageError(IoError(Os { code: 2, kind: NotFound, message: "No such file or directory" }))"#;
        assert_eq!(
            super::plain_message(io),
            "cannot write the image: No such file or directory"
        );
        let fmt = "backend error: Drawing backend error: ImageError(Unsupported(UnsupportedError { format: Unknown, kind: Format(Unknown) }))";
        assert!(super::plain_message(fmt).ends_with("must end in .png"));
    }
}

/// Pads a range by 5 % on each side (and widens an empty one).
pub fn padded(lo: f64, hi: f64) -> (f64, f64) {
    let span = (hi - lo)
        .abs()
        .max(1e-9 * hi.abs().max(lo.abs()).max(1e-12));
    (lo - 0.05 * span, hi + 0.05 * span)
}

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
                .draw_series(LineSeries::new(pts, colour.stroke_width(2)))
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
            let pts: Vec<(f64, f64)> = cycles
                .iter()
                .map(|&(c, z)| (c as f64, (z - z_start) / d))
                .collect();
            let n = cycles.len() as f64;
            let y_hi = pts.iter().map(|p| p.1).fold(0.0f64, f64::max);
            let y_lo = pts.iter().map(|p| p.1).fold(0.0f64, f64::min);
            let (ya, yb) = padded(y_lo, y_hi);
            let mut c2 = ChartBuilder::on(&right)
                .caption("penetration at the end of each cycle", ("sans-serif", 22))
                .margin(15)
                .x_label_area_size(50)
                .y_label_area_size(80)
                .build_cartesian_2d(0.0..n + 1.0, ya..yb)
                .map_err(&err)?;
            c2.configure_mesh()
                .opaque_grid()
                .x_desc("cycle")
                .y_desc("cumulative penetration since the first cycle, Δz/D")
                .label_style(("sans-serif", 16))
                .draw()
                .map_err(&err)?;
            c2.draw_series(LineSeries::new(
                pts.iter().copied(),
                mode_colour(Mode::Repenetration).stroke_width(2),
            ))
            .map_err(&err)?;
            c2.draw_series(
                pts.iter()
                    .map(|&p| Circle::new(p, 3, mode_colour(Mode::Repenetration).filled())),
            )
            .map_err(&err)?;
        }
    }
    write_image(path, &rgb, size)
}

/// How a panel draws its series.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Marks {
    /// Connected lines.
    Lines,
    /// Separate dots.
    Points,
}

/// The x and y ranges of the finite points (within `x_range` if given, which is then the x range),
/// padded by 5 %; a unit box if there is none.
fn data_box(
    points: impl Iterator<Item = (f64, f64)>,
    x_range: Option<(f64, f64)>,
) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in points {
        let inside = x_range.is_none_or(|(a, b)| x >= a && x <= b);
        if x.is_finite() && y.is_finite() && inside {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let xr = x_range.unwrap_or_else(|| padded(x0, x1));
    (xr, padded(y0, y1))
}

/// A captioned chart with labelled axes over the given ranges (the house style of every panel).
fn framed_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    axes: (&str, &str),
    x: (f64, f64),
    y: (f64, f64),
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    String,
> {
    framed_chart_sized(area, caption, axes, x, y, 18)
}

/// [`framed_chart`] with the caption's font size.
fn framed_chart_sized<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    (xlabel, ylabel): (&str, &str),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    caption_size: u32,
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    String,
> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", caption_size))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .opaque_grid()
        .x_desc(xlabel)
        .y_desc(ylabel)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

/// A labelled line for [`legend_panel`].
struct Labelled<'a> {
    points: Vec<(f64, f64)>,
    colour: RGBColor,
    label: &'a str,
}

/// Draws one panel of labelled lines with a legend, optional vertical markers `(x, label, colour)`
/// drawn dashed across the panel, and an optional x range (else the data's).
fn legend_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    axes: (&str, &str),
    series: &[Labelled<'_>],
    markers: &[(f64, &str, RGBColor)],
    x_range: Option<(f64, f64)>,
) -> Result<(), String> {
    lines_panel(area, caption, axes, series, markers, x_range, true)
}

/// [`legend_panel`], with the legend drawn or not (a figure of many panels shares one legend).
fn lines_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    (xlabel, ylabel): (&str, &str),
    series: &[Labelled<'_>],
    markers: &[(f64, &str, RGBColor)],
    x_range: Option<(f64, f64)>,
    legend: bool,
) -> Result<(), String> {
    let ((x0, x1), (y0, y1)) = data_box(
        series.iter().flat_map(|s| s.points.iter().copied()),
        x_range,
    );
    let mut chart = framed_chart(area, caption, (xlabel, ylabel), (x0, x1), (y0, y1))?;
    for s in series {
        let c = s.colour;
        let drawn = chart
            .draw_series(LineSeries::new(
                s.points
                    .iter()
                    .copied()
                    .filter(|(x, _)| x_range.is_none_or(|(a, b)| *x >= a && *x <= b)),
                c.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?;
        // An unlabelled line (a repeat of one listed) is drawn, not listed.
        if !s.label.is_empty() {
            drawn.label(s.label).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3))
            });
        }
    }
    for &(x, label, c) in markers {
        if !(x.is_finite() && x >= x0 && x <= x1) {
            continue;
        }
        let n = 40;
        let dash = (0..n).filter(|k| k % 2 == 0).map(move |k| {
            let a = y0 + (y1 - y0) * k as f64 / n as f64;
            let b = y0 + (y1 - y0) * (k + 1) as f64 / n as f64;
            PathElement::new(vec![(x, a), (x, b)], c.stroke_width(2))
        });
        let drawn = chart.draw_series(dash).map_err(|e| e.to_string())?;
        if label.is_empty() {
            // A repeated marker (the second section boundary on): drawn, not listed again.
            continue;
        }
        drawn.label(label).legend(move |(x, y)| {
            PathElement::new(
                vec![(x, y), (x + 8, y), (x + 12, y), (x + 20, y)],
                c.stroke_width(2),
            )
        });
    }
    if legend {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// A legend strip across a figure: a short line (dashed for a marker) and its label per entry.
fn legend_strip<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    entries: &[(&str, RGBColor, bool)],
) -> Result<(), String> {
    let (w, h) = area.dim_in_pixel();
    let y = h as i32 / 2;
    let step = (w as i32 - 40) / entries.len().max(1) as i32;
    for (k, (label, c, dashed)) in entries.iter().enumerate() {
        let x = 20 + k as i32 * step;
        if *dashed {
            for d in 0..3 {
                area.draw(&PathElement::new(
                    vec![(x + 14 * d, y), (x + 14 * d + 8, y)],
                    c.stroke_width(3),
                ))
                .map_err(|e| e.to_string())?;
            }
        } else {
            area.draw(&PathElement::new(
                vec![(x, y), (x + 36, y)],
                c.stroke_width(3),
            ))
            .map_err(|e| e.to_string())?;
        }
        area.draw(&Text::new(
            label.to_string(),
            (x + 44, y - 9),
            ("sans-serif", 18).into_font(),
        ))
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Draws one panel: `series` of (x, y) lines with a caption and axis labels.
fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    xlabel: &str,
    ylabel: &str,
    series: &[(Vec<(f64, f64)>, RGBColor)],
) -> Result<(), String> {
    marked_panel(area, caption, xlabel, ylabel, series, Marks::Lines)
}

/// Draws one panel of lines with equal scales on both axes (a metre is as long across as up): the
/// data box of the shorter side widened about its centre to the plotting area's proportions.
fn scaled_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    xlabel: &str,
    ylabel: &str,
    series: &[(Vec<(f64, f64)>, RGBColor)],
) -> Result<(), String> {
    let ((x0, x1), (y0, y1)) = data_box(series.iter().flat_map(|(v, _)| v.iter().copied()), None);
    // The plotting area inside `framed_chart`'s margins, label areas and caption.
    let (w, h) = area.dim_in_pixel();
    let (wp, hp) = (
        (w as f64 - 2.0 * 12.0 - 75.0).max(1.0),
        (h as f64 - 2.0 * 12.0 - 45.0 - 30.0).max(1.0),
    );
    let u = ((x1 - x0) / wp).max((y1 - y0) / hp);
    let (xc, yc) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let xr = (xc - 0.5 * u * wp, xc + 0.5 * u * wp);
    let yr = (yc - 0.5 * u * hp, yc + 0.5 * u * hp);
    let mut chart = framed_chart(area, caption, (xlabel, ylabel), xr, yr)?;
    for (v, c) in series {
        chart
            .draw_series(LineSeries::new(v.iter().copied(), c.stroke_width(2)))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Draws one panel of lines or dots, scaled to the finite data (a unit box if there is none).
fn marked_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    xlabel: &str,
    ylabel: &str,
    series: &[(Vec<(f64, f64)>, RGBColor)],
    marks: Marks,
) -> Result<(), String> {
    let (xr, yr) = data_box(series.iter().flat_map(|(v, _)| v.iter().copied()), None);
    let mut chart = framed_chart(area, caption, (xlabel, ylabel), xr, yr)?;
    for (v, c) in series {
        match marks {
            Marks::Lines => chart
                .draw_series(LineSeries::new(v.iter().copied(), c.stroke_width(2)))
                .map(|_| ()),
            Marks::Points => chart
                .draw_series(v.iter().map(|p| Circle::new(*p, 2, c.filled())))
                .map(|_| ()),
        }
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

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
type Marker = (f64, &'static str, RGBColor);

/// The markers of a whole-line panel: the static touchdown point (the first) and the section
/// boundaries (the touchdown zone's other markers crowd only the zoomed panels).
fn whole_line_marks(markers: &[Marker]) -> Vec<Marker> {
    markers
        .iter()
        .enumerate()
        .filter(|(k, m)| *k == 0 || m.1 == "section boundary" || m.1.is_empty())
        .map(|(_, m)| *m)
        .collect()
}

/// The boundaries between a line's sections (none for one type), grey, the first labelled.
fn section_marks(model: &catena_fe::model::LineModel) -> Vec<Marker> {
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
fn touchdown_marks(r: &DynamicRun) -> (Vec<Marker>, Option<(f64, f64)>) {
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

/// Range graphs (`ranges.png`): for every quantity of [`catena::observe::RANGE_QUANTITIES`] the
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

/// The design check (`design_check.png`): each node's largest utilisation over the run with the
/// static state's (functional only) and the limit 1.0, over the whole line and around the touchdown
/// zone; beneath, each node's least effective tension with the static tension (compression below 0).
pub fn design_check(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    let Some(d) = r.output::<catena::design_observer::DesignCheck>() else {
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
    items: &[(&catena::extremes::Extremes, &[f64], f64)],
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
            let p = catena::extremes::paper(e, x, *dt);
            let side = match e.tail {
                catena::extremes::Tail::Max => "",
                catena::extremes::Tail::Min => " (least, negated)",
            };
            let mpm = |v: Option<f64>| {
                v.map_or("—".to_string(), |v| {
                    if v.abs() >= 1e3 {
                        format!("{v:.4e}")
                    } else {
                        format!("{v:.4}")
                    }
                })
            };
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
                    &p.weibull,
                    w_caption,
                    ("ln(peak − mean)", "ln(−ln(1 − F))"),
                ),
                (
                    &areas[2 * k + 1],
                    &p.gumbel,
                    g_caption,
                    ("block maximum (negated for a least)", "−ln(−ln F)"),
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
                    .draw_series(LineSeries::new(line.iter().copied(), red.stroke_width(2)))
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
    runs: &[catena::strength::RunResult],
    storms: &[catena::strength::StormSummary],
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
            let mut m = u.per_seed.clone();
            m.sort_by(f64::total_cmp);
            let n = m.len() as f64;
            let points: Vec<(f64, f64)> = m
                .iter()
                .enumerate()
                .map(|(i, v)| (*v, -(-((i as f64 + 1.0) / (n + 1.0)).ln()).ln()))
                .collect();
            let line: Vec<(f64, f64)> = match (u.gumbel, m.first(), m.last()) {
                (Some((g, _)), Some(a), Some(b)) => [*a, *b]
                    .iter()
                    .map(|v| (*v, (v - g.location) / g.scale))
                    .collect(),
                _ => Vec::new(),
            };
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
                .draw_series(LineSeries::new(line.iter().copied(), red.stroke_width(2)))
                .map_err(|e| perr(e.to_string()))?;
        }
    }
    write_image(path, &rgb, size)
}

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
        legend_panel(
            &areas[5],
            "top tension",
            ("time (s)", "T_top (kN)"),
            &[lab(th, blue, "top effective tension")],
            &[(r.spec.envelope_start, "envelopes start", grey)],
            None,
        )
        .map_err(&perr)?;
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

/// The sea and the hang-off (runs with waves): the wave elevation at the RAO origin (or above the
/// top end without a vessel) and the vessel's pitch; the hang-off's displacement from its static
/// position — horizontal (blue), vertical (red) and along the riser's static top tangent (black,
/// the motion that drives touchdown fatigue).
pub fn sea(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    let Some(waves) = r.model.environment.waves.as_ref() else {
        return Ok(());
    };
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let size = (1600, 1000);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let title = format!("{} — sea and hang-off motion", r.statics.scene.title);
        let root = root.titled(&title, ("sans-serif", 24)).map_err(&err)?;
        let areas = root.split_evenly((2, 1));
        let h = &r.top;
        let x_ref = r
            .model
            .vessel
            .as_ref()
            .map_or(r.statics.results.x[0], |v| v.origin_x);
        let eta: Vec<(f64, f64)> =
            h.t.iter()
                .map(|t| (*t, waves.elevation(x_ref, *t)))
                .collect();
        let pitch: Vec<(f64, f64)> =
            h.t.iter()
                .map(|t| (*t, r.model.top_at(*t).map_or(0.0, |s| s.pitch.to_degrees())))
                .collect();
        let black = RGBColor(0, 0, 0);
        let red = RGBColor(200, 30, 30);
        let blue = RGBColor(20, 90, 200);
        let mut series = vec![(eta, blue)];
        if r.model.vessel.is_some() {
            series.push((pitch, red));
        }
        panel(
        &areas[0],
        "wave elevation at the RAO origin (blue, m) and vessel pitch (red, deg, positive bow down)",
        "time (s)",
        "η (m), pitch (deg)",
        &series,
    )
    .map_err(&perr)?;
        let (x0, z0) = (r.statics.results.x[0], r.statics.results.z[0]);
        let th = r.statics.summary.top_angle_from_vertical;
        let dx: Vec<(f64, f64)> =
            h.t.iter()
                .zip(&h.top_x)
                .map(|(t, x)| (*t, x - x0))
                .collect();
        let dz: Vec<(f64, f64)> =
            h.t.iter()
                .zip(&h.top_z)
                .map(|(t, z)| (*t, z - z0))
                .collect();
        let ax: Vec<(f64, f64)> =
            h.t.iter()
                .zip(h.top_x.iter().zip(&h.top_z))
                .map(|(t, (x, z))| (*t, (x - x0) * th.sin() + (z - z0) * th.cos()))
                .collect();
        panel(
        &areas[1],
        "hang-off displacement: horizontal (blue), vertical (red), along the riser's top tangent (black)",
        "time (s)",
        "displacement (m)",
        &[(dx, blue), (dz, red), (ax, black)],
    )
    .map_err(&perr)?;
    }
    write_image(path, &rgb, size)
}

/// What [`sequence`] draws: the arc, each visit's trench (penetration at rest after it, in visit
/// order), the touchdown window, the life along the arc with memory and as laid (years; empty if
/// not run), the accumulated annual-damage contributions at the critical node after each visit
/// (with memory, as laid), and each node's strength factor after the last visit.
pub struct SequencePlot<'a> {
    /// The figure's title.
    pub title: &'a str,
    /// Arc length of every node, m.
    pub arc: &'a [f64],
    /// The as-laid static penetration, m.
    pub as_laid: &'a [f64],
    /// Each visit's trench, m (in order).
    pub trenches: &'a [Vec<f64>],
    /// The arc window of the touchdown zone drawn, m.
    pub window: (f64, f64),
    /// Life along the arc with memory, years.
    pub life_memory: &'a [f64],
    /// Life along the arc as laid, years (empty if not run).
    pub life_as_laid: &'a [f64],
    /// The critical node's accumulated damage after each visit, with memory and as laid.
    pub accumulated: (&'a [f64], &'a [f64]),
    /// Strength factor after the last visit (empty or all 1 without degradation).
    pub strength: &'a [f64],
}

/// The storm sequence's figure (`sequence.png`): the trench's growth (penetration along the
/// touchdown zone after each visit, coloured from light to dark in visit order), the life along the
/// touchdown zone with memory and as laid, and the accumulated damage at the critical node visit
/// by visit; with degradation, the strength factor after the last visit.
pub fn sequence(path: &Path, p: &SequencePlot<'_>) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let degraded = p.strength.iter().any(|&s| s < 1.0);
    let size = (1800, 1000);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root.titled(p.title, ("sans-serif", 22)).map_err(&err)?;
        let areas = root.split_evenly((2, 2));
        let (a0, a1) = p.window;
        let inside: Vec<usize> = (0..p.arc.len())
            .filter(|&i| p.arc[i] >= a0 && p.arc[i] <= a1)
            .collect();
        // The trench's growth.
        let n = p.trenches.len().max(1);
        let shade = |k: usize| {
            let f = if n > 1 {
                k as f64 / (n - 1) as f64
            } else {
                1.0
            };
            let c = |light: f64, dark: f64| (light + (dark - light) * f) as u8;
            RGBColor(c(170.0, 10.0), c(200.0, 40.0), c(240.0, 120.0))
        };
        let labels: Vec<String> = (0..p.trenches.len())
            .map(|k| {
                if k == 0 {
                    "after the first visit (light)".to_string()
                } else if k + 1 == p.trenches.len() {
                    format!("after visit {} (dark)", k + 1)
                } else {
                    String::new()
                }
            })
            .collect();
        let mut series: Vec<Labelled<'_>> = vec![Labelled {
            points: inside
                .iter()
                .map(|&i| (p.arc[i], p.as_laid.get(i).copied().unwrap_or(0.0).max(0.0)))
                .collect(),
            colour: RGBColor(200, 120, 20),
            label: "as laid (statics)",
        }];
        series.extend(p.trenches.iter().enumerate().map(|(k, t)| Labelled {
            points: inside.iter().map(|&i| (p.arc[i], t[i].max(0.0))).collect(),
            colour: shade(k),
            label: &labels[k],
        }));
        legend_panel(
            &areas[0],
            "trench: penetration at rest after each visit (positive down)",
            (
                "arc length from the top (m)",
                "penetration of the invert (m)",
            ),
            &series,
            &[],
            Some(p.window),
        )
        .map_err(&perr)?;
        // Life along the touchdown zone.
        let log = |v: &[f64]| -> Vec<(f64, f64)> {
            inside
                .iter()
                .filter(|&&i| v.get(i).is_some_and(|x| x.is_finite() && *x > 0.0))
                .map(|&i| (p.arc[i], v[i].log10()))
                .collect()
        };
        let mut lives = vec![Labelled {
            points: log(p.life_memory),
            colour: RGBColor(200, 30, 30),
            label: "with the seabed's memory",
        }];
        if !p.life_as_laid.is_empty() {
            lives.push(Labelled {
                points: log(p.life_as_laid),
                colour: RGBColor(20, 90, 200),
                label: "each visit from the as-laid state",
            });
        }
        legend_panel(
            &areas[1],
            "fatigue life along the touchdown zone",
            ("arc length from the top (m)", "log10 life (years)"),
            &lives,
            &[],
            Some(p.window),
        )
        .map_err(&perr)?;
        // Accumulated damage at the critical node.
        let steps = |v: &[f64]| -> Vec<(f64, f64)> {
            v.iter()
                .enumerate()
                .map(|(k, &d)| ((k + 1) as f64, d))
                .collect()
        };
        let mut acc = vec![Labelled {
            points: steps(p.accumulated.0),
            colour: RGBColor(200, 30, 30),
            label: "with memory",
        }];
        if !p.accumulated.1.is_empty() {
            acc.push(Labelled {
                points: steps(p.accumulated.1),
                colour: RGBColor(20, 90, 200),
                label: "as laid",
            });
        }
        legend_panel(
            &areas[2],
            "annual damage at the critical node, accumulated visit by visit",
            ("visits", "annual damage (1/year)"),
            &acc,
            &[],
            None,
        )
        .map_err(&perr)?;
        let caption = if degraded {
            "strength factor δ after the last visit (1: intact)"
        } else {
            "strength factor δ (no degradation in this scene: intact everywhere)"
        };
        lines_panel(
            &areas[3],
            caption,
            ("arc length from the top (m)", "δ = su / su,intact"),
            &[
                Labelled {
                    points: inside
                        .iter()
                        .filter_map(|&i| p.strength.get(i).map(|&s| (p.arc[i], s)))
                        .collect(),
                    colour: RGBColor(60, 60, 60),
                    label: "",
                },
                // The axis from 0 (remoulded to nothing) to 1 (intact), drawn invisibly.
                Labelled {
                    points: vec![(a0, 0.0), (a0, 1.0)],
                    colour: WHITE,
                    label: "",
                },
            ],
            &[],
            Some(p.window),
            false,
        )
        .map_err(&perr)?;
    }
    write_image(path, &rgb, size)
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
