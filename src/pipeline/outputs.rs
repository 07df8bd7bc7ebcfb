//! Writing a run's output folder: every part's files (`<part>.mesh.obj`, `.pattern.obj`,
//! `.pattern.json`, `.dxf`, `.energy.png`), the nested sheets (`sheets/sheet-NNN.dxf` and `.png`)
//! and `report.json`.

use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use rayon::prelude::*;

use crate::error::Error;
use crate::export::DxfOptions;
use crate::export::part_files::{PartFileOptions, PartFiles, write_part_files};
use crate::export::report::{Report, SheetReport, sheet_reports};
use crate::export::sheets::{SHEETS_FOLDER, sheet_drawings, write_sheet_files};
use crate::pattern::PartDrawing;
use crate::progress::Progress;

use super::config::RunConfig;
use super::output_folder::{InterruptHandle, OutputFolder, check_inputs_outside};
use super::report::{part_report, report_options};
use super::run::{NestedLayout, RunOutput};
use super::run::{load_all, run_loaded};

/// Runs the whole pipeline into the output folder `directory`, safely: checks the options and
/// that no input is in the folder under a name a run writes, loads every input, creates the
/// folder and its staging folder (so an unwritable folder is found before the long work) and
/// hands `on_staging` the handle that abandons the run (for a signal handler); then flattens,
/// cuts and nests, writes every file into the staging folder and replaces the previous run's
/// files with them as one set ([`OutputFolder::commit`]). On an error the folder keeps the
/// previous run; an error met after the run was abandoned is [`Error::Interrupted`]. Returns
/// what the run made and its report.
pub fn run_into(
    config: &RunConfig,
    directory: &Path,
    progress: &dyn Progress,
    on_staging: &dyn Fn(InterruptHandle),
) -> Result<(RunOutput, Report), Error> {
    config.validate()?;
    check_inputs_outside(directory, &config.inputs)?;
    let jobs = load_all(config, progress)?;
    let folder = OutputFolder::prepare(directory)?;
    on_staging(folder.interrupt_handle());
    let written = run_loaded(jobs, config, progress).and_then(|output| {
        let report = write_outputs(&output, config, folder.staging(), progress)?;
        Ok((output, report))
    });
    // A signal that abandoned the staging folder makes the writes fail: that is no input's fault.
    match written {
        Err(_) if folder.abandoned() => Err(Error::Interrupted),
        Err(error) => Err(error),
        Ok((output, report)) => {
            folder.commit()?;
            Ok((output, report))
        }
    }
}

/// Writes the output folder of a run into `directory` (created if missing) and returns the
/// report written to `report.json`; `progress` counts the parts written.
pub fn write_outputs(
    output: &RunOutput,
    config: &RunConfig,
    directory: &Path,
    progress: &dyn Progress,
) -> Result<Report, Error> {
    std::fs::create_dir_all(directory).map_err(|source| Error::CreateDirectory {
        path: directory.to_path_buf(),
        source,
    })?;
    let dxf = DxfOptions {
        version: config.dxf_version,
        pattern: config.pattern,
    };
    let file_options = PartFileOptions {
        dxf,
        energy: config.energy_png,
    };
    // Each part's files are made and written on their own, so parts go in parallel: a part cut
    // into hundreds of pieces writes hundreds of sets, each with its energy picture to render.
    progress.start("writing", output.parts.len() as u64);
    let written = AtomicU64::new(0);
    (output.parts.par_iter().zip(&output.patterns)).try_for_each(|(part, pattern_file)| {
        let files = PartFiles {
            source: &part.job.source,
            model: &part.job.model,
            flattened: &part.flattened,
            uncut: part.uncut.as_ref(),
            pattern: &part.pattern,
            pattern_file,
            cuts: part.cuts.len(),
            spring_constant: config.options.flatten.spring_constant,
        };
        write_part_files(directory, &files, &file_options)?;
        progress.advance(written.fetch_add(1, Ordering::Relaxed) + 1);
        Ok::<(), Error>(())
    })?;
    progress.finish();
    let sheets = match &output.nesting {
        Some(nested) => {
            let drawings: Vec<PartDrawing> = output
                .nested_parts
                .iter()
                .map(|&part| output.patterns[part].sheet_drawing())
                .collect();
            write_sheets(directory, Path::new(SHEETS_FOLDER), &drawings, nested, &dxf)?
        }
        None => Vec::new(),
    };
    let parts = output
        .parts
        .iter()
        .map(|part| part_report(part, config))
        .collect();
    let mut report = Report::new(report_options(config), parts);
    report.sheets = sheets;
    report.write(directory)?;
    Ok(report)
}

/// Writes the sheets of a nested layout of `drawings` (item `i` is `drawings[i]`) into
/// `directory/folder` and returns their report entries (file names relative to `directory`).
pub(super) fn write_sheets(
    directory: &Path,
    folder: &Path,
    drawings: &[PartDrawing],
    nested: &NestedLayout,
    dxf: &DxfOptions,
) -> Result<Vec<SheetReport>, Error> {
    let sheets = sheet_drawings(drawings, &nested.layout);
    let files = write_sheet_files(directory, folder, &sheets, dxf)?;
    let names: Vec<String> = nested.items.iter().map(|item| item.name.clone()).collect();
    Ok(sheet_reports(&nested.layout, &names, &files))
}
