//! Plane geometry shared by every stage.

use glam::DVec2;

/// Signed area of a closed ring (positive when counter-clockwise), by the shoelace formula. The
/// ring's last point may or may not repeat its first.
pub fn signed_area(ring: &[DVec2]) -> f64 {
    let count = ring.len();
    0.5 * (0..count)
        .map(|index| ring[index].perp_dot(ring[(index + 1) % count]))
        .sum::<f64>()
}

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
        if best.is_none_or(|(smallest, _)| area < smallest * (1.0 - 1e-12)) {
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
