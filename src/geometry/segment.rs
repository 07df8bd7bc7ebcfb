//! Straight segments, in the plane and in space: the distance from a point to a segment (the
//! projection of the point on its line, clamped to the segment) and whether two plane segments meet.

use glam::{DVec2, DVec3};

/// Where the projection of `point` on the line through `start` and `end` falls, clamped to the
/// segment: 0 at `start`, 1 at `end`. A segment whose squared length is at most
/// `f64::MIN_POSITIVE` gives 0.
pub fn segment_fraction(point: DVec2, start: DVec2, end: DVec2) -> f64 {
    let direction = end - start;
    let length_squared = direction.length_squared();
    if length_squared <= f64::MIN_POSITIVE {
        return 0.0;
    }
    ((point - start).dot(direction) / length_squared).clamp(0.0, 1.0)
}

/// Distance from `point` to the straight segment from `start` to `end` in the plane. A segment
/// whose squared length is at most `f64::MIN_POSITIVE` is measured as the point `start`.
pub fn distance_to_segment(point: DVec2, start: DVec2, end: DVec2) -> f64 {
    point.distance(start.lerp(end, segment_fraction(point, start, end)))
}

/// Distance from `point` to the straight segment from `start` to `end` in space. Only a segment
/// of exactly zero squared length is measured as the point `start` (unlike the plane version, a
/// subnormal one is still projected on): the formula the fold-line stiffness has always used, kept
/// so that its output does not move.
pub fn distance_to_segment_3d(point: DVec3, start: DVec3, end: DVec3) -> f64 {
    let direction = end - start;
    let length_squared = direction.length_squared();
    let t = if length_squared > 0.0 {
        ((point - start).dot(direction) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    point.distance(start + direction * t)
}

/// True if closed segments `pq` and `rs` have a point in common.
pub fn segments_intersect(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    let orientation = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let on_segment = |a: DVec2, b: DVec2, c: DVec2| {
        c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
    };
    let (d1, d2) = (orientation(r, s, p), orientation(r, s, q));
    let (d3, d4) = (orientation(p, q, r), orientation(p, q, s));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on_segment(r, s, p))
        || (d2 == 0.0 && on_segment(r, s, q))
        || (d3 == 0.0 && on_segment(p, q, r))
        || (d4 == 0.0 && on_segment(p, q, s))
}

/// True if closed segments `pq` and `rs` come within `gap` of each other (meet, or one's end lies
/// within `gap` of the other; with `gap` 0, exactly [`segments_intersect`]).
pub fn segments_within(p: DVec2, q: DVec2, r: DVec2, s: DVec2, gap: f64) -> bool {
    let ends_within = || {
        distance_to_segment(p, r, s) <= gap
            || distance_to_segment(q, r, s) <= gap
            || distance_to_segment(r, p, q) <= gap
            || distance_to_segment(s, p, q) <= gap
    };
    segments_intersect(p, q, r, s) || (gap > 0.0 && ends_within())
}

/// The part of the polyline `points` from its first point along `fraction` (clamped to 0..=1) of
/// its length: its points up to there, and the point at that length on the segment it falls in.
/// An empty polyline gives an empty one.
pub fn polyline_prefix(points: &[DVec3], fraction: f64) -> Vec<DVec3> {
    let Some(&first) = points.first() else {
        return Vec::new();
    };
    if fraction >= 1.0 {
        return points.to_vec();
    }
    let total: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    let mut left = fraction.clamp(0.0, 1.0) * total;
    let mut prefix = vec![first];
    for pair in points.windows(2) {
        let length = pair[0].distance(pair[1]);
        if length >= left {
            if length > 0.0 && left > 0.0 {
                prefix.push(pair[0].lerp(pair[1], left / length));
            }
            break;
        }
        left -= length;
        prefix.push(pair[1]);
    }
    prefix
}

#[cfg(test)]
mod tests {
    use crate::geometry::segment::*;

    #[test]
    fn a_polyline_prefix_ends_at_its_fraction_of_the_length() {
        let points = [
            DVec3::ZERO,
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(3.0, 4.0, 0.0),
        ];
        let prefix = polyline_prefix(&points, 0.5);
        assert_eq!(&prefix[..2], &points[..2]);
        assert!(
            prefix[2].distance(DVec3::new(3.0, 0.5, 0.0)) < 1e-12,
            "{prefix:?}"
        );
        assert_eq!(polyline_prefix(&points, 1.0), points.to_vec());
        assert_eq!(polyline_prefix(&points, 0.0), vec![DVec3::ZERO]);
        assert!(polyline_prefix(&[], 0.5).is_empty());
    }

    #[test]
    fn segments_a_gap_apart_are_within_that_gap_only() {
        let (p, q) = (DVec2::ZERO, DVec2::new(4.0, 0.0));
        let (r, s) = (DVec2::new(2.0, 1e-12), DVec2::new(2.0, 3.0));
        assert!(!segments_intersect(p, q, r, s));
        assert!(!segments_within(p, q, r, s, 0.0));
        assert!(segments_within(p, q, r, s, 1e-9));
        assert!(!segments_within(p, q, r + DVec2::Y, s, 0.5));
        assert!(segments_within(p, q, DVec2::new(2.0, -1.0), s, 0.0));
    }

    #[test]
    fn the_foot_is_clamped_to_the_segment() {
        let (start, end) = (DVec2::ZERO, DVec2::new(4.0, 0.0));
        assert_eq!(distance_to_segment(DVec2::new(2.0, 3.0), start, end), 3.0);
        assert_eq!(distance_to_segment(DVec2::new(7.0, 4.0), start, end), 5.0);
        assert_eq!(
            distance_to_segment(DVec2::new(-3.0, 0.0), start, start),
            3.0
        );
    }

    #[test]
    fn the_3d_distance_agrees_with_the_plane_one_in_a_plane() {
        let (start, end) = (DVec3::new(1.0, 1.0, 0.0), DVec3::new(5.0, 2.0, 0.0));
        for point in [(0.0, 0.0), (3.0, 4.0), (9.0, -1.0), (2.5, 1.5)] {
            let flat = DVec2::from(point);
            let plane = distance_to_segment(flat, start.truncate(), end.truncate());
            let space = distance_to_segment_3d(flat.extend(0.0), start, end);
            assert!((plane - space).abs() < 1e-12, "{point:?}: {plane} {space}");
        }
        assert_eq!(
            distance_to_segment_3d(DVec3::Z, DVec3::ZERO, DVec3::ZERO),
            1.0
        );
    }

    #[test]
    fn crossing_and_disjoint_segments() {
        let v = |x, y| DVec2::new(x, y);
        assert!(segments_intersect(
            v(0., 0.),
            v(2., 2.),
            v(0., 2.),
            v(2., 0.)
        ));
        assert!(!segments_intersect(
            v(0., 0.),
            v(1., 0.),
            v(0., 1.),
            v(1., 1.)
        ));
        assert!(
            segments_intersect(v(0., 0.), v(2., 0.), v(1., 0.), v(1., 1.)),
            "touching counts"
        );
    }
}
