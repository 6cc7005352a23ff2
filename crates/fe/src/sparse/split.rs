//! The twisted band factorisation and solve on two threads: the top end on the caller's thread,
//! the bottom end on a [`Partner`] thread, the middle five on the caller's.
//!
//! The twisted order ([`super::factor_twisted5`]) makes the two ends independent until the middle:
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

use super::{
    backward_bottom_end5, backward_top_end5, factor_bottom5, factor_middle5, factor_top5,
    forward_bottom_end5, forward_top_end5, solve_middle5, BandLdlt, SolveError, SparseSym,
};
use crate::partner::Partner;

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

    /// Goes back to one thread (ends the partner thread).
    pub fn drop_partner(&mut self) {
        self.partner.0 = None;
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
        // Where each column's values end in the pattern (one past its diagonal).
        let ends = &a.col_ptr[1..];
        {
            let mut b = partner.work();
            for (col, &end) in b.band.chunks_exact_mut(W + 1).zip(ends).skip(p) {
                col.copy_from_slice(&a.values[end - (W + 1)..end]);
            }
            for &h in self.above.iter().filter(|&&h| h >= p * (W + 1)) {
                b.band[h] = 0.0;
            }
        }
        partner.ask(FACTOR);
        // The top columns as `factor` copies them: the first W by the map, the rest in blocks.
        let head = ends[W - 1];
        for (v, &k) in a.values[..head].iter().zip(&self.map[..head]) {
            self.band[k] = *v;
        }
        for (col, &end) in self.band.chunks_exact_mut(W + 1).zip(ends).take(p).skip(W) {
            col.copy_from_slice(&a.values[end - (W + 1)..end]);
        }
        for &h in self.above.iter().take_while(|&&h| h < p * (W + 1)) {
            self.band[h] = 0.0;
        }
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
}
