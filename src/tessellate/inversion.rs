//! Point inversion onto a STEP face's surface: a boundary point's parameters by truck's search
//! (a grid search when it fails), refined by Gauss-Newton from the previous point of the loop,
//! periodic parameters unwrapped along the loop.

use std::ops::Bound;

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::Surface as StepSurface;

use super::native::{native_derivatives, native_point};
use crate::geometry::tolerance::{
    BOUNDARY_DEVIATION_RATIO, FOOT_POINT_COSINE, INVERSION_TOLERANCE_RATIO,
};

/// Gauss-Newton steps of a point inversion.
const INVERSION_STEPS: usize = 12;

/// Grid samples per parameter of the fallback search of a point inversion.
const SEARCH_GRID: usize = 24;

/// A boundary point inverted onto the surface failed; the message says where.
#[derive(Debug, Clone, PartialEq)]
pub struct DomainError(pub String);

/// Each parameter's range where evaluation must stay inside it (B-spline and NURBS surfaces, not
/// periodic); `None` elsewhere (elementary surfaces extend beyond their nominal ranges).
pub fn parameter_ranges(
    surface: &StepSurface,
    periods: [Option<f64>; 2],
) -> [Option<(f64, f64)>; 2] {
    if !matches!(
        surface,
        StepSurface::BSplineSurface(_) | StepSurface::NurbsSurface(_)
    ) {
        return [None, None];
    }
    let (u, v) = surface.parameter_range();
    let bounded = |(low, high): (Bound<f64>, Bound<f64>)| match (low, high) {
        (Bound::Included(a) | Bound::Excluded(a), Bound::Included(b) | Bound::Excluded(b)) => {
            Some((a, b))
        }
        _ => None,
    };
    [
        periods[0].map_or(bounded(u), |_| None),
        periods[1].map_or(bounded(v), |_| None),
    ]
}

/// The loop's points in the surface's parameters, periodic parameters unwrapped along the loop.
pub fn invert_loop(
    surface: &StepSurface,
    points: &[DVec3],
    periods: [Option<f64>; 2],
    ranges: [Option<(f64, f64)>; 2],
    size: f64,
) -> Result<Vec<DVec2>, DomainError> {
    let tolerance = INVERSION_TOLERANCE_RATIO * size.max(f64::MIN_POSITIVE);
    let deviation = BOUNDARY_DEVIATION_RATIO * size.max(f64::MIN_POSITIVE);
    let mut native: Vec<DVec2> = Vec::with_capacity(points.len());
    for &point in points {
        let previous = native.last().copied();
        let off = |p: DVec2| native_point(surface, p).distance(point);
        let guess = previous
            .map(|p| refine_inversion(surface, point, p, ranges))
            .filter(|&p| off(p) <= tolerance)
            .or_else(|| global_inversion(surface, point, periods, ranges))
            .filter(|&p| {
                off(p) <= tolerance || is_foot_within(surface, point, p, ranges, deviation)
            })
            .ok_or_else(|| off_surface_error(surface, point, periods, ranges, deviation))?;
        native.push(match previous {
            Some(previous) => unwrap_near(guess, previous, periods),
            None => guess,
        });
    }
    Ok(native)
}

/// Whether `parameters` are a foot point of `point` on the surface (the residual along the
/// surface's normal: its cosine with each tangent at most [`FOOT_POINT_COSINE`]; along a bounded
/// parameter at its bound, the patch's side, only the other tangent counts) at most `deviation`
/// away: an edge an exporter wrote slightly off its face's surface.
fn is_foot_within(
    surface: &StepSurface,
    point: DVec3,
    parameters: DVec2,
    ranges: [Option<(f64, f64)>; 2],
    deviation: f64,
) -> bool {
    let residual = point - native_point(surface, parameters);
    let distance = residual.length();
    if distance.is_nan() || distance > deviation {
        return false;
    }
    let (su, sv) = native_derivatives(surface, parameters);
    let at_bound = |value: f64, range: Option<(f64, f64)>| {
        range.is_some_and(|(low, high)| value <= low || value >= high)
    };
    [
        (su, at_bound(parameters.x, ranges[0])),
        (sv, at_bound(parameters.y, ranges[1])),
    ]
    .iter()
    .all(|&(tangent, bounded)| {
        let length = tangent.length() * distance;
        bounded || (length > 0.0 && residual.dot(tangent).abs() <= FOOT_POINT_COSINE * length)
    })
}

/// The error for a boundary point off its face's surface, with the distance to the nearest
/// surface point found and the largest deviation accepted.
fn off_surface_error(
    surface: &StepSurface,
    point: DVec3,
    periods: [Option<f64>; 2],
    ranges: [Option<(f64, f64)>; 2],
    deviation: f64,
) -> DomainError {
    let distance = global_inversion(surface, point, periods, ranges)
        .map(|p| native_point(surface, p).distance(point))
        .filter(|d| d.is_finite());
    let how_far = distance.map_or_else(
        || "no nearest surface point found".to_string(),
        |d| format!("{d:.3e} mm from the nearest surface point found"),
    );
    DomainError(format!(
        "the boundary point ({:.6}, {:.6}, {:.6}) is not on the face's surface ({how_far}; at \
         most {deviation:.3e} mm accepted)",
        point.x, point.y, point.z
    ))
}

/// `parameters` shifted by whole periods to lie nearest `previous`.
fn unwrap_near(parameters: DVec2, previous: DVec2, periods: [Option<f64>; 2]) -> DVec2 {
    let shift = |value: f64, reference: f64, period: Option<f64>| match period {
        Some(period) => value - ((value - reference) / period).round() * period,
        None => value,
    };
    DVec2::new(
        shift(parameters.x, previous.x, periods[0]),
        shift(parameters.y, previous.y, periods[1]),
    )
}

/// Truck's own search, or the best point of a parameter grid, polished by Gauss-Newton.
pub fn global_inversion(
    surface: &StepSurface,
    point: DVec3,
    periods: [Option<f64>; 2],
    ranges: [Option<(f64, f64)>; 2],
) -> Option<DVec2> {
    let start = surface
        .search_nearest_parameter(Point3::new(point.x, point.y, point.z), None, 100)
        .map(|(u, v)| DVec2::new(u, v))
        .unwrap_or_else(|| grid_search(surface, point, periods, ranges));
    Some(refine_inversion(surface, point, start, ranges))
}

fn grid_search(
    surface: &StepSurface,
    point: DVec3,
    periods: [Option<f64>; 2],
    ranges: [Option<(f64, f64)>; 2],
) -> DVec2 {
    let span = |axis: usize| match (periods[axis], ranges[axis]) {
        (Some(period), _) => (0.0, period),
        (None, Some(range)) => range,
        (None, None) => (-1.0, 1.0),
    };
    let (u, v) = (span(0), span(1));
    let mut best = (f64::INFINITY, DVec2::ZERO);
    for i in 0..=SEARCH_GRID {
        for j in 0..=SEARCH_GRID {
            let t = DVec2::new(i as f64, j as f64) / SEARCH_GRID as f64;
            let p = DVec2::new(u.0 + (u.1 - u.0) * t.x, v.0 + (v.1 - v.0) * t.y);
            let distance = native_point(surface, p).distance_squared(point);
            if distance < best.0 {
                best = (distance, p);
            }
        }
    }
    best.1
}

/// Gauss-Newton on `|S(u, v) − point|²` from `start`, bounded parameters clamped to their range.
fn refine_inversion(
    surface: &StepSurface,
    point: DVec3,
    start: DVec2,
    ranges: [Option<(f64, f64)>; 2],
) -> DVec2 {
    let clamp = |p: DVec2| {
        let axis = |value: f64, range: Option<(f64, f64)>| {
            range.map_or(value, |(low, high)| value.clamp(low, high))
        };
        DVec2::new(axis(p.x, ranges[0]), axis(p.y, ranges[1]))
    };
    let mut p = clamp(start);
    for _ in 0..INVERSION_STEPS {
        let residual = point - native_point(surface, p);
        let (su, sv) = native_derivatives(surface, p);
        let (a, b, c) = (su.dot(su), su.dot(sv), sv.dot(sv));
        let determinant = a * c - b * b;
        if determinant.abs().partial_cmp(&f64::MIN_POSITIVE) != Some(std::cmp::Ordering::Greater) {
            break;
        }
        let (ru, rv) = (su.dot(residual), sv.dot(residual));
        let step = DVec2::new(c * ru - b * rv, a * rv - b * ru) / determinant;
        if !step.is_finite() {
            break;
        }
        p = clamp(p + step);
        if step.length_squared() < 1e-30 * (1.0 + p.length_squared()) {
            break;
        }
    }
    p
}
