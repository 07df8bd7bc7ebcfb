//! Errors of the export stage. Every variant names the part or file and says what to change.

/// Why an export could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A coordinate is NaN or infinite.
    #[error(
        "part `{part}`: the {contour} has a non-finite coordinate (NaN or infinity); the flat pattern is broken upstream, re-run flattening"
    )]
    NonFiniteCoordinate {
        /// Name of the part.
        part: String,
        /// Which contour ("outer contour", "hole 2", "fold line 1", ...).
        contour: String,
    },
    /// A contour collapsed: a closed one has fewer than three distinct points or no area, an open
    /// one fewer than two distinct points.
    #[error(
        "part `{part}`: the {contour} is degenerate (too few distinct points or no area); remove it or fix the pattern"
    )]
    DegenerateContour {
        /// Name of the part.
        part: String,
        /// Which contour ("outer contour", "hole 2", "fold line 1", ...).
        contour: String,
    },
    /// The chord tolerance is not a positive finite length.
    #[error("chord tolerance {value} mm is not a positive length; pass e.g. --chord 0.01")]
    InvalidChordTolerance {
        /// The rejected value, in mm.
        value: f64,
    },
    /// The seam allowance is not a positive finite length.
    #[error("seam allowance {value} mm is not a positive length; pass e.g. --seam-allowance 10")]
    InvalidSeamAllowance {
        /// The rejected value, in mm.
        value: f64,
    },
    /// The seam allowance fills a hole completely, so the hole would not be cut.
    #[error(
        "part `{part}`: a seam allowance of {allowance} mm closes hole {hole}; use a smaller --seam-allowance or remove the hole"
    )]
    SeamAllowanceClosesHole {
        /// Name of the part.
        part: String,
        /// Index of the hole (from 1).
        hole: usize,
        /// The seam allowance, in mm.
        allowance: f64,
    },
    /// Offsetting the outer contour did not give exactly one closed contour (the outline crosses
    /// itself).
    #[error(
        "part `{part}`: offsetting the outline by the seam allowance gave {pieces} contours instead of one; the outline crosses itself, fix the pattern"
    )]
    SeamOffsetFailed {
        /// Name of the part.
        part: String,
        /// How many contours the offset gave.
        pieces: usize,
    },
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
}
