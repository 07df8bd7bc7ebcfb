//! Flattened parts as nesting items: each part's cut outline (with the seam allowance when one is
//! given), in millimetres, in its quantity.

use glam::{DVec2, DVec3};

use super::{NestItem, Rotations};
use crate::export::{DxfOptions, ExportError, PartDrawing, part_contours, sample_closed};
use crate::mesh::FacetModel;

/// Largest step when a fitted contour (lines and arcs) is sampled back into a polygon for the
/// nester, in mm: arcs are followed within a fraction of the chord tolerance.
pub const OUTLINE_SAMPLE_STEP: f64 = 1.0;

/// One nesting item per part drawing, in mm: the contour that will be cut (offset by the seam
/// allowance when `options` has one), with `rotations` and mirroring as given, and the grain
/// direction of the same index in `grains` (degrees in the drawing's frame, see
/// [`pattern_grain_degrees`]).
pub fn items_from_drawings(
    drawings: &[PartDrawing],
    grains: &[Option<f64>],
    options: &DxfOptions,
    rotations: &Rotations,
    mirror_allowed: bool,
) -> Result<Vec<NestItem>, ExportError> {
    drawings
        .iter()
        .zip(grains.iter().chain(std::iter::repeat(&None)))
        .map(|(drawing, &grain_degrees)| {
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
                grain_degrees,
            })
        })
        .collect()
}

/// Direction (degrees counter-clockwise from x) of a 3D grain `grain` on the flat pattern
/// `flat` of `model` (one flat position per model vertex).
///
/// Each triangle maps its tangent plane linearly onto its flat triangle; the grain is projected
/// onto the plane (least squares in the triangle's edge basis) and mapped, and the mapped
/// directions are summed weighted by the triangle's area. `None` when the grain is normal to the
/// surface everywhere (no direction on the pattern) or not finite.
pub fn pattern_grain_degrees(model: &FacetModel, flat: &[DVec2], grain: DVec3) -> Option<f64> {
    let positions = model.positions();
    let mut sum = DVec2::ZERO;
    let mut weight = 0.0;
    for (face, triangle) in model.triangles().iter().enumerate() {
        let [a, b, c] = triangle.map(|vertex| vertex as usize);
        let (edge_u, edge_v) = (positions[b] - positions[a], positions[c] - positions[a]);
        let (uu, uv, vv) = (edge_u.dot(edge_u), edge_u.dot(edge_v), edge_v.dot(edge_v));
        let determinant = uu * vv - uv * uv;
        if determinant <= 0.0 {
            continue;
        }
        let (gu, gv) = (grain.dot(edge_u), grain.dot(edge_v));
        let coefficient_u = (vv * gu - uv * gv) / determinant;
        let coefficient_v = (uu * gv - uv * gu) / determinant;
        let mapped = (flat[b] - flat[a]) * coefficient_u + (flat[c] - flat[a]) * coefficient_v;
        let area = model.triangle_area(face);
        sum += mapped * area;
        weight += area * grain.length();
    }
    let significant = sum.length() > GRAIN_IN_PLANE_RELATIVE * weight;
    (significant && sum.is_finite()).then(|| sum.y.atan2(sum.x).to_degrees())
}

/// The summed flat grain must be at least this fraction of its largest possible length (grain
/// lying in every triangle's plane), or the grain is taken as normal to the surface.
const GRAIN_IN_PLANE_RELATIVE: f64 = 1e-3;
