//! The domain a STEP face is meshed in: its surface's parameters mapped so that the domain has
//! (nearly) the surface's own metric, so the patch mesher's angle and size bounds hold on the
//! surface, not only in the parameter plane.
//!
//! Input: a face's surface (truck-stepio's [`StepSurface`]) and its boundary loops as points on
//! the surface. Output: the loops in the domain ([`FaceDomain::loops`]) and a [`MappedSurface`]
//! that evaluates the surface at domain coordinates, for [`super::patch::mesh_patch`].
//!
//! - Cylinders are unrolled (arc length, height): an isometry, so the domain *is* the flat
//!   surface and a closed side face becomes a rectangle whose two seam sides are sampled alike.
//! - Cones are developed in log-polar coordinates (angle about the apex in the development, log of
//!   the distance from the apex): a conformal map, so angles are the surface's and lengths scale
//!   smoothly; rulings and circles are straight lines along the axes (a polar development would
//!   put a ruling's points off one line by round-off, and the mesher would make slivers there).
//!   Faces that reach their apex are mapped in polar coordinates about it (below).
//! - A face through a pole of a surface of revolution (a sphere's pole, a cone's apex) is mapped
//!   to conformal polar coordinates about the pole (`DomainMap::Polar`).
//! - Other faces of spheres, tori and revolved curves are mapped to Mercator coordinates
//!   (`DomainMap::Mercator`): conformal, parallels and meridians straight.
//! - Other surfaces (planes, B-splines, NURBS, extrusions) keep their own parameters; the patch
//!   mesher scales them by the mean surface speeds.
//!
//! Boundary points are inverted into the surface's parameters (truck's search, then Gauss-Newton
//! from the previous point of the loop), and periodic parameters are unwrapped along each loop so
//! a loop that crosses the seam stays continuous.

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::Surface as StepSurface;

use super::curvature::largest_curvature;
use super::domain_map::{Axis, DomainMap, domain_map, polar_map};
use super::inversion::{DomainError, invert_loop, parameter_ranges};
use super::native::{native_derivatives, native_point};
use crate::cad::MappedSurface;
use crate::geometry::tolerance::STEP_POLE_RATIO;
use crate::geometry::tolerance::{ISO_LINE_RATIO, ROUND_OFF_RATIO};

/// A face's surface evaluated at domain coordinates.
#[derive(Debug, Clone)]
pub struct FaceSurface {
    surface: StepSurface,
    map: DomainMap,
}

impl FaceSurface {
    /// The surface's parameters at domain coordinates.
    pub fn native(&self, domain: DVec2) -> DVec2 {
        self.map.native_of(domain)
    }

    /// The surface's normal `∂S/∂u × ∂S/∂v` at its parameters (not normalised).
    pub fn native_normal(&self, native: DVec2) -> DVec3 {
        let (u, v) = native_derivatives(&self.surface, native);
        u.cross(v)
    }
}

impl MappedSurface for FaceSurface {
    fn point(&self, parameters: DVec2) -> DVec3 {
        native_point(&self.surface, self.map.native_of(parameters))
    }

    fn derivatives(&self, parameters: DVec2) -> (DVec3, DVec3) {
        let native = self.map.native_of(parameters);
        let (su, sv) = native_derivatives(&self.surface, native);
        let (dx, dy) = self.map.native_derivatives(parameters);
        (su * dx.x + sv * dx.y, su * dy.x + sv * dy.y)
    }
}

/// A boundary loop of a face: points on the surface (the loop does not repeat its first point)
/// and the index of each edge's first point.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BoundaryLoop {
    /// The points, in loop order.
    pub points: Vec<DVec3>,
    /// Index in `points` of the first point of each edge, ascending.
    pub edge_starts: Vec<usize>,
}

/// A face's domain: its surface and its boundary loops in domain coordinates.
#[derive(Debug, Clone)]
pub struct FaceDomain {
    /// The surface at domain coordinates.
    pub surface: FaceSurface,
    /// The boundary loops (as given, one domain point per boundary point).
    pub loops: Vec<Vec<DVec2>>,
    /// The largest principal curvature over the face's parameter box (sampled), 1 / length.
    pub curvature: f64,
}

/// Maps a face's boundary loops (points on `surface`) into its meshing domain; `size` is the
/// face's size (for the inversion tolerance).
pub fn face_domain(
    surface: &StepSurface,
    loops: &[BoundaryLoop],
    size: f64,
) -> Result<FaceDomain, DomainError> {
    let periods = [surface.u_period(), surface.v_period()];
    let ranges = parameter_ranges(surface, periods);
    let mut native_loops = Vec::with_capacity(loops.len());
    let mut pole = None;
    for boundary in loops {
        let mut native = invert_loop(surface, &boundary.points, periods, ranges, size)?;
        pole = pole.or(close_at_pole(surface, &mut native, periods, size));
        check_closed(&native, periods)?;
        straighten_iso_edges(&mut native, &boundary.edge_starts);
        native_loops.push(native);
    }
    let map = pole
        .and_then(|(angular, t_pole)| polar_map(surface, &native_loops, angular, t_pole))
        .unwrap_or_else(|| domain_map(surface, &native_loops, periods));
    let curvature = largest_curvature(surface, &native_loops, pole);
    let polar = matches!(map, DomainMap::Polar(_));
    let loops = native_loops
        .iter()
        .map(|native| {
            let mut domain: Vec<DVec2> = native.iter().map(|&p| map.domain_of(p)).collect();
            if polar {
                flush_round_off(&mut domain);
            }
            domain
        })
        .collect();
    Ok(FaceDomain {
        surface: FaceSurface {
            surface: surface.clone(),
            map,
        },
        loops,
        curvature,
    })
}

/// Makes zero each coordinate of a polar-mapped loop whose magnitude is below
/// [`ROUND_OFF_RATIO`] of the loop's extent: the polar map puts a meridian on an axis only up to
/// round-off (`r · cos 90°` is 6e-17 r), and spade's point location can fail on a boundary
/// running along a line at such distances from it (a sphere octant through its pole).
fn flush_round_off(domain: &mut [DVec2]) {
    let extent = domain
        .iter()
        .fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
    let round_off = ROUND_OFF_RATIO * extent;
    let flush = |value: f64| if value.abs() <= round_off { 0.0 } else { value };
    for point in domain {
        *point = DVec2::new(flush(point.x), flush(point.y));
    }
}

/// A loop that does not come back to its start in the parameters wraps around a periodic
/// surface without a seam edge.
fn check_closed(native: &[DVec2], periods: [Option<f64>; 2]) -> Result<(), DomainError> {
    let (Some(first), Some(last)) = (native.first(), native.last()) else {
        return Ok(());
    };
    for (axis, period) in periods.iter().enumerate() {
        if let Some(period) = period
            && (last[axis] - first[axis]).abs() > 0.5 * period
        {
            return Err(DomainError(
                "a boundary loop wraps around the face's periodic surface without a seam edge; \
                 export the face split along a seam (most CAD systems do by default)"
                    .into(),
            ));
        }
    }
    Ok(())
}

/// Where a loop passes through a pole of a periodic surface (a sphere's pole, a cone's apex: a
/// point where the parallel's radius `|∂S/∂θ|` vanishes), the angle about the axis is undefined
/// there and the loop (which has no edge along the pole) does not close in it: the points after
/// the pole are shifted by whole periods so that it does, and the pole takes its predecessor's
/// angle. Returns the angular axis and the pole's other parameter.
fn close_at_pole(
    surface: &StepSurface,
    native: &mut [DVec2],
    periods: [Option<f64>; 2],
    size: f64,
) -> Option<(Axis, f64)> {
    let count = native.len();
    for (axis, period) in [(Axis::U, periods[0]), (Axis::V, periods[1])] {
        let Some(period) = period else { continue };
        let radius = |p: DVec2| {
            let (su, sv) = native_derivatives(surface, p);
            match axis {
                Axis::U => su.length(),
                Axis::V => sv.length(),
            }
        };
        let Some((index, smallest)) = native
            .iter()
            .enumerate()
            .map(|(k, &p)| (k, radius(p)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
        else {
            continue;
        };
        if smallest > STEP_POLE_RATIO * size || smallest.is_nan() || count < 3 {
            continue;
        }
        let angle = |p: DVec2| axis.split(p).1;
        let turns = ((angle(native[count - 1]) - angle(native[0])) / period).round();
        for p in &mut native[index + 1..] {
            let (t, a) = axis.split(*p);
            *p = axis.join(t, a - turns * period);
        }
        let (t_pole, _) = axis.split(native[index]);
        let previous = native[(index + count - 1) % count];
        native[index] = axis.join(t_pole, angle(previous));
        return Some((axis, t_pole));
    }
    None
}

/// Gives every point of an edge that lies on an iso-parameter line the parameter of the edge's
/// first point (edges in loop order, so a run of such edges shares one value).
fn straighten_iso_edges(native: &mut [DVec2], edge_starts: &[usize]) {
    let count = native.len();
    let (low, high) = native
        .iter()
        .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(low, high), &p| {
            (low.min(p), high.max(p))
        });
    let tolerance = ISO_LINE_RATIO * (high - low).max_element().max(f64::MIN_POSITIVE);
    for (k, &start) in edge_starts.iter().enumerate() {
        let end = edge_starts.get(k + 1).copied().unwrap_or(count);
        // The edge runs from its first point to the next edge's first point (inclusive).
        let indices: Vec<usize> = (start..=end).map(|i| i % count).collect();
        #[allow(clippy::needless_range_loop)] // `axis` indexes each point's two parameters
        for axis in 0..2 {
            let (min, max) = indices
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &i| {
                    (a.min(native[i][axis]), b.max(native[i][axis]))
                });
            if max - min <= tolerance {
                let value = native[start % count][axis];
                for &i in &indices {
                    native[i][axis] = value;
                }
            }
        }
    }
}
