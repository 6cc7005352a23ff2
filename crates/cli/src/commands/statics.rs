//! `catena static`: the static configuration alone.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use catena::run::statics;
use catena::AppError;
use catena_io::h5::{self};
use catena_io::{plot, report};

use super::{warn, write_json};

/// `catena static CASE --out DIR`: `results.h5` (`/static`), `summary.json`, `static.png`.
pub fn static_(case: &Path, out: &Path) -> Result<String, AppError> {
    let scene = statics::read_scene(case)?;
    warn(&scene);
    let run = statics::solve(scene)?;
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let h5p = out.join("results.h5");
    h5::write_static(&h5p, &run)?;
    let js = out.join("summary.json");
    write_json(&js, &report::static_json(&run))?;
    let png: PathBuf = out.join("static.png");
    plot::static_line(&png, &run.scene.title, &run.model, &run.results)?;
    let mut t = report::static_text(&run);
    let _ = writeln!(
        t,
        "  wrote {}, {}, {}",
        h5p.display(),
        js.display(),
        png.display()
    );
    Ok(t)
}
