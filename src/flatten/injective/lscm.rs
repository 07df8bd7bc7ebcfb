//! A conformal start: least-squares conformal maps (Lévy, Petitjean, Ray and Maillot 2002). The
//! flat map that is as close to conformal as it can be in the least-squares sense, with two
//! boundary vertices pinned (the boundary is free). It follows the part's shape where a Tutte
//! embedding puts the boundary on a circle, which for a long, narrow garment panel is far from
//! the spring energy's minimum. It is not guaranteed to have no flipped triangle; the caller
//! checks.
//!
//! For a triangle with the gradients `g_j` of its barycentric coordinates in its rest plane and
//! the flat coordinates `(u_j, v_j)` of its corners, the two residuals
//! `√A (∂u/∂x − ∂v/∂y)` and `√A (∂u/∂y + ∂v/∂x)` are linear in the unknowns; their squares summed
//! (the conformal energy) are minimised by one sparse Cholesky solve of the normal equations.

use std::collections::BTreeMap;

use faer::Mat;
use glam::DVec2;

use super::errors::InjectiveError;
use super::sparse::SparsePattern;
use crate::mesh::FacetModel;

/// The least-squares conformal map of `model` (a part with a boundary): one flat position per
/// vertex, at the scale of the rest shape along the two pinned vertices.
pub fn conformal_map(model: &FacetModel) -> Result<Vec<DVec2>, InjectiveError> {
    let (first, second) = pinned_pair(model).ok_or(InjectiveError::Closed)?;
    let rest = model.positions();
    let span = rest[first as usize].distance(rest[second as usize]);
    let mut pinned = vec![None; model.vertex_count()];
    pinned[first as usize] = Some(DVec2::ZERO);
    pinned[second as usize] = Some(DVec2::new(span, 0.0));
    let mut unknown = vec![u32::MAX; model.vertex_count()];
    let mut count = 0u32;
    for v in 0..model.vertex_count() {
        if pinned[v].is_none() {
            unknown[v] = count;
            count += 1;
        }
    }
    let n = 2 * count as usize;
    let mut matrix: BTreeMap<(u32, u32), f64> = BTreeMap::new();
    let mut rhs = vec![0.0; n];
    for t in model.triangles() {
        for row in conformal_rows(model, *t) {
            // row: coefficient per (vertex, axis); split into unknowns and pinned values.
            let mut constant = 0.0;
            let mut entries: Vec<(u32, f64)> = Vec::with_capacity(6);
            for (k, &v) in t.iter().enumerate() {
                for axis in 0..2 {
                    let coefficient = row[k][axis];
                    match pinned[v as usize] {
                        Some(p) => constant += coefficient * p[axis],
                        None => entries.push((2 * unknown[v as usize] + axis as u32, coefficient)),
                    }
                }
            }
            for &(i, a) in &entries {
                rhs[i as usize] -= a * constant;
                for &(j, b) in &entries {
                    if i >= j {
                        *matrix.entry((i, j)).or_insert(0.0) += a * b;
                    }
                }
            }
        }
    }
    let positions: Vec<(u32, u32)> = matrix.keys().copied().collect();
    let values: Vec<f64> = matrix.values().copied().collect();
    let pattern = SparsePattern::new(n, &positions)?;
    let factor = pattern.factor(&values)?;
    let mut solution = Mat::from_fn(n, 1, |i, _| rhs[i]);
    factor.solve_in_place(solution.as_mut());
    Ok((0..model.vertex_count())
        .map(|v| match pinned[v] {
            Some(p) => p,
            None => {
                let u = 2 * unknown[v] as usize;
                DVec2::new(solution[(u, 0)], solution[(u + 1, 0)])
            }
        })
        .collect())
}

/// The two residual rows of a triangle: for each corner, the coefficients of its `u` and `v`.
fn conformal_rows(model: &FacetModel, t: [u32; 3]) -> [[[f64; 2]; 3]; 2] {
    let [p0, p1, p2] = t.map(|v| model.positions()[v as usize]);
    // The rest triangle in its own plane: p0 at the origin, p1 on the x axis.
    let e1 = p1 - p0;
    let x_axis = e1.normalize_or_zero();
    let normal = e1.cross(p2 - p0);
    let y_axis = normal.cross(e1).normalize_or_zero();
    let local = [p0, p1, p2].map(|p| DVec2::new((p - p0).dot(x_axis), (p - p0).dot(y_axis)));
    let doubled_area = (local[1] - local[0]).perp_dot(local[2] - local[0]);
    let mut rows = [[[0.0; 2]; 3]; 2];
    if doubled_area <= 0.0 || !doubled_area.is_finite() {
        return rows;
    }
    let weight = (0.5 * doubled_area).sqrt();
    for j in 0..3 {
        let opposite = local[(j + 2) % 3] - local[(j + 1) % 3];
        let gradient = opposite.perp() / doubled_area;
        // ∂u/∂x − ∂v/∂y and ∂u/∂y + ∂v/∂x.
        rows[0][j] = [weight * gradient.x, -weight * gradient.y];
        rows[1][j] = [weight * gradient.y, weight * gradient.x];
    }
    rows
}

/// Two boundary vertices far apart: the first vertex of the longest boundary loop and the vertex
/// of any loop farthest from it in 3D. `None` for a closed model.
fn pinned_pair(model: &FacetModel) -> Option<(u32, u32)> {
    let loops = model.boundary_loops();
    let longest = loops.iter().max_by_key(|ring| ring.len())?;
    let first = longest[0];
    let origin = model.positions()[first as usize];
    let second = loops.iter().flatten().copied().max_by(|&a, &b| {
        let (da, db) = [a, b]
            .map(|v| model.positions()[v as usize].distance(origin))
            .into();
        da.total_cmp(&db).then(b.cmp(&a))
    })?;
    (second != first).then_some((first, second))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::cad::TriangleSoup;
    use crate::flatten::accuracy::flipped_triangles;
    use crate::mesh::validate;

    #[test]
    fn a_cylinder_panel_maps_to_its_development() {
        // A quarter cylinder of radius 10 and height 5: developable, so the conformal map is
        // an isometry up to the pins' scale, which is the chord's.
        let (around, rows) = (12u32, 4u32);
        let mut positions = Vec::new();
        for j in 0..=rows {
            for i in 0..=around {
                let angle = std::f64::consts::FRAC_PI_2 * i as f64 / around as f64;
                positions.push(DVec3::new(
                    10.0 * angle.cos(),
                    10.0 * angle.sin(),
                    5.0 * j as f64 / rows as f64,
                ));
            }
        }
        let index = |i: u32, j: u32| i + (around + 1) * j;
        let mut triangles = Vec::new();
        for j in 0..rows {
            for i in 0..around {
                triangles.push([index(i, j), index(i + 1, j), index(i + 1, j + 1)]);
                triangles.push([index(i, j), index(i + 1, j + 1), index(i, j + 1)]);
            }
        }
        let model = validate(&TriangleSoup::new(positions, triangles))
            .expect("valid")
            .components
            .remove(0);
        let map = conformal_map(&model).expect("solves");
        assert_eq!(flipped_triangles(&model, &map), 0);
        // Edge lengths all in one ratio to their rest lengths (a similarity of the
        // development, the polygonal cylinder being exactly developable).
        let ratios: Vec<f64> = model
            .edges()
            .iter()
            .map(|&[a, b]| {
                map[a as usize].distance(map[b as usize])
                    / model.positions()[a as usize].distance(model.positions()[b as usize])
            })
            .collect();
        let (low, high) = ratios
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), &r| (l.min(r), h.max(r)));
        assert!(high - low < 1e-9, "{low} to {high}");
    }
}
