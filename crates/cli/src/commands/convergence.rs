//! `catena convergence`: what accuracy costs in time.

use std::fmt::Write as _;
use std::path::Path;

use catena::studies::convergence::ConvergenceOptions;
use catena::AppError;
use catena_io::convergence as cv;

/// The whole command: runs the study and writes `DIR/convergence.csv`, `DIR/convergence.json`,
/// `DIR/convergence.png` and the variant scenes in `DIR/scenes/`.
pub fn convergence(case: &Path, out: &Path, opts: &ConvergenceOptions) -> Result<String, AppError> {
    let st = catena::studies::convergence::study(case, opts)?;
    std::fs::create_dir_all(out.join("scenes")).map_err(|e| AppError::io(out, e))?;
    let stem = case
        .file_stem()
        .map_or_else(|| "case".into(), |s| s.to_string_lossy().into_owned());
    for r in &st.runs {
        let p = out.join("scenes").join(format!(
            "{stem}-mesh{}-dt{}.toml",
            r.mesh_factor, r.dt_factor
        ));
        std::fs::write(&p, &r.scene_text).map_err(|e| AppError::io(&p, e))?;
    }
    let c = out.join("convergence.csv");
    std::fs::write(&c, cv::csv(&st)).map_err(|e| AppError::io(&c, e))?;
    let j = out.join("convergence.json");
    std::fs::write(
        &j,
        serde_json::to_string_pretty(&cv::to_json(&st)).unwrap_or_default(),
    )
    .map_err(|e| AppError::io(&j, e))?;
    let png = out.join("convergence.png");
    catena_io::plot::convergence::plot(&png, &st)?;
    let mut t = cv::summary_text(&st);
    let _ = writeln!(
        t,
        "wrote {}, {}, {} and the variant scenes in {}",
        c.display(),
        j.display(),
        png.display(),
        out.join("scenes").display()
    );
    Ok(t)
}
