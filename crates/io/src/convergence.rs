//! The convergence study's outputs: `convergence.csv` (a row per run: its settings, cost, and each
//! key output with its error), `convergence.json`, the text summary and `convergence.png` (|error|
//! against wall time, log–log).

use std::fmt::Write as _;

use catena::studies::convergence::{error_of, Series, SeriesAnalysis, Study, VariantRun};
use serde_json::json;

/// The table as CSV: a row per run; per output its value and its error (mesh series or Δt series).
pub fn csv(st: &Study) -> String {
    let mut s = String::from(
        "series,mesh_factor,dt_factor,elements,min_element_length_m,time_step_s,steps,newton_iterations,step_cuts,wall_s",
    );
    for o in &st.outputs {
        let unit = o.unit.replace('·', "");
        let _ = write!(s, ",{}_{unit},{}_error_percent", o.id, o.id);
    }
    s.push('\n');
    let mut rows: Vec<(Series, &VariantRun)> = Vec::new();
    for ser in [Series::Mesh, Series::TimeStep] {
        rows.extend(st.series(ser).into_iter().map(|r| (ser, r)));
    }
    for (ser, r) in rows {
        let _ = write!(
            s,
            "{},{},{},{},{},{},{},{},{},{:.4}",
            ser.name(),
            r.mesh_factor,
            r.dt_factor,
            r.elements,
            r.min_element_length,
            r.dt,
            r.steps,
            r.newton_iterations,
            r.step_cuts,
            r.wall_seconds
        );
        for (k, v) in r.values.iter().enumerate() {
            let (em, ed) = error_of(st, k, r);
            let e = if ser == Series::Mesh { em } else { ed };
            // An unknown value or error (a failed run, a series of one factor) is an empty cell,
            // never `NaN`.
            let cell = |x: f64| {
                if x.is_finite() {
                    x.to_string()
                } else {
                    String::new()
                }
            };
            let _ = write!(s, ",{},{}", cell(*v), cell(e));
        }
        s.push('\n');
    }
    s
}

/// The study as JSON.
pub fn to_json(st: &Study) -> serde_json::Value {
    let num = |v: f64| {
        if v.is_finite() {
            json!(v)
        } else {
            serde_json::Value::Null
        }
    };
    let an = |a: &SeriesAnalysis| {
        json!({
            "factors": a.factors,
            "values": a.values.iter().map(|v| num(*v)).collect::<Vec<_>>(),
            "observed_order": a.order,
            "richardson": a.extrapolated,
            "gci_percent": a.gci_percent,
            "reference": num(a.reference),
            "reference_kind": a.reference_kind,
            "errors_percent": a.errors_percent.iter().map(|v| num(*v)).collect::<Vec<_>>(),
        })
    };
    json!({
        "case": st.file,
        "title": st.title,
        "catena_version": env!("CARGO_PKG_VERSION"),
        "runs": st.runs.iter().map(|r| json!({
            "mesh_factor": r.mesh_factor, "dt_factor": r.dt_factor, "elements": r.elements,
            "min_element_length": r.min_element_length, "time_step": r.dt, "steps": r.steps,
            "newton_iterations": r.newton_iterations, "step_cuts": r.step_cuts,
            "wall_seconds": r.wall_seconds,
            "values": r.values.iter().map(|v| num(*v)).collect::<Vec<_>>(),
            "error": r.error.as_ref().map(ToString::to_string),
        })).collect::<Vec<_>>(),
        "outputs": st.outputs.iter().zip(&st.analyses).map(|(o, (m, d))| json!({
            "id": o.id, "label": o.label, "unit": o.unit,
            "mesh": an(m), "time_step": an(d),
        })).collect::<Vec<_>>(),
    })
}

/// The study as text.
pub fn summary_text(st: &Study) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "{} — convergence study ({})", st.title, st.file);
    for ser in [Series::Mesh, Series::TimeStep] {
        let runs = st.series(ser);
        let _ = writeln!(
            t,
            "\n{}:",
            match ser {
                Series::Mesh => "element length refined (time step as written)",
                Series::TimeStep => "time step refined (mesh as written)",
            }
        );
        let _ = write!(
            t,
            "  {:>7} {:>8} {:>9} {:>8} {:>5} {:>8}",
            "factor", "elements", "min el m", "dt s", "cuts", "wall s"
        );
        for o in &st.outputs {
            let _ = write!(t, " | {:>24}", format!("{} ({})", o.id, o.unit));
        }
        t.push('\n');
        for r in &runs {
            let f = if ser == Series::Mesh {
                r.mesh_factor
            } else {
                r.dt_factor
            };
            let _ = write!(
                t,
                "  {:>7} {:>8} {:>9.4} {:>8.4} {:>5} {:>8.2}",
                format!("x{f}"),
                r.elements,
                r.min_element_length,
                r.dt,
                r.step_cuts,
                r.wall_seconds
            );
            for k in 0..st.outputs.len() {
                let (em, ed) = error_of(st, k, r);
                let e = if ser == Series::Mesh { em } else { ed };
                if e.is_finite() {
                    let _ = write!(t, " | {:>12.4} {:>+10.4}%", r.values[k], e);
                } else {
                    let _ = write!(t, " | {:>12.4} {:>11}", r.values[k], "unknown");
                }
            }
            if r.error.is_some() {
                t.push_str("  STOPPED EARLY");
            }
            t.push('\n');
        }
        let _ = write!(t, "  {:>58}", "reference (order p, GCI)");
        for (m, d) in &st.analyses {
            let a = if ser == Series::Mesh { m } else { d };
            let tag = match (a.order, a.gci_percent) {
                (Some(p), Some(g)) => format!("R p={p:.2} GCI {g:.3}%"),
                (Some(p), None) => format!("R p={p:.2}"),
                _ => a.reference_kind.into(),
            };
            let _ = write!(t, " | {:>12.4} {:>11}", a.reference, tag);
        }
        t.push('\n');
    }
    if let Some(b) = st.base() {
        let _ = writeln!(
            t,
            "\nthe scene as written ({} elements, dt {} s, {:.2} s): estimated error = |mesh| + |time step|:",
            b.elements, b.dt, b.wall_seconds
        );
        for (k, o) in st.outputs.iter().enumerate() {
            let (em, ed) = error_of(st, k, b);
            let pct = |e: f64| {
                if e.is_finite() {
                    format!("{e:+.4} %")
                } else {
                    "unknown".into()
                }
            };
            let together = if em.is_finite() && ed.is_finite() {
                format!("together ≤ {:.4} %", em.abs() + ed.abs())
            } else {
                "together unknown (refine the unknown one below the scene's own level)".into()
            };
            let _ = writeln!(
                t,
                "  {:<34} {:>12.4} {:<5} mesh {}, time step {}, {together}",
                o.label,
                b.values[k],
                o.unit,
                pct(em),
                pct(ed),
            );
        }
    }
    for r in &st.runs {
        if let Some(e) = &r.error {
            let _ = writeln!(
                t,
                "run x{} mesh, x{} dt stopped early: {e}",
                r.mesh_factor, r.dt_factor
            );
        }
    }
    t
}

pub(crate) fn a_or(a: &SeriesAnalysis) -> String {
    match (a.order, a.reference_kind) {
        (Some(p), _) => format!("Richardson p={p:.1}"),
        (None, "finest") => "finest".into(),
        _ => "none".into(),
    }
}
