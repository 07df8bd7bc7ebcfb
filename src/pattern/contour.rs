//! Contour fitting: a dense polyline (a mesh boundary, thousands of points, many collinear or on
//! circular arcs) becomes a short polyline of straight segments and true arcs (bulges) that stays
//! within a chord tolerance of it.
//!
//! Input: points in drawing units, a closed ring (the closing point may or may not repeat the first)
//! or an open chain. Output: [`BulgeVertex`]es; for a closed ring the last vertex's segment closes
//! it, for an open chain the last vertex carries bulge 0.
//!
//! Method, greedy and verified:
//! 1. Points closer than [`DUPLICATE_FRACTION`] of the tolerance to the previous point are dropped
//!    (no zero-length segments); the fit then works within the tolerance minus that distance.
//! 2. A closed ring is opened at its sharpest corner, so that arcs and lines end at real corners.
//! 3. From each breakpoint the longest run of points is taken (doubling, then bisection) that one
//!    primitive fits: a straight segment if every point lies within the tolerance of it, else the
//!    circular arc through the run's first, middle and last points if every point and every chord
//!    midpoint lies within the tolerance of the arc, the points advance monotonically along it and
//!    it sweeps at most [`MAX_ARC_SWEEP`].
//! 4. A segment shorter than [`MIN_SEGMENT_LENGTH_IN_TOLERANCES`] tolerances is merged into a
//!    neighbour when the merged primitive still fits; what remains short is a real feature.
//! 5. On a closed ring the last and first primitives are merged across the opening point when one
//!    primitive fits both.
//!
//! A full circle (a drilled hole) comes out as two arcs; a cone's development (an annular sector)
//! as two arcs and two lines.

use super::bulge::BulgeVertex;
use glam::DVec2;
use std::f64::consts::PI;

/// Default chord tolerance, in mm: the largest distance allowed between the input polyline and the
/// fitted contour.
pub const DEFAULT_CHORD_TOLERANCE: f64 = 0.01;

/// Points closer together than this fraction of the chord tolerance are one point.
pub const DUPLICATE_FRACTION: f64 = 1e-3;

/// A fitted segment shorter than this many chord tolerances (0.05 mm at the default) is merged
/// into a neighbour unless that would leave the tolerance (a real corner).
pub const MIN_SEGMENT_LENGTH_IN_TOLERANCES: f64 = 5.0;

/// Largest angle one fitted arc may sweep, in radians (225°): a full circle needs two arcs, and
/// arcs stay well away from the degenerate full turn.
pub const MAX_ARC_SWEEP: f64 = 1.25 * PI;

/// Cross product below which three points are collinear, relative to the squared span.
const COLLINEAR_RATIO: f64 = 1e-12;

/// A primitive covering input points `start..=end` of the working chain.
#[derive(Debug, Clone, Copy)]
struct Span {
    start: usize,
    end: usize,
    bulge: f64,
}

/// Fits a closed ring. Returns `None` when the ring has fewer than three distinct points or no
/// area. The result keeps the ring's orientation.
///
/// ```
/// use flatcut::pattern::{DEFAULT_CHORD_TOLERANCE, fit_closed};
/// use glam::DVec2;
///
/// // A hole of radius 5 mm sampled with 720 points comes out as two true arcs.
/// let ring: Vec<DVec2> =
///     (0..720).map(|step| 5.0 * DVec2::from_angle(step as f64 * std::f64::consts::TAU / 720.0)).collect();
/// let fitted = fit_closed(&ring, DEFAULT_CHORD_TOLERANCE).expect("a valid ring");
/// assert_eq!(fitted.len(), 2);
/// assert!(fitted.iter().all(|vertex| vertex.bulge > 0.0));
/// ```
pub fn fit_closed(ring: &[DVec2], tolerance: f64) -> Option<Vec<BulgeVertex>> {
    let duplicate = tolerance * DUPLICATE_FRACTION;
    let mut points = remove_duplicates(ring, duplicate);
    while points.len() > 1 && points[0].distance(points[points.len() - 1]) < duplicate {
        points.pop();
    }
    if points.len() < 3 || signed_area(&points).abs() <= duplicate * duplicate {
        return None;
    }
    let corner = sharpest_corner(&points);
    points.rotate_left(corner);
    points.push(points[0]);
    let fit_tolerance = tolerance - duplicate;
    let spans = merge_short_spans(
        &points,
        fit_chain(&points, fit_tolerance),
        tolerance,
        fit_tolerance,
    );
    Some(close_across_opening(&points, spans, fit_tolerance))
}

/// Fits an open chain. Returns `None` when it has fewer than two distinct points.
pub fn fit_open(chain: &[DVec2], tolerance: f64) -> Option<Vec<BulgeVertex>> {
    let duplicate = tolerance * DUPLICATE_FRACTION;
    let points = remove_duplicates(chain, duplicate);
    let last = *points.last()?;
    if points.len() < 2 {
        return None;
    }
    let fit_tolerance = tolerance - duplicate;
    let spans = merge_short_spans(
        &points,
        fit_chain(&points, fit_tolerance),
        tolerance,
        fit_tolerance,
    );
    let mut vertices: Vec<BulgeVertex> = spans
        .iter()
        .map(|span| BulgeVertex {
            point: points[span.start],
            bulge: span.bulge,
        })
        .collect();
    vertices.push(BulgeVertex::straight(last));
    Some(vertices)
}

pub use crate::geometry::signed_area;

/// The points with every point closer than `duplicate` to the last kept one removed.
fn remove_duplicates(points: &[DVec2], duplicate: f64) -> Vec<DVec2> {
    let mut kept: Vec<DVec2> = Vec::with_capacity(points.len());
    for &point in points {
        if kept
            .last()
            .is_none_or(|last| last.distance(point) >= duplicate)
        {
            kept.push(point);
        }
    }
    kept
}

/// Index of the ring point where the outline turns most sharply (the first one on a tie).
fn sharpest_corner(ring: &[DVec2]) -> usize {
    let count = ring.len();
    let turn = |index: usize| {
        let incoming = (ring[index] - ring[(index + count - 1) % count]).normalize_or_zero();
        let outgoing = (ring[(index + 1) % count] - ring[index]).normalize_or_zero();
        1.0 - incoming.dot(outgoing)
    };
    (1..count).fold(0, |best, index| {
        if turn(index) > turn(best) {
            index
        } else {
            best
        }
    })
}

/// Greedy fit of the whole chain into maximal spans.
fn fit_chain(points: &[DVec2], tolerance: f64) -> Vec<Span> {
    let mut spans = Vec::new();
    let mut start = 0;
    while start + 1 < points.len() {
        let span = longest_span(points, start, tolerance);
        start = span.end;
        spans.push(span);
    }
    spans
}

/// The longest span from `start` that one primitive fits: doubling the run, then bisection.
fn longest_span(points: &[DVec2], start: usize, tolerance: f64) -> Span {
    let last = points.len() - 1;
    let mut best = Span {
        start,
        end: start + 1,
        bulge: 0.0,
    };
    let mut failed = None;
    let mut run = 2;
    while best.end < last {
        let end = (start + run).min(last);
        match fit_span(&points[start..=end], tolerance) {
            Some(bulge) => best = Span { start, end, bulge },
            None if run <= MIN_SAMPLED_CHORDS => {
                // Too short to be taken for a sampled arc: try a run that is long enough.
                run = MIN_SAMPLED_CHORDS + 1;
                continue;
            }
            None => {
                failed = Some(end);
                break;
            }
        }
        run *= 2;
    }
    if let Some(mut bad) = failed {
        while bad - best.end > 1 {
            let middle = (best.end + bad) / 2;
            match fit_span(&points[start..=middle], tolerance) {
                Some(bulge) => {
                    best = Span {
                        start,
                        end: middle,
                        bulge,
                    }
                }
                None => bad = middle,
            }
        }
    }
    best
}

/// The bulge of one primitive through all `points` (0 for a straight segment), or `None` when no
/// straight segment or arc fits them within `tolerance`.
fn fit_span(points: &[DVec2], tolerance: f64) -> Option<f64> {
    let first = *points.first()?;
    let last = *points.last()?;
    if first.distance(last) <= tolerance * DUPLICATE_FRACTION {
        return None;
    }
    if line_fits(points, tolerance) {
        return Some(0.0);
    }
    arc_bulge(points, tolerance)
}

/// Whether every point lies within `tolerance` of the segment from the first to the last point.
fn line_fits(points: &[DVec2], tolerance: f64) -> bool {
    let (first, last) = (points[0], points[points.len() - 1]);
    points[1..points.len() - 1]
        .iter()
        .all(|&point| super::bulge::distance_to_line_segment(point, first, last) <= tolerance)
}

/// The largest angle one chord of a sampled arc may subtend (15°): a boundary polyline whose
/// vertices lie on a circle, in chords this short, is that circle sampled by a mesh, not a
/// polygon (a hexagon's chords subtend 60°, a 16-gon's 22.5°).
pub const MAX_SAMPLED_CHORD_ANGLE: f64 = PI / 12.0;

/// The fewest chords a run needs before it is taken for a sampled arc.
pub const MIN_SAMPLED_CHORDS: usize = 4;

/// A chord of a sampled arc is at most this many times the run's median chord: a mesh samples
/// an arc in chords of about one length, and a much longer chord is a straight edge that meets
/// the arc (a flange's side running into a conical bend's developed arc), not a sample of it.
pub const MAX_SAMPLED_CHORD_SPREAD: f64 = 3.0;

/// The median length of the chords between consecutive points.
fn median_chord(points: &[DVec2]) -> f64 {
    let mut lengths: Vec<f64> = points
        .windows(2)
        .map(|pair| pair[0].distance(pair[1]))
        .collect();
    lengths.sort_unstable_by(f64::total_cmp);
    lengths.get(lengths.len() / 2).copied().unwrap_or(0.0)
}

/// The bulge of the arc through the first, middle and last points, if it fits every point
/// within `tolerance`, visits the points in order and sweeps at most [`MAX_ARC_SWEEP`], and every
/// chord either has its midpoint within `tolerance` of the arc or is a chord of the arc itself
/// (a sampled arc: see [`MAX_SAMPLED_CHORD_ANGLE`] and [`MAX_SAMPLED_CHORD_SPREAD`]). A mesh boundary samples the true curve at
/// its vertices; the arc through them is the true development, closer to it than the chords.
fn arc_bulge(points: &[DVec2], tolerance: f64) -> Option<f64> {
    let first = points[0];
    let middle = points[points.len() / 2];
    let last = points[points.len() - 1];
    let (center, radius) = circle_through(first, middle, last)?;
    let direction = (middle - first).perp_dot(last - middle).signum();
    let turned = |point: DVec2| {
        let (from, to) = (first - center, point - center);
        (direction * from.perp_dot(to).atan2(from.dot(to))).rem_euclid(std::f64::consts::TAU)
    };
    let sweep = turned(last);
    if sweep > MAX_ARC_SWEEP {
        return None;
    }
    let on_circle = |point: DVec2| ((point - center).length() - radius).abs() <= tolerance;
    let sampled = points.len() > MIN_SAMPLED_CHORDS;
    let longest_sample = if sampled {
        MAX_SAMPLED_CHORD_SPREAD * median_chord(points)
    } else {
        0.0
    };
    let chord_of_arc = |start: DVec2, end: DVec2| {
        let half = start.distance(end) / 2.0;
        let subtended = 2.0 * (half / radius).min(1.0).asin();
        let chord_distance = (radius * radius - half * half).max(0.0).sqrt();
        let midpoint_distance = ((start + end) * 0.5 - center).length();
        sampled
            && 2.0 * half <= longest_sample
            && subtended <= MAX_SAMPLED_CHORD_ANGLE
            && (midpoint_distance - chord_distance).abs() <= tolerance
    };
    let angular_slack = tolerance / radius;
    let mut previous = 0.0;
    for pair in points.windows(2) {
        let angle = turned(pair[1]);
        let in_order = angle + angular_slack >= previous && angle <= sweep + angular_slack;
        let chord_fits = on_circle((pair[0] + pair[1]) * 0.5) || chord_of_arc(pair[0], pair[1]);
        if !in_order || !on_circle(pair[1]) || !chord_fits {
            return None;
        }
        previous = angle;
    }
    Some(direction * (sweep / 4.0).tan())
}

/// Centre and radius of the circle through three points, or `None` when they are collinear.
fn circle_through(first: DVec2, middle: DVec2, last: DVec2) -> Option<(DVec2, f64)> {
    let (to_middle, to_last) = (middle - first, last - first);
    let cross = to_middle.perp_dot(to_last);
    if cross.abs() <= COLLINEAR_RATIO * to_last.length_squared().max(to_middle.length_squared()) {
        return None;
    }
    let center_offset = (to_middle.length_squared() * to_last.perp()
        - to_last.length_squared() * to_middle.perp())
        / (2.0 * cross);
    let center = first - center_offset;
    Some((center, center_offset.length()))
}

/// Merges every span shorter than the minimum segment length into a neighbour where one
/// primitive still fits the merged points.
fn merge_short_spans(
    points: &[DVec2],
    mut spans: Vec<Span>,
    tolerance: f64,
    fit_tolerance: f64,
) -> Vec<Span> {
    let minimum = tolerance * MIN_SEGMENT_LENGTH_IN_TOLERANCES;
    let mut index = 0;
    while index < spans.len() {
        let span = spans[index];
        let short = super::bulge::segment_length(points[span.start], points[span.end], span.bulge)
            < minimum;
        if short
            && spans.len() > 1
            && let Some((first, merged)) =
                merge_with_neighbour(points, &spans, index, fit_tolerance)
        {
            spans[first] = merged;
            spans.remove(first + 1);
            index = first;
            continue;
        }
        index += 1;
    }
    spans
}

/// The merge of span `index` with its previous or else its next neighbour, as the position of
/// the first span of the merged pair and the span replacing the pair; `None` when neither merge
/// fits.
fn merge_with_neighbour(
    points: &[DVec2],
    spans: &[Span],
    index: usize,
    tolerance: f64,
) -> Option<(usize, Span)> {
    let merge = |first: usize| {
        let (from, to) = (spans.get(first)?, spans.get(first + 1)?);
        let bulge = fit_span(&points[from.start..=to.end], tolerance)?;
        Some((
            first,
            Span {
                start: from.start,
                end: to.end,
                bulge,
            },
        ))
    };
    index
        .checked_sub(1)
        .and_then(merge)
        .or_else(|| merge(index))
}

/// The vertices of a closed ring's spans, with the last and first spans merged into one across
/// the opening point when a single primitive fits both.
fn close_across_opening(points: &[DVec2], spans: Vec<Span>, tolerance: f64) -> Vec<BulgeVertex> {
    let vertex = |span: &Span| BulgeVertex {
        point: points[span.start],
        bulge: span.bulge,
    };
    let mut vertices: Vec<BulgeVertex> = spans.iter().map(vertex).collect();
    if let [first, .., last] = spans.as_slice()
        && spans.len() > 2
    {
        let joined: Vec<DVec2> = points[last.start..]
            .iter()
            .chain(&points[1..=first.end])
            .copied()
            .collect();
        if let Some(bulge) = fit_span(&joined, tolerance) {
            vertices.remove(0);
            if let Some(closing) = vertices.last_mut() {
                closing.bulge = bulge;
            }
        }
    }
    vertices
}

#[cfg(test)]
mod tests {
    use crate::pattern::bulge::{BulgeArc, distance_to_segment, sample_closed};
    use crate::pattern::contour::*;
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, TAU};

    /// Distance from `point` to a closed fitted contour.
    fn distance_to_closed(point: DVec2, vertices: &[BulgeVertex]) -> f64 {
        let count = vertices.len();
        (0..count)
            .map(|index| {
                let (vertex, next) = (vertices[index], vertices[(index + 1) % count]);
                distance_to_segment(point, vertex.point, next.point, vertex.bulge)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// `count` points on an arc of `radius` about the origin from `start` sweeping `sweep` radians,
    /// both ends included.
    fn arc_points(radius: f64, start: f64, sweep: f64, count: usize) -> Vec<DVec2> {
        (0..count)
            .map(|step| {
                let angle = start + sweep * step as f64 / (count - 1) as f64;
                radius * DVec2::new(angle.cos(), angle.sin())
            })
            .collect()
    }

    /// `count` points along a straight segment, both ends excluded.
    fn line_points(from: DVec2, to: DVec2, count: usize) -> Vec<DVec2> {
        (1..=count)
            .map(|step| from.lerp(to, step as f64 / (count + 1) as f64))
            .collect()
    }

    /// An annular sector (a cone frustum's development), counter-clockwise, 400 points per arc.
    fn cone_development(inner: f64, outer: f64, angle: f64) -> Vec<DVec2> {
        let mut ring = arc_points(outer, 0.0, angle, 400);
        let outer_end = ring[ring.len() - 1];
        let inner_start = inner * DVec2::new(angle.cos(), angle.sin());
        ring.extend(line_points(outer_end, inner_start, 50));
        let mut inner_arc = arc_points(inner, 0.0, angle, 400);
        inner_arc.reverse();
        ring.extend(inner_arc);
        ring.extend(line_points(
            DVec2::new(inner, 0.0),
            DVec2::new(outer, 0.0),
            50,
        ));
        ring
    }

    /// Largest distance from the fitted sector to the analytic one: samples of the fitted contour
    /// measured to the nearest of the two circles and two radial lines.
    fn deviation_from_sector(vertices: &[BulgeVertex], inner: f64, outer: f64, angle: f64) -> f64 {
        let edge = DVec2::new(angle.cos(), angle.sin());
        sample_closed(vertices, 0.05)
            .into_iter()
            .map(|point| {
                let to_circles = (point.length() - inner)
                    .abs()
                    .min((point.length() - outer).abs());
                let to_start = crate::pattern::bulge::distance_to_line_segment(
                    point,
                    DVec2::X * inner,
                    DVec2::X * outer,
                );
                let to_end = crate::pattern::bulge::distance_to_line_segment(
                    point,
                    edge * inner,
                    edge * outer,
                );
                to_circles.min(to_start).min(to_end)
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn coarsely_meshed_cone_development_is_still_true_arcs() {
        // A mesh boundary: 25 chords per arc (6.4° each, sagitta 0.35 mm), vertices on the circles.
        let (inner, outer, angle) = (111.8, 223.6, 2.81);
        let mut ring = arc_points(outer, 0.0, angle, 26);
        let mut inner_arc = arc_points(inner, 0.0, angle, 26);
        inner_arc.reverse();
        ring.extend(inner_arc);
        let fitted = fit_closed(&ring, DEFAULT_CHORD_TOLERANCE).expect("fits");
        assert_eq!(fitted.len(), 4, "{fitted:?}");
        assert!(deviation_from_sector(&fitted, inner, outer, angle) <= DEFAULT_CHORD_TOLERANCE);
    }

    #[test]
    fn a_regular_polygon_with_few_sides_stays_a_polygon() {
        let octagon = arc_points(50.0, 0.0, std::f64::consts::TAU * 7.0 / 8.0, 8);
        let fitted = fit_closed(&octagon, DEFAULT_CHORD_TOLERANCE).expect("fits");
        assert!(
            fitted
                .iter()
                .all(|v| v.bulge.abs() < crate::pattern::bulge::STRAIGHT_BULGE),
            "{fitted:?}"
        );
        assert_eq!(fitted.len(), 8);
    }

    #[test]
    fn cone_development_is_four_vertices_of_true_arcs() {
        let (inner, outer, angle): (f64, f64, f64) = (120.0, 300.0, 2.0);
        let fitted = fit_closed(
            &cone_development(inner, outer, angle),
            DEFAULT_CHORD_TOLERANCE,
        )
        .expect("the sector is a valid ring");
        let deviation = deviation_from_sector(&fitted, inner, outer, angle);
        assert!(fitted.len() < 20, "{} vertices", fitted.len());
        assert_eq!(fitted.len(), 4, "{fitted:?}");
        assert!(
            deviation <= DEFAULT_CHORD_TOLERANCE,
            "deviation {deviation}"
        );
        let arcs = fitted
            .iter()
            .filter(|vertex| vertex.bulge.abs() > 0.0)
            .count();
        assert_eq!(arcs, 2);
    }

    #[test]
    fn wide_cone_development_splits_arcs_beyond_the_largest_sweep() {
        let (inner, outer, angle): (f64, f64, f64) = (50.0, 400.0, 4.5);
        let fitted = fit_closed(
            &cone_development(inner, outer, angle),
            DEFAULT_CHORD_TOLERANCE,
        )
        .expect("the sector is a valid ring");
        assert!(fitted.len() < 20, "{} vertices", fitted.len());
        assert!(deviation_from_sector(&fitted, inner, outer, angle) <= DEFAULT_CHORD_TOLERANCE);
    }

    #[test]
    fn circle_is_two_arcs() {
        let mut ring = arc_points(5.0, 0.3, TAU, 721);
        ring.pop();
        let fitted = fit_closed(&ring, DEFAULT_CHORD_TOLERANCE).expect("a circle is a valid ring");
        assert_eq!(fitted.len(), 2, "{fitted:?}");
        for (index, vertex) in fitted.iter().enumerate() {
            let next = fitted[(index + 1) % 2];
            let arc =
                BulgeArc::from_segment(vertex.point, next.point, vertex.bulge).expect("an arc");
            assert!(arc.center.length() < 1e-6 && (arc.radius - 5.0).abs() < 1e-6);
        }
    }

    #[test]
    fn rounded_rectangle_is_four_lines_and_four_tangent_arcs() {
        let (width, height, radius) = (200.0, 100.0, 10.0);
        let centres = [
            DVec2::new(width - radius, radius),
            DVec2::new(width - radius, height - radius),
            DVec2::new(radius, height - radius),
            DVec2::new(radius, radius),
        ];
        let mut ring = Vec::new();
        for (corner, centre) in centres.iter().enumerate() {
            let start = (corner as f64 - 1.0) * FRAC_PI_2;
            let mut fillet = arc_points(radius, start, FRAC_PI_2, 100);
            fillet.iter_mut().for_each(|point| *point += *centre);
            let next_centre = centres[(corner + 1) % 4];
            let side_start = fillet[fillet.len() - 1];
            let side_end = next_centre + radius * DVec2::from_angle(start + FRAC_PI_2);
            ring.extend(fillet);
            ring.extend(line_points(side_start, side_end, 99));
        }
        let fitted = fit_closed(&ring, DEFAULT_CHORD_TOLERANCE).expect("a valid ring");
        assert_eq!(fitted.len(), 8, "{fitted:?}");
        assert_eq!(
            fitted
                .iter()
                .filter(|vertex| vertex.bulge.abs() > 0.0)
                .count(),
            4
        );
        for point in &ring {
            assert!(distance_to_closed(*point, &fitted) <= DEFAULT_CHORD_TOLERANCE);
        }
    }

    #[test]
    fn dense_square_keeps_its_four_corners() {
        let corners = [
            DVec2::ZERO,
            DVec2::new(100.0, 0.0),
            DVec2::new(100.0, 100.0),
            DVec2::new(0.0, 100.0),
        ];
        let ring: Vec<DVec2> = (0..4)
            .flat_map(|side| {
                [corners[side]].into_iter().chain(line_points(
                    corners[side],
                    corners[(side + 1) % 4],
                    99,
                ))
            })
            .collect();
        let fitted = fit_closed(&ring, DEFAULT_CHORD_TOLERANCE).expect("a square is a valid ring");
        assert_eq!(fitted.len(), 4);
        assert!(fitted.iter().all(|vertex| vertex.bulge.abs() < 1e-12));
        for corner in corners {
            assert!(
                fitted
                    .iter()
                    .any(|vertex| vertex.point.distance(corner) < 1e-9)
            );
        }
    }

    #[test]
    fn short_step_beyond_the_tolerance_is_kept_as_a_real_feature() {
        let step = 3.0 * DEFAULT_CHORD_TOLERANCE;
        let corners = [
            DVec2::ZERO,
            DVec2::new(50.0, 0.0),
            DVec2::new(50.0, -step),
            DVec2::new(100.0, -step),
            DVec2::new(100.0, 50.0),
            DVec2::new(0.0, 50.0),
        ];
        let ring: Vec<DVec2> = (0..corners.len())
            .flat_map(|side| {
                let (from, to) = (corners[side], corners[(side + 1) % corners.len()]);
                let count = if from.distance(to) > 1.0 { 40 } else { 0 };
                std::iter::once(from).chain(line_points(from, to, count))
            })
            .collect();
        let fitted = fit_closed(&ring, DEFAULT_CHORD_TOLERANCE).expect("a valid ring");
        assert_eq!(fitted.len(), 6, "{fitted:?}");
        let coarse = fit_closed(&ring, 10.0 * DEFAULT_CHORD_TOLERANCE).expect("a valid ring");
        assert_eq!(
            coarse.len(),
            4,
            "within 0.1 mm the step disappears: {coarse:?}"
        );
    }

    #[test]
    fn degenerate_rings_are_refused() {
        assert!(fit_closed(&[DVec2::ZERO, DVec2::X], DEFAULT_CHORD_TOLERANCE).is_none());
        assert!(
            fit_closed(
                &[DVec2::ZERO, DVec2::X, DVec2::X * 2.0],
                DEFAULT_CHORD_TOLERANCE
            )
            .is_none()
        );
        assert!(fit_open(&[DVec2::ZERO, DVec2::ZERO], DEFAULT_CHORD_TOLERANCE).is_none());
    }

    #[test]
    fn open_straight_chain_is_one_segment() {
        let chain: Vec<DVec2> = line_points(DVec2::ZERO, DVec2::new(50.0, 20.0), 30);
        let fitted = fit_open(&chain, DEFAULT_CHORD_TOLERANCE).expect("a valid chain");
        assert_eq!(fitted.len(), 2);
    }

    proptest! {
        /// A wobbly star-shaped ring: fitted within the tolerance of every input point, closed, and
        /// with no zero-length segment.
        #[test]
        fn fitted_ring_stays_within_tolerance(
            radii in proptest::collection::vec(20.0..60.0f64, 5..12),
            samples in 40usize..400,
            wobble in 0.0..0.02f64,
        ) {
            let lobes = radii.len();
            let ring: Vec<DVec2> = (0..samples)
                .map(|step| {
                    let angle = TAU * step as f64 / samples as f64;
                    let lobe = radii[(step * lobes / samples) % lobes];
                    let radius = lobe + wobble * (step as f64 * 1.7).sin();
                    radius * DVec2::new(angle.cos(), angle.sin())
                })
                .collect();
            let fitted = fit_closed(&ring, DEFAULT_CHORD_TOLERANCE).expect("a valid ring");
            prop_assert!(fitted.len() >= 2);
            for point in &ring {
                prop_assert!(distance_to_closed(*point, &fitted) <= DEFAULT_CHORD_TOLERANCE * (1.0 + 1e-9));
            }
            for index in 0..fitted.len() {
                let next = fitted[(index + 1) % fitted.len()];
                prop_assert!(fitted[index].point.distance(next.point) > DEFAULT_CHORD_TOLERANCE * DUPLICATE_FRACTION);
            }
        }
    }
}
