//! A run started from what another left ([`catena::run::RunOptions::start`]): the carried state
//! of the statics is the as-laid start to the bit; a carry of another Model is refused by name.

use std::path::Path;

use catena::run::{self, RunOptions};
use catena::statics;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// The dynamic State the statics of `scene` give, as a carry.
fn statics_carry(scene: &catena::scene::riser::RiserScene) -> catena_fe::dynamics::Carry {
    let st = statics::solve(scene.clone()).expect("statics");
    let (_, dm) = run::prepare(&st).expect("model");
    let mut ws = catena_fe::dynamics::DynWorkspace::new(&dm.line).expect("workspace");
    catena_fe::dynamics::initial_state(&dm, &st.u, &mut ws).carry()
}

/// The heave benchmark (Randolph–Quiggin seabed): started from the statics' state as a carry, the run is the run from the statics to the bit (top
/// tension history and every envelope).
#[test]
fn the_statics_carried_is_the_as_laid_start_to_the_bit() {
    let scene =
        statics::read_scene(&root().join("cases/benchmarks/scr-heave.toml")).expect("scene");
    let carry = statics_carry(&scene);
    let plain = run::simulate(scene.clone(), &mut [], RunOptions::default()).expect("runs");
    let carried = run::simulate(
        scene,
        &mut [],
        RunOptions {
            start: Some(carry),
            ..RunOptions::default()
        },
    )
    .expect("runs");
    assert!(plain.completed() && carried.completed());
    let top = |r: &run::DynamicRun| -> Vec<u64> {
        r.top.top_tension.iter().map(|x| x.to_bits()).collect()
    };
    assert_eq!(top(&plain), top(&carried));
    assert_eq!(plain.carry, carried.carry);
}

/// A carry from another mesh does not fit: the error names the field.
#[test]
fn a_carry_of_another_model_is_refused() {
    let scene =
        statics::read_scene(&root().join("cases/benchmarks/scr-heave.toml")).expect("scene");
    let mut carry = statics_carry(&scene);
    carry.u.truncate(carry.u.len() - 3);
    let e = run::simulate(
        scene,
        &mut [],
        RunOptions {
            start: Some(carry),
            ..RunOptions::default()
        },
    )
    .expect_err("refused")
    .to_string();
    assert!(e.contains("state.u"), "{e}");
}
