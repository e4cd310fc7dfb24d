//! Atomic file output: write to a temporary file beside the target, then rename.
//!
//! The temporary file lives in the target's directory (so the final `rename` stays on one file
//! system and is atomic on POSIX), is named `.<target name>.<pid>.<counter>.tmp`, and is created
//! with `create_new` so two writers never share it. A reader of the target therefore sees either
//! the old file or the complete new one, never a partial write.

use std::ffi::OsString;
use std::fs::{self, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes temporary files made by one process.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// A file written to a temporary path and moved into place only by [`Staged::commit`].
/// Dropping it uncommitted removes the temporary file.
#[derive(Debug)]
pub struct Staged {
    /// The file the data is meant for.
    pub target: PathBuf,
    /// The temporary file to write to, beside `target`.
    pub temp: PathBuf,
    committed: bool,
}

impl Staged {
    /// Creates the temporary path for `target`, and `target`'s directory where it is missing
    /// (the commands check the location before the work: see `cli::check_output_file`). The
    /// temporary file is created empty, so the name is reserved; writers may truncate and
    /// rewrite it.
    pub fn new(target: &Path) -> io::Result<Staged> {
        let name = target.file_name().ok_or_else(|| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "output path '{}' does not name a file: give a file path such as out/image.exr",
                    target.display()
                ),
            )
        })?;
        let dir = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !dir.is_dir() {
            fs::create_dir_all(&dir).map_err(|e| {
                io::Error::new(
                    e.kind(),
                    format!("cannot create the directory '{}' for '{}': {e}", dir.display(), target.display()),
                )
            })?;
        }
        let mut last_err = None;
        for _ in 0..16 {
            let n = COUNTER.fetch_add(1, Ordering::Relaxed);
            let mut temp_name = OsString::from(".");
            temp_name.push(name);
            temp_name.push(format!(".{}.{n}.tmp", std::process::id()));
            let temp = dir.join(temp_name);
            match OpenOptions::new().write(true).create_new(true).open(&temp) {
                Ok(_) => {
                    return Ok(Staged { target: target.to_path_buf(), temp, committed: false });
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => last_err = Some(e),
                Err(e) => {
                    return Err(io::Error::new(
                        e.kind(),
                        format!(
                            "cannot create a temporary file in '{}' for '{}': {e}",
                            dir.display(),
                            target.display()
                        ),
                    ));
                }
            }
        }
        Err(last_err.unwrap_or_else(|| io::Error::other("no free temporary file name")))
    }

    /// Moves the temporary file onto the target. On failure the temporary file is removed
    /// (when `self` drops) and the target is untouched.
    pub fn commit(mut self) -> io::Result<()> {
        fs::rename(&self.temp, &self.target).map_err(|e| {
            io::Error::new(
                e.kind(),
                format!("cannot move '{}' onto '{}': {e}", self.temp.display(), self.target.display()),
            )
        })?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            // Best effort: the file may already be gone.
            let _ = fs::remove_file(&self.temp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch_dir(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("morgana-atomic-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn commit_moves_the_temporary_file_into_place() {
        let dir = scratch_dir("commit");
        let target = dir.join("out.txt");
        fs::write(&target, "old").unwrap();
        let staged = Staged::new(&target).unwrap();
        assert_eq!(staged.temp.parent(), target.parent());
        assert_ne!(staged.temp, target);
        fs::write(&staged.temp, "new").unwrap();
        // Before the commit the target still holds the old content.
        assert_eq!(fs::read_to_string(&target).unwrap(), "old");
        let temp = staged.temp.clone();
        staged.commit().unwrap();
        assert_eq!(fs::read_to_string(&target).unwrap(), "new");
        assert!(!temp.exists());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn drop_without_commit_removes_the_temporary_file() {
        let dir = scratch_dir("drop");
        let target = dir.join("out.txt");
        let (a, b) = (Staged::new(&target).unwrap(), Staged::new(&target).unwrap());
        assert_ne!(a.temp, b.temp, "two staged files for one target must differ");
        fs::write(&a.temp, "partial").unwrap();
        let temp = a.temp.clone();
        assert!(temp.exists());
        drop(a);
        drop(b);
        assert!(!temp.exists());
        assert!(!target.exists());
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 0);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn makes_a_missing_directory_and_names_one_it_cannot_make() {
        let root = scratch_dir("mkdir");
        let target = root.join("a/b/out.exr");
        let s = Staged::new(&target).expect("stage in missing directories");
        fs::write(&s.temp, b"x").unwrap();
        s.commit().unwrap();
        assert_eq!(fs::read(&target).unwrap(), b"x");
        // A directory below a file cannot be made.
        let blocked = root.join("a/b/out.exr/c/out.exr");
        let err = Staged::new(&blocked).unwrap_err();
        assert!(
            err.to_string().contains("cannot create the directory") && err.to_string().contains("out.exr/c"),
            "{err}"
        );
        fs::remove_dir_all(&root).ok();
    }
}
