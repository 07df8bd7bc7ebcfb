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
use super::patch::{Refinement, mesh_patch};
use super::weld::Welded;
use crate::cad::{Brep, CadPart, LooseSurface, PatchGeometry, PatchSurface, Surface, TriangleSoup};

/// Tessellates a STEP file's B-rep (see the module documentation); `options` are in
/// millimetres. Errors name the shell and face, or the surface.
pub fn tessellate_brep(
    brep: &Brep,
    options: &TessellateOptions,
) -> Result<Tessellation, BrepError> {
    tessellate_brep_as(brep, options, Refinement::Full)
}

/// Tessellates a B-rep's shells for an exact unfold, which maps each vertex onto its flat
/// position and needs only the faces' boundaries and points on their surfaces: the chord is at
/// most `largest_chord` (mm), edges are sampled to the chord only (a straight edge is one piece),
/// and faces are triangulated from their boundary samples, refined to the chord but not to a
/// mesh size or angle (`Refinement::ChordOnly`). A plate with many small holes meshes to a
/// few triangles per boundary point instead of graded triangles round every hole. Loose
/// surfaces are meshed as by [`tessellate_brep`].
pub fn tessellate_brep_for_unfold(
    brep: &Brep,
    options: &TessellateOptions,
    largest_chord: f64,
) -> Result<Tessellation, BrepError> {
    let size = shells_size(brep.shells.iter().map(|shell| &shell.shell));
    let (_, chord) = sizes_for_diagonal(size, options).map_err(|e| BrepError {
        message: e.to_string(),
    })?;
    let options = TessellateOptions {
        chord: Some(chord.min(largest_chord)),
        ..*options
    };
    tessellate_brep_as(brep, &options, Refinement::ChordOnly)
}

/// [`tessellate_brep`] with the given refinement of the shells' faces.
fn tessellate_brep_as(
    brep: &Brep,
    options: &TessellateOptions,
    refinement: Refinement,
) -> Result<Tessellation, BrepError> {
    let error = |message: String| BrepError { message };
    let mut soup = TriangleSoup::default();
    let (mesh_size, chord) = if brep.shells.is_empty() {
        append_loose_surfaces(&mut soup, &brep.loose, options).map_err(error)?
    } else {
        let size = shells_size(brep.shells.iter().map(|shell| &shell.shell));
        let (mesh_size, chord) =
            sizes_for_diagonal(size, options).map_err(|e| error(e.to_string()))?;
        let face_size = match refinement {
            Refinement::Full => mesh_size,
            Refinement::ChordOnly => size,
        };
        // Each closed shell (a solid) is welded on its own: two solids that touch at a point or
        // along an edge stay two parts instead of meeting at a non-manifold vertex or edge. Open
        // shells are welded together, so surfaces exported as separate shells that share edges
        // make one part.
        let mut open_shells = TriangleSoup::default();
        for shell in &brep.shells {
            let first_source = soup.face_sources.last().map_or(0, |s| s + 1);
            let mut shell_soup = TriangleSoup::default();
            mesh_shell(
                &mut shell_soup,
                &shell.shell,
                first_source,
                (face_size, chord),
                size,
                refinement,
            )
            .map_err(|e| {
                error(format!(
                    "shell #{}, {}: {}",
                    shell.id,
                    shell.describe_face(e.face),
                    e.message
                ))
            })?;
            weld_coincident(&mut shell_soup);
            if is_closed(&shell_soup) {
                append_soup(&mut soup, shell_soup);
            } else {
                append_soup(&mut open_shells, shell_soup);
            }
        }
        weld_coincident(&mut open_shells);
        append_soup(&mut soup, open_shells);
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

/// Whether every edge of a soup is shared by exactly two triangles.
fn is_closed(soup: &TriangleSoup) -> bool {
    let mut edges: Vec<[u32; 2]> = soup
        .triangles
        .iter()
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .map(|[a, b]| [a.min(b), a.max(b)])
        .collect();
    edges.sort_unstable();
    !edges.is_empty()
        && edges
            .chunk_by(|x, y| x == y)
            .all(|shared| shared.len() == 2)
}

/// Appends `other`'s triangles (with their face sources) and positions to `soup`.
fn append_soup(soup: &mut TriangleSoup, other: TriangleSoup) {
    let offset = soup.positions.len() as u32;
    soup.positions.extend(other.positions);
    soup.triangles
        .extend(other.triangles.iter().map(|t| t.map(|v| v + offset)));
    soup.face_sources.extend(other.face_sources);
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
