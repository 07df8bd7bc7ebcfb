//! Bends on cones: a flange tangent to a cone along a generator runs into a conical bend, whose
//! skins are coaxial cones of one half-angle `t` apart along the normal. The bend is developed
//! at its neutral cone (the inner cone moved `K · t` outwards along the normal, a coaxial cone
//! too), so its flat width at a point of the bend line is `θ_c · (R + K · t)`, `R` the inner
//! radius of curvature there and `θ_c = Δφ · cos α` the developed angle (`Δφ` the bend's angle
//! about the axis, `α` the half-angle); see `docs/sheet-metal.md`, "Conical bends".

use glam::{DVec2, DVec3};

use super::bend::ConicalBend;
use super::face_map::{ConeMap, PlaneMap};
use super::surfaces::{SheetSurface, cone_offset};

/// A conical bend as the unfold enters it from a flange.
#[derive(Debug, Clone, Copy)]
pub(super) struct ConeEntry {
    /// Its development.
    pub map: ConeMap,
    /// The inner radius at the middle of the entered face.
    pub inner_radius: f64,
    /// Whether the drawn skin is the inner one.
    pub skin_inside: bool,
}

/// The conical bend a flange (`plane`, its surface `flange`) runs into at a cone face
/// (`cone`, the skin's; `partner`, the opposite skin's), whose triangle vertices are
/// `positions`: developed from the tangent generator, turning the way the face lies, its
/// neutral cone at the radius `neutral` gives for an inner radius, with the sheet `thickness`.
pub(super) fn enter_cone_bend(
    plane: &PlaneMap,
    flange: &SheetSurface,
    cone: &SheetSurface,
    partner: &SheetSurface,
    positions: impl Iterator<Item = DVec3> + Clone,
    thickness: f64,
    neutral: &dyn Fn(f64) -> f64,
) -> ConeEntry {
    let SheetSurface::Cone {
        apex,
        axis,
        half_angle,
    } = *cone
    else {
        unreachable!("a conical bend is a cone");
    };
    let SheetSurface::Plane { normal, .. } = *flange else {
        unreachable!("a bend is entered from a flange");
    };
    let skin_inside = match *partner {
        SheetSurface::Cone {
            apex: partner_apex, ..
        } => cone_offset(apex, axis, half_angle, partner_apex) > 0.0,
        _ => true,
    };
    let mut map = ConeMap {
        apex,
        axis,
        start: DVec3::ZERO,
        towards: DVec3::ZERO,
        half_angle,
        slant_shift: 0.0,
        flat_origin: DVec2::ZERO,
        flat_axis: DVec2::ZERO,
        flat_across: DVec2::ZERO,
    };
    let across_axis = normal - axis * normal.dot(axis);
    map.start = if normal.dot(axis) <= 0.0 {
        across_axis
    } else {
        -across_axis
    }
    .normalize_or_zero();
    let across = axis.cross(map.start);
    let farthest = positions
        .clone()
        .map(|p| (p - apex).dot(across))
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(1.0);
    map.towards = if farthest >= 0.0 { across } else { -across };
    let (low, high) = slant_range(positions.map(|p| p.distance(apex)));
    let inner_radius = inner_radius_at(&map, skin_inside, thickness, (low + high) / 2.0);
    // The neutral cone's distance outside the skin, along the normal.
    let outside_skin =
        neutral(inner_radius) - inner_radius - if skin_inside { 0.0 } else { thickness };
    map.slant_shift = outside_skin / half_angle.tan();
    let generator = axis * half_angle.cos() + map.start * half_angle.sin();
    map.flat_axis = plane.direction(generator);
    map.flat_across = plane.direction(map.towards);
    map.flat_origin = plane.point(apex) - map.flat_axis * map.slant_shift;
    ConeEntry {
        map,
        inner_radius,
        skin_inside,
    }
}

/// The smallest and largest of some distances.
fn slant_range(slants: impl Iterator<Item = f64>) -> (f64, f64) {
    slants.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), s| {
        (low.min(s), high.max(s))
    })
}

/// The inner radius of curvature across the bend at distance `slant` from the skin cone's apex:
/// the skin's is `slant · tan α`, less the thickness when the skin is the outer one.
fn inner_radius_at(map: &ConeMap, skin_inside: bool, thickness: f64, slant: f64) -> f64 {
    slant * map.half_angle.tan() - if skin_inside { 0.0 } else { thickness }
}

/// A conical bend's figures, from its skin points.
#[derive(Debug, Clone, Copy)]
pub(super) struct ConeFigures {
    /// The bend's angle about the axis, `Δφ`, radians.
    pub sweep: f64,
    /// The developed angle `θ_c = Δφ · cos α`, radians: the allowance is `θ_c` times the neutral
    /// radius of curvature.
    pub developed_angle: f64,
    /// The angle between the two flanges' normals (how far the flange turns), radians:
    /// `cos = sin² α + cos² α · cos Δφ`.
    pub turn: f64,
    /// The skin points' smallest and largest distance from the apex.
    pub slants: [f64; 2],
    /// The inner radius at those two distances.
    pub inner_radii: [f64; 2],
}

impl ConeFigures {
    /// The figures of a conical bend developed by `map` whose skin points are `points`.
    pub fn of(map: &ConeMap, skin_inside: bool, thickness: f64, points: &[DVec3]) -> Self {
        let sweep = points.iter().map(|&p| map.angle(p)).fold(0.0, f64::max);
        let (low, high) = slant_range(points.iter().map(|&p| map.slant(p)));
        let (sin, cos) = map.half_angle.sin_cos();
        let turn = (sin * sin + cos * cos * sweep.cos())
            .clamp(-1.0, 1.0)
            .acos();
        Self {
            sweep,
            developed_angle: sweep * cos,
            turn,
            slants: [low, high],
            inner_radii: [low, high].map(|s| inner_radius_at(map, skin_inside, thickness, s)),
        }
    }

    /// The inner radius at the middle of the bend line.
    pub fn middle_inner_radius(&self) -> f64 {
        (self.inner_radii[0] + self.inner_radii[1]) / 2.0
    }

    /// The bend line on the flat (the developed generator halfway through the bend, end to
    /// end) and what a conical bend adds to it: the radius, allowance and zone edges at the ends.
    pub fn line(&self, map: &ConeMap) -> ([DVec2; 2], ConicalBend) {
        let [low, high] = self.slants;
        let at = |angle: f64| [map.flat(low, angle), map.flat(high, angle)];
        let developed = self.sweep * map.half_angle.sin();
        let conical = ConicalBend {
            inner_radii: self.inner_radii,
            allowances: self.slants.map(|s| developed * (s + map.slant_shift)),
            developed_angle_degrees: self.developed_angle.to_degrees(),
            zone: [at(0.0), at(self.sweep)],
        };
        (at(self.sweep / 2.0), conical)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;

    /// A cone about z, apex at the origin, tan α = 0.1, entered from the flange tangent to it
    /// along the generator in the xz plane (normal (cos α, 0, −sin α)), laid on the flat so that
    /// that generator runs along +x from the origin.
    fn entry(skin_inside: bool) -> ConeEntry {
        let alpha = 0.1f64.atan();
        let (sin, cos) = alpha.sin_cos();
        let normal = DVec3::new(cos, 0.0, -sin);
        let generator = DVec3::new(sin, 0.0, cos);
        let plane = PlaneMap {
            origin: DVec3::ZERO,
            axes: [generator, DVec3::Y],
            flat_origin: DVec2::ZERO,
            flat_axes: [DVec2::X, DVec2::Y],
        };
        let cone = SheetSurface::Cone {
            apex: DVec3::ZERO,
            axis: DVec3::Z,
            half_angle: alpha,
        };
        // The other skin 2 mm outside (inside) along the normal: its apex 2 / sin α below
        // (above) the skin's.
        let offset = if skin_inside { -2.0 } else { 2.0 } / sin;
        let partner = SheetSurface::Cone {
            apex: DVec3::Z * offset,
            axis: DVec3::Z,
            half_angle: alpha,
        };
        let flange = SheetSurface::Plane {
            origin: DVec3::ZERO,
            normal,
        };
        let points = [generator * 20.0, DVec3::new(0.0, 2.0, 19.9)];
        enter_cone_bend(
            &plane,
            &flange,
            &cone,
            &partner,
            points.into_iter(),
            2.0,
            &|inner| inner + 0.44 * 2.0,
        )
    }

    #[test]
    fn the_neutral_cone_lies_k_t_outside_the_inner_skin() {
        let inside = entry(true);
        assert!(inside.skin_inside);
        assert!((inside.map.slant_shift - 0.88 * 10.0).abs() < 1e-9);
        assert!(inside.map.towards.distance(DVec3::Y) < 1e-12);
        let outside = entry(false);
        assert!(!outside.skin_inside);
        assert!((outside.map.slant_shift + 1.12 * 10.0).abs() < 1e-9);
        // The start generator keeps its place on the flat.
        let point = DVec3::new(0.1, 0.0, 1.0).normalize() * 30.0;
        assert!(inside.map.point(point).distance(DVec2::new(30.0, 0.0)) < 1e-9);
    }

    #[test]
    fn a_quarter_turn_about_the_axis_develops_to_its_neutral_arc_and_the_flange_follows() {
        let map = entry(true).map;
        let alpha = map.half_angle;
        let radial = DVec3::Y;
        let generator = DVec3::Z * alpha.cos() + radial * alpha.sin();
        let point = generator * 40.0;
        assert!((map.angle(point) - FRAC_PI_2).abs() < 1e-12);
        let developed = FRAC_PI_2 * alpha.sin();
        let apex = DVec2::new(-map.slant_shift, 0.0);
        let expected =
            apex + DVec2::new(developed.cos(), developed.sin()) * (40.0 + map.slant_shift);
        assert!(map.point(point).distance(expected) < 1e-9);
        // The flange tangent along that generator: normal (0, cos α, −sin α).
        let normal = DVec3::new(0.0, alpha.cos(), -alpha.sin());
        let angle = map.tangent_angle(normal);
        assert!((angle - FRAC_PI_2).abs() < 1e-12);
        let flange = map.flange_at(angle);
        assert!(flange.point(point).distance(expected) < 1e-9);
        // 5 mm on along the circumference (−x here) from that point, perpendicular on the flat.
        let onward = flange.point(point - DVec3::X * 5.0);
        let across = DVec2::new(-developed.sin(), developed.cos());
        assert!(onward.distance(expected + across * 5.0) < 1e-9);
    }
}
