//! Plane geometry shared by every stage.

use glam::DVec2;

use super::segment::distance_to_segment;

/// Signed area of a closed ring (positive when counter-clockwise), by the shoelace formula. The
/// ring's last point may or may not repeat its first.
pub fn signed_area(ring: &[DVec2]) -> f64 {
    let count = ring.len();
    0.5 * (0..count)
        .map(|index| ring[index].perp_dot(ring[(index + 1) % count]))
        .sum::<f64>()
}

/// Two rectangle areas closer than this fraction of the smaller are a tie in
/// [`long_side_of_smallest_rectangle`], so round-off cannot pick between equal rectangles.
const AREA_TIE_RELATIVE: f64 = 1e-12;

/// The unit direction of the longer side of the smallest-area rectangle around `points` (one of
/// the convex hull's edge directions, by the rotating-calipers theorem), pointing into the
/// half-plane x > 0 (or +y); `None` for fewer than three non-collinear points.
pub fn long_side_of_smallest_rectangle(points: &[DVec2]) -> Option<DVec2> {
    let hull = convex_hull(points);
    if hull.len() < 3 {
        return None;
    }
    let mut best: Option<(f64, DVec2)> = None;
    for (i, &start) in hull.iter().enumerate() {
        let edge = (hull[(i + 1) % hull.len()] - start).normalize_or_zero();
        if edge == DVec2::ZERO {
            continue;
        }
        let extent = |axis: DVec2| {
            let (low, high) = hull
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                    (l.min(p.dot(axis)), h.max(p.dot(axis)))
                });
            high - low
        };
        let (along, across) = (extent(edge), extent(edge.perp()));
        let area = along * across;
        // A strictly smaller area wins, so ties keep the first edge: deterministic.
        if best.is_none_or(|(smallest, _)| area < smallest * (1.0 - AREA_TIE_RELATIVE)) {
            best = Some((area, if along >= across { edge } else { edge.perp() }));
        }
    }
    best.map(|(_, direction)| {
        if direction.x < 0.0 || (direction.x == 0.0 && direction.y < 0.0) {
            -direction
        } else {
            direction
        }
    })
}

/// Convex hull of `points`, counter-clockwise without collinear points (Andrew's monotone chain).
pub fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let turns_left = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o) > 0.0;
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * sorted.len());
    for pass in [
        &sorted[..],
        &sorted.iter().rev().copied().collect::<Vec<_>>()[..],
    ] {
        let floor = hull.len();
        for &p in pass {
            while hull.len() >= floor + 2
                && !turns_left(hull[hull.len() - 2], hull[hull.len() - 1], p)
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// The sides of a closed ring, the last from its last point back to the first.
pub fn ring_sides(ring: &[DVec2]) -> impl Iterator<Item = [DVec2; 2]> + '_ {
    (0..ring.len()).map(|k| [ring[k], ring[(k + 1) % ring.len()]])
}

/// Whether `point` lies inside the closed `ring`, by the crossing rule (the ring's last point may
/// or may not repeat its first).
pub fn inside(point: DVec2, ring: &[DVec2]) -> bool {
    ring_sides(ring)
        .filter(|&[p, q]| crosses_ray(point, p, q))
        .count()
        % 2
        == 1
}

/// Whether the side `p`–`q` crosses the ray from `point` towards +x, as the crossing rule counts
/// it ([`inside`]): a side with one end above the point and the other at or below it, crossed
/// right of the point.
pub fn crosses_ray(point: DVec2, p: DVec2, q: DVec2) -> bool {
    (p.y > point.y) != (q.y > point.y)
        && point.x < p.x + (point.y - p.y) / (q.y - p.y) * (q.x - p.x)
}

/// The axis-aligned bounding box of `points`: (lowest corner, highest corner); infinite corners
/// (low +∞, high −∞) for no points.
pub fn bounding_box(points: &[DVec2]) -> (DVec2, DVec2) {
    points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(low, high), &p| (low.min(p), high.max(p)),
    )
}

/// Grid points per side of each search in [`deep_interior_point`].
const DEEP_POINT_GRID: usize = 24;
/// Refinements of [`deep_interior_point`]'s search, each around the best point so far.
const DEEP_POINT_REFINEMENTS: usize = 4;

/// A point deep inside the region of `outer` without `holes`, where a label or a mark belongs:
/// of a grid over the bounding box, refined around the best point a few times, the point inside
/// the region farthest from every ring (an approximate pole of inaccessibility). The bounding
/// box's centre when no grid point lies inside. Rings are skipped by their bounding boxes where
/// that cannot change the answer (a point outside a hole's box is not in it, a ring whose box is
/// no nearer than the nearest side so far has no nearer side), so a plate with hundreds of
/// finely sampled holes costs about as much as a plain one.
pub fn deep_interior_point(outer: &[DVec2], holes: &[Vec<DVec2>]) -> DVec2 {
    let (low, high) = bounding_box(outer);
    let rings: Vec<(&[DVec2], DVec2, DVec2)> = std::iter::once(outer)
        .chain(holes.iter().map(Vec::as_slice))
        .map(|ring| {
            let (ring_low, ring_high) = bounding_box(ring);
            (ring, ring_low, ring_high)
        })
        .collect();
    // The point's distance to the nearest ring when it is inside the region and farther than
    // `to_beat` from every ring.
    let clearance = |point: DVec2, to_beat: f64| {
        let in_hole = rings[1..].iter().any(|&(ring, ring_low, ring_high)| {
            distance_to_box(point, ring_low, ring_high) == 0.0 && inside(point, ring)
        });
        if !inside(point, outer) || in_hole {
            return None;
        }
        let mut nearest = f64::INFINITY;
        for &(ring, ring_low, ring_high) in &rings {
            if distance_to_box(point, ring_low, ring_high) >= nearest {
                continue;
            }
            for [p, q] in ring_sides(ring) {
                nearest = nearest.min(distance_to_segment(point, p, q));
            }
            if nearest <= to_beat {
                return None;
            }
        }
        Some(nearest)
    };
    // A strictly larger clearance wins: the first of equals stays, deterministically.
    refined_grid_search(
        (low, high),
        DEEP_POINT_GRID,
        DEEP_POINT_REFINEMENTS,
        |point, best: Option<f64>| clearance(point, best.unwrap_or(f64::NEG_INFINITY)),
    )
    .map_or(0.5 * (low + high), |(point, _)| point)
}

/// The distance from `point` to the box `low`–`high` (0 inside it).
pub fn distance_to_box(point: DVec2, low: DVec2, high: DVec2) -> f64 {
    (low - point).max(point - high).max(DVec2::ZERO).length()
}

/// A grid search of the box `(low, high)`: `grid + 1` points a side, then a grid of the same
/// count around the best point found, two steps wide, `refinements` times. `better(point, best)`
/// is the point's value when it beats `best` (the best value so far, `None` before any), else
/// `None`, so the first of equals stays: deterministic. The best point and its value, or `None`
/// when no point had a value.
pub fn refined_grid_search<T: Copy>(
    (low, high): (DVec2, DVec2),
    grid: usize,
    refinements: usize,
    mut better: impl FnMut(DVec2, Option<T>) -> Option<T>,
) -> Option<(DVec2, T)> {
    let mut best: Option<(DVec2, T)> = None;
    let (mut centre, mut half) = (0.5 * (low + high), 0.5 * (high - low));
    for _ in 0..=refinements {
        let step = 2.0 * half / grid as f64;
        for i in 0..=grid {
            for j in 0..=grid {
                let point = centre - half + step * DVec2::new(i as f64, j as f64);
                if let Some(value) = better(point, best.map(|(_, value)| value)) {
                    best = Some((point, value));
                }
            }
        }
        (centre, half) = (best.map_or(centre, |(point, _)| point), 2.0 * step);
    }
    best
}

/// Barycentric coordinates of `point` in the triangle `corners` (None when degenerate).
pub fn barycentric(corners: [DVec2; 3], point: DVec2) -> Option<[f64; 3]> {
    let [a, b, c] = corners;
    let area = (b - a).perp_dot(c - a);
    if area.abs() <= f64::MIN_POSITIVE {
        return None;
    }
    let wb = (point - a).perp_dot(c - a) / area;
    let wc = (b - a).perp_dot(point - a) / area;
    Some([1.0 - wb - wc, wb, wc])
}

#[cfg(test)]
mod tests {
    use crate::geometry::plane::*;

    #[test]
    fn unit_square_both_ways() {
        let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        assert!((signed_area(&square) - 1.0).abs() < 1e-15);
        let mut reversed = square;
        reversed.reverse();
        assert!((signed_area(&reversed) + 1.0).abs() < 1e-15);
    }

    fn rectangle(turn: f64) -> Vec<DVec2> {
        let rotation = DVec2::from_angle(turn);
        [
            (0.0, 0.0),
            (80.0, 0.0),
            (80.0, 30.0),
            (0.0, 30.0),
            (40.0, 15.0),
        ]
        .map(|(x, y)| rotation.rotate(DVec2::new(x, y) + DVec2::new(5.0, -7.0)))
        .to_vec()
    }

    #[test]
    fn the_hull_drops_inner_and_collinear_points() {
        let mut points = rectangle(0.0);
        points.push(DVec2::new(45.0, -7.0));
        assert_eq!(convex_hull(&points).len(), 4);
    }

    #[test]
    fn a_turned_rectangle_comes_back_with_its_long_side_along_x() {
        for turn in [0.0, 0.4, 1.3, 2.0, -2.9] {
            let direction = long_side_of_smallest_rectangle(&rectangle(turn)).expect("a side");
            let expected = DVec2::from_angle(turn);
            let expected = if expected.x < 0.0 {
                -expected
            } else {
                expected
            };
            assert!(direction.distance(expected) < 1e-12, "{turn}: {direction}");
        }
    }

    #[test]
    fn collinear_points_have_no_rectangle() {
        let line = [DVec2::ZERO, DVec2::ONE, DVec2::splat(2.0)];
        assert_eq!(long_side_of_smallest_rectangle(&line), None);
    }

    #[test]
    fn the_deep_point_of_an_annulus_sector_lies_in_its_material() {
        // The upper half of an annulus of radii 50 and 100: its bounding box's centre (0, 50)
        // is in the hole; the deepest point is on the y axis, midway between the arcs.
        let arc = |radius: f64, from: f64, to: f64| -> Vec<DVec2> {
            (0..=32)
                .map(|k| DVec2::from_angle(from + (to - from) * k as f64 / 32.0) * radius)
                .collect()
        };
        let mut ring = arc(100.0, 0.0, std::f64::consts::PI);
        ring.extend(arc(50.0, std::f64::consts::PI, 0.0));
        let point = deep_interior_point(&ring, &[]);
        assert!(inside(point, &ring));
        assert!((point.length() - 75.0).abs() < 1.0, "{point}");
    }

    #[test]
    fn the_deep_point_avoids_holes() {
        // A 100 mm square with a 40 mm square hole in the middle: the band around the hole is
        // 30 mm wide, so the deepest points are 15 mm from both.
        let ring = |low: f64, high: f64| -> Vec<DVec2> {
            [(low, low), (high, low), (high, high), (low, high)]
                .map(DVec2::from)
                .to_vec()
        };
        let (outer, hole) = (ring(0.0, 100.0), ring(30.0, 70.0));
        let point = deep_interior_point(&outer, std::slice::from_ref(&hole));
        assert!(inside(point, &outer) && !inside(point, &hole), "{point}");
        let to_ring = |ring: &[DVec2]| {
            (0..4)
                .map(|k| distance_to_segment(point, ring[k], ring[(k + 1) % 4]))
                .fold(f64::INFINITY, f64::min)
        };
        assert!(to_ring(&outer).min(to_ring(&hole)) > 14.0, "{point}");
    }
}
