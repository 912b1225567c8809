//! The lock of an output folder: `.slc.lock`, held exclusively for the whole run (the OS
//! releases it when the process ends, however it ends), holding a line that names the holder.
use std::fs::{self, File};
use std::io::{Read, Write};
use std::os::unix::fs::MetadataExt;
use std::path::Path;

pub const LOCK: &str = ".slc.lock";

/// Takes the lock of `root` (an existing folder), or says who holds it.
///
/// A run that ends without a result in a folder it made removes its lock file while it holds
/// it (`super::remove_created`): a run that opened that file just before can lock it once it
/// is released, though the file is no longer the folder's. So the file locked must still be
/// the one at `.slc.lock`; else the lock is taken again, from the file there now.
pub fn lock(root: &Path) -> Result<File, String> {
    for _ in 0..3 {
        let lock = lock_file(root)?;
        let now = fs::metadata(root.join(LOCK)).ok();
        let held = lock.metadata().ok();
        if let (Some(now), Some(held)) = (now, held) {
            if (now.dev(), now.ino()) == (held.dev(), held.ino()) {
                return Ok(lock);
            }
        }
    }
    Err(format!(
        "{}: the output folder changed while it was being locked (another slc run gave it up); \
         run again",
        root.display()
    ))
}

/// Opens `root`'s lock file (made if missing), locks it and writes the holder's line.
fn lock_file(root: &Path) -> Result<File, String> {
    let at = |what: &str, e: std::io::Error| format!("{}: {what}: {e}", root.display());
    let mut lock = File::options()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .open(root.join(LOCK))
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
    Ok(lock)
}

/// What the lock file says about its holder.
fn holder_line() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let args: Vec<String> = std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
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
