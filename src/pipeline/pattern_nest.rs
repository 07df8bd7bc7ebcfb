//! The fan-in: pattern files (`<part>.pattern.json`, written by every run) nested together without
//! flattening again, for `flatcut nest PATTERNS...`. A batch flattens its parts in separate
//! processes or on separate machines, then nests all their patterns here: grouped by material
//! and thickness, each group on its own stock, through the same code as `flatcut run`
//! ([`nest_checked`]), so one group gives the layout and sheet files a run of the same parts
//! (in the same order, with the same options) gives.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::error::Error;
use crate::export::DxfOptions;
use crate::export::DxfVersion;
use crate::export::nest_report::{
    NestGroupPart, NestGroupReport, PatternNestReport, PatternNestReportOptions,
};
use crate::export::report::SheetReport;
use crate::export::sheets::SHEETS_FOLDER;
use crate::nest::Stock;
use crate::pattern::{PATTERN_FILE_ENDING, PartDrawing, PatternFile, PatternOptions};
use crate::progress::Progress;

use super::config::NestingConfig;
use super::output_folder::{InterruptHandle, OutputFolder, check_inputs_outside};
use super::outputs::write_sheets;
use super::report::nesting_report;
use super::run::{NestedLayout, nest_checked};

/// A fan-in nesting job. `Default` is the only source of defaults: the nesting options are a
/// run's ([`NestingConfig::default`]), so a fan-in with defaults nests like a run with defaults.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PatternNestConfig {
    /// Pattern files and folders holding them (a run's output folder: every `*.pattern.json`
    /// directly inside it, in file-name order), nested in this order.
    pub inputs: Vec<PathBuf>,
    /// The stock every group is nested on; required (`None` is refused).
    pub stock: Option<Stock>,
    /// How the patterns are nested.
    pub nesting: NestingConfig,
    /// DXF version of the sheet files.
    pub dxf_version: DxfVersion,
    /// Whether patterns of rejected parts (over tolerance) are nested; default `false`: refused.
    pub include_rejected: bool,
}

/// What `flatcut nest` was given: pattern inputs or benchmark instances.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NestInputKind {
    /// Pattern files and folders of them ([`nest_patterns`]).
    Patterns,
    /// ESICUP benchmark instances ([`super::nest_benchmark`]).
    Instances,
}

/// A pattern file read, with where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct SourcedPattern {
    /// The pattern file.
    pub path: PathBuf,
    /// What it holds.
    pub pattern: PatternFile,
}

/// Patterns of one material and thickness, nested on their own stock.
#[derive(Debug, Clone)]
pub struct NestedGroup {
    /// The material (`None`: none given).
    pub material: Option<String>,
    /// The thickness, mm (`None`: none given).
    pub thickness_mm: Option<f64>,
    /// Where its sheet files go, relative to the output folder: `sheets` when there is one
    /// group, `sheets/<material>-<thickness>mm` when there are several.
    pub folder: PathBuf,
    /// Its patterns in input order (nesting item `i` is pattern `i`).
    pub patterns: Vec<SourcedPattern>,
    /// Its nesting items and their layout, checked independently.
    pub nested: NestedLayout,
}

/// What a fan-in made.
#[derive(Debug, Clone)]
pub struct PatternNestOutput {
    /// The pattern files read, in input order.
    pub inputs: Vec<PathBuf>,
    /// The stock every group was nested on.
    pub stock: Stock,
    /// Every group, in order of its first pattern.
    pub groups: Vec<NestedGroup>,
    /// The pattern options every pattern was made with.
    pub pattern_options: PatternOptions,
}

/// Whether `path` is a pattern input: a folder, or a file named `*.pattern.json`.
fn is_pattern_input(path: &Path) -> bool {
    path.is_dir()
        || path
            .file_name()
            .is_some_and(|name| name.to_string_lossy().ends_with(PATTERN_FILE_ENDING))
}

/// The kind of `inputs`: all pattern inputs (files named `*.pattern.json` and folders) or all
/// benchmark instances; refuses a mix, naming one input of each kind.
pub fn nest_input_kind(inputs: &[PathBuf]) -> Result<NestInputKind, Error> {
    let (patterns, instances): (Vec<&PathBuf>, Vec<&PathBuf>) =
        inputs.iter().partition(|input| is_pattern_input(input));
    match (patterns.first(), instances.first()) {
        (Some(pattern), Some(instance)) => Err(Error::MixedNestInputs {
            pattern: (*pattern).clone(),
            instance: (*instance).clone(),
        }),
        (Some(_), None) => Ok(NestInputKind::Patterns),
        _ => Ok(NestInputKind::Instances),
    }
}

/// The pattern files of `inputs` in order: a file as given, a folder as every `*.pattern.json`
/// directly inside it, in file-name order. A folder without one (the folder of a batch part that
/// was refused) is skipped with a warning through `progress`; none at all is refused.
pub fn pattern_files(inputs: &[PathBuf], progress: &dyn Progress) -> Result<Vec<PathBuf>, Error> {
    let mut files = Vec::new();
    let mut empty = Vec::new();
    for input in inputs {
        if input.is_dir() {
            let found = pattern_files_in(input)?;
            if found.is_empty() {
                empty.push(input);
            }
            files.extend(found);
        } else {
            files.push(input.clone());
        }
    }
    if let (true, Some(folder)) = (files.is_empty(), empty.first()) {
        return Err(Error::NoPatternFiles {
            folder: folder.to_path_buf(),
        });
    }
    for folder in empty {
        progress.warn(&format!(
            "{}: no `*.pattern.json` file in this folder (a part that was refused?): skipped",
            folder.display()
        ));
    }
    Ok(files)
}

/// Every `*.pattern.json` file directly inside `folder`, sorted by file name (none, maybe).
fn pattern_files_in(folder: &Path) -> Result<Vec<PathBuf>, Error> {
    let unreadable = |source| Error::ReadPatterns {
        path: folder.to_path_buf(),
        source,
    };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(folder).map_err(unreadable)? {
        let entry = entry.map_err(unreadable)?;
        let is_file = entry.file_type().map_err(unreadable)?.is_file();
        if is_file
            && entry
                .file_name()
                .to_string_lossy()
                .ends_with(PATTERN_FILE_ENDING)
        {
            files.push(entry.path());
        }
    }
    files.sort_by(|a, b| a.file_name().cmp(&b.file_name()));
    Ok(files)
}

/// Reads one pattern file.
pub fn read_pattern_file(path: &Path) -> Result<PatternFile, Error> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::ReadPatterns {
        path: path.to_path_buf(),
        source,
    })?;
    PatternFile::from_json(&text).map_err(|source| Error::PatternFile {
        path: path.to_path_buf(),
        source,
    })
}

/// Reads every pattern file and checks them together: no two parts of one name, every pattern
/// made with the same pattern options, and no rejected part unless `include_rejected`.
pub fn read_patterns(
    files: &[PathBuf],
    include_rejected: bool,
) -> Result<Vec<SourcedPattern>, Error> {
    let patterns = files
        .iter()
        .map(|path| {
            Ok(SourcedPattern {
                path: path.clone(),
                pattern: read_pattern_file(path)?,
            })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    check_distinct_names(&patterns)?;
    check_same_options(&patterns)?;
    if !include_rejected {
        check_none_rejected(&patterns)?;
    }
    Ok(patterns)
}

/// Refuses two patterns of parts of one name, naming both files.
fn check_distinct_names(patterns: &[SourcedPattern]) -> Result<(), Error> {
    for (index, sourced) in patterns.iter().enumerate() {
        let name = &sourced.pattern.drawing.name;
        if let Some(earlier) = patterns[..index]
            .iter()
            .find(|other| other.pattern.drawing.name == *name)
        {
            return Err(Error::DuplicatePattern {
                path: sourced.path.clone(),
                name: name.clone(),
                earlier: earlier.path.clone(),
            });
        }
    }
    Ok(())
}

/// Refuses patterns made with different pattern options: the sheet drawings apply one set.
fn check_same_options(patterns: &[SourcedPattern]) -> Result<(), Error> {
    let Some(first) = patterns.first() else {
        return Ok(());
    };
    match patterns
        .iter()
        .find(|other| other.pattern.options != first.pattern.options)
    {
        Some(other) => Err(Error::PatternOptionsDiffer {
            path: other.path.clone(),
            earlier: first.path.clone(),
        }),
        None => Ok(()),
    }
}

/// Refuses the patterns of rejected parts, naming every one.
fn check_none_rejected(patterns: &[SourcedPattern]) -> Result<(), Error> {
    let rejected: Vec<(String, PathBuf)> = patterns
        .iter()
        .filter(|sourced| sourced.pattern.rejected)
        .map(|sourced| (sourced.pattern.drawing.name.clone(), sourced.path.clone()))
        .collect();
    if rejected.is_empty() {
        Ok(())
    } else {
        Err(Error::RejectedPatterns { parts: rejected })
    }
}

/// Checks the options before any input is read: stock given, nesting options in range.
fn validate(config: &PatternNestConfig) -> Result<Stock, Error> {
    let stock = config.stock.ok_or(Error::NoStock)?;
    config.nesting.validate(Some(stock))?;
    Ok(stock)
}

/// Reads, checks, groups and nests the pattern files of `config` (see [`nest_loaded`]).
pub fn nest_patterns(
    config: &PatternNestConfig,
    progress: &dyn Progress,
) -> Result<PatternNestOutput, Error> {
    let stock = validate(config)?;
    let files = pattern_files(&config.inputs, progress)?;
    let patterns = read_patterns(&files, config.include_rejected)?;
    nest_loaded(patterns, stock, &config.nesting, progress)
}

/// Groups `patterns` (read and checked by [`read_patterns`]) by material and thickness, in order
/// of first appearance, and nests each group on `stock`, checking every layout independently.
pub fn nest_loaded(
    patterns: Vec<SourcedPattern>,
    stock: Stock,
    nesting: &NestingConfig,
    progress: &dyn Progress,
) -> Result<PatternNestOutput, Error> {
    let inputs = patterns
        .iter()
        .map(|sourced| sourced.path.clone())
        .collect();
    let pattern_options = patterns
        .first()
        .map(|sourced| sourced.pattern.options)
        .unwrap_or_default();
    let groups = group_by_stock(patterns);
    let folders = group_folders(&groups);
    let groups = groups
        .into_iter()
        .zip(folders)
        .map(|(patterns, folder)| {
            let files = patterns.iter().map(|sourced| &sourced.pattern);
            let nested = nest_checked(files, stock, nesting, progress)?;
            let first = &patterns[0].pattern;
            Ok(NestedGroup {
                material: first.drawing.material.clone(),
                thickness_mm: first.thickness_mm,
                folder,
                patterns,
                nested,
            })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    Ok(PatternNestOutput {
        inputs,
        stock,
        groups,
        pattern_options,
    })
}

/// `patterns` split by (material, thickness), groups in order of their first pattern, patterns
/// in input order inside each.
fn group_by_stock(patterns: Vec<SourcedPattern>) -> Vec<Vec<SourcedPattern>> {
    let mut groups: Vec<Vec<SourcedPattern>> = Vec::new();
    for sourced in patterns {
        let same_stock = |group: &&mut Vec<SourcedPattern>| {
            let first = &group[0].pattern;
            first.drawing.material == sourced.pattern.drawing.material
                && first.thickness_mm == sourced.pattern.thickness_mm
        };
        match groups.iter_mut().find(same_stock) {
            Some(group) => group.push(sourced),
            None => groups.push(vec![sourced]),
        }
    }
    groups
}

/// The folder of each group's sheets, relative to the output folder: [`SHEETS_FOLDER`] for a
/// single group (as a run writes them), otherwise a folder inside it named after the group's
/// material and thickness ([`group_folder_name`]), made distinct with `-2`, `-3`, ... when two
/// names sanitise alike.
fn group_folders(groups: &[Vec<SourcedPattern>]) -> Vec<PathBuf> {
    let sheets = Path::new(SHEETS_FOLDER);
    if groups.len() == 1 {
        return vec![sheets.to_path_buf()];
    }
    let mut taken = BTreeSet::new();
    groups
        .iter()
        .map(|group| {
            let first = &group[0].pattern;
            let name = group_folder_name(first.drawing.material.as_deref(), first.thickness_mm);
            let distinct = (1..)
                .map(|index| match index {
                    1 => name.clone(),
                    _ => format!("{name}-{index}"),
                })
                .find(|candidate| !taken.contains(candidate))
                .unwrap_or(name);
            taken.insert(distinct.clone());
            sheets.join(distinct)
        })
        .collect()
}

/// A folder name for the stock of `material` and `thickness_mm`: `steel-1.5mm`, `cotton`,
/// `no-material-2mm`, with every character but ASCII letters, digits, `-`, `_` and `.` replaced
/// by `_`, and no leading dot.
pub fn group_folder_name(material: Option<&str>, thickness_mm: Option<f64>) -> String {
    let material = material.unwrap_or("no-material");
    let name = match thickness_mm {
        Some(thickness) => format!("{material}-{thickness}mm"),
        None => material.to_string(),
    };
    let sanitised: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    let trimmed = sanitised.trim_start_matches('.');
    if trimmed.is_empty() {
        "unnamed".to_string()
    } else {
        trimmed.to_string()
    }
}

/// Writes the sheets of every group (DXF and PNG, as a run draws them) and `nest.json` into
/// `directory`, and returns the text of `nest.json`.
pub fn write_pattern_nest(
    output: &PatternNestOutput,
    config: &PatternNestConfig,
    directory: &Path,
) -> Result<String, Error> {
    let dxf = DxfOptions {
        version: config.dxf_version,
        pattern: output.pattern_options,
    };
    let mut groups = Vec::with_capacity(output.groups.len());
    for group in &output.groups {
        let drawings: Vec<PartDrawing> = group
            .patterns
            .iter()
            .map(|sourced| sourced.pattern.sheet_drawing())
            .collect();
        let sheets = write_sheets(directory, &group.folder, &drawings, &group.nested, &dxf)?;
        groups.push(group_report(group, sheets));
    }
    let inputs = output
        .inputs
        .iter()
        .map(|path| path.display().to_string())
        .collect();
    let options = PatternNestReportOptions {
        nesting: nesting_report(output.stock, &config.nesting),
        pattern: output.pattern_options,
        dxf_version: config.dxf_version,
        include_rejected: config.include_rejected,
    };
    Ok(PatternNestReport::new(inputs, options, groups).write(directory)?)
}

/// The `nest.json` entry of a nested group whose sheets are `sheets`.
fn group_report(group: &NestedGroup, sheets: Vec<SheetReport>) -> NestGroupReport {
    let layout = &group.nested.layout;
    NestGroupReport {
        material: group.material.clone(),
        thickness_mm: group.thickness_mm,
        folder: group.folder.to_string_lossy().replace('\\', "/"),
        parts: group
            .patterns
            .iter()
            .zip(&group.nested.items)
            .map(|(sourced, item)| NestGroupPart {
                name: item.name.clone(),
                source: sourced.path.display().to_string(),
                quantity: item.quantity,
                area: item.area(),
                rejected: sourced.pattern.rejected,
            })
            .collect(),
        sheets,
        utilisation: layout.utilisation,
        used_length: layout.used_length,
        work: layout.work,
        evaluations: layout.evaluations,
        stop_reason: layout.stop_reason,
    }
}

/// Nests pattern files into the output folder `directory`, safely, as [`super::run_into`] runs:
/// checks the options and that no pattern file lies in the folder, reads and checks every
/// pattern, creates the folder and its staging folder (handing `on_staging` the handle that
/// abandons the job), nests, writes the sheets and `nest.json` into the staging folder and
/// replaces the folder's previous files with them as one set. Returns what was nested and the
/// text of `nest.json`.
pub fn nest_patterns_into(
    config: &PatternNestConfig,
    directory: &Path,
    progress: &dyn Progress,
    on_staging: &dyn Fn(InterruptHandle),
) -> Result<(PatternNestOutput, String), Error> {
    let stock = validate(config)?;
    let files = pattern_files(&config.inputs, progress)?;
    check_inputs_outside(directory, &files)?;
    let patterns = read_patterns(&files, config.include_rejected)?;
    let folder = OutputFolder::prepare(directory)?;
    on_staging(folder.interrupt_handle());
    let output = nest_loaded(patterns, stock, &config.nesting, progress)?;
    let json = write_pattern_nest(&output, config, folder.staging())?;
    folder.commit()?;
    Ok((output, json))
}

#[cfg(test)]
mod tests {
    use crate::pipeline::pattern_nest::*;

    #[test]
    fn group_folders_are_safe_file_names() {
        assert_eq!(group_folder_name(Some("steel"), Some(1.5)), "steel-1.5mm");
        assert_eq!(group_folder_name(None, Some(2.0)), "no-material-2mm");
        assert_eq!(group_folder_name(Some("cotton"), None), "cotton");
        assert_eq!(group_folder_name(Some("../etc/x y"), None), "_etc_x_y");
        assert_eq!(group_folder_name(Some(".."), None), "unnamed");
    }
}
