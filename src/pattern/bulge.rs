//! Polyline vertices with bulges, the way DXF stores arcs inside a polyline, and the circular arc
//! geometry behind them.
//!
//! A segment runs from one [`BulgeVertex`] to the next; its `bulge` is `tan(sweep / 4)`, where
//! `sweep` is the signed angle the arc turns through (positive counter-clockwise, zero for a
//! straight segment, ±1 for a half circle). Coordinates are in drawing units (the part's: mm, cm, m or inches).

use glam::DVec2;
use std::f64::consts::FRAC_PI_2;

/// A bulge below this magnitude is a straight segment: the arc's sagitta is below a billionth of
/// its chord.
pub const STRAIGHT_BULGE: f64 = 1e-9;

/// One polyline vertex and the shape of the segment that leaves it towards the next vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BulgeVertex {
    /// Position, in drawing units.
    pub point: DVec2,
    /// `tan(sweep / 4)` of the segment to the next vertex; 0 for a straight segment.
    pub bulge: f64,
}

impl BulgeVertex {
    /// A vertex whose outgoing segment is straight.
    pub fn straight(point: DVec2) -> Self {
        Self { point, bulge: 0.0 }
    }
}

/// The circle carrying an arc segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BulgeArc {
    /// Centre of the circle, in drawing units.
    pub center: DVec2,
    /// Radius, in drawing units (positive).
    pub radius: f64,
    /// Angle of the start point seen from the centre, in radians.
    pub start_angle: f64,
    /// Signed angle swept from the start to the end point, in radians (positive counter-clockwise).
    pub sweep: f64,
}

impl BulgeArc {
    /// The circle through `start` and `end` that a segment of the given bulge follows, or `None` for
    /// a straight segment or a segment of zero length.
    pub fn from_segment(start: DVec2, end: DVec2, bulge: f64) -> Option<Self> {
        let chord = end - start;
        let chord_length = chord.length();
        if bulge.abs() < STRAIGHT_BULGE || chord_length <= f64::EPSILON {
            return None;
        }
        let sweep = 4.0 * bulge.atan();
        let left_normal = chord.perp() / chord_length;
        // Distance from the chord midpoint to the centre, signed towards the left of the chord.
        let offset = chord_length * (1.0 - bulge * bulge) / (4.0 * bulge);
        let center = (start + end) * 0.5 + left_normal * offset;
        let radius = (start - center).length();
        let start_offset = start - center;
        Some(Self {
            center,
            radius,
            start_angle: start_offset.y.atan2(start_offset.x),
            sweep,
        })
    }

    /// The point at fraction `t` (0 = start, 1 = end) of the arc.
    pub fn point_at(&self, t: f64) -> DVec2 {
        let angle = self.start_angle + self.sweep * t;
        self.center + self.radius * DVec2::new(angle.cos(), angle.sin())
    }

    /// Fraction of the sweep at which the ray from the centre through `point` crosses the arc's
    /// circle, in [0, 2π / |sweep|).
    fn fraction_of(&self, point: DVec2) -> f64 {
        let offset = point - self.center;
        let angle = offset.y.atan2(offset.x) - self.start_angle;
        let turned = (angle * self.sweep.signum()).rem_euclid(std::f64::consts::TAU);
        turned / self.sweep.abs()
    }

    /// Length of the arc, in drawing units.
    pub fn length(&self) -> f64 {
        self.radius * self.sweep.abs()
    }
}

/// Distance from `point` to the segment from `start` to `end` with the given bulge.
pub fn distance_to_segment(point: DVec2, start: DVec2, end: DVec2, bulge: f64) -> f64 {
    match BulgeArc::from_segment(start, end, bulge) {
        Some(arc) if arc.fraction_of(point) <= 1.0 => {
            ((point - arc.center).length() - arc.radius).abs()
        }
        Some(_) => point.distance(start).min(point.distance(end)),
        None => distance_to_line_segment(point, start, end),
    }
}

pub use crate::geometry::distance_to_segment as distance_to_line_segment;

/// Smallest axis-aligned box (lower and upper corner) holding the segment from `start` to `end`
/// with the given bulge: its end points and, for an arc, the circle's extreme points it passes.
pub fn segment_bounds(start: DVec2, end: DVec2, bulge: f64) -> (DVec2, DVec2) {
    let (mut low, mut high) = (start.min(end), start.max(end));
    if let Some(arc) = BulgeArc::from_segment(start, end, bulge) {
        for quarter in 0..4 {
            let extreme =
                arc.center + arc.radius * DVec2::from_angle(f64::from(quarter) * FRAC_PI_2);
            if arc.fraction_of(extreme) <= 1.0 {
                (low, high) = (low.min(extreme), high.max(extreme));
            }
        }
    }
    (low, high)
}

/// Smallest axis-aligned box (lower and upper corner) holding a bulge polyline, closed or open;
/// `None` when it has no vertex.
pub fn polyline_bounds(vertices: &[BulgeVertex], closed: bool) -> Option<(DVec2, DVec2)> {
    let first = vertices.first()?;
    let segments = if closed {
        vertices.len()
    } else {
        vertices.len() - 1
    };
    Some(
        (0..segments).fold((first.point, first.point), |(low, high), index| {
            let (vertex, next) = (vertices[index], vertices[(index + 1) % vertices.len()]);
            let (segment_low, segment_high) =
                segment_bounds(vertex.point, next.point, vertex.bulge);
            (low.min(segment_low), high.max(segment_high))
        }),
    )
}

/// Length of the segment from `start` to `end` with the given bulge (arc length for an arc).
pub fn segment_length(start: DVec2, end: DVec2, bulge: f64) -> f64 {
    BulgeArc::from_segment(start, end, bulge)
        .map_or_else(|| start.distance(end), |arc| arc.length())
}

/// Points along the segment from `start` to `end`, `start` included and `end` excluded, no two
/// further apart than `max_step` along the curve (a straight segment gives `start` alone).
pub fn sample_segment(start: DVec2, end: DVec2, bulge: f64, max_step: f64) -> Vec<DVec2> {
    let Some(arc) = BulgeArc::from_segment(start, end, bulge) else {
        return vec![start];
    };
    let steps = (arc.length() / max_step).ceil().max(1.0) as usize;
    (0..steps)
        .map(|step| arc.point_at(step as f64 / steps as f64))
        .collect()
}

/// The length of a closed bulge polyline (its arcs along the arc).
pub fn closed_length(vertices: &[BulgeVertex]) -> f64 {
    let count = vertices.len();
    (0..count)
        .map(|index| {
            let (vertex, next) = (vertices[index], vertices[(index + 1) % count]);
            segment_length(vertex.point, next.point, vertex.bulge)
        })
        .sum()
}

/// Points along a closed bulge polyline, for drawing and measuring: every vertex, and points on
/// arcs no further apart than `max_step`.
pub fn sample_closed(vertices: &[BulgeVertex], max_step: f64) -> Vec<DVec2> {
    let count = vertices.len();
    (0..count)
        .flat_map(|index| {
            let vertex = vertices[index];
            let next = vertices[(index + 1) % count];
            sample_segment(vertex.point, next.point, vertex.bulge, max_step)
        })
        .collect()
}

/// Points along a closed bulge polyline: every vertex, and points on arcs close enough that each
/// chord between them stays within `sagitta` of its arc.
pub fn sample_closed_within(vertices: &[BulgeVertex], sagitta: f64) -> Vec<DVec2> {
    let count = vertices.len();
    (0..count)
        .flat_map(|index| {
            let (vertex, next) = (vertices[index], vertices[(index + 1) % count]);
            let max_step = BulgeArc::from_segment(vertex.point, next.point, vertex.bulge)
                .map_or(f64::INFINITY, |arc| {
                    arc.radius * 2.0 * (1.0 - sagitta / arc.radius).clamp(-1.0, 1.0).acos()
                });
            sample_segment(vertex.point, next.point, vertex.bulge, max_step)
        })
        .collect()
}

/// Points along an open bulge polyline (the last vertex's bulge is ignored), its end included.
pub fn sample_open(vertices: &[BulgeVertex], max_step: f64) -> Vec<DVec2> {
    let mut points: Vec<DVec2> = vertices
        .windows(2)
        .flat_map(|pair| sample_segment(pair[0].point, pair[1].point, pair[0].bulge, max_step))
        .collect();
    points.extend(vertices.last().map(|vertex| vertex.point));
    points
}

#[cfg(test)]
mod tests {
    use crate::pattern::bulge::*;

    #[test]
    fn half_circle_has_bulge_one_and_centre_on_chord() {
        let arc = BulgeArc::from_segment(DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0), 1.0);
        let arc = arc.expect("a bulge of 1 is an arc");
        assert!(arc.center.length() < 1e-12);
        assert!((arc.radius - 1.0).abs() < 1e-12);
        // Counter-clockwise from (-1, 0) to (1, 0) passes below the chord.
        assert!((arc.point_at(0.5) - DVec2::new(0.0, -1.0)).length() < 1e-12);
    }

    #[test]
    fn quarter_circle_distance_and_length() {
        let bulge = (FRAC_PI_2 / 4.0).tan();
        let start = DVec2::new(1.0, 0.0);
        let end = DVec2::new(0.0, 1.0);
        let length = segment_length(start, end, bulge);
        assert!((length - FRAC_PI_2).abs() < 1e-12);
        let on_arc = DVec2::new(0.5_f64.sqrt(), 0.5_f64.sqrt());
        assert!(distance_to_segment(on_arc, start, end, bulge) < 1e-12);
        assert!((distance_to_segment(DVec2::ZERO, start, end, bulge) - 1.0).abs() < 1e-12);
        assert!(
            (distance_to_segment(DVec2::new(2.0, -1.0), start, end, bulge) - 2.0_f64.sqrt()).abs()
                < 1e-12
        );
    }

    #[test]
    fn bounds_include_the_arc_extremes() {
        // Half circle of radius 1 below the chord from (-1, 0) to (1, 0).
        let (low, high) = segment_bounds(DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0), 1.0);
        assert!(
            low.distance(DVec2::new(-1.0, -1.0)) < 1e-12
                && high.distance(DVec2::new(1.0, 0.0)) < 1e-12
        );
        let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y].map(BulgeVertex::straight);
        assert_eq!(
            polyline_bounds(&square, true),
            Some((DVec2::ZERO, DVec2::ONE))
        );
        assert_eq!(polyline_bounds(&[], false), None);
    }

    #[test]
    fn sagitta_bounded_samples_stay_close_to_the_arc() {
        let semicircle = [
            BulgeVertex {
                point: DVec2::new(-10.0, 0.0),
                bulge: 1.0,
            },
            BulgeVertex {
                point: DVec2::new(10.0, 0.0),
                bulge: 0.0,
            },
        ];
        let points = sample_closed_within(&semicircle, 0.01);
        let arc_points = &points[..points.len() - 1];
        for pair in arc_points.windows(2) {
            let middle = (pair[0] + pair[1]) * 0.5;
            assert!(10.0 - middle.length() <= 0.01 + 1e-12);
        }
        // 2 acos(1 - 0.01 / 10) = 0.0894 rad per step: 36 steps over the half circle.
        assert_eq!(arc_points.len(), 36);
    }

    #[test]
    fn a_closed_length_follows_the_arcs() {
        let square = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]
            .map(|(x, y)| BulgeVertex::straight(DVec2::new(x, y)));
        assert!((closed_length(&square) - 8.0).abs() < 1e-12);
        // Two half circles of radius 1: a full circle.
        let circle = [(-1.0, 0.0), (1.0, 0.0)].map(|(x, y)| BulgeVertex {
            bulge: 1.0,
            ..BulgeVertex::straight(DVec2::new(x, y))
        });
        assert!((closed_length(&circle) - std::f64::consts::TAU).abs() < 1e-12);
    }

    #[test]
    fn straight_segment_samples_to_its_start() {
        assert_eq!(
            sample_segment(DVec2::ZERO, DVec2::X, 0.0, 0.1),
            vec![DVec2::ZERO]
        );
    }
}
