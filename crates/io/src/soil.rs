//! The soil element test's outputs: the CSV (one row per committed increment) and the text summary.

use std::fmt::Write as _;
use std::path::Path;

use catena::studies::soil_test::SoilTestCase;
use catena::AppError;
use catena_seabed::element_test::TestResult;

/// Writes the CSV of a test.
pub fn write_csv(path: &Path, case: &SoilTestCase, r: &TestResult) -> Result<(), AppError> {
    let mut s = String::with_capacity(r.rows.len() * 120);
    s.push_str("step,leg,cycle,z,P,buoyancy,total,tangent,mode,branch\n");
    for row in &r.rows {
        let cycle = if row.leg == 0 {
            0
        } else {
            case.cycle_of_leg[row.leg - 1]
        };
        let branch = serde_json::to_value(row.branch)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default();
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{}",
            row.step,
            row.leg,
            cycle,
            row.z,
            row.p,
            row.buoyancy,
            row.total,
            row.tangent,
            row.mode.name(),
            branch
        );
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| AppError::io(dir, e))?;
    }
    std::fs::write(path, s).map_err(|e| AppError::io(path, e))
}

/// The summary of a test as text; `out` and `plot` name the files written.
pub fn text(case: &SoilTestCase, r: &TestResult, out: &Path, plot: Option<&Path>) -> String {
    let cycles = case.cycle_ends(r);
    let z_start = case.start_of_cycles(r);
    let d = case.seabed.diameter();
    let mut text = String::new();
    let last = r.rows.last().map_or(0.0, |row| row.z);
    let _ = writeln!(text, "soil test {}", case.file);
    let _ = writeln!(
        text,
        "  model: {}, D = {d} m; {} legs, {} committed increments",
        case.seabed.law.name(),
        case.legs.len(),
        r.rows.len() - 1
    );
    for (i, &e) in r
        .leg_ends
        .iter()
        .enumerate()
        .filter(|(i, _)| case.cycle_of_leg[*i] == 0)
    {
        let row = &r.rows[e];
        let _ = writeln!(
            text,
            "  end of leg {:>3}: z = {:.6} m (z/D = {:.4}), P = {:.3} N/m (P/D = {:.3} kPa), mode {}",
            i + 1,
            row.z,
            row.z / d,
            row.p,
            row.p / d / 1000.0,
            row.mode.name()
        );
    }
    if !cycles.is_empty() {
        let _ = writeln!(
            text,
            "  cycles start at z = {z_start:.6} m (z/D = {:.4}); penetration at the end of each cycle:",
            z_start / d
        );
        let _ = writeln!(
            text,
            "  {:>6} {:>12} {:>12} {:>14} {:>14}",
            "cycle", "z (m)", "z/D", "dz/D (cycle)", "(z-2D)/D"
        );
        let mut prev = z_start;
        for &(c, z) in &cycles {
            let show = c <= 3 || c % 10 == 0 || c == cycles.len();
            if show {
                let _ = writeln!(
                    text,
                    "  {c:>6} {z:>12.6} {:>12.5} {:>14.6} {:>14.5}",
                    z / d,
                    (z - prev) / d,
                    (z - 2.0 * d) / d
                );
            }
            prev = z;
        }
    }
    let _ = writeln!(text, "  final z = {last:.6} m; wrote {}", out.display());
    if let Some(p) = plot {
        let _ = writeln!(text, "  plot {}", p.display());
    }
    text
}
