//! Atomic file writing: the bytes go to a temporary file in the destination's directory, are
//! flushed to disk, and the file is renamed to its final name. A reader sees either the old file
//! or the complete new one, never a half-written file; a failure removes the temporary file.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes temporary files of one process (several writers may run at once).
static TEMPORARY_COUNTER: AtomicU64 = AtomicU64::new(0);

/// Removes the temporary files [`write_atomically`] left beside `path` when its process was
/// killed while writing (`.NAME.PID-N.tmp`): before `path` is written anew, so that none
/// lingers. Best effort.
pub fn remove_stale_temporaries(path: &Path) {
    let (Some(directory), Some(name)) = (path.parent(), path.file_name()) else {
        return;
    };
    let directory = if directory.as_os_str().is_empty() {
        Path::new(".")
    } else {
        directory
    };
    let prefix = format!(".{}.", name.to_string_lossy());
    let Ok(entries) = fs::read_dir(directory) else {
        return;
    };
    for entry in entries.flatten() {
        let entry_name = entry.file_name().to_string_lossy().into_owned();
        if entry_name.starts_with(&prefix) && entry_name.ends_with(".tmp") {
            let _ = fs::remove_file(entry.path());
        }
    }
}

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
    fn a_killed_writer_s_temporary_files_are_removed_and_no_other() {
        let directory = tempfile::tempdir().expect("a temporary directory");
        let path = directory.path().join("batch.json");
        for name in [
            ".batch.json.123-0.tmp",
            ".batch.json.9-4.tmp",
            "keep.tmp",
            ".other.json.1-0.tmp",
        ] {
            fs::write(directory.path().join(name), b"x").expect("written");
        }
        remove_stale_temporaries(&path);
        let mut left: Vec<String> = fs::read_dir(directory.path())
            .expect("listable")
            .map(|entry| {
                entry
                    .expect("entry")
                    .file_name()
                    .to_string_lossy()
                    .into_owned()
            })
            .collect();
        left.sort();
        assert_eq!(left, [".other.json.1-0.tmp", "keep.tmp"]);
    }

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
