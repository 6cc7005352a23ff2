//! The twisted band factorisation and solve on two threads: the top end on the caller's thread,
//! the bottom end on a [`Partner`] thread, the middle five on the caller's.
//!
//! The twisted order ([`super::twisted::factor_twisted5`]) makes the two ends independent until the middle:
//! the top end reads and writes the band's columns `0..m`, the bottom end its columns `m+5..n`.
//! So the band is kept in two stores: the caller's (the [`BandLdlt`]'s own, columns `0..m+5`)
//! and the partner's (columns `m+5..n`). Each thread runs exactly the kernels the one-thread
//! factorisation runs on those columns, only not interleaved with the other end's, so every value
//! is the same to the bit (`split_band_is_the_twisted_band_to_the_bit`). What crosses between the
//! threads:
//!
//! - factorisation: the bottom columns' values (copied into the partner's store before it
//!   starts), then the five columns `m+5..m+10` that the middle reads (to the caller) and writes
//!   (back to the partner): 60 numbers;
//! - solve: the bottom half of the right-hand side (to the partner), the five unknowns `m+5..m+10`
//!   after the forward sweeps (to the caller), the middle's five (to the partner), and the bottom
//!   half of the solution (back).
//!
//! Each factorisation and each solve meets the partner twice. Which zero pivot a factorisation
//! names, when both ends have one, is the top end's (one thread names whichever its interleaved
//! loop meets first); the values of a factorisation that succeeds do not depend on it.
//!
//! Handed the bottom columns and half the right-hand side from the caller, this gains little
//! (`benches/README.md`): the copies cost what the split saves. [`BandLdlt::factor_side`] and
//! [`BandLdlt::solve_side`] are the same split for two threads that each hold a copy of the band
//! and fill their own columns from their own assembly (each thread running the same Newton loop
//! on its part of the line, issue 48): only the five columns at the middle (factorisation) and
//! ten unknowns (solve) cross, at a pair of [`Seat`]s.

use super::twisted::{
    backward_bottom_end5, backward_top_end5, factor_bottom5, factor_middle5, factor_top5,
    forward_bottom_end5, forward_top_end5, solve_middle5,
};
use super::{BandLdlt, SolveError, SparseSym};
use crate::partner::{Partner, Seat};

/// The partner's job: factorise the bottom end.
const FACTOR: u8 = 1;
/// The partner's job: the bottom end's forward sweep.
const FORWARD: u8 = 2;
/// The partner's job: the bottom end's backward sweep.
const BACKWARD: u8 = 3;

/// The partner's store: the band's bottom columns and the right-hand side's bottom half (each
/// full length, the top part unused), and the last factorisation's outcome.
#[derive(Debug)]
pub(super) struct Bottom {
    first: Vec<usize>,
    m: usize,
    band: Vec<f64>,
    x: Vec<f64>,
    result: Result<(), SolveError>,
}

/// The partner's job function.
fn job(b: &mut Bottom, code: u8) {
    let m = b.m;
    match code {
        FACTOR => b.result = factor_bottom5(&b.first, &mut b.band, m),
        FORWARD => forward_bottom_end5(&b.first, &b.band, m, &mut b.x),
        BACKWARD => {
            let z: [f64; 5] = b.x[m..m + 5].try_into().expect("the middle's five");
            backward_bottom_end5(&b.band, m, z, &mut b.x);
        }
        _ => unreachable!("job {code}"),
    }
}

/// A [`BandLdlt`]'s partner, if it has one. A clone solves on one thread (a thread is not
/// cloned); the values are the same either way.
#[derive(Debug, Default)]
pub(super) struct Slot(pub(super) Option<Partner<Bottom>>);

impl Clone for Slot {
    fn clone(&self) -> Self {
        Self(None)
    }
}

impl BandLdlt {
    /// Factorises and solves on two threads from now on, when this band is factorised from both
    /// ends (a line of at least [`super::TWIST_MIN`] equations): starts the partner thread and
    /// returns `Ok(true)`; `Ok(false)` for any other band, which stays on one thread. The values
    /// are the same to the bit either way.
    pub fn use_partner(&mut self) -> std::io::Result<bool> {
        let Some(m) = self.twist else {
            return Ok(false);
        };
        if self.partner.0.is_none() {
            let n = self.first.len();
            let bottom = Bottom {
                first: self.first.clone(),
                m,
                band: vec![0.0; self.band.len()],
                x: vec![0.0; n],
                result: Ok(()),
            };
            self.partner.0 = Some(Partner::start(bottom, job)?);
        }
        Ok(true)
    }

    /// Whether a partner thread does the bottom end.
    pub fn has_partner(&self) -> bool {
        self.partner.0.is_some()
    }

    /// [`BandLdlt::factor`] on two threads: the twisted band with its partner.
    pub(super) fn factor_split(&mut self, a: &SparseSym, m: usize) -> Result<(), SolveError> {
        const W: usize = 5;
        let p = m + W;
        let partner = self.partner.0.as_ref().expect("a partner");
        {
            let mut b = partner.work();
            let n = b.first.len();
            fill_columns((&mut b.band, &self.map, &self.above), a, p..n);
        }
        partner.ask(FACTOR);
        fill_columns((&mut self.band, &self.map, &self.above), a, 0..p);
        let top = factor_top5(&self.first, &mut self.band, m);
        let mut b = partner.wait();
        top?;
        b.result.clone()?;
        // The middle reads the bottom end's first five columns and writes them.
        let shared = p * (W + 1)..(p + W) * (W + 1);
        self.band[shared.clone()].copy_from_slice(&b.band[shared.clone()]);
        factor_middle5(&self.first, &mut self.band, m, &mut self.middle)?;
        b.band[shared.clone()].copy_from_slice(&self.band[shared]);
        Ok(())
    }

    /// [`BandLdlt::solve_in_place`] on two threads: the twisted band with its partner.
    pub(super) fn solve_split(&self, m: usize, x: &mut [f64]) {
        const W: usize = 5;
        let (n, p) = (x.len(), m + W);
        let partner = self.partner.0.as_ref().expect("a partner");
        partner.work().x[p..n].copy_from_slice(&x[p..n]);
        partner.ask(FORWARD);
        forward_top_end5(&self.first, &self.band, m, x);
        {
            let b = partner.wait();
            let reach = p..(p + W).min(n);
            x[reach.clone()].copy_from_slice(&b.x[reach]);
        }
        let z = solve_middle5(&self.first, &self.band, m, &self.middle, x);
        partner.work().x[m..p].copy_from_slice(&z);
        partner.ask(BACKWARD);
        backward_top_end5(&self.band, m, z, x);
        x[p..n].copy_from_slice(&partner.wait().x[p..n]);
    }

    /// One side of the twisted band's factorisation by two threads that each hold a copy of this
    /// band and meet at `seat` (issue 48): side 0 the top end `0..m` and the middle, side 1 the
    /// bottom end `m+5..n`. Each side's band holds its own columns' factor afterwards (side 0's
    /// also the middle's), the same values to the bit as [`BandLdlt::factor`] on one thread
    /// (`band_sides_are_the_twisted_band_to_the_bit`); both sides return the same outcome (a zero
    /// pivot in the top end is named first). Two meetings; a band that is not twisted is an
    /// error of the caller's (panics).
    pub fn factor_side(
        &mut self,
        a: &SparseSym,
        side: usize,
        seat: &mut Seat,
    ) -> Result<(), SolveError> {
        const W: usize = 5;
        let m = self.twist.expect("a band factorised from both ends");
        let (n, p) = (self.first.len(), m + W);
        let shared = p * (W + 1)..(p + W) * (W + 1);
        // A message: the side's outcome (NaN: none yet, −1: done, else the singular equation)
        // and the five columns the middle reads and writes.
        let mut mine = [f64::NAN; 1 + W * (W + 1)];
        let mut theirs = [0.0; 1 + W * (W + 1)];
        let code = |r: &Result<(), SolveError>| match r {
            Ok(()) => -1.0,
            Err(SolveError::Singular { equation }) => *equation as f64,
            Err(_) => f64::MAX,
        };
        let outcome = |c: f64| match c {
            c if c < 0.0 => Ok(()),
            // An equation number, exact in an f64.
            c if c < f64::MAX => Err(SolveError::Singular {
                equation: c as usize,
            }),
            _ => Err(SolveError::Symbolic("the other side failed".into())),
        };
        if side == 0 {
            fill_columns((&mut self.band, &self.map, &self.above), a, 0..p);
            let top = factor_top5(&self.first, &mut self.band, m);
            mine[0] = code(&top);
            seat.exchange(&mine, &mut theirs);
            top?;
            outcome(theirs[0])?;
            self.band[shared.clone()].copy_from_slice(&theirs[1..]);
            let middle = factor_middle5(&self.first, &mut self.band, m, &mut self.middle);
            mine[0] = code(&middle);
            mine[1..].copy_from_slice(&self.band[shared]);
            seat.exchange(&mine, &mut []);
            middle
        } else {
            fill_columns((&mut self.band, &self.map, &self.above), a, p..n);
            let bottom = factor_bottom5(&self.first, &mut self.band, m);
            mine[0] = code(&bottom);
            mine[1..].copy_from_slice(&self.band[shared.clone()]);
            seat.exchange(&mine, &mut theirs);
            outcome(theirs[0])?;
            bottom?;
            seat.exchange(&[], &mut theirs);
            self.band[shared].copy_from_slice(&theirs[1..]);
            outcome(theirs[0])
        }
    }

    /// One side of the solve with [`BandLdlt::factor_side`]'s factor: side 0 solves `x[0..m+5]`
    /// (the top end and the middle), side 1 `x[m+5..n]`, each from its own right-hand side's
    /// entries there; two meetings. The same values to the bit as [`BandLdlt::solve_in_place`].
    pub fn solve_side(&self, side: usize, seat: &mut Seat, x: &mut [f64]) {
        const W: usize = 5;
        let m = self.twist.expect("a band factorised from both ends");
        let p = m + W;
        if side == 0 {
            forward_top_end5(&self.first, &self.band, m, x);
            let mut reach = [0.0; W];
            seat.exchange(&[], &mut reach);
            x[p..p + W].copy_from_slice(&reach);
            let z = solve_middle5(&self.first, &self.band, m, &self.middle, x);
            seat.exchange(&z, &mut []);
            backward_top_end5(&self.band, m, z, x);
        } else {
            forward_bottom_end5(&self.first, &self.band, m, x);
            seat.exchange(&x[p..p + W], &mut []);
            let mut z = [0.0; W];
            seat.exchange(&[], &mut z);
            x[m..p].copy_from_slice(&z);
            backward_bottom_end5(&self.band, m, z, x);
        }
    }
}

/// Fills a band's columns `columns` from `a` as [`BandLdlt::factor`] does (the first five by the
/// map, the others in blocks), and zeroes their places above the skyline.
fn fill_columns(
    (band, map, above): (&mut [f64], &[usize], &[usize]),
    a: &SparseSym,
    columns: std::ops::Range<usize>,
) {
    const W: usize = 5;
    let ends = &a.col_ptr[1..];
    if columns.start < W {
        let head = ends[W - 1];
        for (v, &k) in a.values[..head].iter().zip(&map[..head]) {
            band[k] = *v;
        }
    }
    let blocks = band.chunks_exact_mut(W + 1).zip(ends);
    for (col, &end) in blocks.take(columns.end).skip(columns.start.max(W)) {
        col.copy_from_slice(&a.values[end - (W + 1)..end]);
    }
    let places = columns.start * (W + 1)..columns.end * (W + 1);
    for &h in above.iter().filter(|h| places.contains(h)) {
        band[h] = 0.0;
    }
}
