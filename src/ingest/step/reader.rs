//! Reading a STEP file into the CAD model's B-rep: statements parsed, units found, the text
//! rewritten where truck-stepio would misread it, shells (or loose surfaces) converted.

use std::panic::catch_unwind;
use std::path::Path;

use truck_stepio::r#in::Table;

use super::convert::{convert_shells, loose_surfaces};
use super::entities::unsupported_entities;
use super::rewrite::{prefer_3d_curves, rewritten_for_truck};
use super::statements::Statements;
use super::text::exchange_text;
use super::units::file_units;
use crate::cad::Brep;
use crate::ingest::errors::IngestError;

/// Reads a STEP file's shells, or its loose surfaces when it has none (see the module
/// documentation).
pub fn read_step(path: &Path, bytes: &[u8]) -> Result<Brep, IngestError> {
    let error = |message: String| IngestError::Step {
        path: path.to_path_buf(),
        message,
    };
    let text = &exchange_text(bytes);
    let statements = Statements::parse(text);
    let default_units = file_units(&statements).map_err(error)?;
    let mut brep = Brep {
        name: path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("part")
            .to_string(),
        shells: Vec::new(),
        loose: Vec::new(),
        unsupported: unsupported_entities(&statements)
            .iter()
            .map(|(id, name)| format!("{name} (#{id})"))
            .collect(),
    };
    let text = &prefer_3d_curves(text);
    let text = &rewritten_for_truck(text, &statements, default_units).map_err(error)?;
    let table = catch_unwind(|| Table::from_step(text))
        .ok()
        .flatten()
        .ok_or_else(|| error("not a valid STEP exchange structure (ISO 10303-21); export it again from the CAD system".into()))?;
    let mut shell_ids: Vec<u64> = table.shell.keys().copied().collect();
    shell_ids.sort_unstable();
    if shell_ids.is_empty() {
        brep.loose = loose_surfaces(&table, &statements, default_units)
            .map_err(|message| error(format!("{message}{}", brep.unsupported_note())))?;
        if brep.loose.is_empty() {
            return Err(error(format!(
                "the file holds no shell, face or B-spline surface to read{}",
                brep.unsupported_note()
            )));
        }
    } else {
        brep.shells = convert_shells(&table, &shell_ids, &statements, default_units)
            .map_err(|message| error(format!("{message}{}", brep.unsupported_note())))?;
    }
    Ok(brep)
}
