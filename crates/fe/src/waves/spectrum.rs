//! The JONSWAP spectrum (DNV-RP-C205 §3.5.5, the equations in the parent module's docs), the
//! DNV-RP-C205 rule for its peak enhancement γ, and the linear dispersion relation.

/// γ from the sea state by the DNV-RP-C205 rule.
pub fn dnv_gamma(hs: f64, tp: f64) -> f64 {
    let r = tp / hs.sqrt();
    if r <= 3.6 {
        5.0
    } else if r < 5.0 {
        (5.75 - 1.15 * r).exp()
    } else {
        1.0
    }
}

/// The JONSWAP spectral density `S_J(ω)` (m²·s/rad, one-sided), DNV-RP-C205 §3.5.5.
pub fn jonswap(omega: f64, hs: f64, tp: f64, gamma: f64) -> f64 {
    if omega <= 0.0 {
        return 0.0;
    }
    let wp = std::f64::consts::TAU / tp;
    let pm =
        5.0 / 16.0 * hs * hs * wp.powi(4) * omega.powi(-5) * (-1.25 * (omega / wp).powi(-4)).exp();
    let sigma = if omega <= wp { 0.07 } else { 0.09 };
    let a_gamma = 1.0 - 0.287 * gamma.ln();
    a_gamma * pm * gamma.powf((-0.5 * ((omega - wp) / (sigma * wp)).powi(2)).exp())
}

/// The wavenumber of angular frequency `omega` in water of depth `depth` (`ω² = g k tanh(k d)`),
/// by Newton's method from the larger of the deep- and shallow-water values.
pub fn wavenumber(omega: f64, depth: f64, g: f64) -> f64 {
    let deep = omega * omega / g;
    let mut k = deep.max(omega / (g * depth).sqrt());
    for _ in 0..100 {
        let kd = k * depth;
        let t = kd.tanh();
        let f = g * k * t - omega * omega;
        let df = g * t + g * kd * (1.0 - t * t);
        let next = k - f / df;
        let done = (next - k).abs() <= 1e-15 * k;
        k = if next > 0.0 { next } else { 0.5 * k };
        if done {
            break;
        }
    }
    k
}
