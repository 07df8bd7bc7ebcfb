//! Profiles of lines and arcs built from their spec and checked: no zero-length segment, arcs'
//! ends on their circle, no crossing or touching itself, a revolution profile off the far side
//! of its axis.

use std::f64::consts::{PI, TAU};

use glam::DVec2;

use super::checks::check;
use super::errors::SpecDefect;
use super::spec::ProfileSegmentSpec;
use crate::cad::{Profile, ProfileSegment};
use crate::geometry::distance_to_segment;
use crate::geometry::tolerance::GEOMETRY_TOLERANCE;

/// A profile of lines and arcs, checked: no zero-length segment, arcs' ends on their circle.
pub fn build_profile(
    start: [f64; 2],
    segments: &[ProfileSegmentSpec],
) -> Result<Profile, SpecDefect> {
    check(
        !segments.is_empty(),
        "profile",
        "needs at least one segment",
    )?;
    let mut from = DVec2::from_array(start);
    check(from.is_finite(), "start", "must be finite numbers")?;
    let size = segments
        .iter()
        .map(|s| DVec2::from_array(s.to).distance(from))
        .fold(0.0, f64::max);
    let mut built = Vec::with_capacity(segments.len());
    for (index, segment) in segments.iter().enumerate() {
        let field = format!("profile[{index}]");
        let to = DVec2::from_array(segment.to);
        let length = from.distance(to);
        check(
            to.is_finite() && length > GEOMETRY_TOLERANCE * size,
            &field,
            format!("the segment has (almost) zero length ({length}) or a non-finite end point"),
        )?;
        built.push(match segment.center {
            None => {
                check(segment.clockwise.is_none(), &field, "'clockwise' needs a 'center'")?;
                ProfileSegment::Line { to }
            }
            Some(center) => {
                let center = DVec2::from_array(center);
                let radius = from.distance(center);
                check(
                    radius > 0.0 && (to.distance(center) - radius).abs() <= GEOMETRY_TOLERANCE * radius.max(1.0),
                    &format!("{field}.center"),
                    format!(
                        "the arc's ends are {radius} and {} from its centre; they must be equally far",
                        to.distance(center)
                    ),
                )?;
                // The ends differ, so the shorter way turns by a non-zero angle in (-π, π].
                let mut sweep = (from - center).angle_to(to - center);
                check(
                    segment.clockwise.is_some()
                        || (sweep.abs() - PI).abs() > GEOMETRY_TOLERANCE,
                    &format!("{field}.clockwise"),
                    "the arc is a half circle, so it has no shorter way round: add clockwise = true or false",
                )?;
                match segment.clockwise {
                    Some(true) if sweep > 0.0 => sweep -= TAU,
                    Some(false) if sweep < 0.0 => sweep += TAU,
                    _ => {}
                }
                ProfileSegment::Arc { to, center, sweep }
            }
        });
        from = to;
    }
    let profile = Profile {
        start: DVec2::from_array(start),
        segments: built,
    };
    check_simple_profile(&profile)?;
    Ok(profile)
}

/// Pieces per arc when a profile is checked for crossing itself or the axis.
const PROFILE_CHECK_PIECES: usize = 64;

/// The profile as a polyline: its points, for each piece (between points `k` and `k + 1`) the
/// index of the segment it belongs to, and the geometry tolerance at the profile's size.
fn profile_polyline(profile: &Profile) -> (Vec<DVec2>, Vec<usize>, f64) {
    let mut points = vec![profile.start];
    let mut segment_of_piece = Vec::new();
    for (index, segment) in profile.segments.iter().enumerate() {
        let from = *points
            .last()
            .expect("the polyline starts with the profile's start");
        let single = Profile {
            start: from,
            segments: vec![*segment],
        };
        let sampled = match *segment {
            ProfileSegment::Line { to } => vec![from, to],
            ProfileSegment::Arc { .. } => {
                single.sample(single.length() / PROFILE_CHECK_PIECES as f64, f64::INFINITY)
            }
        };
        segment_of_piece.extend(std::iter::repeat_n(index, sampled.len() - 1));
        points.extend(&sampled[1..]);
    }
    let size = points
        .iter()
        .map(|p| p.distance(profile.start))
        .fold(0.0, f64::max);
    (points, segment_of_piece, GEOMETRY_TOLERANCE * size)
}

/// Checks that a profile neither crosses nor touches itself (a closed profile only at its start)
/// and never turns straight back over itself.
pub fn check_simple_profile(profile: &Profile) -> Result<(), SpecDefect> {
    let (points, segment_of_piece, tolerance) = profile_polyline(profile);
    let closed = profile.is_closed(tolerance);
    let pieces = points.len() - 1;
    let crossing = |i: usize, j: usize| {
        let adjacent = j == i + 1 || (closed && i == 0 && j == pieces - 1);
        let touching =
            segment_distance((points[i], points[i + 1]), (points[j], points[j + 1])) <= tolerance;
        let turns_back = j == i + 1 && {
            let (a, b) = (points[i + 1] - points[i], points[j + 1] - points[j]);
            a.dot(b) < 0.0 && a.perp_dot(b).abs() <= GEOMETRY_TOLERANCE * a.length() * b.length()
        };
        (!adjacent && touching) || turns_back
    };
    for i in 0..pieces {
        if let Some(j) = (i + 1..pieces).find(|&j| crossing(i, j)) {
            let (first, second) = (segment_of_piece[i], segment_of_piece[j]);
            let what = if first == second {
                format!("segment {first} runs back over itself")
            } else {
                format!("segments {first} and {second} cross or touch")
            };
            return Err(SpecDefect::new(
                "profile",
                format!("the profile crosses itself: {what}"),
            ));
        }
    }
    Ok(())
}

/// The distance between two line segments in the plane (0 when they cross).
fn segment_distance(a: (DVec2, DVec2), b: (DVec2, DVec2)) -> f64 {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let crosses = side(b.0, b.1, a.0) * side(b.0, b.1, a.1) < 0.0
        && side(a.0, a.1, b.0) * side(a.0, a.1, b.1) < 0.0;
    if crosses {
        return 0.0;
    }
    [
        distance_to_segment(a.0, b.0, b.1),
        distance_to_segment(a.1, b.0, b.1),
        distance_to_segment(b.0, a.0, a.1),
        distance_to_segment(b.1, a.0, a.1),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min)
}

/// Checks that a revolution profile stays off the far side of the axis and meets the axis only
/// at its ends (a pole); a stretch on the axis, or a touch between the ends, would pinch the
/// surface to a point.
pub fn check_profile_off_axis(profile: &Profile) -> Result<(), SpecDefect> {
    let (points, segment_of_piece, tolerance) = profile_polyline(profile);
    let last = points.len() - 1;
    let on_axis = (1..last).find(|&k| points[k].x <= tolerance);
    let beyond = (0..=last).find(|&k| points[k].x < -tolerance);
    match (beyond, on_axis) {
        (Some(k), _) => Err(SpecDefect::new(
            format!("profile[{}]", segment_of_piece[k.min(last - 1)]),
            "the profile crosses the axis (a negative radius); keep every point at radius >= 0",
        )),
        (None, Some(k)) => Err(SpecDefect::new(
            format!("profile[{}]", segment_of_piece[k - 1]),
            "the profile meets the axis between its ends, where the surface would pinch to a point; \
             only its first and last points may lie on the axis (radius 0)",
        )),
        (None, None) => Ok(()),
    }
}
