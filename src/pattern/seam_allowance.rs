//! Seam allowance: a closed contour offset away from the material by a fixed distance, with true
//! arcs, by cavalier_contours' parallel offset (the raw offset segments joined, self-intersections
//! trimmed).
//!
//! Input: a closed bulge polyline with the material on its left (outer contours counter-clockwise,
//! holes clockwise) and the allowance in drawing units. Output: the offset contours, same
//! orientation. Convex corners get round joins of radius equal to the allowance; concave corners
//! are trimmed to a sharp corner. An outer contour gives one contour; a hole may shrink to nothing
//! (no contour) or split in two where it is narrow.
//!
//! Joins between nearly tangent segments come out of the offset as arcs of a few micrometres; so
//! the offset contour is sampled (chords within a quarter of the tolerance of its arcs) and fitted
//! again by [`super::contour::fit_closed`] within the rest of the tolerance, which merges them into
//! their neighbours and keeps the result within the tolerance of the exact offset.

use super::bulge::{BulgeVertex, sample_closed_within};
use super::contour::fit_closed;
use cavalier_contours::polyline::{
    PlineCreation, PlineSource, PlineSourceMut, PlineVertex, Polyline,
};
use glam::DVec2;

/// Positions closer than this fraction of the allowance are merged in the offset result.
const MERGE_FRACTION: f64 = 1e-6;

/// Share of the tolerance given to sampling the exact offset before it is fitted again; the fit
/// gets the rest.
const SAMPLING_SHARE: f64 = 0.25;

/// The contours at `allowance` (drawing units, positive) from `contour`, on the side away from the
/// material (its right), fitted within `tolerance` (drawing units) of the exact offset.
pub(crate) fn offset_away_from_material(
    contour: &[BulgeVertex],
    allowance: f64,
    tolerance: f64,
) -> Vec<Vec<BulgeVertex>> {
    let mut polyline = Polyline::with_capacity(contour.len(), true);
    for vertex in contour {
        polyline.add(vertex.point.x, vertex.point.y, vertex.bulge);
    }
    // cavalier_contours offsets to the left for a positive value; the material is on the left.
    polyline
        .parallel_offset(-allowance)
        .into_iter()
        .map(|offset| {
            offset
                .remove_redundant(allowance * MERGE_FRACTION)
                .unwrap_or(offset)
        })
        .filter(|offset| offset.vertex_count() >= 2)
        .filter_map(|offset| {
            let exact: Vec<BulgeVertex> = offset.iter_vertexes().map(to_bulge_vertex).collect();
            let samples = sample_closed_within(&exact, tolerance * SAMPLING_SHARE);
            fit_closed(&samples, tolerance * (1.0 - SAMPLING_SHARE))
        })
        .collect()
}

/// A cavalier_contours vertex as ours.
fn to_bulge_vertex(vertex: PlineVertex<f64>) -> BulgeVertex {
    BulgeVertex {
        point: DVec2::new(vertex.x, vertex.y),
        bulge: vertex.bulge,
    }
}

#[cfg(test)]
mod tests {
    use crate::pattern::bulge::sample_closed;
    use crate::pattern::contour::signed_area;
    use crate::pattern::seam_allowance::*;

    #[test]
    fn square_grows_by_the_allowance_with_round_corners() {
        let square = [
            DVec2::ZERO,
            DVec2::new(100.0, 0.0),
            DVec2::new(100.0, 50.0),
            DVec2::new(0.0, 50.0),
        ]
        .map(BulgeVertex::straight);
        let offsets = offset_away_from_material(&square, 10.0, 0.01);
        assert_eq!(offsets.len(), 1);
        let outline = sample_closed(&offsets[0], 0.1);
        let area = signed_area(&outline);
        let expected = 100.0 * 50.0 + 2.0 * 10.0 * 150.0 + std::f64::consts::PI * 100.0;
        assert!(
            (area - expected).abs() < 1.0,
            "area {area}, expected {expected}"
        );
        assert!(
            outline
                .iter()
                .all(|point| point.x >= -10.0 - 1e-9 && point.y <= 60.0 + 1e-9)
        );
    }

    #[test]
    fn small_hole_closes() {
        // A clockwise 4 x 4 hole: material on the left, so the offset goes into the hole.
        let hole = [
            DVec2::ZERO,
            DVec2::new(0.0, 4.0),
            DVec2::new(4.0, 4.0),
            DVec2::new(4.0, 0.0),
        ]
        .map(BulgeVertex::straight);
        assert!(offset_away_from_material(&hole, 3.0, 0.01).is_empty());
        assert_eq!(offset_away_from_material(&hole, 1.0, 0.01).len(), 1);
    }
}
