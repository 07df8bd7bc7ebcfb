//! The parameter domain of each kind of surface: where a part file's fold polylines live.
//!
//! Input: a [`Surface`]. Output: a [`SurfaceDomain`] that gives the domain coordinates `(u, v)` of
//! a point of the surface (part units in, the documented domain out) and tells whether a domain
//! point or segment lies on the surface. The domains (`docs/part-format.md`):
//! - cylinder, cone, loft: `u` the angle in degrees about the axis through the two sections'
//!   centres (interpolated along the axis, so an oblique cone's rulings have constant `u`),
//!   measured in the local frame from its x axis (a loft's from its seam ruling at that height,
//!   0 to 360); `v` the local height `z`;
//! - revolution: `u` the angle in degrees, `v` the arc length along the profile from `start`;
//! - extrusion: `u` the arc length along the profile from `start`, `v` the local height `z`;
//! - polygon, bspline: their own parameters (the polygon's plane coordinates, the patch's knots).
//!
//! A periodic `u` (an angle, a closed extrusion profile) has a start and a period: domain points
//! of a mesh are taken in `[start, start + period)`, and a point on the axis of a revolution
//! (a pole) has no `u` at all.

use glam::{DVec2, DVec3};

use super::frame::Frame;
use super::profile::Profile;
use super::rulings::rulings;
use super::surface::{PatchSurface, RuledSurface, Section, Surface};
use crate::geometry::tolerance::{DOMAIN_EDGE_TOLERANCE, DOMAIN_POLE_RATIO};
use crate::geometry::{distance_to_segment, inside};

/// Samples along each fold segment when it is checked against a curved domain edge.
const SEGMENT_SAMPLES: usize = 32;
/// A surface's parameter domain (see the module documentation).
#[derive(Debug, Clone)]
pub enum SurfaceDomain {
    /// Angle about an axis through centres interpolated between two sections, and height.
    Polar {
        /// Local frame.
        frame: Frame,
        /// Section centres (local x, y) at the two heights.
        centres: [DVec2; 2],
        /// Heights of the two sections.
        heights: [f64; 2],
        /// Angular range, degrees.
        angles: [f64; 2],
        /// The height range at an angle (degrees), for mitred ends.
        bounds: HeightBounds,
        /// A loft's seam ruling (local end points): angles are measured from it at each height.
        seam: Option<[DVec3; 2]>,
    },
    /// A surface of revolution: angle and arc length along the profile.
    Revolution {
        /// Local frame.
        frame: Frame,
        /// Profile `(radius, z)`.
        profile: Profile,
        /// Angular range, degrees.
        angles: [f64; 2],
    },
    /// An extrusion: arc length along the profile and height.
    Extrusion {
        /// Local frame.
        frame: Frame,
        /// Profile in the local x-y plane.
        profile: Profile,
        /// Extrusion vector, local.
        direction: DVec3,
    },
    /// A patch: its own parameters.
    Patch(PatchSurface),
}

/// The height range of a cylinder or cone at an angle (its end planes may be tilted).
#[derive(Debug, Clone, Copy)]
pub struct HeightBounds {
    /// Bottom and top: centre height and tilt (radians) about the local y axis, and radius.
    ends: [(f64, f64, f64); 2],
}

impl HeightBounds {
    fn at(&self, angle_degrees: f64) -> [f64; 2] {
        self.ends.map(|(height, tilt, radius)| {
            height + radius * angle_degrees.to_radians().cos() * tilt.tan()
        })
    }
}

impl SurfaceDomain {
    /// The domain of `surface`.
    pub fn new(surface: &Surface) -> Self {
        match surface {
            Surface::Ruled(RuledSurface::Circular {
                frame,
                bottom,
                top,
                angles,
            }) => SurfaceDomain::Polar {
                frame: *frame,
                centres: [bottom.center.truncate(), top.center.truncate()],
                heights: [bottom.center.z, top.center.z],
                angles: angles.map(f64::to_degrees),
                bounds: HeightBounds {
                    ends: [bottom, top].map(|c| (c.center.z, c.tilt, c.radius)),
                },
                seam: None,
            },
            Surface::Ruled(
                loft @ RuledSurface::Loft {
                    frame, bottom, top, ..
                },
            ) => {
                let rulings = rulings(loft, f64::INFINITY, 0.0);
                let seam = [rulings.bottom[0], rulings.top[0]].map(|p| local_point(frame, p));
                SurfaceDomain::Polar {
                    frame: *frame,
                    centres: [bottom, top].map(section_centre),
                    heights: [bottom.z(), top.z()],
                    angles: [0.0, 360.0],
                    bounds: HeightBounds {
                        ends: [(bottom.z(), 0.0, 0.0), (top.z(), 0.0, 0.0)],
                    },
                    seam: Some(seam),
                }
            }
            Surface::Ruled(RuledSurface::Extrusion {
                frame,
                profile,
                direction,
            }) => SurfaceDomain::Extrusion {
                frame: *frame,
                profile: profile.clone(),
                direction: *direction,
            },
            Surface::Revolution(revolution) => SurfaceDomain::Revolution {
                frame: revolution.frame,
                profile: revolution.profile.clone(),
                angles: revolution.angles.map(f64::to_degrees),
            },
            Surface::Patch(patch) => SurfaceDomain::Patch(patch.clone()),
        }
    }

    /// The start and period of a periodic `u` (angles; a closed extrusion profile).
    pub fn period(&self) -> Option<(f64, f64)> {
        match self {
            SurfaceDomain::Polar { angles, .. } | SurfaceDomain::Revolution { angles, .. } => {
                Some((angles[0], 360.0))
            }
            SurfaceDomain::Extrusion { profile, .. } => {
                let length = profile.length();
                profile
                    .is_closed(DOMAIN_EDGE_TOLERANCE * length)
                    .then_some((0.0, length))
            }
            SurfaceDomain::Patch(_) => None,
        }
    }

    /// The domain coordinates of a point of the surface (part coordinates); `None` for `u` on
    /// a pole. A periodic `u` is in `[start, start + period)`.
    pub fn parameters(&self, point: DVec3) -> (Option<f64>, f64) {
        let (u, v) = match self {
            SurfaceDomain::Polar {
                frame,
                centres,
                heights,
                seam,
                ..
            } => {
                let local = local_point(frame, point);
                let t = (local.z - heights[0]) / (heights[1] - heights[0]);
                let centre = centres[0].lerp(centres[1], t);
                let angle = |p: DVec2| (p - centre).to_angle().to_degrees();
                let from = seam.map_or(0.0, |[b, top]| {
                    let s = (local.z - b.z) / (top.z - b.z);
                    angle(b.truncate().lerp(top.truncate(), s))
                });
                (Some(angle(local.truncate()) - from), local.z)
            }
            SurfaceDomain::Revolution { frame, profile, .. } => {
                let local = local_point(frame, point);
                let radius = local.truncate().length();
                let v = profile.nearest_arc_length(DVec2::new(radius, local.z));
                let pole = radius <= DOMAIN_POLE_RATIO * profile.length();
                let u = (!pole).then(|| local.y.atan2(local.x).to_degrees());
                (u, v)
            }
            SurfaceDomain::Extrusion {
                frame,
                profile,
                direction,
            } => {
                let local = local_point(frame, point);
                let base = local.truncate() - direction.truncate() * (local.z / direction.z);
                (Some(profile.nearest_arc_length(base)), local.z)
            }
            SurfaceDomain::Patch(_) => unreachable!("patches carry their parameters"),
        };
        (u.map(|u| self.wrapped(u)), v)
    }

    /// The smallest box `[low, high]` holding the whole domain (`u`, `v`).
    pub fn range(&self) -> [DVec2; 2] {
        match self {
            SurfaceDomain::Polar { angles, bounds, .. } => {
                let heights = bounds.ends.map(|(height, tilt, radius)| {
                    let reach = radius * tilt.tan().abs();
                    [height - reach, height + reach]
                });
                let (low, high) = heights
                    .iter()
                    .flatten()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &z| {
                        (low.min(z), high.max(z))
                    });
                [DVec2::new(angles[0], low), DVec2::new(angles[1], high)]
            }
            SurfaceDomain::Revolution {
                angles, profile, ..
            } => [
                DVec2::new(angles[0], 0.0),
                DVec2::new(angles[1], profile.length()),
            ],
            SurfaceDomain::Extrusion {
                profile, direction, ..
            } => [
                DVec2::new(0.0, direction.z.min(0.0)),
                DVec2::new(profile.length(), direction.z.max(0.0)),
            ],
            SurfaceDomain::Patch(patch) => patch
                .outer
                .iter()
                .fold([DVec2::INFINITY, DVec2::NEG_INFINITY], |[low, high], &p| {
                    [low.min(p), high.max(p)]
                }),
        }
    }

    /// `u` moved by whole periods into `[start, start + period)`.
    pub fn wrapped(&self, u: f64) -> f64 {
        match self.period() {
            Some((start, period)) => start + (u - start).rem_euclid(period),
            None => u,
        }
    }

    /// Why the domain point `point` is off the surface, if it is.
    pub fn outside(&self, point: DVec2) -> Option<String> {
        let range = |value: f64, low: f64, high: f64, name: &str| {
            let tolerance = DOMAIN_EDGE_TOLERANCE * (1.0 + low.abs().max(high.abs()));
            (!(value >= low - tolerance && value <= high + tolerance))
                .then(|| format!("{name} = {value} is outside [{low}, {high}]"))
        };
        match self {
            SurfaceDomain::Polar { angles, bounds, .. } => {
                range(point.x, angles[0], angles[1], "u (angle)").or_else(|| {
                    let [low, high] = bounds.at(point.x);
                    range(point.y, low.min(high), low.max(high), "v (height)")
                })
            }
            SurfaceDomain::Revolution {
                angles, profile, ..
            } => range(point.x, angles[0], angles[1], "u (angle)")
                .or_else(|| range(point.y, 0.0, profile.length(), "v (profile length)")),
            SurfaceDomain::Extrusion {
                profile, direction, ..
            } => range(point.x, 0.0, profile.length(), "u (profile length)").or_else(|| {
                range(
                    point.y,
                    direction.z.min(0.0),
                    direction.z.max(0.0),
                    "v (height)",
                )
            }),
            SurfaceDomain::Patch(patch) => {
                let [low, high] = self.range();
                let tolerance = DOMAIN_EDGE_TOLERANCE * (high - low).length();
                let on = |ring: &[DVec2]| {
                    (0..ring.len()).any(|k| {
                        distance_to_segment(point, ring[k], ring[(k + 1) % ring.len()]) <= tolerance
                    })
                };
                let in_trim = (inside(point, &patch.outer) || on(&patch.outer))
                    && !patch
                        .holes
                        .iter()
                        .any(|hole| inside(point, hole) && !on(hole));
                (!in_trim).then(|| {
                    format!(
                        "({}, {}) is outside the surface's trimmed domain",
                        point.x, point.y
                    )
                })
            }
        }
    }

    /// Why the domain segment from `from` to `to` leaves the surface, if it does: an end or a
    /// sample off the domain, or (patches) a crossing of a trim loop.
    pub fn segment_outside(&self, from: DVec2, to: DVec2) -> Option<String> {
        let samples =
            (0..=SEGMENT_SAMPLES).map(|k| from.lerp(to, k as f64 / SEGMENT_SAMPLES as f64));
        if let Some(reason) = samples.filter_map(|p| self.outside(p)).next() {
            return Some(reason);
        }
        let SurfaceDomain::Patch(patch) = self else {
            return None;
        };
        std::iter::once(&patch.outer)
            .chain(&patch.holes)
            .any(|ring| crosses_ring(from, to, ring))
            .then(|| {
                format!(
                    "the segment from ({}, {}) to ({}, {}) crosses a trim loop",
                    from.x, from.y, to.x, to.y
                )
            })
    }
}

fn section_centre(section: &Section) -> DVec2 {
    match section {
        Section::Circle { center, .. } => *center,
        Section::Polygon { corners, .. } => {
            corners.iter().sum::<DVec2>() / corners.len().max(1) as f64
        }
    }
}

fn local_point(frame: &Frame, point: DVec3) -> DVec3 {
    let d = point - frame.origin;
    DVec3::new(d.dot(frame.x), d.dot(frame.y), d.dot(frame.z))
}

/// Whether the open segment `from`-`to` properly crosses an edge of the closed `ring`.
fn crosses_ring(from: DVec2, to: DVec2, ring: &[DVec2]) -> bool {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    (0..ring.len()).any(|k| {
        let (p, q) = (ring[k], ring[(k + 1) % ring.len()]);
        side(p, q, from) * side(p, q, to) < 0.0 && side(from, to, p) * side(from, to, q) < 0.0
    })
}

#[cfg(test)]
mod tests {
    use crate::cad::surface::RuledCircle;
    use crate::cad::surface_domain::*;

    #[test]
    fn an_oblique_cone_ruling_has_one_angle() {
        let cone = Surface::Ruled(RuledSurface::Circular {
            frame: Frame::WORLD,
            bottom: RuledCircle {
                center: DVec3::ZERO,
                radius: 100.0,
                tilt: 0.0,
            },
            top: RuledCircle {
                center: DVec3::new(30.0, 10.0, 80.0),
                radius: 50.0,
                tilt: 0.0,
            },
            angles: [0.0, std::f64::consts::TAU],
        });
        let domain = SurfaceDomain::new(&cone);
        let angle = 130f64.to_radians();
        let bottom = DVec3::new(100.0 * angle.cos(), 100.0 * angle.sin(), 0.0);
        let top = DVec3::new(30.0 + 50.0 * angle.cos(), 10.0 + 50.0 * angle.sin(), 80.0);
        for t in [0.0, 0.3, 1.0] {
            let (u, v) = domain.parameters(bottom.lerp(top, t));
            assert!((u.unwrap() - 130.0).abs() < 1e-9 && (v - 80.0 * t).abs() < 1e-9);
        }
        assert!(domain.outside(DVec2::new(130.0, 81.0)).is_some());
        assert!(domain.outside(DVec2::new(361.0, 40.0)).is_some());
        assert!(domain.outside(DVec2::new(360.0, 40.0)).is_none());
    }
}
