//! `nest.json`, the result of `flatcut nest`: the instances, the options, every item, and the
//! checked layout with its density.

use std::path::Path;

use serde::Serialize;

use super::atomic::write_atomically;
use super::errors::ExportError;
use crate::nest::{NestItem, NestLayout, Rotations, Stock};

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
    /// The report of a checked layout of `items` from the instances `names`.
    pub fn new(
        names: &[String],
        options: NestReportOptions<'a>,
        items: &'a [NestItem],
        layout: &'a NestLayout,
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
        }
    }

    /// Pretty JSON with a final newline.
    pub fn to_json(&self) -> Result<String, ExportError> {
        Ok(serde_json::to_string_pretty(self).map_err(ExportError::Json)? + "\n")
    }

    /// Writes `directory/nest.json` (the directory is created if missing) and returns its text.
    pub fn write(&self, directory: &Path) -> Result<String, ExportError> {
        let json = self.to_json()?;
        std::fs::create_dir_all(directory).map_err(|source| ExportError::CreateDirectory {
            path: directory.to_path_buf(),
            source,
        })?;
        let path = directory.join("nest.json");
        write_atomically(&path, json.as_bytes())
            .map_err(|source| ExportError::Write { path, source })?;
        Ok(json)
    }
}
