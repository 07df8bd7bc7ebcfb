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

/// The Tutte embedding of `model`: one flat position per vertex, every triangle positively
/// oriented (up to round-off on degenerate input). The boundary loop of largest perimeter goes on
/// the circle; every other loop (a hole) is filled, for this start only, by a fan of triangles
/// around a virtual vertex joined to each of its vertices with the mean weight, which makes the
/// part a disk whose embedding holds the model's. An error for a closed model.
pub fn tutte_embedding(model: &FacetModel) -> Result<Vec<DVec2>, InjectiveError> {
    let loops = model.boundary_loops();
    let rest = model.rest_lengths();
    let edge_length = |a: u32, b: u32| model.find_edge(a, b).map_or(0.0, |e| rest[e]);
    let perimeter = |ring: &[u32]| -> f64 {
        (0..ring.len())
            .map(|i| edge_length(ring[i], ring[(i + 1) % ring.len()]))
            .sum()
    };
    let outer = (0..loops.len())
        .max_by(|&i, &j| {
            perimeter(&loops[i])
                .total_cmp(&perimeter(&loops[j]))
                .then(j.cmp(&i))
        })
        .ok_or(InjectiveError::Closed)?;
    let boundary = &loops[outer];
    let mut positions = vec![DVec2::ZERO; model.vertex_count()];
    let total_length = perimeter(boundary);
    let radius = (model.area() / PI).sqrt();
    let mut travelled = 0.0;
    for (i, &v) in boundary.iter().enumerate() {
        let angle = 2.0 * PI * travelled / total_length;
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
    let holes: Vec<&[u32]> = loops
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != outer)
        .map(|(_, ring)| ring.as_slice())
        .collect();
    if interior > 0 {
        solve_interior(model, &unknown, interior as usize, &holes, &mut positions)?;
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
/// neighbours, the outer boundary being placed already; each hole's vertices are also joined to a
/// virtual vertex of their own.
pub(super) fn solve_interior(
    model: &FacetModel,
    unknown: &[u32],
    interior: usize,
    holes: &[&[u32]],
    positions: &mut [DVec2],
) -> Result<(), InjectiveError> {
    let weights = edge_weights(model);
    let unknowns = interior + holes.len();
    let mut entries: Vec<(u32, u32)> = (0..unknowns as u32).map(|i| (i, i)).collect();
    let mut values = vec![0.0; unknowns];
    let mut right = vec![DVec2::ZERO; unknowns];
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
    let fan_weight = weights.iter().sum::<f64>() / weights.len().max(1) as f64;
    for (h, hole) in holes.iter().enumerate() {
        let centre = (interior + h) as u32;
        for &v in *hole {
            let i = unknown[v as usize];
            values[i as usize] += fan_weight;
            values[centre as usize] += fan_weight;
            entries.push((centre, i));
            values.push(-fan_weight);
        }
    }
    let pattern = SparsePattern::new(unknowns, &entries)?;
    let factor = pattern.factor(&values)?;
    let mut rhs = Mat::from_fn(unknowns, 2, |i, axis| right[i][axis]);
    factor.solve_in_place(rhs.as_mut());
    for (v, &i) in unknown.iter().enumerate() {
        if i != u32::MAX {
            positions[v] = DVec2::new(rhs[(i as usize, 0)], rhs[(i as usize, 1)]);
        }
    }
    Ok(())
}
