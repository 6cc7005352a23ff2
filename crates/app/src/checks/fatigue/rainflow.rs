//! Rainflow counting by the three-point rule of ASTM E1049-85 (reapproved 2017), §5.4.4, streaming.
//!
//! The series is reduced to its reversals as it arrives (a sample continuing the current direction
//! replaces the last point; plateaus are passed over); each reversal goes onto a stack, and while
//! the stack holds three points or more, with X the latest range and Y the one before it:
//!
//! ```text
//! if X < Y:                read on;
//! else if Y contains S:    count Y as ½ cycle, drop its first point (S moves on);
//! else:                    count Y as 1 cycle, drop both its points, keep X's last point.
//! ```
//!
//! (S, the starting point, is the bottom of the stack.) At the end the last sample is a reversal too,
//! and every range left on the stack (the residue) counts as ½ cycle. Only the residue stack is
//! kept, never the history: a 3-hour storm at 0.05 s is 216 000 samples per fibre per node, and the
//! stack is bounded by the number of reversals of decreasing range, a few dozen in practice. No
//! maintained Rust crate counts by ASTM's rule while streaming, which is why this is written here.
//!
//! Each cycle is reported as `(range, mean, count)` with count ½ or 1, in the order found.

/// A counted cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cycle {
    /// Range (peak to valley), in the series' unit.
    pub range: f64,
    /// Mean of its two points.
    pub mean: f64,
    /// ½ or 1.
    pub count: f64,
}

/// A streaming rainflow counter: push samples, then [`Rainflow::finish`]; each counted cycle is
/// handed to a callback as soon as it is found. Allocation: only the stack's growth (amortised; it
/// does not grow once it holds the series' largest decreasing run of reversals).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Rainflow {
    stack: Vec<f64>,
    last: Option<f64>,
    direction: i8,
}

impl Rainflow {
    /// An empty counter.
    pub fn new() -> Self {
        Self::default()
    }

    /// `p` is a turning point: onto the stack, and the cycles it closes counted. Out of line and
    /// cold: most samples continue the current direction ([`Rainflow::push`]'s inlined path).
    #[cold]
    #[inline(never)]
    fn reversal(&mut self, p: f64, sink: &mut impl FnMut(Cycle)) {
        self.stack.push(p);
        while self.stack.len() >= 3 {
            let n = self.stack.len();
            let (a, b, c) = (self.stack[n - 3], self.stack[n - 2], self.stack[n - 1]);
            let (x, y) = ((c - b).abs(), (b - a).abs());
            if x < y {
                break;
            }
            let cycle = Cycle {
                range: y,
                mean: 0.5 * (a + b),
                count: if n == 3 { 0.5 } else { 1.0 },
            };
            sink(cycle);
            if n == 3 {
                self.stack.remove(0);
            } else {
                self.stack.truncate(n - 3);
                self.stack.push(c);
            }
        }
    }

    /// Takes one sample; counts the cycles it closes. Non-finite samples must not be pushed.
    /// Inlined into the caller's loop: a sample that continues the direction (most of a
    /// riser's, a step at a time) is a comparison and a store.
    #[inline(always)]
    pub fn push(&mut self, x: f64, sink: &mut impl FnMut(Cycle)) {
        let Some(prev) = self.last else {
            self.last = Some(x);
            return;
        };
        let d: i8 = if x > prev {
            1
        } else if x < prev {
            -1
        } else {
            return;
        };
        if self.direction != d {
            // `prev` is a turning point (or the first point).
            self.reversal(prev, sink);
            self.direction = d;
        }
        self.last = Some(x);
    }

    /// Ends the series: the last sample is a reversal, and the residue counts as half cycles.
    pub fn finish(mut self, sink: &mut impl FnMut(Cycle)) {
        if let Some(p) = self.last.take() {
            self.reversal(p, sink);
        }
        for w in self.stack.windows(2) {
            sink(Cycle {
                range: (w[1] - w[0]).abs(),
                mean: 0.5 * (w[0] + w[1]),
                count: 0.5,
            });
        }
    }

    /// The residue's length (for tests of the bounded memory).
    pub fn residue_len(&self) -> usize {
        self.stack.len()
    }
}

/// All cycles of a series, in the order found.
pub fn count(series: &[f64]) -> Vec<Cycle> {
    let mut out = Vec::new();
    let mut rf = Rainflow::new();
    let mut sink = |c| out.push(c);
    for &x in series {
        rf.push(x, &mut sink);
    }
    rf.finish(&mut sink);
    out
}
