//! What the exporters draw: a part's flat pattern as polylines in drawing units, and a sheet of
//! placed parts. Plain values, built by the caller from the pipeline's results.

use glam::DVec2;

pub use crate::units::Units;

/// One part's flat pattern, at 1:1 in `units`: nominal geometry (the CAM adds kerf).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PartDrawing {
    /// Part name: labels the part and names its file.
    pub name: String,
    /// Unit of every coordinate.
    pub units: Units,
    /// How many to cut.
    pub quantity: u32,
    /// Material, printed on the label when given.
    pub material: Option<String>,
    /// The outer contour: a closed ring (the first point may or may not be repeated at the end),
    /// typically a dense polyline from a mesh boundary.
    pub outer: Vec<DVec2>,
    /// Inner cut-outs, each a closed ring like `outer`.
    pub holes: Vec<Vec<DVec2>>,
    /// Fold or bend lines: open polylines, drawn but not cut.
    pub fold_lines: Vec<Vec<DVec2>>,
    /// Grain line, from tail to head, when the part has a grain direction.
    pub grain: Option<[DVec2; 2]>,
}

/// A part placed on a sheet, its coordinates already in the sheet's frame.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PlacedPart {
    /// The part, transformed into sheet coordinates.
    pub drawing: PartDrawing,
}

/// One nested sheet (or the used length of a roll) and the parts on it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SheetDrawing {
    /// Sheet number, from 1 (the file is `sheet-NNN.dxf`).
    pub index: usize,
    /// Unit of every coordinate.
    pub units: Units,
    /// Width along x, in `units`; the sheet spans [0, width] x [0, height].
    pub width: f64,
    /// Height along y, in `units`.
    pub height: f64,
    /// The parts placed on it.
    pub parts: Vec<PlacedPart>,
}
