//! Tessellation of a part file's surfaces into one triangle soup fit for the spring model.
//!
//! Input: a [`CadPart`] (surfaces, fold lines) in part units and [`TessellateOptions`]. Output: a
//! [`Tessellation`]: a soup whose `face_sources` name the surface of each triangle and whose
//! `fold_edges` carry every fold line onto mesh edges, with the figures a user checks
//! (triangles, worst angle). Each surface is meshed by the algorithm that suits it; faces are
//! then welded along their shared edges (`weld.rs`); a fold line given as the edge between two
//! surfaces becomes the mesh edges those surfaces share.

use glam::{DVec2, DVec3};

use super::crossings::with_crossings;
use super::face_mesh::FaceMesh;
use super::figures::Tessellation;
use super::fold_insert::insert_fold_polylines;
use super::options::{TessellateError, TessellateOptions, resolve_sizes};
use super::patch::mesh_patch;
use super::revolution::mesh_revolution;
use super::ruled::{RulingFolds, mesh_ruled, mesh_rulings};
use super::ruled_folds::fold_rulings;
use super::weld::weld_faces;
use crate::cad::{
    CadPart, FoldEdge, FoldLineGeometry, Surface, SurfaceDomain, TriangleSoup, rulings,
    rulings_through,
};
use crate::geometry::tolerance::WELD_TOLERANCE_RATIO;

/// Tessellates a part (see the module documentation).
pub fn tessellate_part(
    part: &CadPart,
    options: &TessellateOptions,
) -> Result<Tessellation, TessellateError> {
    let (mesh_size, chord) = resolve_sizes(part, options)?;
    let weld_tolerance = part.size() * WELD_TOLERANCE_RATIO;
    let folds: Vec<Vec<(u32, Vec<DVec2>)>> = (0..part.surfaces.len())
        .map(|index| surface_folds(part, index))
        .collect();
    // Structured meshes first without their fold polylines: a ruled surface's polylines may add
    // rulings, which must not add points on a section another surface is welded to.
    let mut faces = Vec::with_capacity(part.surfaces.len());
    for (index, surface) in part.surfaces.iter().enumerate() {
        let face = match surface {
            Surface::Ruled(ruled) => mesh_ruled(ruled, mesh_size, chord),
            Surface::Revolution(revolution) => mesh_revolution(revolution, mesh_size, chord),
            Surface::Patch(patch) => mesh_patch(patch, &folds[index], mesh_size, chord)?,
        };
        faces.push(face);
    }
    for (index, surface) in part.surfaces.iter().enumerate() {
        if folds[index].is_empty() || matches!(surface, Surface::Patch(_)) {
            continue;
        }
        // A section is welded when one of its edges is shared (both ends on another face).
        let shared = |p: &DVec3| {
            faces.iter().enumerate().any(|(other, face)| {
                other != index
                    && face
                        .positions
                        .iter()
                        .any(|q| p.distance(*q) <= weld_tolerance)
            })
        };
        let welded =
            |points: &[DVec3]| part.weld && points.windows(2).any(|pair| pair.iter().all(shared));
        let face = mesh_with_folds(surface, &folds[index], mesh_size, chord, welded)?;
        faces[index] = face;
    }
    if let Some(index) = faces.iter().position(|face| face.triangles.is_empty()) {
        return Err(TessellateError::EmptySurface { surface: index });
    }
    let mut welded = weld_faces(&faces, part.weld, weld_tolerance);
    add_shared_edge_folds(part, &mut welded.soup);
    Ok(Tessellation::new(welded, mesh_size, chord))
}

/// The fold polylines `(fold line index, domain points)` on surface `index`.
fn surface_folds(part: &CadPart, index: usize) -> Vec<(u32, Vec<DVec2>)> {
    part.fold_lines
        .iter()
        .enumerate()
        .filter_map(|(line, fold)| match fold {
            FoldLineGeometry::OnSurface { surface, points } if *surface == index => {
                Some((line as u32, points.clone()))
            }
            _ => None,
        })
        .collect()
}

/// The structured mesh of a ruled surface or a surface of revolution with its fold polylines.
/// A ruled surface carries them along its rulings (`ruled_folds.rs`: the mesh stays exactly
/// developable) unless that would add a point on a section `welded` says another surface shares
/// an edge of (given the section's points), or a polyline crosses a cone fan other than along
/// one of its rows; then, and on surfaces of
/// revolution, they are inserted by a constrained re-triangulation around them (`fold_insert.rs`).
fn mesh_with_folds(
    surface: &Surface,
    folds: &[(u32, Vec<DVec2>)],
    mesh_size: f64,
    chord: f64,
    welded: impl Fn(&[DVec3]) -> bool,
) -> Result<FaceMesh, TessellateError> {
    let domain = SurfaceDomain::new(surface);
    let mut mesh = match surface {
        Surface::Ruled(ruled) => {
            let plain = rulings(ruled, mesh_size, chord);
            let sections = [welded(&plain.bottom), welded(&plain.top)];
            // Rulings through the polylines' vertices where the sections may get new points.
            let rulings = if sections.contains(&true) {
                plain
            } else {
                let through: Vec<f64> = with_crossings(folds)
                    .iter()
                    .flat_map(|(_, points)| points.iter().map(|p| p.x))
                    .collect();
                rulings_through(ruled, mesh_size, chord, &through)
            };
            if let Some((rulings, ruling_folds)) =
                fold_rulings(&rulings, &domain, folds, sections, mesh_size, chord)
            {
                return Ok(mesh_rulings(&rulings, &ruling_folds, mesh_size));
            }
            mesh_rulings(&rulings, &RulingFolds::default(), mesh_size)
        }
        Surface::Revolution(revolution) => mesh_revolution(revolution, mesh_size, chord),
        Surface::Patch(patch) => return mesh_patch(patch, folds, mesh_size, chord),
    };
    insert_fold_polylines(&mut mesh, &domain, folds, mesh_size)?;
    Ok(mesh)
}

/// Tags the edges shared by the two surfaces of each `Between` fold line.
fn add_shared_edge_folds(part: &CadPart, soup: &mut TriangleSoup) {
    let mut half_edges: Vec<([u32; 2], u32)> = Vec::with_capacity(soup.triangles.len() * 3);
    for (t, source) in soup.triangles.iter().zip(&soup.face_sources) {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            half_edges.push(([a.min(b), a.max(b)], *source));
        }
    }
    half_edges.sort_unstable();
    for (line, fold) in part.fold_lines.iter().enumerate() {
        let FoldLineGeometry::Between { surfaces } = fold else {
            continue;
        };
        let wanted = [
            surfaces[0].min(surfaces[1]) as u32,
            surfaces[0].max(surfaces[1]) as u32,
        ];
        for pair in half_edges.windows(2) {
            let (first, second) = (pair[0], pair[1]);
            if first.0 == second.0 && [first.1, second.1] == wanted {
                soup.fold_edges.push(FoldEdge {
                    vertices: first.0,
                    fold_line: line as u32,
                });
            }
        }
    }
}
