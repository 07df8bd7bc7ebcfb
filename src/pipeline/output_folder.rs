//! The output folder of a run, kept safe: an input inside it under a name a run writes is
//! refused before any work ([`check_inputs_outside`]); a run writes into a staging folder inside
//! it ([`OutputFolder`]) and, at the end, replaces the previous run's files as one set, removing
//! those of the previous run it did not write (listed in [`MANIFEST_FILE`]) and leaving alone the
//! files no run wrote. An interrupted run ([`InterruptHandle`]) removes its staging folder, so
//! the folder holds the previous complete run.

use std::collections::BTreeSet;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use crate::error::Error;
use crate::export::write_atomically;
use crate::pattern::PATTERN_FILE_ENDING;

/// Name of the file, in the output folder, listing every file the last complete run wrote.
pub const MANIFEST_FILE: &str = ".flatcut-manifest.json";

/// Endings of the file names a run writes into its output folder (`<part>.mesh.obj`,
/// `<part>.pattern.obj`, `<part>.pattern.json`, `<part>.dxf`, `<part>.REJECTED.dxf`,
/// `<part>.energy.png`, and in `sheets/` `sheet-NNN.dxf` and `.png`).
const WRITTEN_ENDINGS: [&str; 5] = [
    ".mesh.obj",
    ".pattern.obj",
    PATTERN_FILE_ENDING,
    ".dxf",
    ".png",
];

/// Whole names a run (or `flatcut nest`) writes into its output folder.
const WRITTEN_NAMES: [&str; 3] = ["report.json", "nest.json", MANIFEST_FILE];

/// Refuses an input that lies in `directory` (or its `sheets/` folder) under a name of the kind a
/// run writes or replaces there: the run would overwrite or remove it. Nothing is created; an
/// output folder that does not exist yet holds no input.
pub fn check_inputs_outside(directory: &Path, inputs: &[PathBuf]) -> Result<(), Error> {
    let Ok(folder) = directory.canonicalize() else {
        return Ok(());
    };
    let sheets = folder.join("sheets");
    for input in inputs {
        let Ok(path) = input.canonicalize() else {
            continue;
        };
        let inside = path
            .parent()
            .is_some_and(|parent| parent == folder || parent == sheets);
        let name = path
            .file_name()
            .map(|name| name.to_string_lossy().into_owned())
            .unwrap_or_default();
        let written_kind = WRITTEN_NAMES.contains(&name.as_str())
            || WRITTEN_ENDINGS
                .iter()
                .any(|ending| name.to_ascii_lowercase().ends_with(ending));
        if inside && written_kind {
            return Err(Error::InputInOutput {
                input: input.clone(),
                directory: directory.to_path_buf(),
            });
        }
    }
    Ok(())
}

/// Prefix of the staging folders inside an output folder (followed by the process id).
const STAGING_PREFIX: &str = ".flatcut-staging-";

/// Where a run's files are while it writes them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Being written into the staging folder.
    Writing,
    /// Replacing the previous run's files: an interruption waits for the end.
    Replacing,
    /// Replaced, or the staging folder removed.
    Finished,
}

/// An output folder being written: its staging folder and what phase the run is in.
#[derive(Debug)]
pub struct OutputFolder {
    directory: PathBuf,
    /// Whether this run created the folder (an error then removes it again when empty).
    created: bool,
    staging: PathBuf,
    phase: Arc<Mutex<Phase>>,
}

/// Lets another thread (a signal handler) abandon a run's staging folder.
#[derive(Debug, Clone)]
pub struct InterruptHandle {
    staging: PathBuf,
    phase: Arc<Mutex<Phase>>,
}

impl InterruptHandle {
    /// Removes the staging folder unless the run is already replacing the folder's files, and
    /// returns whether it did (the caller may then end the process: the folder holds the previous
    /// run). While this runs, the run cannot start replacing.
    pub fn abandon(&self) -> bool {
        let mut phase = self.phase.lock().unwrap_or_else(PoisonError::into_inner);
        match *phase {
            Phase::Writing => {
                remove_staging(&self.staging);
                *phase = Phase::Finished;
                true
            }
            Phase::Replacing => false,
            Phase::Finished => true,
        }
    }
}

/// Removes a staging folder the run may still be writing into from another thread: renamed
/// first (still a staging folder's name), so that no new file lands in it by its path, then
/// removed. Best effort: a staging folder left behind is removed by the next run.
fn remove_staging(staging: &Path) {
    let mut abandoned = staging.as_os_str().to_owned();
    abandoned.push("-abandoned");
    let abandoned = PathBuf::from(abandoned);
    let doomed = if fs::rename(staging, &abandoned).is_ok() {
        abandoned.as_path()
    } else {
        staging
    };
    for _ in 0..3 {
        if fs::remove_dir_all(doomed).is_ok() || !doomed.exists() {
            return;
        }
    }
}

impl OutputFolder {
    /// Creates `directory` if missing and a fresh staging folder inside it, after removing the
    /// staging folders that interrupted runs left; an error names the folder that cannot be
    /// written.
    pub fn prepare(directory: &Path) -> Result<Self, Error> {
        let cannot_write = |path: &Path, source: io::Error| Error::CreateDirectory {
            path: path.to_path_buf(),
            source,
        };
        let created = !directory.exists();
        fs::create_dir_all(directory).map_err(|source| cannot_write(directory, source))?;
        let entries = fs::read_dir(directory).map_err(|source| cannot_write(directory, source))?;
        for entry in entries.flatten() {
            let staging = entry
                .file_name()
                .to_string_lossy()
                .starts_with(STAGING_PREFIX);
            if staging && entry.file_type().is_ok_and(|kind| kind.is_dir()) {
                let _ = fs::remove_dir_all(entry.path());
            }
        }
        let staging = directory.join(format!("{STAGING_PREFIX}{}", std::process::id()));
        fs::create_dir(&staging).map_err(|source| cannot_write(directory, source))?;
        Ok(Self {
            directory: directory.to_path_buf(),
            created,
            staging,
            phase: Arc::new(Mutex::new(Phase::Writing)),
        })
    }

    /// Whether the run was abandoned ([`InterruptHandle::abandon`]): an error it meets while
    /// writing is then the interruption's doing.
    pub fn abandoned(&self) -> bool {
        *self.phase.lock().unwrap_or_else(PoisonError::into_inner) == Phase::Finished
    }

    /// The staging folder: the run writes its files here.
    pub fn staging(&self) -> &Path {
        &self.staging
    }

    /// A handle to abandon the run from another thread.
    pub fn interrupt_handle(&self) -> InterruptHandle {
        InterruptHandle {
            staging: self.staging.clone(),
            phase: Arc::clone(&self.phase),
        }
    }

    /// Replaces the previous run's files by the staged ones as one set: moves every staged file
    /// into place, removes the files the previous run wrote (its manifest) that this run did not,
    /// writes the new manifest and removes the staging folder. Returns the files written,
    /// relative to the folder, sorted. Errors when the run was abandoned.
    pub fn commit(self) -> Result<Vec<PathBuf>, Error> {
        {
            let mut phase = self.phase.lock().unwrap_or_else(PoisonError::into_inner);
            if *phase != Phase::Writing {
                return Err(Error::Interrupted);
            }
            *phase = Phase::Replacing;
        }
        let result = self.replace();
        let _ = fs::remove_dir_all(&self.staging);
        *self.phase.lock().unwrap_or_else(PoisonError::into_inner) = Phase::Finished;
        result
    }

    /// The replacement itself (see [`Self::commit`]).
    fn replace(&self) -> Result<Vec<PathBuf>, Error> {
        let write_error = |path: &Path, source: io::Error| {
            Error::Export(crate::export::ExportError::Write {
                path: path.to_path_buf(),
                source,
            })
        };
        let mut written = Vec::new();
        list_files(&self.staging, Path::new(""), &mut written)
            .map_err(|source| write_error(&self.staging, source))?;
        written.sort();
        let previous = read_manifest(&self.directory);
        for relative in &written {
            let target = self.directory.join(relative);
            if let Some(parent) = target.parent() {
                fs::create_dir_all(parent).map_err(|source| write_error(parent, source))?;
            }
            fs::rename(self.staging.join(relative), &target)
                .map_err(|source| write_error(&target, source))?;
        }
        let kept: BTreeSet<&PathBuf> = written.iter().collect();
        for stale in previous.iter().filter(|path| !kept.contains(path)) {
            // Only plain relative names a run writes: a doctored manifest removes nothing else.
            if is_run_file(stale) {
                let _ = fs::remove_file(self.directory.join(stale));
            }
        }
        let names: Vec<String> = written
            .iter()
            .map(|path| path.to_string_lossy().replace('\\', "/"))
            .collect();
        let mut manifest = serde_json::to_string_pretty(&serde_json::json!({
            "written_by": format!("flatcut {}", env!("CARGO_PKG_VERSION")),
            "files": names,
        }))
        .unwrap_or_default();
        manifest.push('\n');
        let path = self.directory.join(MANIFEST_FILE);
        write_atomically(&path, manifest.as_bytes())
            .map_err(|source| write_error(&path, source))?;
        Ok(written)
    }
}

impl Drop for OutputFolder {
    /// A run that ends before its commit (an error) removes its staging folder, and the output
    /// folder too when it created it and it is empty: a failed run writes nothing.
    fn drop(&mut self) {
        let mut phase = self.phase.lock().unwrap_or_else(PoisonError::into_inner);
        if *phase == Phase::Writing {
            let _ = fs::remove_dir_all(&self.staging);
            if self.created {
                let _ = fs::remove_dir(&self.directory);
            }
            *phase = Phase::Finished;
        }
    }
}

/// Every file under `root/relative`, as paths relative to `root`.
fn list_files(root: &Path, relative: &Path, files: &mut Vec<PathBuf>) -> io::Result<()> {
    for entry in fs::read_dir(root.join(relative))? {
        let entry = entry?;
        let path = relative.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            list_files(root, &path, files)?;
        } else {
            files.push(path);
        }
    }
    Ok(())
}

/// Whether `directory` holds a complete run: its manifest and every file the manifest lists.
pub fn complete_run_present(directory: &Path) -> bool {
    directory.join(MANIFEST_FILE).is_file()
        && read_manifest(directory)
            .iter()
            .all(|file| directory.join(file).is_file())
}

/// Removes the last complete run's files and its manifest from `directory`, leaving the files no
/// run wrote: for a folder whose new run was refused, so that no stale run looks current.
pub fn remove_previous_run(directory: &Path) -> io::Result<()> {
    for file in read_manifest(directory) {
        if is_run_file(&file) {
            match fs::remove_file(directory.join(&file)) {
                Err(error) if error.kind() != io::ErrorKind::NotFound => return Err(error),
                _ => {}
            }
        }
    }
    match fs::remove_file(directory.join(MANIFEST_FILE)) {
        Err(error) if error.kind() != io::ErrorKind::NotFound => Err(error),
        _ => Ok(()),
    }
}

/// The files the previous complete run in `directory` wrote (none without a manifest).
fn read_manifest(directory: &Path) -> Vec<PathBuf> {
    let Ok(text) = fs::read_to_string(directory.join(MANIFEST_FILE)) else {
        return Vec::new();
    };
    let Ok(value) = serde_json::from_str::<serde_json::Value>(&text) else {
        return Vec::new();
    };
    value["files"]
        .as_array()
        .map(|files| {
            files
                .iter()
                .filter_map(|file| file.as_str().map(PathBuf::from))
                .collect()
        })
        .unwrap_or_default()
}

/// Whether `path` is a name a run writes: a file of the folder, of `sheets/` or of a folder in
/// `sheets/` (`flatcut nest` puts each group's sheets in one), of a kind a run writes.
fn is_run_file(path: &Path) -> bool {
    use std::path::Component::Normal;
    let components: Vec<_> = path.components().collect();
    let in_place = match components.as_slice() {
        [Normal(_)] => true,
        [Normal(folder), Normal(_)] | [Normal(folder), Normal(_), Normal(_)] => *folder == "sheets",
        _ => false,
    };
    let name = path
        .file_name()
        .map(|name| name.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    in_place
        && (WRITTEN_NAMES.contains(&name.as_str())
            || WRITTEN_ENDINGS.iter().any(|ending| name.ends_with(ending)))
}

#[cfg(test)]
mod tests {
    use crate::pipeline::output_folder::*;

    #[test]
    fn an_input_named_like_an_output_inside_the_folder_is_refused() {
        let directory = tempfile::tempdir().expect("a temporary directory");
        let input = directory.path().join("cone.mesh.obj");
        std::fs::write(&input, "v 0 0 0\n").expect("written");
        let other = directory.path().join("cone.obj");
        std::fs::write(&other, "v 0 0 0\n").expect("written");
        assert!(check_inputs_outside(directory.path(), std::slice::from_ref(&other)).is_ok());
        assert!(matches!(
            check_inputs_outside(directory.path(), &[other, input]),
            Err(Error::InputInOutput { .. })
        ));
        assert!(check_inputs_outside(&directory.path().join("missing"), &[]).is_ok());
    }

    #[test]
    fn the_sheets_of_a_nest_group_are_run_files_and_nothing_deeper() {
        for name in [
            "sheets/steel-2mm/sheet-001.dxf",
            "nest.json",
            "a.pattern.json",
        ] {
            assert!(is_run_file(Path::new(name)), "{name}");
        }
        for name in [
            "parts/a/a.dxf",
            "sheets/a/b/sheet-001.dxf",
            "../a.dxf",
            "notes.txt",
        ] {
            assert!(!is_run_file(Path::new(name)), "{name}");
        }
    }

    fn stage(folder: &OutputFolder, files: &[&str]) {
        for file in files {
            let path = folder.staging().join(file);
            fs::create_dir_all(path.parent().expect("a parent")).expect("created");
            fs::write(path, file).expect("written");
        }
    }

    #[test]
    fn a_commit_replaces_the_previous_run_and_keeps_the_user_files() {
        let directory = tempfile::tempdir().expect("a temporary directory");
        let root = directory.path();
        fs::write(root.join("notes.txt"), "mine").expect("written");
        let first = OutputFolder::prepare(root).expect("prepared");
        stage(
            &first,
            &[
                "a.dxf",
                "report.json",
                "sheets/sheet-001.dxf",
                "sheets/sheet-002.dxf",
            ],
        );
        first.commit().expect("committed");
        assert!(root.join("sheets/sheet-002.dxf").exists());
        let second = OutputFolder::prepare(root).expect("prepared");
        stage(&second, &["b.dxf", "report.json", "sheets/sheet-001.dxf"]);
        let written = second.commit().expect("committed");
        assert_eq!(written.len(), 3);
        let mut names: Vec<PathBuf> = Vec::new();
        list_files(root, Path::new(""), &mut names).expect("listed");
        names.sort();
        let expected: Vec<PathBuf> = [
            MANIFEST_FILE,
            "b.dxf",
            "notes.txt",
            "report.json",
            "sheets/sheet-001.dxf",
        ]
        .iter()
        .map(PathBuf::from)
        .collect();
        assert_eq!(names, expected);
    }

    #[test]
    fn an_abandoned_or_failed_run_leaves_the_previous_one() {
        let directory = tempfile::tempdir().expect("a temporary directory");
        let root = directory.path();
        let first = OutputFolder::prepare(root).expect("prepared");
        stage(&first, &["a.dxf"]);
        first.commit().expect("committed");
        let second = OutputFolder::prepare(root).expect("prepared");
        stage(&second, &["b.dxf"]);
        assert!(second.interrupt_handle().abandon());
        assert!(matches!(second.commit(), Err(Error::Interrupted)));
        let third = OutputFolder::prepare(root).expect("prepared");
        stage(&third, &["c.dxf"]);
        drop(third);
        // a.dxf and the manifest: no staging folder is left.
        assert_eq!(fs::read_dir(root).expect("listable").count(), 2);
        assert!(root.join("a.dxf").exists());
    }
}
