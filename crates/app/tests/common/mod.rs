//! Helpers shared by the integration tests.

/// Edits scene text and fails the test when the text to replace is not there: an edit that silently
/// replaced nothing would leave the test checking the unedited scene.
pub trait Edit {
    /// `self` with every `from` replaced by `to`; panics if `from` does not occur.
    fn edit(&self, from: &str, to: &str) -> String;
}

impl Edit for str {
    fn edit(&self, from: &str, to: &str) -> String {
        assert!(
            self.contains(from),
            "scene edit: `{from}` does not occur in the scene text"
        );
        self.replace(from, to)
    }
}

/// `cases/scr1000/storm23.toml` shortened to 30 s (10 s ramp, envelopes and fatigue from 20 s), for
/// tests that need a short storm with waves, a vessel and fatigue. Its RAO file must be copied
/// beside the written scene.
#[allow(dead_code)]
pub fn short_storm23(root: &std::path::Path) -> String {
    std::fs::read_to_string(root.join("cases/scr1000/storm23.toml"))
        .expect("case")
        .edit("duration = 1800.0 ", "duration = 30.0 ")
        .edit("envelope_start = 200.0 ", "envelope_start = 20.0 ")
        .edit("\nstart = 200.0 ", "\nstart = 20.0 ")
        .edit("ramp = 100.0 ", "ramp = 10.0 ")
}

/// The scene in the file `case` with `edits` applied (files it names are found beside it), for
/// tests that shorten or trim a repository case.
#[allow(dead_code)]
pub fn edited_case(
    case: &std::path::Path,
    edits: &[catena::scene::edit::Edit],
) -> catena::scene::riser::RiserScene {
    catena::statics::read_scene(case)
        .expect("scene")
        .edited(edits, &catena::scene::DirResolver::beside(case))
        .expect("edited")
}
