//! What became of one part of a batch, kept in its folder (`OUT/parts/<name>/batch-part.json`):
//! its status, the fingerprint of the input and options it was made from, its patterns' figures
//! and warnings. A rerun skips a part whose record is final and whose fingerprint still matches.

use std::fs::{self, File};
use std::io;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::export::report::PartReport;
use crate::export::{remove_stale_temporaries, write_atomically};

use super::errors::BatchError;

/// Name of a part's record in its folder.
pub const RECORD_FILE: &str = "batch-part.json";

/// Name of the lock file a worker holds in a part's folder while it runs the part.
pub const PART_LOCK_FILE: &str = ".flatcut-batch.lock";

/// What became of a part.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PartStatus {
    /// Every pattern within tolerance and valid.
    Ok,
    /// Written, but a pattern is rejected (over tolerance, flipped or overlapping): its cut file
    /// is `<part>.REJECTED.dxf`.
    OverTolerance,
    /// Refused (bad input, a part flatcut cannot do): the reason says why; nothing written.
    Refused,
    /// Stopped at the batch's time limit; nothing written.
    TimedOut,
    /// The worker ended without a result (killed, crashed); the reason says how.
    Failed,
}

impl PartStatus {
    /// The status as records, summaries and the command line write it (`over_tolerance`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Ok => "ok",
            Self::OverTolerance => "over_tolerance",
            Self::Refused => "refused",
            Self::TimedOut => "timed_out",
            Self::Failed => "failed",
        }
    }

    /// Whether a rerun with the same input and options would give the same: a timed-out or
    /// failed part is tried again.
    pub fn is_final(self) -> bool {
        matches!(self, Self::Ok | Self::OverTolerance | Self::Refused)
    }

    /// The exit code this status asks for: 0 ok, 3 over tolerance, 1 otherwise.
    pub fn exit_code(self) -> u8 {
        match self {
            Self::Ok => 0,
            Self::OverTolerance => 3,
            Self::Refused | Self::TimedOut | Self::Failed => 1,
        }
    }
}

/// What identifies the work a record was made from: the input's content and the options.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Fingerprint {
    /// SHA-256 of the input file (and its cut sidecar, when it has one), hex.
    pub input_sha256: String,
    /// SHA-256 of the part's name, options and the flatcut version, hex.
    pub options_sha256: String,
}

/// One pattern of a part, as its run's report gives it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PatternFigures {
    /// Pattern name.
    pub name: String,
    /// Area error E_S (fraction).
    pub area_error: f64,
    /// Shape error E_C (fraction).
    pub shape_error: f64,
    /// Flipped triangles.
    pub flipped: usize,
    /// Crest-line cuts made.
    pub cuts: usize,
    /// Why the pattern is rejected (empty when it is not).
    pub rejected: Vec<String>,
}

impl PatternFigures {
    /// The figures of one part of a run's report.
    pub fn of_report(part: &PartReport) -> Self {
        Self {
            name: part.name.clone(),
            area_error: part.area_error,
            shape_error: part.shape_error,
            flipped: part.flipped,
            cuts: part.cuts.len(),
            rejected: part.rejected.clone(),
        }
    }
}

/// A part's record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PartRecord {
    /// The part's name.
    pub name: String,
    /// The input, as the manifest or command line wrote it.
    pub input: String,
    /// What became of it.
    pub status: PartStatus,
    /// Why it was refused, timed out or failed.
    pub reason: Option<String>,
    /// What it was made from.
    pub fingerprint: Fingerprint,
    /// Its patterns (a file may hold several parts), when written.
    pub patterns: Vec<PatternFigures>,
    /// Repairs made to the input and other warnings.
    pub warnings: Vec<String>,
}

impl PartRecord {
    /// Reads the record in `folder`, if there is a readable one.
    pub fn read(folder: &Path) -> Option<Self> {
        let text = fs::read_to_string(folder.join(RECORD_FILE)).ok()?;
        serde_json::from_str(&text).ok()
    }

    /// Writes the record into `folder`, atomically.
    pub fn write(&self, folder: &Path) -> Result<(), BatchError> {
        let path = folder.join(RECORD_FILE);
        let mut text = serde_json::to_string_pretty(self).expect("a record serialises");
        text.push('\n');
        write_atomically(&path, text.as_bytes())
            .map_err(|source| BatchError::Write { path, source })
    }

    /// Removes the record in `folder`, if any, and what a worker killed while writing it left:
    /// the part is being made anew.
    pub fn remove(folder: &Path) -> Result<(), BatchError> {
        let path = folder.join(RECORD_FILE);
        remove_stale_temporaries(&path);
        match fs::remove_file(&path) {
            Err(source) if source.kind() != io::ErrorKind::NotFound => {
                Err(BatchError::Write { path, source })
            }
            _ => Ok(()),
        }
    }
}

/// Takes the exclusive lock of `path` (created if missing), waiting for its holder; the lock
/// goes with the returned file (and with the process, however it ends).
pub fn lock_exclusive(path: &Path) -> Result<File, BatchError> {
    let write_error = |source| BatchError::Write {
        path: PathBuf::from(path),
        source,
    };
    let file = File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(path)
        .map_err(write_error)?;
    file.lock().map_err(write_error)?;
    Ok(file)
}

#[cfg(test)]
mod tests {
    use crate::batch::record::*;

    #[test]
    fn a_status_is_named_as_records_write_it() {
        for status in [
            PartStatus::Ok,
            PartStatus::OverTolerance,
            PartStatus::Refused,
            PartStatus::TimedOut,
            PartStatus::Failed,
        ] {
            let written = serde_json::to_value(status).expect("serialises");
            assert_eq!(written.as_str(), Some(status.name()));
        }
    }
}
