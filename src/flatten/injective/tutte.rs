//! The injective start: a Tutte embedding (Tutte 1963, Floater 1997). The boundary loop is
//! placed on a circle, each vertex at its arc length along the loop (rest lengths), the circle's
//! area being the part's; every interior vertex is the weighted mean of its neighbours, with
//! positive weights. With a convex boundary and positive weights every triangle comes out
//! positively oriented (Floater 2003), whatever the surface's curvature.
//!
//! The weights are the cotangent weights `½ (cot α + cot β)` of the rest triangles (from the rest
//! lengths, so the start follows the part's shape: uniform weights crowd the interior toward the
//! centre), clamped from below to [`SMALLEST_WEIGHT`] times their mean absolute value so that
//! they stay positive on obtuse meshes. The weights are symmetric: one sparse Cholesky solve for
//! both coordinates.

use std::f64::consts::PI;

use faer::Mat;
use glam::DVec2;

use super::errors::InjectiveError;
use super::sparse::SparsePattern;
use crate::flatten::accuracy::signed_area;
use crate::mesh::FacetModel;

/// The smallest cotangent weight, as a fraction of the mean absolute weight.
pub const SMALLEST_WEIGHT: f64 = 0.01;

/// The Tutte embedding of a disk `model`: one flat position per vertex, every triangle positively
/// oriented (up to round-off on degenerate input).
pub fn tutte_embedding(model: &FacetModel) -> Result<Vec<DVec2>, InjectiveError> {
    let [boundary] = model.boundary_loops() else {
        return Err(InjectiveError::NotADisk {
            loops: model.boundary_loops().len(),
        });
    };
    let mut positions = vec![DVec2::ZERO; model.vertex_count()];
    let rest = model.rest_lengths();
    let edge_length = |a: u32, b: u32| model.find_edge(a, b).map_or(0.0, |e| rest[e]);
    let perimeter: f64 = (0..boundary.len())
        .map(|i| edge_length(boundary[i], boundary[(i + 1) % boundary.len()]))
        .sum();
    let radius = (model.area() / PI).sqrt();
    let mut travelled = 0.0;
    for (i, &v) in boundary.iter().enumerate() {
        let angle = 2.0 * PI * travelled / perimeter;
        positions[v as usize] = DVec2::new(angle.cos(), angle.sin()) * radius;
        travelled += edge_length(v, boundary[(i + 1) % boundary.len()]);
    }
    let mut unknown = vec![u32::MAX; model.vertex_count()];
    let mut on_boundary = vec![false; model.vertex_count()];
    for &v in boundary {
        on_boundary[v as usize] = true;
    }
    let mut interior = 0;
    for (v, slot) in unknown.iter_mut().enumerate() {
        if !on_boundary[v] {
            *slot = interior;
            interior += 1;
        }
    }
    if interior > 0 {
        solve_interior(model, &unknown, interior as usize, &mut positions)?;
    }
    let total: f64 = model
        .triangles()
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| positions[v as usize]);
            signed_area(a, b, c)
        })
        .sum();
    if total < 0.0 {
        for p in &mut positions {
            p.x = -p.x;
        }
    }
    Ok(positions)
}

/// The clamped cotangent weight of every edge (see the module documentation).
fn edge_weights(model: &FacetModel) -> Vec<f64> {
    let rest = model.rest_lengths();
    let mut weights = vec![0.0; model.edges().len()];
    for &edges in model.face_edges() {
        let lengths = edges.map(|e| rest[e as usize]);
        let [l0, l1, l2] = lengths;
        let s = 0.5 * (l0 + l1 + l2);
        let area = (s * (s - l0) * (s - l1) * (s - l2)).max(0.0).sqrt();
        if area <= 0.0 {
            continue;
        }
        for (k, &e) in edges.iter().enumerate() {
            // The angle opposite edge k, between the other two edges.
            let (opposite, first, second) =
                (lengths[k], lengths[(k + 1) % 3], lengths[(k + 2) % 3]);
            let cotangent = (first * first + second * second - opposite * opposite) / (4.0 * area);
            weights[e as usize] += 0.5 * cotangent;
        }
    }
    let mean = weights.iter().map(|w| w.abs()).sum::<f64>() / weights.len().max(1) as f64;
    let floor = SMALLEST_WEIGHT * mean.max(f64::MIN_POSITIVE);
    for w in &mut weights {
        *w = w.max(floor);
    }
    weights
}

/// Places the interior vertices (those with an `unknown` index) at the weighted means of their
/// neighbours, the boundary ones being placed already.
fn solve_interior(
    model: &FacetModel,
    unknown: &[u32],
    interior: usize,
    positions: &mut [DVec2],
) -> Result<(), InjectiveError> {
    let weights = edge_weights(model);
    let mut entries: Vec<(u32, u32)> = (0..interior as u32).map(|i| (i, i)).collect();
    let mut values = vec![0.0; interior];
    let mut right = vec![DVec2::ZERO; interior];
    for (&[a, b], &w) in model.edges().iter().zip(&weights) {
        let (ia, ib) = (unknown[a as usize], unknown[b as usize]);
        for (i, other) in [(ia, b), (ib, a)] {
            if i != u32::MAX {
                values[i as usize] += w;
                if unknown[other as usize] == u32::MAX {
                    right[i as usize] += positions[other as usize] * w;
                }
            }
        }
        if ia != u32::MAX && ib != u32::MAX {
            entries.push((ia.max(ib), ia.min(ib)));
            values.push(-w);
        }
    }
    let pattern = SparsePattern::new(interior, &entries)?;
    let factor = pattern.factor(&values)?;
    let mut rhs = Mat::from_fn(interior, 2, |i, axis| right[i][axis]);
    factor.solve_in_place(rhs.as_mut());
    for (v, &i) in unknown.iter().enumerate() {
        if i != u32::MAX {
            positions[v] = DVec2::new(rhs[(i as usize, 0)], rhs[(i as usize, 1)]);
        }
    }
    Ok(())
}
