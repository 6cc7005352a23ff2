//! The cores a run can have (issue 69): the machine's, less those that the runs under way in this
//! process hold.
//!
//! A run that is not told how many threads it may keep busy ([`super::RunOptions::threads`]:
//! `None`) takes the cores no other run of the process holds, at least one: the first of two runs
//! started together from two Python threads takes the machine's cores, the second one thread,
//! and neither oversubscribes the cores the other already uses. A run told its threads holds what
//! it was told. What a run holds is given back when it ends ([`Cores`] on drop), whether it
//! completed, failed or panicked.
//!
//! Other processes' load is not counted here (a build beside the run, another `catena`): where the
//! cores are busy with other work, the run's [`catena_fe::dynamics::Drive`] measures that two
//! threads do not pay and steps on one.

use std::sync::atomic::{AtomicUsize, Ordering};

/// The threads the runs under way in this process hold.
static HELD: AtomicUsize = AtomicUsize::new(0);

/// The machine's cores (1 when they cannot be read).
pub fn machine_cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
}

/// The threads a run would take now if not told: the machine's cores less those the runs under
/// way in this process hold, at least 1.
pub fn default_threads() -> usize {
    free(machine_cores(), HELD.load(Ordering::Acquire))
}

fn free(cores: usize, held: usize) -> usize {
    cores.saturating_sub(held).max(1)
}

/// The threads a run holds while it runs, given back on drop.
#[derive(Debug)]
pub struct Cores {
    threads: usize,
    held: &'static AtomicUsize,
}

impl Cores {
    /// Takes `threads` (at least 1), or when `None` the cores free now ([`default_threads`]),
    /// counted at once so that two runs starting together do not both take the free cores.
    pub fn take(threads: Option<usize>) -> Self {
        Self::take_from(&HELD, machine_cores(), threads)
    }

    fn take_from(held: &'static AtomicUsize, cores: usize, threads: Option<usize>) -> Self {
        let threads = match threads {
            Some(t) => {
                let t = t.max(1);
                held.fetch_add(t, Ordering::AcqRel);
                t
            }
            None => {
                let mut now = held.load(Ordering::Acquire);
                loop {
                    let t = free(cores, now);
                    match held.compare_exchange_weak(
                        now,
                        now + t,
                        Ordering::AcqRel,
                        Ordering::Acquire,
                    ) {
                        Ok(_) => break t,
                        Err(seen) => now = seen,
                    }
                }
            }
        };
        Self { threads, held }
    }

    /// The threads held.
    pub fn threads(&self) -> usize {
        self.threads
    }
}

impl Drop for Cores {
    fn drop(&mut self) {
        self.held.fetch_sub(self.threads, Ordering::AcqRel);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run not told its threads takes the cores the others do not hold, at least one, and gives
    /// them back when it ends; two runs taking at once from eight threads never hold more than
    /// the cores between them but for the one each always gets. (A count of its own: the
    /// process's is shared with the other tests' runs.)
    #[test]
    fn a_run_takes_the_cores_the_others_do_not_hold() {
        let held: &'static AtomicUsize = Box::leak(Box::new(AtomicUsize::new(0)));
        let first = Cores::take_from(held, 2, None);
        assert_eq!(first.threads(), 2);
        let second = Cores::take_from(held, 2, None);
        assert_eq!(second.threads(), 1, "the cores are held by the first");
        let told = Cores::take_from(held, 2, Some(3));
        assert_eq!(told.threads(), 3);
        drop((first, second, told));
        assert_eq!(held.load(Ordering::Acquire), 0, "every core given back");
        let taken: Vec<usize> = std::thread::scope(|s| {
            let hs: Vec<_> = (0..8)
                .map(|_| s.spawn(|| Cores::take_from(held, 4, None)))
                .collect();
            let all: Vec<Cores> = hs
                .into_iter()
                .map(|h| h.join().expect("a thread"))
                .collect();
            all.iter().map(Cores::threads).collect()
        });
        assert_eq!(taken.iter().filter(|&&t| t > 1).count(), 1, "{taken:?}");
        assert_eq!(taken.iter().sum::<usize>(), 4 + 7, "{taken:?}");
        assert_eq!(held.load(Ordering::Acquire), 0);
    }
}
