//! Stitching two rows of vertices into a strip of triangles: the building block of the structured
//! meshes of ruled surfaces (rows are rulings) and surfaces of revolution (rows are parallels).
//!
//! Input: two rows of vertex indices into `positions`, both running the same way, which may share
//! their first or last vertex (a fan, a pole). Output: triangles appended to `triangles`, all
//! oriented alike: `(left[p], right[q], left[p + 1])` or `(left[p], right[q], right[q + 1])`.
//! Triangles that would repeat a vertex are not produced. Each step adds the shorter of the two
//! candidate diagonals, which keeps triangles close to Delaunay within the strip.

use glam::DVec3;

/// Appends the triangles joining rows `left` and `right` (see the module documentation).
pub fn stitch_rows(
    left: &[u32],
    right: &[u32],
    positions: &[DVec3],
    triangles: &mut Vec<[u32; 3]>,
) {
    if left.is_empty() || right.is_empty() {
        return;
    }
    let (mut p, mut q) = (0, 0);
    let position = |v: u32| positions[v as usize];
    while p + 1 < left.len() || q + 1 < right.len() {
        let advance_left = if p + 1 >= left.len() {
            false
        } else if q + 1 >= right.len() {
            true
        } else {
            let left_diagonal = position(left[p + 1]).distance_squared(position(right[q]));
            let right_diagonal = position(left[p]).distance_squared(position(right[q + 1]));
            left_diagonal <= right_diagonal
        };
        let triangle = if advance_left {
            p += 1;
            [left[p - 1], right[q], left[p]]
        } else {
            q += 1;
            [left[p], right[q - 1], right[q]]
        };
        let [a, b, c] = triangle;
        if a != b && b != c && a != c {
            triangles.push(triangle);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::tessellate::strip::*;

    #[test]
    fn rows_of_different_lengths_make_a_full_strip() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
        ];
        let mut triangles = Vec::new();
        stitch_rows(&[0, 1, 2], &[3, 4], &positions, &mut triangles);
        assert_eq!(triangles.len(), 3);
        let area: f64 = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| positions[v as usize]);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum();
        assert!((area - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_shared_first_vertex_makes_a_fan_without_degenerate_triangles() {
        let positions = vec![
            DVec3::ZERO,
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        ];
        let mut triangles = Vec::new();
        stitch_rows(&[0, 1], &[0, 2], &positions, &mut triangles);
        assert_eq!(triangles.len(), 1);
        let mut corners = triangles[0];
        corners.sort_unstable();
        assert_eq!(corners, [0, 1, 2]);
    }
}
