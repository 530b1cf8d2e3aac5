//! Output files that appear whole or not at all: each is written under a temporary name next
//! to its target and renamed over it only once every file of the set is complete, so a failed
//! run (a full disk, a bad path) leaves no half-written file and no partial set behind.

use super::mesh_writer;
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use std::ffi::OsString;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Distinguishes the temporary files of concurrent writes from one process.
static TEMP_COUNTER: AtomicUsize = AtomicUsize::new(0);

/// A hidden name for a temporary `role` of `name` (`.NAME.ROLE-PID-K`), unique within this
/// process and apart from other processes'.
fn hidden(name: &std::ffi::OsStr, role: &str) -> OsString {
    let mut hidden = OsString::from(".");
    hidden.push(name);
    hidden.push(format!(
        ".{role}-{}-{}",
        std::process::id(),
        TEMP_COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    hidden
}

/// Runs `write` on a temporary file next to `path`, then renames it over `path`, so that readers
/// see either the old file or the complete new one, never a partial write. On failure the
/// temporary file is removed and `path` is left untouched.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let mut outputs = Outputs::new();
    outputs.file(path, write)?;
    outputs.commit()
}

/// A set of files written together: [`Outputs::commit`] renames them into place in the order
/// they were written; dropped before that (an error on the way), it removes what it wrote.
#[derive(Default)]
pub struct Outputs {
    /// (temporary file, target), in writing order.
    staged: Vec<(PathBuf, PathBuf)>,
}

impl Outputs {
    pub fn new() -> Outputs {
        Outputs::default()
    }

    /// Writes one file of the set under its temporary name.
    pub fn file(
        &mut self,
        path: &Path,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<()> {
        let name = path.file_name().ok_or_else(|| {
            Error::Parameter(format!("cannot write {}: not a file name", path.display()))
        })?;
        // Same directory as the target: a rename is only atomic within one file system.
        let temp = path.with_file_name(hidden(name, "tmp"));
        let written = (|| {
            let mut writer = BufWriter::new(File::create(&temp)?);
            write(&mut writer)?;
            let file = writer.into_inner().map_err(|e| e.into_error())?;
            file.sync_all()
        })();
        match written {
            Ok(()) => {
                self.staged.push((temp, path.to_path_buf()));
                Ok(())
            }
            Err(source) => {
                // Best effort: the write error is the one worth reporting.
                let _ = std::fs::remove_file(&temp);
                Err(Error::Io {
                    path: path.to_path_buf(),
                    source,
                })
            }
        }
    }

    /// Writes a mesh of the set, in the format its extension names.
    pub fn mesh(&mut self, path: &Path, mesh: &PolyMesh) -> Result<()> {
        let write = mesh_writer(path, mesh)?;
        self.file(path, write)
    }

    /// Renames every file into place; a file meant to describe the others (a report) is
    /// best written last, so it is also renamed last.
    pub fn commit(mut self) -> Result<()> {
        let mut staged = std::mem::take(&mut self.staged).into_iter();
        while let Some((temp, path)) = staged.next() {
            if let Err(source) = std::fs::rename(&temp, &path) {
                let _ = std::fs::remove_file(&temp);
                // The files not yet renamed go when `self` is dropped.
                self.staged = staged.collect();
                return Err(Error::Io { path, source });
            }
        }
        Ok(())
    }
}

/// Fills a new folder that takes `dir`'s place whole: `fill` writes into a hidden folder beside
/// `dir`, which is then renamed to `dir` (an old `dir` is moved aside first and removed after).
/// If `fill` or a rename fails, the hidden folder is removed and an old `dir` stays as it was.
pub fn replace_folder(dir: &Path, fill: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let io = |path: &Path, source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let (Some(parent), Some(name)) = (dir.parent(), dir.file_name()) else {
        return Err(Error::Parameter(format!(
            "cannot write the folder {}: not a folder name",
            dir.display()
        )));
    };
    let (temp, old) = (
        parent.join(hidden(name, "saving")),
        parent.join(hidden(name, "old")),
    );
    std::fs::create_dir_all(&temp).map_err(|e| io(&temp, e))?;
    let swapped = fill(&temp).and_then(|()| {
        if !dir.exists() {
            return std::fs::rename(&temp, dir).map_err(|e| io(dir, e));
        }
        std::fs::rename(dir, &old).map_err(|e| io(dir, e))?;
        std::fs::rename(&temp, dir).map_err(|e| {
            // Best effort: put the old folder back; the rename's error is the one to report.
            let _ = std::fs::rename(&old, dir);
            io(dir, e)
        })?;
        let _ = std::fs::remove_dir_all(&old);
        Ok(())
    });
    if swapped.is_err() {
        let _ = std::fs::remove_dir_all(&temp);
    }
    swapped
}

impl Drop for Outputs {
    fn drop(&mut self) {
        for (temp, _) in &self.staged {
            let _ = std::fs::remove_file(temp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("honeycomb-outputs-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_set_appears_whole_on_commit() {
        let dir = scratch("whole");
        let mut outputs = Outputs::new();
        outputs
            .file(&dir.join("a.txt"), |w| w.write_all(b"a"))
            .unwrap();
        outputs
            .file(&dir.join("b.txt"), |w| w.write_all(b"b"))
            .unwrap();
        // Before the commit only the temporary files exist.
        assert!(
            names(&dir).iter().all(|n| n.starts_with('.')),
            "{:?}",
            names(&dir)
        );
        outputs.commit().unwrap();
        assert_eq!(names(&dir), ["a.txt", "b.txt"]);
        assert_eq!(std::fs::read_to_string(dir.join("b.txt")).unwrap(), "b");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_replaced_folder_holds_only_the_new_files() {
        let root = scratch("replace");
        let dir = root.join("saved");
        for contents in ["first", "second"] {
            replace_folder(&dir, |d| {
                write_atomically(&d.join("a.txt"), |w| w.write_all(contents.as_bytes()))
            })
            .unwrap();
            assert_eq!(
                std::fs::read_to_string(dir.join("a.txt")).unwrap(),
                contents
            );
        }
        std::fs::write(dir.join("stale.txt"), "x").unwrap();
        replace_folder(&dir, |d| {
            write_atomically(&d.join("b.txt"), |w| w.write_all(b"b"))
        })
        .unwrap();
        assert_eq!(names(&dir), ["b.txt"]);
        assert_eq!(names(&root), ["saved"]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_failed_fill_leaves_the_old_folder_and_nothing_else() {
        let root = scratch("replace-failure");
        let dir = root.join("saved");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("a.txt"), "old").unwrap();
        let failed = replace_folder(&dir, |d| {
            write_atomically(&d.join("a.txt"), |w| w.write_all(b"new"))?;
            Err(Error::Parameter("a failure half way".into()))
        });
        assert!(matches!(failed, Err(Error::Parameter(_))), "{failed:?}");
        assert_eq!(names(&root), ["saved"]);
        assert_eq!(names(&dir), ["a.txt"]);
        assert_eq!(std::fs::read_to_string(dir.join("a.txt")).unwrap(), "old");
        // Without an old folder, a failure leaves no folder at all.
        let fresh = root.join("fresh");
        assert!(replace_folder(&fresh, |_| Err(Error::Parameter("no".into()))).is_err());
        assert_eq!(names(&root), ["saved"]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_failure_within_the_set_leaves_nothing() {
        let dir = scratch("failure");
        std::fs::write(dir.join("a.txt"), "old").unwrap();
        let mut outputs = Outputs::new();
        outputs
            .file(&dir.join("a.txt"), |w| w.write_all(b"new"))
            .unwrap();
        // A write that fails half way (a full disk, say).
        let failed = outputs.file(&dir.join("b.txt"), |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("no space left"))
        });
        assert!(matches!(failed, Err(Error::Io { .. })), "{failed:?}");
        drop(outputs);
        // The old file is as it was, and no temporary file is left.
        assert_eq!(names(&dir), ["a.txt"]);
        assert_eq!(std::fs::read_to_string(dir.join("a.txt")).unwrap(), "old");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
