use super::*;
use crate::beam::Section;
use crate::model::{LineSpec, SeabedContact, Segment, Support};
use catena_seabed::law::{Law, Seabed};
use catena_seabed::linear::LinearSeabed;
use catena_seabed::rq::{RandolphQuiggin, RqParams};

pub(super) const N: usize = 11;

/// A 10 m pipe (D 0.3 m) lying across a mudline at z = 0, its nodes pressed in by 1–25 mm
/// except two clear above it, gently bent, pinned at its left end.
pub(super) fn line(law: Law) -> (LineModel, Placement) {
    let model = LineModel::build(&LineSpec {
        segments: vec![Segment::uniform(
            10.0,
            1.0,
            Section { ea: 1e8, ei: 1e5 },
            500.0,
            100.0,
            0.3,
        )],
        top: Support::Pinned,
        anchor: Support::Free,
        seabed: Some(SeabedContact {
            seabed: Seabed {
                law,
                buoyancy: None,
            },
            mudline_z: 0.0,
            friction: None,
        }),
        flexjoint: None,
    })
    .expect("line");
    let mut q = vec![0.0; 3 * N];
    for i in 0..N {
        let pen = match i {
            3 | 7 => -0.05,
            _ => 0.001 + 0.0024 * i as f64,
        };
        q[3 * i] = i as f64;
        q[3 * i + 1] = 0.15 - pen;
        q[3 * i + 2] = 0.01 * (i as f64 - 5.0);
    }
    (model, Placement::new(&q))
}

/// Each node's history at the start of the dynamics, from its penetration with the line at rest.
pub(super) fn histories_at_rest(model: &LineModel, pl: &Placement) -> Vec<SeabedHistory> {
    let sb = model.seabed.as_ref().expect("seabed");
    (0..N)
        .map(|i| {
            let (z0, _) = penetration(model, pl, &[0.0; 3 * N], &[0.0; 3 * N], i).expect("z");
            sb.seabed.start_of_dynamics(z0.max(0.0))
        })
        .collect()
}

/// Displacements of a few millimetres and velocities of every size and direction, `(u, v)`.
pub(super) fn small_motion() -> (Vec<f64>, Vec<f64>) {
    let u = (0..3 * N)
        .map(|g| 2e-3 * (((g * 7919) % 13) as f64 / 13.0 - 0.5))
        .collect();
    let v = (0..3 * N)
        .map(|g| 0.4 * (((g * 104_729) % 17) as f64 / 17.0 - 0.5))
        .collect();
    (u, v)
}

fn hydro() -> Hydro {
    Hydro {
        water_density: 1025.0,
        cd_normal: 1.2,
        cd_axial: 0.008,
        ca_normal: 1.0,
        current: vec![(-10.0, 0.2), (1.0, 0.6)],
    }
}

/// The residual on the free equations and the tangent's product with `d` (free equations).
#[allow(clippy::too_many_arguments)]
fn evaluate(
    model: &LineModel,
    pl: &Placement,
    hydro: Option<&Hydro>,
    static_pass: bool,
    (u, v): (&[f64], &[f64]),
    scale: TangentScale,
    d: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let mut asm = Assembler::new(model).expect("assembler");
    let mut scratch = LoadScratch::new(N);
    let committed = histories_at_rest(model, pl);
    let pass = if static_pass {
        SeabedPass::Backbone
    } else {
        SeabedPass::Trial {
            committed: &committed,
            anchors: &[],
            dt: 0.1,
            memo: &mut [],
            keep: None,
        }
    };
    let m = LoadModel {
        line: model,
        placement: pl,
        hydro,
        structural_damping: Some(0.01),
    };
    // The loads alone (the structure's tangent has its own test).
    asm.residual.fill(0.0);
    asm.k.clear();
    let at = Iterate {
        u,
        v,
        wave_kin: &[],
    };
    assemble(&m, &at, pass, scale, &mut asm, &mut scratch);
    let mut r = vec![0.0; model.n_eq];
    asm.gather(model, &mut r);
    let mut kd = vec![0.0; model.n_eq];
    asm.k.mul(d, &mut kd);
    (r, kd)
}

/// A direction on the free equations and the same as a global displacement.
fn direction(model: &LineModel, scale: f64) -> (Vec<f64>, Vec<f64>) {
    let mut free = vec![0.0; model.n_eq];
    let mut global = vec![0.0; 3 * N];
    for (g, e) in model.equation.iter().enumerate() {
        if let Some(e) = e {
            let x = scale * (((g * 7919) % 13) as f64 / 13.0 - 0.4);
            free[*e] = x;
            global[g] = x;
        }
    }
    (free, global)
}

/// `(R(+h) − R(−h))/2h` of two residuals.
fn central_difference(rp: &[f64], rm: &[f64], h: f64) -> Vec<f64> {
    rp.iter()
        .zip(rm)
        .map(|(p, m)| (p - m) / (2.0 * h))
        .collect()
}

/// The worst difference (of the largest entry) between `K·d` and the central difference of the
/// residual along `d`, seabed alone, at rest (the structural damping's force is then zero).
fn seabed_fd_worst(model: &LineModel, pl: &Placement, static_pass: bool) -> f64 {
    let (d, dg) = direction(model, 1.0);
    let v = vec![0.0; 3 * N];
    let scale = TangentScale {
        with_k: true,
        k: 1.0,
        c_v: 0.0,
    };
    let (_, kd) = evaluate(
        model,
        pl,
        None,
        static_pass,
        (&vec![0.0; 3 * N], &v),
        scale,
        &d,
    );
    let h = 1e-7;
    let shifted = |s: f64| -> Vec<f64> {
        let u: Vec<f64> = dg.iter().map(|x| s * h * x).collect();
        evaluate(model, pl, None, static_pass, (&u, &v), scale, &d).0
    };
    worst(&kd, &central_difference(&shifted(1.0), &shifted(-1.0), h))
}

fn worst(a: &[f64], b: &[f64]) -> f64 {
    let big = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / big
}

/// `K·d` against the central difference `(R(u + h·d) − R(u − h·d))/2h` with the seabed alone:
/// the statics' backbone (Randolph–Quiggin) and the dynamics' trial (linear law with damping,
/// structural damping on), to 1e-6 of the largest entry. A wrong sign, tributary length or dof
/// fails by orders of magnitude.
#[test]
fn seabed_tangent_matches_finite_differences() {
    let rq = Law::RandolphQuiggin(RandolphQuiggin::new(RqParams::table1()).expect("rq"));
    let linear = Law::Linear(LinearSeabed::new(0.3, 2e5, 3e3).expect("linear"));
    for (name, law, static_pass) in [("rq backbone", rq, true), ("linear trial", linear, false)] {
        let (model, pl) = line(law);
        let w = seabed_fd_worst(&model, &pl, static_pass);
        println!("{name}: worst difference {w:.2e} of the largest entry");
        assert!(w < 1e-6, "{name}: {w}");
    }
}

/// `C·d` (the tangent with `c_v = 1` less the one with `c_v = 0`) against the central difference
/// of the residual in the velocities: drag (normal and axial, in a current), the seabed's damping
/// and the structural damping, to 1e-6 of the largest entry. With `c_v = 0` (the statics) no
/// damping enters the tangent.
#[test]
fn damping_tangent_matches_finite_differences() {
    let linear = Law::Linear(LinearSeabed::new(0.3, 2e5, 3e3).expect("linear"));
    let (model, pl) = line(linear);
    let h_sea = hydro();
    let (d, dg) = direction(&model, 1.0);
    let u = vec![0.0; 3 * N];
    // Velocities of every size and direction (the drag's normal and axial parts both act).
    let v: Vec<f64> = (0..3 * N)
        .map(|g| 0.3 * (((g * 104_729) % 17) as f64 / 17.0 - 0.5))
        .collect();
    let with = |c_v: f64| TangentScale {
        with_k: true,
        k: 1.0,
        c_v,
    };
    let (_, k1) = evaluate(&model, &pl, Some(&h_sea), false, (&u, &v), with(1.0), &d);
    let (_, k0) = evaluate(&model, &pl, Some(&h_sea), false, (&u, &v), with(0.0), &d);
    let cd: Vec<f64> = k1.iter().zip(&k0).map(|(a, b)| a - b).collect();
    let h = 1e-7;
    let shifted = |s: f64| -> Vec<f64> {
        let vs: Vec<f64> = v.iter().zip(&dg).map(|(v, x)| v + s * h * x).collect();
        evaluate(&model, &pl, Some(&h_sea), false, (&u, &vs), with(0.0), &d).0
    };
    let (rp, rm) = (shifted(1.0), shifted(-1.0));
    let fd = central_difference(&rp, &rm, h);
    let w = worst(&cd, &fd);
    println!("damping: worst difference {w:.2e} of the largest entry");
    assert!(w < 1e-6, "{w}");
}

/// Zero motion: at rest in still water (no current, no waves) the hydrodynamics add nothing to
/// the residual, to the bit; and a rigid translation along the flat mudline moves no seabed
/// force.
#[test]
fn still_water_and_a_rigid_slide_add_nothing() {
    let linear = Law::Linear(LinearSeabed::new(0.3, 2e5, 0.0).expect("linear"));
    let (model, pl) = line(linear);
    let still = Hydro {
        current: vec![],
        ..hydro()
    };
    let zero = vec![0.0; 3 * N];
    let d = vec![0.0; model.n_eq];
    let scale = TangentScale {
        with_k: false,
        k: 1.0,
        c_v: 0.0,
    };
    let (r_dry, _) = evaluate(&model, &pl, None, false, (&zero, &zero), scale, &d);
    let (r_wet, _) = evaluate(&model, &pl, Some(&still), false, (&zero, &zero), scale, &d);
    assert_eq!(r_dry, r_wet);
    let mut slide = vec![0.0; 3 * N];
    for i in 0..N {
        slide[3 * i] = 0.37;
    }
    let mut s = LoadScratch::new(N);
    let mut a = Assembler::new(&model).expect("assembler");
    let m = LoadModel {
        line: &model,
        placement: &pl,
        hydro: None,
        structural_damping: None,
    };
    let mut forces = |u: &[f64]| {
        a.residual.fill(0.0);
        let at = Iterate {
            u,
            v: &zero,
            wave_kin: &[],
        };
        assemble(&m, &at, SeabedPass::Backbone, scale, &mut a, &mut s);
        s.seabed_force.clone()
    };
    assert_eq!(forces(&zero), forces(&slide));
}

/// Friction's tangent against central differences in the axial displacements (the coupling
/// through the normal force is left out of the tangent by design, so the directions are
/// axial): nodes in stick (|s| < δ) and in slip (|s| > δ), away from the switch, to 1e-6 of the
/// largest entry; and the force itself: `μN·s/δ` in stick and `μN` in slip, N the node's
/// seabed force over its tributary length.
#[test]
fn friction_tangent_matches_finite_differences() {
    let linear = Law::Linear(LinearSeabed::new(0.3, 2e5, 0.0).expect("linear"));
    let (mut model, pl) = line(linear);
    let f = AxialFriction {
        mu: 0.6,
        mobilisation: 0.01,
    };
    if let Some(sb) = model.seabed.as_mut() {
        sb.friction = Some(f);
    }
    // Anchors: stick (s = ±0.004 m) and slip (s = ±0.03 m) in turn.
    let anchors: Vec<f64> = (0..N)
        .map(|i| pl.base[3 * i] - [0.004, -0.004, 0.03, -0.03][i % 4])
        .collect();
    let committed: Vec<SeabedHistory> = (0..N)
        .map(|_| model.seabed.as_ref().expect("sb").seabed.untouched())
        .collect();
    let zero = vec![0.0; 3 * N];
    let run = |u: &[f64], with_k: bool| friction_pass(&model, &pl, &committed, &anchors, u, with_k);
    // The force, node by node.
    let (asm, scratch) = run(&zero, false);
    for i in 0..N {
        let n = model.tributary[i] * scratch.seabed_force[i];
        let s: f64 = [0.004, -0.004, 0.03, -0.03][i % 4];
        let want = if n <= 0.0 {
            0.0
        } else if s.abs() <= f.mobilisation {
            f.mu * n * s / f.mobilisation
        } else {
            f.mu * n * s.signum()
        };
        // The residual's x entry is the friction alone here (no drag, no elements).
        assert!(
            (asm.residual[3 * i] - want).abs() <= 1e-9 * want.abs().max(1.0),
            "node {i}"
        );
    }
    // The tangent, in the axial directions.
    let mut d = vec![0.0; model.n_eq];
    let mut dg = vec![0.0; 3 * N];
    for (g, e) in model.equation.iter().enumerate() {
        if let (Some(e), 0) = (e, g % 3) {
            let x = 0.5 + ((g * 7919) % 13) as f64 / 13.0;
            d[*e] = x;
            dg[g] = x;
        }
    }
    let (asm, _) = run(&zero, true);
    let mut kd = vec![0.0; model.n_eq];
    asm.k.mul(&d, &mut kd);
    let h = 1e-7;
    let residual = |sgn: f64| {
        let u: Vec<f64> = dg.iter().map(|x| sgn * h * x).collect();
        let (a, _) = run(&u, false);
        let mut r = vec![0.0; model.n_eq];
        a.gather(&model, &mut r);
        r
    };
    let (rp, rm) = (residual(1.0), residual(-1.0));
    let fd = central_difference(&rp, &rm, h);
    let w = worst(&kd, &fd);
    println!("friction: worst difference {w:.2e} of the largest entry");
    assert!(w < 1e-6, "{w}");
    assert!(kd.iter().any(|x| *x != 0.0));
}

/// Friction on a sloping mudline acts along its tangent: on a profile of two slopes (−6° and
/// +4°, the kink between nodes), nodes in stick and in slip, `K·d` against central differences
/// along each node's mudline tangent (the coupling through the normal force is left out of
/// the tangent by design, so the directions keep the penetration), to 1e-6 of the largest
/// entry; and the force: `μN·s/δ` (stick) or `μN` (slip) along the tangent.
#[test]
fn sloped_friction_acts_along_the_mudline_and_its_tangent_matches() {
    let linear = Law::Linear(LinearSeabed::new(0.3, 2e5, 0.0).expect("linear"));
    let (mut model, _) = line(linear);
    let f = AxialFriction {
        mu: 0.6,
        mobilisation: 0.01,
    };
    if let Some(sb) = model.seabed.as_mut() {
        sb.friction = Some(f);
    }
    let (t1, t2) = (6f64.to_radians().tan(), 4f64.to_radians().tan());
    let model = model.with_mudline_profile(vec![(-5.0, 9.5 * t1), (4.5, 0.0), (20.0, 15.5 * t2)]);
    // Each node pressed in by 1–25 mm normal to its slope, at its own mudline.
    let mut q = vec![0.0; 3 * N];
    for i in 0..N {
        let x = i as f64;
        let (zm, m) = model.mudline_at(x);
        let c = 1.0 / (1.0 + m * m).sqrt();
        q[3 * i] = x;
        q[3 * i + 1] = zm + (0.15 - (0.001 + 0.0024 * i as f64)) / c;
        q[3 * i + 2] = m.atan();
    }
    let pl = Placement::new(&q);
    let dist = |i: usize| [0.004, -0.004, 0.03, -0.03][i % 4];
    // Anchors: stick and slip in turn, behind each node along its tangent.
    let anchors: Vec<f64> = (0..N)
        .flat_map(|i| {
            let (tx, tz) = model.mudline_tangent(q[3 * i]);
            [q[3 * i] - dist(i) * tx, q[3 * i + 1] - dist(i) * tz]
        })
        .collect();
    let committed: Vec<SeabedHistory> = (0..N)
        .map(|_| model.seabed.as_ref().expect("sb").seabed.untouched())
        .collect();
    let zero = vec![0.0; 3 * N];
    let run = |u: &[f64], with_k: bool| friction_pass(&model, &pl, &committed, &anchors, u, with_k);
    // The force along the tangent: the residual less the contact's (along the normal).
    let (asm, scratch) = run(&zero, false);
    for i in 0..N {
        let l_p = model.tributary[i] * scratch.seabed_force[i];
        let (tx, tz) = model.mudline_tangent(q[3 * i]);
        let along = asm.residual[3 * i] * tx + asm.residual[3 * i + 1] * tz;
        let want = if dist(i).abs() <= f.mobilisation {
            f.mu * l_p * dist(i) / f.mobilisation
        } else {
            f.mu * l_p * dist(i).signum()
        };
        assert!(l_p > 0.0, "node {i} in contact");
        assert!(
            (along - want).abs() <= 1e-9 * want.abs(),
            "node {i}: {along} vs {want}"
        );
    }
    let mut d = vec![0.0; model.n_eq];
    let mut dg = vec![0.0; 3 * N];
    for i in 0..N {
        let (tx, tz) = model.mudline_tangent(q[3 * i]);
        let x = 0.5 + ((i * 7919) % 13) as f64 / 13.0;
        for (g, c) in [(3 * i, tx), (3 * i + 1, tz)] {
            if let Some(e) = model.equation[g] {
                d[e] = x * c;
                dg[g] = x * c;
            }
        }
    }
    let (asm, _) = run(&zero, true);
    let mut kd = vec![0.0; model.n_eq];
    asm.k.mul(&d, &mut kd);
    let h = 1e-7;
    let residual = |sgn: f64| {
        let u: Vec<f64> = dg.iter().map(|x| sgn * h * x).collect();
        let (a, _) = run(&u, false);
        let mut r = vec![0.0; model.n_eq];
        a.gather(&model, &mut r);
        r
    };
    let (rp, rm) = (residual(1.0), residual(-1.0));
    let fd = central_difference(&rp, &rm, h);
    let w = worst(&kd, &fd);
    println!("friction on a slope: worst difference {w:.2e} of the largest entry");
    assert!(w < 1e-6, "{w}");
}

/// Every load of `model` at `u` (at rest), its seabed in the dynamics' trial pass from the
/// histories `committed` and the friction anchors `anchors`, with the tangent if `with_k`.
fn friction_pass(
    model: &LineModel,
    pl: &Placement,
    committed: &[SeabedHistory],
    anchors: &[f64],
    u: &[f64],
    with_k: bool,
) -> (Assembler, LoadScratch) {
    let mut asm = Assembler::new(model).expect("assembler");
    let mut scratch = LoadScratch::new(N);
    asm.residual.fill(0.0);
    asm.k.clear();
    let m = LoadModel {
        line: model,
        placement: pl,
        hydro: None,
        structural_damping: None,
    };
    let pass = SeabedPass::Trial {
        committed,
        anchors,
        dt: 0.1,
        memo: &mut [],
        keep: None,
    };
    let zero = vec![0.0; 3 * N];
    let at = Iterate {
        u,
        v: &zero,
        wave_kin: &[],
    };
    let scale = TangentScale {
        with_k,
        k: 1.0,
        c_v: 0.0,
    };
    assemble(&m, &at, pass, scale, &mut asm, &mut scratch);
    (asm, scratch)
}

/// The attached bodies' drag damping against central differences in the velocities (bodies
/// with and without drag area, in a current), to 1e-6 of the largest entry; and still water at
/// rest adds nothing.
#[test]
fn attachment_drag_tangent_matches_finite_differences() {
    use crate::model::Attachment;
    let linear = Law::Linear(LinearSeabed::new(0.3, 2e5, 0.0).expect("linear"));
    let (model, pl) = line(linear);
    let body = |drag_area: f64| Attachment {
        node: 0,
        mass: 50.0,
        weight: -200.0,
        drag_area,
        added_mass: 30.0,
    };
    let model = model.with_attachments(&[(2.0, body(0.8)), (5.2, body(0.0)), (9.0, body(1.5))]);
    let h_sea = hydro();
    let committed: Vec<SeabedHistory> = (0..N)
        .map(|_| model.seabed.as_ref().expect("sb").seabed.untouched())
        .collect();
    let u = vec![0.0; 3 * N];
    let v: Vec<f64> = (0..3 * N)
        .map(|g| 0.4 * (((g * 104_729) % 17) as f64 / 17.0 - 0.5))
        .collect();
    let run = |v: &[f64], c_v: f64, hydro: &Hydro| {
        let mut asm = Assembler::new(&model).expect("assembler");
        let mut scratch = LoadScratch::new(N);
        asm.residual.fill(0.0);
        asm.k.clear();
        let m = LoadModel {
            line: &model,
            placement: &pl,
            hydro: Some(hydro),
            structural_damping: None,
        };
        let pass = SeabedPass::Trial {
            committed: &committed,
            anchors: &[],
            dt: 0.1,
            memo: &mut [],
            keep: None,
        };
        let at = Iterate {
            u: &u,
            v,
            wave_kin: &[],
        };
        let scale = TangentScale {
            with_k: true,
            k: 1.0,
            c_v,
        };
        assemble(&m, &at, pass, scale, &mut asm, &mut scratch);
        asm
    };
    let (d, dg) = direction(&model, 1.0);
    let (a1, a0) = (run(&v, 1.0, &h_sea), run(&v, 0.0, &h_sea));
    let (mut k1, mut k0) = (vec![0.0; model.n_eq], vec![0.0; model.n_eq]);
    a1.k.mul(&d, &mut k1);
    a0.k.mul(&d, &mut k0);
    let cd: Vec<f64> = k1.iter().zip(&k0).map(|(a, b)| a - b).collect();
    let h = 1e-7;
    let residual = |sgn: f64| {
        let vs: Vec<f64> = v.iter().zip(&dg).map(|(v, x)| v + sgn * h * x).collect();
        let a = run(&vs, 0.0, &h_sea);
        let mut r = vec![0.0; model.n_eq];
        a.gather(&model, &mut r);
        r
    };
    let (rp, rm) = (residual(1.0), residual(-1.0));
    let fd = central_difference(&rp, &rm, h);
    let w = worst(&cd, &fd);
    println!("attachment drag: worst difference {w:.2e} of the largest entry");
    assert!(w < 1e-6, "{w}");
    // Still water, at rest: no force from the bodies.
    let still = Hydro {
        current: vec![],
        ..hydro()
    };
    let zero = vec![0.0; 3 * N];
    let a = run(&zero, 0.0, &still);
    let plain = {
        let m2 = LoadModel {
            line: &model,
            placement: &pl,
            hydro: None,
            structural_damping: None,
        };
        let mut asm = Assembler::new(&model).expect("assembler");
        let mut scratch = LoadScratch::new(N);
        asm.residual.fill(0.0);
        let pass = SeabedPass::Trial {
            committed: &committed,
            anchors: &[],
            dt: 0.1,
            memo: &mut [],
            keep: None,
        };
        let at = Iterate {
            u: &u,
            v: &zero,
            wave_kin: &[],
        };
        let scale = TangentScale {
            with_k: false,
            k: 1.0,
            c_v: 0.0,
        };
        assemble(&m2, &at, pass, scale, &mut asm, &mut scratch);
        asm.residual
    };
    assert_eq!(a.residual, plain);
}

/// On a sloping mudline the contact acts along its normal: `K·d` against central differences
/// in every direction (x and z coupled through the normal), the statics' backbone (R–Q) and the
/// dynamics' trial (linear with damping), nodes on two slopes either side of a kink (no node
/// at the kink), to 1e-6 of the largest entry.
#[test]
fn sloped_contact_tangent_matches_finite_differences() {
    let rq = Law::RandolphQuiggin(RandolphQuiggin::new(RqParams::table1()).expect("rq"));
    let linear = Law::Linear(LinearSeabed::new(0.3, 2e5, 3e3).expect("linear"));
    for (name, law, static_pass) in [("rq backbone", rq, true), ("linear trial", linear, false)] {
        let (model, pl) = line(law);
        let model = model.with_mudline_profile(vec![(-5.0, 0.004), (4.5, 0.0), (20.0, -0.006)]);
        let w = seabed_fd_worst(&model, &pl, static_pass);
        println!("{name} on a slope: worst difference {w:.2e} of the largest entry");
        assert!(w < 1e-6, "{name}: {w}");
    }
}

/// An attached body in waves: its drag acts on the water's velocity relative to it,
/// `f = ½ρ·CdA·|w − v|·(w − v)`. With the line's own drag, added mass and current off, a body at
/// rest in a wave particle velocity `w` feels exactly `½ρ·CdA·|w|·w` (to 1e-12), and a body moving
/// with the water feels nothing; nodes without a body feel nothing either.
#[test]
fn a_body_in_waves_is_dragged_by_the_water() {
    use crate::model::Attachment;
    use crate::waves::Kinematics;
    let linear = Law::Linear(LinearSeabed::new(0.3, 2e5, 0.0).expect("linear"));
    let (model, pl) = line(linear);
    let body = Attachment {
        node: 0,
        mass: 50.0,
        weight: -200.0,
        drag_area: 1.3,
        added_mass: 0.0,
    };
    let model = model.with_attachments(&[(5.0, body)]);
    let i = model.attachments[0].node;
    let calm = Hydro {
        water_density: 1025.0,
        cd_normal: 0.0,
        cd_axial: 0.0,
        ca_normal: 0.0,
        current: vec![],
    };
    let committed: Vec<SeabedHistory> = (0..N)
        .map(|_| model.seabed.as_ref().expect("sb").seabed.untouched())
        .collect();
    let w = [0.7, -0.4];
    let kin = vec![
        Some(Kinematics {
            velocity: w,
            acceleration: [0.0; 2],
        });
        N
    ];
    let u = vec![0.0; 3 * N];
    let forces = |v: &[f64], wave_kin: &[Option<Kinematics>]| {
        let mut asm = Assembler::new(&model).expect("assembler");
        let mut scratch = LoadScratch::new(N);
        asm.residual.fill(0.0);
        asm.k.clear();
        let m = LoadModel {
            line: &model,
            placement: &pl,
            hydro: Some(&calm),
            structural_damping: None,
        };
        let pass = SeabedPass::Trial {
            committed: &committed,
            anchors: &[],
            dt: 0.1,
            memo: &mut [],
            keep: None,
        };
        let at = Iterate { u: &u, v, wave_kin };
        let scale = TangentScale {
            with_k: false,
            k: 1.0,
            c_v: 0.0,
        };
        assemble(&m, &at, pass, scale, &mut asm, &mut scratch);
        asm.residual.clone()
    };
    let rest = vec![0.0; 3 * N];
    let (still, waves) = (forces(&rest, &[]), forces(&rest, &kin));
    let c = 0.5 * 1025.0 * 1.3;
    let speed = (w[0] * w[0] + w[1] * w[1]).sqrt();
    for k in 0..3 * N {
        let expected = if k == 3 * i {
            -c * speed * w[0]
        } else if k == 3 * i + 1 {
            -c * speed * w[1]
        } else {
            0.0
        };
        let got = waves[k] - still[k];
        assert!(
            (got - expected).abs() <= 1e-12 * c,
            "dof {k}: {got} against {expected}"
        );
    }
    // Moving with the water: no drag.
    let mut with = vec![0.0; 3 * N];
    (with[3 * i], with[3 * i + 1]) = (w[0], w[1]);
    let along = forces(&with, &kin);
    assert!((along[3 * i] - still[3 * i]).abs() <= 1e-12 * c);
    assert!((along[3 * i + 1] - still[3 * i + 1]).abs() <= 1e-12 * c);
}

/// Every load over the two parts of the line ([`assemble_part`] on [`Part::halves`]) gives each
/// part's own nodes the whole line's residual, tangent columns, seabed forces and kept trial
/// histories to the bit, at every boundary: the Randolph–Quiggin trial with friction (stick and
/// slip), drag in a current with its damping, structural damping and attached bodies' drag; and a
/// part evaluates no trial history outside its nodes.
#[test]
fn parts_of_the_line_get_the_whole_loads_to_the_bit() {
    use crate::model::Attachment;
    let rq = Law::RandolphQuiggin(RandolphQuiggin::new(RqParams::table1()).expect("rq"));
    let (mut model, pl) = line(rq);
    if let Some(sb) = model.seabed.as_mut() {
        sb.friction = Some(AxialFriction {
            mu: 0.6,
            mobilisation: 0.01,
        });
    }
    let body = |drag_area: f64| Attachment {
        node: 0,
        mass: 50.0,
        weight: -200.0,
        drag_area,
        added_mass: 30.0,
    };
    let model = model.with_attachments(&[(2.0, body(0.8)), (6.0, body(1.5))]);
    let sb = model.seabed.as_ref().expect("seabed");
    let committed = histories_at_rest(&model, &pl);
    let anchors: Vec<f64> = (0..N)
        .map(|i| pl.base[3 * i] - [0.004, -0.004, 0.03, -0.03][i % 4])
        .collect();
    let (u, v) = small_motion();
    let h = hydro();
    let m = LoadModel {
        line: &model,
        placement: &pl,
        hydro: Some(&h),
        structural_damping: Some(0.01),
    };
    let at = Iterate {
        u: &u,
        v: &v,
        wave_kin: &[],
    };
    let scale = TangentScale {
        with_k: true,
        k: 0.9,
        c_v: 40.0,
    };
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    let run = |part: &Part| {
        let mut asm = Assembler::new(&model).expect("assembler");
        let mut scratch = LoadScratch::new(N);
        asm.residual.fill(0.0);
        asm.k.clear();
        let untouched = sb.seabed.untouched();
        let mut kept = vec![untouched; N];
        let pass = SeabedPass::Trial {
            committed: &committed,
            anchors: &anchors,
            dt: 0.1,
            memo: &mut [],
            keep: Some(&mut kept),
        };
        assemble_part(&m, &at, pass, scale, (&mut asm, &mut scratch), part);
        (asm, scratch, kept)
    };
    let (whole, ws, wkept) = run(&Part::whole(&model));
    assert!(wkept.iter().any(|h| *h != sb.seabed.untouched()));
    for k in 0..N - 1 {
        for part in Part::halves(&model, k) {
            let (asm, scratch, kept) = run(&part);
            let dofs = 3 * part.nodes.start..3 * part.nodes.end;
            assert_eq!(
                bits(&asm.residual[dofs.clone()]),
                bits(&whole.residual[dofs.clone()]),
                "boundary {k}, {part:?}"
            );
            let eq: Vec<usize> = model.equation[dofs].iter().filter_map(|e| *e).collect();
            let cols = eq[0]..eq[eq.len() - 1] + 1;
            assert_eq!(
                bits(&asm.k.values[asm.k.column_slots(cols.clone())]),
                bits(&whole.k.values[whole.k.column_slots(cols)]),
                "boundary {k}, {part:?}: tangent"
            );
            let own = part.nodes.clone();
            assert_eq!(
                bits(&scratch.seabed_force[own.clone()]),
                bits(&ws.seabed_force[own.clone()])
            );
            assert_eq!(kept[own.clone()], wkept[own.clone()]);
            for i in (0..N).filter(|i| !own.contains(i)) {
                assert_eq!(kept[i], sb.seabed.untouched(), "node {i} outside {part:?}");
            }
        }
    }
}
