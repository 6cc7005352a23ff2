//! Spectral fatigue of a Gaussian stress process: the narrow-band estimate and Dirlik's formula, the
//! closed forms a time-domain count is checked against.
//!
//! With the one-sided stress PSD `G(f)` in Hz units and its moments `m_n = ∫ fⁿ G(f) df`, a record of
//! `T` seconds on a single-slope S-N curve `N = ā·S^{−m}` (S the stress range):
//!
//! ```text
//! narrow band:  D_NB = ν₀ T (2√(2 m0))^m Γ(1 + m/2) / ā,      ν₀ = √(m2/m0)
//! Dirlik:       D_DK = ν_p T / ā · E[S^m],                     ν_p = √(m4/m2)
//!   E[S^m] = (2√m0)^m · [D1 Q^m Γ(1 + m) + (√2)^m Γ(1 + m/2) (D2 |R|^m + D3)]
//!   x_m = (m1/m0)√(m2/m4),  γ = m2/√(m0 m4),
//!   D1 = 2(x_m − γ²)/(1 + γ²),  R = (γ − x_m − D1²)/(1 − γ − D1 + D1²),
//!   D2 = (1 − γ − D1 + D1²)/(1 − R),  D3 = 1 − D1 − D2,  Q = 1.25(γ − D3 − D2 R)/D1
//! ```
//!
//! (Dirlik 1985; the form of Bishop & Sherratt). Γ is evaluated by the Lanczos approximation
//! (g = 7, nine coefficients: relative error below 1e-13 for the arguments used here).

/// Γ(x) for x > 0 (Lanczos).
pub fn gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return std::f64::consts::PI / ((std::f64::consts::PI * x).sin() * gamma(1.0 - x));
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + G + 0.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    (2.0 * std::f64::consts::PI).sqrt() * t.powf(x + 0.5) * (-t).exp() * a
}

/// Spectral moments `m_n = ∫ fⁿ G(f) df` of a PSD sampled at equally spaced frequencies `f`
/// (trapezoidal rule), for n = 0, 1, 2, 4.
pub fn moments(f: &[f64], g: &[f64]) -> [f64; 4] {
    let mut m = [0.0; 4];
    for i in 1..f.len() {
        let h = f[i] - f[i - 1];
        for (k, n) in [0, 1, 2, 4].into_iter().enumerate() {
            m[k] += 0.5 * h * (f[i - 1].powi(n) * g[i - 1] + f[i].powi(n) * g[i]);
        }
    }
    m
}

/// The narrow-band damage of a record of `t` seconds, moments `[m0, m1, m2, m4]`, slope `m`,
/// `log10 ā` (S in the PSD's unit).
pub fn narrow_band(mo: [f64; 4], t: f64, m: f64, log_a: f64) -> f64 {
    let nu0 = (mo[2] / mo[0]).sqrt();
    nu0 * t * (2.0 * (2.0 * mo[0]).sqrt()).powf(m) * gamma(1.0 + m / 2.0) / 10f64.powf(log_a)
}

/// Dirlik's damage of a record of `t` seconds (see the module docs).
pub fn dirlik(mo: [f64; 4], t: f64, m: f64, log_a: f64) -> f64 {
    let [m0, m1, m2, m4] = mo;
    let xm = m1 / m0 * (m2 / m4).sqrt();
    let g = m2 / (m0 * m4).sqrt();
    let d1 = 2.0 * (xm - g * g) / (1.0 + g * g);
    let r = (g - xm - d1 * d1) / (1.0 - g - d1 + d1 * d1);
    let d2 = (1.0 - g - d1 + d1 * d1) / (1.0 - r);
    let d3 = 1.0 - d1 - d2;
    let q = 1.25 * (g - d3 - d2 * r) / d1;
    let es = (2.0 * m0.sqrt()).powf(m)
        * (d1 * q.powf(m) * gamma(1.0 + m)
            + 2f64.sqrt().powf(m) * gamma(1.0 + m / 2.0) * (d2 * r.abs().powf(m) + d3));
    (m4 / m2).sqrt() * t * es / 10f64.powf(log_a)
}
