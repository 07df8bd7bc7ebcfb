//! The outline of a flat pattern: its boundary loops in the plane, sorted into the outer contour
//! and the holes. This is what gets cut, drawn and nested.
//!
//! Input: a facet model and its flat positions (a valid pattern: no overlap). Output: closed
//! rings without a repeated last point, the outer one counter-clockwise and the holes clockwise
//! (the facet model's boundary loops keep the surface on their left, so this holds for any
//! pattern without flips). The outer contour is the loop enclosing the largest area.

use glam::DVec2;

use crate::mesh::FacetModel;

/// Outer contour and holes of a flat pattern, in model units.
#[derive(Debug, Clone, PartialEq)]
pub struct Outline {
    /// The outer contour, counter-clockwise.
    pub outer: Vec<DVec2>,
    /// Inner contours (holes), clockwise.
    pub holes: Vec<Vec<DVec2>>,
}

impl Outline {
    /// The outline of `pattern` (flat positions of `model`'s vertices). Empty for a model
    /// without boundary.
    pub fn of_pattern(model: &FacetModel, pattern: &[DVec2]) -> Self {
        let mut rings: Vec<Vec<DVec2>> = model
            .boundary_loops()
            .iter()
            .map(|ring| ring.iter().map(|&v| pattern[v as usize]).collect())
            .collect();
        let outer_index = (0..rings.len())
            .max_by(|&a, &b| {
                signed_area(&rings[a])
                    .abs()
                    .total_cmp(&signed_area(&rings[b]).abs())
            })
            .unwrap_or(0);
        if rings.is_empty() {
            return Self {
                outer: Vec::new(),
                holes: Vec::new(),
            };
        }
        let outer = rings.swap_remove(outer_index);
        Self {
            outer,
            holes: rings,
        }
    }

    /// Area enclosed: the outer contour's minus the holes'.
    pub fn area(&self) -> f64 {
        signed_area(&self.outer).abs()
            - self.holes.iter().map(|h| signed_area(h).abs()).sum::<f64>()
    }

    /// The outline moved by `offset`.
    pub fn translated(&self, offset: DVec2) -> Self {
        let shift = |ring: &Vec<DVec2>| ring.iter().map(|&p| p + offset).collect();
        Self {
            outer: shift(&self.outer),
            holes: self.holes.iter().map(shift).collect(),
        }
    }
}

pub use crate::geometry::signed_area;

#[cfg(test)]
mod tests {
    use crate::flatten::outline::*;
    use crate::mesh::{TriangleSoup, validate};
    use glam::DVec3;

    #[test]
    fn square_with_a_square_hole() {
        // 4x4 square with the middle 2x2 removed, as 8 quads on a 4x4 vertex grid.
        let coordinates = [0.0, 1.0, 3.0, 4.0];
        let positions: Vec<DVec3> = coordinates
            .iter()
            .flat_map(|&y| coordinates.iter().map(move |&x| DVec3::new(x, y, 0.0)))
            .collect();
        let mut triangles = Vec::new();
        for row in 0..3u32 {
            for column in 0..3u32 {
                if (row, column) == (1, 1) {
                    continue;
                }
                let a = row * 4 + column;
                triangles.extend([[a, a + 1, a + 5], [a, a + 5, a + 4]]);
            }
        }
        let model = validate(&TriangleSoup::new(positions.clone(), triangles))
            .expect("valid")
            .components
            .remove(0);
        let flat: Vec<DVec2> = model.positions().iter().map(|p| p.truncate()).collect();
        let outline = Outline::of_pattern(&model, &flat);
        assert_eq!(outline.outer.len(), 12);
        assert!(
            signed_area(&outline.outer) > 0.0,
            "outer contour is counter-clockwise"
        );
        assert_eq!(outline.holes.len(), 1);
        assert_eq!(outline.holes[0].len(), 4);
        assert!(signed_area(&outline.holes[0]) < 0.0, "hole is clockwise");
        assert!((outline.area() - 12.0).abs() < 1e-12);
    }
}
