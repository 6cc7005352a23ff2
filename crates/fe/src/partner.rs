//! A partner thread: the second processor of one run, awake when its work arrives.
//!
//! A step's phases are a few microseconds each (a solve of the heave benchmark's line takes about
//! 4 µs), too short for a pool whose worker sleeps between jobs: waking a sleeping thread costs
//! tens of microseconds (a rayon split of a 66 µs job measured 59–74 µs). So a [`Partner`] owns one
//! thread for the life of the workspace that holds it. After each job the thread spins, reading
//! one atomic, for [`SPIN`] before it parks; within a run's step loop the next job comes sooner
//! than that, so it is picked up within a fraction of a microsecond, and a partner left idle (the
//! run writing its outputs, or finished) sleeps and costs nothing.
//!
//! **The protocol.** The work `W` (the partner's own data: its half of a band, say) lives in a
//! mutex. [`Partner::ask`] publishes a job (a sequence number and a code) with release ordering
//! and unparks the thread; the thread takes the mutex, runs the job function on the work,
//! releases it and publishes the job's number as done. [`Partner::wait`] spins until it reads
//! that number (acquire ordering) and then hands the caller the work; [`Partner::work`] hands it
//! over while no job is asked. The two sides never hold the mutex at once, so it is never
//! contended: it is what lets the work cross threads in safe Rust, not a lock anyone waits on.
//! A job asked while the thread is deciding to park leaves the unpark token set, and `park`
//! returns at once: no wake-up is lost.
//!
//! **Oversubscribed.** Where the two threads share a processor with others (a build beside the
//! run, tests side by side, a study's jobs), the other side of a wait may not be running for a
//! time slice (milliseconds). A waiting side then must not keep its core: it spins for
//! [`YIELD_AFTER`], yields the processor until [`PARK_AFTER`], and then parks until the other side
//! rings its [`Bell`], giving its core to whatever else runs; an idle partner parks after
//! [`SPIN`]. (Whether two threads pay at all on a shared machine is measured by the run:
//! [`crate::dynamics::Drive`].) A partner that died (its job panicked) is noticed by the waiter,
//! which then panics too rather than waiting for ever.
//!
//! **Meetings.** Two threads that each run the same loop on their own part of a line meet where
//! the parts touch, each leaving a few numbers for the other: a [`Seat`] each ([`seats`]).
//!
//! **Chores.** A side that waits, at a meeting or for its next job, may do [`Chores`] meanwhile:
//! work in pieces well under a microsecond each, between two reads of what it waits for (a run's
//! fatigue counting of the step before, each side its half of the line's nodes). The wait then
//! ends at most a piece later than it would have; a side with no chore left spins as before.

use std::cell::Cell;
use std::sync::atomic::{fence, AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::thread::{JoinHandle, Thread};
use std::time::{Duration, Instant};

/// How long the partner spins for its next job before it parks.
pub const SPIN: Duration = Duration::from_micros(500);

/// How long a waiting side spins before it yields the processor between reads: longer than most
/// waits of a step, short against a time slice.
pub const YIELD_AFTER: Duration = Duration::from_micros(20);

/// How long a waiting side spins (then yields) before it parks: a wait this long means the other
/// side is not running (on a processor shared with other work, descheduled for a time slice,
/// milliseconds), so the waiter gives its core away until the other side rings ([`Bell`]).
pub const PARK_AFTER: Duration = Duration::from_micros(500);

/// Work a waiting side does in small pieces ([`seats_with_chores`], [`Partner::start_with_chores`]; see the
/// module docs).
pub trait Chores: Send + Sync {
    /// Does one piece of side `side`'s chores (well under a microsecond); `false` when none was
    /// left to do.
    fn chore(&self, side: usize) -> bool;
}

/// A side's chores, if any, and the side.
pub type SideChores = Option<(Arc<dyn Chores>, usize)>;

/// Chores both sides of a pair share, each doing its own ([`Chores::chore`]'s `side`).
#[derive(Clone)]
pub struct SharedChores(pub Arc<dyn Chores>);

impl SharedChores {
    /// Side `side`'s chores.
    pub fn side(&self, side: usize) -> SideChores {
        Some((Arc::clone(&self.0), side))
    }
}

/// Several chores, done in turn: a piece of the first with any left.
pub struct ChoreList(pub Vec<Arc<dyn Chores>>);

impl Chores for ChoreList {
    fn chore(&self, side: usize) -> bool {
        self.0.iter().any(|c| c.chore(side))
    }
}

impl std::fmt::Debug for SharedChores {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SharedChores")
    }
}

/// A waiter's bell: a side that waits long parks after saying so here, and the side that makes
/// it ready rings it ([`Bell::ring`]), waking it only when it sleeps (one fence and one load
/// otherwise). A waiter sets `sleeping` and then reads whether it is ready; the ringer makes it
/// ready and then reads `sleeping`, each with a sequentially consistent fence between, so at least
/// one of them sees the other's write: no wake-up is lost. A park also ends after
/// [`Bell::NAP`], and the waiter reads again.
#[derive(Debug, Default)]
struct Bell {
    sleeping: AtomicBool,
    thread: Mutex<Option<Thread>>,
}

impl Bell {
    /// The longest a waiter sleeps before it reads again (a safeguard: a ring wakes it sooner).
    const NAP: Duration = Duration::from_millis(2);

    /// Wakes the waiter if it sleeps; called after the write that makes it ready.
    #[inline]
    fn ring(&self) {
        fence(Ordering::SeqCst);
        if self.sleeping.load(Ordering::Relaxed) {
            if let Some(t) = lock(&self.thread).as_ref() {
                t.unpark();
            }
        }
    }

    /// Waits until `ready`, doing `chores` while there are any: spins, yields the processor after
    /// [`YIELD_AFTER`], parks after [`PARK_AFTER`] until rung; panics with `gone` when `alive`
    /// says the other side has gone.
    #[inline]
    fn wait(
        &self,
        ready: impl Fn() -> bool,
        alive: impl Fn() -> bool,
        gone: &str,
        chores: &SideChores,
    ) {
        let mut spins = 0u32;
        let mut since = None;
        let mut busy = chores.is_some();
        while !ready() {
            if busy {
                if let Some((c, side)) = chores {
                    busy = c.chore(*side);
                    continue;
                }
            }
            std::hint::spin_loop();
            spins = spins.wrapping_add(1);
            if spins % 64 != 0 {
                continue;
            }
            let t0 = *since.get_or_insert_with(Instant::now);
            let waited = t0.elapsed();
            if waited <= YIELD_AFTER {
                continue;
            }
            assert!(alive(), "{gone}");
            if waited <= PARK_AFTER {
                std::thread::yield_now();
                continue;
            }
            *lock(&self.thread) = Some(std::thread::current());
            self.sleeping.store(true, Ordering::Relaxed);
            fence(Ordering::SeqCst);
            if !ready() {
                std::thread::park_timeout(Self::NAP);
            }
            self.sleeping.store(false, Ordering::Relaxed);
        }
    }
}

/// The job code that ends the thread.
const EXIT: u8 = u8::MAX;

/// What the two sides share.
struct Shared<W> {
    /// The last job asked: its sequence number `<< 8`, its code in the low byte.
    asked: AtomicU64,
    /// The sequence number of the last job done.
    done: AtomicU64,
    /// The partner's work.
    work: Mutex<W>,
    /// What the partner thread does while it waits for a job, and what the caller does while it
    /// waits for a job to be done.
    chores: [SideChores; 2],
    /// The caller's bell, rung when a job is done.
    bell: Bell,
}

/// A thread that runs one job function on its own work, on request (see the module docs).
pub struct Partner<W: Send + 'static> {
    shared: Arc<Shared<W>>,
    handle: Option<JoinHandle<()>>,
    /// The sequence number of the last job asked (a `Cell`: a partner has one caller, and the
    /// `Cell` keeps it from being shared between threads).
    seq: Cell<u64>,
}

impl<W: Send + 'static> std::fmt::Debug for Partner<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Partner")
            .field("jobs", &self.seq.get())
            .finish()
    }
}

impl<W: Send + 'static> Partner<W> {
    /// Starts the thread with its work and the function that runs a job (`code` < 255) on it.
    pub fn start(work: W, job: fn(&mut W, u8)) -> std::io::Result<Self> {
        Self::start_with_chores(work, job, [None, None])
    }

    /// [`Partner::start`], the caller doing `chores[0]` while it waits for a job to be done and
    /// the partner thread `chores[1]` while it waits for the next.
    pub fn start_with_chores(
        work: W,
        job: fn(&mut W, u8),
        chores: [SideChores; 2],
    ) -> std::io::Result<Self> {
        let shared = Arc::new(Shared {
            asked: AtomicU64::new(0),
            done: AtomicU64::new(0),
            work: Mutex::new(work),
            chores,
            bell: Bell::default(),
        });
        let theirs = Arc::clone(&shared);
        let handle = std::thread::Builder::new()
            .name("catena-partner".into())
            .spawn(move || serve(&theirs, job))?;
        Ok(Self {
            shared,
            handle: Some(handle),
            seq: Cell::new(0),
        })
    }

    /// Asks for job `code` and returns at once. The previous job must have been waited for.
    pub fn ask(&self, code: u8) {
        let seq = self.seq.get();
        debug_assert_eq!(self.shared.done.load(Ordering::Acquire), seq);
        self.seq.set(seq + 1);
        self.shared
            .asked
            .store((seq + 1) << 8 | u64::from(code), Ordering::Release);
        if let Some(h) = &self.handle {
            h.thread().unpark();
        }
    }

    /// Waits for the job asked last to be done and hands over the work.
    ///
    /// # Panics
    /// When the partner thread has died (its job panicked).
    pub fn wait(&self) -> MutexGuard<'_, W> {
        let seq = self.seq.get();
        self.shared.bell.wait(
            || self.shared.done.load(Ordering::Acquire) == seq,
            || !self.handle.as_ref().is_none_or(JoinHandle::is_finished),
            "the partner thread stopped before its job was done (it panicked)",
            &self.shared.chores[0],
        );
        self.work()
    }

    /// The work, while no job is asked.
    pub fn work(&self) -> MutexGuard<'_, W> {
        lock(&self.shared.work)
    }
}

impl<W: Send + 'static> Drop for Partner<W> {
    fn drop(&mut self) {
        if let Some(h) = self.handle.take() {
            let seq = self.seq.get() + 1;
            self.shared
                .asked
                .store(seq << 8 | u64::from(EXIT), Ordering::Release);
            h.thread().unpark();
            // Not joined while this thread panics: the partner may be waiting for it at a
            // meeting (`Seat`), which it leaves, panicking, once this side's seat is gone.
            if !std::thread::panicking() {
                // A job that panicked has already said so on the thread's own output.
                let _ = h.join();
            }
        }
    }
}

/// The partner's loop: spin (then park) for the next job, run it, say it is done.
fn serve<W>(s: &Shared<W>, job: fn(&mut W, u8)) {
    let mut last = 0u64;
    loop {
        let mut spins = 0u32;
        let mut since = Instant::now();
        let mut busy = s.chores[1].is_some();
        let asked = loop {
            let a = s.asked.load(Ordering::Acquire);
            if a >> 8 != last {
                break a;
            }
            if busy {
                if let Some((c, side)) = &s.chores[1] {
                    busy = c.chore(*side);
                    // The idle time counts from the last chore.
                    since = Instant::now();
                    continue;
                }
            }
            std::hint::spin_loop();
            spins = spins.wrapping_add(1);
            if spins % 256 == 0 {
                let idle = since.elapsed();
                if idle > SPIN {
                    std::thread::park();
                    since = Instant::now();
                } else if idle > YIELD_AFTER {
                    // Where the processors are oversubscribed, the caller may be waiting for one.
                    std::thread::yield_now();
                }
            }
        };
        last = asked >> 8;
        // The low byte is the code (the mask makes the narrowing exact).
        let code = (asked & 0xff) as u8;
        if code == EXIT {
            return;
        }
        {
            let mut w = lock(&s.work);
            job(&mut w, code);
        }
        s.done.store(last, Ordering::Release);
        s.bell.ring();
    }
}

/// One side of a meeting place for two threads that run the same loop on their parts of a line
/// (issue 48): at each meeting each side leaves a few numbers, waits for the other, and takes what
/// the other left. [`seats`] makes the pair.
///
/// Meeting `c` uses the mailboxes of parity `c mod 2`: a side can leave its numbers for meeting
/// `c + 2` only after the other has arrived at `c + 1`, that is after it has read those of meeting
/// `c`, so nothing is overwritten before it is read. Arrival is an atomic count (release when
/// leaving, acquire when reading); the mailboxes are mutexes that the two sides never hold at once.
/// A side that waits for an other side that has gone (its thread ended or panicked) panics rather
/// than waiting for ever.
pub struct Seat {
    table: Arc<Table>,
    me: usize,
    /// The meetings this side has been to.
    count: u64,
}

/// What the two seats share.
struct Table {
    arrived: [AtomicU64; 2],
    /// `mail[side][parity]`.
    mail: [[Mutex<Vec<f64>>; 2]; 2],
    capacity: usize,
    /// Each side's bell, rung by the other when it arrives.
    bells: [Bell; 2],
    /// What each side does while it waits.
    chores: [SideChores; 2],
}

impl std::fmt::Debug for Seat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Seat")
            .field("side", &self.me)
            .field("meetings", &self.count)
            .finish()
    }
}

/// Two seats of one meeting place, each leaving at most `capacity` numbers at a meeting.
pub fn seats(capacity: usize) -> (Seat, Seat) {
    seats_with_chores(capacity, [None, None])
}

/// [`seats`], side `i` doing `chores[i]` while it waits at a meeting.
pub fn seats_with_chores(capacity: usize, chores: [SideChores; 2]) -> (Seat, Seat) {
    let mailbox = || Mutex::new(Vec::with_capacity(capacity));
    let table = Arc::new(Table {
        arrived: [AtomicU64::new(0), AtomicU64::new(0)],
        mail: [[mailbox(), mailbox()], [mailbox(), mailbox()]],
        capacity,
        bells: [Bell::default(), Bell::default()],
        chores,
    });
    let seat = |me| Seat {
        table: Arc::clone(&table),
        me,
        count: 0,
    };
    (seat(0), seat(1))
}

impl Seat {
    /// Leaves `mine` for the other side, waits for it to reach the same meeting, and copies what
    /// it left into `theirs` (which must have its length). Allocates nothing.
    ///
    /// # Panics
    /// When `mine` is longer than the capacity, `theirs` is not as long as what the other side
    /// left, or the other side has gone.
    pub fn exchange(&mut self, mine: &[f64], theirs: &mut [f64]) {
        assert!(
            mine.len() <= self.table.capacity,
            "a meeting's numbers over the capacity"
        );
        self.count += 1;
        let (c, other) = (self.count, 1 - self.me);
        let parity = usize::from(c % 2 == 1);
        {
            let mut m = lock(&self.table.mail[self.me][parity]);
            m.clear();
            m.extend_from_slice(mine);
        }
        self.table.arrived[self.me].store(c, Ordering::Release);
        self.table.bells[other].ring();
        self.table.bells[self.me].wait(
            || self.table.arrived[other].load(Ordering::Acquire) >= c,
            || Arc::strong_count(&self.table) == 2,
            "the other side of the meeting has gone",
            &self.table.chores[self.me],
        );
        theirs.copy_from_slice(&lock(&self.table.mail[other][parity]));
    }
}

/// A mutex's guard, whether or not a thread panicked while holding it (the numbers are rewritten
/// at each meeting).
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn add(w: &mut Vec<u64>, code: u8) {
        let k = w.len() as u64;
        w.push(k * 1000 + u64::from(code));
    }

    /// A ring wakes a sleeping waiter at once: the waiter's park token is set, so its next park
    /// (here ten seconds long) returns at once instead of at its timeout. (A bell that rang nobody
    /// would still be correct, every park ends after [`Bell::NAP`], but each wait for a
    /// descheduled partner would last a nap.)
    #[test]
    fn a_ring_wakes_a_sleeping_waiter_at_once() {
        let bell = Arc::new(Bell::default());
        *lock(&bell.thread) = Some(std::thread::current());
        bell.sleeping.store(true, Ordering::Relaxed);
        // Joined by its handle (a scope's end would park this thread, taking the token).
        let ringer = Arc::clone(&bell);
        std::thread::spawn(move || ringer.ring())
            .join()
            .expect("ringer");
        let t0 = Instant::now();
        std::thread::park_timeout(Duration::from_secs(10));
        assert!(
            t0.elapsed() < Duration::from_secs(5),
            "the ring woke nobody"
        );
    }

    /// Every job asked is run once, in order, on the partner's work, and the caller sees the
    /// work it left after each wait: 20 000 jobs, some asked at once, some after the partner
    /// has parked.
    #[test]
    fn every_job_runs_once_in_order() {
        let p = Partner::start(Vec::new(), add).expect("thread");
        for k in 0..20_000u64 {
            if k % 5000 == 4999 {
                std::thread::sleep(2 * SPIN);
            }
            let code = (k % 200) as u8;
            p.ask(code);
            let w = p.wait();
            assert_eq!(w.len() as u64, k + 1);
            assert_eq!(w[k as usize], k * 1000 + u64::from(code));
        }
        p.work().clear();
        p.ask(7);
        assert_eq!(*p.wait(), vec![7]);
    }

    fn explode(_: &mut (), _: u8) {
        panic!("on purpose");
    }

    /// A partner whose job panics makes the waiting caller panic instead of waiting for ever.
    #[test]
    fn a_dead_partner_is_reported() {
        let p = Partner::start((), explode).expect("thread");
        p.ask(1);
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| drop(p.wait())));
        assert!(r.is_err());
    }

    /// Dropping a partner ends its thread, whether it spins or sleeps.
    #[test]
    fn dropping_ends_the_thread() {
        for sleep in [false, true] {
            let p = Partner::start(Vec::new(), add).expect("thread");
            p.ask(1);
            drop(p.wait());
            if sleep {
                std::thread::sleep(2 * SPIN);
            }
            let shared = Arc::clone(&p.shared);
            drop(p);
            assert_eq!(
                Arc::strong_count(&shared),
                1,
                "the thread let go of its work"
            );
        }
    }

    /// Two threads meet 50 000 times, leaving numbers of every length up to the capacity: each
    /// takes exactly what the other left at the same meeting, whichever arrives first.
    #[test]
    fn each_side_takes_what_the_other_left_at_the_same_meeting() {
        let (mut a, mut b) = seats(5);
        let k = 50_000u32;
        let other = std::thread::spawn(move || {
            let mut theirs = [0.0; 5];
            for c in 0..k {
                let len = (c % 6) as usize;
                let mine: Vec<f64> = (0..len).map(|j| f64::from(c) + 0.5 + j as f64).collect();
                b.exchange(&mine, &mut theirs[..len]);
                for (j, t) in theirs[..len].iter().enumerate() {
                    assert_eq!(*t, -(f64::from(c) + j as f64));
                }
            }
        });
        let mut theirs = [0.0; 5];
        for c in 0..k {
            let len = (c % 6) as usize;
            let mine: Vec<f64> = (0..len).map(|j| -(f64::from(c) + j as f64)).collect();
            a.exchange(&mine, &mut theirs[..len]);
            for (j, t) in theirs[..len].iter().enumerate() {
                assert_eq!(*t, f64::from(c) + 0.5 + j as f64);
            }
            if c % 10_000 == 0 {
                std::thread::sleep(Duration::from_millis(1));
            }
        }
        other.join().expect("the other side");
    }

    /// A side whose other side has gone panics instead of waiting for ever.
    #[test]
    fn a_meeting_with_a_side_gone_is_reported() {
        let (mut a, b) = seats(1);
        drop(b);
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            a.exchange(&[1.0], &mut [0.0]);
        }));
        assert!(r.is_err());
    }

    /// Chores that count up to `limit`, a piece at a time, per side.
    struct Tally {
        done: [AtomicU64; 2],
        limit: u64,
    }

    impl Chores for Tally {
        fn chore(&self, side: usize) -> bool {
            let d = &self.done[side];
            if d.load(Ordering::Relaxed) >= self.limit {
                return false;
            }
            d.fetch_add(1, Ordering::Relaxed);
            true
        }
    }

    /// A side that waits does its chores meanwhile, a piece between two reads of what it waits
    /// for, and still takes what it waits for: at a meeting (side 0 waits 5 ms for side 1, which
    /// does not wait) all of side 0's 1000 pieces are done and none of side 1's; a caller waiting
    /// 5 ms for a job does its 1000; a partner thread waiting for its next job does its 1000.
    #[test]
    fn a_waiting_side_does_its_chores() {
        let tally = Arc::new(Tally {
            done: [AtomicU64::new(0), AtomicU64::new(0)],
            limit: 1000,
        });
        let chores = SharedChores(Arc::clone(&tally) as Arc<dyn Chores>);
        let (mut a, mut b) = seats_with_chores(1, [chores.side(0), chores.side(1)]);
        let late = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(5));
            let mut theirs = [0.0];
            b.exchange(&[2.0], &mut theirs);
            theirs[0]
        });
        let mut theirs = [0.0];
        a.exchange(&[1.0], &mut theirs);
        assert_eq!(theirs[0], 2.0);
        assert_eq!(late.join().expect("side 1"), 1.0);
        let done = |side: usize| tally.done[side].load(Ordering::Relaxed);
        assert_eq!((done(0), done(1)), (1000, 0), "at a meeting");

        let tally = Arc::new(Tally {
            done: [AtomicU64::new(0), AtomicU64::new(0)],
            limit: 1000,
        });
        let chores = SharedChores(Arc::clone(&tally) as Arc<dyn Chores>);
        let slow = |w: &mut Vec<u64>, code: u8| {
            std::thread::sleep(Duration::from_millis(5));
            add(w, code);
        };
        let p = Partner::start_with_chores(Vec::new(), slow, [chores.side(0), chores.side(1)])
            .expect("thread");
        p.ask(7);
        assert_eq!(p.wait()[0], 7);
        assert_eq!(
            tally.done[0].load(Ordering::Relaxed),
            1000,
            "waiting for a job"
        );
        let t0 = Instant::now();
        while tally.done[1].load(Ordering::Relaxed) < 1000 {
            assert!(
                t0.elapsed() < Duration::from_secs(10),
                "the partner's chores"
            );
            std::thread::yield_now();
        }
    }
}
