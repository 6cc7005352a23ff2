//! The band LDLᵀ from both ends (the "twisted" order). A line of at least [`TWIST_MIN`] equations is factorised from both ends at
//! once ([`factor_twisted5`], the "twisted" or "burn at both ends" order of tridiagonal solvers):
//! the equations `0..m` top-down as above, `m+5..n` bottom-up by the same recurrence on the
//! reversed order, and the five in the middle from their Schur complement; the solve sweeps from
//! both ends to the middle and back. Each column's recurrence is a chain of dependent operations
//! (the division by the last pivot, then the next pivot's update; each unknown of a sweep from
//! the one before it) that leaves the processor waiting; two independent chains in one loop
//! overlap. The same operations, another order: the solution agrees with the top-down one to
//! rounding (`twisted_band_is_the_band_to_rounding`), not to the bit. Measured on 2577 equations:
//! the factorisation 27.0 → 24.5 µs, a solve 10.1 → 7.6 µs (`benches/README.md`).

use super::top_down::{
    backward_top5, factor_columns_dyn, forward_rows_dyn, forward_top5, top_column5,
};
use super::SolveError;

/// [`factor_twisted5`], compiled for the baseline processor only: compiled for AVX2 or AVX-512
/// the compiler packs the two ends' scalar recurrences into vectors, and the shuffles between them
/// lengthen the very chains that the two ends are there to overlap (2577 equations, the copy into
/// the band included: 24.5 µs for the baseline, 29.8 µs for AVX-512, against 27.0 µs top-down;
/// `benches/README.md`). The values are the same either way: no fused multiply-adds.
pub(super) fn factor_twisted_dispatch(
    first: &[usize],
    band: &mut [f64],
    m: usize,
    middle: &mut [f64; 25],
) -> Result<(), SolveError> {
    factor_twisted5(first, band, m, middle)
}

/// [`solve_twisted5`] compiled as [`factor_dispatch`] is.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
pub(super) fn solve_twisted_dispatch(
    first: &[usize],
    band: &[f64],
    m: usize,
    middle: &[f64; 25],
    x: &mut [f64],
) {
    solve_twisted5(first, band, m, middle, x)
}

/// Row `i` of column `l` (`l − 5 ≤ i ≤ l`) in the band.
#[inline(always)]
pub(super) fn at(i: usize, l: usize) -> usize {
    l * 6 + 5 + i - l
}

/// The twisted ("burn at both ends") LDLᵀ of a line's half-width-5 band, `P A Pᵀ = L D Lᵀ` in the
/// elimination order `0, 1, …, m−1`, then `n−1, n−2, …, m+5`, then the middle `m, …, m+4`:
///
/// - the top equations `j < m` as [`factor_band5`] does (`L_ji` in column `j`, `i < j`);
/// - the bottom equations `i ≥ m+5` from the last one up, the same recurrence on the reversed
///   order: `t_l = A_il − Σ_{k>l} U_lk t_k` for the equations `l = i+5 … i+1` eliminated before
///   `i`, `U_il = t_l / D_l`, `D_i = A_ii − Σ_l U_il t_l`, `U_il` in place of `A_il` (row `i` of
///   column `l`);
/// - the middle five from their Schur complement `S = A_MM − Σ_top L D Lᵀ − Σ_bottom U D Uᵀ`,
///   densely (`middle`).
///
/// The two ends are independent until the middle, and their columns are computed in the same loop:
/// each column's recurrence is a chain of dependent operations (the division by the last pivot,
/// then the pivot's update) that one end alone leaves the processor waiting on, and two ends
/// overlap. The same operations' count as top-down, a different order: the factor, and the
/// solution, agree with [`factor_band5`]'s to rounding (`twisted_band_is_the_band_to_rounding`).
/// The band's rows are the line's skyline (each column's `first` nondecreasing: the rows of row
/// `i`'s band beyond the diagonal are then `i+1 ..= last` with no gap, and neither end fills in
/// outside them); a place above the skyline is zero (`BandLdlt::above`) and stays zero: the
/// kernels select by `first` and write back what they read there.
#[inline(always)]
pub(super) fn factor_twisted5(
    first: &[usize],
    band: &mut [f64],
    m: usize,
    middle: &mut [f64; 25],
) -> Result<(), SolveError> {
    const W: usize = 5;
    let n = first.len();
    let p = m + W;
    // The first five columns and the last five rows by the general loops.
    factor_columns_dyn(first, W, band, 0..W)?;
    factor_bottom_tail(first, band)?;
    let (mut j, mut i) = (W, n - W - 1);
    while j < m && i >= p {
        top_column5(first, band, j)?;
        bottom_row5(first, band, i)?;
        j += 1;
        i -= 1;
    }
    while j < m {
        top_column5(first, band, j)?;
        j += 1;
    }
    while i >= p {
        bottom_row5(first, band, i)?;
        i -= 1;
    }
    factor_middle5(first, band, m, middle)
}

/// The top end of [`factor_twisted5`] alone: the columns `0..m`, top-down (the partner of a split
/// factorisation does the bottom end at the same time, [`factor_bottom5`]). They read and write
/// the band's columns `0..m` only.
#[inline(always)]
pub(super) fn factor_top5(first: &[usize], band: &mut [f64], m: usize) -> Result<(), SolveError> {
    factor_columns_dyn(first, 5, band, 0..5)?;
    for j in 5..m {
        top_column5(first, band, j)?;
    }
    Ok(())
}

/// The bottom end of [`factor_twisted5`] alone: the rows `n−1` down to `m+5`. They read and write
/// the band's columns `m+5..n` only.
#[inline(always)]
pub(super) fn factor_bottom5(
    first: &[usize],
    band: &mut [f64],
    m: usize,
) -> Result<(), SolveError> {
    factor_bottom_tail(first, band)?;
    for i in (m + 5..first.len() - 5).rev() {
        bottom_row5(first, band, i)?;
    }
    Ok(())
}

/// The last five rows of the bottom end, by the general loops.
#[inline(always)]
pub(super) fn factor_bottom_tail(first: &[usize], band: &mut [f64]) -> Result<(), SolveError> {
    let n = first.len();
    for i in (n - 5..n).rev() {
        bottom_row(first, band, i, i + 1, true)?;
    }
    Ok(())
}

/// The middle five of [`factor_twisted5`] once both ends are factorised: their couplings with
/// either end and the dense LDLᵀ of their Schur complement. They read the band's columns
/// `first[m]..m+10` and write columns `m..m+10`.
#[inline(always)]
pub(super) fn factor_middle5(
    first: &[usize],
    band: &mut [f64],
    m: usize,
    middle: &mut [f64; 25],
) -> Result<(), SolveError> {
    const W: usize = 5;
    let n = first.len();
    let p = m + W;
    // The middle's couplings with either end, t = L·D in place of A: top rows q < m of
    // columns m..m+4, bottom columns l ≥ m+5 of rows m..m+4.
    for c in m..p {
        let lo = first[c];
        for q in lo..m {
            let mut t = band[at(q, c)];
            for k in lo.max(first[q])..q {
                t -= band[at(k, q)] * band[at(k, c)];
            }
            band[at(q, c)] = t;
        }
        bottom_row(first, band, c, p, false)?;
    }
    // S = A_MM − C_top − C_bottom (upper triangle; outside the skyline, zero).
    let mut s = [0.0; 25];
    for a in 0..W {
        let ja = m + a;
        for c in a..W {
            let jc = m + c;
            let mut v = if first[jc] <= ja {
                band[at(ja, jc)]
            } else {
                0.0
            };
            for q in first[jc].max(first[ja])..m {
                v -= band[at(q, ja)] * band[at(q, jc)] / band[at(q, q)];
            }
            for l in p..(ja + W + 1).min(n) {
                if first[l] <= ja {
                    v -= band[at(ja, l)] * band[at(jc, l)] / band[at(l, l)];
                }
            }
            s[5 * a + c] = v;
        }
    }
    // The middle's couplings as L and U.
    for c in m..p {
        for q in first[c]..m {
            band[at(q, c)] /= band[at(q, q)];
        }
        for l in p..(c + W + 1).min(n) {
            if first[l] <= c {
                band[at(c, l)] /= band[at(l, l)];
            }
        }
    }
    // The dense LDLᵀ of S, left-looking as the band's columns.
    for c in 0..W {
        for a in 0..c {
            let mut t = s[5 * a + c];
            for k in 0..a {
                t -= s[5 * k + a] * s[5 * k + c];
            }
            s[5 * a + c] = t;
        }
        let mut d = s[6 * c];
        for a in 0..c {
            let t = s[5 * a + c];
            let l = t / s[6 * a];
            d -= l * t;
            s[5 * a + c] = l;
        }
        if d == 0.0 || !d.is_finite() {
            return Err(SolveError::Singular { equation: m + c });
        }
        s[6 * c] = d;
    }
    *middle = s;
    Ok(())
}

/// Row `i` of the bottom end ([`factor_twisted5`]), general: `t_l` for the columns `l` from
/// `from` to `i+5` (and below `n`) whose skyline holds row `i`, from the last down, in place of
/// `A_il`; with `full`, then `U_il = t_l/D_l` and `D_i`, else the `t_l` are left (the middle's).
#[inline(always)]
pub(super) fn bottom_row(
    first: &[usize],
    band: &mut [f64],
    i: usize,
    from: usize,
    full: bool,
) -> Result<(), SolveError> {
    let hi = (i + 5).min(first.len() - 1);
    for l in (from..=hi).rev().filter(|&l| first[l] <= i) {
        let mut t = band[at(i, l)];
        for k in (l + 1..=hi.min(l + 5)).rev().filter(|&k| first[k] <= i) {
            t -= band[at(l, k)] * band[at(i, k)];
        }
        band[at(i, l)] = t;
    }
    if full {
        let mut d = band[at(i, i)];
        for l in (from..=hi).rev().filter(|&l| first[l] <= i) {
            let t = band[at(i, l)];
            let u = t / band[at(l, l)];
            d -= u * t;
            band[at(i, l)] = u;
        }
        if d == 0.0 || !d.is_finite() {
            return Err(SolveError::Singular { equation: i });
        }
        band[at(i, i)] = d;
    }
    Ok(())
}

/// Row `i` of the bottom end (`i + 5 < n`), unrolled as [`top_column5`]: the columns `l = i+5−a`
/// (`a = 0..5`) after it, `U_il` at row `i` of column `l` (held when `first[l] ≤ i`).
#[inline(always)]
pub(super) fn bottom_row5(first: &[usize], band: &mut [f64], i: usize) -> Result<(), SolveError> {
    const W: usize = 5;
    let (head, rest) = band.split_at_mut((i + 1) * (W + 1));
    // Columns i+1..i+5: column l = i+5−a at win[6(4−a)..]; its row r at win[6(4−a) + 5 + r − l].
    let win: &mut [f64; W * (W + 1)] = (&mut rest[..W * (W + 1)]).try_into().expect("window");
    let fl: &[usize; W] = first[i + 1..i + 1 + W].try_into().expect("firsts");
    let keep = |a: usize| fl[4 - a] <= i;
    let mut c = [0.0; W];
    for (a, ca) in c.iter_mut().enumerate() {
        *ca = win[6 * (4 - a) + a]; // A_il, l = i+5−a
    }
    for a in 0..W {
        let mut t = c[a];
        for b in 0..a {
            // U_{l_a l_b} (l_b = i+5−b > l_a): row l_a of column l_b.
            t -= if keep(b) {
                win[6 * (4 - b) + 5 - (a - b)] * c[b]
            } else {
                0.0
            };
        }
        c[a] = if keep(a) { t } else { c[a] };
    }
    let mut d = head[i * (W + 1) + W];
    for a in 0..W {
        let t = c[a];
        let u = t / win[6 * (4 - a) + 5];
        d -= if keep(a) { u * t } else { 0.0 };
        c[a] = if keep(a) { u } else { t };
    }
    if d == 0.0 || !d.is_finite() {
        return Err(SolveError::Singular { equation: i });
    }
    for (a, ca) in c.iter().enumerate() {
        win[6 * (4 - a) + a] = *ca;
    }
    head[i * (W + 1) + W] = d;
    Ok(())
}

/// The solve with [`factor_twisted5`]'s factor: forward from both ends to the middle, the
/// middle's five densely, backward from the middle to both ends; the two ends' sweeps in the same
/// loops (each a chain of dependent operations; together they overlap), each keeping its last
/// five unknowns in registers as [`solve_band5`] does.
#[inline(always)]
pub(super) fn solve_twisted5(
    first: &[usize],
    band: &[f64],
    m: usize,
    middle: &[f64; 25],
    x: &mut [f64],
) {
    const W: usize = 5;
    let n = first.len();
    let p = m + W;
    // Forward: z_j = b_j − Σ_i L_ji z_i (top), z_i = b_i − Σ_l U_il z_l (bottom).
    forward_rows_dyn(first, W, band, x, 0..W);
    forward_bottom_tail(first, band, x);
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; W] = x[..W].try_into().expect("window");
    // v0..v4 = x_{i+5} .. x_{i+1}.
    let [mut v4, mut v3, mut v2, mut v1, mut v0]: [f64; W] = x[n - W..].try_into().expect("window");
    let (top, bottom) = (forward_top5, forward_bottom5);
    let (mut j, mut i) = (W, n - W - 1);
    while j < m && i >= p {
        let s = top(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (w1, w2, w3, w4, s);
        let r = bottom(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
        j += 1;
        i -= 1;
    }
    while j < m {
        let s = top(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (w1, w2, w3, w4, s);
        j += 1;
    }
    while i >= p {
        let r = bottom(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
        i -= 1;
    }
    let z = solve_middle5(first, band, m, middle, x);
    // Backward: x_j = z_j/D_j − Σ_{q>j} L_qj x_q (top, j descending), x_i = z_i/D_i −
    // Σ_{q<i} U_qi x_q (bottom, i ascending); each from the middle's five.
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; W] = z; // x_{j+1} .. x_{j+5}
    let [mut v0, mut v1, mut v2, mut v3, mut v4]: [f64; W] = z; // x_{i−5} .. x_{i−1}
    let (top, bottom) = (backward_top5, backward_bottom5);
    let (mut j, mut i) = (m, p);
    while j > 0 && i < n {
        j -= 1;
        let s = top(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (s, w0, w1, w2, w3);
        let r = bottom(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
        i += 1;
    }
    while j > 0 {
        j -= 1;
        let s = top(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (s, w0, w1, w2, w3);
    }
    while i < n {
        let r = bottom(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
        i += 1;
    }
}

/// The forward sweep of the last five rows (the bottom end's general start).
#[inline(always)]
pub(super) fn forward_bottom_tail(first: &[usize], band: &[f64], x: &mut [f64]) {
    let n = first.len();
    for i in (n - 5..n).rev() {
        let mut s = x[i];
        for l in (i + 1..n).rev().filter(|&l| first[l] <= i) {
            s -= band[at(i, l)] * x[l];
        }
        x[i] = s;
    }
}

/// The forward sweep of [`solve_twisted5`]'s top end alone (rows `0..m`; reads the band's columns
/// `0..m`), the same operations in the same order.
#[inline(always)]
pub(super) fn forward_top_end5(first: &[usize], band: &[f64], m: usize, x: &mut [f64]) {
    forward_rows_dyn(first, 5, band, x, 0..5);
    let [mut w0, mut w1, mut w2, mut w3, mut w4]: [f64; 5] = x[..5].try_into().expect("window");
    for j in 5..m {
        let s = forward_top5(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (w1, w2, w3, w4, s);
    }
}

/// The forward sweep of [`solve_twisted5`]'s bottom end alone (rows `n−1` down to `m+5`; reads
/// the band's columns `m+6..n`).
#[inline(always)]
pub(super) fn forward_bottom_end5(first: &[usize], band: &[f64], m: usize, x: &mut [f64]) {
    let n = first.len();
    forward_bottom_tail(first, band, x);
    let [mut v4, mut v3, mut v2, mut v1, mut v0]: [f64; 5] = x[n - 5..].try_into().expect("window");
    for i in (m + 5..n - 5).rev() {
        let r = forward_bottom5(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
    }
}

/// The middle five of [`solve_twisted5`] once both forward sweeps are done: their right-hand side
/// less both ends' couplings (`x[first[m]..m]` and `x[m+5..m+10]`), then `L z = r`, `z/D`,
/// `Lᵀ x = z` densely; written into `x[m..m+5]` and returned.
#[inline(always)]
pub(super) fn solve_middle5(
    first: &[usize],
    band: &[f64],
    m: usize,
    middle: &[f64; 25],
    x: &mut [f64],
) -> [f64; 5] {
    const W: usize = 5;
    let n = first.len();
    let p = m + W;
    let mut z = [0.0; W];
    for (a, za) in z.iter_mut().enumerate() {
        let c = m + a;
        let mut s = x[c];
        for q in first[c]..m {
            s -= band[at(q, c)] * x[q];
        }
        for l in p..(c + W + 1).min(n) {
            if first[l] <= c {
                s -= band[at(c, l)] * x[l];
            }
        }
        *za = s;
    }
    for c in 0..W {
        for a in 0..c {
            z[c] -= middle[5 * a + c] * z[a];
        }
    }
    for (c, zc) in z.iter_mut().enumerate() {
        *zc /= middle[6 * c];
    }
    for a in (0..W).rev() {
        for c in a + 1..W {
            z[a] -= middle[5 * a + c] * z[c];
        }
    }
    x[m..p].copy_from_slice(&z);
    z
}

/// The backward sweep of [`solve_twisted5`]'s top end alone, from the middle's five `z` (rows
/// `m−1` down to 0; reads the band's columns `0..m+5`).
#[inline(always)]
pub(super) fn backward_top_end5(band: &[f64], m: usize, z: [f64; 5], x: &mut [f64]) {
    let [mut w0, mut w1, mut w2, mut w3, mut w4] = z;
    for j in (0..m).rev() {
        let s = backward_top5(band, j, x, [w0, w1, w2, w3, w4]);
        x[j] = s;
        (w0, w1, w2, w3, w4) = (s, w0, w1, w2, w3);
    }
}

/// The backward sweep of [`solve_twisted5`]'s bottom end alone, from the middle's five `z` (rows
/// `m+5..n`; reads the band's columns `m+5..n`).
#[inline(always)]
pub(super) fn backward_bottom_end5(band: &[f64], m: usize, z: [f64; 5], x: &mut [f64]) {
    let [mut v0, mut v1, mut v2, mut v3, mut v4] = z;
    for i in m + 5..x.len() {
        let r = backward_bottom5(band, i, x, [v0, v1, v2, v3, v4]);
        x[i] = r;
        (v0, v1, v2, v3, v4) = (v1, v2, v3, v4, r);
    }
}

/// Forward row `i` (`i + 5 < n`) of the bottom end: `z_i = b_i − Σ_l U_il z_l`, `v` =
/// `z_{i+5} .. z_{i+1}`.
#[inline(always)]
pub(super) fn forward_bottom5(band: &[f64], i: usize, x: &[f64], v: [f64; 5]) -> f64 {
    // U_il, l = i+5−a: row i of column l, u[6(4−a) + a].
    let u: &[f64; 30] = band[(i + 1) * 6..][..30].try_into().expect("columns");
    x[i] - u[24] * v[0] - u[19] * v[1] - u[14] * v[2] - u[9] * v[3] - u[4] * v[4]
}

/// Backward row `i ≥ 5` of the bottom end: `x_i = z_i/D_i − Σ_{q<i} U_qi x_q`, `v` =
/// `x_{i−5} .. x_{i−1}`.
#[inline(always)]
pub(super) fn backward_bottom5(band: &[f64], i: usize, x: &[f64], v: [f64; 5]) -> f64 {
    // Row q = i−5+a of column i: col[a].
    let col: &[f64; 6] = band[i * 6..][..6].try_into().expect("column");
    x[i] / col[5] - col[0] * v[0] - col[1] * v[1] - col[2] * v[2] - col[3] * v[3] - col[4] * v[4]
}
