use super::*;
use crate::test_rng::uniform;

/// The kernel against its derivation written as matrix products (nalgebra): with
/// `B = [r; e3 − q/L; e6 − q/L]` (3×6) and `K_l = diag(EA/L0, EI/L0·[[4, 2], [2, 4]])`,
/// `f = Bᵀ (N, M1, M2)` and `K = Bᵀ K_l B + (N/L)·q qᵀ + ((M1 + M2)/L²)·(r qᵀ + q rᵀ)`, to 1e-12
/// of the largest entry, at several deformed states (a hand expansion that drops or swaps a term
/// fails).
#[test]
fn kernel_is_its_matrix_derivation() {
    use nalgebra::{Matrix3, RowSVector, SMatrix, Vector3};
    for (d, l0) in [
        (deformed(), 4.0),
        ([0.0, 0.0, 0.1, 3.0, 0.2, -0.3], 3.1),
        ([1.0, 2.0, -2.9, 0.5, 7.0, 2.0], 5.5),
    ] {
        let (dx, dz) = (d[3] - d[0], d[4] - d[1]);
        let l = (dx * dx + dz * dz).sqrt();
        let (c, s) = (dx / l, dz / l);
        let r = RowSVector::<f64, 6>::from_row_slice(&[-c, -s, 0.0, c, s, 0.0]);
        let q = RowSVector::<f64, 6>::from_row_slice(&[s, -c, 0.0, -s, c, 0.0]);
        let mut e3 = RowSVector::<f64, 6>::zeros();
        e3[2] = 1.0;
        let mut e6 = RowSVector::<f64, 6>::zeros();
        e6[5] = 1.0;
        let b = SMatrix::<f64, 3, 6>::from_rows(&[r, e3 - q / l, e6 - q / l]);
        let (ka, kb) = (SEC.ea / l0, SEC.ei / l0);
        let kl = Matrix3::new(
            ka,
            0.0,
            0.0,
            0.0,
            4.0 * kb,
            2.0 * kb,
            0.0,
            2.0 * kb,
            4.0 * kb,
        );
        let beta = dz.atan2(dx);
        let t = Vector3::new(l - l0, wrap(d[2] - beta), wrap(d[5] - beta));
        let basic = kl * t;
        let f = b.transpose() * basic;
        let (n, m1, m2) = (basic[0], basic[1], basic[2]);
        let k = b.transpose() * kl * b
            + (n / l) * q.transpose() * q
            + ((m1 + m2) / (l * l)) * (r.transpose() * q + q.transpose() * r);
        let got = corotational_beam(&d, l0, &SEC, true);
        let big = k.amax();
        for i in 0..6 {
            assert!((got.force[i] - f[i]).abs() <= 1e-12 * f.amax(), "f[{i}]");
            for j in 0..6 {
                let diff = (got.stiffness[i][j] - k[(i, j)]).abs();
                assert!(
                    diff <= 1e-12 * big,
                    "K[{i}][{j}]: {} vs {}",
                    got.stiffness[i][j],
                    k[(i, j)]
                );
            }
        }
    }
}

const SEC: Section = Section {
    ea: 3.0e9,
    ei: 1.7e7,
};

fn deformed() -> [f64; 6] {
    [0.3, -0.2, 0.35, 4.1, 1.4, 0.52]
}

/// The tangent equals a central finite difference of the force (relative 1e-6 of the largest entry).
#[test]
fn tangent_matches_finite_difference() {
    for (d, l0) in [
        (deformed(), 4.0),
        ([0.0, 0.0, -1.9, -0.5, -4.9, -1.7], 5.05),
        ([1.0, 2.0, 3.1, -2.9, 2.3, -3.05], 3.9),
    ] {
        let k = corotational_beam(&d, l0, &SEC, true).stiffness;
        let scale = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for j in 0..6 {
            let h = 1e-7;
            let mut dp = d;
            let mut dm = d;
            dp[j] += h;
            dm[j] -= h;
            let fp = corotational_beam(&dp, l0, &SEC, false).force;
            let fm = corotational_beam(&dm, l0, &SEC, false).force;
            for i in 0..6 {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                assert!(
                    (fd - k[i][j]).abs() <= 1e-6 * scale,
                    "K[{i}][{j}]: analytic {} FD {fd}",
                    k[i][j]
                );
            }
        }
    }
}

/// A rigid-body motion (translation and a finite rotation, past ±π) of a stress-free element gives
/// zero force, and of a deformed element gives the same N, M1, M2.
#[test]
fn rigid_body_motion_gives_no_force() {
    let l0 = 4.0;
    for angle in [0.0, 0.7, 2.9, -3.1, 10.0] {
        let (c, s) = (f64::cos(angle), f64::sin(angle));
        let d = [1.5, -2.0, angle, 1.5 + l0 * c, -2.0 + l0 * s, angle];
        let r = corotational_beam(&d, l0, &SEC, false);
        for f in r.force {
            assert!(f.abs() < 1e-6, "{angle}: {:?}", r.force);
        }
    }
    let d0 = deformed();
    let r0 = corotational_beam(&d0, 4.2, &SEC, false);
    let (a, tx, tz) = (2.5f64, 7.0, -3.0);
    let rot = |x: f64, z: f64| {
        (
            a.cos() * x - a.sin() * z + tx,
            a.sin() * x + a.cos() * z + tz,
        )
    };
    let (x1, z1) = rot(d0[0], d0[1]);
    let (x2, z2) = rot(d0[3], d0[4]);
    let d1 = [x1, z1, d0[2] + a, x2, z2, d0[5] + a];
    let r1 = corotational_beam(&d1, 4.2, &SEC, false);
    assert!((r1.axial - r0.axial).abs() < 1e-6 * r0.axial.abs());
    assert!((r1.moment1 - r0.moment1).abs() < 1e-6 * r0.moment1.abs());
    assert!((r1.moment2 - r0.moment2).abs() < 1e-6 * r0.moment2.abs());
}

/// A uniform curvature κ (an arc) gives M = EI·κ at both ends; a sag (dθ/ds < 0) is negative.
#[test]
fn constant_curvature_moment_and_sign() {
    let (l0, kappa): (f64, f64) = (2.0, -0.01);
    // Arc of length l0 starting at the origin heading along +x with dθ/ds = κ.
    let th = kappa * l0;
    let (x2, z2) = (th.sin() / kappa, (1.0 - th.cos()) / kappa);
    let d = [0.0, 0.0, 0.0, x2, z2, th];
    let r = corotational_beam(&d, l0, &SEC, false);
    let m = SEC.ei * kappa;
    assert!(
        (r.moment1 - m).abs() < 1e-3 * m.abs(),
        "{} vs {m}",
        r.moment1
    );
    assert!(
        (r.moment2 - m).abs() < 1e-3 * m.abs(),
        "{} vs {m}",
        r.moment2
    );
    assert!(r.moment1 < 0.0);
}

#[test]
fn structural_damping_spares_rigid_motion_and_its_c_is_exact() {
    let sec = Section {
        ea: 3.4e9,
        ei: 1.8e7,
    };
    let (dx, dz) = (3.0, -4.0);
    let beta = 0.002;
    // Rigid translation and a rigid rotation about node 1 (ω = 0.3 rad/s).
    let w = 0.3;
    for v in [
        [1.0, -2.0, 0.0, 1.0, -2.0, 0.0],
        [0.0, 0.0, w, -w * dz, w * dx, w],
    ] {
        let d = structural_damping(dx, dz, 5.0, &sec, beta, &v, false);
        let big = d.force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
        assert!(
            big < 1e-6 * sec.ea * beta,
            "rigid motion damped: {:?}",
            d.force
        );
    }
    // Linear in v: f = C·v exactly; and a stretching velocity is damped against itself.
    let v = [0.1, 0.2, -0.05, -0.3, 0.4, 0.02];
    let d = structural_damping(dx, dz, 5.0, &sec, beta, &v, true);
    for i in 0..6 {
        let cv: f64 = (0..6).map(|j| d.damping[i][j] * v[j]).sum();
        assert!((cv - d.force[i]).abs() <= 1e-9 * d.force[i].abs().max(1.0));
    }
    let power: f64 = d.force.iter().zip(&v).map(|(f, x)| f * x).sum();
    assert!(power > 0.0, "damping dissipates");
}

#[test]
fn wrap_is_in_range() {
    for a in [
        -10.0,
        -3.2,
        -std::f64::consts::PI,
        0.0,
        3.0,
        std::f64::consts::PI,
        7.0,
    ] {
        let w = wrap(a);
        assert!(w > -std::f64::consts::PI - 1e-15 && w <= std::f64::consts::PI + 1e-15);
        assert!(
            ((w - a) / std::f64::consts::TAU).fract().abs() < 1e-12
                || ((w - a) / std::f64::consts::TAU).fract().abs() > 1.0 - 1e-12
        );
    }
}

/// The lanes kernels give [`corotational_beam_chord_k`]'s forces, axial force, end moments and
/// tangent to the bit, on chords in every quadrant (every reduction of the arctangent), chords
/// pointing along −x with dz of either sign (the chord angle jumps between ±π there, as on a
/// seabed laid from the top: the end rotations then need the wrap), end angles up to 5π away
/// (past the lanes' wrap: the element-by-element fallback), vertical and zero chords.
#[test]
fn lanes_give_the_element_kernel_to_the_bit() {
    use std::f64::consts::PI;
    const L: usize = ELEMENT_LANES;
    let mut rng = 7u64;
    let mut cases = Vec::new();
    for n in 0..4000 {
        let ang = match n % 4 {
            0 => (2.0 * uniform(&mut rng) - 1.0) * PI,
            1 => PI - 1e-6 * (2.0 * uniform(&mut rng) - 1.0),
            2 => 0.5 * PI * (n % 3) as f64,
            _ => 20.0 * (uniform(&mut rng) - 0.5),
        };
        let len = 4.0 * (1.0 + 0.01 * (uniform(&mut rng) - 0.5));
        let (dx, dz) = if n % 97 == 0 {
            (0.0, 0.0)
        } else {
            (len * ang.cos(), len * ang.sin())
        };
        let spread = if n % 5 == 0 { 5.0 * PI } else { 0.2 };
        let th1 = ang + spread * (2.0 * uniform(&mut rng) - 1.0);
        let th2 = ang + spread * (2.0 * uniform(&mut rng) - 1.0);
        cases.push((dx, dz, th1, th2));
    }
    let (l0, ka, kb) = (4.0, SEC.ea / 4.0, SEC.ei / 4.0);
    let (mut fallback, mut wrapped) = (0, 0);
    for chunk in cases.chunks(L) {
        let mut inp = ChordLanes::<L>::default();
        for (k, &(dx, dz, th1, th2)) in chunk.iter().enumerate() {
            (inp.dx[k], inp.dz[k], inp.theta1[k], inp.theta2[k]) = (dx, dz, th1, th2);
            (inp.l0[k], inp.ka[k], inp.kb[k]) = (l0, ka, kb);
        }
        let mut only_forces = ForceLanes::<L>::default();
        let mut out = ForceLanes::<L>::default();
        let mut kl = [[0.0; L]; 21];
        if corotational_forces_lanes(&inp, &mut only_forces) {
            fallback += 1;
        }
        corotational_tangent_lanes(&inp, &mut out, &mut kl);
        for (k, &(dx, dz, th1, th2)) in chunk.iter().enumerate() {
            let beta = crate::fastmath::atan2(dz, dx);
            if !(-PI..=PI).contains(&(th1 - beta)) {
                wrapped += 1;
            }
            let r = corotational_beam_chord_k(dx, dz, th1, th2, l0, (ka, kb), true);
            for o in [&only_forces, &out] {
                let got = [
                    -o.f3[k], -o.f4[k], o.f2[k], o.f3[k], o.f4[k], o.f5[k], o.axial[k], o.m1[k],
                    o.m2[k],
                ];
                let want = [
                    r.force[0], r.force[1], r.force[2], r.force[3], r.force[4], r.force[5],
                    r.axial, r.moment1, r.moment2,
                ];
                for (g, w) in got.iter().zip(&want) {
                    assert!(
                        g.to_bits() == w.to_bits() || (g.is_nan() && w.is_nan()),
                        "chord ({dx}, {dz}), angles ({th1}, {th2}): {got:?} against {want:?}"
                    );
                }
            }
            for (t, &(i, j)) in UPPER_PAIRS.iter().enumerate() {
                let (g, w) = (kl[t][k], r.stiffness[i][j]);
                assert!(
                    g.to_bits() == w.to_bits() || (g.is_nan() && w.is_nan()),
                    "K[{i}][{j}] of chord ({dx}, {dz}), angles ({th1}, {th2}): {g} against {w}"
                );
            }
        }
    }
    // Both paths were taken: most chunks in lanes (wrapped angles included), some by the
    // fallback.
    assert!(wrapped > 500, "{wrapped} wrapped angles");
    assert!(
        fallback > 50 && fallback < 700,
        "{fallback} of 1000 chunks fell back"
    );
}

/// [`upper_index`] numbers the 21 entries of the upper triangle by rows.
#[test]
fn upper_index_numbers_the_upper_triangle_by_rows() {
    let mut t = 0;
    for i in 0..6 {
        for j in i..6 {
            assert_eq!(upper_index(i, j), t);
            assert_eq!(UPPER_PAIRS[t], (i, j));
            t += 1;
        }
    }
}

/// The upper triangle [`fold_tangent`] writes (four sums, the bending rows and their signs) is
/// each of the 21 entries as [`tangent_entry`] computes it on its own, to the bit (a zero may
/// differ in its sign only), on chords in every direction, horizontal and vertical ones included:
/// a wrong fold, row or sign fails.
#[test]
fn folded_tangent_is_every_entry_computed() {
    let mut rng = 11u64;
    for n in 0..2000 {
        let ang = match n % 5 {
            0 => 0.0,
            1 => 0.5 * std::f64::consts::PI,
            _ => (2.0 * uniform(&mut rng) - 1.0) * std::f64::consts::PI,
        };
        let len = 4.0 * (1.0 + 0.01 * (uniform(&mut rng) - 0.5));
        let (dx, dz) = (len * ang.cos(), len * ang.sin());
        let th1 = ang + 0.2 * (2.0 * uniform(&mut rng) - 1.0);
        let th2 = ang + 0.2 * (2.0 * uniform(&mut rng) - 1.0);
        let (l0, ka, kb) = (4.0, SEC.ea / 4.0, SEC.ei / 4.0);
        let got = corotational_beam_chord_k(dx, dz, th1, th2, l0, (ka, kb), true);
        let bs = basis(dx, dz);
        let (m1, m2) = (-got.moment1, got.moment2);
        let (gq, gm) = (got.axial / bs.l, (m1 + m2) / (bs.l * bs.l));
        for i in 0..6 {
            for j in i..6 {
                let want = bs.tangent_entry((ka, kb), (gq, gm), i, j);
                let (a, b) = (got.stiffness[i][j], got.stiffness[j][i]);
                // `==` takes a zero of either sign for the other; any other value to the bit.
                assert!(
                    a == want && a.to_bits() == b.to_bits(),
                    "K[{i}][{j}] of chord ({dx}, {dz}): {a} against {want}"
                );
            }
        }
    }
}
