//! Errors of the export stage. Every variant names the part or file and says what to change.

use std::path::PathBuf;

use super::energy_png::EnergyPngError;
use crate::pattern::PatternError;

/// Why an export could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A part's contours could not be made (see the pattern stage).
    #[error(transparent)]
    Pattern(#[from] PatternError),
    /// The sheet has no positive finite size.
    #[error("sheet {index}: size {width} x {height} is not positive; check --sheet WxH")]
    InvalidSheetSize {
        /// Sheet number.
        index: usize,
        /// Width, in drawing units.
        width: f64,
        /// Height, in drawing units.
        height: f64,
    },
    /// A part on a sheet is in other units than the sheet.
    #[error(
        "part `{part}` on sheet {sheet} is in {part_units} but the sheet in {sheet_units}; convert the part to the sheet's units before placing it"
    )]
    MixedUnits {
        /// Name of the part.
        part: String,
        /// Sheet number.
        sheet: usize,
        /// The part's unit name.
        part_units: &'static str,
        /// The sheet's unit name.
        sheet_units: &'static str,
    },
    /// The preview image size is zero or too large to allocate.
    #[error("preview size of {pixels} pixels is not usable; pass between 16 and 8192 pixels")]
    InvalidPreviewSize {
        /// The requested size of the longer side, in pixels.
        pixels: u32,
    },
    /// The dxf crate refused the drawing.
    #[error(
        "could not encode the DXF: {0}; this is a bug in flatcut, please report it with the input"
    )]
    Dxf(#[from] dxf::DxfError),
    /// The PNG encoder failed.
    #[error("could not encode the PNG preview: {0}; this is a bug in flatcut, please report it")]
    Png(String),
    /// A directory could not be created.
    #[error("{}: cannot create the directory", path.display())]
    CreateDirectory {
        /// The directory.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A JSON report could not be encoded.
    #[error(transparent)]
    Json(serde_json::Error),
    /// A file could not be written.
    #[error("{path}: cannot write: {source}")]
    Write {
        /// The output file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A part's cut file (or a sheet's) could not be drawn.
    #[error("{path}: part '{part}': cannot write its DXF: {source}")]
    Drawing {
        /// The input file the part came from (the sheet's file for a sheet).
        path: PathBuf,
        /// The part's name (the sheet's file stem for a sheet).
        part: String,
        /// Why.
        source: Box<ExportError>,
    },
    /// A part's energy map could not be drawn.
    #[error("{path}: part '{part}': cannot draw its energy map: {source}")]
    EnergyMap {
        /// The input file the part came from.
        path: PathBuf,
        /// The part's name.
        part: String,
        /// Why.
        source: EnergyPngError,
    },
}
