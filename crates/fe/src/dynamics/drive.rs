//! The drive: one thread or two for the next steps, chosen by what each measures (issue 69).
//!
//! A [`Pair`] steps a line to the same bits as one thread, faster on a machine whose second core
//! is free (storm 23 about 1.2–1.3× on two cores). On a machine whose cores are busy with other
//! work (a build beside the run, a study's jobs, another run), it is slower than one thread: its
//! threads meet a dozen times a step, and each meeting where the other thread is not running
//! waits for it to be scheduled again. No count of the machine's cores says which case a run is
//! in, and the load beside it may come and go. So a [`Drive`] times the steps and keeps the faster:
//!
//! - the steps are timed in **blocks** of [`Drive::BLOCK`] steps, as seconds per Newton iteration
//!   (a step's iterations are the same on one thread and two, so a block of either is a sample of
//!   the same work);
//! - after `interval` blocks on the current side, one block is a **probe** on the other; if the
//!   probe is faster per iteration than the block before it by [`Drive::MARGIN`], the drive
//!   stays on the other side, else it goes back. The probe's first step, on the side just
//!   engaged, is not timed: a new pair's first step took 250–970 µs against 110 µs on one thread
//!   for the J-lay in Hs 2 m on an idle machine, its next ones under 110 µs, and judged with the
//!   rest it failed every probe of one lay (43 044 of 200 102 steps on two, 26.6 s, against
//!   198 721 and 22.3 s in the next run). A probe that is already three times as slow as the
//!   block before it after one timed step, or twice after two, ends there (storm 23 beside two
//!   busy processes: a pair 2.5–24× slower than one thread, a step on two up to tens of
//!   milliseconds).
//! - After a failed probe the interval doubles (up to [`Drive::DOUBLED`] blocks), and is at least
//!   what spreads the probe's cost beyond the side kept (its two shifts included: a pair's start
//!   about 1.4 ms, its stop up to a time slice on a busy machine) to [`Drive::BUDGET`] of the
//!   blocks' time, up to [`Drive::LONGEST`] blocks: a J-lay beside two busy processes, whose
//!   probes cost 1–10 ms against blocks of 4 ms, tries two threads again after some 20 000 steps.
//! - The first block is on one thread, the reference. Two threads (where the run may keep two
//!   busy and the line can be cut, [`Pair::start`]) are tried only where the machine's other
//!   work left at least half a core idle since the last look ([`Idle`], `/proc/stat`, looks at
//!   least 200 ms apart): on cores that other work keeps busy, trying a pair costs a run more
//!   than its own steps (the scheduler moves the threads about), so it is not tried there. A
//!   caller that asked for two threads ([`Drive::asked`]: `--threads 2`) has them tried after
//!   the first block whatever the idle time, and kept where faster; later probes are gated as
//!   the default's (beside two busy processes the J-lay at `--threads 2`, probing whatever the
//!   idle time, was 7.7 and 13.2 % slower than at `--threads 1`, with 26 and 111 steps on two).
//!
//! Shifting is exact: from two threads to one, the first thread takes the pair's solver memory
//! (the second part's factorised columns), the pair stops and the Workspace keeps the
//! factorisation; from one to two, a pair starts from the State and that factorisation (as
//! [`Pair::start`] does). The steps are the same to the bit whichever side takes each
//! (`a_drive_shifting_between_one_and_two_threads_steps_as_one_to_the_bit`). A shift costs a
//! thread's start and a second Workspace (about a millisecond on the heave benchmark's line), paid
//! once a probe.
//!
//! A caller that changes the line (a lay's window) calls [`Drive::stop`] before; the next
//! [`Drive::advance`] starts a pair again if the drive is on two threads.

use std::sync::Arc;
use std::time::{Duration, Instant};

use super::*;

/// Which of one thread or two steps the next steps of a line (see the module docs).
#[derive(Debug)]
pub struct Drive {
    /// Whether the run may keep two threads busy (until a pair could not start a thread).
    two_allowed: bool,
    /// Whether the line stepped now can be cut in two parts (until [`Pair::start`] says it
    /// cannot; again after [`Drive::stop`], for a line that changes).
    cuttable: bool,
    /// The pair, while two threads step.
    pair: Option<Pair>,
    /// Whether the current block is stepped on two threads.
    on_two: bool,
    /// The block under way: steps, seconds and iterations.
    steps: u32,
    seconds: f64,
    iterations: usize,
    /// Whether the block under way is a probe of the other side: the seconds per iteration of
    /// the block before it, and that block's seconds.
    probe: Option<(f64, f64)>,
    /// Whether the next step is a probe's first, its side just engaged: not timed (below).
    warming: bool,
    /// When the probe under way began (its first shift), and a failed probe's cost to settle
    /// once its shift back is done: when it began, its iterations, and the kept side's seconds
    /// per iteration and per block.
    probe_began: Option<Instant>,
    failed: Option<(Instant, usize, f64, f64)>,
    /// The machine's idle time since the last look ([`Idle`]), and whether the next probe of two
    /// threads is tried whatever it (the first of a drive the caller asked for two).
    idle: Idle,
    ungated: bool,
    /// Blocks on the current side since the last probe, and how many before the next.
    since: u32,
    interval: u32,
    /// Steps taken on two threads and on one, and shifts (for the run's summary).
    steps_on: [u64; 2],
    shifts: u64,
    /// A fixed schedule instead of the timing (tests): step `k` on two threads when it says so.
    schedule: Option<fn(u64) -> bool>,
    count: u64,
}

impl Default for Drive {
    /// One thread.
    fn default() -> Self {
        Self::new(1)
    }
}

impl Drive {
    /// Steps in a block.
    pub const BLOCK: u32 = 32;
    /// How much faster a probe must be to be kept.
    pub const MARGIN: f64 = 0.03;
    /// The most blocks between probes by doubling.
    pub const DOUBLED: u32 = 64;
    /// The most blocks between probes.
    pub const LONGEST: u32 = 1024;
    /// The share of the time a failed probe may cost: the next probe waits for enough blocks.
    /// Small, because a probe's cost beyond what it measures (the scheduler moving the threads
    /// about) is not measured: a J-lay beside two busy processes was 2.6–8 % slower than one
    /// thread with 1 % (a probe every 2 000 steps), within the host's spread with 0.2 %.
    pub const BUDGET: f64 = 0.002;

    /// A drive for a run that may keep `threads` busy for its line: two threads where `threads`
    /// ≥ 2 and the line can be cut, chosen block by block; one otherwise.
    pub fn new(threads: usize) -> Self {
        Self {
            two_allowed: threads >= 2,
            cuttable: true,
            pair: None,
            on_two: false,
            steps: 0,
            seconds: 0.0,
            iterations: 0,
            probe: None,
            warming: false,
            probe_began: None,
            failed: None,
            idle: Idle::default(),
            ungated: false,
            since: 0,
            interval: 1,
            steps_on: [0; 2],
            shifts: 0,
            schedule: None,
            count: 0,
        }
    }

    /// [`Drive::new`] for a caller that asked for `threads` (`--threads 2`): two threads are
    /// tried after the first block whatever the machine's idle time, and kept where faster; after
    /// that, as [`Drive::new`]'s, only beside an idle core ([`Idle`]).
    pub fn asked(threads: usize) -> Self {
        Self {
            ungated: true,
            ..Self::new(threads)
        }
    }

    /// A drive that steps on two threads exactly where `two(k)` says, `k` counting its steps
    /// from 0 (for tests of the shifts themselves).
    pub fn with_schedule(two: fn(u64) -> bool) -> Self {
        Self {
            schedule: Some(two),
            ..Self::new(2)
        }
    }

    /// Takes one step of `dt` on the side the drive is on (starting or stopping the pair first
    /// when it shifts), as [`advance`] does, and times it.
    ///
    /// # Errors
    /// As [`advance`]. A pair that cannot start (a line too short to cut, no thread to be had)
    /// is not an error: the drive stays on one thread.
    pub fn advance(
        &mut self,
        dm: &Arc<DynamicModel>,
        state: &mut DynState,
        ws: &mut DynWorkspace,
        dt: f64,
    ) -> Result<StepInfo, StepError> {
        if let Some(two) = self.schedule {
            self.on_two = two(self.count);
        }
        self.count += 1;
        if self.probe.is_some() && self.warming {
            // The probe's first step (before `time` counts it, or not).
            self.probe_began = Some(Instant::now());
        }
        self.engage(dm, state, ws);
        if let Some((began, iterations, before, block)) = self.failed.take() {
            // The failed probe's whole cost, its two shifts included, is known now.
            self.settle(began.elapsed(), iterations, before, block);
        }
        // The step alone is compared; the shifts count in a failed probe's cost.
        let t0 = Instant::now();
        let step = match &mut self.pair {
            Some(p) => p.advance(dm, state, ws, dt),
            None => advance(dm, state, ws, dt),
        };
        let side = usize::from(self.pair.is_some());
        self.steps_on[side] += 1;
        if let Ok(info) = &step {
            self.time(t0.elapsed(), info.iterations);
        }
        step
    }

    /// Engages the side the drive is on before the first step; returns whether two threads may
    /// step the line (the run may keep two busy and the line can be cut), that is how many
    /// threads to count for the stepping.
    pub fn start(&mut self, dm: &DynamicModel, state: &DynState, ws: &mut DynWorkspace) -> bool {
        self.engage(dm, state, ws);
        self.two_allowed && ws.split.is_some()
    }

    /// The side the drive is on, engaged: the pair started or stopped to match.
    fn engage(&mut self, dm: &DynamicModel, state: &DynState, ws: &mut DynWorkspace) {
        let want = self.on_two && self.two_allowed && self.cuttable;
        match (&self.pair, want) {
            (None, true) => match Pair::start(dm, state, ws) {
                Ok(Some(p)) => {
                    self.pair = Some(p);
                    self.shifts += 1;
                }
                // A line too short to cut: one thread while it is stepped.
                Ok(None) => self.cuttable = false,
                // No thread to be had: one thread from now on.
                Err(_) => self.two_allowed = false,
            },
            (Some(_), false) => {
                self.park_pair(dm, ws);
                self.shifts += 1;
            }
            _ => {}
        }
    }

    /// Stops the pair, the Workspace keeping its whole factorisation for the next step.
    fn park_pair(&mut self, dm: &DynamicModel, ws: &mut DynWorkspace) {
        if let Some(p) = self.pair.take() {
            let memory = p.solver_memory(ws);
            p.stop(dm, ws);
            if let Some(m) = memory {
                ws.restore_solver_memory(&m)
                    .expect("the pair's solver memory fits its own Workspace");
            }
        }
    }

    /// Counts a step of `iterations` that took `took` into the block, and decides the next
    /// block's side when the block is full (see the module docs).
    fn time(&mut self, took: Duration, iterations: usize) {
        if self.schedule.is_some() || !self.two_allowed || !self.cuttable {
            return;
        }
        if std::mem::take(&mut self.warming) {
            // A probe's first step, on a side just engaged, is not a sample of that side's
            // steps (a pair's new thread is scheduled and touches its memory for the first
            // time): 2.5–9 times a step on one thread on an idle machine, where the next take
            // under one. It counts in a failed probe's cost, not in the comparison.
            return;
        }
        self.steps += 1;
        self.seconds += took.as_secs_f64();
        self.iterations += iterations;
        let per = self.seconds / self.iterations.max(1) as f64;
        // A probe already three times as slow as the block before it after a step, or twice
        // after two, ends early.
        let hopeless = matches!(self.probe, Some((before, _))
            if (self.steps == 1 && per > 3.0 * before) || (self.steps >= 2 && per > 2.0 * before));
        if self.steps < Self::BLOCK && !hopeless {
            return;
        }
        let (seconds, iterations) = (self.seconds, self.iterations);
        (self.steps, self.seconds, self.iterations) = (0, 0.0, 0);
        match self.probe.take() {
            Some((before, block)) => {
                if per < (1.0 - Self::MARGIN) * before {
                    // The other side is faster: it is the side now.
                    self.interval = 1;
                } else {
                    self.on_two = !self.on_two;
                    self.interval = (2 * self.interval).min(Self::DOUBLED);
                    if let Some(began) = self.probe_began.take() {
                        self.failed = Some((began, iterations, before, block));
                    }
                }
                self.since = 0;
            }
            None => {
                self.since += 1;
                if self.since < self.interval {
                    return;
                }
                // Two threads are tried only where a second core was mostly idle meanwhile; where
                // the caller asked for them, the first time whatever the idle time.
                if !self.on_two && !self.ungated {
                    match self.idle.second_core_free() {
                        Some(true) => {}
                        Some(false) => {
                            self.since = 0;
                            self.interval = (2 * self.interval).min(Self::DOUBLED);
                            return;
                        }
                        // Too soon to tell: the next block.
                        None => return,
                    }
                }
                self.probe = Some((per, seconds));
                self.warming = true;
                self.ungated &= self.on_two;
                self.on_two = !self.on_two;
            }
        }
    }

    /// After a failed probe that took `took` from its first shift to the shift back, over
    /// `iterations` that the side kept takes `before` s each (in blocks of `block` s): the next
    /// probe waits at least until the probe's cost beyond the side kept is [`Drive::BUDGET`] of
    /// the blocks' time.
    fn settle(&mut self, took: Duration, iterations: usize, before: f64, block: f64) {
        let penalty = took.as_secs_f64() - iterations as f64 * before;
        let spread = (penalty / (Self::BUDGET * block)).ceil();
        let spread = if spread.is_finite() {
            spread.clamp(0.0, f64::from(Self::LONGEST))
        } else {
            f64::from(Self::LONGEST)
        };
        // Within the range by the clamp.
        self.interval = self.interval.max(spread as u32).min(Self::LONGEST);
    }

    /// Stops the pair, if there is one, as [`Pair::stop`] (before the caller changes the line, or
    /// at the run's end): the Workspace forgets the factorisation. The next step starts a pair
    /// again if the drive is on two threads.
    pub fn stop(&mut self, dm: &DynamicModel, ws: &mut DynWorkspace) {
        if let Some(p) = self.pair.take() {
            p.stop(dm, ws);
        }
        self.cuttable = true;
    }

    /// The factorisation kept for the next step, as data (a checkpoint's), the pair's second
    /// part's columns included.
    pub fn solver_memory(&self, ws: &mut DynWorkspace) -> Option<SolverMemory> {
        match &self.pair {
            Some(p) => p.solver_memory(ws),
            None => ws.solver_memory(),
        }
    }

    /// Whether two threads step the line now.
    pub fn on_two(&self) -> bool {
        self.pair.is_some()
    }

    /// The steps taken on one thread and on two, and the shifts between them.
    pub fn tally(&self) -> ([u64; 2], u64) {
        (self.steps_on, self.shifts)
    }
}

/// The machine's idle processor time (Linux: `/proc/stat`'s `idle` and `iowait`, in clock ticks of
/// 10 ms), read before a probe of two threads: where the other work on the machine left less than
/// half a core idle since the last look, a pair would share a core with it and is not tried
/// (measured on two cores beside busy processes: a probe there cost the run 5–10 %, more than
/// the probe's own steps, as the scheduler moves the threads about). Where `/proc/stat` cannot be
/// read, every probe is tried.
#[derive(Debug, Default)]
struct Idle {
    /// When the last look was, and the idle ticks then.
    last: Option<(Instant, u64)>,
    /// The answer without a look (tests of the drive's timing).
    assumed: Option<bool>,
}

impl Idle {
    /// The shortest time between two looks for their difference to mean something (ticks of
    /// 10 ms).
    const WINDOW: Duration = Duration::from_millis(200);
    /// Clock ticks per second (`USER_HZ`: 100 on Linux).
    const TICKS: f64 = 100.0;

    /// Whether at least half a core was idle since the last look (`None`: too soon to tell, or the
    /// first look), and a new look from now; `Some(true)` where the idle time cannot be read.
    fn second_core_free(&mut self) -> Option<bool> {
        if self.assumed.is_some() {
            return self.assumed;
        }
        let Some(ticks) = Self::idle_ticks() else {
            return Some(true);
        };
        let now = Instant::now();
        match self.last {
            Some((then, before)) if now.duration_since(then) >= Self::WINDOW => {
                self.last = Some((now, ticks));
                let idle = ticks.saturating_sub(before) as f64 / Self::TICKS;
                Some(idle >= 0.5 * now.duration_since(then).as_secs_f64())
            }
            Some(_) => None,
            None => {
                self.last = Some((now, ticks));
                None
            }
        }
    }

    /// The idle and iowait ticks of every processor together, from `/proc/stat`'s first line.
    fn idle_ticks() -> Option<u64> {
        let text = std::fs::read_to_string("/proc/stat").ok()?;
        let line = text.lines().next()?;
        let mut fields = line.split_whitespace();
        (fields.next()? == "cpu").then_some(())?;
        let numbers: Vec<u64> = fields.take(5).filter_map(|f| f.parse().ok()).collect();
        Some(numbers.get(3)? + numbers.get(4)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steps a drive (its timing only, no line) `steps` times, a step on one thread taking
    /// `cost(k).0` s an iteration and on two `cost(k).1`, iterations 2 to 4; returns the steps
    /// on each side and the total time.
    fn drive(steps: u64, cost: impl Fn(u64) -> (f64, f64)) -> ([u64; 2], f64) {
        drive_beside(steps, cost, true)
    }

    /// [`drive`], the second core found free or not by every look.
    fn drive_beside(steps: u64, cost: impl Fn(u64) -> (f64, f64), free: bool) -> ([u64; 2], f64) {
        let mut d = Drive::new(2);
        d.idle.assumed = Some(free);
        let (mut on, mut total) = ([0u64; 2], 0.0);
        for k in 0..steps {
            let iterations = 2 + (k % 3) as usize;
            let side = usize::from(d.on_two);
            let per = if d.on_two { cost(k).1 } else { cost(k).0 };
            let took = per * iterations as f64;
            on[side] += 1;
            total += took;
            d.time(Duration::from_secs_f64(took), iterations);
        }
        (on, total)
    }

    /// Where two threads are faster (an idle machine: 1.3×), the drive spends under 2 % of the
    /// steps on one (its probes), and its time is within 1 % of two threads all along; where they
    /// are slower (a busy machine: 3× slower), under 1 % of the steps on two, its time within 2 %
    /// of one thread all along; where the load comes and goes (every 40 000 steps), it follows
    /// within 5 %.
    #[test]
    fn the_drive_keeps_the_faster_side() {
        let n = 200_000;
        let (on, total) = drive(n, |_| (1.3e-5, 1.0e-5));
        assert!((on[0] as f64) < 0.02 * n as f64, "{on:?}");
        let best: f64 = (0..n).map(|k| 1.0e-5 * (2 + k % 3) as f64).sum();
        assert!(total < 1.01 * best, "{total} against {best}");
        let (on, total) = drive(n, |_| (1.0e-5, 3.0e-5));
        assert!((on[1] as f64) < 0.01 * n as f64, "{on:?}");
        assert!(total < 1.02 * best, "{total} against {best}");
        // Busy for 40 000 steps, idle for 40 000, and again.
        let cost = |k: u64| match (k / 40_000) % 2 {
            0 => (1.0e-5, 3.0e-5),
            _ => (1.3e-5, 1.0e-5),
        };
        let (_, total) = drive(n, cost);
        let best: f64 = (0..n)
            .map(|k| cost(k).0.min(cost(k).1) * (2 + k % 3) as f64)
            .sum();
        assert!(total < 1.05 * best, "{total} against {best}");
    }

    /// Where the machine's other work leaves no second core idle, two threads are not tried,
    /// however fast they would be; the machine's own idle time reads as a fraction of the cores.
    #[test]
    fn two_threads_are_tried_only_beside_an_idle_core() {
        let (on, _) = drive_beside(100_000, |_| (1.3e-5, 1.0e-5), false);
        assert_eq!(on, [100_000, 0]);
        if let Some(ticks) = Idle::idle_ticks() {
            let mut idle = Idle::default();
            assert_eq!(idle.second_core_free(), None, "the first look");
            std::thread::sleep(Idle::WINDOW);
            assert!(idle.second_core_free().is_some());
            assert!(Idle::idle_ticks().is_some_and(|t| t >= ticks));
        }
    }

    /// Where a side's first step after a shift costs ten times its others (a pair's new thread
    /// starting: 2.5–9 times on an idle machine, measured on the J-lay), and two threads are
    /// otherwise 1.3× faster, the drive still keeps two for most steps: a probe is not judged
    /// on its first step.
    #[test]
    fn a_probe_is_not_judged_on_its_first_step() {
        let mut d = Drive::new(2);
        d.idle.assumed = Some(true);
        let n = 100_000;
        let (mut on, mut was) = ([0u64; 2], false);
        for k in 0..n {
            let iterations = 2 + (k % 3) as usize;
            let per = if d.on_two { 1.0e-5 } else { 1.3e-5 };
            let start = if d.on_two != was { 10.0 } else { 1.0 };
            was = d.on_two;
            on[usize::from(d.on_two)] += 1;
            d.time(
                Duration::from_secs_f64(start * per * iterations as f64),
                iterations,
            );
        }
        assert!(on[1] as f64 > 0.95 * n as f64, "{on:?}");
    }

    /// A drive asked for two threads tries them after its first block whatever the machine's
    /// idle time, and beside busy cores not again.
    #[test]
    fn an_asked_drive_tries_two_once_beside_busy_cores() {
        let mut d = Drive::asked(2);
        d.idle.assumed = Some(false);
        let mut on = [0u64; 2];
        for k in 0..100_000u64 {
            let iterations = 2 + (k % 3) as usize;
            let per = if d.on_two { 3.0e-5 } else { 1.0e-5 };
            on[usize::from(d.on_two)] += 1;
            d.time(Duration::from_secs_f64(per * iterations as f64), iterations);
        }
        assert!((1..=3).contains(&on[1]), "{on:?}");
    }

    /// A probe twice as slow as the block before it ends after two steps, and the next waits
    /// until its cost is 0.2 % of the time.
    #[test]
    fn a_hopeless_probe_ends_early() {
        let mut d = Drive::new(2);
        d.idle.assumed = Some(true);
        d.on_two = false;
        for _ in 0..Drive::BLOCK {
            d.time(Duration::from_micros(10), 1);
        }
        assert!(d.on_two, "the first probe is after the first block");
        // Its first step, the pair's start, is not judged however slow.
        d.time(Duration::from_micros(1000), 1);
        assert!(d.on_two, "a probe's first step ended it");
        d.time(Duration::from_micros(30), 1);
        assert!(d.on_two);
        d.time(Duration::from_micros(30), 1);
        assert!(!d.on_two, "the probe went on");
        assert_eq!(d.interval, 2, "the interval doubles");
        // The probe cost 2 × (30 − 10) µs beyond the side kept (its shifts nothing): spread to
        // 0.2 % of the blocks' 320 µs, 62.5 blocks.
        d.settle(Duration::from_micros(60), 2, 10e-6, 320e-6);
        assert_eq!(d.interval, 63, "the interval spreads the probe's cost");
    }
}
