//! Curvature sampling of a STEP face's surface: the largest principal curvature over a face (for
//! its mesh size), and a cone's curvature toward its apex (for grading the edges that reach it).

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::{ElementarySurface, Surface as StepSurface};

use super::domain_map::Axis;
use super::inversion::global_inversion;
use super::native::{native_derivatives, native_point};
use crate::geometry::tolerance::{INVERSION_TOLERANCE_RATIO, STEP_POLE_RATIO};

/// Grid intervals per parameter on which a face's curvature is sampled.
const CURVATURE_SAMPLES: usize = 6;

/// Curvature is not sampled within this fraction of the parameter range from a pole.
const POLE_CURVATURE_EXCLUSION: f64 = 0.25;

/// The largest principal curvature `|H| + √(H² − K)` on a grid over the loops' parameter box,
/// away from a pole (a cone's curvature grows without bound at its apex, where its triangles
/// are small across the rulings anyway).
pub fn largest_curvature(
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
    if angular_speed > STEP_POLE_RATIO * size {
        return None;
    }
    let product = principal_curvature(surface, on_surface(far)?)? * far.distance(apex);
    (product > 0.0 && product.is_finite()).then_some(product)
}
