//! How a STEP face's parameters map to the domain it is meshed in, so that the domain has
//! (nearly) the surface's own metric: cylinders unrolled, cones developed in log-polar
//! coordinates, faces through a pole in conformal polar coordinates about it, other faces of
//! surfaces of revolution in Mercator coordinates, other surfaces in their own parameters.

use glam::DVec2;
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::{ElementarySurface, Surface as StepSurface, SweptCurve};

use super::native::native_derivatives;
use crate::geometry::tolerance::{CYLINDER_SLOPE, REVOLUTION_TOLERANCE, SMOOTH_POLE_TOLERANCE};

/// A cone face reaching closer to its apex than this fraction of its largest distance from it
/// keeps its own parameters (the log-polar map is singular at the apex).
const APEX_RATIO: f64 = 1e-3;

/// Samples of a polar map's table along the meridian.
const POLAR_SAMPLES: usize = 1024;

/// Finite-difference step of a polar map's derivatives, fraction of the domain's radius.
const POLAR_DIFFERENCE_RATIO: f64 = 1e-6;

/// How a face's parameters `(u, v)` map to the domain it is meshed in.
#[derive(Debug, Clone, PartialEq)]
pub enum DomainMap {
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
pub struct MercatorMap {
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
pub struct PolarMap {
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
pub enum Axis {
    U,
    V,
}

impl Axis {
    /// `(t, θ)` (ruling parameter, angle) from `(u, v)`.
    pub fn split(self, native: DVec2) -> (f64, f64) {
        match self {
            Axis::U => (native.y, native.x),
            Axis::V => (native.x, native.y),
        }
    }

    /// `(u, v)` from `(t, θ)`.
    pub fn join(self, t: f64, angle: f64) -> DVec2 {
        match self {
            Axis::U => DVec2::new(angle, t),
            Axis::V => DVec2::new(t, angle),
        }
    }
}

impl DomainMap {
    pub fn domain_of(&self, native: DVec2) -> DVec2 {
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

    pub fn native_of(&self, domain: DVec2) -> DVec2 {
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
    pub fn native_derivatives(&self, domain: DVec2) -> (DVec2, DVec2) {
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

/// The polar map about the pole at `t_pole` (see [`DomainMap::Polar`]), tabulated along the
/// meridian from the pole to the loops' farthest parameter.
pub fn polar_map(
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

/// The map that suits the surface: cones developed, cylinders unrolled, the rest native.
pub fn domain_map(
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
    use crate::tessellate::domain_map::*;

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
