//! The fatigue counting lent to a pair's waits (see the parent module's docs, "In the pair's
//! waits"): the counting split at a node into two halves, each counted by one thread of the pair
//! in pieces of [`CHORE_NODES`] nodes while it waits for the other
//! ([`catena_fe::partner::Chores`]), what is left of a step counted when the next is handed over.

use std::sync::Mutex;

use super::Counting;

/// Nodes counted in one of the pair's chores ([`Lent`]): about a fifth of a microsecond, so
/// that a wait ends at most that much later.
pub const CHORE_NODES: usize = 16;

/// The counting split in two halves, each counted in the waits of one thread of a pair (see the
/// module docs).
#[derive(Debug)]
pub struct Lent {
    /// The node where the second half starts.
    at: usize,
    /// Each half, while lent (`None` while the observer holds the whole counting).
    halves: [Mutex<Option<Half>>; 2],
}

/// One half of a lent counting and the step it has to count.
#[derive(Debug)]
struct Half {
    counting: Counting,
    /// The first node of the half.
    first: usize,
    /// The step waiting to be counted: the half's tensions, then moments, then heights.
    step: Vec<f64>,
    /// The half's nodes counted of that step.
    done: usize,
}

impl Half {
    fn len(&self) -> usize {
        self.step.len() / 3
    }

    /// Counts the next `nodes` nodes of the step waiting, at most; whether there were any.
    fn count_next(&mut self, nodes: usize) -> bool {
        let n = self.len();
        let (a, b) = (self.done, self.done.saturating_add(nodes).min(n));
        if a == b {
            return false;
        }
        let (t, rest) = self.step.split_at(n);
        let (m, z) = rest.split_at(n);
        self.counting.count_from(a, &t[a..b], &m[a..b], &z[a..b]);
        self.done = b;
        true
    }

    /// Counts what is left of the step waiting, then takes the next step's numbers at the
    /// half's nodes.
    fn take(&mut self, tension: &[f64], moment: &[f64], z: &[f64]) {
        self.count_next(usize::MAX);
        let nodes = self.first..self.first + self.counting.node_curve.len();
        self.step.clear();
        for v in [tension, moment, z] {
            self.step.extend_from_slice(&v[nodes.clone()]);
        }
        self.done = 0;
    }
}

impl Lent {
    /// Nothing lent yet; the second half to start at node `at`.
    pub(super) fn new(at: usize) -> Self {
        Self {
            at,
            halves: [Mutex::new(None), Mutex::new(None)],
        }
    }

    /// Hands each half the step's tension, moment and height (every node's), each counting what
    /// is left of its last step first; lends `counting` first when the observer holds it.
    pub(super) fn hand(
        &self,
        counting: Option<Counting>,
        (tension, moment, z): (&[f64], &[f64], &[f64]),
    ) {
        if let Some(c) = counting {
            self.lend(c);
        }
        for side in 0..2 {
            if let Some(h) = self.half(side).as_mut() {
                h.take(tension, moment, z);
            }
        }
    }

    fn half(&self, side: usize) -> std::sync::MutexGuard<'_, Option<Half>> {
        self.halves[side]
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Lends `counting`'s two halves.
    fn lend(&self, counting: Counting) {
        let (a, b) = counting.split_at(self.at);
        for (side, (c, first)) in [(a, 0), (b, self.at)].into_iter().enumerate() {
            *self.half(side) = Some(Half {
                step: Vec::with_capacity(3 * c.node_curve.len()),
                counting: c,
                first,
                done: 0,
            });
        }
    }

    /// Counts what is left of each half's step and takes the counting back (`None` when it was
    /// not lent).
    pub(super) fn take_back(&self) -> Option<Counting> {
        let mut halves = [0, 1].map(|side| {
            let mut h = self.half(side).take()?;
            h.count_next(usize::MAX);
            Some(h.counting)
        });
        let (a, b) = (halves[0].take()?, halves[1].take()?);
        Some(a.join(b))
    }
}

impl catena_fe::partner::Chores for Lent {
    fn chore(&self, side: usize) -> bool {
        // The observer holds the half only to hand it a step; a chore never waits for it.
        let Ok(mut h) = self.halves[side].try_lock() else {
            return false;
        };
        h.as_mut().is_some_and(|h| h.count_next(CHORE_NODES))
    }
}
