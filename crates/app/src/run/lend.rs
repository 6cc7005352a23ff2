//! An observer's per-node work lent to the waits of the pair that steps the line (issue 69).
//!
//! Where two threads step the line ([`catena_fe::dynamics::Pair`]), each waits for the other at
//! their meetings and between steps, and the calling thread alone ran the observers between steps
//! while the partner idled. An observer whose work on a step is node by node (each node's own
//! counters or range graph, in step order) splits its state at a node into two halves ([`Piece`]),
//! each handed a copy of the step's numbers at its nodes ([`Halves::hand`]), and the pair's two
//! threads do the halves of the step before, [`CHORE_NODES`] nodes at a time, while they wait
//! ([`catena_fe::partner::Chores`]: side 0 the first half, side 1 the second). Handed the next
//! step, a half first does whatever of the last is left (all of it on the steps one thread
//! takes); [`Halves::take_back`] does the rest and gives the halves back. Every node takes the
//! same steps in the same order: the results are the same to the bit whoever does each piece.

use std::ops::Range;
use std::sync::{Mutex, MutexGuard, PoisonError};

/// Nodes done in one chore: a fifth of a microsecond or so, so that a wait ends at most that much
/// later.
pub const CHORE_NODES: usize = 16;

/// One half of an observer's per-node state.
pub trait Piece: Send {
    /// The nodes of the half.
    fn nodes(&self) -> usize;
    /// Takes the step's numbers at the half's nodes `nodes` (local: `0..` the half's first node):
    /// `step[k]` is the `k`-th quantity handed, the half's nodes only.
    fn take(&mut self, step: &[&[f64]], nodes: Range<usize>);
}

/// A half, and the step it has to take.
#[derive(Debug)]
struct Pending<P> {
    piece: P,
    /// The half's first node on the line.
    first: usize,
    /// The step waiting: each quantity at the half's nodes, one after the other.
    step: Vec<f64>,
    /// The half's nodes done of that step.
    done: usize,
}

impl<P: Piece> Pending<P> {
    /// Does the next `nodes` nodes of the step waiting, at most; whether there were any.
    fn next(&mut self, nodes: usize) -> bool {
        // No step handed yet: nothing to do.
        let n = if self.step.is_empty() {
            0
        } else {
            self.piece.nodes()
        };
        let (a, b) = (self.done, self.done.saturating_add(nodes).min(n));
        if a == b {
            return false;
        }
        let mut quantities: [&[f64]; 8] = [&[]; 8];
        for (q, s) in quantities.iter_mut().zip(self.step.chunks_exact(n)) {
            *q = s;
        }
        let k = self.step.len() / n.max(1);
        self.piece.take(&quantities[..k], a..b);
        self.done = b;
        true
    }
}

/// An observer's state in two halves, each done in one thread's waits (see the module docs).
#[derive(Debug)]
pub struct Halves<P> {
    /// The node where the second half starts.
    at: usize,
    halves: [Mutex<Option<Pending<P>>>; 2],
}

impl<P: Piece> Halves<P> {
    /// Nothing lent yet; the second half to start at node `at`.
    pub fn new(at: usize) -> Self {
        Self {
            at,
            halves: [Mutex::new(None), Mutex::new(None)],
        }
    }

    /// The node where the second half starts.
    pub fn at(&self) -> usize {
        self.at
    }

    fn half(&self, side: usize) -> MutexGuard<'_, Option<Pending<P>>> {
        self.halves[side]
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// Whether the halves are lent (not given back).
    pub fn lent(&self) -> bool {
        self.half(0).is_some()
    }

    /// Lends the two halves, of the nodes `..at` and `at..`.
    pub fn lend(&self, [first, second]: [P; 2]) {
        for (side, (piece, first)) in [(first, 0), (second, self.at)].into_iter().enumerate() {
            *self.half(side) = Some(Pending {
                piece,
                first,
                step: Vec::new(),
                done: 0,
            });
        }
    }

    /// Hands each half the step's `quantities` (every node's; at most eight), each half doing
    /// what is left of its last step first. Nothing while the halves are not lent.
    pub fn hand(&self, quantities: &[&[f64]]) {
        assert!(quantities.len() <= 8, "at most eight quantities a step");
        for side in 0..2 {
            if let Some(h) = self.half(side).as_mut() {
                h.next(usize::MAX);
                let nodes = h.first..h.first + h.piece.nodes();
                h.step.clear();
                for q in quantities {
                    h.step.extend_from_slice(&q[nodes.clone()]);
                }
                h.done = 0;
            }
        }
    }

    /// Does what is left of each half's step and gives the halves back (`None` when they were not
    /// lent).
    pub fn take_back(&self) -> Option<[P; 2]> {
        let mut back = [0, 1].map(|side| {
            let mut h = self.half(side).take()?;
            h.next(usize::MAX);
            Some(h.piece)
        });
        Some([back[0].take()?, back[1].take()?])
    }
}

impl<P: Piece> catena_fe::partner::Chores for Halves<P> {
    fn chore(&self, side: usize) -> bool {
        // The observer holds a half only to hand it a step; a chore never waits for it.
        let Ok(mut h) = self.halves[side].try_lock() else {
            return false;
        };
        h.as_mut().is_some_and(|h| h.next(CHORE_NODES))
    }
}

/// Runs `f` while two threads do the chores of sides 0 and 1 as fast as they can (racing whatever
/// `f` hands the halves); returns how many pieces they did.
#[cfg(test)]
pub(crate) fn racing_chores(chores: &catena_fe::partner::SharedChores, f: impl FnOnce()) -> usize {
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    let (stop, pieces) = (AtomicBool::new(false), AtomicUsize::new(0));
    std::thread::scope(|sc| {
        for side in 0..2 {
            let (c, stop, pieces) = (&chores.0, &stop, &pieces);
            sc.spawn(move || {
                while !stop.load(Ordering::Relaxed) {
                    if c.chore(side) {
                        pieces.fetch_add(1, Ordering::Relaxed);
                    }
                    std::hint::spin_loop();
                }
            });
        }
        f();
        stop.store(true, Ordering::Relaxed);
    });
    pieces.load(Ordering::Relaxed)
}

/// A pseudo-random sequence in [−½, ½) from `seed` (xorshift: the same sequence each time), for
/// the lent observers' tests.
#[cfg(test)]
pub(crate) fn xorshift(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}
