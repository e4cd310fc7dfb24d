//! Atomic file output: write to a temporary file beside the target, then rename.

use std::io;
use std::path::{Path, PathBuf};

/// A file written to a temporary path and moved into place only by [`Staged::commit`].
/// Dropping it uncommitted removes the temporary file.
#[derive(Debug)]
pub struct Staged {
    pub target: PathBuf,
    pub temp: PathBuf,
    committed: bool,
}

impl Staged {
    /// Creates the temporary path for `target` (its directory must exist).
    pub fn new(target: &Path) -> io::Result<Staged> {
        todo!("{}{}", target.display(), false)
    }
    pub fn commit(mut self) -> io::Result<()> {
        self.committed = true;
        todo!()
    }
}
