//! Sine, cosine and exponential for the wave-kinematics loops: branch-free, so that a loop over
//! wave components compiles to straight-line (and, where the target allows, SIMD) code, and
//! accurate to a few units in the last place over the arguments waves produce.
//!
//! Why by hand: the sums over hundreds of wave components at every node near the surface were
//! two thirds of a storm step, nearly all of it in the C library's `sincos`, `cos` and `exp`
//! (a profile of `benches/dynamics.rs` `waves/step_400_components`). The C library's functions
//! are correctly rounded for any argument, with branches for huge ones; the phases here are
//! below 10⁴ rad after reduction by 2π and the exponents are non-positive. No maintained crate
//! offers a scalar, branch-free, deterministic pair (the SIMD-math crates need nightly or a
//! target feature); these are the classic fdlibm kernels (Sun Microsystems, 1993, freely
//! distributable) with the magic-number rounding trick instead of a float-to-integer branch.
//!
//! **sin/cos.** `x = nπ/2 + r` with `n` the nearest integer to `2x/π` and
//! `r = ((x − n·p₁) − n·p₂) − n·p₃` (Cody–Waite, π/2 split in three so that `n·p₁` and `n·p₂` are
//! exact for |n| < 2²⁰), `|r| ≤ π/4`; then fdlibm's `__kernel_sin` / `__kernel_cos` minimax
//! polynomials and the quadrant `n mod 4`. Absolute error below 2e-16 for |x| ≤ 1.6·10⁶
//! (tested against the C library to 4e-16 over |x| ≤ 10⁴).
//!
//! **exp.** `x = n·ln2 + r`, `|r| ≤ ln2/2`, `e^r` by a degree-13 Taylor polynomial (truncation
//! below 1e-17 relative), scaled by `2ⁿ` built in the exponent bits. Arguments below −708 give 0
//! (the components it is used for have decayed to nothing there); the relative error is below
//! 3e-16 (tested to 1e-15 over [−700, 0]). Only for `x ≤ 0`.

/// `1.5·2⁵²`: adding it rounds a double of magnitude below 2⁵¹ to an integer held in the low
/// bits of the sum's mantissa.
const SHIFTER: f64 = 6_755_399_441_055_744.0;

/// `(sin x, cos x)`.
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    const TWO_OVER_PI: f64 = std::f64::consts::FRAC_2_PI;
    const P1: f64 = 1.570_796_326_734_125_6; // the first 33 bits of π/2
    const P2: f64 = 6.077_100_506_303_966e-11; // the next 33
    const P3: f64 = 2.022_266_248_795_950_6e-21; // the rest
    const S1: f64 = -1.666_666_666_666_663_2e-1;
    const S2: f64 = 8.333_333_333_322_49e-3;
    const S3: f64 = -1.984_126_982_985_795e-4;
    const S4: f64 = 2.755_731_370_707_006_8e-6;
    const S5: f64 = -2.505_076_025_340_686_3e-8;
    const S6: f64 = 1.589_690_995_211_55e-10;
    const C1: f64 = 4.166_666_666_666_66e-2;
    const C2: f64 = -1.388_888_888_887_411e-3;
    const C3: f64 = 2.480_158_728_947_673e-5;
    const C4: f64 = -2.755_731_435_139_066_3e-7;
    const C5: f64 = 2.087_572_321_298_175e-9;
    const C6: f64 = -1.135_964_755_778_819_5e-11;
    let shifted = x * TWO_OVER_PI + SHIFTER;
    let q = shifted.to_bits(); // n in the low bits (two's complement modulo 2^51)
    let n = shifted - SHIFTER;
    let r = ((x - n * P1) - n * P2) - n * P3;
    let z = r * r;
    let s = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    let c = 1.0 - 0.5 * z + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    // Quadrant n mod 4: (sin, cos) = (s, c), (c, −s), (−s, −c), (−c, s), with bit masks rather
    // than branches (the quadrant is random from one component to the next).
    let swap = 0u64.wrapping_sub(q & 1);
    let (sb, cb) = (s.to_bits(), c.to_bits());
    let sn = (sb & !swap) | (cb & swap);
    let cs = (cb & !swap) | (sb & swap);
    let sin_sign = ((q >> 1) & 1) << 63;
    let cos_sign = ((q.wrapping_add(1) >> 1) & 1) << 63;
    (f64::from_bits(sn ^ sin_sign), f64::from_bits(cs ^ cos_sign))
}

/// fdlibm's `atan`: `atan` at the reduction points 0.5, 1, 1.5 and ∞, in a high part and a low part.
const HI: [f64; 4] = [
    4.636_476_090_008_061e-1,
    std::f64::consts::FRAC_PI_4,
    9.827_937_232_473_29e-1,
    std::f64::consts::FRAC_PI_2,
];
const LO: [f64; 4] = [
    2.269_877_745_296_168_7e-17,
    3.061_616_997_868_383e-17,
    1.390_331_103_123_099_8e-17,
    6.123_233_995_736_766e-17,
];
/// fdlibm's `atan` series coefficients.
const AT: [f64; 11] = [
    3.333_333_333_333_293e-1,
    -1.999_999_999_987_648_3e-1,
    1.428_571_427_250_346_6e-1,
    -1.111_111_040_546_235_6e-1,
    9.090_887_133_436_507e-2,
    -7.691_876_205_044_83e-2,
    6.661_073_137_387_531e-2,
    -5.833_570_133_790_573e-2,
    4.976_877_994_615_932e-2,
    -3.653_157_274_421_691_6e-2,
    1.628_582_011_536_578_2e-2,
];
/// 2⁶⁶: from there on `atan` is π/2 in a double.
const TWO_POW_66: f64 = 7.378_697_629_483_821e19;
/// π's low part (fdlibm's `pi_lo`).
const PI_LO: f64 = 1.224_646_799_147_353_2e-16;

/// fdlibm's `atan` series of the reduced argument, `s1 + s2` (the caller forms `t·(s1 + s2)`).
#[inline(always)]
fn atan_series(t: f64) -> f64 {
    let z = t * t;
    let w = z * z;
    let s1 = z * (AT[0] + w * (AT[2] + w * (AT[4] + w * (AT[6] + w * (AT[8] + w * AT[10])))));
    let s2 = w * (AT[1] + w * (AT[3] + w * (AT[5] + w * (AT[7] + w * AT[9]))));
    s1 + s2
}

/// `atan(x)` for finite `x` (fdlibm's `atan`: reduction to |x| < 7/16 about 0.5, 1, 1.5 or ∞,
/// then an 11-term odd polynomial; error below one unit in the last place).
#[inline]
fn atan(x: f64) -> f64 {
    let a = x.abs();
    if a >= TWO_POW_66 {
        // |x| ≥ 2⁶⁶
        return (HI[3] + LO[3]).copysign(x);
    }
    let (id, t) = if a < 0.4375 {
        (None, x)
    } else if a < 0.6875 {
        (Some(0), (2.0 * a - 1.0) / (2.0 + a))
    } else if a < 1.1875 {
        (Some(1), (a - 1.0) / (a + 1.0))
    } else if a < 2.4375 {
        (Some(2), (a - 1.5) / (1.0 + 1.5 * a))
    } else {
        (Some(3), -1.0 / a)
    };
    let series = atan_series(t);
    match id {
        None => t - t * series,
        Some(i) => (HI[i] - ((t * series - LO[i]) - t)).copysign(x),
    }
}

/// `atan2(y, x)`, the angle of `(x, y)` in (−π, π], for finite arguments (within two units in the
/// last place of the C library's: the quotient `y/x` adds one). `(0, 0)` gives 0 and a NaN gives
/// NaN, as the C library does.
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    use std::f64::consts::PI;
    if x.is_nan() || y.is_nan() {
        return f64::NAN;
    }
    if x == 0.0 {
        return if y == 0.0 {
            if x.is_sign_negative() {
                PI.copysign(y)
            } else {
                y
            }
        } else {
            std::f64::consts::FRAC_PI_2.copysign(y)
        };
    }
    let z = atan((y / x).abs());
    if x > 0.0 {
        z.copysign(y)
    } else {
        // π − z, with π's low part (fdlibm's pi_lo) kept.
        (PI - (z - PI_LO)).copysign(y)
    }
}

/// [`atan2`] of `L` pairs at once, without branches (the five reductions of [`atan`] chosen by
/// selects, so that the loops vectorise): the same operations in the same order as [`atan2`], so
/// the same values to the bit, wherever [`atan2`] takes its common path. Lanes where it does not
/// (`x = 0`, a NaN, `|y/x| ≥ 2⁶⁶`) are flagged in the returned mask for the caller to redo with
/// [`atan2`].
#[inline(always)]
// A NaN must count as special: hence `!(a < b)`, not `a >= b`.
#[allow(clippy::needless_range_loop, clippy::neg_cmp_op_on_partial_ord)]
pub fn atan2_lanes<const L: usize>(y: &[f64; L], x: &[f64; L], out: &mut [f64; L]) -> bool {
    use std::f64::consts::PI;
    // Stage by stage over the lanes, each choice a select of values computed for every lane: in
    // one loop with the reductions as an `if` chain the compiler kept the lanes scalar, with
    // branches. A nested select from the last reduction to the first picks what the chain picks
    // (each bound implies the next).
    let mut a = [0.0; L];
    let mut special = [false; L];
    for k in 0..L {
        a[k] = (y[k] / x[k]).abs();
        // `!(a < 2⁶⁶)` also catches a NaN (from x = 0 = y or a NaN argument); x = 0 alone gives ∞.
        special[k] = !(a[k] < TWO_POW_66) | (x[k] == 0.0);
    }
    // One operation over the lanes per loop: each loop becomes one vector instruction.
    let mut num = [-1.0; L];
    let mut den = a;
    let mut hi = [HI[3]; L];
    let mut lo = [LO[3]; L];
    for k in 0..L {
        let c3 = a[k] < 2.4375;
        num[k] = if c3 { a[k] - 1.5 } else { num[k] };
        den[k] = if c3 { 1.0 + 1.5 * a[k] } else { den[k] };
        hi[k] = if c3 { HI[2] } else { hi[k] };
        lo[k] = if c3 { LO[2] } else { lo[k] };
    }
    for k in 0..L {
        let c2 = a[k] < 1.1875;
        num[k] = if c2 { a[k] - 1.0 } else { num[k] };
        den[k] = if c2 { a[k] + 1.0 } else { den[k] };
        hi[k] = if c2 { HI[1] } else { hi[k] };
        lo[k] = if c2 { LO[1] } else { lo[k] };
    }
    for k in 0..L {
        let c1 = a[k] < 0.6875;
        num[k] = if c1 { 2.0 * a[k] - 1.0 } else { num[k] };
        den[k] = if c1 { 2.0 + a[k] } else { den[k] };
        hi[k] = if c1 { HI[0] } else { hi[k] };
        lo[k] = if c1 { LO[0] } else { lo[k] };
    }
    let mut t = [0.0; L];
    for k in 0..L {
        let c0 = a[k] < 0.4375;
        num[k] = if c0 { a[k] } else { num[k] };
        den[k] = if c0 { 1.0 } else { den[k] };
    }
    for k in 0..L {
        // t = a exactly in the first reduction (a / 1).
        t[k] = num[k] / den[k];
    }
    for k in 0..L {
        let t = t[k];
        let series = atan_series(t);
        let reduced = hi[k] - ((t * series - lo[k]) - t);
        let direct = t - t * series;
        let z = if a[k] < 0.4375 { direct } else { reduced };
        let r = if x[k] > 0.0 { z } else { PI - (z - PI_LO) };
        out[k] = r.copysign(y[k]);
    }
    special.iter().any(|s| *s)
}

/// `eˣ` for `x ≤ 0`.
#[inline(always)]
pub fn exp_nonpositive(x: f64) -> f64 {
    const LOG2E: f64 = std::f64::consts::LOG2_E;
    const LN2_HI: f64 = 6.931_471_803_691_238e-1;
    const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
    let x = x.max(-708.0);
    let shifted = x * LOG2E + SHIFTER;
    let n = shifted - SHIFTER;
    let r = (x - n * LN2_HI) - n * LN2_LO;
    // e^r, |r| ≤ 0.347: Taylor to r¹³ (Horner).
    let mut p = 1.0 / 6_227_020_800.0;
    for c in [
        1.0 / 479_001_600.0,
        1.0 / 39_916_800.0,
        1.0 / 3_628_800.0,
        1.0 / 362_880.0,
        1.0 / 40_320.0,
        1.0 / 5_040.0,
        1.0 / 720.0,
        1.0 / 120.0,
        1.0 / 24.0,
        1.0 / 6.0,
        0.5,
        1.0,
        1.0,
    ] {
        p = p * r + c;
    }
    // 2^n in the exponent bits: n ≥ −1022 here, so 1023 + n ≥ 1 (normal numbers only).
    let bits = (shifted.to_bits().wrapping_add(1023)) << 52;
    p * f64::from_bits(bits)
}

/// Lanes of [`lane_sum`] and [`lane_dot`].
pub const LANES: usize = 8;

/// The eight partial sums of [`lane_sum`] added in a fixed order.
#[inline(always)]
pub fn combine_lanes(acc: [f64; LANES]) -> f64 {
    ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7]))
}

/// `Σ vᵢ` as eight interleaved partial sums (`vᵢ` into lane `i mod 8`), combined by
/// [`combine_lanes`]. One running sum is a chain of dependent additions (four cycles each, whatever
/// the vector width); eight independent lanes fill a vector register, and the compiler may
/// vectorise them because each lane keeps its own order: the same IEEE operations in the same order
/// on every processor, so the result is the same to the bit with or without SIMD. (It differs from
/// the left-to-right sum by rounding only.)
#[inline(always)]
pub fn lane_sum(v: &[f64]) -> f64 {
    let mut acc = [0.0; LANES];
    let mut chunks = v.chunks_exact(LANES);
    for c in &mut chunks {
        for j in 0..LANES {
            acc[j] += c[j];
        }
    }
    for (a, x) in acc.iter_mut().zip(chunks.remainder()) {
        *a += x;
    }
    combine_lanes(acc)
}

/// `Σ aᵢ bᵢ` in the lanes of [`lane_sum`] (the products rounded, then added lane by lane).
#[inline(always)]
pub fn lane_dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0; LANES];
    let (mut ca, mut cb) = (a.chunks_exact(LANES), b.chunks_exact(LANES));
    for (x, y) in (&mut ca).zip(&mut cb) {
        for j in 0..LANES {
            acc[j] += x[j] * y[j];
        }
    }
    for ((s, x), y) in acc.iter_mut().zip(ca.remainder()).zip(cb.remainder()) {
        *s += x * y;
    }
    combine_lanes(acc)
}

#[cfg(test)]
mod tests {

    /// [`atan2_lanes`] gives [`atan2`] to the bit wherever it does not flag a lane: every
    /// reduction of the arctangent (|y/x| below 7/16, up to 11/16, 19/16, 39/16 and beyond) in
    /// every quadrant, and flags `x = 0`, NaNs and `|y/x| ≥ 2⁶⁶`.
    #[test]
    fn atan2_lanes_is_atan2_to_the_bit() {
        let ratios = [
            0.0, 1e-300, 0.1, 0.4374, 0.4375, 0.6, 0.6875, 1.0, 1.1875, 2.0, 2.4375, 1e6,
        ];
        let mut flagged = 0;
        for &r in &ratios {
            for k in 0..200 {
                let x = (1.0 + 0.37 * k as f64) * if k % 2 == 0 { 1.0 } else { -1.0 };
                for sy in [1.0, -1.0] {
                    let y = [sy * r * x.abs() * (1.0 + 1e-3 * k as f64); 2];
                    let mut out = [0.0; 2];
                    assert!(!atan2_lanes(&y, &[x; 2], &mut out));
                    assert_eq!(
                        out[0].to_bits(),
                        atan2(y[0], x).to_bits(),
                        "atan2({}, {x})",
                        y[0]
                    );
                }
            }
        }
        for (y, x) in [
            (1.0, 0.0),
            (0.0, 0.0),
            (f64::NAN, 1.0),
            (1.0, f64::NAN),
            (1e300, 1e-300),
        ] {
            let mut out = [0.0; 1];
            if atan2_lanes(&[y], &[x], &mut out) {
                flagged += 1;
            }
        }
        assert_eq!(flagged, 5);
    }

    use super::*;

    #[test]
    fn sin_cos_matches_the_c_library() {
        let mut worst: f64 = 0.0;
        let mut x = -1.0e4;
        while x < 1.0e4 {
            let (s, c) = sin_cos(x);
            let (s0, c0) = x.sin_cos();
            worst = worst.max((s - s0).abs()).max((c - c0).abs());
            x += 0.012_345_678_9;
        }
        // Small arguments and quadrant boundaries.
        for k in -8..=8 {
            for d in [-1e-9, 0.0, 1e-9] {
                let x = k as f64 * std::f64::consts::FRAC_PI_4 + d;
                let (s, c) = sin_cos(x);
                worst = worst.max((s - x.sin()).abs()).max((c - x.cos()).abs());
            }
        }
        assert!(worst < 4e-16, "worst absolute error {worst:e}");
        // A wrong quadrant or a dropped polynomial term is far beyond this.
        assert!((sin_cos(2.0).0 - 2f64.sin()).abs() < 4e-16);
        assert!((sin_cos(-4.0).1 - (-4f64).cos()).abs() < 4e-16);
    }

    #[test]
    fn atan2_matches_the_c_library() {
        let mut worst: f64 = 0.0;
        let mut state: u64 = 7;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..200_000 {
            let (y, x) = (
                next() * 10f64.powf(6.0 * next()),
                next() * 10f64.powf(6.0 * next()),
            );
            let (a, b) = (atan2(y, x), y.atan2(x));
            worst = worst.max((a - b).abs() / b.abs().max(1e-300));
        }
        assert!(worst < 5e-16, "worst relative error {worst:e}");
        for (y, x) in [
            (0.0, 1.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (1.0, 1.0),
            (-1.0, -1.0),
            (1e-300, 1.0),
            (1.0, 1e-300),
        ] {
            let (a, b): (f64, f64) = (atan2(y, x), y.atan2(x));
            assert!(
                (a - b).abs() <= 4.5e-16 * b.abs(),
                "atan2({y}, {x}) = {a}, C library {b}"
            );
        }
        assert!(atan2(f64::NAN, 1.0).is_nan());
    }

    #[test]
    fn exp_matches_the_c_library() {
        let mut worst: f64 = 0.0;
        let mut x = -700.0;
        while x <= 0.0 {
            let e = exp_nonpositive(x);
            worst = worst.max((e / x.exp() - 1.0).abs());
            x += 0.001_234_567;
        }
        assert!(worst < 1e-15, "worst relative error {worst:e}");
        assert_eq!(exp_nonpositive(0.0), 1.0);
        assert_eq!(exp_nonpositive(-1e6), exp_nonpositive(-708.0));
        assert!(exp_nonpositive(-1e6) < 1e-307);
    }

    #[test]
    fn lane_sums_are_sums() {
        // Exact on integers (every partial sum representable), for every remainder length.
        for n in 0..40 {
            let v: Vec<f64> = (0..n).map(|i| (i * i) as f64 - 7.0).collect();
            let w: Vec<f64> = (0..n).map(|i| 3.0 - i as f64).collect();
            let sum: f64 = v.iter().sum();
            let dot: f64 = v.iter().zip(&w).map(|(a, b)| a * b).sum();
            assert_eq!(lane_sum(&v), sum, "{n}");
            assert_eq!(lane_dot(&v, &w), dot, "{n}");
        }
        // Element 8 goes into lane 0, with element 0, before the lanes are combined: 1 + 1e-16
        // rounds to 1 there, and cancels with element 1 (left to right it would survive).
        let mut v = vec![0.0; 9];
        (v[0], v[1], v[8]) = (1.0, -1.0, 1e-16);
        assert_eq!(v.iter().sum::<f64>(), 1e-16);
        assert_eq!(lane_sum(&v), 0.0);
    }
}
