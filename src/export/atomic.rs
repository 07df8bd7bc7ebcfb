//! Atomic file writing: the bytes go to a temporary file in the destination's directory, are
//! flushed to disk, and the file is renamed to its final name. A reader sees either the old file
//! or the complete new one, never a half-written file; a failure removes the temporary file.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes temporary files of one process (several writers may run at once).
static TEMPORARY_COUNTER: AtomicU64 = AtomicU64::new(0);

/// Writes `bytes` to `path` atomically: temporary file in the same directory, fsync, rename, then
/// fsync of the directory (on Unix) so the rename itself survives a crash.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let directory = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let file_name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("`{}` names no file", path.display()),
        )
    })?;
    let temporary = directory.join(format!(
        ".{}.{}-{}.tmp",
        file_name.to_string_lossy(),
        std::process::id(),
        TEMPORARY_COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let written = write_and_sync(&temporary, bytes).and_then(|()| fs::rename(&temporary, path));
    if written.is_err() {
        // The temporary file may not exist (creation failed); its removal error is not the news.
        let _ = fs::remove_file(&temporary);
        return written;
    }
    sync_directory(&directory)
}

/// Creates `path` (failing if it exists), writes `bytes` and flushes them to disk.
fn write_and_sync(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut file = OpenOptions::new().write(true).create_new(true).open(path)?;
    file.write_all(bytes)?;
    file.sync_all()
}

/// Flushes a directory's entries (the rename) to disk; a no-op where directories cannot be opened.
fn sync_directory(directory: &Path) -> io::Result<()> {
    if cfg!(unix) {
        File::open(directory)?.sync_all()
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::export::atomic::*;

    #[test]
    fn writes_replaces_and_leaves_no_temporary_file() {
        let directory = tempfile::tempdir().expect("a temporary directory");
        let path = directory.path().join("part.dxf");
        write_atomically(&path, b"first").expect("first write");
        write_atomically(&path, b"second").expect("second write");
        assert_eq!(fs::read(&path).expect("readable"), b"second");
        let entries = fs::read_dir(directory.path()).expect("listable").count();
        assert_eq!(entries, 1);
    }

    #[test]
    fn failure_leaves_nothing_under_the_final_name() {
        let directory = tempfile::tempdir().expect("a temporary directory");
        let path = directory.path().join("missing").join("part.dxf");
        assert!(write_atomically(&path, b"bytes").is_err());
        assert!(!path.exists());
    }
}
