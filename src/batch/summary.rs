//! The batch summary, `OUT/batch.json`: every part of the manifest in its order, with its status
//! from its record (`pending` when it has none matching its input and options yet: not run, or
//! run by another shard still going), and the count of each status. It is made from the records
//! alone, so every shard writing into one output folder writes the same summary once all are
//! done, and it is the same as an unsharded batch's.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Serialize;

use crate::export::{remove_stale_temporaries, write_atomically};

use super::errors::BatchError;
use super::record::{Fingerprint, PartRecord, PatternFigures, lock_exclusive};
use super::task::{PARTS_FOLDER, PartTask};

/// Name of the summary in the batch's output folder.
pub const SUMMARY_FILE: &str = "batch.json";

/// Name of the lock file held while the summary is made and written.
const SUMMARY_LOCK_FILE: &str = ".flatcut-batch.lock";

/// The status of a part with no record matching its input and options yet.
const PENDING: &str = "pending";

/// Version of the summary's layout.
pub const SUMMARY_VERSION: u32 = 1;

/// A part as the summary lists it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SummaryPart {
    /// The part's name.
    pub name: String,
    /// The input, as written.
    pub input: String,
    /// The part's folder, relative to the output folder.
    pub folder: String,
    /// Its status, or `pending`.
    pub status: String,
    /// Why it was refused, timed out or failed.
    pub reason: Option<String>,
    /// Its patterns' figures.
    pub patterns: Vec<PatternFigures>,
    /// Warnings.
    pub warnings: Vec<String>,
}

/// The summary of a batch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BatchSummary {
    /// Always `flatcut-batch`.
    pub format: &'static str,
    /// [`SUMMARY_VERSION`].
    pub version: u32,
    /// The flatcut version that wrote it.
    pub flatcut_version: &'static str,
    /// How many parts have each status.
    pub counts: BTreeMap<String, usize>,
    /// Every part, in manifest order.
    pub parts: Vec<SummaryPart>,
}

impl BatchSummary {
    /// The summary of `tasks` from their records, a record counting only when it matches the
    /// task's fingerprint.
    pub fn from_records(tasks: &[PartTask], fingerprints: &[Fingerprint]) -> Self {
        let parts: Vec<SummaryPart> = tasks
            .iter()
            .zip(fingerprints)
            .map(|(task, fingerprint)| {
                let record = PartRecord::read(&task.folder)
                    .filter(|record| &record.fingerprint == fingerprint);
                SummaryPart {
                    name: task.name.clone(),
                    input: task.input.clone(),
                    folder: format!("{PARTS_FOLDER}/{}", task.name),
                    status: record
                        .as_ref()
                        .map_or(PENDING, |record| record.status.name())
                        .to_string(),
                    reason: record.as_ref().and_then(|record| record.reason.clone()),
                    patterns: record
                        .as_ref()
                        .map(|record| record.patterns.clone())
                        .unwrap_or_default(),
                    warnings: record.map(|record| record.warnings).unwrap_or_default(),
                }
            })
            .collect();
        let mut counts = BTreeMap::new();
        for part in &parts {
            *counts.entry(part.status.clone()).or_insert(0) += 1;
        }
        Self {
            format: "flatcut-batch",
            version: SUMMARY_VERSION,
            flatcut_version: env!("CARGO_PKG_VERSION"),
            counts,
            parts,
        }
    }
}

/// Makes the summary of `tasks` from their records and writes it to `OUT/batch.json`
/// atomically, holding the output folder's batch lock (so that shards finishing together write
/// one after the other, the last seeing every record). Returns the summary.
pub fn write_summary(
    output: &Path,
    tasks: &[PartTask],
    fingerprints: &[Fingerprint],
) -> Result<BatchSummary, BatchError> {
    std::fs::create_dir_all(output).map_err(|source| BatchError::Write {
        path: output.to_path_buf(),
        source,
    })?;
    let _lock = lock_exclusive(&output.join(SUMMARY_LOCK_FILE))?;
    let summary = BatchSummary::from_records(tasks, fingerprints);
    let mut text = serde_json::to_string_pretty(&summary).expect("a summary serialises");
    text.push('\n');
    let path = output.join(SUMMARY_FILE);
    remove_stale_temporaries(&path);
    write_atomically(&path, text.as_bytes())
        .map_err(|source| BatchError::Write { path, source })?;
    Ok(summary)
}
