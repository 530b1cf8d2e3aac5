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
    let (parent, name) = parent_and_name(dir)?;
    let temp = parent.join(hidden(name, "saving"));
    std::fs::create_dir_all(&temp).map_err(|e| io_error(&temp, e))?;
    let swapped = fill(&temp).and_then(|()| put_in_place(&temp, dir, Previous::Remove));
    if swapped.is_err() {
        let _ = std::fs::remove_dir_all(&temp);
    }
    swapped
}

fn io_error(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// The folder `dir` lies in and its own name; `.`, `..` and `/` name no folder to replace.
fn parent_and_name(dir: &Path) -> Result<(&Path, &std::ffi::OsStr)> {
    match (dir.parent(), dir.file_name()) {
        (Some(parent), Some(name)) => Ok((parent, name)),
        _ => Err(Error::Parameter(format!(
            "cannot write the folder {}: not a folder name (name the folder itself, e.g. out)",
            dir.display()
        ))),
    }
}

/// Renames the filled folder `staged` to `target`. An old `target` is moved aside first and,
/// once the new one is in place, removed or kept as `TARGET.previous`; if the second rename
/// fails, the old one is put back.
fn put_in_place(staged: &Path, target: &Path, previous: Previous) -> Result<()> {
    if std::fs::symlink_metadata(target).is_err() {
        return std::fs::rename(staged, target).map_err(|e| io_error(target, e));
    }
    let (parent, name) = parent_and_name(target)?;
    let aside = match previous {
        Previous::Keep => {
            let kept = sibling(target, "previous");
            if kept.is_dir() {
                std::fs::remove_dir_all(&kept).map_err(|e| io_error(&kept, e))?;
            }
            kept
        }
        Previous::Remove => parent.join(hidden(name, "old")),
    };
    std::fs::rename(target, &aside).map_err(|e| io_error(target, e))?;
    std::fs::rename(staged, target).map_err(|e| {
        // Best effort: put the old folder back; the rename's error is the one to report.
        let _ = std::fs::rename(&aside, target);
        io_error(target, e)
    })?;
    if previous == Previous::Remove {
        let _ = std::fs::remove_dir_all(&aside);
    }
    Ok(())
}

/// `DIR.suffix` beside `DIR`.
fn sibling(dir: &Path, suffix: &str) -> PathBuf {
    let mut name = dir.file_name().unwrap_or_default().to_os_string();
    name.push(".");
    name.push(suffix);
    dir.with_file_name(name)
}

/// Whether a run's outputs are the result asked for, or only for inspection.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The result: the outputs take `DIR`'s place.
    Passed,
    /// Not the result asked for (no honeycomb, say): the outputs go to `DIR.failed`, and a
    /// good `DIR` of an earlier run stays as it was.
    Failed,
}

/// What becomes of the `DIR` of an earlier run once a passed run's outputs take its place.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Previous {
    /// Removed (after the new one is in place).
    #[default]
    Remove,
    /// Kept as `DIR.previous` (an older `DIR.previous` removed).
    Keep,
}

/// Files that mark a folder as an output directory of an earlier run, which a new run may
/// replace; a folder that holds other files and none of these is someone else's.
const OUTPUT_MARKERS: [&str; 3] = ["export.json", "report.json", "structure.json"];

/// Every file a run writes into its output directory. An earlier run's folder that holds
/// anything else (a picture rendered into it, a note) is kept as `DIR.previous`, not removed.
const RUN_FILES: [&str; 22] = [
    "analysis.json",
    "base.obj",
    "bom.csv",
    "demo.json",
    "export.json",
    "init.json",
    "initial.obj",
    "input_base.obj",
    "nodes.csv",
    "offset.obj",
    "panels.dxf",
    "panels.svg",
    "quads.obj",
    "report.json",
    "spherical_image.obj",
    "structure.glb",
    "structure.json",
    "structure.mtl",
    "structure.obj",
    "surface.obj",
    "walls.csv",
    "walls.obj",
];

/// An output directory written as a whole: the files go into a hidden staging folder beside
/// `DIR`, which takes `DIR`'s place only once every file is complete, so no file of an earlier
/// run survives into a new one and a failure part way leaves `DIR` as it was.
///
/// ```no_run
/// # use honeycomb::mesh::{OutputDir, Verdict};
/// # fn main() -> honeycomb::Result<()> {
/// // Before a long run, so that an unusable DIR fails at once:
/// let out = OutputDir::begin(std::path::Path::new("out"), &[])?;
/// // ... the run ...
/// let written = out.finish(Verdict::Passed, |staging| {
///     honeycomb::export::write_json(&staging.join("report.json"), &"...")
/// })?;
/// assert_eq!(written, std::path::Path::new("out"));
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct OutputDir {
    dir: PathBuf,
    staging: PathBuf,
    previous: Previous,
    /// A file in the earlier `DIR` that no run writes.
    foreign: Option<String>,
}

impl OutputDir {
    /// Checks `dir` (a folder name; absent, empty or an output directory of an earlier run,
    /// holding none of `inputs`) and makes the staging folder beside it (and `dir`'s parents),
    /// so that a `dir` that cannot be written fails before a long run rather than after it. An
    /// earlier run's folder that holds files no run writes is kept as `DIR.previous` (see
    /// [`OutputDir::note`]). Staging folders that killed runs left beside `dir` are removed.
    pub fn begin(dir: &Path, inputs: &[&Path]) -> Result<OutputDir> {
        let (parent, name) = parent_and_name(dir)?;
        let names = check_replaceable(dir)?;
        check_inputs_outside(dir, inputs)?;
        remove_abandoned(parent, name);
        let staging = parent.join(hidden(name, "staging"));
        std::fs::create_dir_all(&staging).map_err(|e| io_error(dir, e))?;
        let foreign = names.into_iter().find(|n| !RUN_FILES.contains(&n.as_str()));
        Ok(OutputDir {
            dir: dir.to_path_buf(),
            staging,
            previous: if foreign.is_some() {
                Previous::Keep
            } else {
                Previous::Remove
            },
            foreign,
        })
    }

    /// What happens to the earlier folder under `verdict`, when the user should know: it held
    /// files no run writes, so a passed run keeps it as `DIR.previous` (a failed one leaves
    /// it as it is).
    pub fn note(&self, verdict: Verdict) -> Option<String> {
        if verdict == Verdict::Failed {
            return None;
        }
        self.foreign.as_ref().map(|f| {
            format!(
                "{} held files no run writes (such as {f}): the earlier folder is kept as {}",
                self.dir.display(),
                sibling(&self.dir, "previous").display()
            )
        })
    }

    /// Sets what becomes of an earlier run's `DIR` (removed by default, kept when it holds
    /// files no run writes).
    pub fn previous(mut self, previous: Previous) -> OutputDir {
        if self.foreign.is_none() {
            self.previous = previous;
        }
        self
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// `DIR.failed`, where the outputs of a failed verdict go.
    pub fn failed_dir(&self) -> PathBuf {
        sibling(&self.dir, "failed")
    }

    /// Runs `fill` on the staging folder, then puts it in place by `verdict`: as `DIR` (and a
    /// `DIR.failed` of an earlier run is removed) or as `DIR.failed` (and `DIR` stays as it
    /// was). Returns where the outputs are. If `fill` or a rename fails, nothing changes.
    pub fn finish(
        self,
        verdict: Verdict,
        fill: impl FnOnce(&Path) -> Result<()>,
    ) -> Result<PathBuf> {
        fill(&self.staging)?;
        match verdict {
            Verdict::Passed => {
                put_in_place(&self.staging, &self.dir, self.previous)?;
                let failed = self.failed_dir();
                if failed.is_dir() {
                    // Stale: it was about an earlier run.
                    let _ = std::fs::remove_dir_all(&failed);
                }
                Ok(self.dir.clone())
            }
            Verdict::Failed => {
                let failed = self.failed_dir();
                check_replaceable(&failed)?;
                // A failed run's folder replaces an earlier failed one's whole.
                put_in_place(&self.staging, &failed, Previous::Remove)?;
                Ok(failed)
            }
        }
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        // Gone when `finish` put it in place; otherwise what an unfinished run wrote.
        let _ = std::fs::remove_dir_all(&self.staging);
    }
}

/// [`OutputDir::begin`] and [`OutputDir::finish`] in one: for a front that knows its verdict
/// before it writes.
pub fn write_output_dir(
    dir: &Path,
    verdict: Verdict,
    fill: impl FnOnce(&Path) -> Result<()>,
) -> Result<PathBuf> {
    OutputDir::begin(dir, &[])?.finish(verdict, fill)
}

/// Refuses a `dir` that holds one of `inputs`: replacing it whole would take the input away.
fn check_inputs_outside(dir: &Path, inputs: &[&Path]) -> Result<()> {
    let Ok(dir) = dir.canonicalize() else {
        return Ok(());
    };
    for input in inputs {
        if input.canonicalize().is_ok_and(|p| p.starts_with(&dir)) {
            return Err(Error::Parameter(format!(
                "-o {}: holds the input {}, and the outputs replace the folder whole: write them \
                 elsewhere",
                dir.display(),
                input.display()
            )));
        }
    }
    Ok(())
}

/// Removes the staging folders of `name` beside it whose run has ended without finishing
/// (killed, or out of memory): their process is gone.
fn remove_abandoned(parent: &Path, name: &std::ffi::OsStr) {
    let prefix = format!(".{}.staging-", name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = file.strip_prefix(&prefix) else {
            continue;
        };
        let pid = rest.split('-').next().and_then(|p| p.parse::<u32>().ok());
        let alive = pid.is_some_and(|p| Path::new(&format!("/proc/{p}")).exists());
        if pid.is_some() && !alive && Path::new("/proc/self").exists() {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

/// `dir` may be replaced: it does not exist, or it is an empty folder or one that an earlier
/// run wrote. Returns the names it holds.
fn check_replaceable(dir: &Path) -> Result<Vec<String>> {
    let Ok(meta) = std::fs::symlink_metadata(dir) else {
        return Ok(Vec::new());
    };
    let is_dir = meta.is_dir() || (meta.file_type().is_symlink() && dir.is_dir());
    if !is_dir {
        return Err(Error::Parameter(format!(
            "-o {}: exists and is not a directory",
            dir.display()
        )));
    }
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| io_error(dir, e))?
        .filter_map(|entry| entry.ok())
        .map(|entry| entry.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    if names.is_empty() || OUTPUT_MARKERS.iter().any(|m| names.iter().any(|n| n == m)) {
        return Ok(names);
    }
    Err(Error::Parameter(format!(
        "-o {}: a folder with other files (such as {}) and no report.json, structure.json \
         or export.json of an earlier run; the outputs replace the folder whole: give a new or empty one",
        dir.display(),
        names[0]
    )))
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

    /// Writes `files` (name, contents) into `dir`.
    fn fill_with<'a>(files: &'a [(&str, &str)]) -> impl FnOnce(&Path) -> Result<()> + 'a {
        move |dir| {
            let mut outputs = Outputs::new();
            for (name, text) in files {
                outputs.file(&dir.join(name), |w| w.write_all(text.as_bytes()))?;
            }
            outputs.commit()
        }
    }

    #[test]
    fn an_output_dir_holds_only_the_new_run() {
        let root = scratch("output-dir");
        let dir = root.join("out");
        let first = [
            ("report.json", "1"),
            ("analysis.json", "old"),
            ("surface.obj", "s"),
        ];
        let written = write_output_dir(&dir, Verdict::Passed, fill_with(&first)).unwrap();
        assert_eq!(written, dir);
        assert_eq!(names(&dir), ["analysis.json", "report.json", "surface.obj"]);
        let second = [("report.json", "2")];
        write_output_dir(&dir, Verdict::Passed, fill_with(&second)).unwrap();
        // Nothing of the first run survives, and nothing is left beside it.
        assert_eq!(names(&dir), ["report.json"]);
        assert_eq!(
            std::fs::read_to_string(dir.join("report.json")).unwrap(),
            "2"
        );
        assert_eq!(names(&root), ["out"]);
        // Kept on request: the earlier run as DIR.previous.
        let third = [("report.json", "3")];
        let out = OutputDir::begin(&dir, &[])
            .unwrap()
            .previous(Previous::Keep);
        out.finish(Verdict::Passed, fill_with(&third)).unwrap();
        assert_eq!(names(&root), ["out", "out.previous"]);
        let previous = root.join("out.previous/report.json");
        assert_eq!(std::fs::read_to_string(previous).unwrap(), "2");
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// A user's file in an earlier run's folder survives as DIR.previous; a folder holding
    /// an input of the run is refused; a staging folder a killed run left is cleared.
    #[test]
    fn nothing_of_the_user_is_lost() {
        let root = scratch("output-dir-user");
        let dir = root.join("out");
        let first = [("report.json", "1"), ("structure.json", "s")];
        write_output_dir(&dir, Verdict::Passed, fill_with(&first)).unwrap();
        std::fs::write(dir.join("thesis.tex"), "mine").unwrap();
        let out = OutputDir::begin(&dir, &[]).unwrap();
        assert!(out.note(Verdict::Failed).is_none());
        assert!(out.note(Verdict::Passed).unwrap().contains("thesis.tex"));
        out.finish(Verdict::Passed, fill_with(&[("report.json", "2")]))
            .unwrap();
        assert_eq!(names(&dir), ["report.json"]);
        let kept = root.join("out.previous/thesis.tex");
        assert_eq!(std::fs::read_to_string(kept).unwrap(), "mine");

        let input = dir.join("report.json");
        let e = OutputDir::begin(&dir, &[&input]).unwrap_err().to_string();
        assert!(e.contains("holds the input"), "{e}");

        // A staging folder of a process that is gone (pid 0 never names a user process).
        let abandoned = root.join(".out.staging-0-7");
        std::fs::create_dir_all(&abandoned).unwrap();
        drop(OutputDir::begin(&dir, &[]).unwrap());
        assert!(!abandoned.exists());
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_failed_verdict_goes_beside_a_good_dir_and_a_later_pass_clears_it() {
        let root = scratch("output-dir-failed");
        let dir = root.join("out");
        write_output_dir(&dir, Verdict::Passed, fill_with(&[("report.json", "good")])).unwrap();
        let failed = [("report.json", "bad"), ("base.obj", "b")];
        let written = write_output_dir(&dir, Verdict::Failed, fill_with(&failed)).unwrap();
        assert_eq!(written, root.join("out.failed"));
        assert_eq!(
            std::fs::read_to_string(dir.join("report.json")).unwrap(),
            "good"
        );
        assert_eq!(names(&written), ["base.obj", "report.json"]);
        // A second failure replaces the first one's outputs whole.
        write_output_dir(
            &dir,
            Verdict::Failed,
            fill_with(&[("report.json", "worse")]),
        )
        .unwrap();
        assert_eq!(names(&written), ["report.json"]);
        assert_eq!(names(&root), ["out", "out.failed"]);
        // A pass removes the failure's outputs, which were about an earlier run.
        write_output_dir(&dir, Verdict::Passed, fill_with(&[("report.json", "new")])).unwrap();
        assert_eq!(names(&root), ["out"]);
        // Without a DIR, a failure writes DIR.failed only.
        let fresh = root.join("fresh");
        write_output_dir(&fresh, Verdict::Failed, fill_with(&[("report.json", "x")])).unwrap();
        assert_eq!(names(&root), ["fresh.failed", "out"]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn an_output_dir_that_fails_to_fill_changes_nothing() {
        let root = scratch("output-dir-fill");
        let dir = root.join("out");
        write_output_dir(&dir, Verdict::Passed, fill_with(&[("report.json", "good")])).unwrap();
        let failed = write_output_dir(&dir, Verdict::Passed, |d| {
            fill_with(&[("report.json", "half")])(d)?;
            Err(Error::Parameter("a full disk".into()))
        });
        assert!(matches!(failed, Err(Error::Parameter(_))), "{failed:?}");
        assert_eq!(names(&root), ["out"]);
        assert_eq!(
            std::fs::read_to_string(dir.join("report.json")).unwrap(),
            "good"
        );
        // Begun and dropped (the run failed before writing): no staging folder is left.
        drop(OutputDir::begin(&root.join("never"), &[]).unwrap());
        assert_eq!(names(&root), ["out"]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn an_output_dir_is_refused_where_it_would_replace_what_is_not_a_run() {
        let root = scratch("output-dir-refused");
        let file = root.join("notes.txt");
        std::fs::write(&file, "mine").unwrap();
        let e = OutputDir::begin(&file, &[]).unwrap_err().to_string();
        assert!(
            e.contains("notes.txt: exists and is not a directory"),
            "{e}"
        );
        // A folder of someone else's files (the home folder, say) is not replaced whole.
        let e = OutputDir::begin(&root, &[]).unwrap_err().to_string();
        assert!(
            e.contains("a folder with other files (such as notes.txt)"),
            "{e}"
        );
        for dot in [".", "..", "/"] {
            let e = OutputDir::begin(Path::new(dot), &[])
                .unwrap_err()
                .to_string();
            assert!(e.contains("not a folder name"), "{dot}: {e}");
        }
        // An empty folder is fine.
        let empty = root.join("empty");
        std::fs::create_dir(&empty).unwrap();
        write_output_dir(&empty, Verdict::Passed, fill_with(&[("report.json", "1")])).unwrap();
        assert_eq!(names(&root), ["empty", "notes.txt"]);
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
