//! Flattened parts as nesting items: each part's cut outline (with the seam allowance when one is
//! given), in millimetres, in its quantity.

use glam::DVec2;

use super::{NestItem, Rotations};
use crate::export::{DxfOptions, ExportError, PartDrawing, part_contours, sample_closed};

/// Largest step when a fitted contour (lines and arcs) is sampled back into a polygon for the
/// nester, in mm: arcs are followed within a fraction of the chord tolerance.
pub const OUTLINE_SAMPLE_STEP: f64 = 1.0;

/// One nesting item per part drawing, in mm: the contour that will be cut (offset by the seam
/// allowance when `options` has one), with `rotations` and mirroring as given.
pub fn items_from_drawings(
    drawings: &[PartDrawing],
    options: &DxfOptions,
    rotations: &Rotations,
    mirror_allowed: bool,
) -> Result<Vec<NestItem>, ExportError> {
    drawings
        .iter()
        .map(|drawing| {
            let scale = drawing.units.millimetres();
            let contours = part_contours(drawing, options)?;
            let to_millimetres = |ring: Vec<DVec2>| ring.into_iter().map(|p| p * scale).collect();
            let step = OUTLINE_SAMPLE_STEP / scale;
            Ok(NestItem {
                name: drawing.name.clone(),
                outer: to_millimetres(sample_closed(&contours.outer, step)),
                holes: contours
                    .holes
                    .iter()
                    .map(|hole| to_millimetres(sample_closed(hole, step)))
                    .collect(),
                quantity: drawing.quantity,
                rotations: rotations.clone(),
                mirror_allowed,
            })
        })
        .collect()
}
