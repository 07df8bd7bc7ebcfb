//! A STEP surface evaluated at its own parameters.

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::Surface as StepSurface;

/// The surface's point at its own parameters.
pub fn native_point(surface: &StepSurface, native: DVec2) -> DVec3 {
    let p = surface.subs(native.x, native.y);
    DVec3::new(p.x, p.y, p.z)
}

/// The surface's partial derivatives at its own parameters.
pub fn native_derivatives(surface: &StepSurface, native: DVec2) -> (DVec3, DVec3) {
    let u = surface.uder(native.x, native.y);
    let v = surface.vder(native.x, native.y);
    (DVec3::new(u.x, u.y, u.z), DVec3::new(v.x, v.y, v.z))
}
