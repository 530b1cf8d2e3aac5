//! Tests across modules: scenarios of the solver, the variants, the edits and the base
//! meshes on built-in surfaces (and on `../shared/data` where it is present).

mod edit;
mod init;
mod optimize;
mod quads;
mod variants;

use std::path::PathBuf;

/// `../shared/data` beside the repository, when it is there (tests that read it skip otherwise).
fn shared_data() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    dir.is_dir().then_some(dir)
}
