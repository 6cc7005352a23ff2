//! `catena animate`: the animated touchdown zone.

use std::path::Path;

use catena::AppError;

/// `catena animate RESULTS.h5 --out tdz.gif`: the animated touchdown zone
/// ([`catena_io::animate`]); prints the frames, the file's size and the time it took.
pub fn animate(
    results: &Path,
    out: &Path,
    frames: usize,
    fps: f64,
    colour: &str,
) -> Result<String, AppError> {
    let bad = |key: &str, what: String| AppError::Run {
        file: results.display().to_string(),
        message: format!("{key}: {what}"),
    };
    let colour = catena_io::animate::Colour::parse(colour).ok_or_else(|| {
        bad(
            "--colour",
            format!("expected penetration or seabed-force, got `{colour}`"),
        )
    })?;
    if frames < 2 {
        return Err(bad(
            "--frames",
            format!("expected at least 2, got {frames}"),
        ));
    }
    if !(fps.is_finite() && fps > 0.0 && fps <= 50.0) {
        return Err(bad("--fps", format!("expected 0 < fps <= 50, got {fps}")));
    }
    if out.extension().and_then(|e| e.to_str()) != Some("gif") {
        return Err(bad(
            "--out",
            format!("expected a file name ending in .gif, got {}", out.display()),
        ));
    }
    let t0 = std::time::Instant::now();
    let rec = catena_io::h5::read_animation(results)?;
    let opts = catena_io::animate::Options {
        frames,
        fps,
        colour,
        ..Default::default()
    };
    let r = catena_io::animate::animate(out, &rec, &opts)?;
    let [(a0, b0), (a1, b1)] = r.windows;
    let follows = if rec.follow_touchdown {
        format!(
            "; the touchdown zone follows the touchdown, x {a0:.1}–{b0:.1} m to {a1:.1}–{b1:.1} m"
        )
    } else {
        String::new()
    };
    Ok(format!(
        "animation: {} ({} frames of {:.1} s of the run, {:.0} kB, {:.1} s to draw{follows})\n",
        out.display(),
        r.frames,
        r.seconds,
        r.bytes as f64 / 1e3,
        t0.elapsed().as_secs_f64()
    ))
}
