//! Range graphs (`catena::observe::Envelopes`) against the step-by-step record of the same run:
//! with every step recorded, the least, greatest and mean of each quantity at each node must equal
//! those of the recorded fields over the envelope window, and the derived quantities (curvature,
//! wall tension, fibre stresses) must follow from the recorded moment, tension and height by the
//! section's formulas, written out here.

mod common;

use std::path::{Path, PathBuf};

use catena::observe::Observer;
use catena::run::records::Records;
use catena::run::{self, RunOptions};
use catena::scene::edit::Edit;
use catena::statics;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The least, greatest and mean over the rows `from..` of a `rows × n` field, per column.
fn column_stats(v: &[f64], n: usize, from: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let rows = v.len() / n;
    let mut lo = vec![f64::INFINITY; n];
    let mut hi = vec![f64::NEG_INFINITY; n];
    let mut sum = vec![0.0; n];
    for r in from..rows {
        for i in 0..n {
            let x = v[r * n + i];
            lo[i] = lo[i].min(x);
            hi[i] = hi[i].max(x);
            sum[i] += x;
        }
    }
    let k = (rows - from) as f64;
    (lo, hi, sum.iter().map(|s| s / k).collect())
}

fn close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    let scale = b.iter().fold(0.0_f64, |m, x| m.max(x.abs())).max(1e-30);
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tol * scale,
            "{what} at node {i}: {x} vs {y} (scale {scale})"
        );
    }
}

/// Watchet's pull-up (the line lifts off and resettles), 30 s of it with every step recorded and the
/// envelopes from 20 s: ranges equal the records' statistics to rounding (1e-12 of the largest
/// value; the mean sums in a different order).
#[test]
fn ranges_equal_the_statistics_of_every_step() {
    let case = root().join("cases/watchet/pull-up-lay-down.toml");
    let scene = common::edited_case(
        &case,
        &[
            Edit::set("dynamic.duration", 30.0),
            Edit::set("dynamic.output_interval", 0.02),
            Edit::set("dynamic.envelope_start", 20.0),
        ],
    );
    let st = statics::solve(scene).expect("statics");
    let mut records = Records::new();
    let r = {
        let mut extra: [&mut dyn Observer; 1] = [&mut records];
        run::run(st, &mut extra, RunOptions::default()).expect("run")
    };
    assert!(r.completed());
    let e = &r.envelopes;
    let n = r.model.line.nodes();
    let time = &records.series[0].1;
    let from = time.iter().position(|t| *t >= 20.0 - 1e-9).expect("window");
    assert_eq!(
        e.samples as usize,
        time.len() - from,
        "every step is sampled"
    );
    let field = |name: &str| -> &[f64] {
        &records
            .fields
            .iter()
            .find(|(f, _)| *f == name)
            .expect("field")
            .1
    };
    let check = |name: &str, v: &[f64], range: &catena::observe::Range| {
        let (lo, hi, mean) = column_stats(v, n, from);
        close(&range.min, &lo, 1e-12, &format!("{name} min"));
        close(&range.max, &hi, 1e-12, &format!("{name} max"));
        close(
            &range.mean(e.samples),
            &mean,
            1e-12,
            &format!("{name} mean"),
        );
    };
    let (m, te, z) = (
        field("bending_moment"),
        field("effective_tension"),
        field("z"),
    );
    check("bending_moment", m, &e.moment);
    check("effective_tension", te, &e.tension);
    check("penetration", field("penetration"), &e.penetration);
    check("seabed_force", field("seabed_force"), &e.seabed_force);
    // The line lifts off in the window: the ranges are not trivially flat.
    let dm = e.moment.range().iter().fold(0.0_f64, |a, b| a.max(*b));
    assert!(dm > 1e3, "moment range {dm} N·m");

    // Curvature M/EI: Watchet's pipe, E 207 GPa, D 0.1683 m, wall 0.00792 m (uniform line).
    let (od, wall, e_mod): (f64, f64, f64) = (0.1683, 0.00792, 207.0e9);
    let id = od - 2.0 * wall;
    let inertia = std::f64::consts::PI / 64.0 * (od.powi(4) - id.powi(4));
    let area = std::f64::consts::PI / 4.0 * (od * od - id * id);
    let kappa: Vec<f64> = m.iter().map(|m| m / (e_mod * inertia)).collect();
    check("curvature", &kappa, &e.curvature);

    // Wall tension T_w = T_e + p_i A_i − p_o A_o, flooded (contents 1025 kg/m³ = the sea), so
    // T_w − T_e = −ρ g (d − z) π/4 (D² − D_i²) = −ρ g (d − z) A; stresses T_w/A ∓ M (D/2)/I.
    let (rho, g, depth) = (1025.0, 9.80665, 9.0);
    let [wt, top, bottom] = e.wall.as_ref().expect("the section is known");
    let tw: Vec<f64> = te
        .iter()
        .zip(z)
        .map(|(t, z)| t - rho * g * (depth - z).max(0.0) * area)
        .collect();
    check("wall_tension", &tw, wt);
    let sig = |sign: f64| -> Vec<f64> {
        tw.iter()
            .zip(m)
            .map(|(t, m)| t / area + sign * m * (0.5 * od) / inertia)
            .collect()
    };
    check("stress_top", &sig(-1.0), top);
    check("stress_bottom", &sig(1.0), bottom);
}

/// Without the pipe's wall (the heave benchmark gives EA and EI), there is no wall tension or stress
/// range: nothing is guessed.
#[test]
fn no_section_no_stress_ranges() {
    let case = root().join("cases/benchmarks/scr-heave.toml");
    let scene = common::edited_case(
        &case,
        &[
            Edit::set("dynamic.duration", 1.0),
            Edit::set("dynamic.envelope_start", 0.0),
        ],
    );
    let st = statics::solve(scene).expect("statics");
    let r = run::run(st, &mut [], RunOptions::default()).expect("run");
    assert!(r.envelopes.wall.is_none());
    let names: Vec<&str> = r.envelopes.ranges().iter().map(|(n, _)| *n).collect();
    assert_eq!(
        names,
        [
            "bending_moment",
            "effective_tension",
            "curvature",
            "penetration",
            "seabed_force"
        ]
    );
}
