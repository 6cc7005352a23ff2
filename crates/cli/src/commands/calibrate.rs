//! `catena calibrate TEST.csv --law randolph-quiggin --start START.toml --fit KEYS --out FIT.toml`:
//! the Randolph–Quiggin parameters fitted to an element test ([`catena::studies::calibrate`]). Writes the
//! fitted `[seabed]` table (FIT.toml, with the misfit and each parameter's determination in its
//! header comments), FIT.json (the whole report) and FIT.png (test against fit) beside it.

use std::path::Path;

use catena::scene::invalid;
use catena::scene::seabed::SeabedTable;
use catena::studies::calibrate::{calibrate, read_test, seabed_toml};
use catena::AppError;
use catena_seabed::law::Law;

use super::write_json;

/// The start file: any TOML with a `[seabed]` table (a soil-test case, a fitted table); other
/// tables are ignored.
#[derive(serde::Deserialize)]
struct StartFile {
    seabed: SeabedTable,
}

/// Runs the command (see the module docs); `fit` is the comma-separated list of keys.
pub fn run(
    test: &Path,
    law: &str,
    start: &Path,
    fit: &str,
    out: &Path,
) -> Result<String, AppError> {
    let t0 = std::time::Instant::now();
    if law != "randolph-quiggin" {
        return Err(invalid(
            "--law",
            "law",
            format!("\"randolph-quiggin\" (the one law with parameters to fit), got \"{law}\""),
        )
        .into());
    }
    let tfile = test.display().to_string();
    let data = read_test(&tfile, &catena::scene::read_text(test)?)?;
    let sfile = start.display().to_string();
    let raw: StartFile = catena::scene::parse(&sfile, &catena::scene::read_text(start)?)?;
    let seabed = raw.seabed.build(&sfile, "seabed", None, None)?;
    let Law::RandolphQuiggin(rq) = seabed.law else {
        return Err(invalid(
            &sfile,
            "seabed.model",
            "\"randolph-quiggin\" (the law to fit)",
        )
        .into());
    };
    let keys: Vec<String> = fit
        .split(',')
        .map(|k| k.trim().to_string())
        .filter(|k| !k.is_empty())
        .collect();
    let c = calibrate(&data, *rq.params(), &keys, "--fit")?;
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| AppError::io(dir, e))?;
    }
    std::fs::write(out, seabed_toml(&c, &tfile)).map_err(|e| AppError::io(out, e))?;
    write_json(
        &out.with_extension("json"),
        &serde_json::to_value(&c).map_err(|e| AppError::Output {
            path: out.with_extension("json"),
            message: e.to_string(),
        })?,
    )?;
    catena_io::plot::calibration(
        &out.with_extension("png"),
        &format!("{tfile}: fitted {}", keys.join(", ")),
        &data.z,
        (&data.p, &c.start_p, &c.model_p),
    )?;
    let mut t = format!(
        "calibrated {} to {tfile} ({} points): RMS misfit {:.4e} N/m ({:.3} % of the peak force), {:.4e} N/m at the start; {} misfit evaluations, {:.1} s\n",
        keys.join(", "),
        data.z.len(),
        c.rms,
        100.0 * c.rms_relative,
        c.rms_start,
        c.evaluations,
        t0.elapsed().as_secs_f64()
    );
    for d in &c.determination {
        t.push_str(&format!(
            "  {:<12} {:>14.6e} (start {:.6e}): {}; 1 % moves P by {:.2e} of the peak; relative standard error {:.2e} (with a 0.1 % scatter: {:.2e})\n",
            d.name,
            d.value,
            d.start,
            d.verdict,
            d.sensitivity_per_percent,
            d.relative_standard_error,
            d.error_at_reference_scatter
        ));
    }
    t.push_str(&format!(
        "  wrote {}, {}, {}\n",
        out.display(),
        out.with_extension("json").display(),
        out.with_extension("png").display()
    ));
    Ok(t)
}
