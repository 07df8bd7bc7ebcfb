//! Shells and loose surfaces converted by truck-stepio under `catch_unwind` and scaled to
//! millimetres by the units of their representation's context.

use std::panic::{AssertUnwindSafe, catch_unwind};

use truck_meshalgo::prelude::*;
use truck_modeling::{BSplineSurface, Matrix4, NurbsSurface, Vector4};
use truck_stepio::r#in::Table;
use truck_stepio::r#in::ruststep::tables::IntoOwned;

use super::entities::{describe_face, shell_faces, unreadable_faces};
use super::statements::Statements;
use super::units::{ContextUnits, units_of};
use crate::cad::{BrepShell, FaceSource, LooseSurface, PatchGeometry, StepShell};

/// Faces named in the message about a shell none of whose faces could be read, at most.
const NAMED_FACES: usize = 3;

/// A shell with its vertices, curves and surfaces scaled by `factor` (file units to
/// millimetres).
fn scaled_shell(mut shell: StepShell, factor: f64) -> StepShell {
    if factor == 1.0 {
        return shell;
    }
    let scale = Matrix4::from_scale(factor);
    for vertex in &mut shell.vertices {
        *vertex = Point3::from_vec(vertex.to_vec() * factor);
    }
    for edge in &mut shell.edges {
        edge.curve.transform_by(scale);
    }
    for face in &mut shell.faces {
        face.surface.transform_by(scale);
    }
    shell
}

/// Converts the shells with truck-stepio and scales each to millimetres by the units of its
/// representation (`default_units` where none is found); a face it drops (an unreadable
/// surface) is an error naming the face. Faces on surfaces flatcut knows truck-stepio cannot read are named before
/// truck-stepio is called: it would print `Lookup failed for #N` on stderr for each (it
/// reports a failed lookup of a referenced entity on stderr and drops the face).
pub fn convert_shells(
    table: &Table,
    shell_ids: &[u64],
    statements: &Statements,
    default_units: ContextUnits,
) -> Result<Vec<BrepShell>, String> {
    let mut shells = Vec::with_capacity(shell_ids.len());
    for &id in shell_ids {
        let declared = shell_faces(statements, id);
        let unreadable = unreadable_faces(statements, &declared);
        let cannot_read = |count: usize| {
            format!(
                "shell #{id}: {count} of its {} faces cannot be read{}",
                declared.len(),
                if unreadable.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", unreadable.join(", "))
                }
            )
        };
        if !unreadable.is_empty() {
            return Err(cannot_read(unreadable.len()));
        }
        let shell = &table.shell[&id];
        let converted = catch_unwind(AssertUnwindSafe(|| table.to_compressed_shell(shell)))
            .map_err(|_| format!("shell #{id}: truck-stepio failed on it"))?
            .map_err(|e| format!("shell #{id}: {e}"))?;
        if converted.faces.is_empty() && !declared.is_empty() {
            // Every face was dropped: those are the faces to name.
            let named: Vec<String> = declared
                .iter()
                .take(NAMED_FACES)
                .map(|&face| describe_face(statements, face))
                .collect();
            return Err(format!(
                "{} ({}{}; truck-stepio dropped them: a degenerate face, or a loop it cannot \
                 close)",
                cannot_read(declared.len()),
                named.join(", "),
                if declared.len() > NAMED_FACES {
                    ", ..."
                } else {
                    ""
                }
            ));
        }
        if converted.faces.len() < declared.len() {
            return Err(cannot_read(declared.len() - converted.faces.len()));
        }
        let units = units_of(statements, id)?.unwrap_or(default_units);
        shells.push(BrepShell {
            id,
            shell: scaled_shell(converted, units.millimetres),
            faces: declared
                .iter()
                .map(|&face| FaceSource {
                    id: face,
                    description: describe_face(statements, face),
                })
                .collect(),
        });
    }
    Ok(shells)
}

/// Entity ids in increasing order, so that loose surfaces are met in file order.
fn sorted_ids<'a>(ids: impl Iterator<Item = &'a u64>) -> Vec<u64> {
    let mut ids: Vec<u64> = ids.copied().collect();
    ids.sort_unstable();
    ids
}

/// Runs truck-stepio's conversion of the loose surface `entity #id` under `catch_unwind`, so a
/// panic or a refusal is an error naming the entity.
fn convert_loose<T>(
    entity: &str,
    id: u64,
    convert: impl FnOnce() -> Result<T, String>,
) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(convert))
        .map_err(|_| format!("{entity} #{id}: truck-stepio failed on it"))?
        .map_err(|e| format!("{entity} #{id}: {e}"))
}

/// The B-spline and NURBS surfaces of a file with no shell (a surface-only export), each with
/// its entity id, as truck-geometry NURBS patches in millimetres (by the units of each
/// surface's representation, `default_units` where none is found).
pub fn loose_surfaces(
    table: &Table,
    statements: &Statements,
    default_units: ContextUnits,
) -> Result<Vec<LooseSurface>, String> {
    let millimetres = |id: u64| -> Result<f64, String> {
        Ok(units_of(statements, id)?
            .unwrap_or(default_units)
            .millimetres)
    };
    let mut surfaces = Vec::new();
    for id in sorted_ids(table.b_spline_surface_with_knots.keys()) {
        let holder = table.b_spline_surface_with_knots[&id].clone();
        let converted = convert_loose("B_SPLINE_SURFACE_WITH_KNOTS", id, || {
            let owned = holder.into_owned(table).map_err(|e| e.to_string())?;
            BSplineSurface::<Point3>::try_from(&owned).map_err(|e| e.to_string())
        })?;
        let (knots, points) = (
            converted.knot_vecs().clone(),
            converted.control_points().clone(),
        );
        let homogeneous: Vec<Vec<Vector4>> = points
            .iter()
            .map(|row| {
                row.iter()
                    .map(|p| Vector4::new(p.x, p.y, p.z, 1.0))
                    .collect()
            })
            .collect();
        let surface = BSplineSurface::try_new(knots, homogeneous)
            .map_err(|e| format!("B_SPLINE_SURFACE_WITH_KNOTS #{id}: {e}"))?;
        let scale = Matrix4::from_scale(millimetres(id)?);
        let surface = NurbsSurface::new(surface).transformed(scale);
        surfaces.push(LooseSurface {
            id,
            geometry: PatchGeometry::Nurbs(surface),
        });
    }
    for id in sorted_ids(table.rational_b_spline_surface.keys()) {
        let holder = table.rational_b_spline_surface[&id].clone();
        let converted = convert_loose("RATIONAL_B_SPLINE_SURFACE", id, || {
            let owned = holder.into_owned(table).map_err(|e| e.to_string())?;
            NurbsSurface::<Vector4>::try_from(&owned).map_err(|e| e.to_string())
        })?;
        let scale = Matrix4::from_scale(millimetres(id)?);
        surfaces.push(LooseSurface {
            id,
            geometry: PatchGeometry::Nurbs(converted.transformed(scale)),
        });
    }
    Ok(surfaces)
}
