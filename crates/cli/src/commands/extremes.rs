//! `catena extremes`: the short-term extremes of recorded channels.

use std::fmt::Write as _;
use std::path::Path;

use catena::AppError;

use super::write_json;

/// What `catena extremes` is asked for.
#[derive(Debug, Clone, Default)]
pub struct ExtremesOptions {
    /// The channels (empty: the defaults of the input).
    pub channels: Vec<String>,
    /// The record starts here, s (default: the file's first time).
    pub start: Option<f64>,
    /// The analysis' target duration, quantile and block (defaults: 3 h, 0.9, 600 s).
    pub settings: catena::checks::extremes::Settings,
}

/// `catena extremes RESULTS.h5|SERIES.csv --out DIR`: the short-term extremes of recorded channels
/// (`catena::checks::extremes`): from a results file, `top_tension`, `least_tension`, `sag_moment`,
/// `utilisation` (with a design check) and `gauge:NAME[:max]`; from a CSV file (a header with
/// `time` first, then one column per channel; a `:min` suffix on a column's name analyses its
/// least), every column or the chosen ones. Writes DIR/extremes.json and DIR/extremes.png.
pub fn extremes(input: &Path, out: &Path, opts: &ExtremesOptions) -> Result<String, AppError> {
    use catena::checks::extremes::{analyse, Tail};
    let bad = |message: String| AppError::Run {
        file: input.display().to_string(),
        message,
    };
    let s = &opts.settings;
    if !(s.target > 0.0 && s.block > 0.0 && s.quantile > 0.0 && s.quantile < 1.0) {
        return Err(bad(
            "--target and --block must be > 0 s and --quantile in (0, 1)".into(),
        ));
    }
    let is_h5 = input.extension().is_some_and(|e| e == "h5" || e == "hdf5");
    let (time, channels) = if is_h5 {
        catena_io::h5::read_extreme_channels(input, &opts.channels)?
    } else {
        let names = catena_io::series::column_names(input)?;
        if names.first().map(String::as_str) != Some("time") {
            return Err(bad(format!(
                "expected `time` (s) as the first column, then one column per channel; the header has {}",
                names.join(", ")
            )));
        }
        let time = catena_io::series::read_series(input, Some("time"))?;
        let wanted: Vec<String> = if opts.channels.is_empty() {
            names[1..].to_vec()
        } else {
            opts.channels.clone()
        };
        let mut v = Vec::new();
        for w in wanted {
            if !names.contains(&w) {
                return Err(bad(format!(
                    "--channel {w}: no such column (the header has {})",
                    names.join(", ")
                )));
            }
            let tail = if w.ends_with(":min") {
                Tail::Min
            } else {
                Tail::Max
            };
            v.push((
                w.clone(),
                tail,
                catena_io::series::read_series(input, Some(&w))?,
            ));
        }
        (time, v)
    };
    if time.len() < 3 {
        return Err(bad("fewer than three samples".into()));
    }
    let dt = time[1] - time[0];
    if time
        .windows(2)
        .any(|w| ((w[1] - w[0]) - dt).abs() > 1e-6 * dt.abs().max(1e-12))
        || dt <= 0.0
    {
        return Err(bad(
            "the times are not equally spaced and increasing (the statistics need a uniform record)".into(),
        ));
    }
    let from = opts.start.unwrap_or(time[0]);
    let first = time.partition_point(|t| *t < from - 1e-9);
    let mut results = Vec::new();
    let mut records = Vec::new();
    for (name, tail, v) in &channels {
        let x = &v[first..];
        match analyse(name, *tail, x, dt, s) {
            Some(e) => {
                results.push(e);
                records.push(x);
            }
            None => {
                return Err(bad(format!(
                    "--channel {name}: too short or constant from t = {from} s to analyse"
                )))
            }
        }
    }
    std::fs::create_dir_all(out).map_err(|e| AppError::io(out, e))?;
    let js = out.join("extremes.json");
    write_json(&js, &serde_json::to_value(&results).unwrap_or_default())?;
    let items: Vec<_> = results
        .iter()
        .zip(&records)
        .map(|(e, x)| (e, *x, dt))
        .collect();
    catena_io::plot::extremes(
        &out.join("extremes.png"),
        &format!("{} — short-term extremes", input.display()),
        &items,
    )?;
    let mut t = format!(
        "extremes of {}: {} channels, records from t = {from} s every {dt} s\n",
        input.display(),
        results.len()
    );
    for e in &results {
        t.push_str(&catena_io::report::extremes_line(e));
    }
    let _ = writeln!(
        t,
        "  wrote {} and {}",
        js.display(),
        out.join("extremes.png").display()
    );
    Ok(t)
}
