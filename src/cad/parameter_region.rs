//! Stiffness regions given in a surface's parameter domain: which mesh vertices lie in them.
//!
//! Input: a surface's [`SurfaceDomain`] (`docs/part-format.md`: angles in degrees, heights and
//! profile lengths in part units, a patch's own parameters) and a polygon `[[u, v], ...]` in it.
//! Output: a [`ParameterRegion`] that tells whether a domain point is in the region (the
//! tessellator finds the mesh vertices in it), and whether the region misses the domain
//! altogether (a part-file error).
//!
//! Conventions, the same on every kind of surface:
//! - a vertex is on the surface when that surface's mesher produced it (a vertex of an edge two
//!   surfaces share is on both); its domain coordinates are the patch's own parameters, or those
//!   of its position ([`SurfaceDomain::parameters`]) on the structured kinds;
//! - the region is closed: a point within `BOUNDARY_TOLERANCE` of its boundary is inside;
//! - a periodic `u` (an angle; the arc length along a closed extrusion profile) is matched
//!   modulo its period: a point is inside when `(u + k · period, v)` is, for some whole `k`, so a
//!   region across a full turn's seam may be written from −10 to 10 or from 350 to 370 degrees;
//! - a pole (a profile point of a surface of revolution on its axis, which has no angle) is
//!   inside when the region reaches its `v` at an angle of the surface.

use glam::DVec2;

use super::surface_domain::SurfaceDomain;
use crate::geometry::tolerance::BOUNDARY_TOLERANCE;
use crate::geometry::{distance_to_segment, inside};

/// A polygon in a surface's parameter domain (see the module documentation).
#[derive(Debug, Clone)]
pub struct ParameterRegion {
    domain: SurfaceDomain,
    polygon: Vec<DVec2>,
    /// The polygon's bounding box.
    bounds: [DVec2; 2],
    /// Absolute boundary tolerance (domain units).
    tolerance: f64,
}

impl ParameterRegion {
    /// The region bounded by `polygon` (at least three points) in `domain`.
    pub fn new(domain: SurfaceDomain, polygon: Vec<DVec2>) -> Self {
        let bounds = polygon
            .iter()
            .fold([DVec2::INFINITY, DVec2::NEG_INFINITY], |[low, high], &p| {
                [low.min(p), high.max(p)]
            });
        let largest = polygon
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        Self {
            domain,
            polygon,
            bounds,
            tolerance: BOUNDARY_TOLERANCE * (1.0 + largest),
        }
    }

    /// Why the region misses its surface, if it does: its bounding box does not overlap the
    /// domain's (`u` shifted by whole periods on a periodic domain).
    pub fn off_domain(&self) -> Option<String> {
        let [low, high] = self.domain.range();
        let [from, to] = self.bounds;
        let overlaps = self.u_overlaps(from.x, to.x, self.tolerance)
            && to.y.min(high.y) - from.y.max(low.y) > self.tolerance;
        let [u, v] = self.axis_names();
        // Rounded to 9 decimals, so that 120 degrees is not printed as 119.99999999999999.
        let [from, to, low, high] = [from, to, low, high].map(|p| (p * 1e9).round() / 1e9);
        (!overlaps).then(|| {
            format!(
                "the region ({u} from {} to {}, {v} from {} to {}) lies off its surface, whose \
                 domain is {u} from {} to {}, {v} from {} to {}",
                from.x, to.x, from.y, to.y, low.x, high.x, low.y, high.y
            )
        })
    }

    /// The domain the region is given in.
    pub fn domain(&self) -> &SurfaceDomain {
        &self.domain
    }

    /// Whether the domain point `(u, v)` is in the region (`u` is `None` on a pole).
    pub fn contains(&self, u: Option<f64>, v: f64) -> bool {
        match u {
            Some(u) => self.shifts(u).any(|u| self.covers(DVec2::new(u, v))),
            None => self.reaches_pole(v),
        }
    }

    /// The names of the two domain coordinates, for messages.
    fn axis_names(&self) -> [&'static str; 2] {
        match self.domain {
            SurfaceDomain::Polar { .. } => ["u (angle)", "v (height)"],
            SurfaceDomain::Revolution { .. } => ["u (angle)", "v (profile length)"],
            SurfaceDomain::Extrusion { .. } => ["u (profile length)", "v (height)"],
            SurfaceDomain::Patch(_) => ["u", "v"],
        }
    }

    /// `u` and its copies a whole number of periods away that fall within the region's `u` range.
    fn shifts(&self, u: f64) -> impl Iterator<Item = f64> + '_ {
        let [from, to] = self.bounds;
        let (first, last, period) = match self.domain.period() {
            Some((_, period)) => (
                ((from.x - self.tolerance - u) / period).ceil() as i64,
                ((to.x + self.tolerance - u) / period).floor() as i64,
                period,
            ),
            None => (0, 0, 0.0),
        };
        (first..=last).map(move |k| u + k as f64 * period)
    }

    /// Whether `point` is inside the polygon or on its boundary.
    fn covers(&self, point: DVec2) -> bool {
        let ring = &self.polygon;
        inside(point, ring)
            || (0..ring.len()).any(|k| {
                distance_to_segment(point, ring[k], ring[(k + 1) % ring.len()]) <= self.tolerance
            })
    }

    /// Whether the polygon meets the line at height `v` at an angle of the surface.
    fn reaches_pole(&self, v: f64) -> bool {
        let ring = &self.polygon;
        (0..ring.len()).any(|k| {
            let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
            let (low, high) = (a.y.min(b.y), a.y.max(b.y));
            if v < low - self.tolerance || v > high + self.tolerance {
                return false;
            }
            // The stretch of the edge at height v: a point where it crosses, the whole edge
            // where it runs along it.
            let [from, to] = if high - low <= self.tolerance {
                [a.x.min(b.x), a.x.max(b.x)]
            } else {
                let t = ((v - a.y) / (b.y - a.y)).clamp(0.0, 1.0);
                [a.x + t * (b.x - a.x); 2]
            };
            self.u_overlaps(from, to, -self.tolerance)
        })
    }

    /// Whether `u` from `from` to `to` (shifted by whole periods on a periodic domain) overlaps
    /// the domain's `u` range by more than `margin`.
    fn u_overlaps(&self, from: f64, to: f64, margin: f64) -> bool {
        let [low, high] = self.domain.range();
        let overlap = |shift: f64| (to + shift).min(high.x) - (from + shift).max(low.x) > margin;
        match self.domain.period() {
            Some((_, period)) => {
                let first = ((low.x - to) / period).floor() as i64;
                let last = ((high.x - from) / period).ceil() as i64;
                (first..=last).any(|k| overlap(k as f64 * period))
            }
            None => overlap(0.0),
        }
    }
}
