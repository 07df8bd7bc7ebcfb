//! Batches: a whole job's parts in one command. Each part of a manifest (or each input file) is
//! run by a worker process of its own into `OUT/parts/<name>/` (a complete run folder, with its
//! report), at most `jobs` at once, each within an optional time limit; what became of it is
//! recorded in its folder ([`PartRecord`]) with the fingerprint of its input and options, so a
//! rerun skips the parts already done ([`run_batch`]). `--shard I/N` takes a fixed 1/N of the
//! parts, for N machines or array tasks sharing one output folder or merging theirs; the
//! summary `OUT/batch.json` is made from the records alone ([`BatchSummary`]).
//!
//! `docs/batch.md` describes the manifest, the folder layout and the summary; `docs/cluster.md`
//! gives the Slurm, Kubernetes and GNU parallel recipes.

mod errors;
mod manifest;
mod record;
mod schedule;
mod summary;
mod task;

use std::path::PathBuf;
use std::str::FromStr;
use std::sync::atomic::AtomicBool;

pub use errors::BatchError;
pub use manifest::{
    BatchPart, MANIFEST_FIELDS, MAXIMUM_NAME_BYTES, ManifestEntry, parse_manifest, parts_of_inputs,
    read_manifest,
};
pub use record::{
    Fingerprint, PART_LOCK_FILE, PartRecord, PartStatus, PatternFigures, RECORD_FILE,
};
pub use schedule::{
    BatchEvent, KILL_GRACE, Scheduling, WORKER_SUBCOMMAND, default_kill_after, run_tasks,
};
pub use summary::{BatchSummary, SUMMARY_FILE, SUMMARY_VERSION, SummaryPart, write_summary};
pub use task::{PARTS_FOLDER, PartTask, error_chain, run_part_task};

use crate::pipeline::RunConfig;

/// Which of N shards a batch runs: the parts at positions `index - 1`, `index - 1 + count`, …
/// of the manifest.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, from 1.
    pub index: usize,
    /// The number of shards.
    pub count: usize,
}

impl Default for Shard {
    fn default() -> Self {
        Self { index: 1, count: 1 }
    }
}

impl Shard {
    /// Whether the part at `position` (from 0) of the manifest is this shard's.
    pub fn contains(&self, position: usize) -> bool {
        position % self.count == self.index - 1
    }
}

impl FromStr for Shard {
    type Err = String;

    /// Reads `I/N`, with 1 ≤ I ≤ N.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let invalid = || format!("{text:?}: give I/N, the shard I of N, with 1 <= I <= N");
        let (index, count) = text.split_once('/').ok_or_else(invalid)?;
        let index: usize = index.trim().parse().map_err(|_| invalid())?;
        let count: usize = count.trim().parse().map_err(|_| invalid())?;
        if index == 0 || index > count {
            return Err(invalid());
        }
        Ok(Self { index, count })
    }
}

/// Where a batch's parts come from.
#[derive(Debug, Clone, PartialEq)]
pub enum BatchSource {
    /// A manifest file (CSV or JSON Lines).
    Manifest(PathBuf),
    /// Input files, one part each, named by their file stems.
    Inputs(Vec<PathBuf>),
}

/// A batch.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchConfig {
    /// The parts.
    pub source: BatchSource,
    /// The output folder.
    pub output: PathBuf,
    /// Every part's options (its inputs are ignored); a manifest line's fields go over them.
    pub base: RunConfig,
    /// The shard this batch runs.
    pub shard: Shard,
    /// How the parts are run.
    pub scheduling: Scheduling,
}

/// What a batch did.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchOutcome {
    /// The summary written (every part of the manifest).
    pub summary: BatchSummary,
    /// The record of each part of this shard, `None` for a part not run because the batch was
    /// stopped.
    pub records: Vec<Option<PartRecord>>,
}

impl BatchOutcome {
    /// The exit code of the worst part of this shard: 0 all ok, 3 a part over tolerance, 1 a
    /// part refused, timed out or failed (or not run: the batch was stopped).
    pub fn exit_code(&self) -> u8 {
        self.records
            .iter()
            .map(|record| {
                record
                    .as_ref()
                    .map_or(1, |record| record.status.exit_code())
            })
            .fold(0, |worst, code| match (worst, code) {
                (1, _) | (_, 1) => 1,
                (3, _) | (_, 3) => 3,
                _ => 0,
            })
    }
}

/// The tasks of every part of the batch, in manifest order, checked.
pub fn batch_tasks(config: &BatchConfig) -> Result<Vec<PartTask>, BatchError> {
    config
        .base
        .validate()
        .map_err(|source| BatchError::Options {
            name: "(every part)".to_string(),
            source: Box::new(source),
        })?;
    let parts = match &config.source {
        BatchSource::Manifest(path) => read_manifest(path)?,
        BatchSource::Inputs(inputs) => parts_of_inputs(inputs)?,
    };
    parts
        .iter()
        .map(|part| PartTask::new(part, &config.base, &config.output))
        .collect()
}

/// Runs a batch: reads and checks every part's task, runs this shard's parts
/// ([`run_tasks`]: complete ones skipped), and writes the summary of every part
/// ([`write_summary`]). `stop`, once raised, stops the workers and starts no more.
pub fn run_batch(
    config: &BatchConfig,
    stop: &AtomicBool,
    on_event: &(dyn Fn(BatchEvent<'_>) + Sync),
) -> Result<BatchOutcome, BatchError> {
    let tasks = batch_tasks(config)?;
    let fingerprints: Vec<Fingerprint> = tasks.iter().map(PartTask::fingerprint).collect();
    let (shard_tasks, shard_fingerprints): (Vec<PartTask>, Vec<Fingerprint>) = tasks
        .iter()
        .zip(&fingerprints)
        .enumerate()
        .filter(|(position, _)| config.shard.contains(*position))
        .map(|(_, (task, fingerprint))| (task.clone(), fingerprint.clone()))
        .unzip();
    let records = run_tasks(
        &shard_tasks,
        &shard_fingerprints,
        &config.scheduling,
        stop,
        on_event,
    )?;
    let summary = write_summary(&config.output, &tasks, &fingerprints)?;
    Ok(BatchOutcome { summary, records })
}

/// Reads a worker's task (JSON) from `reader`.
pub fn read_task(reader: impl std::io::Read) -> Result<PartTask, BatchError> {
    serde_json::from_reader(reader).map_err(|error| BatchError::Task(error.to_string()))
}

#[cfg(test)]
mod tests {
    use crate::batch::*;

    #[test]
    fn shards_split_the_manifest_between_them() {
        let shards: Vec<Shard> = ["1/3", "2/3", "3/3"]
            .iter()
            .map(|text| text.parse().expect("a shard"))
            .collect();
        for position in 0..10 {
            let owners = shards
                .iter()
                .filter(|shard| shard.contains(position))
                .count();
            assert_eq!(owners, 1, "position {position}");
        }
        for bad in ["0/3", "4/3", "1", "a/b", "1/0"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
