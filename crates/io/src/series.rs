//! Time series in CSV (for `catena rainflow` and `catena extremes`): one numeric column, or a column
//! chosen by its header name; and the cycles table it writes (`range,mean,count`, in the order
//! found).

use std::fmt::Write as _;
use std::path::Path;

use catena::checks::fatigue::rainflow::Cycle;
use catena::AppError;

fn bad(path: &Path, message: String) -> AppError {
    AppError::Run {
        file: path.display().to_string(),
        message,
    }
}

/// Reads a series from a CSV file: a header line, then rows; `column` names the column to read
/// (required when there is more than one). Every cell of that column must be a finite number: an
/// error names the line and the column.
pub fn read_series(path: &Path, column: Option<&str>) -> Result<Vec<f64>, AppError> {
    let text = std::fs::read_to_string(path).map_err(|e| AppError::io(path, e))?;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (_, header) = lines.next().ok_or_else(|| {
        bad(
            path,
            "expected a header line and rows of numbers; the file is empty".into(),
        )
    })?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let col = match column {
        Some(c) => names.iter().position(|n| *n == c).ok_or_else(|| {
            bad(
                path,
                format!(
                    "--column {c}: no such column (the header has {})",
                    names.join(", ")
                ),
            )
        })?,
        None if names.len() == 1 => 0,
        None => {
            return Err(bad(
                path,
                format!(
                    "{} columns ({}): choose one with --column NAME",
                    names.len(),
                    names.join(", ")
                ),
            ))
        }
    };
    let mut v = Vec::new();
    for (i, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let cell = cells.get(col).ok_or_else(|| {
            bad(
                path,
                format!("line {}: no value in column `{}`", i + 1, names[col]),
            )
        })?;
        let x: f64 = cell
            .parse()
            .ok()
            .filter(|x: &f64| x.is_finite())
            .ok_or_else(|| {
                bad(
                    path,
                    format!(
                        "line {}: column `{}`: `{cell}` is not a finite number",
                        i + 1,
                        names[col]
                    ),
                )
            })?;
        v.push(x);
    }
    if v.is_empty() {
        return Err(bad(path, "no rows after the header".into()));
    }
    Ok(v)
}

/// Writes the cycles as CSV: `range,mean,count`, in the order found.
pub fn write_cycles(path: &Path, cycles: &[Cycle]) -> Result<(), AppError> {
    let mut s = String::with_capacity(32 * cycles.len() + 20);
    s.push_str("range,mean,count\n");
    for c in cycles {
        let _ = writeln!(s, "{},{},{}", c.range, c.mean, c.count);
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| AppError::io(dir, e))?;
    }
    std::fs::write(path, s).map_err(|e| AppError::io(path, e))
}

/// The header's column names of a CSV file.
pub fn column_names(path: &Path) -> Result<Vec<String>, AppError> {
    let text = std::fs::read_to_string(path).map_err(|e| AppError::io(path, e))?;
    let header = text
        .lines()
        .find(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .ok_or_else(|| {
            bad(
                path,
                "expected a header line and rows of numbers; the file is empty".into(),
            )
        })?;
    Ok(header.split(',').map(|c| c.trim().to_string()).collect())
}
