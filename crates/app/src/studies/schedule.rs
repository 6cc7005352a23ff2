//! Many independent runs on `jobs` threads, the most expensive first.
//!
//! A study's runs (the storms of a fatigue study, the points of a sweep, the runs of a strength
//! study) differ in cost: a storm of Hs 7.5 m takes about twice a calm one's Newton iterations. Run
//! in the table's order, the last wave of runs can be one slow storm while the other cores idle.
//! Here each thread takes the next run of a list sorted by expected cost, most expensive first
//! (longest processing time first, LPT: within 4/3 of the best schedule whatever the costs, Graham
//! 1969), so that the last runs to start are the cheapest. The results come back in the items'
//! order, whatever order they ran in: a study's outputs do not depend on the schedule.
//!
//! **Expected cost** ([`run_cost`]): time steps × nodes × the seabed law's relative cost × the
//! sea's factor `1 + Hs/H_ITER` ([`H_ITER`]: measured on the scaling study, the Newton iterations a
//! step grow with the waves' height). Only the order matters, so the model need only rank runs.
//!
//! **Threads per run** ([`threads_per_run`]): the cores shared between the `jobs` runs side by
//! side, at least one each. At `--jobs` equal to the cores every run keeps one thread busy (its
//! fatigue counting on its stepping thread, [`crate::run::RunOptions::threads`]), so the study
//! does not run more busy threads than there are cores.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use crate::scene::riser::RiserScene;

/// The significant wave height at which a storm costs twice a calm run of the same size, m: a
/// round upper estimate from the scaling study (`cases/scr1000/fatigue/scaling/`, 30 storms of
/// 200 s on the Randolph–Quiggin seabed, one at a time: 1.4–1.8 s a storm at Hs 0.5 m, 1.5–2.7 s at
/// Hs 7.5 m, the longest periods the dearest). Between storms of one study only the ranking matters
/// (any positive value ranks them by Hs); between runs of different sizes the steps and nodes
/// dominate.
pub const H_ITER: f64 = 10.0;

/// The expected cost of a dynamic run of `scene`, in arbitrary units (comparable between runs).
pub fn run_cost(scene: &RiserScene) -> f64 {
    let steps = scene.size.steps.max(1) as f64;
    let nodes = (scene.size.elements + 1) as f64;
    let law = scene
        .model
        .seabed
        .as_ref()
        .map_or(1.0, |s| s.seabed.law.relative_cost());
    // Hs of the realised components: 4·√m0, m0 = Σ a²/2.
    let hs = scene
        .dynamic
        .as_ref()
        .and_then(|d| d.environment.waves.as_ref())
        .map_or(0.0, |w| {
            let m0: f64 = w.components.iter().map(|c| 0.5 * c.amplitude.powi(2)).sum();
            4.0 * m0.sqrt()
        });
    steps * nodes * law * (1.0 + hs / H_ITER)
}

/// The threads each of `jobs` runs side by side may keep busy on this machine
/// ([`threads_per_run_on`] its cores).
pub fn threads_per_run(jobs: usize) -> usize {
    threads_per_run_on(jobs, crate::run::default_threads())
}

/// The threads each of `jobs` runs side by side may keep busy on `cores` cores: an equal share,
/// at least one.
pub fn threads_per_run_on(jobs: usize, cores: usize) -> usize {
    (cores / jobs.max(1)).max(1)
}

/// The indices of `costs` by decreasing cost (ties: in their order; a cost that is not a number
/// counts as the greatest).
pub fn order(costs: &[f64]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..costs.len()).collect();
    let key = |i: usize| {
        if costs[i].is_nan() {
            f64::INFINITY
        } else {
            costs[i]
        }
    };
    idx.sort_by(|&a, &b| key(b).total_cmp(&key(a)).then(a.cmp(&b)));
    idx
}

/// Runs `run` on every item on `jobs` threads, the items taken by decreasing `cost` (each thread
/// takes the next as it finishes one); the results in the items' order.
pub fn by_cost<I: Sync, R: Send>(
    items: &[I],
    jobs: usize,
    cost: impl Fn(&I) -> f64,
    run: impl Fn(&I) -> R + Sync,
) -> Vec<R> {
    let n = items.len();
    let costs: Vec<f64> = items.iter().map(cost).collect();
    let queue = order(&costs);
    let next = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<R>>> = (0..n).map(|_| Mutex::new(None)).collect();
    std::thread::scope(|s| {
        for _ in 0..jobs.clamp(1, n.max(1)) {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::SeqCst);
                let Some(&i) = queue.get(k) else {
                    break;
                };
                let r = run(&items[i]);
                *slots[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
            });
        }
    });
    slots
        .into_iter()
        .map(|m| {
            m.into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .expect("every item ran")
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs side by side share the cores: one thread each once the jobs reach the cores.
    #[test]
    fn runs_side_by_side_share_the_cores() {
        assert_eq!(threads_per_run_on(1, 2), 2);
        assert_eq!(threads_per_run_on(2, 2), 1);
        assert_eq!(threads_per_run_on(3, 2), 1);
        assert_eq!(threads_per_run_on(0, 2), 2);
        assert_eq!(threads_per_run_on(8, 16), 2);
        assert_eq!(threads_per_run_on(16, 16), 1);
        assert_eq!(threads_per_run_on(4, 1), 1);
    }

    #[test]
    fn the_order_is_by_decreasing_cost_ties_in_order() {
        assert_eq!(order(&[1.0, 3.0, 2.0, 3.0]), vec![1, 3, 2, 0]);
        assert_eq!(order(&[1.0, f64::NAN, 2.0]), vec![1, 2, 0]);
        assert!(order(&[]).is_empty());
    }

    /// The most expensive items start first (one thread: exactly in cost order), and the results
    /// come back in the items' order whatever the number of threads.
    #[test]
    fn runs_start_most_expensive_first_and_return_in_order() {
        let items: Vec<u32> = vec![3, 9, 1, 7, 5];
        let started = Mutex::new(Vec::new());
        let out = by_cost(
            &items,
            1,
            |&c| f64::from(c),
            |&c| {
                started.lock().expect("lock").push(c);
                2 * c
            },
        );
        assert_eq!(out, vec![6, 18, 2, 14, 10]);
        assert_eq!(*started.lock().expect("lock"), vec![9, 7, 5, 3, 1]);
        for jobs in [2, 3, 8] {
            let out = by_cost(&items, jobs, |&c| f64::from(c), |&c| 2 * c);
            assert_eq!(out, vec![6, 18, 2, 14, 10], "{jobs} jobs");
        }
    }

    /// The finish time of list scheduling (each of `jobs` threads takes the next item as it
    /// finishes one) of items of these durations in this order.
    fn makespan(durations: &[f64], jobs: usize, order: &[usize]) -> f64 {
        let mut free = vec![0.0f64; jobs];
        for &i in order {
            let t = free
                .iter_mut()
                .min_by(|a, b| a.total_cmp(b))
                .expect("a thread");
            *t += durations[i];
        }
        free.into_iter().fold(0.0, f64::max)
    }

    /// One long item listed last among short ones, two threads: in the table's order it starts
    /// last and ends alone (100); by cost it starts first (80, the best).
    #[test]
    fn the_long_item_is_not_the_last_wave() {
        let d = [20.0, 20.0, 20.0, 20.0, 60.0];
        let table: Vec<usize> = (0..d.len()).collect();
        assert_eq!(makespan(&d, 2, &table), 100.0);
        assert_eq!(makespan(&d, 2, &order(&d)), 80.0);
    }

    /// The scaling study's storms (`cases/scr1000/fatigue/scaling/`): the same size, so ranked by
    /// Hs; a storm with twice the steps costs twice as much.
    #[test]
    fn storms_cost_by_their_sea_and_their_size() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let study = crate::studies::fatigue_study::Study::read(
            &root.join("cases/scr1000/fatigue/scaling/study-rq-30-storms-200s.toml"),
        )
        .expect("study");
        let cost = |k: usize| run_cost(&study.storms[k].1);
        let hs = |k: usize| study.storms[k].0.hs;
        for k in 1..study.storms.len() {
            if hs(k) > hs(k - 1) {
                assert!(cost(k) > cost(k - 1), "storm {k}");
            }
        }
        let calm = cost(0);
        let mut longer = study.storms[0].1.clone();
        longer.size.steps *= 2;
        assert!((run_cost(&longer) / calm - 2.0).abs() < 1e-12);
    }
}
