//! The band LDLᵀ top-down (see [`super`] for the band's layout): the general loops over each
//! column's skyline for any half-width up to [`super::BAND_LIMIT`], and their unrolled twin for a
//! line's half-width 5.
//!
//! **Band LDLᵀ** (no pivoting, like faer's; the tangent is symmetric and, at a converged state,
//! positive definite; an indefinite but nonsingular matrix factors too):
//!
//! **Why more than one path, and what each buys.** The band's general loops (any half-width up to
//! [`BAND_LIMIT`]) are the reference; for a line's half-width 5 the same operations in the same
//! order are unrolled over five fixed rows (`factor_band5`, `solve_band5`: the unknowns in
//! registers, the backward sweep gathering instead of scattering), kept for the speed they were
//! measured to buy — the heave benchmark's dynamics 0.230 → 0.188 s (−18 %), the factorisation's
//! share of the run 13 % → 8 % and the solves' 14 % → 7 % (`benches/README.md`) — and held to the
//! general loops to the bit by `unrolled_band_is_the_general_band_to_the_bit`. faer's LDLᵀ serves
//! patterns wider than a band (held to the band to rounding by `band_and_sparse_agree`).

use super::SolveError;

/// [`BandLdlt::factor`] compiled for the baseline processor and for AVX2 and AVX-512, chosen at
/// run time (no fused multiply-adds: the same values to the bit).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
pub(super) fn factor_dispatch(
    w: usize,
    first: &[usize],
    band: &mut [f64],
) -> Result<(), SolveError> {
    // A beam line's half-width (5) as a constant: the column's slices have a known bound.
    // The same arithmetic in the same order as the general path.
    match w {
        5 => factor_band::<5>(first, band),
        w => factor_band_dyn(first, w, band),
    }
}

/// [`BandLdlt::solve_in_place`] compiled as [`factor_dispatch`] is.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
pub(super) fn solve_dispatch(w: usize, first: &[usize], band: &[f64], x: &mut [f64]) {
    match w {
        5 => solve_band::<5>(first, band, x),
        w => solve_band_dyn(first, w, band, x),
    }
}

/// [`BandLdlt::factor`] for a half-width known at compile time: a beam line's 5 unrolled
/// ([`factor_band5`]), any other through the general loops.
#[inline(always)]
pub(super) fn factor_band<const W: usize>(
    first: &[usize],
    band: &mut [f64],
) -> Result<(), SolveError> {
    if W == 5 {
        factor_band5(first, band)
    } else {
        factor_band_dyn(first, W, band)
    }
}

/// [`BandLdlt::solve_in_place`] for a half-width known at compile time, as [`factor_band`].
#[inline(always)]
pub(super) fn solve_band<const W: usize>(first: &[usize], band: &[f64], x: &mut [f64]) {
    if W == 5 {
        solve_band5(first, band, x)
    } else {
        solve_band_dyn(first, W, band, x)
    }
}

/// [`factor_band_dyn`] for half-width 5, each column's loops unrolled over the five rows above
/// the diagonal: a row or a product outside the skyline is not taken (a select, not a branch on
/// data), every kept operation is the general loop's, in its order, so the factor is the same to
/// the bit (`unrolled_band_is_the_general_band_to_the_bit`). The general loops' trip counts vary
/// with each column's skyline (3, 4 or 5 rows up) and their bookkeeping, not the arithmetic,
/// was most of the factorisation's time.
#[inline(always)]
pub(super) fn factor_band5(first: &[usize], band: &mut [f64]) -> Result<(), SolveError> {
    const W: usize = 5;
    let n = first.len();
    let head = n.min(W);
    factor_columns_dyn(first, W, band, 0..head)?;
    for j in head..n {
        top_column5(first, band, j)?;
    }
    Ok(())
}

/// Column `j ≥ 5` of [`factor_band5`]: `L_ji` for the rows `i` of its skyline and `D_j`, from
/// the five columns before it.
#[inline(always)]
pub(super) fn top_column5(first: &[usize], band: &mut [f64], j: usize) -> Result<(), SolveError> {
    const W: usize = 5;
    let lo = first[j];
    let (before, rest) = band.split_at_mut(j * (W + 1));
    let col: &mut [f64; W + 1] = (&mut rest[..W + 1]).try_into().expect("column");
    // Columns j−5..j−1; row k = j−5+b of column i = j−5+a is cols[6a + 5 + b − a].
    let cols: &[f64; W * (W + 1)] = before[(j - W) * (W + 1)..].try_into().expect("columns");
    let fi: &[usize; W] = first[j - W..j].try_into().expect("firsts");
    let mut c = *col;
    for a in 0..W {
        let i = j - W + a;
        let klo = lo.max(fi[a]);
        let mut t = c[a];
        for b in 0..a {
            // A product outside the skyline subtracts +0: exactly nothing.
            t -= if j - W + b >= klo {
                cols[a * (W + 1) + W + b - a] * c[b]
            } else {
                0.0
            };
        }
        c[a] = if i >= lo { t } else { c[a] };
    }
    let mut d = c[W];
    for a in 0..W {
        let t = c[a];
        let l = t / cols[a * (W + 1) + W];
        let keep = j - W + a >= lo; // row i = j−5+a is in the skyline
        d -= if keep { l * t } else { 0.0 };
        c[a] = if keep { l } else { t };
    }
    if d == 0.0 || !d.is_finite() {
        return Err(SolveError::Singular { equation: j });
    }
    c[W] = d;
    *col = c;
    Ok(())
}

/// [`solve_band_dyn`] for half-width 5, unrolled as [`factor_band5`]: the forward sweep keeps the
/// last five unknowns in registers; the backward sweep gathers each unknown's terms from the
/// columns below it (`x_i ← x_i/D_i − Σ_{j=i+5..i+1} L_ji x_j`, j descending) instead of
/// scattering each column into the unknowns above it: the same operations in the same order, the
/// same values to the bit, and no store of a vector overlapping the next column's load.
#[inline(always)]
pub(super) fn solve_band5(first: &[usize], band: &[f64], x: &mut [f64]) {
    const W: usize = 5;
    let n = first.len();
    if n <= W {
        return solve_band_dyn(first, W, band, x);
    }
    // Forward: z_j = b_j − Σ_{i=lo..j−1} L_ji z_i, the first five rows by the general loop.
    forward_rows_dyn(first, W, band, x, 0..W);
    // The last five unknowns, x_{j−5} .. x_{j−1}, in registers (a window array would go through
    // the stack, each row's scalar store then read back as a vector).
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; W] = x[..W].try_into().expect("window");
    for j in W..n {
        let lo = first[j];
        let l: &[f64; W + 1] = band[j * (W + 1)..][..W + 1].try_into().expect("column");
        // A row outside the skyline subtracts +0 (exactly nothing), the select off the chain.
        let term = |a: usize, xi: f64| if j - W + a >= lo { l[a] * xi } else { 0.0 };
        let s = x[j] - term(0, w0) - term(1, w1) - term(2, w2) - term(3, w3) - term(4, w4);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (w1, w2, w3, w4, s);
    }
    // Backward: x_i = z_i/D_i − Σ_j L_ji x_j over the columns j > i whose skyline reaches row i,
    // in descending j (the order in which the column-oriented sweep subtracts them).
    let tail = n - W;
    for i in (tail..n).rev() {
        let mut s = x[i] / band[i * (W + 1) + W];
        for j in (i + 1..n).rev() {
            if first[j] <= i {
                s -= band[j * (W + 1) + W + i - j] * x[j];
            }
        }
        x[i] = s;
    }
    // x_{i+1} .. x_{i+5} in registers.
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; W] = x[tail..].try_into().expect("window");
    for i in (0..tail).rev() {
        let f: &[usize; W] = first[i + 1..][..W].try_into().expect("firsts");
        let below = &band[(i + 1) * (W + 1)..][..W * (W + 1)];
        // Column j = i+1+b, row i: below[6b + 5 + i − j] = below[6b + 4 − b].
        let term = |b: usize, xj: f64| {
            if f[b] <= i {
                below[b * (W + 1) + W - 1 - b] * xj
            } else {
                0.0
            }
        };
        let s = x[i] / band[i * (W + 1) + W]
            - term(4, w4)
            - term(3, w3)
            - term(2, w2)
            - term(1, w1)
            - term(0, w0);
        x[i] = s;
        (w0, w1, w2, w3, w4) = (s, w0, w1, w2, w3);
    }
}

/// Forward row `j ≥ 5` of the top end: `z_j = b_j − Σ_i L_ji z_i`, `w` = `z_{j−5} .. z_{j−1}`
/// (zeros above the skyline).
#[inline(always)]
pub(super) fn forward_top5(band: &[f64], j: usize, x: &[f64], w: [f64; 5]) -> f64 {
    let l: &[f64; 6] = band[j * 6..][..6].try_into().expect("column");
    x[j] - l[0] * w[0] - l[1] * w[1] - l[2] * w[2] - l[3] * w[3] - l[4] * w[4]
}

/// Backward row `j` (`j + 5 < n`) of the top end: `x_j = z_j/D_j − Σ_{q>j} L_qj x_q`, `w` =
/// `x_{j+1} .. x_{j+5}`.
#[inline(always)]
pub(super) fn backward_top5(band: &[f64], j: usize, x: &[f64], w: [f64; 5]) -> f64 {
    // Column q = j+1+b, row j: below[6b + 4 − b].
    let below: &[f64; 30] = band[(j + 1) * 6..][..30].try_into().expect("columns");
    x[j] / band[j * 6 + 5]
        - below[24] * w[4]
        - below[18 + 1] * w[3]
        - below[12 + 2] * w[2]
        - below[6 + 3] * w[1]
        - below[4] * w[0]
}

/// The general band factorisation over all columns.
#[inline(always)]
pub(super) fn factor_band_dyn(
    first: &[usize],
    w: usize,
    band: &mut [f64],
) -> Result<(), SolveError> {
    factor_columns_dyn(first, w, band, 0..first.len())
}

/// The band factorisation (see the module docs) over each column's skyline: a row above a
/// column's first stored row stays zero in the factor (no fill above the first nonzero), so
/// leaving it out changes no value; `#[inline(always)]` so that a constant `w` from
/// [`factor_band`] specialises it.
#[inline(always)]
pub(super) fn factor_columns_dyn(
    first: &[usize],
    w: usize,
    band: &mut [f64],
    columns: std::ops::Range<usize>,
) -> Result<(), SolveError> {
    for j in columns {
        let lo = first[j];
        // Column j holds rows j−w..=j at band[cj ..= cj + w]; its skyline starts at row lo.
        let cj = j * (w + 1);
        let (before, col_j) = band.split_at_mut(cj);
        let col_j = &mut col_j[..w + 1];
        let off_j = w - j; // row r of column j is col_j[r + off_j] (r ≥ lo)
                           // t_i = A_ij − Σ_{k = max(lo, first_i)}^{i−1} L_ik t_k, in place of A_ij.
        for i in lo..j {
            let klo = lo.max(first[i]);
            let off_i = i * (w + 1) + w - i; // row r of column i is before[r + off_i]
            let l_i = &before[klo + off_i..i + off_i];
            let t_k = &col_j[klo + off_j..i + off_j];
            let mut t = col_j[i + off_j];
            for (l, tk) in l_i.iter().zip(t_k) {
                t -= l * tk;
            }
            col_j[i + off_j] = t;
        }
        let mut d = col_j[w];
        for i in lo..j {
            let t = col_j[i + off_j];
            let l = t / before[i * (w + 1) + w];
            d -= l * t;
            col_j[i + off_j] = l;
        }
        if d == 0.0 || !d.is_finite() {
            return Err(SolveError::Singular { equation: j });
        }
        col_j[w] = d;
    }
    Ok(())
}

/// The forward sweep `z_j = b_j − Σ_{i=lo..j−1} L_ji z_i` over the rows `rows`, in place.
#[inline(always)]
pub(super) fn forward_rows_dyn(
    first: &[usize],
    w: usize,
    band: &[f64],
    x: &mut [f64],
    rows: std::ops::Range<usize>,
) {
    for j in rows {
        let lo = first[j];
        let cj = j * (w + 1) + w - j;
        let mut s = x[j];
        for (li, xi) in band[lo + cj..j + cj].iter().zip(&x[lo..j]) {
            s -= li * xi;
        }
        x[j] = s;
    }
}

/// The band solve over each column's skyline; `#[inline(always)]` for the same reason as
/// [`factor_band_dyn`].
#[inline(always)]
pub(super) fn solve_band_dyn(first: &[usize], w: usize, band: &[f64], x: &mut [f64]) {
    let n = first.len();
    forward_rows_dyn(first, w, band, x, 0..n);
    for (j, xj) in x.iter_mut().enumerate().take(n) {
        *xj /= band[j * (w + 1) + w];
    }
    for (j, &lo) in first.iter().enumerate().rev() {
        let cj = j * (w + 1) + w - j;
        let l = &band[lo + cj..j + cj];
        let xj = x[j];
        for (xi, li) in x[lo..j].iter_mut().zip(l) {
            *xi -= li * xj;
        }
    }
}
