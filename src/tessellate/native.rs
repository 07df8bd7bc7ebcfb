//! A STEP surface evaluated at its own parameters, and what makes a boundary point a pole.

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::Surface as StepSurface;

/// A boundary point where the parallel's radius `|∂S/∂θ|` is below this fraction of the face's
/// size is a pole.
pub const POLE_RATIO: f64 = 1e-7;

pub fn native_point(surface: &StepSurface, native: DVec2) -> DVec3 {
    let p = surface.subs(native.x, native.y);
    DVec3::new(p.x, p.y, p.z)
}

pub fn native_derivatives(surface: &StepSurface, native: DVec2) -> (DVec3, DVec3) {
    let u = surface.uder(native.x, native.y);
    let v = surface.vder(native.x, native.y);
    (DVec3::new(u.x, u.y, u.z), DVec3::new(v.x, v.y, v.z))
}
