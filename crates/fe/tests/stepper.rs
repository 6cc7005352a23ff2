//! The production stepper (`advance`) against closed-form answers: each test here fails when one
//! piece of the dynamics is wrong (the α-weighting of HHT, the added mass, the drag, the flexjoint's
//! sign), which the accuracy tests of whole risers can miss.
//!
//! The single-degree-of-freedom system is a vertical bar of one element, its top fixed and its bottom
//! node free: for purely axial motion the bottom node is exactly a mass `m = μ·L0/2` (lumped) on a
//! spring `k = EA/L0` (the corotational chord stays vertical, so no moment or transverse force
//! arises and the element is linear in the axial displacement).

mod common;

use catena_fe::analytical::tensioned_beam_frequency;
use catena_fe::beam::Section;
use catena_fe::dynamics::{
    advance, initial_state, DynWorkspace, DynamicModel, DynamicSettings, Scheme,
};
use catena_fe::environment::{Environment, Hydro};
use catena_fe::model::{LineModel, LineSpec, Segment, Support};
use catena_fe::statics::{self, Placement, StaticOptions, StaticWorkspace};

const PI: f64 = std::f64::consts::PI;

fn segment(length: f64, n: usize, ea: f64, ei: f64, mass: f64, weight: f64, od: f64) -> Segment {
    Segment::uniform(
        length,
        length / n as f64,
        Section { ea, ei },
        weight,
        mass,
        od,
    )
}

fn model(seg: Segment, top: Support, anchor: Support, flexjoint: Option<(f64, f64)>) -> LineModel {
    LineModel::build(&LineSpec {
        segments: vec![seg],
        top,
        anchor,
        seabed: None,
        flexjoint,
    })
    .expect("model")
}

/// Settings: HHT with `alpha`, the sea `hydro` (None: in air) and structural damping `beta`.
struct Settings {
    alpha: f64,
    hydro: Option<Hydro>,
    beta: Option<f64>,
}

fn settings(alpha: f64, hydro: Option<Hydro>) -> Settings {
    Settings {
        alpha,
        hydro,
        beta: None,
    }
}

fn dynamic(line: &LineModel, pl: &Placement, set: &Settings) -> DynamicModel {
    DynamicModel {
        line: line.clone(),
        placement: pl.clone(),
        environment: Environment {
            hydro: set.hydro.clone(),
            ..Environment::default()
        },
        motion: None,
        vessel: None,
        structural_damping: set.beta,
        settings: DynamicSettings {
            scheme: Scheme::Hht { alpha: set.alpha },
            tol: 1e-10,
            max_iter: 20,
            max_cuts: 0,
        },
    }
}

fn hydro(cd_normal: f64, cd_axial: f64, ca_normal: f64) -> Hydro {
    Hydro {
        water_density: 1025.0,
        cd_normal,
        cd_axial,
        ca_normal,
        current: Vec::new(),
    }
}

/// The vertical one-element bar (top fixed at the origin, bottom node free), its bottom node
/// displaced by `u0` along the bar, advanced `steps` steps of `dt`: the bottom node's axial
/// displacement after each step (index 0 is the start).
fn bar_history(
    seg: Segment,
    set: &Settings,
    u0: f64,
    dt: f64,
    steps: usize,
) -> (Vec<f64>, Vec<f64>) {
    let m = model(seg, Support::Fixed, Support::Free, None);
    let l = seg.length;
    let q = vec![0.0, 0.0, -PI / 2.0, 0.0, -l, -PI / 2.0];
    let pl = Placement::new(&q);
    let dm = dynamic(&m, &pl, set);
    let mut ws = DynWorkspace::new(&m).expect("workspace");
    let mut u = vec![0.0; 6];
    u[4] = -u0; // stretched by u0 (downwards)
    let mut st = initial_state(&dm, &u, &mut ws);
    let (mut t, mut x) = (vec![0.0], vec![u0]);
    for _ in 0..steps {
        let info = advance(&dm, &mut st, &mut ws, dt).expect("step");
        assert_eq!(info.cuts, 0);
        t.push(st.t);
        x.push(-st.u[4]);
        // The motion stays axial: no transverse displacement, no rotation.
        assert!(st.u[3].abs() < 1e-12 && st.u[5].abs() < 1e-12, "{:?}", st.u);
    }
    (t, x)
}

/// The falling pendulum: a 10 m stiff bar (EA 1e10 N, EI 1e7 N·m², 10 kg/m, its weight) of `n`
/// elements, pinned at its top and free at its tip, lying horizontal at rest: the Model, its base
/// configuration and its placement.
fn falling_pendulum(n: usize) -> (LineModel, Vec<f64>, Placement) {
    let (l, m, g) = (10.0, 10.0, 9.80665);
    let mline = model(
        segment(l, n, 1e10, 1e7, m, m * g, 0.1),
        Support::Pinned,
        Support::Free,
        None,
    );
    let q: Vec<f64> = (0..mline.nodes())
        .flat_map(|i| [mline.arc[i], 0.0, 0.0])
        .collect();
    let pl = Placement::new(&q);
    (mline, q, pl)
}

/// Peaks (local maxima, parabolic refinement) of a sampled signal: `(time, value)`.
fn peaks(t: &[f64], x: &[f64]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 1..x.len() - 1 {
        if x[i] > x[i - 1] && x[i] >= x[i + 1] && x[i] > 0.0 {
            let (a, b, c) = (x[i - 1], x[i], x[i + 1]);
            let den = a - 2.0 * b + c;
            let d = if den != 0.0 { 0.5 * (a - c) / den } else { 0.0 };
            let h = t[i + 1] - t[i];
            out.push((t[i] + d * h, b - 0.25 * (a - c) * d));
        }
    }
    out
}

/// The mean period between the first and the last upward zero crossing.
fn mean_period(t: &[f64], x: &[f64]) -> f64 {
    let c = up_crossings(t, x);
    (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64
}

/// Times of the upward zero crossings (linear interpolation).
fn up_crossings(t: &[f64], x: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 1..x.len() {
        if x[i - 1] < 0.0 && x[i] >= 0.0 {
            out.push(t[i - 1] + (t[i] - t[i - 1]) * (-x[i - 1]) / (x[i] - x[i - 1]));
        }
    }
    out
}

/// HHT-α with α = 0, −0.1, −0.3 through the production `advance`, at Ω = ωΔt = 0.5 (a coarse step,
/// where the algorithmic damping and period elongation are large): the amplitude decay per step and
/// the period measured on the bar's free vibration equal the closed-form values of the scheme,
/// `|λ|` and `2πΔt/arg λ` of the principal eigenvalue of its one-step map (Hilber et al. 1977), to
/// 0.1 % (amplitude lost per period, measured over 60 periods) and 0.05 % (period). The three α give visibly different answers
/// (1.26 % amplitude loss per period at α = −0.3, 0.71 % at −0.1, none at α = 0; periods 0.5 % apart), so flipping the α-weighting of
/// the force average fails this test.
#[test]
fn hht_alpha_decay_and_period_elongation_through_advance() {
    let (ea, l, mu): (f64, f64, f64) = (1.0e6, 1.0, 2.0);
    let omega = (ea / l / (mu * l / 2.0)).sqrt(); // 1000 rad/s
    let omega_dt = 0.5;
    let dt = omega_dt / omega;
    let seg = segment(l, 1, ea, 1.0, mu, 0.0, 0.1);
    for alpha in [0.0, -0.1, -0.3] {
        let lam = common::one_step_eigenvalues(Scheme::Hht { alpha }, omega_dt * omega_dt);
        // The principal root: the complex pair with the largest modulus.
        let pr = lam
            .iter()
            .filter(|z| z.1 > 1e-9)
            .copied()
            .fold((0.0f64, 0.0f64), |b, z| {
                if z.0.hypot(z.1) > f64::hypot(b.0, b.1) {
                    z
                } else {
                    b
                }
            });
        let rho = pr.0.hypot(pr.1);
        let period = 2.0 * PI * dt / pr.1.atan2(pr.0);
        let steps = (60.0 * period / dt) as usize;
        let (t, x) = bar_history(seg, &settings(alpha, None), 1e-3, dt, steps);
        let c = up_crossings(&t, &x);
        let measured_period = (c[c.len() - 1] - c[1]) / (c.len() - 2) as f64;
        // Decay: amplitude from the last crossing-to-crossing window against the second one.
        let pk = peaks(&t, &x);
        let (t0, a0) = pk[2];
        let (t1, a1) = pk[pk.len() - 2];
        let measured_rho = (a1 / a0).powf(dt / (t1 - t0));
        let exact_period = 2.0 * PI / omega;
        println!(
            "α = {alpha}: ρ = {measured_rho:.6} (closed form {rho:.6}), period {:.6} ms \
             (closed form {:.6} ms, exact {:.6} ms, elongation {:+.3} %), loss per period {:.2} %",
            measured_period * 1e3,
            period * 1e3,
            exact_period * 1e3,
            100.0 * (period / exact_period - 1.0),
            100.0 * (1.0 - rho.powf(period / dt))
        );
        let decay_err = (measured_rho.powf(period / dt) - rho.powf(period / dt)).abs();
        assert!(
            decay_err < 1e-3,
            "α = {alpha}: decay per period off by {decay_err}"
        );
        assert!(
            (measured_period / period - 1.0).abs() < 5e-4,
            "α = {alpha}: period {measured_period} vs {period}"
        );
    }
}

/// Added mass acts normal to the line only. A taut horizontal string (L 100 m, T 100 kN, μ 10 kg/m,
/// D 0.1 m) in water with `Ca = 1`: its first transverse period is that of a string of mass
/// `μ + Ca·ρ·πD²/4` (8.05 kg/m more, so 34 % longer), within 0.5 %; the vertical bar's axial period
/// is unchanged by the water, within 0.05 %. A line type's own `Ca` (here 1 in a sea of 0) is the
/// one its nodes take. Dropping, doubling or applying the added mass axially, or taking the sea's
/// coefficient over the type's, fails one of them.
#[test]
fn added_mass_is_normal_and_of_the_right_size() {
    let (l, t, ea, mu, d) = (100.0, 1e5, 1e10, 10.0, 0.1);
    let ca = 1.0;
    let ma = ca * 1025.0 * PI * d * d / 4.0;
    // Transverse: the string.
    let m = model(
        segment(l, 40, ea, 1.0, mu, 0.0, d),
        Support::Pinned,
        Support::Pinned,
        None,
    );
    let stretch = 1.0 + t / ea;
    let nn = m.nodes();
    let q: Vec<f64> = (0..nn)
        .flat_map(|i| [m.arc[i] * stretch, 0.0, 0.0])
        .collect();
    let pl = Placement::new(&q);
    // The same string whose line type has its own Ca = 1 in a sea of Ca = 0: the type's is used.
    let mut own = segment(l, 40, ea, 1.0, mu, 0.0, d);
    own.coefficients = Some(catena_fe::environment::Coefficients {
        cd_normal: 0.0,
        cd_axial: 0.0,
        ca_normal: ca,
    });
    let m_own = model(own, Support::Pinned, Support::Pinned, None)
        .with_sea_coefficients(hydro(0.0, 0.0, 0.0).coefficients());
    for (label, m, h, mass) in [
        ("in air", &m, None, mu),
        ("in water", &m, Some(hydro(0.0, 0.0, ca)), mu + ma),
        (
            "with its type's own Ca",
            &m_own,
            Some(hydro(0.0, 0.0, 0.0)),
            mu + ma,
        ),
    ] {
        let dm = dynamic(m, &pl, &settings(0.0, h));
        let mut ws = DynWorkspace::new(m).expect("ws");
        let mut st = initial_state(&dm, &vec![0.0; q.len()], &mut ws);
        for i in 0..nn {
            st.v[3 * i + 1] = 1e-3 * (PI * m.arc[i] / l).sin();
        }
        let period = 2.0 * PI / tensioned_beam_frequency(1, l, 1.0, mass, t);
        let dt = period / 100.0;
        let mid = (nn - 1) / 2;
        let (mut ts, mut zs) = (vec![0.0], vec![0.0]);
        for _ in 0..500 {
            advance(&dm, &mut st, &mut ws, dt).expect("step");
            ts.push(st.t);
            zs.push(st.u[3 * mid + 1]);
        }
        let measured = mean_period(&ts, &zs);
        println!(
            "string {label}: period {measured:.5} s, analytical {period:.5} s (mass {mass:.3} kg/m)"
        );
        assert!(
            (measured / period - 1.0).abs() < 5e-3,
            "{label}: {measured} vs {period}"
        );
    }
    // Axial: the bar, in air and in water.
    let (ea, lb, mub): (f64, f64, f64) = (1.0e6, 1.0, 2.0);
    let omega_dt = 0.05;
    let dt = omega_dt / (ea / lb / (mub * lb / 2.0)).sqrt();
    let seg = segment(lb, 1, ea, 1.0, mub, 0.0, 0.3);
    let mut periods = Vec::new();
    for h in [None, Some(hydro(0.0, 0.0, 1.0))] {
        let (t, x) = bar_history(seg, &settings(0.0, h), 1e-3, dt, 2000);
        periods.push(mean_period(&t, &x));
    }
    println!(
        "bar axial period in air {:.6e} s, in water {:.6e} s",
        periods[0], periods[1]
    );
    assert!(
        (periods[1] / periods[0] - 1.0).abs() < 5e-4,
        "added mass acts axially: {periods:?}"
    );
}

/// Morison drag decays a free vibration as the closed form of quadratic damping says. The bar
/// vibrating along its axis with axial drag only (`Cd_a`, on the area πD per length, over the bottom
/// node's tributary length L0/2) is `m ẍ + c|ẋ|ẋ + k x = 0` with `c = ½ρ·Cd_a·πD·L0/2`; to first
/// order in the damping the amplitude follows `1/A(t) = 1/A₀ + (4/3π)(c/m)·ω·t` (energy balance over a
/// cycle). Over 10 periods the amplitude halves; the measured peaks follow the formula within 2 %.
/// The trapezoidal rule (α = 0) at Δt = T/200 adds no algorithmic damping.
#[test]
fn drag_decays_a_free_vibration_as_quadratic_damping() {
    let (ea, l, mu, d, cda): (f64, f64, f64, f64, f64) = (1.0e6, 1.0, 2.0, 0.2, 1.0);
    let m = mu * l / 2.0;
    let omega = (ea / l / m).sqrt();
    let c = 0.5 * 1025.0 * cda * PI * d * l / 2.0;
    // A₀ such that the amplitude halves in 10 periods.
    let a0 = 1.0 / ((4.0 / (3.0 * PI)) * (c / m) * omega * 10.0 * 2.0 * PI / omega);
    let dt = 2.0 * PI / omega / 200.0;
    let seg = segment(l, 1, ea, 1.0, mu, 0.0, d);
    let (t, x) = bar_history(
        seg,
        &settings(0.0, Some(hydro(0.0, cda, 0.0))),
        a0,
        dt,
        2000,
    );
    let pk = peaks(&t, &x);
    assert!(pk.len() >= 9, "{} peaks", pk.len());
    let mut worst: f64 = 0.0;
    for &(tp, ap) in &pk {
        let want = 1.0 / (1.0 / a0 + (4.0 / (3.0 * PI)) * (c / m) * omega * tp);
        worst = worst.max((ap / want - 1.0).abs());
    }
    let (tl, al) = pk[pk.len() - 1];
    println!(
        "A0 = {a0:.4e} m; last peak at t = {tl:.5} s: {al:.4e} m, formula {:.4e} m; worst {:.3} %",
        1.0 / (1.0 / a0 + (4.0 / (3.0 * PI)) * (c / m) * omega * tl),
        100.0 * worst
    );
    assert!(worst < 0.02, "drag decay off by {worst}");
    assert!(al < 0.6 * a0, "the vibration must decay: {al} vs {a0}");
}

/// The flexjoint pulls the top tangent towards its neutral angle. A stiff bar of length L and weight
/// W hangs from a pinned top whose flexjoint (stiffness k) has its neutral angle tilted by δ from the
/// downward vertical: it settles at the angle φ from the vertical where the moments balance,
/// `k(φ − δ) + W·(L/2)·sin φ = 0` (solved here by bisection), within 0.1 %. A flexjoint moment of the
/// wrong sign pushes the bar the other way and fails.
#[test]
fn flexjoint_pulls_towards_its_neutral_angle() {
    let (l, w, k, delta) = (10.0, 100.0, 2000.0, 0.2);
    let m = model(
        segment(l, 10, 1e10, 1e9, w / 9.80665, w, 0.1),
        Support::Pinned,
        Support::Free,
        Some((k, -PI / 2.0 + delta)),
    );
    let nn = m.nodes();
    let q: Vec<f64> = (0..nn).flat_map(|i| [0.0, -m.arc[i], -PI / 2.0]).collect();
    let pl = Placement::new(&q);
    let mut ws = StaticWorkspace::new(&m).expect("ws");
    let mut u = vec![0.0; q.len()];
    statics::solve(&m, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("statics");
    let phi = pl.base[2] + u[2] + PI / 2.0;
    // k(φ − δ) + W L/2 sin φ = 0 on [0, δ].
    let f = |p: f64| k * (p - delta) + w * l * l / 2.0 * p.sin();
    let (mut lo, mut hi) = (0.0, delta);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let want = 0.5 * (lo + hi);
    // The tip lies on the straight bar's line.
    let tip_x = pl.base[3 * (nn - 1)] + u[3 * (nn - 1)];
    println!(
        "top angle from vertical {phi:.6} rad (moment balance {want:.6} rad); tip x {tip_x:.4} m"
    );
    assert!((phi / want - 1.0).abs() < 1e-3, "{phi} vs {want}");
    assert!(tip_x > 0.0 && (tip_x / (l * want.sin()) - 1.0).abs() < 1e-2);
}

/// Structural damping given as a fraction ζ of critical at a period T (`β = ζT/π`) damps a mode of
/// that period at ζ: the bar's axial vibration with ζ = 2 % at its own period decays with the
/// logarithmic decrement `δ = 2πζ/√(1 − ζ²)`; the measured ζ is within 2 % of 0.02 (trapezoidal rule,
/// Ω = 0.05, which adds no algorithmic damping). Without the damping the amplitude does not decay.
#[test]
fn structural_damping_gives_the_damping_ratio_at_its_period() {
    let (ea, l, mu): (f64, f64, f64) = (1.0e6, 1.0, 2.0);
    let omega = (ea / l / (mu * l / 2.0)).sqrt();
    let period = 2.0 * PI / omega;
    let zeta = 0.02;
    let dt = 0.05 / omega;
    let seg = segment(l, 1, ea, 1.0, mu, 0.0, 0.1);
    let set = Settings {
        alpha: 0.0,
        hydro: None,
        beta: Some(zeta * period / PI),
    };
    let (t, x) = bar_history(seg, &set, 1e-3, dt, (20.0 * period / dt) as usize);
    let pk = peaks(&t, &x);
    let (a0, a1) = (pk[1].1, pk[pk.len() - 1].1);
    let cycles = (pk[pk.len() - 1].0 - pk[1].0) / period;
    let delta = (a0 / a1).ln() / cycles;
    let measured = delta / (4.0 * PI * PI + delta * delta).sqrt();
    println!("ζ measured {measured:.5} (given {zeta}) over {cycles:.1} cycles");
    assert!((measured / zeta - 1.0).abs() < 0.02, "{measured}");
}

/// Structural damping spares rigid-body motion: a stiff bar (L 10 m) pinned at one end and released
/// from horizontal swings as a rigid pendulum; with heavy structural damping (10 % of critical at the
/// bar's first bending period) it still swings to the other side (its tip reaches x = −L within
/// 0.5 %) in half the rigid pendulum's period (6.1137 s, within 0.5 %).
#[test]
fn structural_damping_spares_a_rigid_pendulum() {
    let (l, m, g) = (10.0, 10.0, 9.80665);
    let (ea, ei) = (1e10, 1e7);
    let mline = model(
        segment(l, 20, ea, ei, m, m * g, 0.1),
        Support::Pinned,
        Support::Free,
        None,
    );
    let nn = mline.nodes();
    let q: Vec<f64> = (0..nn).flat_map(|i| [mline.arc[i], 0.0, 0.0]).collect();
    let pl = Placement::new(&q);
    // First bending period of a pinned–free bar is far below a second: 10 % of critical there.
    let f1 = 1.875f64.powi(2) / (2.0 * PI) * (ei / (m * l.powi(4))).sqrt();
    let set = Settings {
        alpha: -0.1,
        hydro: None,
        beta: Some(0.10 / f1 / PI),
    };
    let dm = dynamic(&mline, &pl, &set);
    let mut ws = DynWorkspace::new(&mline).expect("ws");
    let mut st = initial_state(&dm, &vec![0.0; q.len()], &mut ws);
    let tip = 3 * (nn - 1);
    let (mut t_min, mut x_min) = (0.0, f64::INFINITY);
    while st.t < 4.0 {
        advance(&dm, &mut st, &mut ws, 0.002).expect("steps");
        let x = pl.base[tip] + st.u[tip];
        if x < x_min {
            (t_min, x_min) = (st.t, x);
        }
    }
    println!("tip reaches x = {x_min:.4} m at t = {t_min:.4} s (rigid: −10 m at 3.0569 s)");
    assert!((x_min / -l - 1.0).abs() < 5e-3, "{x_min}");
    assert!((t_min / (6.1137 / 2.0) - 1.0).abs() < 5e-3, "{t_min}");
}

/// A step that fails leaves the State exactly as it was (to the bit), also after sub-steps of a
/// cut step have been committed; a step that succeeds after cuts ends at the full step. The falling
/// pendulum is stepped with Newton allowed 1 to 4 iterations and 0 to 3 cuts: among them, steps that
/// fail outright, steps that fail after committed sub-steps, and steps that succeed only when cut.
#[test]
fn a_failed_step_leaves_the_state_as_it_was() {
    let (mline, q, pl) = falling_pendulum(10);
    let set = settings(-0.1, None);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let (mut failed, mut failed_after_substeps, mut cut_and_done) = (0, 0, 0);
    for max_iter in 1..=4 {
        for max_cuts in 0..=3 {
            let mut dm = dynamic(&mline, &pl, &set);
            dm.settings.max_iter = max_iter;
            dm.settings.max_cuts = max_cuts;
            let mut ws = DynWorkspace::new(&mline).expect("ws");
            let mut st = initial_state(&dm, &vec![0.0; q.len()], &mut ws);
            for _ in 0..40 {
                let before = st.clone();
                let dt = 0.1;
                match advance(&dm, &mut st, &mut ws, dt) {
                    Ok(info) => {
                        assert_eq!(st.t, before.t + dt);
                        cut_and_done += usize::from(info.cuts > 0);
                    }
                    Err(e) => {
                        assert_eq!(st.t, before.t);
                        assert_eq!(st.step, before.step);
                        for (a, b) in [(&st.u, &before.u), (&st.v, &before.v), (&st.a, &before.a)] {
                            assert_eq!(bits(a), bits(b), "{e}");
                        }
                        assert_eq!(bits(&st.f_prev), bits(&before.f_prev));
                        failed += 1;
                        // Sub-steps were committed before the failure when the failed
                        // sub-step did not start at the step's start.
                        if let catena_fe::dynamics::StepError::NotConverged { t, dt: h, .. } = e {
                            failed_after_substeps += usize::from(t - h > before.t + 1e-12);
                        }
                        break;
                    }
                }
            }
        }
    }
    println!(
        "{failed} failed ({failed_after_substeps} after sub-steps), {cut_and_done} cut and done"
    );
    assert!(failed > 0 && failed_after_substeps > 0 && cut_and_done > 0);
}

/// The prescribed top is the motion at the step's end, exactly (the module's convention: only the
/// forces are α-weighted). A vertical bar in air, its top heaved harmonically (2 m, 10 s, ramped
/// over 5 s) with HHT α = −0.1: after every step the top node's displacement, velocity and
/// acceleration are the motion's at `t_{n+1}` to the bit, and the bottom node follows a
/// stiff bar, its axial stretch `m·a/k` within 1e-3 of the top's acceleration's share. Evaluating
/// the motion at `t_{n+1+α}` lags the top by `α·Δt·v` and fails both.
#[test]
fn the_prescribed_top_is_the_motion_at_the_step_end() {
    use catena_fe::motion::TopMotion;
    let (l, mu, ea) = (10.0, 50.0, 1e9);
    let seg = segment(l, 1, ea, 1e6, mu, 0.0, 0.2);
    let m = model(seg, Support::Fixed, Support::Free, None);
    let q = vec![0.0, 0.0, -PI / 2.0, 0.0, -l, -PI / 2.0];
    let pl = Placement::new(&q);
    let motion = TopMotion::Harmonic {
        surge: 0.0,
        heave: 2.0,
        period: 10.0,
        phase: 0.0,
        ramp: 5.0,
    };
    let mut dm = dynamic(&m, &pl, &settings(-0.1, None));
    dm.motion = Some(motion.clone());
    let mut ws = DynWorkspace::new(&m).expect("workspace");
    let mut st = initial_state(&dm, &[0.0; 6], &mut ws);
    let dt = 0.05;
    for _ in 0..200 {
        advance(&dm, &mut st, &mut ws, dt).expect("step");
        let (d, v, a) = motion.at(st.t);
        for k in 0..2 {
            assert_eq!(st.u[k].to_bits(), d[k].to_bits(), "t {}: u[{k}]", st.t);
            assert_eq!(st.v[k].to_bits(), v[k].to_bits(), "t {}: v[{k}]", st.t);
            assert_eq!(st.a[k].to_bits(), a[k].to_bits(), "t {}: a[{k}]", st.t);
        }
        // The bar is stiff (ω = 632 rad/s): the bottom node moves with the top, stretched by the
        // force that accelerates its lumped mass, m·a/k with m = μL/2.
        let stretch = (st.u[1] - st.u[4]) - (0.5 * mu * l) * st.a[4] / (ea / l);
        assert!(
            stretch.abs() < 1e-3 * 1e-4,
            "t {}: stretch {stretch:e} m",
            st.t
        );
    }
}

/// Wave inertia through the stepper: a horizontal bar 5 m under the still water level (L 10 m,
/// D 0.5 m, EA 10 MN, EI 10 GN·m² so that it hardly bends, no drag), its left end fixed and its right node free, in a regular wave
/// (H 2 m, T 10 s, deep water). Along the bar the water's acceleration meets the displaced mass
/// alone (Froude–Krylov, no added mass along the axis), so the free node is a stiff spring
/// (ω_n = 45 rad/s against the wave's 0.63) loaded by `ρ·πD²/4·(L/2)·a_x`: it stretches the bar
/// by that force over `EA/L`, quasi-statically (the dynamic amplification `1/(1 − (ω/ω_n)²)` is
/// 1.0002). Measured over a wave period after a 20 s ramp, within 0.5 % of the amplitude (0.33 mm;
/// measured 0.02 %).
/// Without the wave inertia the bar does not move.
#[test]
fn wave_inertia_moves_a_free_node_with_the_water() {
    use catena_fe::waves::{Direction, Waves};
    let (l, d, ea, level, depth) = (10.0, 0.5, 1e7, 95.0, 100.0);
    let seg = segment(l, 1, ea, 1e10, 100.0, 0.0, d);
    let m = model(seg, Support::Fixed, Support::Free, None);
    let q = vec![0.0, level, 0.0, l, level, 0.0];
    let pl = Placement::new(&q);
    let waves = Waves::regular(2.0, 10.0, Direction::PlusX, depth, 9.81, 20.0).expect("wave");
    let mut dm = dynamic(&m, &pl, &settings(-0.1, Some(hydro(0.0, 0.0, 1.0))));
    dm.environment.waves = Some(waves.clone());
    dm.environment.water_level = depth;
    let mut ws = DynWorkspace::new(&m).expect("workspace");
    let mut st = initial_state(&dm, &[0.0; 6], &mut ws);
    let dt = 0.02;
    let force_per_accel = 1025.0 * PI * d * d / 4.0 * (0.5 * l);
    let (mut worst, mut amplitude) = (0.0f64, 0.0f64);
    while st.t < 40.0 - 1e-9 {
        advance(&dm, &mut st, &mut ws, dt).expect("step");
        if st.t >= 30.0 {
            let x = l + st.u[3];
            let ax = waves
                .kinematics(x, level + st.u[4] - depth, st.t)
                .expect("under water")
                .acceleration[0];
            let want = force_per_accel * ax / (ea / l);
            worst = worst.max((st.u[3] - want).abs());
            amplitude = amplitude.max(want.abs());
        }
    }
    println!("stretch amplitude {amplitude:e} m, worst difference {worst:e} m");
    assert!(amplitude > 3e-4, "{amplitude}");
    assert!(worst < 0.005 * amplitude, "{worst} against {amplitude}");
}

/// Axial seabed friction through the stepper: a 20 m pipe (w = 500 N/m, D 0.3 m) lying on a linear
/// seabed with friction μ = 0.5, δ = 10 mm, its end pushed and pulled axially (±0.1 m at 5 mm/s, in
/// air). The force at the moving end rises over δ to the whole pipe's friction μ·w·L = 5000 N
/// (within 1 %: 2500 N at δ/2, within 2 %) and stays there while the pipe slides; a full cycle
/// between ±A dissipates the elastic–slip loop's area, `4·μ·w·L·(A − δ)` = 1800 J, within 2 %.
#[test]
fn friction_rises_over_its_mobilisation_and_slides() {
    use catena_fe::model::{AxialFriction, SeabedContact};
    use catena_fe::motion::TopMotion;
    use catena_seabed::law::{Law, Seabed};
    use catena_seabed::LinearSeabed;
    let (l, w, od, k) = (20.0, 500.0, 0.3, 2e5);
    let (mu, delta, v, a_amp) = (0.5, 0.01, 0.005, 0.1);
    let model = LineModel::build(&LineSpec {
        segments: vec![segment(l, 20, 1e9, 1e6, 100.0, w, od)],
        top: Support::Pinned,
        anchor: Support::Free,
        seabed: Some(SeabedContact {
            seabed: Seabed {
                law: Law::Linear(LinearSeabed::new(od, k, 0.0).expect("law")),
                buoyancy: None,
            },
            mudline_z: 0.0,
            friction: Some(AxialFriction {
                mu,
                mobilisation: delta,
            }),
        }),
        flexjoint: None,
    })
    .expect("model");
    // Resting at its embedment w/(kD) (every node carries its weight over its tributary length).
    let z = 0.5 * od - w / (k * od);
    let q: Vec<f64> = (0..=20).flat_map(|i| [i as f64, z, 0.0]).collect();
    let pl = Placement::new(&q);
    // α = −0.3: the velocity steps of the staged motion ring the stiff pipe axially (ω ≈ 250
    // rad/s, ωΔt ≈ 12), and the scheme's strongest damping takes the ringing out within a second.
    let mut dm = dynamic(&model, &pl, &settings(-0.3, None));
    let t1 = a_amp / v;
    dm.motion = Some(TopMotion::Staged(vec![
        (t1, v, 0.0),
        (2.0 * t1, -v, 0.0),
        (2.0 * t1, v, 0.0),
    ]));
    let mut ws = DynWorkspace::new(&model).expect("workspace");
    let n3 = 3 * model.nodes();
    let mut st = initial_state(&dm, &vec![0.0; n3], &mut ws);
    let dt = 0.05;
    let full = mu * w * l;
    let (mut work, mut prev) = (0.0, (0.0, 0.0));
    while st.t < 5.0 * t1 - 1e-9 {
        advance(&dm, &mut st, &mut ws, dt).expect("step");
        let (x, r) = (st.u[0], st.f_prev[0]);
        let t = st.t;
        if (t - 0.5 * delta / v).abs() < 1e-9 {
            assert!((r.abs() / (0.5 * full) - 1.0).abs() < 0.02, "at δ/2: {r} N");
        }
        // Sliding, away from the reversals: the whole friction.
        let since = [0.0, t1, 3.0 * t1]
            .iter()
            .map(|s| t - s)
            .fold(f64::INFINITY, |m, d| if d >= 0.0 { m.min(d) } else { m });
        if since > 4.0 * delta / v {
            assert!((r.abs() / full - 1.0).abs() < 0.01, "t {t}: {r} N sliding");
        }
        if t > t1 + 1e-9 {
            // The work of the force at the moving end over the cycle from x = +A back to +A.
            work += 0.5 * (r + prev.1) * (x - prev.0);
        }
        prev = (x, r);
    }
    let loop_area = 4.0 * full * (a_amp - delta);
    println!("friction {full} N; loop {work:.1} J against {loop_area:.1} J");
    assert!(
        (work.abs() / loop_area - 1.0).abs() < 0.02,
        "{work} against {loop_area}"
    );
}

/// Friction on a sloping seabed acts along the mudline: the 20 m pipe of the test above lying down
/// a 15° slope (its top end pinned, holding the down-slope weight in the frictionless statics),
/// its top pushed and pulled along the slope (±0.1 m at 5 mm/s). The pin's force along the slope
/// changes by the whole friction `μ·w·cos α·L` (the normal force is `w·cos α` per length) while
/// the pipe slides (within 1 %), and a full cycle dissipates `4·μ·w·cos α·L·(A − δ)` (within 2 %).
/// With friction along x instead, the sliding force is `cos α` smaller (3.4 % at 15°).
#[test]
fn friction_on_a_slope_acts_along_the_mudline() {
    use catena_fe::model::{AxialFriction, SeabedContact};
    use catena_fe::motion::TopMotion;
    use catena_seabed::law::{Law, Seabed};
    use catena_seabed::LinearSeabed;
    let (l, n, w, od, k) = (20.0, 20, 500.0, 0.3, 2e5);
    let (mu, delta, v, a_amp) = (0.5, 0.01, 0.005, 0.1);
    let alpha = 15f64.to_radians();
    let (c, s) = (alpha.cos(), alpha.sin());
    let m = -alpha.tan();
    let model = LineModel::build(&LineSpec {
        segments: vec![segment(l, n, 1e9, 1e6, 100.0, w, od)],
        top: Support::Pinned,
        anchor: Support::Free,
        seabed: Some(SeabedContact {
            seabed: Seabed {
                law: Law::Linear(LinearSeabed::new(od, k, 0.0).expect("law")),
                buoyancy: None,
            },
            mudline_z: 0.0,
            friction: Some(AxialFriction {
                mu,
                mobilisation: delta,
            }),
        }),
        flexjoint: None,
    })
    .expect("model")
    .with_mudline_profile(vec![(-100.0, -100.0 * m), (100.0, 100.0 * m)]);
    // On the slope at its normal embedment, then the frictionless statics.
    let h = 0.5 * od - w * c / (k * od);
    let q: Vec<f64> = (0..=n)
        .flat_map(|i| {
            let sx = i as f64 * l / n as f64;
            [sx * c + h * s, m * (sx * c) + h * c, -alpha]
        })
        .collect();
    let pl = Placement::new(&q);
    let mut sws = StaticWorkspace::new(&model).expect("ws");
    let mut u0 = vec![0.0; q.len()];
    statics::solve(&model, &pl, &mut u0, &mut sws, &StaticOptions::default()).expect("statics");
    let mut dm = dynamic(&model, &pl, &settings(-0.3, None));
    let t1 = a_amp / v;
    // Down the slope first, then up, then down again.
    dm.motion = Some(TopMotion::Staged(vec![
        (t1, v * c, -v * s),
        (2.0 * t1, -v * c, v * s),
        (2.0 * t1, v * c, -v * s),
    ]));
    let mut ws = DynWorkspace::new(&model).expect("workspace");
    let mut st = initial_state(&dm, &u0, &mut ws);
    // The pin's force along the slope (down-slope positive) and the top's travel along it.
    let along = |st: &catena_fe::dynamics::DynState| {
        (
            st.f_prev[0] * c - st.f_prev[1] * s,
            st.u[0] * c - st.u[1] * s,
        )
    };
    let r0 = along(&st).0;
    let dt = 0.05;
    let full = mu * w * c * l;
    let (mut work, mut prev, mut worst) = (0.0, (0.0, 0.0), 0.0f64);
    while st.t < 5.0 * t1 - 1e-9 {
        advance(&dm, &mut st, &mut ws, dt).expect("step");
        let (r, x) = along(&st);
        let r = r - r0;
        let t = st.t;
        let since = [0.0, t1, 3.0 * t1]
            .iter()
            .map(|s| t - s)
            .fold(f64::INFINITY, |m, d| if d >= 0.0 { m.min(d) } else { m });
        if since > 4.0 * delta / v {
            worst = worst.max((r.abs() / full - 1.0).abs());
        }
        if t > t1 + 1e-9 {
            work += 0.5 * (r + prev.1) * (x - prev.0);
        }
        prev = (x, r);
    }
    let loop_area = 4.0 * full * (a_amp - delta);
    println!(
        "friction on a 15° slope: sliding force within {:.3} % of μ·w·cos α·L = {full:.1} N; loop {work:.1} J against {loop_area:.1} J",
        100.0 * worst
    );
    assert!(worst < 0.01, "sliding force off by {worst}");
    assert!(
        (work.abs() / loop_area - 1.0).abs() < 0.02,
        "{work} against {loop_area}"
    );
}

/// Attached bodies through the stepper: the vertical bar's free bottom node (an axial spring
/// `k = EA/L0` with the lumped `μL0/2`) carries a body of mass M and, in water, added mass Ma
/// (isotropic, so it acts along the bar too, where the pipe's own added mass does not): the period
/// is `2π·√((μL0/2 + M + Ma)/k)` (measured over 40 periods, to 0.1 %). A hanging line with a clump
/// of weight W at its end carries `w·L + W` at its top (statics, to 1e-9).
#[test]
fn attached_bodies_add_mass_and_weight() {
    use catena_fe::model::Attachment;
    let (l, mu, ea) = (1.0, 100.0, 1e6);
    let seg = segment(l, 1, ea, 1e3, mu, 0.0, 0.2);
    let body = |mass: f64, added_mass: f64, weight: f64| Attachment {
        node: 0,
        mass,
        weight,
        drag_area: 0.0,
        added_mass,
    };
    for (mass, added, hydro_on) in [(30.0, 0.0, false), (30.0, 20.0, true)] {
        let m = model(seg, Support::Fixed, Support::Free, None)
            .with_attachments(&[(l, body(mass, added, 0.0))]);
        let q = vec![0.0, 0.0, -PI / 2.0, 0.0, -l, -PI / 2.0];
        let pl = Placement::new(&q);
        let h = hydro_on.then(|| hydro(0.0, 0.0, 1.0));
        let dm = dynamic(&m, &pl, &settings(0.0, h));
        let mut ws = DynWorkspace::new(&m).expect("workspace");
        let mut u = vec![0.0; 6];
        u[4] = -1e-3;
        let mut st = initial_state(&dm, &u, &mut ws);
        let m_tot = 0.5 * mu * l + mass + added;
        let period = 2.0 * PI * (m_tot / (ea / l)).sqrt();
        let dt = period / 200.0;
        let (mut t, mut x) = (vec![0.0], vec![1e-3]);
        for _ in 0..(40 * 200 + 50) {
            advance(&dm, &mut st, &mut ws, dt).expect("step");
            t.push(st.t);
            x.push(-st.u[4]);
        }
        let measured = mean_period(&t, &x);
        // The trapezoidal rule's period elongation at Ω = 2π/200: (Ω²/12) = 8.2e-5.
        println!(
            "attached mass {mass} kg, added {added} kg: period {measured:.6} s ({period:.6} s)"
        );
        assert!(
            (measured / period - 1.0).abs() < 1e-3,
            "{measured} vs {period}"
        );
    }
    // Statics: a hanging 10 m line (w = 300 N/m) with a 2 kN clump at its end.
    let (len, w, clump) = (10.0, 300.0, 2000.0);
    let m = model(
        segment(len, 10, 1e9, 1e4, 30.0, w, 0.2),
        Support::Pinned,
        Support::Free,
        None,
    )
    .with_attachments(&[(len, body(200.0, 0.0, clump))]);
    let q: Vec<f64> = (0..=10)
        .flat_map(|i| [0.0, -(i as f64), -PI / 2.0])
        .collect();
    let pl = Placement::new(&q);
    let mut ws = StaticWorkspace::new(&m).expect("ws");
    let mut u = vec![0.0; q.len()];
    statics::solve(&m, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("statics");
    let top = ws.asm.residual[1];
    println!(
        "hanging line with a clump: top reaction {top:.6} N (w·L + W = {})",
        w * len + clump
    );
    assert!((top / (w * len + clump) - 1.0).abs() < 1e-9, "{top}");
}

/// Soil that varies along the route (statics): a 30 m pipe (w 500 N/m, D 0.3 m) resting on a linear
/// seabed of stiffness 1e5 N/m/m² with a zone of 2e4 N/m/m² over x ∈ [12, 40) m. Far from the
/// boundary each node sinks to its own soil's embedment `w/(k·D)` (16.7 mm and 83.3 mm), to 1e-5
/// relative; the default law holds before the zone.
#[test]
fn a_soft_zone_sinks_the_pipe_to_its_own_embedment() {
    use catena_fe::model::{SeabedContact, SeabedZone};
    use catena_seabed::law::{Law, Seabed};
    use catena_seabed::LinearSeabed;
    let (len, w, od, k1, k2) = (30.0, 500.0, 0.3, 1e5, 2e4);
    let law = |k: f64| Seabed {
        law: Law::Linear(LinearSeabed::new(od, k, 0.0).expect("law")),
        buoyancy: None,
    };
    let model = LineModel::build(&LineSpec {
        segments: vec![segment(len, 30, 1e9, 1e3, 100.0, w, od)],
        top: Support::Pinned,
        anchor: Support::Free,
        seabed: Some(SeabedContact {
            seabed: law(k1),
            mudline_z: 0.0,
            friction: None,
        }),
        flexjoint: None,
    })
    .expect("model")
    .with_seabed_zones(vec![SeabedZone {
        from_x: 12.0,
        to_x: 40.0,
        seabed: law(k2),
    }]);
    let z0 = 0.5 * od - w / (k1 * od);
    let q: Vec<f64> = (0..=30).flat_map(|i| [i as f64, z0, 0.0]).collect();
    let model = model.zoned_at(&q);
    let pl = Placement::new(&q);
    let mut ws = StaticWorkspace::new(&model).expect("ws");
    let mut u = vec![0.0; q.len()];
    statics::solve(&model, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("statics");
    let pen = |i: usize| 0.5 * od - (z0 + u[3 * i + 1]);
    for (i, k) in [(3, k1), (5, k1), (22, k2), (28, k2)] {
        let want = w / (k * od);
        println!(
            "node {i} (x {i} m): penetration {:.6} m (w/kD = {want:.6} m)",
            pen(i)
        );
        assert!(
            (pen(i) / want - 1.0).abs() < 1e-5,
            "node {i}: {} vs {want}",
            pen(i)
        );
    }
}

/// A sloping seabed (statics): a 20 m pipe (w 500 N/m, D 0.3 m) lying down a 5° slope of a linear
/// seabed (k 1e5 N/m/m²), pinned at its upper end. Contact acts normal to the mudline, and the
/// seabed is frictionless in the statics: the pipe presses into the slope by `w·cos α/(k·D)` at every
/// node away from the ends (to 1e-6) and hangs from its pin by the slope's share of its weight,
/// `w·L·sin α` along the slope (to 1e-6). With the contact force vertical instead of normal, both
/// fail.
#[test]
fn a_pipe_on_a_slope_presses_normal_to_it_and_hangs_from_its_pin() {
    use catena_fe::model::SeabedContact;
    use catena_seabed::law::{Law, Seabed};
    use catena_seabed::LinearSeabed;
    let (len, n, w, od, k) = (20.0, 20, 500.0, 0.3, 1e5);
    let alpha = 5f64.to_radians();
    let (c, s) = (alpha.cos(), alpha.sin());
    let m = -alpha.tan();
    let model = LineModel::build(&LineSpec {
        segments: vec![segment(len, n, 1e10, 1e3, 100.0, w, od)],
        top: Support::Pinned,
        anchor: Support::Free,
        seabed: Some(SeabedContact {
            seabed: Seabed {
                law: Law::Linear(LinearSeabed::new(od, k, 0.0).expect("law")),
                buoyancy: None,
            },
            mudline_z: 0.0,
            friction: None,
        }),
        flexjoint: None,
    })
    .expect("model")
    .with_mudline_profile(vec![(-100.0, -100.0 * m), (100.0, 100.0 * m)]);
    let pen = w * c / (k * od);
    // Each node on the slope, its centre (D/2 − pen) above the mudline along the normal
    // n = (sin α, cos α) (the slope descends towards +x).
    let h = 0.5 * od - pen;
    let q: Vec<f64> = (0..=n)
        .flat_map(|i| {
            let sx = i as f64 * len / n as f64;
            [sx * c + h * s, m * (sx * c) + h * c, -alpha]
        })
        .collect();
    let pl = Placement::new(&q);
    let mut ws = StaticWorkspace::new(&model).expect("ws");
    let mut u = vec![0.0; q.len()];
    statics::solve(&model, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("statics");
    for i in [3, 10, 17] {
        let (x, z) = (q[3 * i] + u[3 * i], q[3 * i + 1] + u[3 * i + 1]);
        let p = model.penetration(i, x, z).expect("seabed");
        assert!((p / pen - 1.0).abs() < 1e-6, "node {i}: {p} vs {pen}");
    }
    // The reaction at the pin (the residual there), along the slope (down-slope unit vector).
    let (rx, rz) = (ws.asm.residual[0], ws.asm.residual[1]);
    let along = rx * c - rz * s;
    println!(
        "pipe on a 5° slope: penetration {:.6} m (w·cos α/kD {pen:.6}); pin force along the slope {along:.3} N (w·L·sin α {:.3})",
        model
            .penetration(10, q[30] + u[30], q[31] + u[31])
            .expect("seabed"),
        w * len * s
    );
    assert!((along.abs() / (w * len * s) - 1.0).abs() < 1e-6, "{along}");
}

/// A Workspace rebuilt from the solver memory (the factorisation kept for reuse and the contraction
/// rate its corrections had) holds the same memory and continues bit for bit: the falling pendulum
/// of [`structural_damping_spares_a_rigid_pendulum`] (undamped) is stepped 200 times, and from its
/// State and solver memory after each of steps 100 to 139 (a predictor retry among them, after
/// which no rate is known yet) the rest is stepped again in a fresh Workspace.
#[test]
fn a_restored_solver_memory_continues_bit_for_bit() {
    let (mline, q, pl) = falling_pendulum(20);
    let dm = dynamic(&mline, &pl, &settings(-0.1, None));
    let (steps, dt) = (200, 0.002);
    let mut ws = DynWorkspace::new(&mline).expect("workspace");
    let mut st = initial_state(&dm, &vec![0.0; q.len()], &mut ws);
    let mut saved = Vec::new();
    for step in 1..=steps {
        advance(&dm, &mut st, &mut ws, dt).expect("step");
        if (100..140).contains(&step) {
            let memory = ws.solver_memory().expect("a factorisation is kept");
            saved.push((step, st.clone(), memory));
        }
    }
    let rated = saved.iter().filter(|(_, _, m)| m.rate.is_some()).count();
    assert!(
        rated > 30,
        "rates measured at {rated} of {} steps",
        saved.len()
    );
    let bits = |s: &catena_fe::dynamics::DynState| -> Vec<u64> {
        s.u.iter()
            .chain(&s.v)
            .chain(&s.a)
            .map(|x| x.to_bits())
            .collect()
    };
    for (step, state, memory) in &saved {
        let mut again = state.clone();
        let mut fresh = DynWorkspace::new(&mline).expect("workspace");
        fresh.restore_solver_memory(memory).expect("restores");
        assert_eq!(
            fresh.solver_memory().as_ref(),
            Some(memory),
            "step {step}: the memory as restored"
        );
        for _ in *step..steps {
            advance(&dm, &mut again, &mut fresh, dt).expect("step");
        }
        assert_eq!(bits(&st), bits(&again), "from step {step}");
    }
}

/// A top element's rest length changed at run time (`LineModel::set_top_rest_length` and
/// `DynWorkspace::top_rest_length_changed`, a lay's top element growing with the payout) is the
/// Model built with that length: the same arc lengths, tributary lengths and dead loads to the bit,
/// and 40 steps of a pendulum in water (its top element 0.6 m of 10 m, set from 1 m after the
/// workspace was built) the same bits as the pendulum built with it.
#[test]
fn a_top_rest_length_set_at_run_time_is_the_model_built_with_it() {
    let (l, m, g) = (10.0, 10.0, 9.80665);
    let section =
        |len: f64, h: f64| segment(len, (len / h).round() as usize, 1e9, 1e5, m, m * g, 0.3);
    let line = |top: f64| {
        LineModel::build(&LineSpec {
            segments: vec![section(top, top), section(l - 0.6, 1.0)],
            top: Support::Pinned,
            anchor: Support::Free,
            seabed: None,
            flexjoint: None,
        })
        .expect("model")
    };
    let built = line(0.6);
    let mut changed = line(1.0);
    assert_eq!(changed.elements.len(), built.elements.len());
    let mut ws_changed = DynWorkspace::new(&changed).expect("ws");
    changed.set_top_rest_length(0.6);
    ws_changed.top_rest_length_changed(&changed);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&changed.arc), bits(&built.arc));
    assert_eq!(bits(&changed.tributary), bits(&built.tributary));
    assert_eq!(bits(&changed.dead_load), bits(&built.dead_load));
    // The pendulum lying horizontal at rest, released in water.
    let q: Vec<f64> = (0..built.nodes())
        .flat_map(|i| [built.arc[i], 0.0, 0.0])
        .collect();
    let pl = Placement::new(&q);
    let set = settings(-0.1, Some(hydro(1.0, 0.01, 1.0)));
    let run = |line: &LineModel, ws: &mut DynWorkspace| {
        let dm = dynamic(line, &pl, &set);
        let mut st = initial_state(&dm, &vec![0.0; q.len()], ws);
        for _ in 0..40 {
            advance(&dm, &mut st, ws, 0.05).expect("step");
        }
        st
    };
    let a = run(&changed, &mut ws_changed);
    let b = run(&built, &mut DynWorkspace::new(&built).expect("ws"));
    let tip = 3 * (built.nodes() - 1);
    println!("tip after 2 s: ({:.4}, {:.4}) m", a.u[tip], a.u[tip + 1]);
    assert!(a.u[tip + 1] < -1.0, "the pendulum falls");
    assert_eq!(bits(&a.u), bits(&b.u));
    assert_eq!(bits(&a.v), bits(&b.v));
}
