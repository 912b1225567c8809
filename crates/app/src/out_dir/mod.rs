//! A run's output folder: locked for the whole run, written through a staging folder and
//! committed by renames, so the folder holds one run's complete result or the previous one's.
//!
//! - [`OutDir::open`] runs before any work: it creates the folder, takes an exclusive lock on
//!   `.slc.lock` (released by the OS when the process ends, however it ends) and makes the
//!   staging folder `.slc-staging-<pid>`. A second run into a locked folder fails at once with
//!   the holder's pid, command line and start time.
//! - Every result is written at a [`OutDir::stage`]d path inside the staging folder.
//! - [`OutDir::commit`] checks that no final name is a folder, then renames the files into
//!   place, every `report.json` last (the top-level one very last), and removes what the
//!   previous run wrote (its list is `.slc-manifest`) that this run did not write again.
//! - A run that fails or is dropped before committing removes its staging folder; one that is
//!   killed leaves only the hidden staging folder, which the next run removes.
use std::fs::{self, File};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

const LOCK: &str = ".slc.lock";
const MANIFEST: &str = ".slc-manifest";
const STAGING_PREFIX: &str = ".slc-staging-";

/// A locked output folder with the files staged so far.
pub struct OutDir {
    root: PathBuf,
    staging: PathBuf,
    /// Staged files, relative to the root, in the order they were staged.
    files: Vec<PathBuf>,
    committed: bool,
    _lock: File,
}

impl OutDir {
    /// Creates and locks `root` and prepares an empty staging folder in it.
    pub fn open(root: &Path) -> Result<Self, String> {
        let at = |what: &str, e: std::io::Error| format!("{}: {what}: {e}", root.display());
        if root.exists() && !root.is_dir() {
            return Err(format!(
                "{}: the output path exists and is not a folder",
                root.display()
            ));
        }
        fs::create_dir_all(root).map_err(|e| at("cannot create the output folder", e))?;
        let lock_path = root.join(LOCK);
        let mut lock = File::options()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&lock_path)
            .map_err(|e| at("cannot write in the output folder", e))?;
        if let Err(e) = lock.try_lock() {
            let mut holder = String::new();
            lock.read_to_string(&mut holder).ok();
            return Err(match e {
                fs::TryLockError::WouldBlock => format!(
                    "{}: the output folder is in use by another slc run ({}); wait for it or choose another --out",
                    root.display(),
                    holder_text(&holder)
                ),
                fs::TryLockError::Error(e) => at("cannot lock the output folder", e),
            });
        }
        lock.set_len(0)
            .and_then(|()| lock.write_all(holder_line().as_bytes()))
            .map_err(|e| at("cannot write the lock file", e))?;
        remove_stale_staging(root).map_err(|e| at("cannot remove an old staging folder", e))?;
        let staging = root.join(format!("{STAGING_PREFIX}{}", std::process::id()));
        fs::create_dir(&staging).map_err(|e| at("cannot create the staging folder", e))?;
        Ok(Self {
            root: root.to_path_buf(),
            staging,
            files: Vec::new(),
            committed: false,
            _lock: lock,
        })
    }

    /// The final folder (for messages).
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// Where to write the file that will be committed as `root/relative` (its parent folders
    /// are created in the staging folder).
    pub fn stage(&mut self, relative: impl AsRef<Path>) -> Result<PathBuf, String> {
        let relative = relative.as_ref().to_path_buf();
        let path = self.staging.join(&relative);
        if let Some(parent) = path.parent() {
            fs::create_dir_all(parent)
                .map_err(|e| format!("{}: cannot create folder: {e}", parent.display()))?;
        }
        if !self.files.contains(&relative) {
            self.files.push(relative);
        }
        Ok(path)
    }

    /// Whether `relative` has been staged.
    pub fn has(&self, relative: impl AsRef<Path>) -> bool {
        self.files.iter().any(|f| f == relative.as_ref())
    }

    /// Stages a file with the given contents.
    pub fn write(&mut self, relative: impl AsRef<Path>, contents: &[u8]) -> Result<(), String> {
        let relative = relative.as_ref();
        let path = self.stage(relative)?;
        fs::write(&path, contents)
            .map_err(|e| format!("{}: cannot write: {e}", self.root.join(relative).display()))
    }

    /// Moves every staged file to its final name, `report.json` files last.
    pub fn commit(mut self) -> Result<(), String> {
        self.files.sort_by_key(|f| commit_rank(f));
        for f in &self.files {
            let target = self.root.join(f);
            if target.is_dir() {
                return Err(format!(
                    "{}: a folder is in the way of a result file; nothing was replaced",
                    target.display()
                ));
            }
        }
        let previous = fs::read_to_string(self.root.join(MANIFEST)).unwrap_or_default();
        for f in &self.files {
            let target = self.root.join(f);
            if let Some(parent) = target.parent() {
                fs::create_dir_all(parent)
                    .map_err(|e| format!("{}: cannot create folder: {e}", parent.display()))?;
            }
            fs::rename(self.staging.join(f), &target)
                .map_err(|e| format!("{}: cannot move into place: {e}", target.display()))?;
        }
        for old in previous.lines().map(Path::new) {
            if !self.files.iter().any(|f| f == old) && is_plain_relative(old) {
                fs::remove_file(self.root.join(old)).ok();
            }
        }
        let manifest: String = self
            .files
            .iter()
            .map(|f| format!("{}\n", f.display()))
            .collect();
        let staged_manifest = self.staging.join(MANIFEST);
        fs::write(&staged_manifest, manifest)
            .and_then(|()| fs::rename(&staged_manifest, self.root.join(MANIFEST)))
            .map_err(|e| format!("{}: cannot write the manifest: {e}", self.root.display()))?;
        self.committed = true;
        fs::remove_dir_all(&self.staging).ok();
        Ok(())
    }
}

impl Drop for OutDir {
    fn drop(&mut self) {
        if !self.committed {
            fs::remove_dir_all(&self.staging).ok();
        }
    }
}

/// The order of commit: other files first, then nested `report.json`, the top one last.
fn commit_rank(f: &Path) -> (u8, std::cmp::Reverse<usize>) {
    let depth = f.components().count();
    match f.file_name().is_some_and(|n| n == "report.json") {
        false => (0, std::cmp::Reverse(0)),
        true => (1, std::cmp::Reverse(depth)),
    }
}

/// A manifest entry that stays inside the folder (no `..`, not absolute).
fn is_plain_relative(p: &Path) -> bool {
    p.components()
        .all(|c| matches!(c, std::path::Component::Normal(_)))
}

/// Removes staging folders left by runs that were killed (we hold the lock, so none is live).
fn remove_stale_staging(root: &Path) -> std::io::Result<()> {
    for entry in fs::read_dir(root)? {
        let entry = entry?;
        if entry
            .file_name()
            .to_string_lossy()
            .starts_with(STAGING_PREFIX)
        {
            fs::remove_dir_all(entry.path())?;
        }
    }
    Ok(())
}

/// What the lock file says about its holder.
fn holder_line() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let args: Vec<String> = std::env::args().collect();
    format!(
        "pid {}, started at unix time {secs}: {}",
        std::process::id(),
        args.join(" ")
    )
}

fn holder_text(holder: &str) -> &str {
    match holder.trim() {
        "" => "holder unknown",
        h => h,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("slc-outdir-{name}-{}", std::process::id()));
        fs::remove_dir_all(&d).ok();
        d
    }

    fn listing(root: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(root)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn commit_moves_files_and_removes_the_previous_runs_leftovers() {
        let root = temp("commit");
        let mut out = OutDir::open(&root).unwrap();
        out.write("a.txt", b"1").unwrap();
        out.write("sub/report.json", b"{}").unwrap();
        out.write("report.json", b"{}").unwrap();
        // Nothing at a final name before the commit.
        assert_eq!(listing(&root).len(), 2, "{:?}", listing(&root));
        out.commit().unwrap();
        assert_eq!(fs::read(root.join("a.txt")).unwrap(), b"1");
        assert!(root.join("sub/report.json").is_file());
        // A second run that writes less removes what the first wrote and it did not.
        fs::write(root.join("mine.txt"), "user file").unwrap();
        let mut out = OutDir::open(&root).unwrap();
        out.write("report.json", b"{\"run\": 2}").unwrap();
        out.commit().unwrap();
        assert!(!root.join("a.txt").exists() && !root.join("sub/report.json").exists());
        assert!(
            root.join("mine.txt").is_file(),
            "files slc did not write stay"
        );
        assert_eq!(
            listing(&root),
            [
                ".slc-manifest",
                ".slc.lock",
                "mine.txt",
                "report.json",
                "sub"
            ]
        );
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_second_run_is_refused_while_the_first_holds_the_folder() {
        let root = temp("lock");
        let first = OutDir::open(&root).unwrap();
        let e = OutDir::open(&root).err().unwrap();
        let pid = format!("pid {}", std::process::id());
        assert!(
            e.contains("in use by another slc run") && e.contains(&pid),
            "{e}"
        );
        drop(first);
        OutDir::open(&root).unwrap();
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_dropped_run_leaves_the_previous_result() {
        let root = temp("drop");
        let mut out = OutDir::open(&root).unwrap();
        out.write("report.json", b"old").unwrap();
        out.commit().unwrap();
        let mut out = OutDir::open(&root).unwrap();
        out.write("report.json", b"new").unwrap();
        drop(out);
        assert_eq!(fs::read(root.join("report.json")).unwrap(), b"old");
        assert!(!listing(&root).iter().any(|f| f.starts_with(STAGING_PREFIX)));
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn a_folder_in_the_way_replaces_nothing() {
        let root = temp("inway");
        let mut out = OutDir::open(&root).unwrap();
        out.write("a.txt", b"old").unwrap();
        out.commit().unwrap();
        fs::create_dir_all(root.join("b.txt")).unwrap();
        let mut out = OutDir::open(&root).unwrap();
        out.write("a.txt", b"new").unwrap();
        out.write("b.txt", b"new").unwrap();
        let e = out.commit().unwrap_err();
        assert!(
            e.contains("b.txt") && e.contains("nothing was replaced"),
            "{e}"
        );
        assert_eq!(fs::read(root.join("a.txt")).unwrap(), b"old");
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn stale_staging_is_removed_and_a_file_is_not_a_folder() {
        let root = temp("stale");
        fs::create_dir_all(root.join(".slc-staging-1/x")).unwrap();
        let out = OutDir::open(&root).unwrap();
        assert!(!root.join(".slc-staging-1").exists());
        drop(out);
        let file = root.join("file");
        fs::write(&file, "").unwrap();
        assert!(OutDir::open(&file).err().unwrap().contains("not a folder"));
        fs::remove_dir_all(&root).unwrap();
    }
}
