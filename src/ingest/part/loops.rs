//! Trim loops and polygons in a plane: areas, simplicity, nesting, point-in-polygon. Used to
//! check the loops of polygon surfaces and patch trims before they reach the tessellator.

use glam::DVec2;

use super::checks::check;
use super::errors::SpecDefect;
pub use crate::geometry::signed_area as polygon_area;
use crate::geometry::tolerance::LOOP_TOLERANCE;
use crate::geometry::{distance_to_segment, inside};

/// Checks trim loops: simple, nested (holes inside the outer loop, apart from each other);
/// returns the outer loop counter-clockwise and the holes.
pub fn check_loops(
    mut outer: Vec<DVec2>,
    holes: Vec<Vec<DVec2>>,
    outer_field: &str,
    holes_field: &str,
) -> Result<(Vec<DVec2>, Vec<Vec<DVec2>>), SpecDefect> {
    let loops = std::iter::once((outer_field.to_string(), &outer)).chain(
        holes
            .iter()
            .enumerate()
            .map(|(i, h)| (format!("{holes_field}[{i}]"), h)),
    );
    let named: Vec<(String, &Vec<DVec2>)> = loops.collect();
    let size = extent(&outer);
    let tolerance = LOOP_TOLERANCE * size;
    for (field, points) in &named {
        check(
            points.len() >= 3,
            field,
            "a loop needs at least three points",
        )?;
        check(
            points.iter().all(|p| p.is_finite()),
            field,
            "every point must be a finite number",
        )?;
        check(
            !self_intersects(points),
            field,
            "the loop intersects itself",
        )?;
        check(
            polygon_area(points).abs() > tolerance * extent(points),
            field,
            "the loop has (almost) no area",
        )?;
    }
    for (i, (field, hole)) in named.iter().enumerate().skip(1) {
        check(
            hole.iter().all(|&p| inside(p, &outer)) && !loops_cross(hole, &outer),
            field,
            "the hole must lie inside the outer boundary",
        )?;
        check(
            loop_distance(hole, &outer) > tolerance,
            field,
            "the hole touches the outer boundary; keep it apart, or make it a notch of the outer boundary",
        )?;
        for (_, other) in named.iter().skip(i + 1) {
            check(
                !loops_cross(hole, other) && !inside(hole[0], other) && !inside(other[0], hole),
                field,
                "two holes overlap",
            )?;
            check(
                loop_distance(hole, other) > tolerance,
                field,
                "two holes touch; keep them apart or join them into one hole",
            )?;
        }
    }
    if polygon_area(&outer) < 0.0 {
        outer.reverse();
    }
    Ok((outer, holes))
}

/// The larger side of the loop's bounding box.
fn extent(points: &[DVec2]) -> f64 {
    let (low, high) = points
        .iter()
        .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(l, h), &p| {
            (l.min(p), h.max(p))
        });
    (high - low).max_element()
}

/// The smallest distance from a corner of either loop to an edge of the other.
fn loop_distance(a: &[DVec2], b: &[DVec2]) -> f64 {
    let corner_to_edges = |corners: &[DVec2], ring: &[DVec2]| {
        corners
            .iter()
            .flat_map(|&p| segments(ring).map(move |(s, t)| distance_to_segment(p, s, t)))
            .fold(f64::INFINITY, f64::min)
    };
    corner_to_edges(a, b).min(corner_to_edges(b, a))
}

fn segments(points: &[DVec2]) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
    (0..points.len()).map(move |k| (points[k], points[(k + 1) % points.len()]))
}

fn segments_cross(a: (DVec2, DVec2), b: (DVec2, DVec2)) -> bool {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (d1, d2) = (side(b.0, b.1, a.0), side(b.0, b.1, a.1));
    let (d3, d4) = (side(a.0, a.1, b.0), side(a.0, a.1, b.1));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

fn self_intersects(points: &[DVec2]) -> bool {
    let count = points.len();
    let all: Vec<(DVec2, DVec2)> = segments(points).collect();
    (0..count).any(|i| {
        (i + 2..count)
            .filter(|&j| !(i == 0 && j == count - 1))
            .any(|j| segments_cross(all[i], all[j]))
    }) || (0..count).any(|i| (i + 1..count).any(|j| points[i].distance(points[j]) <= 0.0))
}

fn loops_cross(a: &[DVec2], b: &[DVec2]) -> bool {
    segments(a).any(|s| segments(b).any(|t| segments_cross(s, t)))
}

#[cfg(test)]
mod tests {
    use crate::ingest::part::loops::*;

    #[test]
    fn a_self_intersecting_loop_is_found() {
        let bow_tie = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]].map(DVec2::from_array);
        assert!(self_intersects(&bow_tie));
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]].map(DVec2::from_array);
        assert!(!self_intersects(&square));
    }
}
