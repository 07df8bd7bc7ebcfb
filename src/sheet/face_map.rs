//! Where each point of a skin face goes on the flat pattern: a rigid motion for a flange
//! (plane), for a bend on a cylinder its unrolling at the neutral fibre (the axial coordinate
//! kept, the angle turned into arc length at the neutral radius), and for a bend on a cone the
//! development of its neutral cone onto a circular sector (each point's distance from the apex
//! kept, its angle about the axis scaled by the sine of the half-angle).

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

/// Angles this far below zero are still the bend's start (round-off), not a full turn.
const ANGLE_ROUND_OFF: f64 = 1e-9;

/// A rigid map of a plane into the flat pattern: `origin` goes to `flat_origin`, the unit
/// in-plane directions `axes` to the unit flat directions `flat_axes`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneMap {
    /// A point of the plane.
    pub origin: DVec3,
    /// Two orthonormal directions in the plane.
    pub axes: [DVec3; 2],
    /// Where `origin` goes.
    pub flat_origin: DVec2,
    /// Where the two axes go (orthonormal).
    pub flat_axes: [DVec2; 2],
}

impl PlaneMap {
    /// The flat image of a direction lying in the plane.
    pub fn direction(&self, direction: DVec3) -> DVec2 {
        self.flat_axes[0] * direction.dot(self.axes[0])
            + self.flat_axes[1] * direction.dot(self.axes[1])
    }

    /// The flat image of a point of the plane.
    pub fn point(&self, point: DVec3) -> DVec2 {
        self.flat_origin + self.direction(point - self.origin)
    }
}

/// The unrolling of a bend: a point at axial coordinate `a` (from `axis_origin` along `axis`)
/// and angle `φ` (from the radial direction `start`, turning towards `towards`) goes to
/// `flat_origin + a · flat_axis + φ · neutral_radius · flat_across`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BendMap {
    /// A point of the axis.
    pub axis_origin: DVec3,
    /// Unit axis.
    pub axis: DVec3,
    /// Unit radial direction where the bend starts (φ = 0).
    pub start: DVec3,
    /// Unit direction, perpendicular to `axis` and `start`, the bend turns towards.
    pub towards: DVec3,
    /// The radius of the skin's cylinder.
    pub skin_radius: f64,
    /// The neutral fibre's radius, `R_inner + K · t`.
    pub neutral_radius: f64,
    /// Where the start line's point at `a = 0` goes.
    pub flat_origin: DVec2,
    /// Where the axis goes (unit).
    pub flat_axis: DVec2,
    /// The flat direction arc length runs along (unit, perpendicular to `flat_axis`).
    pub flat_across: DVec2,
}

impl BendMap {
    /// The axial coordinate of a point.
    pub fn axial(&self, point: DVec3) -> f64 {
        (point - self.axis_origin).dot(self.axis)
    }

    /// The angle of a point from the start line, in `[0, 2π)` (a round-off below 0 is 0).
    pub fn angle(&self, point: DVec3) -> f64 {
        let offset = point - self.axis_origin;
        let angle = offset.dot(self.towards).atan2(offset.dot(self.start));
        if angle < -ANGLE_ROUND_OFF {
            angle + TAU
        } else {
            angle.max(0.0)
        }
    }

    /// The unit radial direction at angle `angle`.
    pub fn radial(&self, angle: f64) -> DVec3 {
        self.start * angle.cos() + self.towards * angle.sin()
    }

    /// The flat position of axial coordinate `axial` and angle `angle`.
    pub fn flat(&self, axial: f64, angle: f64) -> DVec2 {
        self.flat_origin + self.flat_axis * axial + self.flat_across * (angle * self.neutral_radius)
    }

    /// The flat image of a point of the bend.
    pub fn point(&self, point: DVec3) -> DVec2 {
        self.flat(self.axial(point), self.angle(point))
    }

    /// The rigid map of the flange tangent to the bend at angle `angle`, continuing it: the
    /// tangent line keeps its flat position and the flange runs on along `flat_across`.
    pub fn flange_at(&self, angle: f64) -> PlaneMap {
        let radial = self.radial(angle);
        let onward = self.towards * angle.cos() - self.start * angle.sin();
        PlaneMap {
            origin: self.axis_origin + radial * self.skin_radius,
            axes: [self.axis, onward],
            flat_origin: self.flat(0.0, angle),
            flat_axes: [self.flat_axis, self.flat_across],
        }
    }
}

/// The development of a conical bend. A skin point at distance `s` from the skin cone's apex
/// and angle `φ` about the axis (from the generator along `start`, turning towards `towards`) is
/// projected along the normal onto the neutral cone, coaxial with the skin's and of the same
/// half-angle `α`, where its distance from the neutral apex is `s + slant_shift`
/// (`slant_shift = d · cot α` for a neutral cone `d` outside the skin); the neutral cone develops
/// onto a sector, isometrically: the point goes to polar coordinates `(s + slant_shift,
/// φ · sin α)` about `flat_origin` (the developed neutral apex), the angle measured from
/// `flat_axis` towards `flat_across`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConeMap {
    /// The skin cone's apex.
    pub apex: DVec3,
    /// Unit axis, from the apex into the cone.
    pub axis: DVec3,
    /// Unit radial direction (perpendicular to the axis) of the generator where the bend
    /// starts (φ = 0).
    pub start: DVec3,
    /// Unit direction, perpendicular to `axis` and `start`, the bend turns towards.
    pub towards: DVec3,
    /// The half-angle `α`, radians.
    pub half_angle: f64,
    /// The neutral cone's distance from its apex less the skin's, along one normal.
    pub slant_shift: f64,
    /// Where the developed neutral apex goes.
    pub flat_origin: DVec2,
    /// Where the start generator's direction goes (unit).
    pub flat_axis: DVec2,
    /// Unit, perpendicular to `flat_axis`: the side the development turns to.
    pub flat_across: DVec2,
}

impl ConeMap {
    /// A point's distance from the skin cone's apex (along its generator).
    pub fn slant(&self, point: DVec3) -> f64 {
        point.distance(self.apex)
    }

    /// The angle of a point about the axis from the start generator, in `[0, 2π)` (a round-off
    /// below 0 is 0).
    pub fn angle(&self, point: DVec3) -> f64 {
        let offset = point - self.apex;
        let angle = offset.dot(self.towards).atan2(offset.dot(self.start));
        if angle < -ANGLE_ROUND_OFF {
            angle + TAU
        } else {
            angle.max(0.0)
        }
    }

    /// The angle about the axis of the generator a plane tangent to the cone touches it along
    /// (the plane's unit `normal` either way round).
    pub fn tangent_angle(&self, normal: DVec3) -> f64 {
        let across_axis = normal - self.axis * normal.dot(self.axis);
        let outward = if normal.dot(self.axis) <= 0.0 {
            across_axis
        } else {
            -across_axis
        };
        self.angle(self.apex + outward.normalize_or_zero())
    }

    /// The unit flat direction of the developed generator at angle `angle` about the axis, and
    /// the unit flat direction perpendicular to it the development turns towards.
    fn flat_ray(&self, angle: f64) -> [DVec2; 2] {
        let (sin, cos) = (angle * self.half_angle.sin()).sin_cos();
        [
            self.flat_axis * cos + self.flat_across * sin,
            self.flat_across * cos - self.flat_axis * sin,
        ]
    }

    /// The flat position of the skin point at distance `slant` from the apex and angle `angle`.
    pub fn flat(&self, slant: f64, angle: f64) -> DVec2 {
        self.flat_origin + self.flat_ray(angle)[0] * (slant + self.slant_shift)
    }

    /// The flat image of a point of the bend.
    pub fn point(&self, point: DVec3) -> DVec2 {
        self.flat(self.slant(point), self.angle(point))
    }

    /// The rigid map of the flange tangent to the cone along the generator at angle `angle`,
    /// continuing it: the generator keeps its flat position (a ray of the sector) and the flange
    /// runs on perpendicular to it, the way the development turns.
    pub fn flange_at(&self, angle: f64) -> PlaneMap {
        let radial = self.start * angle.cos() + self.towards * angle.sin();
        let onward = self.towards * angle.cos() - self.start * angle.sin();
        let generator = self.axis * self.half_angle.cos() + radial * self.half_angle.sin();
        let [ray, across] = self.flat_ray(angle);
        PlaneMap {
            origin: self.apex,
            axes: [generator, onward],
            flat_origin: self.flat_origin + ray * self.slant_shift,
            flat_axes: [ray, across],
        }
    }
}

/// How a bend's skin goes flat: a cylinder unrolled or a cone developed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BendSurfaceMap {
    /// A bend on a cylinder.
    Cylinder(BendMap),
    /// A bend on a cone.
    Cone(ConeMap),
}

impl BendSurfaceMap {
    /// The angle of a point from the bend's start (about the axis).
    pub fn angle(&self, point: DVec3) -> f64 {
        match self {
            Self::Cylinder(map) => map.angle(point),
            Self::Cone(map) => map.angle(point),
        }
    }

    /// A point's position along the bend line: its axial coordinate on a cylinder, its distance
    /// from the apex on a cone.
    pub fn along(&self, point: DVec3) -> f64 {
        match self {
            Self::Cylinder(map) => map.axial(point),
            Self::Cone(map) => map.slant(point),
        }
    }

    /// The flat position at `along` ([`Self::along`]) and angle `angle`.
    pub fn flat(&self, along: f64, angle: f64) -> DVec2 {
        match self {
            Self::Cylinder(map) => map.flat(along, angle),
            Self::Cone(map) => map.flat(along, angle),
        }
    }

    /// The flat image of a point of the bend.
    pub fn point(&self, point: DVec3) -> DVec2 {
        match self {
            Self::Cylinder(map) => map.point(point),
            Self::Cone(map) => map.point(point),
        }
    }
}

/// How one skin face goes flat.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FaceMap {
    /// A flange, placed rigidly.
    Flange(PlaneMap),
    /// A bend (index into the unfold's bends), unrolled at the neutral fibre.
    Bend(usize, BendSurfaceMap),
}

impl FaceMap {
    /// The flat image of a point of the face.
    pub fn point(&self, point: DVec3) -> DVec2 {
        match self {
            Self::Flange(map) => map.point(point),
            Self::Bend(_, map) => map.point(point),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;

    #[test]
    fn a_quarter_bend_unrolls_to_its_neutral_arc_length_and_the_next_flange_follows() {
        let bend = BendMap {
            axis_origin: DVec3::ZERO,
            axis: DVec3::Z,
            start: -DVec3::Y,
            towards: DVec3::X,
            skin_radius: 2.0,
            neutral_radius: 2.5,
            flat_origin: DVec2::new(10.0, 0.0),
            flat_axis: DVec2::Y,
            flat_across: DVec2::X,
        };
        let end = DVec3::new(2.0, 0.0, 3.0);
        assert!((bend.angle(end) - FRAC_PI_2).abs() < 1e-12);
        let expected = DVec2::new(10.0 + FRAC_PI_2 * 2.5, 3.0);
        assert!(bend.point(end).distance(expected) < 1e-12);
        let flange = bend.flange_at(FRAC_PI_2);
        let further = DVec3::new(2.0, 7.0, 3.0);
        assert!(flange.point(further).distance(expected + DVec2::X * 7.0) < 1e-12);
        assert!(flange.point(end).distance(expected) < 1e-12);
    }
}
