//! Helpers shared by the integration tests.

use std::path::PathBuf;

/// `../shared/data` beside the repository, when it is there (tests that read it skip otherwise).
pub fn shared_data() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    dir.is_dir().then_some(dir)
}
