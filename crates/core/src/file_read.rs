//! Reading input files with a size cap: scene files, material libraries, buffers, textures.
//! What a load read is recorded (`recording`), so a report can name and hash every file
//! that went into a scene.
use std::cell::RefCell;
use std::io::{Error, ErrorKind, Read};
use std::path::{Path, PathBuf};

thread_local! {
    /// The files read so far by the [`recording`] running on this thread, if one is.
    static READ: RefCell<Option<Vec<PathBuf>>> = const { RefCell::new(None) };
}

/// Runs `f` (a load: the loaders run on the calling thread) and returns, with its result,
/// every file [`read_capped`] read during it, in the order first read, each once. Inside
/// another recording, the files go to both.
pub(crate) fn recording<T>(f: impl FnOnce() -> T) -> (T, Vec<PathBuf>) {
    let outer = READ.with(|r| r.borrow_mut().replace(Vec::new()));
    let out = f();
    let files = READ.with(|r| r.borrow_mut().take()).unwrap_or_default();
    if let Some(mut outer) = outer {
        for file in &files {
            if !outer.contains(file) {
                outer.push(file.clone());
            }
        }
        READ.with(|r| *r.borrow_mut() = Some(outer));
    }
    (out, files)
}

/// Notes that `path` was read, for the [`recording`] running on this thread.
fn note_read(path: &Path) {
    READ.with(|r| {
        if let Some(files) = r.borrow_mut().as_mut() {
            if !files.iter().any(|f| f == path) {
                files.push(path.to_path_buf());
            }
        }
    });
}

/// The largest file slc reads: 4 GiB. Larger scene files, buffers or textures (or a device
/// such as `/dev/zero` given a scene file's name) are refused before they are read.
pub const MAX_INPUT_FILE_BYTES: u64 = 4 << 30;

/// A regular file of at most [`MAX_INPUT_FILE_BYTES`], opened to be read as a stream (one
/// that grows past the cap while it is read ends there: [`capped_at_end`] tells).
pub(crate) fn open_capped(path: &Path) -> std::io::Result<std::io::Take<std::fs::File>> {
    check_regular(path)?;
    let file = std::fs::File::open(path)?;
    note_read(path);
    Ok(file.take(MAX_INPUT_FILE_BYTES + 1))
}

/// An error if a stream from [`open_capped`] went past the cap.
pub(crate) fn capped_at_end(stream: &std::io::Take<std::fs::File>) -> std::io::Result<()> {
    match stream.limit() {
        0 => Err(too_big(MAX_INPUT_FILE_BYTES + 1)),
        _ => Ok(()),
    }
}

fn too_big(n: u64) -> Error {
    Error::new(
        ErrorKind::InvalidData,
        format!(
            "{n} bytes or more, above the {MAX_INPUT_FILE_BYTES} bytes slc reads from one file"
        ),
    )
}

/// Refuses what is not a regular file of at most [`MAX_INPUT_FILE_BYTES`].
fn check_regular(path: &Path) -> std::io::Result<u64> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a folder, not a file"
        } else {
            "not a regular file (a device, pipe or socket)"
        };
        return Err(Error::new(ErrorKind::InvalidInput, what));
    }
    if meta.len() > MAX_INPUT_FILE_BYTES {
        return Err(too_big(meta.len()));
    }
    Ok(meta.len())
}

/// The bytes of a regular file of at most [`MAX_INPUT_FILE_BYTES`].
pub(crate) fn read_capped(path: &Path) -> std::io::Result<Vec<u8>> {
    let len = check_regular(path)?;
    let mut bytes = Vec::with_capacity(len as usize);
    // A file that grows while it is read stops at the cap too.
    std::fs::File::open(path)?
        .take(MAX_INPUT_FILE_BYTES + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_INPUT_FILE_BYTES {
        return Err(too_big(bytes.len() as u64));
    }
    note_read(path);
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_and_devices_are_refused() {
        let e = read_capped(&std::env::temp_dir()).unwrap_err();
        assert!(e.to_string().contains("a folder"), "{e}");
        let e = read_capped(Path::new("/dev/zero")).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
        assert_eq!(
            read_capped(Path::new("/nonexistent/x")).unwrap_err().kind(),
            ErrorKind::NotFound
        );
    }

    #[test]
    fn a_recording_lists_the_files_read_once_each_in_order() {
        let dir = std::env::temp_dir().join(format!("slc-core-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (a, b) = (dir.join("a.obj"), dir.join("b.mtl"));
        std::fs::write(&a, "a").unwrap();
        std::fs::write(&b, "b").unwrap();
        let ((), outer) = recording(|| {
            read_capped(&a).unwrap();
            let ((), inner) = recording(|| {
                read_capped(&b).unwrap();
                read_capped(&a).unwrap();
                // A file that cannot be read was not read.
                read_capped(&dir.join("missing.png")).unwrap_err();
            });
            assert_eq!(inner, [b.clone(), a.clone()]);
            read_capped(&b).unwrap();
        });
        assert_eq!(outer, [a.clone(), b.clone()]);
        // Outside a recording nothing is kept.
        read_capped(&a).unwrap();
        assert_eq!(recording(|| ()).1, Vec::<PathBuf>::new());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
