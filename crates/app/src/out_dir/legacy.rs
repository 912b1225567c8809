//! Output folders of slc before versioned results: regular files renamed into place one by
//! one, listed in `.slc-manifest`. Opening one turns its result into a version: each listed
//! file is hard-linked (copied where the file system has no hard links) into the version
//! folder, `.slc-result` is pointed at it, and each final name is replaced by slc's link with
//! one rename, so every name shows the same bytes throughout. A run killed midway leaves the
//! manifest, and the next one finishes the work.
use super::layout::{
    check_relative, current_version, link_target, version_name, CURRENT, LEGACY_MANIFEST, LINK_TMP,
    NEXT,
};
use std::fs;
use std::path::Path;

pub fn migrate(root: &Path) -> Result<(), String> {
    let manifest = root.join(LEGACY_MANIFEST);
    let Ok(list) = fs::read_to_string(&manifest) else {
        return Ok(());
    };
    let failed = |e: std::io::Error| {
        format!(
            "{}: cannot convert the result of an earlier slc to versioned results: {e}",
            root.display()
        )
    };
    let current = current_version(root)?;
    let version = root.join(version_name(current.unwrap_or(1)));
    let files: Vec<&Path> = list
        .lines()
        .map(Path::new)
        .filter(|f| check_relative(f).is_ok())
        .filter(|f| root.join(f).symlink_metadata().is_ok_and(|m| m.is_file()))
        .collect();
    for f in &files {
        let kept = version.join(f);
        if let Some(parent) = kept.parent() {
            fs::create_dir_all(parent).map_err(failed)?;
        }
        if kept.symlink_metadata().is_err() {
            fs::hard_link(root.join(f), &kept)
                .or_else(|_| fs::copy(root.join(f), &kept).map(|_| ()))
                .map_err(failed)?;
        }
    }
    if current.is_none() {
        std::os::unix::fs::symlink(version_name(1), root.join(NEXT))
            .and_then(|()| fs::rename(root.join(NEXT), root.join(CURRENT)))
            .map_err(failed)?;
    }
    for f in &files {
        std::os::unix::fs::symlink(link_target(f), root.join(LINK_TMP))
            .and_then(|()| fs::rename(root.join(LINK_TMP), root.join(f)))
            .map_err(failed)?;
    }
    fs::remove_file(&manifest).map_err(failed)
}
