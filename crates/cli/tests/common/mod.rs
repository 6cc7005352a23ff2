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
