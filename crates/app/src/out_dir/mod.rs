//! A run's output folder: locked for the whole run, its result written whole into a hidden
//! version folder and made visible at every final name at once by one rename.
//!
//! - [`OutDir::open`] runs before any work: it creates the folder, takes an exclusive lock on
//!   `.slc.lock` (released by the OS when the process ends, however it ends; a second run into
//!   a locked folder fails at once with the holder's pid, command line and start time),
//!   removes what killed runs left, and makes the new version folder `.slc-result-N`.
//! - A run that ends without a result (refused input, a failed pass or write) in a folder its
//!   own `mkdir` made removes that folder again, with its lock and the folders above it that
//!   it made, each only if nothing else is in it (a killed run leaves them to the next).
//! - Every result is written into the version folder ([`OutDir::write`],
//!   [`OutDir::write_with`]); [`OutDir::expect`] checks before the work that nothing a user put
//!   in the folder is where a result will go.
//! - [`OutDir::commit`] (the layout: the `layout` module): (1) checks every final name is free or
//!   already slc's link, (2) syncs the new files, (3) makes the links of names the previous
//!   result lacked (they resolve to nothing until (4)), (4) renames a link to the new version
//!   over `.slc-result`: the one step that changes what every final name shows, (5) removes
//!   the links of names only the previous result had, the folders that leaves empty, and the
//!   previous version.
//! - A failure before (4) undoes (3) and removes the version folder: the previous result is
//!   untouched. A run killed at any instant leaves the previous result at every final name
//!   (before (4) the names still resolve through the old link; (3)'s links resolve to
//!   nothing) or the new one (after (4); names only the previous result had resolve to
//!   nothing); the next run removes what it left. Files slc did not write stay as they are.
//!
//! Every change to the file system is a step of the `faults` module, so the tests make each one fail,
//! or kill the run there, and check the folder.
mod faults;
mod layout;
mod legacy;
mod lock;
#[cfg(test)]
mod tests;

use faults::Faults;
use layout::{
    check_relative, current_version, files_under, is_our_link, link_target, version_name,
    version_of, CURRENT, LEGACY_STAGING_PREFIX, LINK_TMP, NEXT,
};
use std::fmt::Display;
use std::fs::{self, File};
use std::io;
use std::path::{Path, PathBuf};

/// A locked output folder with the files written so far into its new version.
pub struct OutDir {
    root: PathBuf,
    /// The version the folder showed when the run began.
    previous: Option<u64>,
    /// The new version's folder.
    version: u64,
    staging: PathBuf,
    /// Files written, relative to the root.
    files: Vec<PathBuf>,
    committed: bool,
    /// The topmost of the folders this run's own `mkdir` made, the root and those above it
    /// down to the root (removed again without a result); `None` where the root was there.
    created: Option<PathBuf>,
    faults: Faults,
    _lock: File,
}

/// What a commit made before its rename, undone if it fails.
#[derive(Default)]
struct Made {
    dirs: Vec<PathBuf>,
    links: Vec<PathBuf>,
}

impl OutDir {
    /// Creates and locks `root`, removes what killed runs left there and makes an empty
    /// version folder for this run's result.
    pub fn open(root: &Path) -> Result<Self, String> {
        Self::open_with(root, Faults::default())
    }

    fn open_with(root: &Path, faults: Faults) -> Result<Self, String> {
        let at = |what: &str, e: io::Error| format!("{}: {what}: {e}", root.display());
        if root.symlink_metadata().is_ok() && !root.is_dir() {
            return Err(format!(
                "{}: the output path exists and is not a folder",
                root.display()
            ));
        }
        let created = make_folders(root).map_err(|e| at("cannot create the output folder", e))?;
        // A lock held by another run: nothing here is this run's to remove.
        let lock = lock::lock(root)?;
        match Self::stage(root) {
            Ok((previous, version, staging)) => Ok(Self {
                root: root.to_path_buf(),
                previous,
                version,
                staging,
                files: Vec::new(),
                committed: false,
                created,
                faults,
                _lock: lock,
            }),
            Err(e) => {
                // Removed while the lock is held.
                if let Some(top) = &created {
                    remove_created(root, top);
                }
                Err(e)
            }
        }
    }

    /// Removes what killed runs left in the locked `root` and makes the new version folder:
    /// the version the folder showed, the new version and its folder.
    fn stage(root: &Path) -> Result<(Option<u64>, u64, PathBuf), String> {
        let at = |what: &str, e: io::Error| format!("{}: {what}: {e}", root.display());
        let previous = current_version(root)?;
        tidy(root, previous).map_err(|e| at("cannot remove what an earlier run left", e))?;
        legacy::migrate(root)?;
        let previous = current_version(root)?;
        let version = previous.map_or(1, |n| n + 1);
        let staging = root.join(version_name(version));
        fs::create_dir(&staging).map_err(|e| at("cannot create the result folder", e))?;
        Ok((previous, version, staging))
    }

    /// The final folder (for messages).
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// Checks, before any work, that the results `relatives` (files, relative to the root)
    /// can take their final names: nothing slc did not write lies at one of them or at a
    /// folder above one.
    pub fn expect<P: AsRef<Path>>(
        &self,
        relatives: impl IntoIterator<Item = P>,
    ) -> Result<(), String> {
        for relative in relatives {
            let relative = relative.as_ref();
            check_relative(relative)?;
            if let Some(e) = in_the_way(&self.root, relative) {
                return Err(format!("{e}; nothing was written"));
            }
        }
        Ok(())
    }

    /// Writes the result `relative` by calling `write` with the path to write it at (in the
    /// version folder, its parent folders made). An error names the final name.
    pub fn write_with<E: Display>(
        &mut self,
        relative: impl AsRef<Path>,
        write: impl FnOnce(&Path) -> Result<(), E>,
    ) -> Result<(), String> {
        let relative = relative.as_ref().to_path_buf();
        check_relative(&relative)?;
        let path = self.staging.join(&relative);
        let shown = self.root.join(&relative);
        let failed = |e: &dyn Display| {
            let e = e
                .to_string()
                .replace(&path.display().to_string(), &shown.display().to_string());
            format!(
                "{}: cannot write: {e}; {} keeps its previous result",
                shown.display(),
                self.root.display()
            )
        };
        self.faults.step().map_err(|e| failed(&e))?;
        if let Some(parent) = path.parent() {
            fs::create_dir_all(parent).map_err(|e| failed(&e))?;
        }
        write(&path).map_err(|e| failed(&e))?;
        if !self.files.contains(&relative) {
            self.files.push(relative);
        }
        Ok(())
    }

    /// Writes the result `relative` with the given contents.
    pub fn write(&mut self, relative: impl AsRef<Path>, contents: &[u8]) -> Result<(), String> {
        self.write_with(relative, |path| fs::write(path, contents))
    }

    /// Whether `relative` has been written.
    pub fn has(&self, relative: impl AsRef<Path>) -> bool {
        self.files.iter().any(|f| f == relative.as_ref())
    }

    /// Makes the written files the folder's result, at once (see the module doc).
    pub fn commit(mut self) -> Result<(), String> {
        self.commit_in_place()
    }

    fn commit_in_place(&mut self) -> Result<(), String> {
        self.files.sort();
        let mut made = Made::default();
        match self.publish(&mut made) {
            Ok(()) => {
                self.committed = true;
                self.remove_previous();
                Ok(())
            }
            Err(e) => {
                self.undo(made);
                Err(e)
            }
        }
    }

    /// Steps (1) to (4) of the commit.
    fn publish(&mut self, made: &mut Made) -> Result<(), String> {
        let root = self.root.clone();
        for f in &self.files {
            if let Some(e) = in_the_way(&root, f) {
                return Err(format!("{e}; nothing was replaced"));
            }
        }
        let failed = |what: &str, e: io::Error| {
            format!(
                "{}: cannot commit the result ({what}): {e}; the folder keeps its previous result",
                root.display()
            )
        };
        for f in &self.files {
            self.faults.step().map_err(|e| failed("sync", e))?;
            File::open(self.staging.join(f))
                .and_then(|file| file.sync_all())
                .map_err(|e| failed("sync", e))?;
        }
        for f in &self.files {
            if is_our_link(&root, f) {
                continue;
            }
            let mut folder = PathBuf::new();
            for c in f.parent().into_iter().flat_map(Path::components) {
                folder.push(c);
                if root.join(&folder).symlink_metadata().is_err() {
                    self.faults.step().map_err(|e| failed("folder", e))?;
                    fs::create_dir(root.join(&folder)).map_err(|e| failed("folder", e))?;
                    made.dirs.push(folder.clone());
                }
            }
            self.faults.step().map_err(|e| failed("link", e))?;
            std::os::unix::fs::symlink(link_target(f), root.join(f))
                .map_err(|e| failed("link", e))?;
            made.links.push(f.clone());
        }
        self.faults.step().map_err(|e| failed("new version", e))?;
        std::os::unix::fs::symlink(version_name(self.version), root.join(NEXT))
            .map_err(|e| failed("new version", e))?;
        self.faults.step().map_err(|e| failed("switch", e))?;
        fs::rename(root.join(NEXT), root.join(CURRENT)).map_err(|e| failed("switch", e))
    }

    /// Removes what a failed commit made before its rename.
    fn undo(&mut self, made: Made) {
        let root = self.root.clone();
        let mut steps = made
            .links
            .iter()
            .rev()
            .map(|l| (l, false))
            .chain(made.dirs.iter().rev().map(|d| (d, true)))
            .collect::<Vec<_>>();
        let next = PathBuf::from(NEXT);
        steps.push((&next, false));
        for (path, folder) in steps {
            if self.faults.step().is_ok() {
                match folder {
                    true => fs::remove_dir(root.join(path)).ok(),
                    false => fs::remove_file(root.join(path)).ok(),
                };
            }
        }
    }

    /// Step (5): the previous version and the links of names only it had. The result is
    /// committed whatever fails here (the next run removes what is left).
    fn remove_previous(&mut self) {
        let Some(previous) = self.previous else {
            return;
        };
        let folder = self.root.join(version_name(previous));
        let mut result = Ok(());
        for f in files_under(&folder) {
            if !self.files.contains(&f) && is_our_link(&self.root, &f) && result.is_ok() {
                result = self
                    .faults
                    .step()
                    .and_then(|()| remove_link(&self.root, &f));
            }
        }
        result = result
            .and_then(|()| self.faults.step())
            .and_then(|()| fs::remove_dir_all(&folder));
        if let Err(e) = result {
            eprintln!(
                "warning: {}: the previous result was replaced but not all of it removed ({e}); the next run into this folder removes it",
                self.root.display()
            );
        }
    }
}

impl Drop for OutDir {
    /// Without a result: removes the new version folder, and a folder this run created
    /// along with its lock (only if nothing else is in it).
    fn drop(&mut self) {
        if !self.committed && self.faults.step().is_ok() {
            fs::remove_dir_all(&self.staging).ok();
            if let Some(top) = &self.created {
                remove_created(&self.root, top);
            }
        }
    }
}

/// Makes `root` and the folders above it that are missing, top down, each by its own
/// `mkdir`. Returns the topmost folder made from which every folder down to the root was
/// made here; `None` where the root was there (or another process made it, or a folder
/// below the one made, first). On an error the folders made are removed again.
fn make_folders(root: &Path) -> io::Result<Option<PathBuf>> {
    let missing: Vec<&Path> = root
        .ancestors()
        .take_while(|f| !f.as_os_str().is_empty() && f.symlink_metadata().is_err())
        .collect();
    let (mut top, mut made) = (None, Vec::new());
    for folder in missing.into_iter().rev() {
        match fs::create_dir(folder) {
            Ok(()) => {
                top.get_or_insert_with(|| folder.to_path_buf());
                made.push(folder);
            }
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && folder.is_dir() => top = None,
            Err(e) => {
                for folder in made.into_iter().rev() {
                    fs::remove_dir(folder).ok();
                }
                return Err(e);
            }
        }
    }
    Ok(top)
}

/// Removes `root` and the folders above it up to `top`, made by a run that ends without a
/// result, and the root's lock (while this run holds it): each folder only if nothing else
/// is in it (what a failed commit could not undo stays for the next run).
fn remove_created(root: &Path, top: &Path) {
    fs::remove_file(root.join(lock::LOCK)).ok();
    for folder in root.ancestors() {
        if fs::remove_dir(folder).is_err() || folder == top {
            break;
        }
    }
}

/// Why the final name of `relative` cannot be slc's: something slc did not write is there
/// or at a folder above it.
fn in_the_way(root: &Path, relative: &Path) -> Option<String> {
    let what = |meta: &fs::Metadata| match meta {
        m if m.is_symlink() => "link",
        m if m.is_dir() => "folder",
        m if m.is_file() => "file",
        _ => "special file",
    };
    let mut folder = PathBuf::new();
    for c in relative.parent().into_iter().flat_map(Path::components) {
        folder.push(c);
        match root.join(&folder).symlink_metadata() {
            Err(_) => return None,
            Ok(m) if m.is_dir() => {}
            Ok(m) => {
                return Some(format!(
                    "{}: a {} slc did not write is where the result folder {}/ goes; move it away",
                    root.join(&folder).display(),
                    what(&m),
                    root.join(&folder).display()
                ))
            }
        }
    }
    match root.join(relative).symlink_metadata() {
        Err(_) => None,
        Ok(_) if is_our_link(root, relative) => None,
        Ok(m) => Some(format!(
            "{}: a {} slc did not write is where this result goes; move it away",
            root.join(relative).display(),
            what(&m)
        )),
    }
}

/// Removes slc's link at `relative` and the folders above it that this leaves empty.
fn remove_link(root: &Path, relative: &Path) -> io::Result<()> {
    fs::remove_file(root.join(relative))?;
    remove_empty_folders(root, relative);
    Ok(())
}

/// Removes the folders above `relative` that are empty, from the deepest up (those that do
/// not exist are passed over).
fn remove_empty_folders(root: &Path, relative: &Path) {
    let mut folder = relative.parent();
    while let Some(f) = folder.filter(|f| !f.as_os_str().is_empty()) {
        match fs::remove_dir(root.join(f)) {
            Err(e) if e.kind() != io::ErrorKind::NotFound => break,
            _ => folder = f.parent(),
        }
    }
}

/// Removes what killed runs left in `root` (whose lock we hold, so no other run is live):
/// versions other than the `current` one (after the links to them that resolve to nothing),
/// the half-made links of a commit or migration, and the staging folders of slc's earlier
/// layout.
fn tidy(root: &Path, current: Option<u64>) -> io::Result<()> {
    for entry in fs::read_dir(root)? {
        let entry = entry?;
        let name = entry.file_name();
        let path = entry.path();
        let stale_version = version_of(&name).is_some_and(|n| Some(n) != current);
        if stale_version {
            // Its links that resolve to nothing, and the folders a killed commit made for
            // them (empty, or emptied).
            for f in files_under(&path) {
                if is_our_link(root, &f) && fs::metadata(root.join(&f)).is_err() {
                    remove_link(root, &f)?;
                } else if root.join(&f).symlink_metadata().is_err() {
                    remove_empty_folders(root, &f);
                }
            }
        }
        let legacy = name.to_string_lossy().starts_with(LEGACY_STAGING_PREFIX);
        if stale_version || legacy || name == NEXT || name == LINK_TMP {
            match entry.file_type()?.is_dir() {
                true => fs::remove_dir_all(&path)?,
                false => fs::remove_file(&path)?,
            }
        }
    }
    Ok(())
}
