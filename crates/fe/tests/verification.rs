//! Verification of the static solver against the analytical anchors of `docs/cases.md` §5.
//! Each test states its source and tolerance.

use catena_fe::analytical::{
    touchdown_moment, ElasticTouchdownCatenary, SlopedTouchdownCatenary, TouchdownCatenary,
};
use catena_fe::beam::Section;
use catena_fe::model::{LineModel, LineSpec, SeabedContact, Segment, Support};
use catena_fe::statics::{
    catenary_seed, line_results, solve, static_embedment, summarise, EndPositions, LineResults,
    Placement, StaticOptions, StaticSummary, StaticWorkspace,
};
use catena_seabed::law::{Law, Seabed};
use catena_seabed::{LinearSeabed, RandolphQuiggin, RqParams, SoilBuoyancy};

const W: f64 = 1010.0;
const OD: f64 = 0.228;
const EI: f64 = 17.69e6;
const EA: f64 = 3.395e9;

fn linear(k: f64) -> Seabed {
    Seabed {
        law: Law::Linear(LinearSeabed::new(OD, k, 0.0).expect("valid")),
        buoyancy: None,
    }
}

fn scr(seabed: Seabed, ea: f64, ei: f64, tdz_element: f64) -> LineModel {
    let seg = |length, element_length| {
        Segment::uniform(length, element_length, Section { ea, ei }, W, 144.8, OD)
    };
    LineModel::build(&LineSpec {
        segments: vec![seg(1050.0, 5.0), seg(300.0, tdz_element), seg(250.0, 5.0)],
        top: Support::Pinned,
        anchor: Support::Pinned,
        seabed: Some(SeabedContact {
            seabed,
            mudline_z: 0.0,
            friction: None,
        }),
        flexjoint: None,
    })
    .expect("model")
}

struct Solved {
    r: LineResults,
    s: StaticSummary,
    z_contact: f64,
}

fn solve_scr(model: &LineModel) -> Solved {
    let emb = static_embedment(model, W).expect("embedment");
    let z_contact = 0.5 * OD - emb;
    let ends = EndPositions {
        top: (933.79, 980.0),
        anchor: (0.0, z_contact),
    };
    let q = catenary_seed(model, &ends).expect("seed");
    let pl = Placement::new(&q);
    let mut u = vec![0.0; q.len()];
    let mut ws = StaticWorkspace::new(model).expect("workspace");
    let rep = solve(model, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("converges");
    assert!(rep.residual <= 1e-8, "relative residual {}", rep.residual);
    let sb = model.seabed.expect("seabed");
    let r = line_results(model, &pl, &u, &mut ws, |_, p| {
        sb.seabed.backbone(p).total()
    });
    let n3 = ws.asm.residual.len();
    let s = summarise(
        &model.arc,
        &r,
        [
            (ws.asm.residual[0], ws.asm.residual[1]),
            (ws.asm.residual[n3 - 3], ws.asm.residual[n3 - 2]),
        ],
    );
    Solved { r, s, z_contact }
}

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

/// cases.md §5: the inextensible catenary against the FE with a very small EI (1 kN·m²), very
/// large EA (3.4e10 N) and a very stiff seabed (1e8 N/m/m²): top tension, H and touchdown arc length
/// within 0.2 %.
#[test]
fn inextensible_catenary_small_ei() {
    let m = scr(linear(1e8), EA * 10.0, 1e3, 0.5);
    let f = solve_scr(&m);
    let c = TouchdownCatenary::solve(W, 933.79, 980.0 - f.z_contact, 1600.0).expect("catenary");
    println!(
        "inextensible: T_top FE {:.1} / analytic {:.1} N; H {:.1} / {:.1} N; TDP {:.3} / {:.3} m",
        f.s.top_tension,
        c.top_tension(),
        f.s.horizontal_tension,
        c.horizontal_tension(),
        f.s.touchdown_arc.unwrap_or(0.0),
        c.suspended
    );
    assert!(
        rel(f.s.top_tension, c.top_tension()) < 2e-3,
        "{} {}",
        f.s.top_tension,
        c.top_tension()
    );
    assert!(rel(f.s.horizontal_tension, c.horizontal_tension()) < 2e-3);
    let tdp = f.s.touchdown_arc.expect("touches down");
    assert!(rel(tdp, c.suspended) < 2e-3, "{tdp} {}", c.suspended);
}

/// A heavy chain on a sloping seabed (issue 28): the SCR of the test above (EI 1 kN·m², EA ×10, a
/// seabed of 1e8 N/m/m²) on a mudline rising at 3° towards the anchor, against the inextensible
/// catenary tangent to the slope ([`SlopedTouchdownCatenary`]): top tension, H at the top, the
/// touchdown's arc length (shifted along the line by the slope: 1220.0 m against the flat 1167.7 m)
/// and the anchor's tension (the touchdown's plus the laid line's down-slope weight) within 0.1 %
/// (measured: 0.02 % at most). The static seed is the same sloped catenary, so Newton takes 5
/// iterations. With the contact vertical instead of normal to the slope the anchor tension is 8 %
/// low (the seabed then carries the laid line's down-slope weight).
#[test]
fn heavy_chain_on_a_slope_against_the_sloped_catenary() {
    let alpha = 3f64.to_radians();
    let (k, od) = (1e8, OD);
    let m = scr(linear(k), EA * 10.0, 1e3, 0.5).with_mudline_profile(vec![
        (-200.0, 200.0 * alpha.tan()),
        (2000.0, -2000.0 * alpha.tan()),
    ]);
    // The anchor's centre on the slope: D/2 less the normal penetration w·cos α/(kD), along the
    // normal.
    let pen = W * alpha.cos() / (k * od);
    let z_contact = (0.5 * od - pen) / alpha.cos();
    let ends = EndPositions {
        top: (933.79, 980.0),
        anchor: (0.0, z_contact),
    };
    let q = catenary_seed(&m, &ends).expect("seed");
    let pl = Placement::new(&q);
    let mut u = vec![0.0; q.len()];
    let mut ws = StaticWorkspace::new(&m).expect("workspace");
    let rep = solve(&m, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("converges");
    let sb = m.seabed.expect("seabed");
    let r = line_results(&m, &pl, &u, &mut ws, |_, p| sb.seabed.backbone(p).total());
    let n3 = ws.asm.residual.len();
    let (ax, az) = (ws.asm.residual[n3 - 3], ws.asm.residual[n3 - 2]);
    let s = summarise(
        &m.arc,
        &r,
        [(ws.asm.residual[0], ws.asm.residual[1]), (ax, az)],
    );
    let c = SlopedTouchdownCatenary::solve(W, alpha, 933.79, 980.0 - z_contact, 1600.0)
        .expect("catenary");
    let flat = TouchdownCatenary::solve(W, 933.79, 980.0 - z_contact, 1600.0).expect("flat");
    let anchor = ax.hypot(az);
    let tdp = s.touchdown_arc.expect("touches down");
    println!(
        "chain on a 3° slope ({} Newton iterations): T_top FE {:.1} / analytic {:.1} N; H {:.1} / {:.1} N; TDP {tdp:.3} / {:.3} m (flat {:.3} m); anchor {anchor:.1} / {:.1} N",
        rep.iterations,
        s.top_tension,
        c.top_tension(),
        s.horizontal_tension,
        c.horizontal_tension(),
        c.suspended,
        flat.suspended,
        c.anchor_tension()
    );
    assert!(rel(s.top_tension, c.top_tension()) < 1e-3);
    assert!(rel(s.horizontal_tension, c.horizontal_tension()) < 1e-3);
    assert!(rel(tdp, c.suspended) < 1e-3, "{tdp} {}", c.suspended);
    assert!(rel(anchor, c.anchor_tension()) < 1e-3, "{anchor}");
    assert!(
        tdp - flat.suspended > 30.0,
        "the slope shifts the touchdown"
    );
}

/// cases.md §5: the elastic catenary (Irvine, grounded part stretched by H/EA) against the FE with
/// the SCR's EA, a very small EI and a very stiff seabed: top tension, H and touchdown within 0.2 %.
/// The touchdown arc is compared in unstretched arc length.
#[test]
fn elastic_catenary_small_ei() {
    let m = scr(linear(1e8), EA, 1e3, 0.5);
    let f = solve_scr(&m);
    let c = ElasticTouchdownCatenary::solve(W, EA, 933.79, 980.0 - f.z_contact, 1600.0)
        .expect("catenary");
    println!(
        "elastic: T_top FE {:.1} / analytic {:.1} N; H {:.1} / {:.1} N; TDP {:.3} / {:.3} m",
        f.s.top_tension,
        c.top_tension,
        f.s.horizontal_tension,
        c.h_tension,
        f.s.touchdown_arc.unwrap_or(0.0),
        c.suspended
    );
    assert!(
        rel(f.s.top_tension, c.top_tension) < 2e-3,
        "{} {}",
        f.s.top_tension,
        c.top_tension
    );
    assert!(
        rel(f.s.horizontal_tension, c.h_tension) < 2e-3,
        "{} {}",
        f.s.horizontal_tension,
        c.h_tension
    );
    let tdp = f.s.touchdown_arc.expect("touches down");
    assert!(rel(tdp, c.suspended) < 2e-3, "{tdp} {}", c.suspended);
}

/// cases.md §5: the touchdown boundary-layer moment `M_TDP = (EI w/H)/(p + 1/2)` on a linear
/// seabed, within 3 %, for k = 100, 1000, 10000 kN/m/m² (H from the FE). Also the far-field
/// embedment `w/k` (per unit length, `k·D`), to 1e-6 relative, and the maximum sag moment lying a few
/// λ above touchdown and slightly below `EI·w/H`.
#[test]
fn touchdown_moment_and_far_field_embedment() {
    for k in [100e3, 1000e3, 10000e3] {
        let m = scr(linear(k), EA, EI, 0.5);
        let f = solve_scr(&m);
        let h = f.s.horizontal_tension;
        let expect = touchdown_moment(EI, W, h, k * OD);
        let got = -f.s.touchdown_moment.expect("touchdown");
        println!(
            "k {k}: M_TDP FE {got:.1} / formula {expect:.1} N·m ({:+.2} %); embedment {:.6e} / {:.6e} m; max sag {:.1} N·m at {:.2} m, TDP {:.2} m, λ {:.2} m",
            100.0 * (got / expect - 1.0),
            f.r.penetration[f.r.penetration.len() * 9 / 10],
            W / (k * OD),
            f.s.max_sag_moment.0,
            f.s.max_sag_moment.1,
            f.s.touchdown_arc.unwrap_or(0.0),
            (EI / h).sqrt()
        );
        assert!(rel(got, expect) < 0.03, "k {k}: M_TDP {got} vs {expect}");
        let n = f.r.penetration.len();
        let far = f.r.penetration[n * 9 / 10];
        assert!(rel(far, W / (k * OD)) < 1e-6, "k {k}: embedment {far}");
        let (m_sag, s_sag) = f.s.max_sag_moment;
        let lambda = (EI / h).sqrt();
        let tdp = f.s.touchdown_arc.expect("touchdown");
        assert!(
            -m_sag < EI * W / h && -m_sag > 0.9 * EI * W / h,
            "k {k}: {m_sag}"
        );
        assert!(
            tdp - s_sag > 1.0 * lambda && tdp - s_sag < 8.0 * lambda,
            "k {k}: {s_sag} {tdp}"
        );
    }
}

/// cases.md §5: on the Randolph–Quiggin seabed (Table 4, su0 = 1 kPa, fsuc = 0.2, f_b = 1.5, soil
/// 1500 kg/m³) the far-field embedment equals the law's own static solution: backbone plus buoyancy
/// equals the submerged weight (to 1e-6 relative).
#[test]
fn rq_far_field_embedment_is_the_laws_static_solution() {
    let p = RqParams {
        diameter: OD,
        su0: 1000.0,
        su_gradient: 1300.0,
        a: 6.0,
        b: 0.25,
        k_max: 200.0,
        f_suc: 0.2,
        lambda_suc: 1.0,
        lambda_rep: 0.3,
        liftoff_smoothing: false,
        degradation: None,
        rate_suction: None,
    };
    let seabed = Seabed {
        law: Law::RandolphQuiggin(RandolphQuiggin::new(p).expect("valid")),
        buoyancy: Some(SoilBuoyancy::new(OD, 1.5, 1500.0, 1025.0).expect("valid")),
    };
    let m = scr(seabed, EA, EI, 0.5);
    let f = solve_scr(&m);
    let n = f.r.penetration.len();
    let far = f.r.penetration[n * 9 / 10];
    let force = seabed.backbone(far).total();
    println!("R-Q far field: z = {far:.6} m, P + F_b = {force:.6} N/m (w = {W})");
    assert!(rel(force, W) < 1e-6, "F(z_far) = {force} at z = {far}");
}

fn cantilever(n: usize, l: f64, ei: f64) -> LineModel {
    LineModel::build(&LineSpec {
        segments: vec![Segment::uniform(
            l,
            l / n as f64,
            Section { ea: ei * 1e6, ei },
            0.0,
            0.0,
            0.1,
        )],
        top: Support::Fixed,
        anchor: Support::Free,
        seabed: None,
        flexjoint: None,
    })
    .expect("model")
}

/// Solves a cantilever along +x (root at node 0) with extra tip loads `(Fx, Fz, M)`.
fn solve_cantilever(m: &mut LineModel, tip: (f64, f64, f64)) -> Vec<f64> {
    let n = m.nodes();
    let q: Vec<f64> = (0..n).flat_map(|i| [m.arc[i], 0.0, 0.0]).collect();
    let g = 3 * (n - 1);
    m.dead_load[g] += tip.0;
    m.dead_load[g + 1] += tip.1;
    m.dead_load[g + 2] += tip.2;
    let pl = Placement::new(&q);
    let mut u = vec![0.0; q.len()];
    let mut ws = StaticWorkspace::new(m).expect("workspace");
    solve(m, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("converges");
    pl.absolute(&u)
}

/// cases.md §5: a cantilever under an end moment M rolls into a circle of radius EI/M; with
/// M = πEI/L the tip is at (0, 2L/π) with rotation π, with M = 2πEI/L it returns to the root.
/// 40 elements; tolerance 0.2 % of L on positions, 1e-6 on the rotation (which is exact).
#[test]
fn cantilever_end_moment_rolls_into_a_circle() {
    let (l, ei) = (10.0, 1.0e4);
    for (mult, tip) in [
        (1.0, (0.0, 2.0 * l / std::f64::consts::PI)),
        (2.0, (0.0, 0.0)),
    ] {
        let mut m = cantilever(40, l, ei);
        let mom = mult * std::f64::consts::PI * ei / l;
        let q = solve_cantilever(&mut m, (0.0, 0.0, mom));
        let g = q.len() - 3;
        println!(
            "end moment {mult}πEI/L: tip ({:.5}, {:.5}) m, expected ({:.5}, {:.5}); rotation {:.8}",
            q[g],
            q[g + 1],
            tip.0,
            tip.1,
            q[g + 2]
        );
        assert!(
            (q[g] - tip.0).abs() < 2e-3 * l,
            "M = {mult}πEI/L: x {}",
            q[g]
        );
        assert!(
            (q[g + 1] - tip.1).abs() < 2e-3 * l,
            "M = {mult}πEI/L: z {}",
            q[g + 1]
        );
        assert!(
            (q[g + 2] - mult * std::f64::consts::PI).abs() < 1e-6,
            "rotation {}",
            q[g + 2]
        );
    }
}

/// cases.md §5: the tip-load elastica (inextensible), `(u/L, v/L, tip rotation)` for PL²/EI = 1, 2,
/// 5, 10, with 40 elements: to 2e-3 on u/L and v/L, 2e-3 rad on the rotation.
#[test]
fn tip_load_elastica_table() {
    let (l, ei) = (10.0, 1.0e4);
    let table = [
        (1.0, 0.05643, 0.30172, 0.46135),
        (2.0, 0.16064, 0.49346, 0.78175),
        (5.0, 0.38763, 0.71379, 1.21537),
        (10.0, 0.55500, 0.81061, 1.43029),
    ];
    for (pl2, u_l, v_l, rot) in table {
        let mut m = cantilever(40, l, ei);
        let p = pl2 * ei / (l * l);
        let q = solve_cantilever(&mut m, (0.0, -p, 0.0));
        let g = q.len() - 3;
        let (u, v, th) = ((l - q[g]) / l, -q[g + 1] / l, -q[g + 2]);
        println!("elastica PL²/EI {pl2}: u/L {u:.5} ({u_l}), v/L {v:.5} ({v_l}), rotation {th:.5} ({rot})");
        assert!((u - u_l).abs() < 2e-3, "PL²/EI {pl2}: u/L {u} vs {u_l}");
        assert!((v - v_l).abs() < 2e-3, "PL²/EI {pl2}: v/L {v} vs {v_l}");
        assert!(
            (th - rot).abs() < 2e-3,
            "PL²/EI {pl2}: rotation {th} vs {rot}"
        );
    }
}

/// Mesh convergence of the maximum sag moment near touchdown (k = 100 kN/m/m²): touchdown-zone
/// elements 2, 1, 0.5, 0.25 m. The observed order from the three finest, `p = log2(e1/e2)`, must
/// exceed 1.5 (the element is cubic in bending; nodal moments from element-end values converge at
/// second order). Results are recorded in `validation/static-scr.md`.
#[test]
fn mesh_convergence_of_touchdown_moment() {
    let sizes = [2.0, 1.0, 0.5, 0.25];
    let mut m_max = Vec::new();
    for &h in &sizes {
        let f = solve_scr(&scr(linear(100e3), EA, EI, h));
        m_max.push(f.s.max_sag_moment.0);
        println!(
            "TDZ element {h} m: max sag moment {:.3} N·m at {:.2} m, M_TDP {:.3}",
            f.s.max_sag_moment.0,
            f.s.max_sag_moment.1,
            f.s.touchdown_moment.unwrap_or(0.0)
        );
    }
    let e1 = m_max[1] - m_max[2];
    let e2 = m_max[2] - m_max[3];
    let order = (e1 / e2).abs().log2();
    let richardson = m_max[3] + (m_max[3] - m_max[2]) / (2f64.powf(order) - 1.0);
    println!("observed order {order:.2}; Richardson extrapolation {richardson:.3} N·m");
    assert!(order > 1.5, "order {order}");
    assert!(rel(m_max[3], richardson) < 1e-3);
}
