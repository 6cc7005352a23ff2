//! Two threads step a line as one does, to the bit (issue 48): from the same statics, each case is
//! stepped by [`dynamics::advance`] on one thread and by a [`Pair`] on two, and after every step
//! the two States (displacements, velocities, accelerations, forces, seabed histories, friction
//! anchors), the step's counts (iterations, retries, cuts) and the nodal results are compared
//! bit for bit. The cases cover the effects a pair steps: the heave benchmark (linear seabed,
//! drag, harmonic heave), the Randolph–Quiggin seabed through lift-off with step cuts, axial
//! friction, soil zones, attached bodies, a current, and lazy waves' sections with a flexjoint.

use std::path::Path;

use catena::run;
use catena::scene::edit::Edit;
use catena::scene::DirResolver;
use catena::statics;
use catena_fe::assembly::LineResults;
use catena_fe::dynamics::{self, Drive, DynState, DynWorkspace, Pair, Samples};
use catena_fe::wave_sampling::Sample;

/// The bits of a list of numbers.
fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

fn same_state(case: &str, k: usize, one: &DynState, two: &DynState) {
    for (what, a, b) in [
        ("u", &one.u, &two.u),
        ("v", &one.v, &two.v),
        ("a", &one.a, &two.a),
        ("f_prev", &one.f_prev, &two.f_prev),
        (
            "friction_anchor",
            &one.friction_anchor,
            &two.friction_anchor,
        ),
    ] {
        assert_eq!(bits(a), bits(b), "{case}: step {k}: {what} differs");
    }
    assert_eq!(
        one.history, two.history,
        "{case}: step {k}: histories differ"
    );
    assert_eq!(
        one.t.to_bits(),
        two.t.to_bits(),
        "{case}: step {k}: t differs"
    );
    let grid = |s: &DynState| {
        s.wave_grid.as_ref().map(|g| {
            let sample = |x: &Option<_>| -> Vec<u64> {
                x.iter()
                    .flat_map(|s: &Sample| [s.v, s.a, s.j])
                    .flatten()
                    .map(f64::to_bits)
                    .collect()
            };
            let samples: Vec<_> = g.samples.iter().flatten().map(sample).collect();
            (g.index, samples)
        })
    };
    assert_eq!(
        grid(one),
        grid(two),
        "{case}: step {k}: the wave kinematics samples differ"
    );
}

fn same_results(case: &str, k: usize, one: &LineResults, two: &LineResults) {
    for (what, a, b) in [
        ("x", &one.x, &two.x),
        ("z", &one.z, &two.z),
        ("tension", &one.tension, &two.tension),
        ("moment", &one.moment, &two.moment),
        ("penetration", &one.penetration, &two.penetration),
        ("seabed_force", &one.seabed_force, &two.seabed_force),
    ] {
        assert_eq!(bits(a), bits(b), "{case}: step {k}: results' {what} differ");
    }
    assert_eq!(one.mode, two.mode, "{case}: step {k}: contact modes differ");
}

/// Steps `case` `steps` times on one thread and on two; returns the step cuts and retries taken.
fn one_and_two(case: &str, steps: usize) -> (u32, u32) {
    let (cuts, retries, ..) = edited_one_and_two(case, &[], steps, Samples::Own);
    (cuts, retries)
}

/// How the second line is stepped: by a pair all along, its wave samples shared as it says, or by
/// a [`Drive`] shifting between one thread and two on a fixed schedule.
#[derive(Clone, Copy)]
enum How {
    Pair(Samples),
    Drive(fn(u64) -> bool),
}

impl From<Samples> for How {
    fn from(s: Samples) -> Self {
        Self::Pair(s)
    }
}

/// The second line's stepping.
enum Second {
    Pair(Pair),
    Drive(Drive),
}

/// [`one_and_two`] on `case` with `edits`, the pair's wave samples shared as `samples` says; also
/// returns how many of the steps had a node out of the water at a wave kinematics sample, and how
/// many of the first part's nodes the second thread sampled.
fn edited_one_and_two(
    case: &str,
    edits: &[Edit],
    steps: usize,
    how: impl Into<How>,
) -> (u32, u32, usize, usize) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../cases")
        .join(case);
    let scene = statics::read_scene(&path).expect("case");
    let scene = scene
        .edited(edits, &DirResolver::beside(&path))
        .expect("edits");
    let st = statics::solve(scene).expect("statics");
    let (spec, dm) = run::prepare(&st).expect("dynamic model");
    // Shared with the second thread during each step.
    let dm = std::sync::Arc::new(dm);
    let n = dm.line.nodes();
    let mut ws1 = DynWorkspace::new(&dm.line).expect("workspace");
    let mut ws2 = DynWorkspace::new(&dm.line).expect("workspace");
    let mut one = dynamics::initial_state(&dm, &st.u, &mut ws1);
    let mut two = dynamics::initial_state(&dm, &st.u, &mut ws2);
    let (mut second, lent) = match how.into() {
        How::Pair(samples) => {
            let pair = Pair::start_with(&dm, &two, &mut ws2, samples)
                .expect("a thread")
                .unwrap_or_else(|| panic!("{case}: a line a pair steps"));
            let lent = pair.lent_nodes(&ws2);
            (Second::Pair(pair), lent)
        }
        How::Drive(schedule) => (Second::Drive(Drive::with_schedule(schedule)), 0),
    };
    let (mut r1, mut r2) = (LineResults::new(n), LineResults::new(n));
    let (mut cuts, mut retries, mut dry) = (0, 0, 0);
    for k in 1..=steps {
        let i1 = dynamics::advance(&dm, &mut one, &mut ws1, spec.dt);
        let i2 = match &mut second {
            Second::Pair(p) => p.advance(&dm, &mut two, &mut ws2, spec.dt),
            Second::Drive(d) => d.advance(&dm, &mut two, &mut ws2, spec.dt),
        };
        assert_eq!(i1, i2, "{case}: step {k}: the steps' outcomes differ");
        let info = i1.unwrap_or_else(|e| panic!("{case}: step {k}: {e}"));
        (cuts, retries) = (cuts + info.cuts, retries + info.retries);
        let samples = one
            .wave_grid
            .iter()
            .flat_map(|g| g.samples.iter().flatten());
        dry += usize::from(samples.clone().any(Option::is_none));
        // As a run does: the time is the step count times Δt.
        one.t = k as f64 * spec.dt;
        two.t = one.t;
        same_state(case, k, &one, &two);
        dynamics::results(&dm, &one, &ws1, &mut r1);
        dynamics::results(&dm, &two, &ws2, &mut r2);
        same_results(case, k, &r1, &r2);
    }
    let m1 = ws1.solver_memory().expect("a factorisation");
    let m2 = match &second {
        Second::Pair(p) => p.solver_memory(&mut ws2),
        Second::Drive(d) => d.solver_memory(&mut ws2),
    }
    .expect("a factorisation");
    assert_eq!(
        bits(&m1.values),
        bits(&m2.values),
        "{case}: solver memories differ"
    );
    assert_eq!(m1.dt.to_bits(), m2.dt.to_bits());
    match second {
        Second::Pair(p) => p.stop(&dm, &mut ws2),
        Second::Drive(mut d) => {
            let ([on_one, on_two], shifts) = d.tally();
            assert!(
                on_one > 0 && on_two > 0 && shifts >= 4,
                "{case}: the drive did not shift"
            );
            d.stop(&dm, &mut ws2);
        }
    }
    println!("{case}: {steps} steps, {cuts} cuts, {retries} retries, {dry} with a node out of the water, {lent} nodes sampled by the second thread for the first: the same bits");
    (cuts, retries, dry, lent)
}

#[test]
fn two_threads_step_the_heave_benchmark_as_one_to_the_bit() {
    one_and_two("benchmarks/scr-heave.toml", 400);
}

/// Sticky soil: the Randolph–Quiggin seabed at lift-off, where steps are cut and retried (the
/// decisions must be the same on both threads).
#[test]
fn two_threads_step_through_cuts_as_one_to_the_bit() {
    let (cuts, retries) = one_and_two("hard/sticky-soil.toml", 300);
    assert!(cuts + retries > 0, "the case no longer cuts a step");
}

#[test]
fn two_threads_step_friction_zones_and_attachments_as_one_to_the_bit() {
    for case in [
        "hard/friction-stick-slip.toml",
        "hard/zone-boundary.toml",
        "benchmarks/scr-attachments.toml",
        "benchmarks/scr-current.toml",
        "lazy-wave/heave.toml",
    ] {
        one_and_two(case, 150);
    }
}

/// A lazy wave heaved hard (CableDyn's comparison case): the convergence test's rounding floor
/// grows with the largest displacement anywhere on the line, which each thread finds on its own
/// part (a floor from a thread's stale copy of the other part made the threads take different
/// iterations here).
#[test]
fn two_threads_step_a_heaved_lazy_wave_as_one_to_the_bit() {
    one_and_two("lazy-wave/cabledyn-heave.toml", 600);
}

/// Waves, their kinematics taken at each thread's own nodes: storm 23's JONSWAP sea (400
/// components) with the semi-submersible's RAO motion, its kinematics sampled on the time grid
/// (each thread sampling its own nodes, and the samples shared: the second thread sampling some
/// of the first part's too), exact at every step, and with the hang-off 1 m below the surface
/// (nodes out of the water at a sample get their exact kinematics); and Airy's regular wave on a
/// riser held still.
#[test]
fn two_threads_step_waves_as_one_to_the_bit() {
    let storm = "scr1000/storm23.toml";
    let ramp = Edit::set("waves.ramp", 5.0);
    let (.., lent) = edited_one_and_two(storm, std::slice::from_ref(&ramp), 300, Samples::Own);
    assert_eq!(lent, 0, "each thread samples its own nodes");
    let (.., lent) = edited_one_and_two(storm, std::slice::from_ref(&ramp), 300, Samples::Shared);
    // The second thread samples some of the first part's nodes (the surface is all in the first).
    assert!(lent > 0, "no samples lent");
    // Newton given two iterations: steps cut in sub-steps, some taking new samples after the
    // first sub-step (the lent nodes sampled from the State it committed).
    let two_iterations = Edit::set("dynamic.max_iterations", 2);
    let (cuts, ..) =
        edited_one_and_two(storm, &[ramp.clone(), two_iterations], 300, Samples::Shared);
    assert!(cuts > 0, "no step cut");
    let exact = Edit::set("waves.kinematics_interval", 0.0);
    let (.., lent) = edited_one_and_two(storm, &[ramp.clone(), exact], 150, Samples::Shared);
    assert_eq!(lent, 0, "nothing to lend without samples");
    let above = Edit::set("ends.top_z", 999.0);
    let (_, _, dry, _) = edited_one_and_two(storm, &[ramp, above], 300, Samples::Shared);
    assert!(dry > 0, "no node was ever out of the water");
    one_and_two("benchmarks/riser-airy-wave.toml", 300);
}

/// A [`Drive`] shifting between one thread and two mid-run (issue 69) steps as one thread does, to
/// the bit: the pair's solver memory kept by the first thread when the pair stops, a pair started
/// from the State and that memory, on a schedule with runs of both lengths and single steps, through
/// step cuts (sticky soil, Newton given two iterations in storm 23's waves) and the wave samples
/// lent between the threads.
#[test]
fn a_drive_shifting_between_one_and_two_threads_steps_as_one_to_the_bit() {
    let schedule: fn(u64) -> bool = |k| (k / 7) % 2 == 0 || k % 13 == 5;
    let (cuts, retries, ..) =
        edited_one_and_two("hard/sticky-soil.toml", &[], 300, How::Drive(schedule));
    assert!(cuts + retries > 0, "the case no longer cuts a step");
    let ramp = Edit::set("waves.ramp", 5.0);
    let two_iterations = Edit::set("dynamic.max_iterations", 2);
    let (cuts, ..) = edited_one_and_two(
        "scr1000/storm23.toml",
        &[ramp, two_iterations],
        300,
        How::Drive(schedule),
    );
    assert!(cuts > 0, "no step cut");
    edited_one_and_two("benchmarks/scr-heave.toml", &[], 200, How::Drive(schedule));
}

/// A run on two threads (`RunOptions::threads`) is the run on one, to the bit: the heave
/// benchmark's envelopes, gauges, top history and Newton counts. A run stopped at a checkpoint on
/// two threads and restarted, on two threads or on one, ends as the uninterrupted run (the
/// checkpoint's solver memory is the whole tangent's).
#[test]
fn a_run_on_two_threads_is_the_run_on_one_and_restarts_bit_for_bit() {
    use catena::checkpoint::Checkpoint;
    use catena::observe::Checkpointer;
    use catena::run::RunOptions;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/benchmarks/scr-heave.toml");
    let st = statics::solve(statics::read_scene(&path).expect("case")).expect("statics");
    let on = |threads| {
        let opts = RunOptions::with_threads(Some(threads));
        run::run(st.clone(), &mut [], opts).expect("runs")
    };
    let (one, two) = (on(1), on(2));
    assert!(one.completed() && two.completed());
    assert_eq!(one.envelopes, two.envelopes, "envelopes");
    assert_eq!(one.gauges, two.gauges, "gauges");
    assert_eq!(one.top, two.top, "top history");
    assert_eq!(
        (one.iterations, one.cuts, one.retries),
        (two.iterations, two.cuts, two.retries)
    );
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("two-threads-restart");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut cut = Checkpointer::new(&dir.join("cut.json"), 250);
    let opts = RunOptions {
        stop_after: Some(1000),
        ..RunOptions::with_threads(Some(2))
    };
    run::run(st.clone(), &mut [&mut cut], opts).expect("runs");
    let cp = Checkpoint::read(&dir.join("cut.json")).expect("checkpoint");
    assert_eq!(cp.step, 1000);
    for threads in [2, 1] {
        let opts = RunOptions {
            restart: Some(cp.clone()),
            restart_file: "cut.json".into(),
            ..RunOptions::with_threads(Some(threads))
        };
        let after = run::run(st.clone(), &mut [], opts).expect("runs");
        assert_eq!(after.steps, one.steps);
        assert_eq!(one.envelopes, after.envelopes, "restarted on {threads}");
        assert_eq!(one.top, after.top, "restarted on {threads}");
    }
}

/// An observer that says it keeps a thread busy (as the HDF5 writer does).
struct Busy;

impl catena::observe::Observer for Busy {
    fn name(&self) -> &'static str {
        "busy"
    }

    fn step(
        &mut self,
        _: &catena::observe::RunContext<'_>,
        _: &catena::observe::StepView<'_>,
    ) -> Result<catena::observe::Control, catena::AppError> {
        Ok(catena::observe::Control::Continue)
    }

    fn busy_threads(&self) -> usize {
        1
    }
}

/// A run steps the line on two threads where its threads leave two beside its observers' own
/// (the HDF5 writer's), with waves or without; else on one. (40 steps: asked for two threads, a
/// run's drive tries them after a first block of 32 steps on one, [`Drive`].)
#[test]
fn a_run_steps_on_two_threads_only_where_it_has_them() {
    use catena::run::RunOptions;
    let heave = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/benchmarks/scr-heave.toml");
    let mut st = statics::solve(statics::read_scene(&heave).expect("case")).expect("statics");
    st.scene.dynamic.as_mut().expect("dynamic").duration = 2.0;
    let stepping = |threads, extra: &mut [&mut dyn catena::observe::Observer]| {
        let opts = RunOptions::with_threads(Some(threads));
        run::run(st.clone(), extra, opts)
            .expect("runs")
            .stepping_threads
    };
    assert_eq!(stepping(1, &mut []), 1);
    assert_eq!(stepping(2, &mut []), 2);
    assert_eq!(stepping(2, &mut [&mut Busy]), 1);
    assert_eq!(stepping(3, &mut [&mut Busy]), 2);
    let waves = heave.with_file_name("scr-regular-wave.toml");
    let mut st = statics::solve(statics::read_scene(&waves).expect("case")).expect("statics");
    st.scene.dynamic.as_mut().expect("dynamic").duration = 2.0;
    let opts = RunOptions::with_threads(Some(2));
    let r = run::run(st, &mut [], opts).expect("runs");
    assert_eq!(
        r.stepping_threads, 2,
        "a scene with waves steps on two threads"
    );
}
