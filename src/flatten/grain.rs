//! A part's grain direction, given in 3D on the surface, carried onto its flat pattern.

use glam::{DMat2, DVec2, DVec3};

use crate::mesh::FacetModel;

/// The unit flat direction of the 3D grain `direction` on the pattern `flat` of `model`.
///
/// In each triangle the direction is projected into the triangle's plane, written in the
/// triangle's edge vectors and mapped by the same combination of the flat edge vectors (the
/// triangle's affine map from surface to plane); the images are summed weighted by the 3D
/// triangle areas. `None` for a zero or non-finite direction, or when the sum is shorter than
/// [`GRAIN_IN_PLANE_FRACTION`] of its largest possible length (the direction lying in every
/// triangle's plane): a direction normal to the surface, or one that cancels over it.
pub fn flat_grain(model: &FacetModel, flat: &[DVec2], direction: DVec3) -> Option<DVec2> {
    if !direction.is_finite() || direction.length_squared() == 0.0 {
        return None;
    }
    let positions = model.positions();
    let unit = direction.normalize();
    let sum = model
        .triangles()
        .iter()
        .filter_map(|&[a, b, c]| {
            let [p0, p1, p2] = [a, b, c].map(|v| positions[v as usize]);
            let [f0, f1, f2] = [a, b, c].map(|v| flat[v as usize]);
            let (e1, e2) = (p1 - p0, p2 - p0);
            let area = 0.5 * e1.cross(e2).length();
            let gram = DMat2::from_cols_array(&[e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2)]);
            if gram.determinant().abs() <= f64::EPSILON * e1.dot(e1) * e2.dot(e2) {
                return None;
            }
            let weights = gram.inverse() * DVec2::new(unit.dot(e1), unit.dot(e2));
            let image = weights.x * (f1 - f0) + weights.y * (f2 - f0);
            Some(image * area)
        })
        .fold(DVec2::ZERO, |total, image| total + image);
    let significant = sum.length() > GRAIN_IN_PLANE_FRACTION * model.area();
    (significant && sum.is_finite()).then(|| sum.normalize())
}

/// The flat grain must sum to at least this fraction of the part's area (the length of the sum
/// of unit images in an isometric pattern when the grain lies in every triangle's plane), or the
/// grain is taken as normal to the surface; see [`flat_grain`].
pub const GRAIN_IN_PLANE_FRACTION: f64 = 1e-3;

#[cfg(test)]
mod tests {
    use crate::flatten::grain::*;
    use crate::mesh::{TriangleSoup, validate};

    /// A 100 x 50 strip bent around the y axis into a half cylinder of radius 100 / π, its
    /// middle at the top (+z), and its development turned by `turn` radians.
    fn half_cylinder(turn: f64) -> (FacetModel, Vec<DVec2>) {
        let (columns, radius) = (20, 100.0 / std::f64::consts::PI);
        let mut positions = Vec::new();
        let mut flat = Vec::new();
        for row in 0..2 {
            for column in 0..=columns {
                let s = 100.0 * column as f64 / columns as f64;
                let y = 50.0 * row as f64;
                let angle = (s - 50.0) / radius;
                positions.push(DVec3::new(radius * angle.sin(), y, radius * angle.cos()));
                flat.push(DVec2::from_angle(turn).rotate(DVec2::new(s, y)));
            }
        }
        let side = columns as u32 + 1;
        let triangles = (0..columns as u32)
            .flat_map(|c| [[c, c + 1, side + c + 1], [c, side + c + 1, side + c]])
            .collect();
        let model = validate(&TriangleSoup::new(positions, triangles))
            .expect("valid")
            .components
            .remove(0);
        (model, flat)
    }

    #[test]
    fn a_grain_along_the_cylinder_axis_stays_along_it_in_the_development() {
        let turn = 0.3;
        let (model, flat) = half_cylinder(turn);
        let grain = flat_grain(&model, &flat, DVec3::Y).expect("a grain");
        let expected = DVec2::from_angle(turn).rotate(DVec2::Y);
        assert!(grain.distance(expected) < 1e-12, "{grain}");
    }

    #[test]
    fn a_grain_around_the_cylinder_follows_the_unrolled_arc() {
        // At the top the surface tangent across the axis is +x; down the sides the tangent turns
        // and x's projection on it shrinks, but its image is along the development's x axis.
        let (model, flat) = half_cylinder(0.0);
        let grain = flat_grain(&model, &flat, DVec3::X).expect("a grain");
        assert!(grain.distance(DVec2::X) < 1e-12, "{grain}");
    }

    #[test]
    fn a_zero_direction_has_no_grain() {
        let (model, flat) = half_cylinder(0.0);
        assert_eq!(flat_grain(&model, &flat, DVec3::ZERO), None);
        assert_eq!(flat_grain(&model, &flat, DVec3::NAN), None);
        // Across the cylinder at its middle, the grain is normal to the surface at the top and
        // cancels over the two sides.
        assert_eq!(flat_grain(&model, &flat, DVec3::Z), None);
    }
}
