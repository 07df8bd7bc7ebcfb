//! Tessellation of a STEP file's B-rep: every shell's faces meshed (`brep.rs`) into one welded
//! soup in millimetres, or, for a file with no shell, its loose B-spline and NURBS surfaces
//! meshed over their whole parameter domains by the patch mesher. Face sources number the
//! shells' faces in file order (a face boundary is an edge between triangles of different
//! sources).

use std::panic::{AssertUnwindSafe, catch_unwind};

use glam::DVec2;

use super::brep::{mesh_shell, shells_size, weld_coincident};
use super::figures::Tessellation;
use super::options::{BrepError, TessellateOptions, resolve_sizes, sizes_for_diagonal};
use super::patch::mesh_patch;
use super::weld::Welded;
use crate::cad::{Brep, CadPart, LooseSurface, PatchGeometry, PatchSurface, Surface, TriangleSoup};

/// Tessellates a STEP file's B-rep (see the module documentation); `options` are in
/// millimetres. Errors name the shell and face, or the surface.
pub fn tessellate_brep(
    brep: &Brep,
    options: &TessellateOptions,
) -> Result<Tessellation, BrepError> {
    let error = |message: String| BrepError { message };
    let mut soup = TriangleSoup::default();
    let (mesh_size, chord) = if brep.shells.is_empty() {
        append_loose_surfaces(&mut soup, &brep.loose, options).map_err(error)?
    } else {
        let size = shells_size(brep.shells.iter().map(|shell| &shell.shell));
        let (mesh_size, chord) =
            sizes_for_diagonal(size, options).map_err(|e| error(e.to_string()))?;
        for shell in &brep.shells {
            let first_source = soup.face_sources.last().map_or(0, |s| s + 1);
            mesh_shell(
                &mut soup,
                &shell.shell,
                first_source,
                mesh_size,
                chord,
                size,
            )
            .map_err(|e| {
                error(format!(
                    "shell #{}, {}: {}",
                    shell.id,
                    shell.describe_face(e.face),
                    e.message
                ))
            })?;
        }
        weld_coincident(&mut soup);
        (mesh_size, chord)
    };
    if soup.triangles.is_empty() {
        return Err(error(format!(
            "no face could be tessellated{}",
            brep.unsupported_note()
        )));
    }
    let welded = Welded {
        soup,
        vertex_sources: Vec::new(),
    };
    Ok(Tessellation::new(welded, mesh_size, chord))
}

/// Meshes loose surfaces over their whole parameter domains with the patch mesher
/// (millimetres); returns the mesh size and chord of the last surface.
fn append_loose_surfaces(
    soup: &mut TriangleSoup,
    surfaces: &[LooseSurface],
    options: &TessellateOptions,
) -> Result<(f64, f64), String> {
    let mut sizes = (0.0, 0.0);
    for (index, LooseSurface { id, geometry }) in surfaces.iter().enumerate() {
        let PatchGeometry::Nurbs(nurbs) = geometry else {
            continue;
        };
        let (u_knots, v_knots) = nurbs.knot_vecs();
        let (u_degree, v_degree) = (nurbs.udegree(), nurbs.vdegree());
        let low = DVec2::new(u_knots[u_degree], v_knots[v_degree]);
        let high = DVec2::new(
            u_knots[u_knots.len() - 1 - u_degree],
            v_knots[v_knots.len() - 1 - v_degree],
        );
        let patch = PatchSurface {
            geometry: geometry.clone(),
            outer: vec![
                low,
                DVec2::new(high.x, low.y),
                high,
                DVec2::new(low.x, high.y),
            ],
            holes: Vec::new(),
        };
        let part = CadPart {
            surfaces: vec![Surface::Patch(patch.clone())],
            fold_lines: Vec::new(),
            weld: true,
        };
        let (mesh_size, chord) =
            resolve_sizes(&part, options).map_err(|e| format!("surface #{id}: {e}"))?;
        sizes = (mesh_size, chord);
        let mesh = catch_unwind(AssertUnwindSafe(|| {
            mesh_patch(&patch, &[], mesh_size, chord)
        }))
        .map_err(|_| format!("surface #{id}: the surface could not be tessellated"))?
        .map_err(|e| format!("surface #{id}: {e}"))?;
        let offset = soup.positions.len() as u32;
        soup.positions.extend_from_slice(&mesh.positions);
        soup.triangles
            .extend(mesh.triangles.iter().map(|t| t.map(|v| v + offset)));
        soup.face_sources
            .extend(std::iter::repeat_n(index as u32, mesh.triangles.len()));
    }
    Ok(sizes)
}
