//! `nest.json`, the result of `flatcut nest`: for benchmark instances ([`NestReport`]) the
//! instances, the options, every item, and the checked layout with its density; for pattern files
//! ([`PatternNestReport`]) the inputs, the options, and per group of material and thickness its
//! parts and sheets.

use std::path::Path;

use serde::Serialize;

use super::atomic::write_atomically;
use super::dxf_options::DxfVersion;
use super::errors::ExportError;
use super::report::{NestingReport, SheetReport};
use crate::nest::{NestItem, NestLayout, Rotations, Stock, StopReason};
use crate::pattern::PatternOptions;

/// Version of the `nest.json` layout; raised when a key changes meaning.
pub const NEST_SCHEMA_VERSION: u32 = 1;

/// What `nest.json` holds.
#[derive(Debug, Serialize)]
pub struct NestReport<'a> {
    schema_version: u32,
    flatcut_version: &'static str,
    instances: Vec<String>,
    options: NestReportOptions<'a>,
    parts: Vec<NestReportPart<'a>>,
    verified: bool,
    #[serde(flatten)]
    layout: &'a NestLayout,
    density: f64,
    /// The sheets' DXF files, relative to the output folder, in sheet order (each with a PNG
    /// preview of the same name).
    sheet_files: Vec<String>,
}

/// The options recorded in `nest.json`.
#[derive(Debug, Serialize)]
pub struct NestReportOptions<'a> {
    /// The stock nested on.
    pub stock: Stock,
    /// Gap between parts and to the stock edge, mm.
    pub gap: f64,
    /// Search budget, seconds.
    pub time_limit_seconds: f64,
    /// Seed of the search.
    pub seed: u64,
    /// Work budget in collision queries, when given.
    pub work_limit: Option<u64>,
    /// Rotations overriding the instances', when given.
    pub rotations: Option<&'a Rotations>,
    /// Whether items could be mirrored.
    pub mirror: bool,
    /// Whether items could go inside holes.
    pub in_holes: bool,
}

#[derive(Debug, Serialize)]
struct NestReportPart<'a> {
    name: &'a str,
    quantity: u32,
    area: f64,
}

impl<'a> NestReport<'a> {
    /// The report of a checked layout of `items` from the instances `names`, whose sheets were
    /// written to `sheet_files` (relative to the output folder).
    pub fn new(
        names: &[String],
        options: NestReportOptions<'a>,
        items: &'a [NestItem],
        layout: &'a NestLayout,
        sheet_files: &[std::path::PathBuf],
    ) -> Self {
        Self {
            schema_version: NEST_SCHEMA_VERSION,
            flatcut_version: env!("CARGO_PKG_VERSION"),
            instances: names.to_vec(),
            options,
            parts: items
                .iter()
                .map(|item| NestReportPart {
                    name: &item.name,
                    quantity: item.quantity,
                    area: item.area(),
                })
                .collect(),
            verified: true,
            layout,
            density: layout.utilisation,
            sheet_files: (sheet_files.iter())
                .map(|file| file.to_string_lossy().replace('\\', "/"))
                .collect(),
        }
    }

    /// Writes `directory/nest.json` (the directory is created if missing) and returns its text.
    pub fn write(&self, directory: &Path) -> Result<String, ExportError> {
        write_nest_json(self, directory)
    }
}

/// What `nest.json` holds for pattern files nested together (`flatcut nest PATTERNS...`).
#[derive(Debug, Serialize)]
pub struct PatternNestReport {
    schema_version: u32,
    flatcut_version: &'static str,
    inputs: Vec<String>,
    options: PatternNestReportOptions,
    groups: Vec<NestGroupReport>,
}

/// The options recorded in `nest.json` for pattern files.
#[derive(Debug, Serialize)]
pub struct PatternNestReportOptions {
    /// Stock, gap, budgets, seed, rotations, holes and mirroring, as `report.json` records them.
    #[serde(flatten)]
    pub nesting: NestingReport,
    /// Chord tolerance and seam allowance of every pattern's cut contours.
    pub pattern: PatternOptions,
    /// DXF version of the sheet files.
    pub dxf_version: DxfVersion,
    /// Whether patterns of rejected parts were nested.
    pub include_rejected: bool,
}

/// One group of patterns of one material and thickness, nested on its own stock.
#[derive(Debug, Serialize)]
pub struct NestGroupReport {
    /// The group's material (`None`: no material given).
    pub material: Option<String>,
    /// The group's thickness, mm (`None`: no thickness given).
    pub thickness_mm: Option<f64>,
    /// The folder its sheet files are in, relative to the output folder.
    pub folder: String,
    /// Its patterns, in input order (nesting item `i` is part `i`).
    pub parts: Vec<NestGroupPart>,
    /// Its sheets, as `report.json` lists a run's.
    pub sheets: Vec<SheetReport>,
    /// Net part area over the total area of its sheets (on a roll: width × used length).
    pub utilisation: f64,
    /// Length used on its last sheet or on the roll, mm.
    pub used_length: f64,
    /// Collision queries the search spent.
    pub work: u64,
    /// Layouts the search evaluated.
    pub evaluations: u64,
    /// Why the search stopped.
    pub stop_reason: StopReason,
}

/// One pattern of a group.
#[derive(Debug, Serialize)]
pub struct NestGroupPart {
    /// The part's name.
    pub name: String,
    /// The pattern file it was read from.
    pub source: String,
    /// Copies placed.
    pub quantity: u32,
    /// Area of one copy's nested contour, mm².
    pub area: f64,
    /// Whether the part was rejected (over tolerance).
    pub rejected: bool,
}

impl PatternNestReport {
    /// The report of the pattern files `inputs` nested in `groups` with `options`.
    pub fn new(
        inputs: Vec<String>,
        options: PatternNestReportOptions,
        groups: Vec<NestGroupReport>,
    ) -> Self {
        Self {
            schema_version: NEST_SCHEMA_VERSION,
            flatcut_version: env!("CARGO_PKG_VERSION"),
            inputs,
            options,
            groups,
        }
    }

    /// Writes `directory/nest.json` (the directory is created if missing) and returns its text.
    pub fn write(&self, directory: &Path) -> Result<String, ExportError> {
        write_nest_json(self, directory)
    }
}

/// Writes `report` as pretty JSON with a final newline to `directory/nest.json` (the directory is
/// created if missing) and returns the text.
fn write_nest_json(report: &impl Serialize, directory: &Path) -> Result<String, ExportError> {
    let json = serde_json::to_string_pretty(report).map_err(ExportError::Json)? + "\n";
    std::fs::create_dir_all(directory).map_err(|source| ExportError::CreateDirectory {
        path: directory.to_path_buf(),
        source,
    })?;
    let path = directory.join("nest.json");
    write_atomically(&path, json.as_bytes())
        .map_err(|source| ExportError::Write { path, source })?;
    Ok(json)
}
