//! Helpers shared by the integration tests of `catena-fe`.

use catena_fe::dynamics::Scheme;

/// A complex number `(re, im)`.
pub type C = (f64, f64);

/// The eigenvalues of the one-step map of a scheme (HHT-α or Newmark, Hilber, Hughes & Taylor
/// 1977) for `ü + ω²u = 0` with Δt = 1, acting on `(u, v, a)` (so `omega2 = (ωΔt)²`): from the
/// scheme's three equations `a₁ + ω²[(1+α)u₁ − αu₀] = 0`, `u₁ = u₀ + v₀ + (½−β)a₀ + βa₁`,
/// `v₁ = v₀ + (1−γ)a₀ + γa₁`, as the roots of the map's characteristic cubic (Durand–Kerner).
pub fn one_step_eigenvalues(scheme: Scheme, omega2: f64) -> [C; 3] {
    let (alpha, beta, gamma) = scheme.coefficients();
    let step = |x: [f64; 3]| {
        let (u, v, a) = (x[0], x[1], x[2]);
        let up = u + v + (0.5 - beta) * a;
        let a1 = -((1.0 + alpha) * omega2 * up - alpha * omega2 * u)
            / (1.0 + (1.0 + alpha) * omega2 * beta);
        [up + beta * a1, v + (1.0 - gamma) * a + gamma * a1, a1]
    };
    let cols = [
        step([1.0, 0.0, 0.0]),
        step([0.0, 1.0, 0.0]),
        step([0.0, 0.0, 1.0]),
    ];
    let m = |i: usize, j: usize| cols[j][i];
    // λ³ − c2 λ² + c1 λ − c0.
    let c2 = m(0, 0) + m(1, 1) + m(2, 2);
    let c1 = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0) + m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0)
        + m(1, 1) * m(2, 2)
        - m(1, 2) * m(2, 1);
    let c0 = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
        - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
        + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
    let mul = |a: C, b: C| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let sub = |a: C, b: C| (a.0 - b.0, a.1 - b.1);
    let div = |a: C, b: C| {
        let d = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
    };
    let p = |x: C| {
        let x2 = mul(x, x);
        let x3 = mul(x2, x);
        (
            x3.0 - c2 * x2.0 + c1 * x.0 - c0,
            x3.1 - c2 * x2.1 + c1 * x.1,
        )
    };
    let mut r: [C; 3] = [(0.4, 0.9), (-0.65, 0.72), (0.1, -0.8)];
    for _ in 0..1000 {
        for i in 0..3 {
            let mut den = (1.0, 0.0);
            for j in 0..3 {
                if i != j {
                    den = mul(den, sub(r[i], r[j]));
                }
            }
            r[i] = sub(r[i], div(p(r[i]), den));
        }
    }
    r
}
