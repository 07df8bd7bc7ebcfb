//! The elastic energy map of a flat pattern (paper §6.3, Fig. 9): the energy of every vertex
//! (Eq. 1), its linear interpolation over each triangle (Eq. 16) and its isolines.
//!
//! Inputs: a [`FacetModel`], its flat pattern (`pattern[v]` for model vertex `v`, model units)
//! and its spring system. Outputs: per-vertex energies (energy units of the spring system), the
//! interpolated energy at a point of a flat triangle, and isolines as flat segments for drawing.

use glam::DVec2;

use crate::flatten::SpringSystem;
use crate::flatten::accuracy::signed_area;
use crate::mesh::FacetModel;

/// Per-vertex elastic energy of Eq. 1, `E(P_i) = Σ_j ½ C_ij (|P_i P_j| − d_ij)²`.
pub fn vertex_energies(springs: &SpringSystem, pattern: &[DVec2]) -> Vec<f64> {
    springs.vertex_energies(pattern)
}

/// The shape functions `N_i, N_j, N_m` of Eq. 16 at `point` for the flat triangle `corners`, or
/// `None` for a degenerate triangle. They sum to 1 and are all in `[0, 1]` inside the triangle.
pub fn shape_functions(corners: [DVec2; 3], point: DVec2) -> Option<[f64; 3]> {
    let twice_area = 2.0 * signed_area(corners[0], corners[1], corners[2]);
    if twice_area.abs() <= f64::MIN_POSITIVE {
        return None;
    }
    let weight = |k: usize| {
        let (j, m) = (corners[(k + 1) % 3], corners[(k + 2) % 3]);
        // a_k + b_k x + c_k y with a_k = x_j y_m − x_m y_j, b_k = y_j − y_m, c_k = x_m − x_j.
        let a = j.x * m.y - m.x * j.y;
        let b = j.y - m.y;
        let c = m.x - j.x;
        (a + b * point.x + c * point.y) / twice_area
    };
    Some([weight(0), weight(1), weight(2)])
}

/// The energy at `point` of a flat triangle with corner energies `energies` (Eq. 16), or `None`
/// for a degenerate triangle.
pub fn interpolate(corners: [DVec2; 3], energies: [f64; 3], point: DVec2) -> Option<f64> {
    let n = shape_functions(corners, point)?;
    Some(n[0] * energies[0] + n[1] * energies[1] + n[2] * energies[2])
}

/// Isolines of a per-vertex field on the flat pattern at each of `levels`: in every triangle the
/// linear interpolation (Eq. 16) equals the level along one straight segment, returned with its
/// two ends. Triangles whose corners all lie on one side of a level contribute nothing for it.
pub fn isolines(
    model: &FacetModel,
    pattern: &[DVec2],
    values: &[f64],
    levels: &[f64],
) -> Vec<[DVec2; 2]> {
    let mut segments = Vec::new();
    for &level in levels {
        for triangle in model.triangles() {
            let corners = triangle.map(|v| (pattern[v as usize], values[v as usize]));
            if let Some(segment) = level_segment(corners, level) {
                segments.push(segment);
            }
        }
    }
    segments
}

/// Evenly spaced levels strictly between the smallest and largest value (`count` of them).
pub fn even_levels(values: &[f64], count: usize) -> Vec<f64> {
    let low = values.iter().copied().fold(f64::INFINITY, f64::min);
    let high = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if !(low.is_finite() && high.is_finite()) || high <= low {
        return Vec::new();
    }
    (1..=count)
        .map(|i| low + (high - low) * i as f64 / (count + 1) as f64)
        .collect()
}

/// Where the linear field of one triangle crosses `level`: the points on the edges whose ends lie
/// on opposite sides (a corner exactly on the level counts as above).
fn level_segment(corners: [(DVec2, f64); 3], level: f64) -> Option<[DVec2; 2]> {
    let mut crossings = Vec::with_capacity(2);
    for k in 0..3 {
        let (p, a) = corners[k];
        let (q, b) = corners[(k + 1) % 3];
        if (a >= level) != (b >= level) {
            let t = (level - a) / (b - a);
            crossings.push(p + (q - p) * t);
        }
    }
    match crossings[..] {
        [start, end] => Some([start, end]),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CORNERS: [DVec2; 3] = [
        DVec2::new(0.0, 0.0),
        DVec2::new(2.0, 0.0),
        DVec2::new(0.0, 1.0),
    ];

    #[test]
    fn shape_functions_reproduce_the_corners_and_sum_to_one() {
        for (k, &corner) in CORNERS.iter().enumerate() {
            let n = shape_functions(CORNERS, corner).expect("proper triangle");
            for (i, value) in n.iter().enumerate() {
                let expected = if i == k { 1.0 } else { 0.0 };
                assert!((value - expected).abs() < 1e-12);
            }
        }
        let n = shape_functions(CORNERS, DVec2::new(0.3, 0.2)).expect("proper triangle");
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn interpolation_is_linear() {
        // e = 1 + 2x + 3y at the corners; Eq. 16 must reproduce it everywhere.
        let field = |p: DVec2| 1.0 + 2.0 * p.x + 3.0 * p.y;
        let energies = CORNERS.map(field);
        let point = DVec2::new(0.5, 0.25);
        let value = interpolate(CORNERS, energies, point).expect("proper triangle");
        assert!((value - field(point)).abs() < 1e-12);
    }

    #[test]
    fn a_level_crosses_a_triangle_in_one_segment() {
        let corners = [(CORNERS[0], 0.0), (CORNERS[1], 2.0), (CORNERS[2], 1.0)];
        let [start, end] = level_segment(corners, 0.5).expect("level inside the range");
        assert!((start - DVec2::new(0.5, 0.0)).length() < 1e-12);
        assert!((end - DVec2::new(0.0, 0.5)).length() < 1e-12);
        assert!(level_segment(corners, 3.0).is_none());
    }

    #[test]
    fn even_levels_lie_strictly_inside_the_range() {
        assert_eq!(even_levels(&[0.0, 4.0], 3), vec![1.0, 2.0, 3.0]);
        assert!(even_levels(&[1.0, 1.0], 3).is_empty());
    }
}
