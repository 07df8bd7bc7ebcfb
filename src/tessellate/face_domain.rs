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

use std::ops::Bound;

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::{ElementarySurface, Surface as StepSurface, SweptCurve};

use super::surface::MappedSurface;

/// Grid intervals per parameter on which a face's curvature is sampled.
const CURVATURE_SAMPLES: usize = 6;
/// Gauss-Newton steps of a point inversion.
const INVERSION_STEPS: usize = 12;
/// Grid samples per parameter of the fallback search of a point inversion.
const SEARCH_GRID: usize = 24;
/// A boundary point farther than this fraction of the face's size from its inverted surface point
/// means the inversion failed.
const INVERSION_TOLERANCE_RATIO: f64 = 1e-5;
/// A cone face reaching closer to its apex than this fraction of its largest distance from it
/// keeps its own parameters (the log-polar map is singular at the apex).
const APEX_RATIO: f64 = 1e-3;
/// A cone whose radius changes less than this per unit of ruling length is a cylinder.
const CYLINDER_SLOPE: f64 = 1e-9;
/// A boundary point where the parallel's radius `|∂S/∂θ|` is below this fraction of the face's
/// size is a pole.
const POLE_RATIO: f64 = 1e-7;
/// Curvature is not sampled within this fraction of the parameter range from a pole.
const POLE_CURVATURE_EXCLUSION: f64 = 0.25;
/// Samples of a polar map's table along the meridian.
const POLAR_SAMPLES: usize = 1024;
/// A polar map's `c` within this of 1 is a smooth pole (`c = 1`).
const SMOOTH_POLE_TOLERANCE: f64 = 1e-3;
/// Finite-difference step of a polar map's derivatives, fraction of the domain's radius.
const POLAR_DIFFERENCE_RATIO: f64 = 1e-6;

/// A boundary point inverted onto the surface failed; the message says where.
#[derive(Debug, Clone, PartialEq)]
pub struct DomainError(pub String);

/// How a face's parameters `(u, v)` map to the domain it is meshed in.
#[derive(Debug, Clone, PartialEq)]
enum DomainMap {
    /// The parameters themselves.
    Native,
    /// A cylinder unrolled: `(radius × angle, speed × t)`.
    Unrolled {
        angular: Axis,
        radius: f64,
        speed: f64,
    },
    /// A cone mapped conformally: its development in log-polar coordinates
    /// `(ρ₀ k θ, ρ₀ ln(ρ / ρ₀))` with `ρ = r(t) / k` the distance from the apex along a ruling,
    /// `r(t) = r0 + slope t` the radius and `k` the sine of the half-angle. Rulings and circles
    /// are straight lines along the axes (so points of one ruling are exactly collinear) and
    /// angles are those of the surface; lengths scale by `ρ / ρ₀`.
    Developed {
        angular: Axis,
        r0: f64,
        slope: f64,
        k: f64,
        /// Reference distance from the apex (the face's largest).
        reference: f64,
    },
    /// A face around a pole of a surface of revolution (a sphere's pole, a cone's apex, a
    /// revolved profile meeting the axis) in conformal polar coordinates about the pole:
    /// `g(t) (cos c θ, sin c θ)` with `ln g = ∫ c s / r dt` (`r` the parallel's radius, `s` the
    /// meridian's speed) and `c = r / G` at the pole (`G` the meridian arc length from it): 1
    /// at a smooth pole, the sine of the half-angle at a cone's apex (where the map is the
    /// cone's development). The pole is the origin, so triangles keep their shape up to it.
    Polar(PolarMap),
    /// A face of a surface of revolution away from its poles (a torus, a sphere's zone, a
    /// revolved profile) in Mercator coordinates `(r₀ θ, r₀ ∫ s / r dt)` (`r` the parallel's
    /// radius, `s` the meridian's speed, `r₀` the face's largest radius): a conformal map, so
    /// angles are the surface's; parallels and meridians are straight lines along the axes and
    /// lengths scale by `r / r₀`.
    Mercator(MercatorMap),
}

/// The table of a [`DomainMap::Mercator`] map.
#[derive(Debug, Clone, PartialEq)]
struct MercatorMap {
    angular: Axis,
    /// `r₀`: the domain's length per angle about the axis.
    radius0: f64,
    /// Parameter `t` at the samples (increasing).
    t: Vec<f64>,
    /// `y(t)` at the samples (increasing).
    y: Vec<f64>,
}

/// The table of a [`DomainMap::Polar`] map.
#[derive(Debug, Clone, PartialEq)]
struct PolarMap {
    angular: Axis,
    /// `c`: the angle in the domain per angle about the axis.
    c: f64,
    /// Angle about the axis that maps to the domain's x axis.
    angle0: f64,
    /// Parameter `t` at the samples, from the pole outwards (monotone).
    t: Vec<f64>,
    /// `g(t)` at the samples (0 at the pole, increasing).
    g: Vec<f64>,
}

impl PolarMap {
    fn radius_of(&self, t: f64) -> f64 {
        interpolate(&self.t, &self.g, t)
    }

    fn t_of(&self, radius: f64) -> f64 {
        interpolate(&self.g, &self.t, radius)
    }
}

/// Piecewise-linear interpolation of `ys` over monotone `xs` (either direction), extrapolated
/// linearly past the ends.
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let increasing = xs[xs.len() - 1] >= xs[0];
    let k = xs
        .partition_point(|&v| if increasing { v < x } else { v > x })
        .clamp(1, xs.len() - 1);
    let (x0, x1, y0, y1) = (xs[k - 1], xs[k], ys[k - 1], ys[k]);
    if x1 == x0 {
        return y0;
    }
    y0 + (y1 - y0) * (x - x0) / (x1 - x0)
}

/// Which surface parameter is the angle about the axis.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Axis {
    U,
    V,
}

impl Axis {
    /// `(t, θ)` (ruling parameter, angle) from `(u, v)`.
    fn split(self, native: DVec2) -> (f64, f64) {
        match self {
            Axis::U => (native.y, native.x),
            Axis::V => (native.x, native.y),
        }
    }

    /// `(u, v)` from `(t, θ)`.
    fn join(self, t: f64, angle: f64) -> DVec2 {
        match self {
            Axis::U => DVec2::new(angle, t),
            Axis::V => DVec2::new(t, angle),
        }
    }
}

impl DomainMap {
    fn domain_of(&self, native: DVec2) -> DVec2 {
        match *self {
            DomainMap::Native => native,
            DomainMap::Unrolled {
                angular,
                radius,
                speed,
            } => {
                let (t, angle) = angular.split(native);
                DVec2::new(radius * angle, speed * t)
            }
            DomainMap::Developed {
                angular,
                r0,
                slope,
                k,
                reference,
            } => {
                let (t, angle) = angular.split(native);
                let rho = (r0 + slope * t) / k;
                DVec2::new(reference * k * angle, reference * (rho / reference).ln())
            }
            DomainMap::Polar(ref polar) => {
                let (t, angle) = polar.angular.split(native);
                DVec2::from_angle(polar.c * (angle - polar.angle0)) * polar.radius_of(t)
            }
            DomainMap::Mercator(ref mercator) => {
                let (t, angle) = mercator.angular.split(native);
                DVec2::new(
                    mercator.radius0 * angle,
                    interpolate(&mercator.t, &mercator.y, t),
                )
            }
        }
    }

    fn native_of(&self, domain: DVec2) -> DVec2 {
        match *self {
            DomainMap::Native => domain,
            DomainMap::Unrolled {
                angular,
                radius,
                speed,
            } => angular.join(domain.y / speed, domain.x / radius),
            DomainMap::Developed {
                angular,
                r0,
                slope,
                k,
                reference,
            } => {
                let rho = reference * (domain.y / reference).exp();
                angular.join((k * rho - r0) / slope, domain.x / (reference * k))
            }
            DomainMap::Polar(ref polar) => {
                // The cut of the angle is in the middle of the sector's gap (none when c = 1).
                let gap = std::f64::consts::TAU * (1.0 - polar.c);
                let angle = (domain.y.atan2(domain.x) + 0.5 * gap)
                    .rem_euclid(std::f64::consts::TAU)
                    - 0.5 * gap;
                polar
                    .angular
                    .join(polar.t_of(domain.length()), polar.angle0 + angle / polar.c)
            }
            DomainMap::Mercator(ref mercator) => mercator.angular.join(
                interpolate(&mercator.y, &mercator.t, domain.y),
                domain.x / mercator.radius0,
            ),
        }
    }

    /// `(∂(u, v)/∂x, ∂(u, v)/∂y)` at domain coordinates.
    fn native_derivatives(&self, domain: DVec2) -> (DVec2, DVec2) {
        match *self {
            DomainMap::Native => (DVec2::X, DVec2::Y),
            DomainMap::Unrolled {
                angular,
                radius,
                speed,
            } => (
                angular.join(0.0, 1.0 / radius),
                angular.join(1.0 / speed, 0.0),
            ),
            DomainMap::Developed {
                angular,
                slope,
                k,
                reference,
                ..
            } => {
                let rho = reference * (domain.y / reference).exp();
                (
                    angular.join(0.0, 1.0 / (reference * k)),
                    angular.join(k / slope * rho / reference, 0.0),
                )
            }
            DomainMap::Polar(ref polar) => {
                let step = POLAR_DIFFERENCE_RATIO * polar.g[polar.g.len() - 1];
                // The angle jumps by a turn across the cut (inside the domain when c = 1).
                let turn = std::f64::consts::TAU / polar.c;
                let difference = |offset: DVec2| {
                    let change = self.native_of(domain + offset) - self.native_of(domain - offset);
                    let (t, angle) = polar.angular.split(change);
                    polar.angular.join(t, angle - (angle / turn).round() * turn) / (2.0 * step)
                };
                (difference(DVec2::X * step), difference(DVec2::Y * step))
            }
            DomainMap::Mercator(ref mercator) => {
                // The slope of the interpolated table, so derivatives match `native_of`.
                let (t, y) = (&mercator.t, &mercator.y);
                let k = y.partition_point(|&v| v < domain.y).clamp(1, y.len() - 1);
                (
                    mercator.angular.join(0.0, 1.0 / mercator.radius0),
                    mercator
                        .angular
                        .join((t[k] - t[k - 1]) / (y[k] - y[k - 1]), 0.0),
                )
            }
        }
    }
}

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

fn native_point(surface: &StepSurface, native: DVec2) -> DVec3 {
    let p = surface.subs(native.x, native.y);
    DVec3::new(p.x, p.y, p.z)
}

fn native_derivatives(surface: &StepSurface, native: DVec2) -> (DVec3, DVec3) {
    let u = surface.uder(native.x, native.y);
    let v = surface.vder(native.x, native.y);
    (DVec3::new(u.x, u.y, u.z), DVec3::new(v.x, v.y, v.z))
}

/// Samples along the meridian when a surface is checked for poles at both ends.
const MERIDIAN_SAMPLES: usize = 16;
/// Steps of the golden-section search for a pole along a periodic meridian.
const GOLDEN_SECTION_STEPS: usize = 80;

/// A surface closed on itself from pole to pole: periodic in its angle about an axis, its other
/// parameter running between two poles (a full sphere, a closed surface of revolution). STEP
/// writes a face covering such a surface with a vertex loop only (no edge), so flatcut splits it
/// along its middle parallel into two caps, each bounded by that parallel and a seam meridian out
/// to its pole and back (the layout of a hemisphere's face), and meshes each cap in the polar map.
#[derive(Debug, Clone)]
pub struct PoleToPole {
    surface: StepSurface,
    angular: Axis,
    period: f64,
    /// The meridian parameter at the two poles.
    poles: [f64; 2],
    /// Angle of the seam meridian (the parallel's start).
    angle0: f64,
}

impl PoleToPole {
    /// The surface's pole-to-pole structure, if it has one: a periodic angle whose parallel's
    /// radius `|∂S/∂θ|` vanishes (relative to its largest) at two values of the other parameter,
    /// the ends of its range, or, when that parameter is periodic too (a full ellipse revolved
    /// covers its ellipsoid twice), two consecutive zeros over one period.
    pub fn of(surface: &StepSurface) -> Option<Self> {
        let periods = [surface.u_period(), surface.v_period()];
        let (u, v) = surface.parameter_range();
        [
            (Axis::U, periods[0], v, periods[1]),
            (Axis::V, periods[1], u, periods[0]),
        ]
        .into_iter()
        .find_map(|(angular, period, range, meridian_period)| {
            Self::about(surface, angular, period?, range, meridian_period)
        })
    }

    fn about(
        surface: &StepSurface,
        angular: Axis,
        period: f64,
        range: (Bound<f64>, Bound<f64>),
        meridian_period: Option<f64>,
    ) -> Option<Self> {
        let finite = |bound: Bound<f64>| match bound {
            Bound::Included(t) | Bound::Excluded(t) => Some(t).filter(|t| t.is_finite()),
            Bound::Unbounded => None,
        };
        let (t0, t1) = match meridian_period {
            Some(meridian_period) => {
                let start = finite(range.0).unwrap_or(0.0);
                (start, start + meridian_period)
            }
            None => (finite(range.0)?, finite(range.1)?),
        };
        if t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        let closed = PoleToPole {
            surface: surface.clone(),
            angular,
            period,
            poles: [t0, t1],
            angle0: 0.0,
        };
        let step = (t1 - t0) / MERIDIAN_SAMPLES as f64;
        let radii: Vec<f64> = (0..=MERIDIAN_SAMPLES)
            .map(|i| closed.parallel_radius(t0 + step * i as f64))
            .collect();
        let largest = radii.iter().copied().fold(0.0_f64, f64::max);
        if !(largest > 0.0 && largest.is_finite()) {
            return None;
        }
        let is_pole = |t: f64| closed.parallel_radius(t) <= POLE_RATIO * largest;
        let poles = match meridian_period {
            None => [t0, t1],
            Some(_) => {
                let count = MERIDIAN_SAMPLES;
                let mut zeros = (0..count)
                    .filter(|&i| {
                        radii[i] <= radii[(i + count - 1) % count] && radii[i] <= radii[i + 1]
                    })
                    .map(|i| {
                        let t = t0 + step * i as f64;
                        closed.smallest_radius(t - step, t + step)
                    })
                    .filter(|&t| is_pole(t));
                let first = zeros.next()?;
                let second = zeros.find(|&t| t - first > 0.5 * step)?;
                [first, second]
            }
        };
        (is_pole(poles[0]) && is_pole(poles[1])).then_some(PoleToPole { poles, ..closed })
    }

    /// The parameter in `[low, high]` where the parallel's radius is smallest (golden section).
    fn smallest_radius(&self, mut low: f64, mut high: f64) -> f64 {
        let ratio = 0.5 * (5.0_f64.sqrt() - 1.0);
        for _ in 0..GOLDEN_SECTION_STEPS {
            let a = high - ratio * (high - low);
            let b = low + ratio * (high - low);
            if self.parallel_radius(a) <= self.parallel_radius(b) {
                high = b;
            } else {
                low = a;
            }
        }
        0.5 * (low + high)
    }

    fn parallel_radius(&self, t: f64) -> f64 {
        let (su, sv) = native_derivatives(&self.surface, self.angular.join(t, self.angle0));
        match self.angular {
            Axis::U => su.length(),
            Axis::V => sv.length(),
        }
    }

    fn middle(&self) -> f64 {
        0.5 * (self.poles[0] + self.poles[1])
    }

    /// The point of the middle parallel at `s` of the way round (0 and 1 on the seam).
    pub fn parallel(&self, s: f64) -> DVec3 {
        let angle = self.angle0 + self.period * s;
        native_point(&self.surface, self.angular.join(self.middle(), angle))
    }

    /// The point of the seam meridian at `s` of the way from the middle parallel to pole
    /// `pole` (0 or 1).
    pub fn meridian(&self, pole: usize, s: f64) -> DVec3 {
        let t = self.middle() + (self.poles[pole] - self.middle()) * s;
        native_point(&self.surface, self.angular.join(t, self.angle0))
    }

    /// Points on a grid of parallels and meridians (for the part's size).
    pub fn grid_points(&self) -> Vec<DVec3> {
        let count = MERIDIAN_SAMPLES;
        let mut points = Vec::with_capacity((count + 1) * (count + 1));
        for i in 0..=count {
            let t = self.poles[0] + (self.poles[1] - self.poles[0]) * i as f64 / count as f64;
            for j in 0..=count {
                let angle = self.angle0 + self.period * j as f64 / count as f64;
                points.push(native_point(&self.surface, self.angular.join(t, angle)));
            }
        }
        points
    }
}

/// Relative spread of a parameter along an edge below which the edge lies on an iso-parameter
/// line (a seam, a circle of a cone, a B-spline patch's side); its points then get exactly the
/// same parameter, so the loop is straight there and the mesher makes no sliver along it.
const ISO_LINE_RATIO: f64 = 1e-7;

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
    let loops = native_loops
        .iter()
        .map(|native| native.iter().map(|&p| map.domain_of(p)).collect())
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

/// The largest principal curvature `|H| + √(H² − K)` on a grid over the loops' parameter box,
/// away from a pole (a cone's curvature grows without bound at its apex, where its triangles
/// are small across the rulings anyway).
fn largest_curvature(
    surface: &StepSurface,
    native_loops: &[Vec<DVec2>],
    pole: Option<(Axis, f64)>,
) -> f64 {
    let (low, high) = native_loops
        .iter()
        .flatten()
        .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(low, high), &p| {
            (low.min(p), high.max(p))
        });
    if !(low.is_finite() && high.is_finite()) {
        return 0.0;
    }
    let mut largest = 0.0_f64;
    for i in 0..=CURVATURE_SAMPLES {
        for j in 0..=CURVATURE_SAMPLES {
            let t = DVec2::new(i as f64, j as f64) / CURVATURE_SAMPLES as f64;
            let p = low + (high - low) * t;
            if let Some((angular, t_pole)) = pole {
                let range = angular.split(high - low).0;
                if (angular.split(p).0 - t_pole).abs() < POLE_CURVATURE_EXCLUSION * range {
                    continue;
                }
            }
            if let Some(curvature) = principal_curvature(surface, p) {
                largest = largest.max(curvature);
            }
        }
    }
    largest
}

/// The largest principal curvature `|H| + √(H² − K)` at parameters `p` (none where the surface
/// is singular).
fn principal_curvature(surface: &StepSurface, p: DVec2) -> Option<f64> {
    let vector = |v: Vector3| DVec3::new(v.x, v.y, v.z);
    let (su, sv) = native_derivatives(surface, p);
    let (suu, suv, svv) = (
        vector(surface.uuder(p.x, p.y)),
        vector(surface.uvder(p.x, p.y)),
        vector(surface.vvder(p.x, p.y)),
    );
    let normal = su.cross(sv).normalize_or_zero();
    let (e, f, g) = (su.dot(su), su.dot(sv), sv.dot(sv));
    let (l, m, n) = (suu.dot(normal), suv.dot(normal), svv.dot(normal));
    let area = e * g - f * f;
    if area.partial_cmp(&(f64::EPSILON * e * g)) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let mean = (e * n + g * l - 2.0 * f * m) / (2.0 * area);
    let gauss = (l * n - m * m) / area;
    Some(mean.abs() + (mean * mean - gauss).max(0.0).sqrt()).filter(|c| c.is_finite())
}

/// For a cone and `apex` its apex (a point where the parallel's radius vanishes): the product
/// `κ d` of the cone's largest curvature and the distance from the apex, constant along the
/// cone (`1 / tan` of its half-angle), measured at `far` (a point of the cone away from the
/// apex). `None` on other surfaces and points.
pub fn apex_curvature(surface: &StepSurface, apex: DVec3, far: DVec3, size: f64) -> Option<f64> {
    let StepSurface::ElementarySurface(elementary) = surface else {
        return None;
    };
    if !matches!(elementary.as_ref(), ElementarySurface::ConicalSurface(_)) {
        return None;
    }
    let periods = [surface.u_period(), surface.v_period()];
    let tolerance = INVERSION_TOLERANCE_RATIO * size;
    let on_surface = |point: DVec3| {
        global_inversion(surface, point, periods, [None, None])
            .filter(|&p| native_point(surface, p).distance(point) <= tolerance)
    };
    let at_apex = on_surface(apex)?;
    let (su, sv) = native_derivatives(surface, at_apex);
    let angular_speed = match periods {
        [Some(_), None] => su.length(),
        [None, Some(_)] => sv.length(),
        _ => return None,
    };
    if angular_speed > POLE_RATIO * size {
        return None;
    }
    let product = principal_curvature(surface, on_surface(far)?)? * far.distance(apex);
    (product > 0.0 && product.is_finite()).then_some(product)
}

/// Each parameter's range where evaluation must stay inside it (B-spline and NURBS surfaces, not
/// periodic); `None` elsewhere (elementary surfaces extend beyond their nominal ranges).
fn parameter_ranges(surface: &StepSurface, periods: [Option<f64>; 2]) -> [Option<(f64, f64)>; 2] {
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
fn invert_loop(
    surface: &StepSurface,
    points: &[DVec3],
    periods: [Option<f64>; 2],
    ranges: [Option<(f64, f64)>; 2],
    size: f64,
) -> Result<Vec<DVec2>, DomainError> {
    let tolerance = INVERSION_TOLERANCE_RATIO * size.max(f64::MIN_POSITIVE);
    let mut native: Vec<DVec2> = Vec::with_capacity(points.len());
    for &point in points {
        let previous = native.last().copied();
        let guess = previous
            .map(|p| refine_inversion(surface, point, p, ranges))
            .filter(|&p| native_point(surface, p).distance(point) <= tolerance)
            .or_else(|| global_inversion(surface, point, periods, ranges))
            .filter(|&p| native_point(surface, p).distance(point) <= tolerance)
            .ok_or_else(|| {
                DomainError(format!(
                    "the boundary point ({:.6}, {:.6}, {:.6}) is not on the face's surface",
                    point.x, point.y, point.z
                ))
            })?;
        native.push(match previous {
            Some(previous) => unwrap_near(guess, previous, periods),
            None => guess,
        });
    }
    Ok(native)
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
        if smallest > POLE_RATIO * size || smallest.is_nan() || count < 3 {
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

/// The polar map about the pole at `t_pole` (see [`DomainMap::Polar`]), tabulated along the
/// meridian from the pole to the loops' farthest parameter.
fn polar_map(
    surface: &StepSurface,
    native_loops: &[Vec<DVec2>],
    angular: Axis,
    t_pole: f64,
) -> Option<DomainMap> {
    let angle0 = angular.split(*native_loops.first()?.first()?).1;
    let t_far = native_loops
        .iter()
        .flatten()
        .map(|&p| angular.split(p).0)
        .max_by(|a, b| (a - t_pole).abs().total_cmp(&(b - t_pole).abs()))?;
    let step = (t_far - t_pole) / POLAR_SAMPLES as f64;
    if !(step.is_finite() && step != 0.0) {
        return None;
    }
    let radius_speed = |t: f64| {
        let (su, sv) = native_derivatives(surface, angular.join(t, angle0));
        match angular {
            Axis::U => (su.length(), sv.length()),
            Axis::V => (sv.length(), su.length()),
        }
    };
    let t: Vec<f64> = (0..=POLAR_SAMPLES)
        .map(|i| t_pole + step * i as f64)
        .collect();
    // The meridian's arc length to the first sample, and c = r / G there.
    let substeps = 16;
    let first_arc: f64 = (0..substeps)
        .map(|j| radius_speed(t_pole + step * (j as f64 + 0.5) / substeps as f64).1)
        .sum::<f64>()
        * step.abs()
        / substeps as f64;
    let c = radius_speed(t[1]).0 / first_arc;
    let c = if (1.0 - c).abs() <= SMOOTH_POLE_TOLERANCE {
        1.0
    } else {
        c
    };
    if !(c > 0.0 && c < 1.0 + SMOOTH_POLE_TOLERANCE && first_arc > 0.0) {
        return None;
    }
    let mut g = vec![0.0, first_arc];
    let mut log = first_arc.ln();
    for &sample in &t[1..POLAR_SAMPLES] {
        let (radius, speed) = radius_speed(sample + 0.5 * step);
        log += c * speed * step.abs() / radius;
        g.push(log.exp());
    }
    if !g.iter().all(|v| v.is_finite()) || g.windows(2).any(|w| w[1] <= w[0]) {
        return None;
    }
    Some(DomainMap::Polar(PolarMap {
        angular,
        c,
        angle0,
        t,
        g,
    }))
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

/// Truck's own search, or the best point of a parameter grid, polished by Gauss-Newton.
fn global_inversion(
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

/// The map that suits the surface: cones developed, cylinders unrolled, the rest native.
fn domain_map(
    surface: &StepSurface,
    native_loops: &[Vec<DVec2>],
    periods: [Option<f64>; 2],
) -> DomainMap {
    if let Some(mercator) = mercator_map(surface, native_loops) {
        return mercator;
    }
    let StepSurface::ElementarySurface(elementary) = surface else {
        return DomainMap::Native;
    };
    if !matches!(
        elementary.as_ref(),
        ElementarySurface::CylindricalSurface(_) | ElementarySurface::ConicalSurface(_)
    ) {
        return DomainMap::Native;
    }
    let angular = match periods {
        [Some(_), None] => Axis::U,
        [None, Some(_)] => Axis::V,
        _ => return DomainMap::Native,
    };
    let (mut low, mut high) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
    for p in native_loops.iter().flatten() {
        low = low.min(*p);
        high = high.max(*p);
    }
    let ((t0, angle0), (t1, _)) = (angular.split(low), angular.split(high));
    if !(t0.is_finite() && t1.is_finite()) {
        return DomainMap::Native;
    }
    let t1 = if t1 > t0 { t1 } else { t0 + 1.0 };
    let radius_speed = |t: f64| {
        let (su, sv) = native_derivatives(surface, angular.join(t, angle0));
        match angular {
            Axis::U => (su.length(), sv.length()),
            Axis::V => (sv.length(), su.length()),
        }
    };
    let ((radius0, speed), (radius1, _)) = (radius_speed(t0), radius_speed(t1));
    let slope = (radius1 - radius0) / (t1 - t0);
    if !(speed > 0.0 && radius0.max(radius1) > 0.0) {
        return DomainMap::Native;
    }
    if slope.abs() <= CYLINDER_SLOPE * speed {
        return DomainMap::Unrolled {
            angular,
            radius: 0.5 * (radius0 + radius1),
            speed,
        };
    }
    let k = slope.abs() / speed;
    let (near, far) = (radius0.min(radius1) / k, radius0.max(radius1) / k);
    if near < APEX_RATIO * far {
        return DomainMap::Native;
    }
    DomainMap::Developed {
        angular,
        r0: radius0 - slope * t0,
        slope,
        k,
        reference: far,
    }
}

/// Relative change of a surface of revolution's parallel radius and meridian speed along a
/// parallel below which the angular parameter is the angle about its axis.
const REVOLUTION_TOLERANCE: f64 = 1e-9;

/// Whether `surface` is a sphere, a torus or a revolved curve (the surfaces the Mercator map is
/// for; cylinders and cones have their own maps).
fn is_revolution(surface: &StepSurface) -> bool {
    match surface {
        StepSurface::ElementarySurface(elementary) => matches!(
            elementary.as_ref(),
            ElementarySurface::Sphere(_) | ElementarySurface::ToroidalSurface(_)
        ),
        StepSurface::SweptCurve(swept) => matches!(swept.as_ref(), SweptCurve::RevolutedCurve(_)),
        _ => false,
    }
}

/// The periodic parameter of a surface of revolution that is its angle about the axis: along
/// it, the parallel's radius `|∂S/∂θ|` and the meridian's speed `|∂S/∂t|` do not change (a
/// torus's tube angle has a constant speed but the other parameter's speed changes along it).
fn revolution_angle(surface: &StepSurface, at: DVec2) -> Option<Axis> {
    [(Axis::U, surface.u_period()), (Axis::V, surface.v_period())]
        .into_iter()
        .filter(|(_, period)| period.is_some())
        .map(|(axis, _)| axis)
        .find(|&axis| {
            let (t, angle) = axis.split(at);
            let speeds = |angle: f64| {
                let (su, sv) = native_derivatives(surface, axis.join(t, angle));
                match axis {
                    Axis::U => DVec2::new(su.length(), sv.length()),
                    Axis::V => DVec2::new(sv.length(), su.length()),
                }
            };
            let reference = speeds(angle);
            let scale = reference.max_element();
            scale > 0.0
                && [0.7, 2.1, 4.4].iter().all(|&turn| {
                    (speeds(angle + turn) - reference).abs().max_element()
                        <= REVOLUTION_TOLERANCE * scale
                })
        })
}

/// The Mercator map of a face of a surface of revolution that stays away from its poles (see
/// [`DomainMap::Mercator`]), tabulated over the loops' range of the meridian parameter.
fn mercator_map(surface: &StepSurface, native_loops: &[Vec<DVec2>]) -> Option<DomainMap> {
    if !is_revolution(surface) {
        return None;
    }
    let first = *native_loops.first()?.first()?;
    let angular = revolution_angle(surface, first)?;
    let angle0 = angular.split(first).1;
    let (low, high) = native_loops
        .iter()
        .flatten()
        .map(|&p| angular.split(p).0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), t| {
            (low.min(t), high.max(t))
        });
    let step = (high - low) / POLAR_SAMPLES as f64;
    if !(step.is_finite() && step > 0.0) {
        return None;
    }
    let radius_speed = |t: f64| {
        let (su, sv) = native_derivatives(surface, angular.join(t, angle0));
        match angular {
            Axis::U => (su.length(), sv.length()),
            Axis::V => (sv.length(), su.length()),
        }
    };
    let t: Vec<f64> = (0..=POLAR_SAMPLES).map(|i| low + step * i as f64).collect();
    let radius0 = t.iter().map(|&t| radius_speed(t).0).fold(0.0_f64, f64::max);
    let mut y = Vec::with_capacity(t.len());
    let mut total = 0.0;
    y.push(total);
    for &sample in &t[..POLAR_SAMPLES] {
        let (radius, speed) = radius_speed(sample + 0.5 * step);
        total += radius0 * speed * step / radius;
        y.push(total);
    }
    if !y.iter().all(|v| v.is_finite()) || y.windows(2).any(|w| w[1] <= w[0]) {
        return None;
    }
    Some(DomainMap::Mercator(MercatorMap {
        angular,
        radius0,
        t,
        y,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_development_of_a_cone_round_trips() {
        let map = DomainMap::Developed {
            angular: Axis::V,
            r0: 100.0,
            slope: -0.5,
            k: 0.53,
            reference: 190.0,
        };
        for native in [DVec2::new(0.0, 0.1), DVec2::new(60.0, 6.0)] {
            let back = map.native_of(map.domain_of(native));
            assert!(back.distance(native) < 1e-9, "{native} -> {back}");
        }
    }

    #[test]
    fn a_mercator_map_round_trips_and_its_derivatives_match() {
        let t: Vec<f64> = (0..=8).map(|i| 0.25 * i as f64).collect();
        let y: Vec<f64> = t.iter().map(|t| 3.0 * t + t * t).collect();
        let map = DomainMap::Mercator(MercatorMap {
            angular: Axis::U,
            radius0: 40.0,
            t,
            y,
        });
        for native in [DVec2::new(0.3, 0.1), DVec2::new(5.9, 1.6)] {
            let domain = map.domain_of(native);
            assert!(map.native_of(domain).distance(native) < 1e-12);
            let (dx, dy) = map.native_derivatives(domain);
            let step = 1e-7;
            let along = |offset: DVec2| {
                (map.native_of(domain + offset) - map.native_of(domain - offset)) / (2.0 * step)
            };
            assert!(along(DVec2::X * step).distance(dx) < 1e-6, "{dx}");
            assert!(along(DVec2::Y * step).distance(dy) < 1e-6, "{dy}");
        }
    }

    #[test]
    fn a_polar_map_round_trips_on_both_sides_of_its_cut() {
        // A cone's apex (c = 0.5): g grows linearly with the distance from the pole.
        let t: Vec<f64> = (0..=10).map(|i| i as f64).collect();
        let g: Vec<f64> = t.iter().map(|t| 2.0 * t).collect();
        let map = DomainMap::Polar(PolarMap {
            angular: Axis::V,
            c: 0.5,
            angle0: 1.0,
            t,
            g,
        });
        for native in [
            DVec2::new(3.5, 1.0),
            DVec2::new(7.25, 1.0 + 6.2),
            DVec2::new(9.0, 1.0 + 3.0),
        ] {
            let back = map.native_of(map.domain_of(native));
            assert!(back.distance(native) < 1e-9, "{native} -> {back}");
        }
    }
}
