//! What the integration tests of `catena-io` share.

use std::path::Path;

/// The heave benchmark's scene (`cases/benchmarks/scr-heave.toml`) with `edits`, each a key of
/// the case file and its new number.
pub fn heave_scene(edits: &[(&str, f64)]) -> catena::scene::riser::RiserScene {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let case = root.join("cases/benchmarks/scr-heave.toml");
    let scene = catena::statics::read_scene(&case).expect("the heave benchmark reads");
    let files = catena::scene::DirResolver::beside(&case);
    let edits: Vec<_> = edits
        .iter()
        .map(|(k, v)| catena::scene::edit::Edit::set(k, toml::Value::Float(*v)))
        .collect();
    scene.edited(&edits, &files).expect("edits apply")
}
