//! Fold polylines carried onto a structured mesh by a constrained re-triangulation around them:
//! surfaces of revolution, and ruled surfaces where [`super::ruled_folds`] cannot carry them
//! along the rulings (a section welded to another surface, a fold across a cone fan other than
//! along one of its rows). The re-triangulated band spans several rulings, so it is not exactly
//! developable.
//!
//! Input: a [`FaceMesh`] made by a structured mesher, its surface's [`SurfaceDomain`], fold
//! polylines in that domain and the mesh size. Output: the same mesh, re-triangulated near each
//! polyline so that mesh edges follow it exactly, those edges tagged as fold edges.
//!
//! Method, the same for every kind of surface:
//! 1. Each triangle corner gets its domain coordinates (periodic `u` unwrapped within the
//!    triangle, a pole's `u` that of its neighbours), so a domain point is located in a triangle
//!    and mapped onto the mesh linearly. The polylines are split to the mesh size (lengths on
//!    the mesh).
//! 2. The cavity is every triangle a polyline piece meets, and every triangle sharing a vertex
//!    with one (room for well-shaped triangles). Each edge-connected part of it is unfolded into
//!    the plane triangle by triangle from its 3D edge lengths (exact on a developable surface,
//!    nearly so on a narrow band of a doubly curved one): a chart in part units.
//! 3. In the chart, the cavity's boundary edges and the polyline pieces are constraint edges of a
//!    Delaunay triangulation refined like a patch ([`super::patch`]: 25°, triangles of the mesh
//!    size, constraint edges kept, so the cavity's boundary still matches the mesh around it).
//! 4. The refined triangles inside the cavity replace it; each new vertex is mapped back onto
//!    the old mesh (its chart triangle's barycentric coordinates), so it lies on the old mesh,
//!    within the chord tolerance of the surface.

use glam::DVec2;

use super::crossings::with_crossings;
use super::face_mesh::FaceMesh;
use super::fold_cavity::{boundary_vertices, cavity, edge_components, retriangulate, unfold};
use super::fold_locate::{corner_domains, split_polyline};
use super::options::TessellateError;
use crate::cad::SurfaceDomain;

/// Inserts fold polylines `(fold line index, domain points)` into `mesh` (see the module
/// documentation).
pub fn insert_fold_polylines(
    mesh: &mut FaceMesh,
    domain: &SurfaceDomain,
    folds: &[(u32, Vec<DVec2>)],
    mesh_size: f64,
) -> Result<(), TessellateError> {
    if folds.is_empty() {
        return Ok(());
    }
    let corners = corner_domains(mesh, domain);
    let on_boundary = boundary_vertices(mesh);
    let mut polylines = Vec::with_capacity(folds.len());
    for (line, points) in with_crossings(folds) {
        let split = split_polyline(mesh, &corners, &on_boundary, &points, mesh_size)?;
        polylines.push((line, split));
    }
    let cavity = cavity(mesh, &corners, &polylines);
    let mut removed = vec![false; mesh.triangles.len()];
    let mut added = Vec::new();
    for component in edge_components(mesh, &cavity) {
        let chart = unfold(mesh, &component);
        added.extend(retriangulate(
            mesh, &component, &chart, &polylines, mesh_size,
        )?);
        for &t in &component {
            removed[t] = true;
        }
    }
    let kept = mesh
        .triangles
        .iter()
        .zip(&removed)
        .filter(|&(_, &r)| !r)
        .map(|(t, _)| *t);
    mesh.triangles = kept.chain(added).collect();
    Ok(())
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::cad::{Frame, RuledCircle, RuledSurface, Surface};
    use crate::tessellate::fold_insert::*;
    use crate::tessellate::ruled::mesh_ruled;

    fn cylinder_panel() -> Surface {
        Surface::Ruled(RuledSurface::Circular {
            frame: Frame::WORLD,
            bottom: RuledCircle {
                center: DVec3::ZERO,
                radius: 150.0,
                tilt: 0.0,
            },
            top: RuledCircle {
                center: DVec3::new(0.0, 0.0, 200.0),
                radius: 150.0,
                tilt: 0.0,
            },
            angles: [0.0, 120f64.to_radians()],
        })
    }

    #[test]
    fn a_generator_fold_becomes_mesh_edges_and_keeps_the_area_and_the_shape() {
        let surface = cylinder_panel();
        let Surface::Ruled(ruled) = &surface else {
            unreachable!("a cylinder is ruled")
        };
        let mut mesh = mesh_ruled(ruled, 6.0, 0.03);
        let before = mesh.area();
        let domain = SurfaceDomain::new(&surface);
        let folds = vec![(0, vec![DVec2::new(61.3, 0.0), DVec2::new(61.3, 200.0)])];
        insert_fold_polylines(&mut mesh, &domain, &folds, 6.0).expect("inserts");
        assert!((mesh.area() - before).abs() / before < 1e-5);
        let length: f64 = mesh
            .fold_edges
            .iter()
            .map(|(e, _)| mesh.positions[e[0] as usize].distance(mesh.positions[e[1] as usize]))
            .sum();
        assert!((length - 200.0).abs() < 1e-9, "{length}");
        let worst = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
                [(a, b, c), (b, c, a), (c, a, b)]
                    .map(|(p, q, r)| (q - p).angle_between(r - p).to_degrees())
                    .into_iter()
                    .fold(180.0, f64::min)
            })
            .fold(180.0, f64::min);
        // The fold ends 0.44 mm from a rim vertex on both rims; the rims' edges are kept, which
        // leaves 13.1° there (every other triangle is above 20°).
        assert!(worst >= 13.0, "worst angle {worst}");
    }
}
