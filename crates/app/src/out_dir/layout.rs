//! The names an output folder holds besides its results, and the links through which the
//! results appear at their final names.
//!
//! A result file `a/b.exr` lies in the version folder `.slc-result-N/a/b.exr`; its final name
//! `a/b.exr` is a symbolic link `../.slc-result/a/b.exr` (relative, one `../` per folder above
//! it), and `.slc-result` is a symbolic link to the current version `.slc-result-N`. A link is
//! slc's exactly when its target is that text for its own name, so no list of what slc wrote is
//! kept. Every name that starts with `.slc` at the top of the folder is slc's.
use std::ffi::OsStr;
use std::path::{Component, Path, PathBuf};

/// The link to the current version.
pub const CURRENT: &str = ".slc-result";
/// The new version's link while it is made, before it is renamed over [`CURRENT`].
pub const NEXT: &str = ".slc-result.next";
/// A link made at the top and renamed to a final name (migration from the earlier layout).
pub const LINK_TMP: &str = ".slc-link.tmp";
const VERSION_PREFIX: &str = ".slc-result-";
/// The folder and list of the layout before versions (results renamed into place one by one).
pub const LEGACY_STAGING_PREFIX: &str = ".slc-staging-";
pub const LEGACY_MANIFEST: &str = ".slc-manifest";

/// The folder of version `n`.
pub fn version_name(n: u64) -> String {
    format!("{VERSION_PREFIX}{n}")
}

/// The version number `name` names, if it is a version folder's name.
pub fn version_of(name: &OsStr) -> Option<u64> {
    let digits = name.to_str()?.strip_prefix(VERSION_PREFIX)?;
    (!digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
        .then(|| digits.parse().ok())
        .flatten()
}

/// The version the folder `root` shows now: the target of its [`CURRENT`] link. An error if
/// something other than slc's link has that name.
pub fn current_version(root: &Path) -> Result<Option<u64>, String> {
    let path = root.join(CURRENT);
    let Ok(meta) = path.symlink_metadata() else {
        return Ok(None);
    };
    let target = meta
        .is_symlink()
        .then(|| std::fs::read_link(&path).ok())
        .flatten();
    match target.as_deref().map(|t| version_of(t.as_os_str())) {
        Some(Some(n)) => Ok(Some(n)),
        _ => Err(format!(
            "{}: this name is slc's (the link to the current result) but holds something else; move it away",
            path.display()
        )),
    }
}

/// The text of the link at the final name of `relative`.
pub fn link_target(relative: &Path) -> PathBuf {
    let depth = relative.components().count().saturating_sub(1);
    let mut target = PathBuf::new();
    for _ in 0..depth {
        target.push("..");
    }
    target.join(CURRENT).join(relative)
}

/// Whether the final name of `relative` in `root` is slc's link.
pub fn is_our_link(root: &Path, relative: &Path) -> bool {
    std::fs::read_link(root.join(relative)).is_ok_and(|t| t == link_target(relative))
}

/// Refuses a result path that is not a plain relative path or that lies at a name of slc's.
pub fn check_relative(relative: &Path) -> Result<(), String> {
    let plain = relative.components().count() > 0
        && relative
            .components()
            .all(|c| matches!(c, Component::Normal(_)));
    let reserved = relative
        .components()
        .next()
        .is_some_and(|c| c.as_os_str().to_string_lossy().starts_with(".slc"));
    if plain && !reserved {
        Ok(())
    } else {
        Err(format!(
            "{}: not a result name (a relative path of plain names, not starting with .slc)",
            relative.display()
        ))
    }
}

/// Every file under `dir` (relative to it), folders not listed; symbolic links are not
/// followed. Unreadable folders list nothing.
pub fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(rel) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(dir.join(&rel)) else {
            continue;
        };
        for e in entries.flatten() {
            let path = rel.join(e.file_name());
            match e.file_type() {
                Ok(t) if t.is_dir() => stack.push(path),
                Ok(_) => files.push(path),
                Err(_) => {}
            }
        }
    }
    files.sort();
    files
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn link_targets_climb_to_the_top_and_versions_parse() {
        assert_eq!(
            link_target(Path::new("a.exr")),
            Path::new(".slc-result/a.exr")
        );
        assert_eq!(
            link_target(Path::new("none/x/a.exr")),
            Path::new("../../.slc-result/none/x/a.exr")
        );
        assert_eq!(version_of(OsStr::new(".slc-result-12")), Some(12));
        for other in [
            ".slc-result-",
            ".slc-result-1x",
            ".slc-result",
            ".slc-result-+1",
        ] {
            assert_eq!(version_of(OsStr::new(other)), None, "{other}");
        }
        assert!(check_relative(Path::new("none/total.exr")).is_ok());
        for bad in ["", "../x", "/abs", ".slc-result/x", ".slc.lock", "a/../b"] {
            assert!(check_relative(Path::new(bad)).is_err(), "{bad}");
        }
    }
}
