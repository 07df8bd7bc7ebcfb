//! One part of a batch as a worker runs it: a [`PartTask`] (the part, its folder and its
//! options, the batch's with its manifest line over them), handed to a worker process as JSON,
//! and [`run_part_task`], what the worker does with it: the whole pipeline into the part's
//! folder, then the part's [`PartRecord`].

use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::error::Error;
use crate::export::DxfVersion;
use crate::export::energy_png::EnergyPngOptions;
use crate::ingest::cut_sidecar_path;
use crate::pattern::PatternOptions;
use crate::pipeline::{
    InterruptHandle, RunConfig, RunOptions, complete_run_present, remove_previous_run, run_into,
};
use crate::progress::Progress;

use super::errors::BatchError;
use super::manifest::BatchPart;
use super::record::{
    Fingerprint, PART_LOCK_FILE, PartRecord, PartStatus, PatternFigures, lock_exclusive,
};

/// Folder of the parts' folders inside a batch's output folder.
pub const PARTS_FOLDER: &str = "parts";

/// One part of a batch, ready for a worker.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PartTask {
    /// The part's name.
    pub name: String,
    /// The input as the manifest or command line wrote it (what records and summaries show).
    pub input: String,
    /// The input file to read.
    pub path: PathBuf,
    /// The part's output folder (`OUT/parts/<name>`).
    pub folder: PathBuf,
    /// Loading, flattening and cutting options, with the part's quantity, material, thickness.
    pub options: RunOptions,
    /// Chord tolerance and seam allowance of the cut contours.
    pub pattern: PatternOptions,
    /// DXF version of the cut files.
    pub dxf_version: DxfVersion,
    /// Size of the energy pictures.
    pub energy_png: EnergyPngOptions,
}

impl PartTask {
    /// The task of `part` in the batch writing to `output`: `base`'s options with the part's
    /// manifest line over them, checked.
    pub fn new(part: &BatchPart, base: &RunConfig, output: &Path) -> Result<Self, BatchError> {
        let entry = &part.entry;
        let mut options = base.options.clone();
        let mut pattern = base.pattern;
        if let Some(units) = entry.units {
            options.units = units;
        }
        if let Some(tolerance) = entry.tolerance {
            options.flatten.tolerance = tolerance;
        }
        if let Some(max_cuts) = entry.max_cuts {
            options.cut.max_cuts = Some(max_cuts);
        }
        if let Some(allowance) = entry.seam_allowance {
            pattern.seam_allowance = Some(allowance);
        }
        let overrides = &mut options.overrides;
        overrides.name = Some(part.name.clone());
        overrides.quantity = entry.quantity.or(overrides.quantity);
        overrides.material = entry.material.clone().or(overrides.material.take());
        overrides.thickness_mm = entry.thickness.or(overrides.thickness_mm);
        let task = Self {
            name: part.name.clone(),
            input: entry.input.clone(),
            path: part.path.clone(),
            folder: output.join(PARTS_FOLDER).join(&part.name),
            options,
            pattern,
            dxf_version: base.dxf_version,
            energy_png: base.energy_png,
        };
        task.config()
            .validate()
            .map_err(|source| BatchError::Options {
                name: part.name.clone(),
                source: Box::new(source),
            })?;
        Ok(task)
    }

    /// The run of this part: its input, its options, no stock, no timings (a part's outputs are
    /// the same bytes whenever and wherever it runs).
    pub fn config(&self) -> RunConfig {
        RunConfig {
            inputs: vec![self.path.clone()],
            options: self.options.clone(),
            pattern: self.pattern,
            dxf_version: self.dxf_version,
            energy_png: self.energy_png,
            timings: false,
            ..RunConfig::default()
        }
    }

    /// The fingerprint of the work: the input's content (with its cut sidecar) and the name,
    /// options and flatcut version. An unreadable input gives a fingerprint of its error, so
    /// that the worker reports the error itself.
    pub fn fingerprint(&self) -> Fingerprint {
        let mut input = Sha256::new();
        match std::fs::read(&self.path) {
            Ok(bytes) => input.update(&bytes),
            Err(error) => input.update(format!("unreadable: {error}").as_bytes()),
        }
        if let Ok(sidecar) = std::fs::read(cut_sidecar_path(&self.path)) {
            input.update(b"\0cut sidecar\0");
            input.update(&sidecar);
        }
        let work = serde_json::json!({
            "flatcut_version": env!("CARGO_PKG_VERSION"),
            "name": self.name,
            "options": self.options,
            "pattern": self.pattern,
            "dxf_version": self.dxf_version,
            "energy_png": self.energy_png,
        });
        Fingerprint {
            input_sha256: hex(&input.finalize()),
            options_sha256: hex(&Sha256::digest(work.to_string().as_bytes())),
        }
    }

    /// The part's record, when it is final, matches `fingerprint` and its outputs are all in
    /// the folder: the part need not run again.
    pub fn completed_record(&self, fingerprint: &Fingerprint) -> Option<PartRecord> {
        let record = PartRecord::read(&self.folder)?;
        let outputs_present = match record.status {
            PartStatus::Ok | PartStatus::OverTolerance => complete_run_present(&self.folder),
            _ => true,
        };
        (record.status.is_final() && &record.fingerprint == fingerprint && outputs_present)
            .then_some(record)
    }

    /// A record of this part with no patterns: refused, timed out or failed, for `reason`.
    pub fn record_without_outputs(
        &self,
        fingerprint: Fingerprint,
        status: PartStatus,
        reason: String,
    ) -> PartRecord {
        PartRecord {
            name: self.name.clone(),
            input: self.input.clone(),
            status,
            reason: Some(reason),
            fingerprint,
            patterns: Vec::new(),
            warnings: Vec::new(),
        }
    }
}

/// Lower-case hex of `bytes`.
fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|byte| format!("{byte:02x}")).collect()
}

/// Warnings collected for a part's record.
#[derive(Debug, Default)]
struct WarningCollector {
    warnings: Mutex<Vec<String>>,
}

impl Progress for WarningCollector {
    fn start(&self, _stage: &str, _total: u64) {}
    fn advance(&self, _done: u64) {}
    fn finish(&self) {}
    fn warn(&self, message: &str) {
        self.warnings
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .push(message.to_string());
    }
}

/// Runs a part (what a worker process does): holds the lock of the part's folder, removes its
/// old record, runs the whole pipeline into the folder ([`run_into`], handing `on_staging` the
/// handle that abandons it), and writes and returns the part's record: ok or over tolerance
/// with its patterns' figures, or refused with the reason (the previous run's files are then
/// removed, so that no stale outputs look current). An interrupted part writes no record.
pub fn run_part_task(
    task: &PartTask,
    on_staging: &dyn Fn(InterruptHandle),
) -> Result<PartRecord, BatchError> {
    let write_error = |source| BatchError::Write {
        path: task.folder.clone(),
        source,
    };
    std::fs::create_dir_all(&task.folder).map_err(write_error)?;
    let _lock = lock_exclusive(&task.folder.join(PART_LOCK_FILE))?;
    PartRecord::remove(&task.folder)?;
    let fingerprint = task.fingerprint();
    let collector = WarningCollector::default();
    let record = match run_into(&task.config(), &task.folder, &collector, on_staging) {
        Ok((_, report)) => {
            let patterns: Vec<PatternFigures> =
                report.parts.iter().map(PatternFigures::of_report).collect();
            let rejected = patterns.iter().any(|pattern| !pattern.rejected.is_empty());
            PartRecord {
                name: task.name.clone(),
                input: task.input.clone(),
                status: if rejected {
                    PartStatus::OverTolerance
                } else {
                    PartStatus::Ok
                },
                reason: None,
                fingerprint,
                patterns,
                warnings: Vec::new(),
            }
        }
        Err(Error::Interrupted) => return Err(BatchError::Interrupted),
        Err(error) => {
            remove_previous_run(&task.folder).map_err(write_error)?;
            task.record_without_outputs(fingerprint, PartStatus::Refused, error_chain(&error))
        }
    };
    let record = PartRecord {
        warnings: collector
            .warnings
            .into_inner()
            .unwrap_or_else(PoisonError::into_inner),
        ..record
    };
    record.write(&task.folder)?;
    Ok(record)
}

/// An error and its causes, joined by `: `, leaving out a cause the message already holds.
pub fn error_chain(error: &dyn std::error::Error) -> String {
    let mut message = error.to_string();
    let mut cause = error.source();
    while let Some(source) = cause {
        let text = source.to_string();
        if !message.contains(&text) {
            message.push_str(": ");
            message.push_str(&text);
        }
        cause = source.source();
    }
    message
}
