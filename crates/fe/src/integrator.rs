//! The time integration scheme, apart from Newton and from the stepping: HHT-α and Newmark
//! coefficients, the predictors, the Newmark relations and the HHT residual.
//!
//! **Convention (Hilber 1977).** `α ∈ [−1/3, 0]`, `β = (1 − α)²/4`, `γ = 1/2 − α`; `α = 0` is the
//! trapezoidal rule (Newmark β = 1/4, γ = 1/2). The equations of step `n → n+1` are
//!
//! ```text
//! M a_{n+1} + (1 + α) F(u_{n+1}, v_{n+1}) − α F(u_n, v_n) = 0
//! u_{n+1} = u_n + Δt v_n + Δt² [(1/2 − β) a_n + β a_{n+1}]
//! v_{n+1} = v_n + Δt [(1 − γ) a_n + γ a_{n+1}]
//! ```
//!
//! so that, with `u_{n+1}` the unknown, `a_{n+1} = c_m (u_{n+1} − u_n − Δt v_n) − (1/(2β) − 1) a_n`
//! with `c_m = 1/(βΔt²)`, and the Newton Jacobian is `c_m M + (1 + α)(K + c_v C)`, `c_v = γ/(βΔt)`.
//! The spectral radius at infinite frequency is `(1 + α)/(1 − α)`. Only the forces are α-weighted:
//! prescribed motion is taken at `t_{n+1}` (see [`crate::boundary`]).
//!
//! **Predictors.** Constant acceleration `u_n + Δt v_n + Δt²/2 a_n`, or constant velocity
//! `u_n + Δt v_n` (the careful retry of a diverged attempt).

use serde::{Deserialize, Serialize};

/// The time integration scheme.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Scheme {
    /// HHT-α with `α ∈ [−1/3, 0]` (Hilber's convention).
    Hht {
        /// α.
        alpha: f64,
    },
    /// Newmark with its own β and γ (no force averaging).
    Newmark {
        /// β.
        beta: f64,
        /// γ.
        gamma: f64,
    },
}

impl Scheme {
    /// `(α, β, γ)`.
    pub fn coefficients(&self) -> (f64, f64, f64) {
        match *self {
            Scheme::Hht { alpha } => (alpha, (1.0 - alpha).powi(2) / 4.0, 0.5 - alpha),
            Scheme::Newmark { beta, gamma } => (0.0, beta, gamma),
        }
    }

    /// The coefficients of a step of `dt`.
    pub fn step(&self, dt: f64) -> StepCoefficients {
        let (alpha, beta, gamma) = self.coefficients();
        StepCoefficients {
            alpha,
            beta,
            gamma,
            dt,
            c_m: 1.0 / (beta * dt * dt),
            c_v: gamma / (beta * dt),
        }
    }
}

impl std::fmt::Display for Scheme {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Scheme::Hht { alpha } => write!(f, "HHT-α, α = {alpha}"),
            Scheme::Newmark { beta, gamma } => write!(f, "Newmark, β = {beta}, γ = {gamma}"),
        }
    }
}

/// One step's coefficients (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepCoefficients {
    /// α (0 for Newmark).
    pub alpha: f64,
    /// β.
    pub beta: f64,
    /// γ.
    pub gamma: f64,
    /// Δt, s.
    pub dt: f64,
    /// `1/(βΔt²)`: the mass's factor in the Jacobian.
    pub c_m: f64,
    /// `γ/(βΔt)`: the damping's factor within the forces' tangent.
    pub c_v: f64,
}

impl StepCoefficients {
    /// `1 + α`: the factor on the forces at `t_{n+1}` and on their tangent.
    #[inline]
    pub fn k_scale(&self) -> f64 {
        1.0 + self.alpha
    }

    /// The predicted displacements: constant acceleration, or constant velocity when `careful`.
    pub fn predict(&self, (u0, v0, a0): (&[f64], &[f64], &[f64]), careful: bool, u: &mut [f64]) {
        let dt = self.dt;
        let c_pred = if careful { 0.0 } else { 0.5 * dt * dt };
        for (u, ((u0, v0), a0)) in u.iter_mut().zip(u0.iter().zip(v0).zip(a0)) {
            *u = u0 + dt * v0 + c_pred * a0;
        }
    }

    /// `a_{n+1}` and `v_{n+1}` from the iterate `u_{n+1}` (the Newmark relations) on the dofs of
    /// the runs `(g0, _, len)`, from the step's start `(u0, v0, a0)`.
    pub fn relations(
        &self,
        runs: &[(usize, usize, usize)],
        start: (&[f64], &[f64], &[f64]),
        iterate: (&[f64], &mut [f64], &mut [f64]),
    ) {
        relations_dispatch(self, runs, start, iterate);
    }

    /// The HHT residual at every dof, `G = M a + (1 + α) F − α F_n`, with the lumped mass per node
    /// `[xx, xz, zz, rot]`.
    pub fn residual(&self, mass: &[[f64; 4]], a: &[f64], f: &[f64], f_prev: &[f64], g: &mut [f64]) {
        residual_dispatch(self, mass, a, f, f_prev, g);
    }
}

/// [`StepCoefficients::relations`], compiled for the baseline processor and again for AVX2 and
/// AVX-512, chosen at run time: the same operations in the same order (no fused multiply-adds),
/// so the same values to the bit, in wider vectors (the baseline build's two-wide loops were
/// 2.7 % of the 3-hour storm's samples, and so was the residual's).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn relations_dispatch(
    sc: &StepCoefficients,
    runs: &[(usize, usize, usize)],
    (u0, v0, a0): (&[f64], &[f64], &[f64]),
    (u, v, a): (&[f64], &mut [f64], &mut [f64]),
) {
    let (dt, beta, gamma) = (sc.dt, sc.beta, sc.gamma);
    let c_m = 1.0 / (beta * dt * dt);
    for &(g0, _, len) in runs {
        let r = g0..g0 + len;
        for ((a, v), (u, ((u0, v0), a0))) in a[r.clone()].iter_mut().zip(&mut v[r.clone()]).zip(
            u[r.clone()]
                .iter()
                .zip(u0[r.clone()].iter().zip(&v0[r.clone()]).zip(&a0[r])),
        ) {
            *a = c_m * (u - u0 - dt * v0) - (0.5 / beta - 1.0) * a0;
            *v = v0 + dt * ((1.0 - gamma) * a0 + gamma * *a);
        }
    }
}

/// [`StepCoefficients::residual`], compiled like [`relations_dispatch`].
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn residual_dispatch(
    sc: &StepCoefficients,
    mass: &[[f64; 4]],
    a: &[f64],
    f: &[f64],
    f_prev: &[f64],
    g: &mut [f64],
) {
    let alpha = sc.alpha;
    for ((((g, m), a), f), f_prev) in g
        .chunks_exact_mut(3)
        .zip(mass)
        .zip(a.chunks_exact(3))
        .zip(f.chunks_exact(3))
        .zip(f_prev.chunks_exact(3))
    {
        let inertia = [
            m[0] * a[0] + m[1] * a[1],
            m[1] * a[0] + m[2] * a[1],
            m[3] * a[2],
        ];
        for k in 0..3 {
            g[k] = inertia[k] + (1.0 + alpha) * f[k] - alpha * f_prev[k];
        }
    }
}

/// HHT-α on one degree of freedom `m ü + k u = 0` (the same coefficients as the stepper): returns
/// the displacement after `steps` steps. Used to check the scheme's published numbers.
pub fn sdof_free_vibration(
    scheme: Scheme,
    omega: f64,
    u0: f64,
    v0: f64,
    dt: f64,
    steps: usize,
) -> f64 {
    let (alpha, beta, gamma) = scheme.coefficients();
    let k = omega * omega;
    let (mut u, mut v) = (u0, v0);
    let mut a = -k * u;
    for _ in 0..steps {
        // m a1 + (1+α) k u1 − α k u = 0, u1 = u + dt v + dt²((1/2−β) a + β a1).
        let up = u + dt * v + dt * dt * (0.5 - beta) * a;
        let a1 =
            -((1.0 + alpha) * k * up - alpha * k * u) / (1.0 + (1.0 + alpha) * k * beta * dt * dt);
        let u1 = up + beta * dt * dt * a1;
        let v1 = v + dt * ((1.0 - gamma) * a + gamma * a1);
        (u, v, a) = (u1, v1, a1);
    }
    u
}
