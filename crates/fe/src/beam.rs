//! The 2D corotational Euler–Bernoulli beam element (Crisfield 1991, Battini 2002), as a pure kernel.
//!
//! Degrees of freedom of an element: `d = (x1, z1, θ1, x2, z2, θ2)`, with `θ` the absolute angle of the
//! tangent (counter-clockwise from the x axis) and the stress-free reference **straight** of length
//! `L0` (the catenary is only a starting guess, never a stress-free state).
//!
//! **Corotational frame.** Chord `(dx, dz) = (x2 − x1, z2 − z1)`, `L = |(dx, dz)|`, `β = atan2(dz, dx)`,
//! `c = cos β`, `s = sin β`. Local (basic) deformations:
//!
//! ```text
//! u   = L − L0                       axial extension
//! θ1l = wrap(θ1 − β),  θ2l = wrap(θ2 − β)   end rotations relative to the chord, in (−π, π]
//! ```
//!
//! **Basic response** (linear in the local frame):
//!
//! ```text
//! N  = EA/L0 · u
//! M1 = EI/L0 · (4 θ1l + 2 θ2l)
//! M2 = EI/L0 · (2 θ1l + 4 θ2l)
//! K_l = diag(EA/L0, EI/L0·[[4, 2], [2, 4]])
//! ```
//!
//! **Transformation.** With `r = (−c, −s, 0, c, s, 0)` and `q = (s, −c, 0, −s, c, 0)`,
//! `δu = r·δd`, `δβ = q·δd / L`, so `B = [r; e3 − q/L; e6 − q/L]` and
//!
//! ```text
//! f = Bᵀ (N, M1, M2)
//! K = Bᵀ K_l B + (N/L)·q qᵀ + ((M1 + M2)/L²)·(r qᵀ + q rᵀ)
//! ```
//!
//! The internal bending moment along the element (cubic Hermite interpolation of the local rotations)
//! is `M(0) = −M1` at end 1 and `M(1) = M2` at end 2, with `M = EI·dθ/ds`. With the nodes numbered from
//! the top of a riser, a sag bend (concave up) has `dθ/ds < 0`, so its moment is negative, the paper's
//! convention.

/// Section properties of an element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Axial stiffness EA, N.
    pub ea: f64,
    /// Bending stiffness EI, N·m².
    pub ei: f64,
}

/// What the element kernel returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamResponse {
    /// Internal force vector in global coordinates `(fx1, fz1, m1, fx2, fz2, m2)` (N, N·m).
    pub force: [f64; 6],
    /// Tangent stiffness, 6×6, row-major.
    pub stiffness: [[f64; 6]; 6],
    /// Axial force N (positive in tension), N.
    pub axial: f64,
    /// Internal bending moment at end 1, `−M1`, N·m.
    pub moment1: f64,
    /// Internal bending moment at end 2, `M2`, N·m.
    pub moment2: f64,
    /// Current chord angle β, rad.
    pub chord_angle: f64,
}

/// The corotational transformation of a chord `(dx, dz)`: its length, `r`, `q` and the rows
/// `b1 = e3 − q/L`, `b2 = e6 − q/L` of `B` (the module docs).
struct Basis {
    l: f64,
    r: [f64; 6],
    q: [f64; 6],
    b1: [f64; 6],
    b2: [f64; 6],
}

#[inline]
fn basis(dx: f64, dz: f64) -> Basis {
    let l = (dx * dx + dz * dz).sqrt();
    let c = dx / l;
    let s = dz / l;
    let r = [-c, -s, 0.0, c, s, 0.0];
    let q = [s, -c, 0.0, -s, c, 0.0];
    let mut b1 = [0.0; 6];
    let mut b2 = [0.0; 6];
    for i in 0..6 {
        b1[i] = -q[i] / l;
        b2[i] = -q[i] / l;
    }
    b1[2] += 1.0;
    b2[5] += 1.0;
    Basis { l, r, q, b1, b2 }
}

/// Stiffness-proportional (Rayleigh) structural damping of an element, on its basic (material)
/// deformation rates only: with `ḋ_b = B·v` (extension rate and end-rotation rates relative to the
/// chord, `B` as above),
///
/// ```text
/// f_d = β·Bᵀ K_l B·v,     C = ∂f_d/∂v = β·Bᵀ K_l B
/// ```
///
/// A rigid-body motion of the element (translation or rotation) has `B·v = 0` and is not damped;
/// the geometric stiffness is left out for that reason. `β = ζ·T/π` damps a mode of period `T` at
/// the fraction `ζ` of critical (and a mode of period T' at `ζ·T/T'`). Pure; allocates nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampingResponse {
    /// Damping force in global coordinates, N and N·m.
    pub force: [f64; 6],
    /// `C = ∂f/∂v`, 6×6, row-major (zero unless asked for).
    pub damping: [[f64; 6]; 6],
}

/// See [`DampingResponse`]: the element's chord `(dx, dz)`, `L0`, section, `β` (s) and nodal
/// velocities `v = (ẋ1, ż1, θ̇1, ẋ2, ż2, θ̇2)`.
#[inline]
pub fn structural_damping(
    dx: f64,
    dz: f64,
    l0: f64,
    sec: &Section,
    beta: f64,
    v: &[f64; 6],
    with_damping: bool,
) -> DampingResponse {
    let Basis { r, b1, b2, .. } = basis(dx, dz);
    let dot = |a: &[f64; 6]| a.iter().zip(v).map(|(x, y)| x * y).sum::<f64>();
    let (e0, e1, e2) = (dot(&r), dot(&b1), dot(&b2));
    let ka = beta * sec.ea / l0;
    let kb = beta * sec.ei / l0;
    let n = ka * e0;
    let m1 = kb * (4.0 * e1 + 2.0 * e2);
    let m2 = kb * (2.0 * e1 + 4.0 * e2);
    let mut force = [0.0; 6];
    for i in 0..6 {
        force[i] = r[i] * n + b1[i] * m1 + b2[i] * m2;
    }
    let mut damping = [[0.0; 6]; 6];
    if with_damping {
        for i in 0..6 {
            let a1 = 4.0 * kb * b1[i] + 2.0 * kb * b2[i];
            let a2 = 2.0 * kb * b1[i] + 4.0 * kb * b2[i];
            for j in 0..6 {
                damping[i][j] = ka * r[i] * r[j] + a1 * b1[j] + a2 * b2[j];
            }
        }
    }
    DampingResponse { force, damping }
}

/// Wraps an angle to (−π, π].
#[inline]
pub fn wrap(a: f64) -> f64 {
    if a > -std::f64::consts::PI && a <= std::f64::consts::PI {
        return a; // the usual case, without the remainder (identical result)
    }
    let two_pi = std::f64::consts::TAU;
    let mut w = a % two_pi;
    if w > std::f64::consts::PI {
        w -= two_pi;
    } else if w <= -std::f64::consts::PI {
        w += two_pi;
    }
    w
}

/// The element response at the nodal values `d = (x1, z1, θ1, x2, z2, θ2)`. Pure; allocates nothing.
/// `with_stiffness = false` skips the 6×6 tangent (it is then zero).
#[inline]
pub fn corotational_beam(
    d: &[f64; 6],
    l0: f64,
    sec: &Section,
    with_stiffness: bool,
) -> BeamResponse {
    corotational_beam_chord(
        d[3] - d[0],
        d[4] - d[1],
        d[2],
        d[5],
        l0,
        sec,
        with_stiffness,
    )
}

/// The element response from the chord `(dx, dz) = (x2 − x1, z2 − z1)` and the end angles. The
/// element depends on nothing else (a rigid translation changes nothing), so a solver that keeps
/// positions as a fixed base plus a displacement can pass the chord at full precision.
#[inline]
pub fn corotational_beam_chord(
    dx: f64,
    dz: f64,
    theta1: f64,
    theta2: f64,
    l0: f64,
    sec: &Section,
    with_stiffness: bool,
) -> BeamResponse {
    let Basis { l, r, q, b1, b2 } = basis(dx, dz);
    let beta = crate::fastmath::atan2(dz, dx);
    let t1 = wrap(theta1 - beta);
    let t2 = wrap(theta2 - beta);
    let u = l - l0;
    let ka = sec.ea / l0;
    let kb = sec.ei / l0;
    let n = ka * u;
    let m1 = kb * (4.0 * t1 + 2.0 * t2);
    let m2 = kb * (2.0 * t1 + 4.0 * t2);
    let mut force = [0.0; 6];
    for i in 0..6 {
        force[i] = r[i] * n + b1[i] * m1 + b2[i] * m2;
    }
    let mut k = [[0.0; 6]; 6];
    if with_stiffness {
        let (k11, k12, k22) = (4.0 * kb, 2.0 * kb, 4.0 * kb);
        let gq = n / l;
        let gm = (m1 + m2) / (l * l);
        for i in 0..6 {
            // (K_l B) columns for row i of Bᵀ: Bᵀ K_l B = ka r rᵀ + [b1 b2] Kb [b1 b2]ᵀ
            let a1 = k11 * b1[i] + k12 * b2[i];
            let a2 = k12 * b1[i] + k22 * b2[i];
            // Symmetric: the upper triangle, mirrored.
            for j in i..6 {
                let v = ka * r[i] * r[j]
                    + a1 * b1[j]
                    + a2 * b2[j]
                    + gq * q[i] * q[j]
                    + gm * (r[i] * q[j] + q[i] * r[j]);
                k[i][j] = v;
                k[j][i] = v;
            }
        }
    }
    BeamResponse {
        force,
        stiffness: k,
        axial: n,
        moment1: -m1,
        moment2: m2,
        chord_angle: beta,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
