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
/// allowance when `options` has one), with `rotations` taken from the part's minimum-area
/// bounding rectangle ([`aligned_rotations`]), mirroring as given, and the grain direction of the
/// same index in `grains` (degrees in the drawing's frame, see [`pattern_grain_degrees`]), which
/// overrides the rotations.
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
            let outer: Vec<DVec2> = to_millimetres(sample_closed(&contours.outer, step));
            Ok(NestItem {
                name: drawing.name.clone(),
                outer: outer.clone(),
                holes: contours
                    .holes
                    .iter()
                    .map(|hole| to_millimetres(sample_closed(hole, step)))
                    .collect(),
                quantity: drawing.quantity,
                rotations: aligned_rotations(rotations, &outer),
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

/// `rotations` measured from the orientation that lays the side of the minimum-area bounding
/// rectangle of `outer` along x: rotation 0 of the result puts that rectangle square to the
/// stock, so a flattened pattern, whatever angle the flattening left it at, is tried square to
/// the sheet first. `Free` and invalid rotations are returned unchanged.
pub fn aligned_rotations(rotations: &Rotations, outer: &[DVec2]) -> Rotations {
    match (rotations, rotations.angles()) {
        (Rotations::Free, _) | (_, None) => rotations.clone(),
        (_, Some(angles)) => {
            let offset = minimum_area_rectangle_degrees(outer);
            Rotations::Fixed(angles.into_iter().map(|angle| angle - offset).collect())
        }
    }
}

/// Direction (degrees, in [0, 180)) of a side of the smallest-area rectangle enclosing `ring`:
/// one of its convex hull's edges (rotating calipers, by enumeration of the hull edges).
pub fn minimum_area_rectangle_degrees(ring: &[DVec2]) -> f64 {
    let hull = convex_hull(ring);
    let mut best = (f64::INFINITY, 0.0);
    for index in 0..hull.len() {
        let edge = hull[(index + 1) % hull.len()] - hull[index];
        if edge.length_squared() == 0.0 {
            continue;
        }
        let direction = edge.normalize();
        let (mut low, mut high) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for point in &hull {
            let local = DVec2::new(point.dot(direction), direction.perp_dot(*point));
            (low, high) = (low.min(local), high.max(local));
        }
        let area = (high - low).x * (high - low).y;
        if area < best.0 {
            best = (
                area,
                direction
                    .y
                    .atan2(direction.x)
                    .to_degrees()
                    .rem_euclid(180.0),
            );
        }
    }
    best.1
}

/// Convex hull of `points`, counter-clockwise (Andrew's monotone chain).
fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * sorted.len());
    for pass in [sorted.clone(), sorted.into_iter().rev().collect()] {
        let start = hull.len();
        for point in pass {
            while hull.len() >= start + 2
                && (hull[hull.len() - 1] - hull[hull.len() - 2])
                    .perp_dot(point - hull[hull.len() - 2])
                    <= 0.0
            {
                hull.pop();
            }
            hull.push(point);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tilted_rectangle_is_tried_square_to_the_stock() {
        let tilt = DVec2::from_angle(30f64.to_radians());
        let ring: Vec<DVec2> = [
            (0.0, 0.0),
            (40.0, 0.0),
            (40.0, 10.0),
            (20.0, 12.0),
            (0.0, 10.0),
        ]
        .map(|(x, y)| tilt.rotate(DVec2::new(x, y)))
        .to_vec();
        let side = minimum_area_rectangle_degrees(&ring);
        assert!(
            (side.rem_euclid(90.0) - 30.0).abs() < 1e-9,
            "side at {side}"
        );
        let Rotations::Fixed(angles) = aligned_rotations(&Rotations::Fixed(vec![0.0, 90.0]), &ring)
        else {
            panic!("a list of angles")
        };
        assert_eq!(angles.len(), 2);
        for angle in angles {
            let turn = DVec2::from_angle(angle.to_radians());
            let turned: Vec<DVec2> = ring.iter().map(|point| turn.rotate(*point)).collect();
            let (low, high) = turned.iter().fold(
                (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                |(low, high), point| (low.min(*point), high.max(*point)),
            );
            let size = high - low;
            assert!(
                (size.x * size.y - 480.0).abs() < 1e-6,
                "square to the stock at {angle}: {size}"
            );
        }
        assert_eq!(aligned_rotations(&Rotations::Free, &ring), Rotations::Free);
    }
}
