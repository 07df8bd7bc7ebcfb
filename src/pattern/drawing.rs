//! A part's flat pattern as drawn: its outline, holes and fold lines as polylines in drawing
//! units, with its name, quantity and material, its grain line and where its label goes. Plain
//! values, made by [`super::part_pattern`] from a flattened part.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::sheet::BendLine;
use crate::units::Units;

/// One part's flat pattern, at 1:1 in `units`: nominal geometry (the CAM adds kerf).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
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
    /// Bend lines of a sheet-metal part (drawn on the bend layers, never cut), with their
    /// notes; empty for any other part (and then left out of a pattern file).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bends: Vec<BendLine>,
}

/// Width of one label character as a fraction of the text height (for centring the label and
/// for finding room for it).
pub const LABEL_CHARACTER_WIDTH: f64 = 0.6;

/// Grain arrowhead length as a fraction of the grain line, capped at [`ARROW_MAX_LENGTH_MM`].
const ARROW_FRACTION: f64 = 0.1;

/// Longest grain arrowhead, in mm.
const ARROW_MAX_LENGTH_MM: f64 = 10.0;

/// Angle between the grain line and each side of its arrowhead, in radians (25°).
const ARROW_HALF_ANGLE: f64 = 25.0 * std::f64::consts::PI / 180.0;

impl PartDrawing {
    /// Where a level label is centred (the sheet previews' names): inside the material, clear
    /// of every line drawn on the part, in its most open region ([`Self::label_placement`]'s
    /// search, level only); `None` when the outer contour has fewer than three points.
    pub fn label_anchor(&self) -> Option<DVec2> {
        (self.outer.len() >= 3).then(|| self.level_label_centre(LABEL_CHARACTER_WIDTH))
    }

    /// The label's text: `name xQUANTITY material`.
    pub fn label(&self) -> String {
        let mut label = format!("{} x{}", self.name, self.quantity);
        if let Some(material) = &self.material {
            label.push(' ');
            label.push_str(material);
        }
        label
    }

    /// The grain line (tail, head) and its arrowhead (barb, head, barb) as drawn, or `None` when
    /// the part has no grain line or one of zero or non-finite length.
    pub fn grain_arrow(&self) -> Option<([DVec2; 2], [DVec2; 3])> {
        let [tail, head] = self.grain?;
        let length = tail.distance(head);
        if !length.is_finite() || length <= 0.0 {
            return None;
        }
        let maximum = ARROW_MAX_LENGTH_MM / self.units.millimetres();
        let back = (tail - head) / length * (length * ARROW_FRACTION).min(maximum);
        let barb = |angle: f64| head + DVec2::from_angle(angle).rotate(back);
        Some((
            [tail, head],
            [barb(ARROW_HALF_ANGLE), head, barb(-ARROW_HALF_ANGLE)],
        ))
    }
}
