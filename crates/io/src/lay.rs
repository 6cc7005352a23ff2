//! A lay's summary: `summary.json`'s `lay` object (SI units; values never measured are `null`)
//! and the text for the terminal (kN, kN·m, mm).

use std::fmt::Write as _;

use catena::run::lay::LayRun;
use serde_json::{json, Value};

use crate::report::{num, static_json};

/// The lay's summary as JSON: the static summary of the start with a `lay` object.
pub fn json(r: &LayRun) -> Value {
    let mut js = static_json(&r.statics);
    let s = &r.summary;
    js["lay"] = json!({
        "completed": r.stop.is_none(),
        "stopped": r.stop.as_ref().map(ToString::to_string),
        "time_reached": num(r.records.time.last().copied().unwrap_or(0.0)),
        "paid_out": num(s.paid_out),
        "vessel_travel": num(s.vessel_travel),
        "tower_angle_deg": num(r.tower_angle.to_degrees()),
        "warnings": r.warnings,
        "target_tension": r.target_tension.map(num),
        "steady_nodes": s.steady_nodes,
        "as_laid_embedment": {
            "mean": num(s.as_laid_mean), "min": num(s.as_laid_min), "max": num(s.as_laid_max),
            "range": num(s.as_laid_max - s.as_laid_min),
        },
        "submerged_weight": num(s.submerged_weight),
        "self_weight_embedment": num(s.self_weight_embedment),
        "static_embedment": num(s.static_embedment),
        "static_lay_factor": num(s.static_lay_factor),
        "lay_factor": num(s.lay_factor),
        "lay_factor_closed_form": num(s.lay_factor_closed_form),
        "lambda": num(s.lambda),
        "dynamic_embedment_factor": num(s.dynamic_embedment_factor),
        "top_tension": { "min": num(s.top_tension_min), "max": num(s.top_tension_max),
                         "range": num(s.top_tension_max - s.top_tension_min) },
        "sag_bend": { "moment_max": num(s.sag_moment_max), "strain_max": num(s.sag_strain_max) },
        "episodes_mean": num(s.episodes_mean),
        "steps": r.steps, "iterations": r.iterations, "cuts": r.cuts,
        "windows": r.windows,
        "window_nodes_mean": num(mean(&r.records.window_nodes)),
        "nodes": r.full.nodes(),
        "wall_seconds": num(r.wall_seconds),
        "stepping_threads": r.stepping_threads,
        "installation_check": r.installation.as_ref().map(|c| json!({
            "code": c.spec.code.name(),
            "lcc_max": num(c.lcc_max.0),
            "lcc_max_time": num(c.lcc_max.1),
            "lcc_max_kp": num(c.lcc_max.2),
            "lcc_max_arc_from_exit": num(c.lcc_max.3),
            "dcc_max": num(c.dcc_max.0),
            "dcc_max_strain": num(c.dcc_max.1),
            "dcc_max_time": num(c.dcc_max.2),
            "dcc_max_kp": num(c.dcc_max.3),
            "strain_resistance": num(c.strain_resistance),
        })),
        "lay_down": r.lay_down.map(|d| json!({
            "pipe_end_left_tower_at": num(d.left_tower),
            "kp_touchdown_then": num(d.kp_touchdown),
            "rested_at": d.rested.map(num),
            "end_embedment": num(d.end_embedment),
        })),
    });
    js["lay"]["steps_on_two_threads"] = r.steps_on_two.into();
    js
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// The lay's summary as text.
pub fn text(r: &LayRun) -> String {
    let s = &r.summary;
    let mm = |z: f64| z * 1e3;
    let mut t = String::new();
    let _ = writeln!(t, "{}", r.statics.scene.title);
    for w in &r.warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    let _ = writeln!(
        t,
        "  lay: {:.1} m paid out, vessel {:.1} m along the route in {:.1} s; tower {:.2}° from the vertical",
        s.paid_out,
        s.vessel_travel,
        r.records.time.last().copied().unwrap_or(0.0),
        r.tower_angle.to_degrees()
    );
    let _ = writeln!(
        t,
        "  as-laid embedment over {} steady nodes: mean {:.1} mm (range {:.1} to {:.1} mm); self-weight {:.1} mm, static with force concentration {:.1} mm",
        s.steady_nodes,
        mm(s.as_laid_mean),
        mm(s.as_laid_min),
        mm(s.as_laid_max),
        mm(s.self_weight_embedment),
        mm(s.static_embedment)
    );
    let _ = writeln!(
        t,
        "  touchdown lay factor {:.3} (statics {:.3}; Randolph & White 0.6 + 0.4 λ^0.25 = {:.3} at λ = EI·k/T0² = {:.3e}); dynamic embedment factor {:.2}",
        s.lay_factor, s.static_lay_factor, s.lay_factor_closed_form, s.lambda, s.dynamic_embedment_factor
    );
    let _ = writeln!(
        t,
        "  top tension {:.2} to {:.2} kN; sag bend moment up to {:.2} kN·m, strain {:.3e}; {:.2} uplift–repenetration episodes a node",
        s.top_tension_min / 1e3,
        s.top_tension_max / 1e3,
        s.sag_moment_max / 1e3,
        s.sag_strain_max,
        s.episodes_mean
    );
    let _ = writeln!(
        t,
        "  {} steps, {} iterations, {} cuts; the window moved {} times, {:.0} of {} nodes in the solve on average; {:.2} s, stepped on {} thread{}{}",
        r.steps,
        r.iterations,
        r.cuts,
        r.windows,
        mean(&r.records.window_nodes),
        r.full.nodes(),
        r.wall_seconds,
        r.stepping_threads,
        if r.stepping_threads == 1 { "" } else { "s" },
        crate::report::share_on_two(r.steps_on_two, r.steps)
    );
    if let Some(c) = &r.installation {
        let _ = writeln!(
            t,
            "  installation check ({}): load-controlled {:.3} (at {:.1} m from the exit, KP {:.1} m, t = {:.1} s); sag bend strain {:.3e} against {:.3e}: displacement-controlled {:.3}",
            c.spec.code.name(),
            c.lcc_max.0,
            c.lcc_max.3,
            c.lcc_max.2,
            c.lcc_max.1,
            c.dcc_max.1,
            c.strain_resistance,
            c.dcc_max.0
        );
    }
    if let Some(d) = &r.lay_down {
        let _ = writeln!(
            t,
            "  lay-down: the pipe's end left the tower at {:.1} s (the touchdown at KP {:.1} m: the steady part ends there); {}",
            d.left_tower,
            d.kp_touchdown,
            match d.rested {
                Some(at) => format!(
                    "it rested on the seabed at {at:.1} s, embedded {:.1} mm",
                    mm(d.end_embedment)
                ),
                None => "it did not rest on the seabed before the run's end".into(),
            }
        );
    }
    if let Some(stop) = &r.stop {
        let _ = writeln!(t, "  stopped: {stop}");
    }
    t
}
