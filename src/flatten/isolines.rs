//! Isolines of a per-vertex scalar field over a flat triangle mesh, with the field interpolated
//! linearly over each triangle (the paper's Eq. 16, §6.3: "using equation (16), isolines of the
//! energy distribution are obtained").
//!
//! Input: flat positions (one per vertex, model units), triangles as vertex index triples, one
//! value per vertex (the per-vertex energy of Eq. 1, or any field), and the levels. Output: for
//! each level, the curves where the interpolated field equals the level, as polylines whose
//! points lie on mesh edges, one segment per crossed triangle.
//!
//! A vertex counts as above a level when its value is strictly greater, so a triangle is crossed
//! exactly when its vertices fall on both sides, and the crossing point of an edge is computed
//! once for both triangles that share it. Segments are joined through the mesh edges they cross
//! (exact integer keys, no coordinate comparison) into polylines: open ones end on the boundary,
//! closed ones repeat their first point.

use glam::DVec2;

use crate::mesh::chain_edges;

/// The isoline of one level.
#[derive(Debug, Clone, PartialEq)]
pub struct Isoline {
    /// The field value along the line.
    pub level: f64,
    /// Its curves, in the positions' units.
    pub polylines: Vec<Vec<DVec2>>,
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
            polylines: level_polylines(positions, triangles, values, level),
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

/// The curves of one level: each crossed triangle links the two mesh edges it crosses; the links
/// are chained and each crossed edge becomes its crossing point.
fn level_polylines(
    positions: &[DVec2],
    triangles: &[[u32; 3]],
    values: &[f64],
    level: f64,
) -> Vec<Vec<DVec2>> {
    let value = |v: u32| values.get(v as usize).copied();
    let links: Vec<[[u32; 2]; 2]> = triangles
        .iter()
        .filter(|t| t.iter().all(|&v| (v as usize) < positions.len()))
        .filter_map(|&triangle| crossed_edges(triangle, level, &value))
        .collect();
    let mut crossed: Vec<[u32; 2]> = links.iter().flatten().copied().collect();
    crossed.sort_unstable();
    crossed.dedup();
    let node = |edge: &[u32; 2]| crossed.binary_search(edge).unwrap_or(0) as u32;
    let node_links: Vec<[u32; 2]> = links.iter().map(|[a, b]| [node(a), node(b)]).collect();
    chain_edges(&node_links)
        .into_iter()
        .map(|chain| {
            chain
                .into_iter()
                .map(|n| crossing_point(positions, values, crossed[n as usize], level))
                .collect()
        })
        .collect()
}

/// The two edges (as sorted vertex pairs) of `triangle` whose ends lie on both sides of `level`,
/// if it is crossed; `None` when not, or when a value is missing.
fn crossed_edges(
    triangle: [u32; 3],
    level: f64,
    value: &impl Fn(u32) -> Option<f64>,
) -> Option<[[u32; 2]; 2]> {
    let above = [0, 1, 2].map(|k| value(triangle[k]).map(|v| v > level));
    let above = [above[0]?, above[1]?, above[2]?];
    let mut edges = (0..3).filter(|&k| above[k] != above[(k + 1) % 3]).map(|k| {
        let (a, b) = (triangle[k], triangle[(k + 1) % 3]);
        [a.min(b), a.max(b)]
    });
    Some([edges.next()?, edges.next()?])
}

/// The point of edge `[a, b]` where the linearly interpolated value equals `level` (its ends lie
/// on both sides of it, so the values differ).
fn crossing_point(positions: &[DVec2], values: &[f64], [a, b]: [u32; 2], level: f64) -> DVec2 {
    let (a, b) = (a as usize, b as usize);
    let (low, high) = if values[a] > values[b] {
        (b, a)
    } else {
        (a, b)
    };
    // values[high] > level >= values[low], so the difference is positive.
    let fraction = (level - values[low]) / (values[high] - values[low]);
    positions[low].lerp(positions[high], fraction)
}

#[cfg(test)]
mod tests {
    use crate::flatten::isolines::*;

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
        assert_eq!(lines[0].polylines.len(), 1);
        assert_eq!(lines[0].polylines[0].len(), 3, "two segments joined");
        for point in lines[0].polylines.iter().flatten() {
            assert!((point.x - 0.25).abs() < 1e-12, "{point}");
        }
    }

    #[test]
    fn closed_curves_close() {
        // A fan around a high centre: the isoline is one closed ring.
        let mut positions = vec![DVec2::ZERO];
        let mut values = vec![1.0];
        for k in 0..6 {
            let angle = std::f64::consts::TAU * f64::from(k) / 6.0;
            positions.push(DVec2::new(angle.cos(), angle.sin()));
            values.push(0.0);
        }
        let triangles: Vec<[u32; 3]> = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        let lines = isolines(&positions, &triangles, &values, &[0.5]);
        assert_eq!(lines[0].polylines.len(), 1);
        let ring = &lines[0].polylines[0];
        assert_eq!(ring.len(), 7);
        assert!(ring[0].distance(ring[6]) < 1e-12);
        assert!(ring.iter().all(|p| (p.length() - 0.5).abs() < 1e-12));
    }

    #[test]
    fn levels_outside_the_range_give_nothing() {
        let (positions, triangles, values) = square();
        let lines = isolines(&positions, &triangles, &values, &[-1.0, 1.0, 2.0]);
        assert!(lines.iter().all(|line| line.polylines.is_empty()));
    }

    #[test]
    fn bad_indices_are_skipped() {
        let (positions, _, values) = square();
        let lines = isolines(&positions, &[[0, 1, 9]], &values, &[0.5]);
        assert!(lines[0].polylines.is_empty());
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
