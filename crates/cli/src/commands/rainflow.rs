//! `catena rainflow`: rainflow counting (and Miner damage) of one column of a CSV series.

use std::fmt::Write as _;
use std::path::Path;

use catena::AppError;

/// `catena rainflow SERIES.csv --out CYCLES.csv [--column NAME] [--sn CURVE] [--scf X]`: rainflow
/// counting (ASTM E1049-85) of one column; with an S-N curve, Miner's damage of the series (its
/// values taken as stress in MPa, multiplied by the SCF).
pub fn rainflow(
    series: &Path,
    out: &Path,
    column: Option<&str>,
    sn: Option<&str>,
    scf: f64,
) -> Result<String, AppError> {
    let curve = match sn {
        Some(name) => Some(
            catena::checks::fatigue::sn::SnCurve::dnv(name).ok_or_else(|| AppError::Run {
                file: series.display().to_string(),
                message: format!(
                    "--sn {name}: not a curve catena knows; expected one of {}",
                    catena::checks::fatigue::sn::NAMES.join(", ")
                ),
            })?,
        ),
        None => None,
    };
    if !(scf.is_finite() && scf > 0.0) {
        return Err(AppError::Run {
            file: series.display().to_string(),
            message: format!("--scf {scf}: expected a stress concentration factor > 0"),
        });
    }
    let v = catena_io::series::read_series(series, column)?;
    let cycles = catena::checks::fatigue::rainflow::count(&v);
    catena_io::series::write_cycles(out, &cycles)?;
    let total: f64 = cycles.iter().map(|c| c.count).sum();
    let largest = cycles.iter().map(|c| c.range).fold(0.0, f64::max);
    let mut t = format!(
        "rainflow {}: {} samples, {} cycles counted ({} in all, halves included), largest range {largest}\n  wrote {}\n",
        series.display(),
        v.len(),
        cycles.len(),
        total,
        out.display()
    );
    if let (Some(c), Some(name)) = (curve, sn) {
        let d =
            catena::checks::fatigue::sn::miner(cycles.iter().map(|c| (c.range, c.count)), &c, scf);
        let _ = writeln!(
            t,
            "  Miner damage on {name} (SCF {scf}, ranges in MPa): {d:.6e}"
        );
    }
    Ok(t)
}
