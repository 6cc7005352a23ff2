//! Short-term extreme statistics of a response record (pure): what the largest value of a storm of a
//! given duration is expected to be, from one (or several) realisations of it.
//!
//! A record `x(t)` sampled every `Δt` over a duration `T_s` (from a start, after the ramp). Its mean
//! `x̄` and standard deviation `σ`; its mean up-crossing rate `ν₀ = n₊/T_s` (`n₊` crossings of `x̄`
//! from below). For a target duration `T` the number of cycles is `N = ν₀·T`, and of the largest
//! value of the target duration:
//!
//! ```text
//! Rayleigh (narrow-band Gaussian):  MPM = x̄ + σ·√(2 ln N)
//!                                   q-quantile = x̄ + σ·√(−2 ln(1 − q^(1/N)))
//! Weibull of the up-crossing peaks: the largest value between successive up-crossings of x̄, as
//!   excesses y = peak − x̄ > 0, F(y) = 1 − exp(−(y/λ)^k) (maximum likelihood);
//!                                   MPM = x̄ + λ·(ln N)^(1/k)        (F(y) = 1 − 1/N)
//!                                   q-quantile = x̄ + λ·(−ln(1 − q^(1/N)))^(1/k)
//! Gumbel of block maxima (blocks of T_b, or one maximum per seed of a storm of T_b):
//!   F(x) = exp(−exp(−(x − μ)/β)) (maximum likelihood); over T, n = T/T_b blocks:
//!                                   MPM = μ + β·ln n
//!                                   q-quantile = μ + β·ln n − β·ln(−ln q)
//! ```
//!
//! `q` is the probability that the target duration's largest value does not exceed the quantile
//! (0.9: exceeded once in ten storms). A record whose design extreme is a minimum (the least
//! effective tension, the largest sag moment) is analysed as `−x` and reported back with its sign.
//!
//! Maximum likelihood: Weibull's shape solves `Σ yᵏ ln y / Σ yᵏ − 1/k − mean(ln y) = 0`
//! (increasing in k, bisected), `λ = (mean(yᵏ))^(1/k)`; Gumbel's scale solves
//! `β = x̄ − Σ x e^(−x/β) / Σ e^(−x/β)`, `μ = −β ln(mean(e^(−x/β)))` (Forbes et al., Statistical
//! Distributions, 4th ed., 2011, §22 and §46). Written here: the maintained Rust statistics crates
//! (statrs) give the distributions but not their maximum-likelihood fits.

use serde::{Deserialize, Serialize};

/// Which end of a record is its design extreme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Tail {
    /// The largest value.
    Max,
    /// The least value.
    Min,
}

impl Tail {
    fn sign(self) -> f64 {
        match self {
            Tail::Max => 1.0,
            Tail::Min => -1.0,
        }
    }
}

/// A two-parameter Weibull fit of peak excesses.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Weibull {
    /// Shape k.
    pub shape: f64,
    /// Scale λ, in the record's units.
    pub scale: f64,
    /// Peaks fitted.
    pub peaks: usize,
}

impl Weibull {
    /// Maximum-likelihood fit of excesses `y > 0` (at least 3), or `None`.
    pub fn fit(y: &[f64]) -> Option<Self> {
        let y: Vec<f64> = y.iter().copied().filter(|v| *v > 0.0).collect();
        if y.len() < 3 {
            return None;
        }
        // Scaled by the largest (the fit is scale-free), for well-sized powers.
        let top = y.iter().copied().fold(0.0, f64::max);
        let z: Vec<f64> = y.iter().map(|v| v / top).collect();
        let n = z.len() as f64;
        let mean_ln = z.iter().map(|v| v.ln()).sum::<f64>() / n;
        let g = |k: f64| {
            let (mut a, mut b) = (0.0, 0.0);
            for v in &z {
                let p = v.powf(k);
                a += p * v.ln();
                b += p;
            }
            a / b - 1.0 / k - mean_ln
        };
        let (mut lo, mut hi) = (0.05, 50.0);
        if g(lo) > 0.0 || g(hi) < 0.0 {
            return None;
        }
        let (a, b) = catena_seabed::roots::bisect(lo, hi, |k| g(k) > 0.0);
        (lo, hi) = (a, b);
        let k = 0.5 * (lo + hi);
        let lambda = (z.iter().map(|v| v.powf(k)).sum::<f64>() / n).powf(1.0 / k) * top;
        Some(Self {
            shape: k,
            scale: lambda,
            peaks: y.len(),
        })
    }

    /// The most probable largest of `n` peaks (`F(y) = 1 − 1/n`), as an excess.
    pub fn most_probable(&self, n: f64) -> f64 {
        self.scale * n.max(1.0).ln().powf(1.0 / self.shape)
    }

    /// The excess the largest of `n` peaks stays below with probability `q`.
    pub fn quantile(&self, n: f64, q: f64) -> f64 {
        self.scale * (-(-q.powf(1.0 / n.max(1.0))).ln_1p()).powf(1.0 / self.shape)
    }
}

/// A Gumbel fit of maxima.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Gumbel {
    /// Location μ.
    pub location: f64,
    /// Scale β.
    pub scale: f64,
    /// Maxima fitted.
    pub maxima: usize,
}

impl Gumbel {
    /// Maximum-likelihood fit of maxima (at least 3, not all equal), or `None`.
    pub fn fit(x: &[f64]) -> Option<Self> {
        if x.len() < 3 || x.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let n = x.len() as f64;
        let mean = x.iter().sum::<f64>() / n;
        let sd = (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
        if sd <= 0.0 {
            return None;
        }
        // Centred and scaled: z = (x − x̄)/s; β' = β/s solves β' = −Σ z e^(−z/β') / Σ e^(−z/β').
        let z: Vec<f64> = x.iter().map(|v| (v - mean) / sd).collect();
        let f = |b: f64| {
            let (mut a, mut c) = (0.0, 0.0);
            for v in &z {
                let e = (-v / b).exp();
                a += v * e;
                c += e;
            }
            b + a / c
        };
        let (lo, hi) = (1e-3, 10.0);
        if f(lo) > 0.0 || f(hi) < 0.0 {
            return None;
        }
        let (a, b) = catena_seabed::roots::bisect(lo, hi, |b| f(b) > 0.0);
        let beta = 0.5 * (a + b);
        let m = z.iter().map(|v| (-v / beta).exp()).sum::<f64>() / n;
        Some(Self {
            location: mean + sd * (-beta * m.ln()),
            scale: beta * sd,
            maxima: x.len(),
        })
    }

    /// The most probable largest of `n` maxima, `μ + β ln n`.
    pub fn most_probable(&self, n: f64) -> f64 {
        self.location + self.scale * n.max(1e-300).ln()
    }

    /// The value the largest of `n` maxima stays below with probability `q`.
    pub fn quantile(&self, n: f64, q: f64) -> f64 {
        self.most_probable(n) - self.scale * (-q.ln()).ln()
    }
}

/// What an extreme-value analysis asks for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// The target duration, s (3 hours by default).
    pub target: f64,
    /// The non-exceedance probability of the quantile reported beside the most probable extreme.
    pub quantile: f64,
    /// The block length for the Gumbel fit of block maxima, s.
    pub block: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            target: 10800.0,
            quantile: 0.9,
            block: 600.0,
        }
    }
}

/// The extremes of one record: its statistics and every estimate of the target duration's extreme
/// (in the record's units and sign).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Extremes {
    /// The channel's name.
    pub channel: String,
    /// Which end.
    pub tail: Tail,
    /// Samples analysed.
    pub samples: usize,
    /// Their duration, s.
    pub duration: f64,
    /// Mean.
    pub mean: f64,
    /// Standard deviation.
    pub std_dev: f64,
    /// Mean up-crossing rate ν₀, 1/s.
    pub upcrossing_rate: f64,
    /// The sample's own extreme (over `duration`, not the target).
    pub sample_extreme: f64,
    /// The target duration, s, and the cycles in it `N = ν₀·T`.
    pub target: f64,
    /// `N`.
    pub cycles: f64,
    /// The quantile's non-exceedance probability.
    pub quantile_probability: f64,
    /// Rayleigh: the most probable extreme of the target duration and its quantile.
    pub rayleigh: [f64; 2],
    /// Weibull of the up-crossing peaks: its fit, the most probable extreme and the quantile.
    pub weibull: Option<(Weibull, [f64; 2])>,
    /// Gumbel of block maxima: the block, its fit, the most probable extreme and the quantile.
    pub gumbel: Option<(f64, Gumbel, [f64; 2])>,
}

/// What a channel reads from each step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Source {
    /// The effective tension at the top.
    TopTension,
    /// The least effective tension along the line.
    LeastTension,
    /// The most negative moment along the line.
    SagMoment,
    /// The largest design-check utilisation along the line.
    Utilisation,
    /// The moment at the gauge of this index (into the run's gauges).
    GaugeMoment(usize),
}

/// One channel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Channel {
    /// Its name as the scene gives it.
    pub name: String,
    /// What it reads.
    pub source: Source,
    /// Its design end.
    pub tail: Tail,
}

/// What an `[extremes]` table asks for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExtremesSpec {
    /// The channels.
    pub channels: Vec<Channel>,
    /// The records start here, s.
    pub start: f64,
    /// The analysis' settings.
    pub settings: Settings,
}

/// The up-crossing peaks of `x` about `level`: the largest value between each up-crossing of
/// `level` and the next (the record before the first and after the last up-crossing is left out).
pub fn upcrossing_peaks(x: &[f64], level: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut current: Option<f64> = None;
    for w in x.windows(2) {
        if w[0] < level && w[1] >= level {
            if let Some(p) = current {
                out.push(p);
            }
            current = Some(w[1]);
        } else if let Some(p) = &mut current {
            *p = p.max(w[1]);
        }
    }
    out
}

/// The maxima of successive blocks of `block` samples (a partial last block is left out).
pub fn block_maxima(x: &[f64], block: usize) -> Vec<f64> {
    if block == 0 {
        return Vec::new();
    }
    x.chunks_exact(block)
        .map(|c| c.iter().copied().fold(f64::NEG_INFINITY, f64::max))
        .collect()
}

/// The extremes of a record `x` sampled every `dt` s (its design end `tail`), for `settings`.
/// `None` for fewer than two samples or no up-crossing.
pub fn analyse(
    channel: &str,
    tail: Tail,
    x: &[f64],
    dt: f64,
    settings: &Settings,
) -> Option<Extremes> {
    if x.len() < 2 || dt.is_nan() || dt <= 0.0 {
        return None;
    }
    let s = tail.sign();
    let y: Vec<f64> = x.iter().map(|v| s * v).collect();
    let n = y.len() as f64;
    let mean = y.iter().sum::<f64>() / n;
    let sd = (y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    let duration = dt * (n - 1.0);
    let peaks = upcrossing_peaks(&y, mean);
    let crossings = y.windows(2).filter(|w| w[0] < mean && w[1] >= mean).count();
    if crossings == 0 {
        return None;
    }
    let nu0 = crossings as f64 / duration;
    let cycles = nu0 * settings.target;
    let q = settings.quantile;
    let rayleigh = [
        mean + sd * (2.0 * cycles.max(1.0).ln()).sqrt(),
        mean + sd * (-2.0 * (-q.powf(1.0 / cycles.max(1.0))).ln_1p()).sqrt(),
    ];
    let excess: Vec<f64> = peaks.iter().map(|p| p - mean).collect();
    let weibull = Weibull::fit(&excess).map(|w| {
        (
            w,
            [mean + w.most_probable(cycles), mean + w.quantile(cycles, q)],
        )
    });
    let block = (settings.block / dt).round() as usize;
    let gumbel = Gumbel::fit(&block_maxima(&y, block)).map(|g| {
        let nb = settings.target / (block as f64 * dt);
        (
            block as f64 * dt,
            g,
            [g.most_probable(nb), g.quantile(nb, q)],
        )
    });
    let back = |v: f64| s * v;
    Some(Extremes {
        channel: channel.to_string(),
        tail,
        samples: x.len(),
        duration,
        mean: back(mean),
        std_dev: sd,
        upcrossing_rate: nu0,
        sample_extreme: back(y.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
        target: settings.target,
        cycles,
        quantile_probability: q,
        rayleigh: rayleigh.map(back),
        weibull: weibull.map(|(w, v)| (w, v.map(back))),
        gumbel: gumbel.map(|(b, g, v)| (b, g, v.map(back))),
    })
}

/// The Gumbel fit of one maximum per realisation (the seeds of one storm, each of `duration` s),
/// and the most probable extreme and quantile of the target duration, in the record's sign.
pub fn across_realisations(
    maxima: &[f64],
    tail: Tail,
    duration: f64,
    settings: &Settings,
) -> Option<(Gumbel, [f64; 2])> {
    let s = tail.sign();
    let y: Vec<f64> = maxima.iter().map(|v| s * v).collect();
    let g = Gumbel::fit(&y)?;
    let n = settings.target / duration;
    Some((
        g,
        [s * g.most_probable(n), s * g.quantile(n, settings.quantile)],
    ))
}

/// The points of a record's fits on probability paper, in the analysed sign (`tail`'s: a least
/// extreme's record is negated): the up-crossing peaks' excesses on Weibull paper,
/// `(ln y, ln(−ln(1 − F)))` with `F = i/(n + 1)` for the sorted excesses, and the block maxima on
/// Gumbel paper, `(x, −ln(−ln F))`; and each fit's straight line there at the ends of its points.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Paper {
    /// Weibull paper: the peaks, and the fit's line.
    pub weibull: PointsAndLine,
    /// Gumbel paper: the block maxima, and the fit's line.
    pub gumbel: PointsAndLine,
}

/// Points on probability paper and a fit's straight line there.
pub type PointsAndLine = (Vec<(f64, f64)>, Vec<(f64, f64)>);

/// The probability-paper points of a record analysed as `e` (see [`Paper`]).
pub fn paper(e: &Extremes, x: &[f64], dt: f64) -> Paper {
    let s = e.tail.sign();
    let y: Vec<f64> = x.iter().map(|v| s * v).collect();
    let mean = s * e.mean;
    let plotting = |n: usize| (1..=n).map(move |i| i as f64 / (n as f64 + 1.0));
    let mut out = Paper::default();
    if let Some((w, _)) = &e.weibull {
        let mut ex: Vec<f64> = upcrossing_peaks(&y, mean)
            .into_iter()
            .map(|p| p - mean)
            .filter(|v| *v > 0.0)
            .collect();
        ex.sort_by(f64::total_cmp);
        out.weibull.0 = ex
            .iter()
            .zip(plotting(ex.len()))
            .map(|(v, f)| (v.ln(), (-(-f).ln_1p()).ln()))
            .collect();
        if let (Some(a), Some(b)) = (ex.first(), ex.last()) {
            out.weibull.1 = [a.ln(), b.ln()]
                .iter()
                .map(|l| (*l, w.shape * (l - w.scale.ln())))
                .collect();
        }
    }
    if let Some((block, g, _)) = &e.gumbel {
        let mut m = block_maxima(&y, (block / dt).round() as usize);
        m.sort_by(f64::total_cmp);
        out.gumbel.0 = m
            .iter()
            .zip(plotting(m.len()))
            .map(|(v, f)| (*v, -(-f.ln()).ln()))
            .collect();
        if let (Some(a), Some(b)) = (m.first(), m.last()) {
            out.gumbel.1 = [*a, *b]
                .iter()
                .map(|v| (*v, (v - g.location) / g.scale))
                .collect();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (SplitMix64), uniform in (0, 1).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        }
    }

    /// A Gumbel sample of known parameters (μ 100, β 15; 4000 maxima by the inverse CDF) is
    /// recovered by the fit: μ within 1 %, β within 4 % (the estimators' standard errors are
    /// about 0.25 and 0.19 for this n); the most probable largest of 10 maxima is μ + β ln 10.
    #[test]
    fn a_gumbel_sample_gives_back_its_parameters() {
        let mut rng = Rng(7);
        let x: Vec<f64> = (0..4000)
            .map(|_| 100.0 - 15.0 * (-rng.next().ln()).ln())
            .collect();
        let g = Gumbel::fit(&x).expect("fit");
        println!("gumbel: μ {:.3} (100), β {:.3} (15)", g.location, g.scale);
        assert!((g.location / 100.0 - 1.0).abs() < 0.01, "{g:?}");
        assert!((g.scale / 15.0 - 1.0).abs() < 0.04, "{g:?}");
        assert!((g.most_probable(10.0) - (g.location + g.scale * 10f64.ln())).abs() < 1e-12);
        // The quantile at q = exp(−1/n·…): at q = e^(−1) it is the most probable value.
        assert!((g.quantile(10.0, (-1f64).exp()) - g.most_probable(10.0)).abs() < 1e-9);
    }

    /// A Weibull sample of known parameters (k 1.8, λ 3; 4000 draws) is recovered: k within 4 %,
    /// λ within 2 %.
    #[test]
    fn a_weibull_sample_gives_back_its_parameters() {
        let mut rng = Rng(11);
        let y: Vec<f64> = (0..4000)
            .map(|_| 3.0 * (-rng.next().ln()).powf(1.0 / 1.8))
            .collect();
        let w = Weibull::fit(&y).expect("fit");
        println!("weibull: k {:.4} (1.8), λ {:.4} (3)", w.shape, w.scale);
        assert!((w.shape / 1.8 - 1.0).abs() < 0.04, "{w:?}");
        assert!((w.scale / 3.0 - 1.0).abs() < 0.02, "{w:?}");
    }

    /// A Gaussian process of known σ and up-crossing rate: 400 cosines of random phase, equal
    /// amplitudes, over a band 0.03 Hz wide about 0.1 Hz (σ = 2, mean 5), 6 hours at 0.2 s. The
    /// record's σ within 3 % and ν₀ within 3 % of the band's `√(m₂/m₀) = f₀√(1 + b²/12f₀²)`;
    /// N = ν₀·3 h; the Rayleigh and the Weibull most probable maxima within 3 % and 5 % of
    /// `σ√(2 ln N)` above the mean (the Gaussian narrow-band limit); the Gumbel fit of 10-minute
    /// block maxima within 8 % of it (36 blocks); each quantile above its most probable value; the
    /// least tail (`Min`) the mirror of the greatest for this symmetric process. (A band ten
    /// times narrower clusters its peaks in groups: its sample extremes fall well below
    /// `σ√(2 ln N)`, as they should; not a test of the estimators.)
    #[test]
    fn a_gaussian_process_gives_the_narrow_band_extreme() {
        let mut rng = Rng(3);
        let (sigma, f0, bw, m) = (2.0, 0.1, 0.03, 400);
        let comps: Vec<(f64, f64)> = (0..m)
            .map(|i| {
                let f = f0 - 0.5 * bw + bw * (i as f64 + rng.next()) / m as f64;
                (
                    2.0 * std::f64::consts::PI * f,
                    2.0 * std::f64::consts::PI * rng.next(),
                )
            })
            .collect();
        let a = sigma * (2.0 / m as f64).sqrt();
        let dt = 0.2;
        let x: Vec<f64> = (0..(6 * 3600 * 5))
            .map(|k| {
                let t = k as f64 * dt;
                5.0 + comps
                    .iter()
                    .map(|(w, p)| a * (w * t + p).cos())
                    .sum::<f64>()
            })
            .collect();
        let s = Settings::default();
        let e = analyse("x", Tail::Max, &x, dt, &s).expect("analysed");
        let nu0 = f0 * (1.0 + bw * bw / (12.0 * f0 * f0)).sqrt();
        let n = nu0 * s.target;
        let want = sigma * (2.0 * n.ln()).sqrt();
        let (w, wv) = e.weibull.expect("weibull");
        let (_, g, gv) = e.gumbel.expect("gumbel");
        println!(
            "gaussian: σ {:.4}, ν₀ {:.5} Hz, N {:.0}; σ√(2 ln N) {want:.3}; rayleigh {:.3}, weibull {:.3} (k {:.3}), gumbel {:.3} ({} blocks); sample {:.3}",
            e.std_dev,
            e.upcrossing_rate,
            e.cycles,
            e.rayleigh[0] - 5.0,
            wv[0] - 5.0,
            w.shape,
            gv[0] - 5.0,
            g.maxima,
            e.sample_extreme - 5.0
        );
        assert!((e.std_dev / sigma - 1.0).abs() < 0.03, "{}", e.std_dev);
        assert!(
            (e.upcrossing_rate / nu0 - 1.0).abs() < 0.03,
            "{}",
            e.upcrossing_rate
        );
        assert!(((e.rayleigh[0] - 5.0) / want - 1.0).abs() < 0.03);
        assert!(((wv[0] - 5.0) / want - 1.0).abs() < 0.05);
        assert!(((gv[0] - 5.0) / want - 1.0).abs() < 0.08);
        assert!(e.rayleigh[1] > e.rayleigh[0] && wv[1] > wv[0] && gv[1] > gv[0]);
        let lo = analyse("x", Tail::Min, &x, dt, &s).expect("analysed");
        assert!(
            ((5.0 - lo.rayleigh[0]) / want - 1.0).abs() < 0.03,
            "{}",
            lo.rayleigh[0]
        );
        assert!(lo.sample_extreme < 5.0 && lo.weibull.expect("w").1[0] < 5.0);
    }

    /// Peaks and blocks by hand: a record with three up-crossings of 0 has two complete cycles;
    /// blocks of 3 leave out the partial last one.
    #[test]
    fn peaks_and_blocks_by_hand() {
        let x = [-1.0, 2.0, 3.0, -1.0, 1.0, 4.0, -2.0, 0.5, -1.0, 7.0];
        assert_eq!(upcrossing_peaks(&x, 0.0), vec![3.0, 4.0, 0.5]);
        assert_eq!(block_maxima(&x, 3), vec![3.0, 4.0, 0.5]);
        assert!(analyse("x", Tail::Max, &[1.0, 1.0, 1.0], 0.1, &Settings::default()).is_none());
    }
}
