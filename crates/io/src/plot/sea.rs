//! The sea and the hang-off (`sea.png`).

use std::path::Path;

use plotters::prelude::*;

use catena::run::DynamicRun;
use catena::AppError;

use super::*;

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
