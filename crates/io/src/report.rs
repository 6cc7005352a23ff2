//! Summaries of runs, as text for the terminal and as JSON for `summary.json`. Values that were
//! never measured (a run stopped before its envelope window) are JSON `null`, never 0.

use std::fmt::Write as _;

use catena::run::observe::Stop;
use catena::run::statics::StaticRun;
use catena::run::{self, DynamicRun};
use serde_json::{json, Value};

/// A number, or `null` if it is not finite (not measured).
pub fn num(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else {
        Value::Null
    }
}

fn opt(v: Option<f64>) -> Value {
    v.map_or(Value::Null, num)
}

fn nums(v: &[f64]) -> Vec<Value> {
    v.iter().map(|x| num(*x)).collect()
}

/// The summary as text.
pub fn static_text(run: &StaticRun) -> String {
    let s = &run.summary;
    let mut t = String::new();
    let _ = writeln!(t, "static: {} ({})", run.scene.title, run.scene.file);
    let _ = writeln!(
        t,
        "  {} nodes, {} elements; Newton: {} iterations, {} continuation steps, relative residual {:.2e}; {:.1} ms",
        run.model.nodes(),
        run.model.elements.len(),
        run.report.iterations,
        run.report.steps.max(1),
        run.report.residual,
        run.wall_seconds * 1e3
    );
    let _ = writeln!(
        t,
        "  top tension            {:>12.2} kN",
        s.top_tension / 1e3
    );
    let _ = writeln!(
        t,
        "  horizontal tension     {:>12.2} kN at the top, {:.2} kN at the anchor",
        s.horizontal_tension / 1e3,
        s.anchor_horizontal_tension / 1e3
    );
    let _ = writeln!(
        t,
        "  top angle              {:>12.3} deg from vertical",
        s.top_angle_from_vertical.to_degrees()
    );
    match s.touchdown_arc {
        Some(a) => {
            let _ = writeln!(t, "  touchdown arc length   {a:>12.2} m");
        }
        None => {
            let _ = writeln!(
                t,
                "  touchdown              none (the line does not touch the seabed)"
            );
        }
    }
    let _ = writeln!(
        t,
        "  max sag moment         {:>12.2} kN·m at arc length {:.2} m",
        s.max_sag_moment.0 / 1e3,
        s.max_sag_moment.1
    );
    if let Some(m) = s.touchdown_moment {
        let _ = writeln!(t, "  moment at touchdown    {:>12.2} kN·m", m / 1e3);
    }
    if run.model.seabed.is_some() {
        // Far field: 95 % of the way from the top, away from touchdown and from the anchor pin.
        let i = run.results.penetration.len().saturating_sub(1) * 95 / 100;
        let _ = writeln!(
            t,
            "  far-field penetration  {:>12.5} m at arc length {:.1} m",
            run.results.penetration[i], run.model.arc[i]
        );
    }
    t
}

/// The summary as JSON.
pub fn static_json(run: &StaticRun) -> serde_json::Value {
    let s = &run.summary;
    json!({
        "catena_version": catena::run::checkpoint::VERSION,
        "case": run.scene.file,
        "title": run.scene.title,
        "units": "SI (N, m, N·m, rad; angles in deg where the key says so)",
        "static": {
            "nodes": run.model.nodes(),
            "elements": run.model.elements.len(),
            "top_tension": s.top_tension,
            "horizontal_tension": s.horizontal_tension,
            "anchor_horizontal_tension": s.anchor_horizontal_tension,
            "top_angle_from_vertical_deg": s.top_angle_from_vertical.to_degrees(),
            "touchdown_arc": s.touchdown_arc,
            "max_sag_moment": s.max_sag_moment.0,
            "max_sag_moment_arc": s.max_sag_moment.1,
            "touchdown_moment": s.touchdown_moment,
            "newton_iterations": run.report.iterations,
            "continuation_steps": run.report.steps.max(1),
            "step_cuts": run.report.cuts,
            "relative_residual": run.report.residual,
            "wall_seconds": run.wall_seconds,
        },
        "sections": run
            .scene
            .sections()
            .iter()
            .map(|(t, from, to)| json!({ "type": t, "from": from, "to": to }))
            .collect::<Vec<_>>(),
    })
}

/// The dynamic run's summary as JSON (the static summary with a `dynamic` object).
pub fn dynamic_json(r: &DynamicRun) -> Value {
    let mut js = static_json(&r.statics);
    let (mr, at, tmin, tmax) = run::key_numbers(r);
    let gauges: Vec<Value> = r
        .spec
        .gauges
        .iter()
        .zip(&r.gauges.traces)
        .map(|(g, tr)| {
            let [(rmin, rmax), (fmin, fmax)] = tr.by_direction;
            json!({
                "name": g.name, "arc": g.arc,
                "moment_min": opt(tr.moment_extremes.0),
                "moment_max": opt(tr.moment_extremes.1),
                "moment_min_top_rising": opt(rmin), "moment_max_top_rising": opt(rmax),
                "moment_min_top_falling": opt(fmin), "moment_max_top_falling": opt(fmax),
            })
        })
        .collect();
    let (reason, failed) = match &r.stop {
        None => (Value::Null, Value::Null),
        Some(Stop::Failed(e)) => {
            let failed = match e {
                catena_fe::dynamics::StepError::NotConverged {
                    t,
                    step,
                    dt,
                    cuts,
                    iterations,
                    residual,
                    node,
                    arc,
                    ..
                } => json!({
                    "t": t, "step": step, "dt": dt, "step_cuts": cuts,
                    "newton_iterations": iterations, "relative_residual": num(*residual),
                    "node": node, "arc": arc,
                }),
                catena_fe::dynamics::StepError::Solve(_) => Value::Null,
            };
            (json!(e.to_string()), failed)
        }
        Some(s) => (json!(s.to_string()), Value::Null),
    };
    if let Some(f) = &r.fatigue {
        js["fatigue"] = fatigue_json(r, f);
    }
    if let Some(d) = r.output::<catena::run::observers::design::DesignCheck>() {
        js["design_check"] = design_check_json(d);
    }
    if let Some(x) = r.output::<catena::run::observers::extremes::ExtremesObserver>() {
        js["extremes"] = serde_json::to_value(&x.results).unwrap_or(Value::Null);
    }
    let e = &r.envelopes;
    js["dynamic"] = json!({
        "completed": r.completed(),
        "stop_reason": reason,
        "failed_step": failed,
        "duration": r.spec.duration,
        "time_reached": r.t_reached,
        "time_step": r.spec.dt,
        "scheme": r.spec.settings.scheme.to_string(),
        "steps": r.steps,
        "newton_iterations": r.iterations,
        "iterations_per_step": if r.steps > 0 { num(r.iterations as f64 / r.steps as f64) } else { Value::Null },
        "step_cuts": r.cuts,
        "cut_steps": r.cut_log.iter().map(|c| json!({
            "t": c.t, "step_cuts": c.cuts, "dt": c.dt, "relative_residual": num(c.residual),
            "node": c.node, "arc": c.arc,
        })).collect::<Vec<_>>(),
        "predictor_retries": r.retries,
        "wall_seconds": r.wall_seconds,
        "stepping_threads": r.stepping_threads,
        "steps_on_two_threads": r.steps_on_two,
        "envelope_start": r.spec.envelope_start,
        "envelope_steps": e.samples,
        "max_moment_range": num(mr),
        "max_moment_range_arc": num(at),
        "top_tension_min": num(tmin),
        "top_tension_max": num(tmax),
        "top_tension_range": num(tmax - tmin),
        "touchdown_arc_min": num(r.envelopes.touchdown.0),
        "touchdown_arc_max": num(r.envelopes.touchdown.1),
        "touchdown_arc_range": num(r.envelopes.touchdown.1 - r.envelopes.touchdown.0),
        "gauges": gauges,
        "envelopes": {
            "arc": r.model.line.arc,
            "moment_min": nums(&e.moment.min),
            "moment_max": nums(&e.moment.max),
            "tension_min": nums(&e.tension.min),
            "tension_max": nums(&e.tension.max),
            "moment_range": nums(&e.moment.range()),
            "tension_range": nums(&e.tension.range()),
            "penetration_max": nums(&e.penetration.max),
            "penetration_min": nums(&e.penetration.min),
        }
    });
    js
}

fn kn(v: f64, scale: f64) -> String {
    if v.is_finite() {
        format!("{:.2}", v * scale)
    } else {
        "n/a".into()
    }
}

/// The dynamic run's summary as text.
pub fn dynamic_text(r: &DynamicRun) -> String {
    let mut t = static_text(&r.statics);
    let (mr, at, tmin, tmax) = run::key_numbers(r);
    let _ = writeln!(
        t,
        "dynamic: {:.1} of {:.1} s in {} steps of {} s ({}); {} Newton iterations ({:.2} per step), {} step cuts, {} predictor retries; {:.2} s wall",
        r.t_reached,
        r.spec.duration,
        r.steps,
        r.spec.dt,
        r.spec.settings.scheme,
        r.iterations,
        r.iterations as f64 / r.steps.max(1) as f64,
        r.cuts,
        r.retries,
        r.wall_seconds
    );
    if !r.cut_log.is_empty() {
        let spots: Vec<String> = r
            .cut_hotspots(3)
            .iter()
            .map(|(arc, n)| format!("{arc:.1} m ({n})"))
            .collect();
        let _ = writeln!(
            t,
            "  {} steps were cut, first at t = {} s; where (arc length, steps): {}{}",
            r.cut_log.len(),
            r.cut_log[0].t,
            spots.join(", "),
            if r.cut_log.len() >= run::MAX_CUT_LOG {
                " (the first 1000 listed)"
            } else {
                ""
            }
        );
    }
    let _ = writeln!(t, "  from t = {} s:", r.spec.envelope_start);
    let _ = writeln!(
        t,
        "  top tension            {:>10} to {} kN (range {} kN)",
        kn(tmin, 1e-3),
        kn(tmax, 1e-3),
        kn(tmax - tmin, 1e-3)
    );
    let _ = writeln!(
        t,
        "  max moment range       {:>10} kN·m at arc length {}",
        kn(mr, 1e-3),
        if at.is_finite() {
            format!("{at:.2} m")
        } else {
            "n/a".into()
        }
    );
    let (td0, td1) = r.envelopes.touchdown;
    if td0.is_finite() {
        let _ = writeln!(
            t,
            "  touchdown point       {td0:>10.2} to {td1:.2} m arc length (range {:.2} m)",
            td1 - td0
        );
    }
    for (g, tr) in r.spec.gauges.iter().zip(&r.gauges.traces) {
        let f = |v: Option<f64>| kn(v.unwrap_or(f64::NAN), 1e-3);
        let _ = writeln!(
            t,
            "  gauge {} (arc {:.2} m): moment {} to {} kN·m",
            g.name,
            g.arc,
            f(tr.moment_extremes.0),
            f(tr.moment_extremes.1)
        );
        let [(rmin, rmax), (fmin, fmax)] = tr.by_direction;
        if rmin.is_some() || fmin.is_some() {
            let _ = writeln!(
                t,
                "    top rising (pull-up): {} to {} kN·m; top falling (lay-down): {} to {} kN·m",
                f(rmin),
                f(rmax),
                f(fmin),
                f(fmax)
            );
        }
    }
    if let Some(f) = &r.fatigue {
        let secs = f.counted_seconds();
        for fib in &f.spec.fibres {
            if let Some(d) = f.damage_of(*fib) {
                let (i, dmax) =
                    d.iter()
                        .enumerate()
                        .fold((0, 0.0f64), |b, (i, v)| if *v > b.1 { (i, *v) } else { b });
                let _ = writeln!(
                    t,
                    "  fatigue ({}, SCF {}, {} fibre, {secs:.1} s counted): largest damage {dmax:.4e} at arc length {:.2} m; life {:.4e} years were the record repeated",
                    f.spec.curve_name,
                    f.spec.scf,
                    fib.name(),
                    r.model.line.arc[i],
                    if dmax > 0.0 { secs / dmax / YEAR } else { f64::INFINITY }
                );
            }
        }
    }
    if let Some(d) = r.output::<catena::run::observers::design::DesignCheck>() {
        if let Some((i, u)) = d.worst() {
            let _ = writeln!(
                t,
                "  design check ({}, from {} s): largest utilisation {u:.4} at arc length {:.2} m, t = {:.2} s ({} dominant): {}",
                d.spec.code.name(),
                d.spec.start,
                d.arc[i],
                d.time_of_max[i],
                d.term_of_max[i].name(),
                if u <= 1.0 { "passes" } else { "FAILS" }
            );
        }
        let c = d.compression();
        if let Some(worst) = c
            .iter()
            .min_by(|a, b| a.least_tension.total_cmp(&b.least_tension))
        {
            let _ = writeln!(
                t,
                "  WARNING: compression beyond the element Euler load at {} nodes (arc {:.2} to {:.2} m); the worst {:.2} kN at arc length {:.2} m, t = {:.2} s (Euler load {:.2} kN)",
                c.len(),
                c[0].arc,
                c[c.len() - 1].arc,
                worst.least_tension / 1e3,
                worst.arc,
                worst.time,
                worst.euler_load / 1e3
            );
        }
    }
    if let Some(x) = r.output::<catena::run::observers::extremes::ExtremesObserver>() {
        for e in &x.results {
            t.push_str(&extremes_line(e));
        }
    }
    if let Some(s) = &r.stop {
        let _ = writeln!(t, "  STOPPED EARLY at t = {:.6} s: {s}", r.t_reached);
    }
    t
}

/// The units a channel of extremes is shown in, as the other outputs show its quantity:
/// `(factor from SI, unit)` — tensions in kN, moments (`sag_moment`, a gauge's moment) in kN·m,
/// the utilisation as a number; a CSV column of another name as it is given (`(1, "")`).
pub fn channel_units(channel: &str) -> (f64, &'static str) {
    let name = channel.to_ascii_lowercase();
    if name == "utilisation" {
        (1.0, "")
    } else if name.contains("tension") {
        (1e-3, "kN")
    } else if name.contains("moment") || name.starts_with("gauge:") {
        (1e-3, "kN·m")
    } else {
        (1.0, "")
    }
}

/// A value of a channel in its units ([`channel_units`]): `1439.04 kN`, `0.8312`, or six
/// significant digits for a channel of unknown units.
pub fn channel_value(channel: &str, v: f64) -> String {
    match channel_units(channel) {
        (f, "") if channel.eq_ignore_ascii_case("utilisation") => format!("{:.4}", v * f),
        (_, "") => format!("{v:.6e}"),
        (f, unit) => format!("{:.2} {unit}", v * f),
    }
}

/// One line of the text summary for a channel's extremes, in the channel's units.
pub fn extremes_line(e: &catena::checks::extremes::Extremes) -> String {
    let f = |v: Option<f64>| v.map_or("—".to_string(), |v| channel_value(&e.channel, v));
    let side = match e.tail {
        catena::checks::extremes::Tail::Max => "largest",
        catena::checks::extremes::Tail::Min => "least",
    };
    format!(
        "  extremes of {} ({side}; {:.0} s of record, {} samples): sample {}; most probable in {:.0} s: Rayleigh {}, Weibull {}, Gumbel {}; {:.0} % quantile: Rayleigh {}, Weibull {}, Gumbel {}\n",
        e.channel,
        e.duration,
        e.samples,
        f(Some(e.sample_extreme)),
        e.target,
        f(Some(e.rayleigh[0])),
        f(e.weibull.map(|w| w.1[0])),
        f(e.gumbel.map(|g| g.2[0])),
        100.0 * e.quantile_probability,
        f(Some(e.rayleigh[1])),
        f(e.weibull.map(|w| w.1[1])),
        f(e.gumbel.map(|g| g.2[1])),
    )
}

/// The design check section of `summary.json`: the code, the largest utilisation, where, when and
/// its dominant term, pass or fail, each node's largest utilisation and least effective tension,
/// and the nodes in compression beyond their element's Euler load.
pub fn design_check_json(d: &catena::run::observers::design::DesignCheck) -> Value {
    let worst = d.worst();
    let least: Vec<f64> = d
        .least_tension
        .iter()
        .map(|t| if *t == f64::MAX { f64::NAN } else { *t })
        .collect();
    json!({
        "code": d.spec.code.name(),
        "start": d.spec.start,
        "max_utilisation": worst.map(|(_, u)| num(u)),
        "max_utilisation_arc": worst.map(|(i, _)| d.arc[i]),
        "max_utilisation_time": worst.map(|(i, _)| d.time_of_max[i]),
        "dominant_term": worst.map(|(i, _)| d.term_of_max[i].name()),
        "passes": worst.map(|(_, u)| u <= 1.0),
        "utilisation_max": nums(&d.max),
        "least_effective_tension": nums(&least),
        "compression": d.compression(),
    })
}

const YEAR: f64 = 365.25 * 86400.0;

/// The fatigue section of `summary.json`: per fibre, the damage of the counted record at every node,
/// the largest and where, and the life were the record repeated all year (`T/D` years).
pub fn fatigue_json(r: &DynamicRun, f: &catena::run::observers::fatigue::Fatigue) -> Value {
    let arc = &r.model.line.arc;
    let secs = f.counted_seconds();
    let fibres: Vec<Value> = f
        .spec
        .fibres
        .iter()
        .filter_map(|fib| {
            let d = f.damage_of(*fib)?;
            let (i, dmax) =
                d.iter()
                    .enumerate()
                    .fold((0, 0.0f64), |b, (i, v)| if *v > b.1 { (i, *v) } else { b });
            let life = if dmax > 0.0 {
                secs / dmax / YEAR
            } else {
                f64::INFINITY
            };
            Some(json!({
                "fibre": fib.name(),
                "damage": nums(&d),
                "max_damage": num(dmax),
                "max_damage_arc": arc[i],
                "life_years_if_repeated": num(life),
                "life_years_with_design_factor": f.spec.design_factor.map(|df| num(life / df)),
            }))
        })
        .collect();
    json!({
        "sn_curve": f.spec.curve_name,
        "scf": f.spec.scf,
        "thickness_factor": f.factor() / f.spec.scf,
        "start": f.spec.start,
        "counted_seconds": secs,
        "fibres": fibres,
    })
}

/// How much of a run two threads stepped, for the text summaries: `" for 97 % of the steps"`
/// where a pair took some steps but not all ([`catena::run::DynamicRun::steps_on_two`]: a run on
/// cores busy with other work steps on one where two are slower), else nothing.
pub fn share_on_two(on_two: u64, steps: u64) -> String {
    if on_two == 0 || on_two >= steps {
        return String::new();
    }
    format!(
        " for {:.0} % of the steps",
        100.0 * on_two as f64 / steps as f64
    )
}

#[cfg(test)]
mod units_tests {
    /// Extremes in the units of the other outputs: tensions in kN, moments in kN·m, the
    /// utilisation as a number.
    #[test]
    fn extremes_are_given_in_kilonewtons() {
        use super::channel_value as v;
        assert_eq!(v("top_tension", 1.439044e6), "1439.04 kN");
        assert_eq!(v("least_tension", 2.5e5), "250.00 kN");
        assert_eq!(v("sag_moment", -123_456.0), "-123.46 kN·m");
        assert_eq!(v("gauge:tdz:max", 5_000.0), "5.00 kN·m");
        assert_eq!(v("utilisation", 0.83124), "0.8312");
        assert_eq!(v("heave", 1.5), "1.500000e0");
    }
}
