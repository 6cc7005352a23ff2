//! `catena soil-test`: the soil element test.

use std::path::Path;

use catena::studies::soil_test::SoilTestCase;
use catena::AppError;
use catena_io::{plot, soil};

/// `catena soil-test CASE --out RESULT.csv [--plot PNG]`.
pub fn soil_test(
    case_path: &Path,
    out: &Path,
    plot_path: Option<&Path>,
) -> Result<String, AppError> {
    let case = SoilTestCase::read(case_path)?;
    let r = case.run()?;
    soil::write_csv(out, &case, &r)?;
    if let Some(p) = plot_path {
        let cycles = case.cycle_ends(&r);
        let z_start = case.start_of_cycles(&r);
        plot::soil_test(p, &case, &r, &cycles, z_start)?;
    }
    Ok(soil::text(&case, &r, out, plot_path))
}
