//! Where each point of a skin face goes on the flat pattern: a rigid motion for a flange
//! (plane), and for a bend (cylinder) its unrolling at the neutral fibre: the axial coordinate
//! kept, the angle turned into arc length at the neutral radius.

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

/// How one skin face goes flat.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FaceMap {
    /// A flange, placed rigidly.
    Flange(PlaneMap),
    /// A bend (index into the unfold's bends), unrolled at the neutral fibre.
    Bend(usize, BendMap),
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
