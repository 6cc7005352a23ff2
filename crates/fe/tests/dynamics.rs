//! Verification of the time integration against cases.md §5: HHT-α on one degree of freedom, a
//! tensioned beam's natural frequencies, and the rigid-limit pendulum.

mod common;

use catena_fe::analytical::tensioned_beam_frequency;
use catena_fe::beam::Section;
use catena_fe::dynamics::{
    advance, initial_state, sdof_free_vibration, DynWorkspace, DynamicModel, DynamicSettings,
    Scheme,
};
use catena_fe::environment::{Environment, Hydro};
use catena_fe::model::{LineModel, LineSpec, Segment, Support};
use catena_fe::statics::Placement;

/// cases.md §5: free vibration u0 = 1, v0 = 0, Δt/T = 0.05, after 10 periods (200 steps):
/// u = 0.873109 (α = 0), 0.790708 (α = −0.1), 0.706543 (α = −0.3), to 1e-6. And the spectral radius
/// at infinite frequency `(1+α)/(1−α)` (to 1e-3).
#[test]
fn hht_single_dof_numbers() {
    let omega = std::f64::consts::TAU;
    for (alpha, expect) in [(0.0, 0.873109), (-0.1, 0.790708), (-0.3, 0.706543)] {
        let u = sdof_free_vibration(Scheme::Hht { alpha }, omega, 1.0, 0.0, 0.05, 200);
        println!("HHT α = {alpha}: u(10 T) = {u:.6} (expected {expect})");
        assert!((u - expect).abs() < 1e-6, "α {alpha}: {u}");
        let rho = spectral_radius(Scheme::Hht { alpha }, 1e8);
        let want = (1.0 + alpha) / (1.0 - alpha);
        println!("HHT α = {alpha}: spectral radius at infinity {rho:.6} (expected {want:.6})");
        assert!((rho - want).abs() < 1e-5, "α {alpha}: ρ∞ {rho} vs {want}");
    }
}

/// The largest eigenvalue modulus of the one-step map of `ü + ω²u = 0`, Δt = 1 (the recurrence of
/// `sdof_free_vibration`).
fn spectral_radius(scheme: Scheme, omega2: f64) -> f64 {
    common::one_step_eigenvalues(scheme, omega2)
        .iter()
        .map(|z| (z.0 * z.0 + z.1 * z.1).sqrt())
        .fold(0.0, f64::max)
}

#[allow(clippy::too_many_arguments)]
fn line(
    n: usize,
    l: f64,
    ei: f64,
    ea: f64,
    m: f64,
    w: f64,
    top: Support,
    anchor: Support,
) -> LineModel {
    LineModel::build(&LineSpec {
        segments: vec![Segment::uniform(
            l,
            l / n as f64,
            Section { ea, ei },
            w,
            m,
            0.1,
        )],
        top,
        anchor,
        seabed: None,
        flexjoint: None,
    })
    .expect("model")
}

fn settings(alpha: f64) -> DynamicSettings {
    DynamicSettings {
        scheme: Scheme::Hht { alpha },
        tol: 1e-9,
        max_iter: 20,
        max_cuts: 4,
    }
}

/// The dynamic Model of a line at a placement, without motion.
fn dynamic(line: &LineModel, pl: &Placement, hydro: Option<Hydro>, alpha: f64) -> DynamicModel {
    DynamicModel {
        line: line.clone(),
        placement: pl.clone(),
        environment: Environment {
            hydro,
            ..Environment::default()
        },
        motion: None,
        vessel: None,
        structural_damping: None,
        settings: settings(alpha),
    }
}

/// Times at which `f` crosses zero upwards (linear interpolation).
fn up_crossings(ts: &[f64], f: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 1..f.len() {
        if f[i - 1] < 0.0 && f[i] >= 0.0 {
            out.push(ts[i - 1] + (ts[i] - ts[i - 1]) * (-f[i - 1]) / (f[i] - f[i - 1]));
        }
    }
    out
}

/// cases.md §5: a tensioned pinned–pinned beam (L 100 m, EI 1 MN·m², m 100 kg/m, T 100 kN), started
/// with a small velocity in mode n = 1 and 2: the period from zero crossings of the antinode's
/// displacement matches `ω_n = (nπ/L)²·sqrt(EI/m)·sqrt(1 + TL²/(n²π²EI))` within 0.5 % (40 lumped-mass
/// elements, trapezoidal rule α = 0, Δt = T_n/100).
#[test]
fn tensioned_beam_frequencies() {
    let (l, ei, ea, m, t) = (100.0, 1e6, 1e10, 100.0, 1e5);
    for mode in [1usize, 2] {
        let model = line(40, l, ei, ea, m, 0.0, Support::Pinned, Support::Pinned);
        let stretch = 1.0 + t / ea;
        let nn = model.nodes();
        // Straight and pre-tensioned: nodes on the x axis, the line stretched by T/EA.
        let q: Vec<f64> = (0..nn)
            .flat_map(|i| [model.arc[i] * stretch, 0.0, 0.0])
            .collect();
        let pl = Placement::new(&q);
        let dm = dynamic(&model, &pl, None, 0.0);
        let mut ws = DynWorkspace::new(&model).expect("ws");
        let mut st = initial_state(&dm, &vec![0.0; q.len()], &mut ws);
        for i in 0..nn {
            st.v[3 * i + 1] = 1e-3 * (mode as f64 * std::f64::consts::PI * model.arc[i] / l).sin();
        }
        let omega = tensioned_beam_frequency(mode, l, ei, m, t);
        let period = std::f64::consts::TAU / omega;
        let dt = period / 100.0;
        let probe = (nn - 1) / (2 * mode);
        let (mut ts, mut zs) = (vec![0.0], vec![0.0]);
        for _ in 0..600 {
            advance(&dm, &mut st, &mut ws, dt).expect("steps");
            ts.push(st.t);
            zs.push(st.u[3 * probe + 1]);
        }
        let c = up_crossings(&ts, &zs);
        let measured = (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64;
        println!(
            "mode {mode}: period {measured:.5} s, analytical {period:.5} s ({:+.3} %)",
            100.0 * (measured / period - 1.0)
        );
        assert!(
            (measured / period - 1.0).abs() < 5e-3,
            "mode {mode}: {measured} vs {period}"
        );
    }
}

/// cases.md §5: the rigid-limit pendulum, a stiff uniform bar of L = 10 m pinned at one end and
/// released from horizontal: period 6.1137 s, within 0.5 % (20 elements, HHT α = −0.1 to damp the
/// elastic modes, Δt = 2 ms). Measured as twice the time between the bar's two passes through the
/// vertical.
#[test]
fn rigid_limit_pendulum() {
    let (l, m, g) = (10.0, 10.0, 9.80665);
    let model = line(20, l, 1e7, 1e10, m, m * g, Support::Pinned, Support::Free);
    let nn = model.nodes();
    let q: Vec<f64> = (0..nn).flat_map(|i| [model.arc[i], 0.0, 0.0]).collect();
    let pl = Placement::new(&q);
    let dm = dynamic(&model, &pl, None, -0.1);
    let mut ws = DynWorkspace::new(&model).expect("ws");
    let mut st = initial_state(&dm, &vec![0.0; q.len()], &mut ws);
    let tip = 3 * (nn - 1);
    let (mut ts, mut xs) = (vec![0.0], vec![l]);
    while st.t < 8.0 {
        advance(&dm, &mut st, &mut ws, 0.002).expect("steps");
        ts.push(st.t);
        xs.push(pl.base[tip] + st.u[tip]);
    }
    // Passes through the vertical: the tip's x crosses the pivot (x = 0) downwards, then upwards.
    let mut passes = Vec::new();
    for i in 1..xs.len() {
        if (xs[i - 1] > 0.0) != (xs[i] > 0.0) {
            passes.push(ts[i - 1] + (ts[i] - ts[i - 1]) * xs[i - 1] / (xs[i - 1] - xs[i]));
        }
    }
    let period = 2.0 * (passes[1] - passes[0]);
    println!("pendulum period {period:.5} s (6.1137 s)");
    assert!((period / 6.1137 - 1.0).abs() < 5e-3, "{period}");
}

/// Top-end motions: velocity and acceleration are the time derivatives of the displacement (central
/// differences, relative 1e-5), the quintic ramp is 0 → 1 with zero slope at both ends, stages add up
/// and a series is interpolated linearly.
#[test]
fn top_motion_kinematics() {
    use catena_fe::motion::{quintic_ramp, TopMotion};
    assert_eq!(quintic_ramp(0.0, 10.0), (0.0, 0.0, 0.0));
    assert_eq!(quintic_ramp(10.0, 10.0), (1.0, 0.0, 0.0));
    assert!((quintic_ramp(5.0, 10.0).0 - 0.5).abs() < 1e-15);
    let h = TopMotion::Harmonic {
        surge: 0.5,
        heave: 2.0,
        period: 10.0,
        phase: 0.3,
        ramp: 10.0,
    };
    for t in [1.0, 4.0, 7.5, 12.0] {
        let e = 1e-5;
        let (_, v, a) = h.at(t);
        let (dp, vp, _) = h.at(t + e);
        let (dm, vm, _) = h.at(t - e);
        for k in 0..2 {
            let fd_v = (dp[k] - dm[k]) / (2.0 * e);
            let fd_a = (vp[k] - vm[k]) / (2.0 * e);
            assert!(
                (fd_v - v[k]).abs() <= 1e-5 * v[k].abs().max(1e-3),
                "t {t}: v {fd_v} {}",
                v[k]
            );
            assert!(
                (fd_a - a[k]).abs() <= 1e-5 * a[k].abs().max(1e-3),
                "t {t}: a {fd_a} {}",
                a[k]
            );
        }
    }
    let s = TopMotion::Staged(vec![
        (20.0, 0.0, 0.0),
        (22.0, 0.0, 0.1),
        (5.0, 0.0, 0.0),
        (22.0, 0.0, -0.1),
    ]);
    assert_eq!(s.at(10.0).0, [0.0, 0.0]);
    assert!((s.at(31.0).0[1] - 1.1).abs() < 1e-12 && s.at(31.0).1[1] == 0.1);
    assert!((s.at(44.0).0[1] - 2.2).abs() < 1e-12);
    assert!(s.at(80.0).0[1].abs() < 1e-12 && s.at(80.0).1 == [0.0, 0.0]);
    let ser = TopMotion::Series(vec![(0.0, 0.0, 0.0), (2.0, 1.0, -2.0)]);
    assert_eq!(ser.at(1.0).0, [0.5, -1.0]);
    assert_eq!(ser.at(1.0).1, [0.5, -1.0]);
    assert_eq!(ser.at(5.0).0, [1.0, -2.0]);
}

/// Drag in a current: a taut vertical line (L 100 m, T 100 kN, EA 10 MN, EI 10 N·m², D 0.1 m, pinned
/// at both ends) in a uniform current U = 0.5 m/s (Cd 1.2, ρ 1025) settles, damped by its own drag on
/// the relative velocity, to the taut-string deflection at midspan, within 0.2 %. The span is the
/// stretched length `L = 1.01·L0` and drag is applied per unit unstretched length (like weight and
/// mass), so the load is `q·L0` over the span `L`: `δ = q·L0·L/(8T)` with `q = ½ρ Cd D U²`
/// (0.1939 m; the extra stretch under the load adds 0.1 % to T).
#[test]
fn drag_in_a_current_gives_the_string_deflection() {
    let (l, t, ea) = (100.0, 1e5, 1e7);
    let model = line(
        40,
        l,
        10.0,
        ea,
        100.0,
        0.0,
        Support::Pinned,
        Support::Pinned,
    );
    let nn = model.nodes();
    let stretch = 1.0 + t / ea;
    let q: Vec<f64> = (0..nn)
        .flat_map(|i| {
            [
                0.0,
                l * stretch - model.arc[i] * stretch,
                -std::f64::consts::FRAC_PI_2,
            ]
        })
        .collect();
    let pl = Placement::new(&q);
    let hydro = Hydro {
        water_density: 1025.0,
        cd_normal: 1.2,
        cd_axial: 0.0,
        ca_normal: 1.0,
        current: vec![(0.0, 0.5)],
    };
    let dm = dynamic(&model, &pl, Some(hydro), -0.1);
    let mut ws = DynWorkspace::new(&model).expect("ws");
    let mut st = initial_state(&dm, &vec![0.0; q.len()], &mut ws);
    while st.t < 80.0 {
        advance(&dm, &mut st, &mut ws, 0.05).expect("steps");
    }
    let mid = (nn - 1) / 2;
    let delta = st.u[3 * mid];
    let q_drag = 0.5 * 1025.0 * 1.2 * 0.1 * 0.25;
    let expect = q_drag * l * (l * stretch) / (8.0 * t);
    println!(
        "midspan deflection {delta:.5} m, string theory {expect:.5} m; axial {:.1} .. {:.1} N",
        ws.asm.axial.iter().copied().fold(f64::INFINITY, f64::min),
        ws.asm.axial.iter().copied().fold(0.0, f64::max)
    );
    assert!((delta / expect - 1.0).abs() < 2e-3, "{delta} vs {expect}");
    assert!(st.v[3 * mid].abs() < 1e-4, "settled: v = {}", st.v[3 * mid]);
}

/// A top held in rotation (`"fixed"`) turns with the vessel it hangs from: a 10 m bar hanging from
/// a fixed top on a vessel that only pitches (0.57° per metre of wave, a 2 m regular wave of 10 s,
/// ramped over 20 s, the hang-off at the RAO origin) has, at every step, the top's rotation `−β`,
/// its rate `−β̇` and its acceleration `−β̈` (to 1e-12 rad and the same in rate and acceleration),
/// and the bar swings (its tip moves more than 5 mm). The same top without a vessel holds its
/// rotation at exactly zero and the bar hangs still.
#[test]
fn a_fixed_top_turns_with_the_vessel() {
    use catena_fe::environment::Environment;
    use catena_fe::vessel::{RaoTable, Vessel};
    use catena_fe::waves::{Direction, Waves};
    let (l, m, g) = (10.0, 10.0, 9.80665);
    let model = line(20, l, 1e5, 1e9, m, m * g, Support::Fixed, Support::Free);
    let nn = model.nodes();
    let q: Vec<f64> = (0..nn)
        .flat_map(|i| [0.0, -model.arc[i], -std::f64::consts::FRAC_PI_2])
        .collect();
    let pl = Placement::new(&q);
    let waves = Waves::regular(2.0, 10.0, Direction::PlusX, 1000.0, 9.80665, 20.0).expect("wave");
    let pitch_only = RaoTable {
        periods: vec![5.0, 20.0],
        rao: vec![[(0.0, 0.0), (0.0, 0.0), (0.01, 0.0)]; 2],
    };
    let vessel = Vessel::new(pitch_only, 0.0, [0.0, 0.0], &waves);
    for with_vessel in [true, false] {
        let mut dm = dynamic(&model, &pl, None, -0.1);
        if with_vessel {
            dm.environment = Environment {
                waves: Some(waves.clone()),
                water_level: 1000.0,
                ..Environment::default()
            };
            dm.vessel = Some(vessel.clone());
        }
        let mut ws = DynWorkspace::new(&model).expect("ws");
        let mut st = initial_state(&dm, &vec![0.0; q.len()], &mut ws);
        let tip = 3 * (nn - 1);
        let (mut worst, mut swing, mut pitch) = (0.0f64, 0.0f64, 0.0f64);
        while st.t < 40.0 {
            advance(&dm, &mut st, &mut ws, 0.01).expect("steps");
            let vm = vessel.motion(&waves, st.t);
            let (beta, rates) = if with_vessel {
                (vm.motions[2], vm.pitch_rates)
            } else {
                (0.0, [0.0; 2])
            };
            worst = worst
                .max((st.u[2] + beta).abs())
                .max((st.v[2] + rates[0]).abs())
                .max((st.a[2] + rates[1]).abs());
            if !with_vessel {
                assert_eq!([st.u[2], st.v[2], st.a[2]], [0.0; 3]);
            }
            pitch = pitch.max(beta.abs());
            swing = swing.max(st.u[tip].abs());
        }
        println!(
            "vessel {with_vessel}: the top's turn within {worst:.2e} of −β (|β| up to {pitch:.2e} \
             rad), the tip swings {swing:.2e} m"
        );
        assert!(worst < 1e-12, "{worst}");
        if with_vessel {
            assert!(pitch > 5e-3, "{pitch}");
            assert!(swing > 5e-3, "{swing}");
        } else {
            assert!(swing < 1e-9, "{swing}");
        }
    }
}
