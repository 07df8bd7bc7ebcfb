//! What the sheet exporters draw: a sheet of placed part drawings ([`PartDrawing`], from the
//! pattern stage), in the sheet's frame. Plain values, built from a nested layout.

use glam::DVec2;

use crate::pattern::PartDrawing;
use crate::units::Units;

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

impl SheetDrawing {
    /// The sheet's corners, counter-clockwise from the origin.
    pub fn corners(&self) -> [DVec2; 4] {
        [
            DVec2::ZERO,
            DVec2::new(self.width, 0.0),
            DVec2::new(self.width, self.height),
            DVec2::new(0.0, self.height),
        ]
    }
}
