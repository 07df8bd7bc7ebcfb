//! Distance from a point to a straight segment, in the plane and in space: the projection of the
//! point on the segment's line, clamped to the segment, then the distance to that foot.

use glam::{DVec2, DVec3};

/// Distance from `point` to the straight segment from `start` to `end` in the plane. A segment
/// whose squared length is at most `f64::MIN_POSITIVE` is measured as the point `start`.
pub fn distance_to_segment(point: DVec2, start: DVec2, end: DVec2) -> f64 {
    let direction = end - start;
    let length_squared = direction.length_squared();
    if length_squared <= f64::MIN_POSITIVE {
        return point.distance(start);
    }
    let t = ((point - start).dot(direction) / length_squared).clamp(0.0, 1.0);
    point.distance(start + direction * t)
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

#[cfg(test)]
mod tests {
    use crate::geometry::segment::*;

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
}
