//! A bend as the flat pattern carries it: its centre line on the flat, the way it folds, its
//! angle, inner radius and bend allowance, and the note a press-brake operator reads.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::bend_rule::AllowanceRule;

/// Which way a bend folds, seen on the flat pattern from the side drawn (the chosen skin).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BendDirection {
    /// Towards the viewer: the drawn skin is on the inside of the bend.
    Up,
    /// Away from the viewer: the drawn skin is on the outside of the bend.
    Down,
}

impl BendDirection {
    /// `UP` or `DOWN`, as the note writes it.
    pub fn word(self) -> &'static str {
        match self {
            Self::Up => "UP",
            Self::Down => "DOWN",
        }
    }

    /// The direction seen from the other side (a mirrored pattern).
    pub fn mirrored(self) -> Self {
        match self {
            Self::Up => Self::Down,
            Self::Down => Self::Up,
        }
    }
}

/// One bend of a flat pattern, in the drawing's units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BendLine {
    /// The bend's centre line on the flat pattern (the middle of the bend zone), end to end.
    pub line: [DVec2; 2],
    /// Which way it folds.
    pub direction: BendDirection,
    /// The bend angle (how far the flange turns), degrees.
    pub angle_degrees: f64,
    /// The inner radius.
    pub inner_radius: f64,
    /// The bend allowance: the flat width of the bend zone.
    pub allowance: f64,
    /// The rule that gave the allowance (absent in pattern files written before rules were
    /// recorded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rule: Option<AllowanceRule>,
    /// For a bend on a cone, its radius and allowance at either end and its bend zone (absent
    /// for a bend on a cylinder): `inner_radius` and `allowance` are then the figures at the
    /// middle of the bend line.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conical: Option<ConicalBend>,
}

/// What a bend on a cone adds to its [`BendLine`]: its inner radius grows linearly along the
/// bend line and so does its allowance, `BA = θ_c · (R + K · t)` at every point of the line with
/// the developed angle `θ_c = Δφ · cos α` (`Δφ` the bend's angle about the cone's axis, `α` the
/// cone's half-angle); on the flat the bend zone is a sector of an annulus, its two edges rays
/// from the developed apex at the angle `Δφ · sin α`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConicalBend {
    /// The inner radius (of curvature, across the bend) at the bend line's two ends, in the
    /// order of [`BendLine::line`].
    pub inner_radii: [f64; 2],
    /// The allowance (the bend zone's flat width, along the developed neutral arc) at the two
    /// ends.
    pub allowances: [f64; 2],
    /// The developed angle `θ_c`, degrees.
    pub developed_angle_degrees: f64,
    /// The bend zone's two edges on the flat (where the bend meets its flanges), end to end.
    pub zone: [[DVec2; 2]; 2],
}

impl BendLine {
    /// The note drawn beside the bend line: `UP 90° R2`, the angle and radius rounded to 0.01
    /// (a conical bend's radius from one end to the other, `R2-6`).
    pub fn note(&self) -> String {
        let radius = match &self.conical {
            Some(cone) => format!(
                "{}-{}",
                short_number(cone.inner_radii[0]),
                short_number(cone.inner_radii[1])
            ),
            None => short_number(self.inner_radius),
        };
        format!(
            "{} {}° R{radius}",
            self.direction.word(),
            short_number(self.angle_degrees),
        )
    }

    /// The bend zone's two edges on the flat (the tangent lines where the bend starts and
    /// ends): the bend line moved half the allowance to either side (a conical bend's own
    /// edges).
    pub fn zone_edges(&self) -> [[DVec2; 2]; 2] {
        if let Some(cone) = &self.conical {
            return cone.zone;
        }
        let [start, end] = self.line;
        let across = (end - start).normalize_or_zero().perp() * (self.allowance / 2.0);
        [
            [start - across, end - across],
            [start + across, end + across],
        ]
    }

    /// The bend line's length.
    pub fn length(&self) -> f64 {
        self.line[0].distance(self.line[1])
    }

    /// The same bend with its line moved by `map` (a placement on a sheet) and, when the
    /// placement mirrors the pattern, folding the other way.
    pub fn placed(&self, map: impl Fn(DVec2) -> DVec2, mirrored: bool) -> Self {
        let mut placed = Self {
            direction: if mirrored {
                self.direction.mirrored()
            } else {
                self.direction
            },
            ..self.clone()
        };
        placed.move_points(map);
        placed
    }

    /// Moves the bend's points on the flat (its line and a conical bend's zone) by `map`.
    pub fn move_points(&mut self, map: impl Fn(DVec2) -> DVec2) {
        self.line = self.line.map(&map);
        if let Some(cone) = &mut self.conical {
            cone.zone = cone.zone.map(|edge| edge.map(&map));
        }
    }
}

/// A number rounded to 0.01 without trailing zeros: `90`, `2.4`, `1.64`.
fn short_number(value: f64) -> String {
    let text = format!("{value:.2}");
    text.trim_end_matches('0').trim_end_matches('.').to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_note_names_direction_angle_and_radius() {
        let bend = BendLine {
            line: [DVec2::ZERO, DVec2::new(0.0, 30.0)],
            direction: BendDirection::Up,
            angle_degrees: 90.000000001,
            inner_radius: 2.4,
            allowance: 4.0,
            rule: None,
            conical: None,
        };
        assert_eq!(bend.note(), "UP 90° R2.4");
        assert_eq!(bend.length(), 30.0);
    }
}
