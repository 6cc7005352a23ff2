//! The sea and the hang-off (`sea.png`): the records, a readable window of each, and their
//! realised spectra against the target JONSWAP.
//!
//! **Realised spectrum.** The record after the waves' ramp, its mean removed, `x_n` (n = 0..N−1,
//! interval Δt), has the discrete Fourier transform `X_k = Σ x_n e^{−2πikn/N}` (`rustfft`). The
//! one-sided spectral density in ω (m²·s/rad, the convention of `catena_fe::waves::jonswap`) at
//! `ω_k = 2πk/(NΔt)` is the periodogram `S(ω_k) = 2|X_k|²Δt/(2πN)`, so that `Σ S(ω_k)Δω` is the
//! record's variance (Parseval). It is averaged over `m` neighbouring frequencies (Daniell's
//! smoothing, `2m` degrees of freedom) so that its resolution is about ω_p/25.

use std::path::Path;

use plotters::prelude::*;
use rustfft::num_complex::Complex;

use catena::run::DynamicRun;
use catena::AppError;

use super::*;

/// The sea and the hang-off (runs with waves). Left, the whole record (a band per pixel column
/// where it is long); right, the 100 s around its largest value: the wave elevation at the RAO
/// origin (or above the top end without a vessel) and the vessel's pitch; the hang-off's
/// displacement from its static position — horizontal (blue), vertical (red) and along the
/// riser's static top tangent (black, the motion that drives touchdown fatigue). Beneath, the
/// realised spectra of the elevation and of the hang-off's motion on log axes, against the
/// target JONSWAP of the scene's `[waves]`.
pub fn sea(path: &Path, r: &DynamicRun) -> Result<(), AppError> {
    let Some(waves) = r.model.environment.waves.as_ref() else {
        return Ok(());
    };
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let size = (1800, 1500);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let title = format!("{} — sea and hang-off motion", r.statics.scene.title);
        let root = root.titled(&title, ("sans-serif", 24)).map_err(&err)?;
        let rows = root.split_evenly((3, 1));
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
        let (black, red, blue) = (
            RGBColor(0, 0, 0),
            RGBColor(200, 30, 30),
            RGBColor(20, 90, 200),
        );
        let mut series = vec![(eta.clone(), blue)];
        if r.model.vessel.is_some() {
            series.push((pitch, red));
        }
        record_and_window(
            &rows[0],
            "wave elevation at the RAO origin (blue, m) and vessel pitch (red, deg, positive bow down)",
            "η (m), pitch (deg)",
            &series,
        )
        .map_err(&perr)?;
        let (x0, z0) = (r.statics.results.x[0], r.statics.results.z[0]);
        let th = r.statics.summary.top_angle_from_vertical;
        let moved = |f: &dyn Fn(f64, f64) -> f64| -> Vec<(f64, f64)> {
            h.t.iter()
                .zip(h.top_x.iter().zip(&h.top_z))
                .map(|(t, (x, z))| (*t, f(x - x0, z - z0)))
                .collect()
        };
        let (dx, dz) = (moved(&|dx, _| dx), moved(&|_, dz| dz));
        let ax = moved(&|dx, dz| dx * th.sin() + dz * th.cos());
        record_and_window(
            &rows[1],
            "hang-off displacement: horizontal (blue), vertical (red), along the riser's top tangent (black)",
            "displacement (m)",
            &[(dx, blue), (dz.clone(), red), (ax.clone(), black)],
        )
        .map_err(&perr)?;
        let target = target_sea(r);
        let resolution = target.map_or(0.02, |(_, tp, _)| 2.0 * std::f64::consts::PI / tp / 25.0);
        let after = |v: &[(f64, f64)]| -> Vec<(f64, f64)> {
            v.iter().copied().filter(|p| p.0 >= waves.ramp).collect()
        };
        let spectra = [
            (
                realised_spectrum(&after(&eta), resolution),
                blue,
                "wave elevation",
            ),
            (
                realised_spectrum(&after(&dz), resolution),
                red,
                "hang-off, vertical",
            ),
            (
                realised_spectrum(&after(&ax), resolution),
                black,
                "hang-off, along the top tangent",
            ),
        ];
        spectra_panel(&rows[2], &spectra, target).map_err(&perr)?;
    }
    write_image(path, &rgb, size)
}

/// A row: the whole record (left, two thirds) and the [`WINDOW`] around the largest value of its
/// first series (right); a record of at most twice the window across the row.
fn record_and_window<DB: DrawingBackend>(
    row: &DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    ylabel: &str,
    series: &[(Vec<(f64, f64)>, RGBColor)],
) -> Result<(), String> {
    let Some((first, _)) = series.first() else {
        return Ok(());
    };
    if !wants_window(first) {
        // A short record reads whole.
        return panel(row, caption, "time (s)", ylabel, series);
    }
    let width = row.dim_in_pixel().0;
    let (whole, window) = row.split_horizontally(width * 2 / 3);
    panel(&whole, caption, "time (s)", ylabel, series)?;
    let (_, (lo, hi)) = window_around_peak(first, WINDOW);
    let near: Vec<(Vec<(f64, f64)>, RGBColor)> = series
        .iter()
        .map(|(v, c)| {
            let kept = v.iter().copied().filter(|p| p.0 >= lo && p.0 <= hi);
            (kept.collect(), *c)
        })
        .collect();
    panel(
        &window,
        &format!("{WINDOW:.0} s around the largest |value| of the first"),
        "time (s)",
        ylabel,
        &near,
    )
}

/// The target sea state `(Hs, Tp, γ)` of a JONSWAP `[waves]` table (γ by the DNV-RP-C205 rule
/// when the table gives none); `None` for regular waves.
fn target_sea(r: &DynamicRun) -> Option<(f64, f64, f64)> {
    let w = r.statics.scene.doc.get("waves")?.as_table()?;
    let num = |k: &str| {
        w.get(k)
            .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
    };
    if w.get("kind").and_then(|k| k.as_str()) != Some("jonswap") {
        return None;
    }
    let (hs, tp) = (num("hs")?, num("tp")?);
    let gamma = num("gamma").unwrap_or_else(|| catena_fe::waves::dnv_gamma(hs, tp));
    Some((hs, tp, gamma))
}

/// The realised one-sided spectral density `(ω, S(ω))` (rad/s, units²·s/rad) of a uniformly
/// sampled record, smoothed to about `resolution` rad/s (see the module docs); empty for fewer
/// than 16 samples.
pub fn realised_spectrum(record: &[(f64, f64)], resolution: f64) -> Vec<(f64, f64)> {
    let n = record.len();
    if n < 16 {
        return Vec::new();
    }
    let dt = (record[n - 1].0 - record[0].0) / (n - 1) as f64;
    let mean = record.iter().map(|p| p.1).sum::<f64>() / n as f64;
    let mut x: Vec<Complex<f64>> = record
        .iter()
        .map(|p| Complex::new(p.1 - mean, 0.0))
        .collect();
    rustfft::FftPlanner::new()
        .plan_fft_forward(n)
        .process(&mut x);
    let d_omega = 2.0 * std::f64::consts::PI / (n as f64 * dt);
    let m = ((resolution / d_omega).round() as usize).max(1);
    let scale = 2.0 * dt / (2.0 * std::f64::consts::PI * n as f64);
    let half = (n - 1) / 2;
    (1..=half)
        .step_by(m)
        .filter(|k| k + m - 1 <= half)
        .map(|k| {
            let s: f64 = (k..k + m).map(|j| x[j].norm_sqr() * scale).sum::<f64>() / m as f64;
            ((k as f64 + 0.5 * (m - 1) as f64) * d_omega, s)
        })
        .collect()
}

/// The spectra on log axes over `[0.3, 5]·ω_p` (ω_p from the target, else from the elevation's
/// peak), with the target JONSWAP dashed.
fn spectra_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    spectra: &[(Points, RGBColor, &str)],
    target: Option<(f64, f64, f64)>,
) -> Result<(), String> {
    let wp = target
        .map(|(_, tp, _)| 2.0 * std::f64::consts::PI / tp)
        .unwrap_or_else(|| {
            spectra[0]
                .0
                .iter()
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .map_or(1.0, |p| p.0)
        });
    let (w0, w1) = (0.3 * wp, 5.0 * wp);
    let target_line: Vec<(f64, f64)> = target.map_or(Vec::new(), |(hs, tp, g)| {
        (0..=200)
            .map(|i| w0 * (w1 / w0).powf(i as f64 / 200.0))
            .map(|w| (w, catena_fe::waves::jonswap(w, hs, tp, g)))
            .collect()
    });
    let in_band = |v: &[(f64, f64)]| -> Vec<(f64, f64)> {
        v.iter()
            .copied()
            .filter(|p| p.0 >= w0 && p.0 <= w1 && p.1 > 0.0)
            .collect()
    };
    let shown: Vec<Vec<(f64, f64)>> = spectra.iter().map(|s| in_band(&s.0)).collect();
    let s_hi = shown
        .iter()
        .flatten()
        .chain(&target_line)
        .map(|p| p.1)
        .fold(0.0f64, f64::max)
        .max(1e-12);
    let (s0, s1) = (s_hi * 1e-5, s_hi * 3.0);
    let log_label = |v: &f64| format!("{v:.0e}");
    let mut chart = ChartBuilder::on(area)
        .caption(
            "realised spectra (one-sided, after the ramp) against the target JONSWAP (dashed)",
            ("sans-serif", 18),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d((w0..w1).log_scale(), (s0..s1).log_scale())
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .opaque_grid()
        .x_desc("ω (rad/s)")
        .y_desc("S(ω) (m²·s/rad)")
        .x_label_formatter(&|v| format!("{v:.2}"))
        .y_label_formatter(&log_label)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(|e| e.to_string())?;
    let grey = RGBColor(90, 90, 90);
    if !target_line.is_empty() {
        chart
            .draw_series(DashedLineSeries::new(
                target_line.iter().map(|p| (p.0, p.1.max(s0))),
                8,
                5,
                grey.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?
            .label("target JONSWAP (the wave elevation's)")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], grey.stroke_width(2))
            });
    }
    for (pts, (_, c, label)) in shown.iter().zip(spectra) {
        let c = *c;
        chart
            .draw_series(super::segments(
                pts.iter().map(|p| (p.0, p.1.max(s0))),
                c.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?
            .label(*label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sine of amplitude a at ω0 (with a weaker one at 2.5 ω0), sampled every 0.5 s for 2000 s:
    /// the realised spectrum holds the record's variance a²/2 + b²/2 within 1 % and peaks at ω0
    /// within its resolution.
    #[test]
    fn realised_spectrum_holds_the_variance_and_the_peak() {
        let (a, b, w0) = (2.0, 0.5, 0.8);
        let rec: Vec<(f64, f64)> = (0..4000)
            .map(|i| 0.5 * i as f64)
            .map(|t| (t, 3.0 + a * (w0 * t).cos() + b * (2.5 * w0 * t + 0.3).sin()))
            .collect();
        let res = 0.02;
        let s = realised_spectrum(&rec, res);
        let dw = s[1].0 - s[0].0;
        let var: f64 = s.iter().map(|p| p.1 * dw).sum();
        let expected = 0.5 * (a * a + b * b);
        assert!(
            (var - expected).abs() < 0.01 * expected,
            "{var} against {expected}"
        );
        let peak = s
            .iter()
            .max_by(|x, y| x.1.total_cmp(&y.1))
            .expect("a peak")
            .0;
        assert!((peak - w0).abs() <= res, "peak at {peak} rad/s, not {w0}");
    }

    /// A long record is drawn as per-column bands: 10 000 points on 100 columns give 100 bands,
    /// each holding its column's least and greatest value, the mean between them.
    #[test]
    fn column_bands_hold_each_columns_extremes() {
        let pts: Vec<(f64, f64)> = (0..10_000)
            .map(|i| i as f64 * 0.01)
            .map(|t| (t, (7.0 * t).sin()))
            .collect();
        let bands = column_bands(&pts, (0.0, 100.0), 100);
        assert_eq!(bands.len(), 100);
        for (k, b) in bands.iter().enumerate() {
            let inside: Vec<f64> = pts
                .iter()
                .filter(|p| (p.0 / 1.0).floor() as usize == k)
                .map(|p| p.1)
                .collect();
            let lo = inside.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = inside.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            assert_eq!((b[1], b[2]), (lo, hi), "column {k}");
            assert!(b[1] <= b[3] && b[3] <= b[2]);
        }
        let (near, (lo, hi)) = window_around_peak(&[(0.0, 1.0), (50.0, -9.0), (99.0, 2.0)], 20.0);
        assert_eq!((lo, hi), (40.0, 60.0));
        assert_eq!(near, vec![(50.0, -9.0)]);
    }
}
