//! PNG plots, drawn with plotters. The font (DejaVu Sans, Bitstream Vera licence, `assets/`) is
//! embedded in the binary, so plots need nothing from the system.
//!
//! One module per figure family; this module holds what every figure shares: the font, the colours,
//! the canvas and the PNG writer, the opaque grid, and the panels (framed charts, legends, lines).
//! A new figure: a function in its family's module (or a new module here), drawn on `pixels` with
//! the shared panels, written by `write_image`, re-exported below.

mod checks;
pub mod convergence;
mod dynamic;
mod lay;
// The fatigue study's figures read its tables (`crate::fatigue`, with HDF5).
#[cfg(feature = "hdf5")]
pub mod fatigue;
mod line;
mod sea;
mod sequence;
mod soil;
pub mod sweep;

pub use checks::{design_check, extremes, strength};
pub use dynamic::{dynamic, dynamic_on, gauges};
pub use lay::lay;
pub use line::{ranges, ranges_on, static_line};
pub use sea::sea;
pub use sequence::{sequence, SequencePlot};
pub use soil::{calibration, soil_test};

use std::path::Path;
use std::sync::Once;

use catena_seabed::rq::Mode;
use plotters::prelude::*;

use catena::AppError;

static FONT: &[u8] = include_bytes!("../../../../assets/DejaVuSans.ttf");
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

/// The largest size of [`ranges`]' plot: every quantity of [`catena::run::observe::RANGE_QUANTITIES`]
/// present.
pub const RANGES_MAX_SIZE: (u32, u32) = ranges_size(catena::run::observe::RANGE_QUANTITIES.len());

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

#[cfg(test)]
mod tick_tests {
    use plotters::coord::ranged1d::Ranged;
    use plotters::coord::types::RangedCoordf64;
    use plotters::prelude::*;

    /// The shared axis drawn at 1e-9, 1 and 1e9 (ranges from zero, narrow ranges far from zero as
    /// a tension record's, ranges across zero): the labels of the ticks plotters puts on the axis
    /// are all different, none is `0` but at zero, each reads back within a fifth of a tick
    /// spacing of its value, and none is longer than 9 characters (they fit the label area).
    #[test]
    fn tick_labels_read_at_every_magnitude() {
        super::init_fonts();
        for scale in [1e-9, 1.0, 1e9] {
            for (lo, hi) in [(0.0, 3.0), (1.395, 1.44), (-2.0, 5.0), (0.0, 0.012)] {
                let (lo, hi) = (lo * scale, hi * scale);
                let size = (400, 300);
                let mut rgb = super::pixels(size, None);
                {
                    let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
                    super::framed_chart(&root, "ticks", ("x", "y"), (lo, hi), (lo, hi))
                        .expect("the axis draws");
                }
                assert!(rgb.iter().any(|&b| b < 128), "labels drawn at {scale:e}");
                let f = super::ticks(lo, hi);
                let keys = RangedCoordf64::from(lo..hi).key_points(10);
                assert!(keys.len() >= 3, "{lo:e}..{hi:e}: {keys:?}");
                let spacing = keys[1] - keys[0];
                let labels: Vec<String> = keys.iter().map(&f).collect();
                for (k, l) in keys.iter().zip(&labels) {
                    let back: f64 = l.parse().unwrap_or_else(|_| panic!("{l} parses"));
                    assert!(
                        (back - k).abs() <= 0.2 * spacing,
                        "{lo:e}..{hi:e}: {k:e} reads {l}"
                    );
                    assert!(l.len() <= 9, "{lo:e}..{hi:e}: {l} is too long");
                    assert!(*k == 0.0 || l != "0", "{lo:e}..{hi:e}: {k:e} reads 0");
                }
                for w in labels.windows(2) {
                    assert_ne!(w[0], w[1], "{lo:e}..{hi:e}: neighbouring ticks read alike");
                }
            }
        }
    }
}

/// Pads a range by 5 % on each side (and widens an empty one).
pub fn padded(lo: f64, hi: f64) -> (f64, f64) {
    let span = (hi - lo)
        .abs()
        .max(1e-9 * hi.abs().max(lo.abs()).max(1e-12));
    (lo - 0.05 * span, hi + 0.05 * span)
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
) -> Result<Chart<'a, DB>, String> {
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
) -> Result<Chart<'a, DB>, String> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", caption_size))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| e.to_string())?;
    let (fx, fy) = (ticks(x0, x1), ticks(y0, y1));
    // About one label to 90 pixels, so that a narrow panel's labels do not run together.
    let x_labels = (chart.plotting_area().dim_in_pixel().0 as usize / 90).clamp(3, 10);
    chart
        .configure_mesh()
        .opaque_grid()
        .x_labels(x_labels)
        .x_desc(xlabel)
        .y_desc(ylabel)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

/// The tick labels of a linear axis from `lo` to `hi`, readable at any magnitude: plain decimals
/// with as many places as the tick spacing needs (`0.25`, `1400`) while the axis' largest value is
/// between 1e-3 and 1e5, scientific notation with as many digits as neighbouring ticks need to
/// differ (`1.2e-7`, `1.395e6`) outside it. Zero is `0`. Every figure's axes use it (through
/// [`framed_chart`], or directly as `x_label_formatter(&ticks(lo, hi))`).
pub fn ticks(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let big = lo.abs().max(hi.abs());
    let span = (hi - lo).abs();
    // plotters puts about ten ticks on an axis: their spacing's decade.
    let step = if span > 0.0 && span.is_finite() {
        span / 10.0
    } else {
        big.max(1e-300)
    };
    let step_exp = step.log10().floor();
    let scientific = big > 0.0 && !(1e-3..1e5).contains(&big);
    let digits = if big > 0.0 {
        (big.log10().floor() - step_exp).clamp(0.0, 8.0) as usize
    } else {
        0
    };
    let decimals = (-step_exp).clamp(0.0, 9.0) as usize;
    move |&v: &f64| {
        if v == 0.0 || (span > 0.0 && v.abs() < 1e-9 * span) {
            "0".to_string()
        } else if scientific {
            format!("{v:.digits$e}")
        } else {
            format!("{v:.decimals$}")
        }
    }
}

/// A series of points `(x, y)`.
pub(crate) type Points = Vec<(f64, f64)>;

/// A chart of two linear f64 axes, as every panel here draws on.
type Chart<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Each pixel column's least and greatest value and the mean of its points, `(x, min, max,
/// mean)`, for a series sorted by x drawn `columns` pixels wide over `(x0, x1)`. Empty columns are
/// left out.
pub fn column_bands(points: &[(f64, f64)], (x0, x1): (f64, f64), columns: usize) -> Vec<[f64; 4]> {
    let columns = columns.max(1);
    let width = (x1 - x0) / columns as f64;
    let mut out: Vec<[f64; 4]> = Vec::with_capacity(columns);
    let mut current: Option<(usize, f64, f64, f64, usize)> = None;
    let close = |c: (usize, f64, f64, f64, usize), out: &mut Vec<[f64; 4]>| {
        let x = x0 + (c.0 as f64 + 0.5) * width;
        out.push([x, c.1, c.2, c.3 / c.4 as f64]);
    };
    for &(x, y) in points.iter().filter(|p| p.1.is_finite()) {
        let k = (((x - x0) / width).floor().max(0.0) as usize).min(columns - 1);
        current = match current {
            Some(c) if c.0 == k => Some((k, c.1.min(y), c.2.max(y), c.3 + y, c.4 + 1)),
            Some(c) => {
                close(c, &mut out);
                Some((k, y, y, y, 1))
            }
            None => Some((k, y, y, y, 1)),
        };
    }
    if let Some(c) = current {
        close(c, &mut out);
    }
    out
}

/// A line of more than a pixel's width as its separate segments: plotters joins the segments of a
/// wide `LineSeries` with mitres, and at a peak a pixel or two wide a mitre reaches far beyond the
/// data, out of its panel and across the next (plotters' issue 347). Segments have no joins.
pub(crate) fn segments(
    points: impl IntoIterator<Item = (f64, f64)>,
    style: ShapeStyle,
) -> Vec<PathElement<(f64, f64)>> {
    let p: Vec<(f64, f64)> = points.into_iter().collect();
    p.windows(2)
        .map(|w| PathElement::new(vec![w[0], w[1]], style))
        .collect()
}

/// Draws a series as a line; a long one (more than two points to a pixel column, where a line
/// would blot into a block and dots break up) as each pixel column's least-to-greatest band in a
/// light shade of its colour with a line through the columns' means.
fn line_or_band<'a, 'b, DB: DrawingBackend + 'a>(
    chart: &'b mut Chart<'a, DB>,
    points: &[(f64, f64)],
    colour: RGBColor,
) -> Result<&'b mut plotters::chart::SeriesAnno<'a, DB>, String> {
    let columns = chart.plotting_area().dim_in_pixel().0 as usize;
    if points.len() <= 2 * columns.max(1) {
        return chart
            .draw_series(segments(points.iter().copied(), colour.stroke_width(2)))
            .map_err(|e| e.to_string());
    }
    let range = chart.x_range();
    let bands = column_bands(points, (range.start, range.end), columns);
    let outline: Vec<(f64, f64)> = bands
        .iter()
        .map(|b| (b[0], b[2]))
        .chain(bands.iter().rev().map(|b| (b[0], b[1])))
        .collect();
    let light = colour.mix(0.35);
    chart
        .draw_series(std::iter::once(Polygon::new(outline, light.filled())))
        .map_err(|e| e.to_string())?;
    chart
        .draw_series(LineSeries::new(
            bands.iter().map(|b| (b[0], b[3])),
            colour.stroke_width(1),
        ))
        .map_err(|e| e.to_string())
}

/// What a reader's window of a long record spans, s.
pub const WINDOW: f64 = 100.0;

/// Whether a record `(t, value)` is long enough to be drawn with a [`WINDOW`] beside it (more than
/// twice the window); a shorter one reads whole.
pub fn wants_window(points: &[(f64, f64)]) -> bool {
    let span = points.last().map_or(0.0, |l| l.0) - points.first().map_or(0.0, |f| f.0);
    span > 2.0 * WINDOW
}

/// The points of a series within `span` of its largest absolute value's x (a window a reader can
/// read in a long record), and the window.
pub fn window_around_peak(points: &[(f64, f64)], span: f64) -> (Vec<(f64, f64)>, (f64, f64)) {
    let peak = points
        .iter()
        .filter(|p| p.1.is_finite())
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map_or(0.0, |p| p.0);
    let (first, last) = (
        points.first().map_or(0.0, |p| p.0),
        points.last().map_or(0.0, |p| p.0),
    );
    let lo = (peak - 0.5 * span).max(first).min((last - span).max(first));
    let hi = (lo + span).min(last);
    let kept = points
        .iter()
        .copied()
        .filter(|p| p.0 >= lo && p.0 <= hi)
        .collect();
    (kept, (lo, hi))
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
        let shown: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|(x, _)| x_range.is_none_or(|(a, b)| *x >= a && *x <= b))
            .collect();
        let drawn = line_or_band(&mut chart, &shown, c)?;
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
            .draw_series(segments(v.iter().copied(), c.stroke_width(2)))
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
            Marks::Lines => line_or_band(&mut chart, v, *c).map(|_| ()),
            Marks::Points => chart
                .draw_series(v.iter().map(|p| Circle::new(*p, 2, c.filled())))
                .map(|_| ())
                .map_err(|e| e.to_string()),
        }?;
    }
    Ok(())
}

#[cfg(test)]
mod line_tests {
    use plotters::prelude::*;

    /// A record of sharp one-sample spikes (a tension ringing at a window's moves), fewer points
    /// than two a pixel column so drawn as a line: nothing of its colour outside its panel, the
    /// lower half of the image (plotters' mitres at such peaks reached the panel above).
    #[test]
    fn a_spiky_line_stays_in_its_panel() {
        super::init_fonts();
        let size = (900u32, 800u32);
        let colour = RGBColor(200, 30, 30);
        let points: Vec<(f64, f64)> = (0..1200)
            .map(|i| {
                (
                    i as f64,
                    if i % 37 == 0 {
                        113.0
                    } else {
                        111.5 + 1e-3 * (i % 2) as f64
                    },
                )
            })
            .collect();
        let mut rgb = super::pixels(size, None);
        {
            let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
            let halves = root.split_evenly((2, 1));
            super::lines_panel(
                &halves[1],
                "spikes",
                ("t", "T"),
                &[super::Labelled {
                    points,
                    colour,
                    label: "",
                }],
                &[],
                None,
                false,
            )
            .expect("draws");
        }
        let red = |px: &[u8]| px == [colour.0, colour.1, colour.2];
        let (upper, lower) = rgb.split_at(3 * (size.0 * size.1 / 2) as usize);
        assert!(lower.chunks(3).any(red), "the line is drawn");
        let out = upper.chunks(3).filter(|p| red(p)).count();
        assert_eq!(out, 0, "{out} pixels of the line above its panel");
    }
}
