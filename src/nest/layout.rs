//! The result of nesting: where every copy went, per sheet, and the figures of the search.

use glam::DVec2;
use serde::Serialize;

use super::stock::Stock;

/// Where one copy of an item went.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Placement {
    /// Index of the item in the input slice.
    pub item: usize,
    /// Which copy of the item (0-based, below its quantity).
    pub copy: u32,
    /// Rotation in degrees, counter-clockwise, in [0, 360).
    pub rotation_degrees: f64,
    /// Whether the item was mirrored (x → −x) before the rotation.
    pub mirrored: bool,
    /// Translation applied after the rotation, mm.
    pub translation: DVec2,
}

impl Placement {
    /// Maps a point of the item's own coordinates to the sheet: first mirror about the item's y
    /// axis if `mirrored` (x → −x), then rotate by `rotation_degrees` counter-clockwise about the
    /// item's origin, then add `translation`.
    pub fn transform_point(&self, point: DVec2) -> DVec2 {
        let mirrored = if self.mirrored {
            DVec2::new(-point.x, point.y)
        } else {
            point
        };
        DVec2::from_angle(self.rotation_degrees.to_radians()).rotate(mirrored) + self.translation
    }

    /// The placement of a copy that sits at `inner` in the frame of the copy placed by `self`
    /// (a part in a hole): `result.transform_point(p) == self.transform_point(inner.transform_point(p))`.
    /// The item and copy are those of `inner`.
    pub fn compose(&self, inner: &Placement) -> Placement {
        let turned = if self.mirrored {
            -inner.rotation_degrees
        } else {
            inner.rotation_degrees
        };
        Placement {
            rotation_degrees: (self.rotation_degrees + turned).rem_euclid(360.0),
            mirrored: self.mirrored != inner.mirrored,
            translation: self.transform_point(inner.translation),
            ..*inner
        }
    }

    /// The ring `points` (outer ring or hole of the item) at its placed position. A mirrored ring
    /// is also reversed, so it keeps its orientation (CCW stays CCW).
    pub fn transform_ring(&self, points: &[DVec2]) -> Vec<DVec2> {
        let mut placed: Vec<DVec2> = points
            .iter()
            .map(|point| self.transform_point(*point))
            .collect();
        if self.mirrored {
            placed.reverse();
        }
        placed
    }
}

/// One sheet, or the used part of the roll.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SheetLayout {
    /// Extent along x, mm: the sheet width, or on a roll the used length.
    pub width: f64,
    /// Extent along y, mm: the sheet height, or the roll width.
    pub height: f64,
    /// Length used along x: from 0 to the far edge of the last part plus the gap, mm.
    pub used_length: f64,
    /// The parts on this sheet.
    pub placements: Vec<Placement>,
    /// Net part area divided by `width × height`.
    pub utilisation: f64,
}

/// Why the search stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// The deterministic work budget was spent: the result depends only on input, options, seed.
    WorkBudget,
    /// The wall-clock limit came first: the result depends on the machine's speed.
    TimeLimit,
    /// Every part fits on the first sheet and nothing better is possible to search for.
    Complete,
}

/// The result of [`nest`](crate::nest::nest).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NestLayout {
    /// The stock that was used.
    pub stock: Stock,
    /// The gap kept, mm.
    pub gap: f64,
    /// The sheets in order (exactly one for a roll).
    pub sheets: Vec<SheetLayout>,
    /// Net part area over the total area of all sheets (on a roll: width × used length).
    pub utilisation: f64,
    /// Length used on the last sheet or on the roll, mm.
    pub used_length: f64,
    /// Collision queries spent (the search's unit of work).
    pub work: u64,
    /// Layouts evaluated by the search.
    pub evaluations: u64,
    /// Why the search stopped.
    pub stop_reason: StopReason,
}
