//! Isolines of a per-vertex scalar field over a flat triangle mesh, with the field interpolated
//! linearly over each triangle (the paper's Eq. 16, §6.3: "using equation (16), isolines of the
//! energy distribution are obtained").
//!
//! Input: flat positions (one per vertex, model units), triangles as vertex index triples, one
//! value per vertex (the per-vertex energy of Eq. 1, or any field), and the levels. Output: for
//! each level, the segments where the interpolated field equals the level, one segment per crossed
//! triangle, in triangle order.
//!
//! A vertex counts as above a level when its value is strictly greater, so a triangle is crossed
//! exactly when its vertices fall on both sides and the crossing point on an edge is the same for
//! both triangles that share it: the segments join into continuous curves.

use glam::DVec2;

/// The isoline of one level.
#[derive(Debug, Clone, PartialEq)]
pub struct Isoline {
    /// The field value along the line.
    pub level: f64,
    /// Its pieces, one per crossed triangle, as `[start, end]` in the positions' units.
    pub segments: Vec<[DVec2; 2]>,
}

/// The isolines of `values` at each of `levels`. Triangles referring to a vertex outside
/// `positions` or `values` are skipped.
pub fn isolines(
    positions: &[DVec2],
    triangles: &[[u32; 3]],
    values: &[f64],
    levels: &[f64],
) -> Vec<Isoline> {
    levels
        .iter()
        .map(|&level| Isoline {
            level,
            segments: triangles
                .iter()
                .filter_map(|triangle| triangle_crossing(positions, values, *triangle, level))
                .collect(),
        })
        .collect()
}

/// `count` levels evenly spaced strictly inside `(lower, upper)`: `lower + k (upper − lower) /
/// (count + 1)` for `k = 1..=count`.
pub fn evenly_spaced_levels(lower: f64, upper: f64, count: usize) -> Vec<f64> {
    (1..=count)
        .map(|k| lower + (upper - lower) * k as f64 / (count + 1) as f64)
        .collect()
}

/// The segment where the linear interpolation of the corner values equals `level`, if the
/// triangle's corners lie on both sides of it.
fn triangle_crossing(
    positions: &[DVec2],
    values: &[f64],
    triangle: [u32; 3],
    level: f64,
) -> Option<[DVec2; 2]> {
    let mut corners = [(DVec2::ZERO, 0.0); 3];
    for (corner, &vertex) in corners.iter_mut().zip(&triangle) {
        let vertex = vertex as usize;
        *corner = (*positions.get(vertex)?, *values.get(vertex)?);
    }
    let mut crossings = corners
        .iter()
        .zip(corners.iter().cycle().skip(1))
        .filter_map(|(&start, &end)| edge_crossing(start, end, level));
    let first = crossings.next()?;
    let second = crossings.next()?;
    Some([first, second])
}

/// The point of edge `start → end` where the linearly interpolated value equals `level`, when
/// exactly one end is above the level.
fn edge_crossing(start: (DVec2, f64), end: (DVec2, f64), level: f64) -> Option<DVec2> {
    let (low, high) = if start.1 > end.1 {
        (end, start)
    } else {
        (start, end)
    };
    let crosses = low.1 <= level && high.1 > level;
    // high.1 > level >= low.1, so the difference is positive.
    crosses.then(|| low.0.lerp(high.0, (level - low.1) / (high.1 - low.1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square of two triangles with the field `x`.
    fn square() -> (Vec<DVec2>, Vec<[u32; 3]>, Vec<f64>) {
        let positions = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        let values = positions.iter().map(|p| p.x).collect();
        (positions, vec![[0, 1, 2], [0, 2, 3]], values)
    }

    #[test]
    fn linear_field_gives_a_straight_line_at_the_level() {
        let (positions, triangles, values) = square();
        let lines = isolines(&positions, &triangles, &values, &[0.25]);
        assert_eq!(lines.len(), 1);
        assert_eq!(lines[0].segments.len(), 2);
        for point in lines[0].segments.iter().flatten() {
            assert!((point.x - 0.25).abs() < 1e-12, "{point}");
        }
    }

    #[test]
    fn segments_meet_on_shared_edges() {
        let (positions, triangles, values) = square();
        let lines = isolines(&positions, &triangles, &values, &[0.6]);
        let [first, second] = [lines[0].segments[0], lines[0].segments[1]];
        let shared = first
            .iter()
            .any(|a| second.iter().any(|b| a.distance(*b) < 1e-12));
        assert!(shared, "{first:?} {second:?}");
    }

    #[test]
    fn levels_outside_the_range_give_nothing() {
        let (positions, triangles, values) = square();
        let lines = isolines(&positions, &triangles, &values, &[-1.0, 1.0, 2.0]);
        assert!(lines.iter().all(|line| line.segments.is_empty()));
    }

    #[test]
    fn bad_indices_are_skipped() {
        let (positions, _, values) = square();
        let lines = isolines(&positions, &[[0, 1, 9]], &values, &[0.5]);
        assert!(lines[0].segments.is_empty());
    }

    #[test]
    fn levels_are_evenly_spaced_inside() {
        let levels = evenly_spaced_levels(0.0, 10.0, 4);
        assert_eq!(levels.len(), 4);
        for (k, level) in levels.iter().enumerate() {
            assert!((level - 2.0 * (k + 1) as f64).abs() < 1e-12);
        }
    }
}
