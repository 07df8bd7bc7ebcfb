//! STEP files (AP203/AP214) read through truck-stepio: every shell's faces (advanced faces of
//! solids and open shells) tessellated by flatcut's own B-rep mesher into one welded triangle
//! soup in millimetres.
//!
//! Input: the file's bytes and [`TessellateOptions`] (mesh size and chord tolerance in
//! millimetres, defaults from the part's size). Output: a [`StepInput`]. The units of the
//! context each shell's representation is in are applied (`units.rs`: a length unit `SI_UNIT`
//! with its prefix or a `CONVERSION_BASED_UNIT` such as the inch, and degrees for cone angles):
//! truck-stepio applies neither. Each shell is converted, scaled to millimetres and meshed under
//! `catch_unwind`, so a file that makes truck panic gives an error naming the shell, never a
//! crash; a face truck-stepio drops (its surface is of a kind it cannot read) is an error naming
//! the face and its surface entity. Faces are meshed by [`crate::tessellate::brep`] (each edge
//! sampled once, each face's trimmed domain refined by spade, shared edges and seams welded). A
//! file with no shell (a surface-only export) has its loose B-spline and NURBS surfaces meshed
//! over their whole parameter domains by the patch mesher.

mod statements;
mod units;

use std::collections::BTreeSet;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use glam::DVec2;
use truck_meshalgo::prelude::*;
use truck_modeling::{BSplineSurface, Matrix4, NurbsSurface, Vector4};
use truck_stepio::r#in::Table;
use truck_stepio::r#in::ruststep::tables::IntoOwned;

use self::statements::{Statement, Statements};
use self::units::{ContextUnits, file_units, units_of};
use super::IngestError;
use crate::mesh::TriangleSoup;
use crate::tessellate::brep::{StepShell, mesh_shell, shells_size, weld_coincident};
use crate::tessellate::patch::mesh_patch;
use crate::tessellate::surface::{PatchGeometry, PatchSurface, Surface};
use crate::tessellate::{
    CadPart, TessellateOptions, minimum_angle, resolve_sizes, sizes_for_diagonal,
};

/// Options of STEP ingest: the tessellation options (mesh size and chord, millimetres).
pub type StepOptions = TessellateOptions;

/// Geometric entities truck-stepio converts (and `TRIMMED_CURVE`, which flatcut replaces by its
/// basis curve); other `*_SURFACE` and `*_CURVE` entities are not.
const SUPPORTED_GEOMETRY: &[&str] = &[
    "LINE",
    "POLYLINE",
    "B_SPLINE_CURVE_WITH_KNOTS",
    "BEZIER_CURVE",
    "QUASI_UNIFORM_CURVE",
    "UNIFORM_CURVE",
    "RATIONAL_B_SPLINE_CURVE",
    "B_SPLINE_CURVE",
    "BOUNDED_CURVE",
    "CIRCLE",
    "ELLIPSE",
    "HYPERBOLA",
    "PARABOLA",
    "PCURVE",
    "SURFACE_CURVE",
    "SEAM_CURVE",
    "TRIMMED_CURVE",
    "EDGE_CURVE",
    "PLANE",
    "SPHERICAL_SURFACE",
    "CYLINDRICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "CONICAL_SURFACE",
    "B_SPLINE_SURFACE_WITH_KNOTS",
    "B_SPLINE_SURFACE",
    "BOUNDED_SURFACE",
    "UNIFORM_SURFACE",
    "QUASI_UNIFORM_SURFACE",
    "BEZIER_SURFACE",
    "RATIONAL_B_SPLINE_SURFACE",
    "SURFACE_OF_LINEAR_EXTRUSION",
    "SURFACE_OF_REVOLUTION",
];

/// Face entities a shell lists.
const FACE_ENTITIES: &[&str] = &["ADVANCED_FACE", "FACE_SURFACE", "ORIENTED_FACE"];

/// A STEP file's faces as a triangle soup.
#[derive(Debug, Clone)]
pub struct StepInput {
    /// Part name: the file stem.
    pub name: String,
    /// The faces, in millimetres; face sources number the shells' faces in file order (a face
    /// boundary is an edge between triangles of different sources).
    pub soup: TriangleSoup,
    /// Target edge length used, millimetres.
    pub mesh_size: f64,
    /// Chord tolerance used, millimetres.
    pub chord: f64,
    /// Smallest triangle angle, degrees.
    pub minimum_angle: f64,
}

/// Reads a STEP file (see the module documentation).
pub fn read_step(
    path: &Path,
    bytes: &[u8],
    options: &StepOptions,
) -> Result<StepInput, IngestError> {
    let error = |message: String| IngestError::Step {
        path: path.to_path_buf(),
        message,
    };
    let text =
        std::str::from_utf8(bytes).map_err(|e| error(format!("not a text STEP file: {e}")))?;
    let statements = Statements::parse(text);
    let default_units = file_units(&statements).map_err(error)?;
    let unsupported = unsupported_entities(&statements);
    let unsupported_note = || {
        if unsupported.is_empty() {
            String::new()
        } else {
            let names: Vec<String> = unsupported
                .iter()
                .map(|(id, name)| format!("{name} (#{id})"))
                .collect();
            format!(
                "; the file holds entities flatcut cannot read: {}",
                names.join(", ")
            )
        }
    };
    let text = &prefer_3d_curves(text);
    let text = &rewritten_for_truck(text, &statements, default_units).map_err(error)?;
    let table = catch_unwind(|| Table::from_step(text))
        .ok()
        .flatten()
        .ok_or_else(|| error("not a valid STEP exchange structure (ISO 10303-21); export it again from the CAD system".into()))?;
    let mut shell_ids: Vec<u64> = table.shell.keys().copied().collect();
    shell_ids.sort_unstable();
    let mut soup = TriangleSoup::default();
    let (mesh_size, chord) = if shell_ids.is_empty() {
        let surfaces = loose_surfaces(&table, &statements, default_units)
            .map_err(|message| error(format!("{message}{}", unsupported_note())))?;
        if surfaces.is_empty() {
            return Err(error(format!(
                "the file holds no shell, face or B-spline surface to read{}",
                unsupported_note()
            )));
        }
        append_loose_surfaces(&mut soup, &surfaces, options).map_err(error)?
    } else {
        let shells = convert_shells(&table, &shell_ids, &statements, default_units)
            .map_err(|message| error(format!("{message}{}", unsupported_note())))?;
        let size = shells_size(&shells);
        let (mesh_size, chord) =
            sizes_for_diagonal(size, options).map_err(|e| error(e.to_string()))?;
        for (shell_id, shell) in shell_ids.iter().zip(&shells) {
            let first_source = soup.face_sources.last().map_or(0, |s| s + 1);
            mesh_shell(&mut soup, shell, first_source, mesh_size, chord, size).map_err(|e| {
                let faces = shell_faces(&statements, *shell_id);
                let face = <[u64]>::get(&faces, e.face)
                    .map(|&id| describe_face(&statements, id))
                    .unwrap_or_else(|| format!("face {}", e.face + 1));
                error(format!("shell #{shell_id}, {face}: {}", e.message))
            })?;
        }
        weld_coincident(&mut soup);
        (mesh_size, chord)
    };
    if soup.triangles.is_empty() {
        return Err(error(format!(
            "no face could be tessellated{}",
            unsupported_note()
        )));
    }
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("part")
        .to_string();
    Ok(StepInput {
        name,
        minimum_angle: minimum_angle(&soup),
        soup,
        mesh_size,
        chord,
    })
}

/// The file with every surface curve's 3D curve preferred to its parameter-space curves
/// (`.PCURVE_S1.` and `.PCURVE_S2.` become `.CURVE_3D.`). The representations are equivalent by
/// the standard; truck-stepio trims a closed parameter-space curve (Open CASCADE writes circles
/// as closed 2D B-splines) the long way round, but trims 3D circles and lines correctly.
fn prefer_3d_curves(text: &str) -> String {
    text.replace(".PCURVE_S1.", ".CURVE_3D.")
        .replace(".PCURVE_S2.", ".CURVE_3D.")
}

/// The file rewritten where truck-stepio would misread it: every `CONICAL_SURFACE`'s
/// semi-angle in radians (truck-stepio reads it as radians, but it is in the plane angle unit of
/// its representation's context: degrees in files CATIA V4 writes), and every `TRIMMED_CURVE`
/// replaced by its basis curve (truck-stepio cannot read trimmed curves; an edge's vertices
/// bound its curve anyway).
fn rewritten_for_truck(
    text: &str,
    statements: &Statements,
    default_units: ContextUnits,
) -> Result<String, String> {
    let mut replacements = Vec::new();
    for (&id, statement) in statements.iter() {
        if statement.is("CONICAL_SURFACE") {
            let radians = units_of(statements, id)?.unwrap_or(default_units).radians;
            if radians != 1.0 {
                let rewritten = with_last_argument_scaled(&statement.body, radians)
                    .ok_or_else(|| format!("CONICAL_SURFACE #{id} could not be read"))?;
                replacements.push((id, rewritten));
            }
        } else if statement.is("TRIMMED_CURVE")
            && let Some(basis) = basis_curve(statements, id)
        {
            replacements.push((id, basis.body.clone()));
        }
    }
    let mut spans = Vec::with_capacity(replacements.len());
    for (id, body) in replacements {
        let (start, end) =
            statement_span(text, id).ok_or_else(|| format!("#{id} could not be read"))?;
        spans.push((start, end, format!("#{id}={body}")));
    }
    spans.sort_unstable_by_key(|&(start, _, _)| start);
    let mut rewritten = String::with_capacity(text.len());
    let mut copied = 0;
    for (start, end, statement) in spans {
        rewritten.push_str(&text[copied..start]);
        rewritten.push_str(&statement);
        copied = end;
    }
    rewritten.push_str(&text[copied..]);
    Ok(rewritten)
}

/// Trimmed curves are nested at most this deep.
const MAX_TRIM_DEPTH: usize = 8;

/// The curve a `TRIMMED_CURVE` (possibly of another trimmed curve) trims.
fn basis_curve(statements: &Statements, id: u64) -> Option<&Statement> {
    let mut current = statements.get(&id)?;
    for _ in 0..MAX_TRIM_DEPTH {
        if !current.is("TRIMMED_CURVE") {
            return Some(current);
        }
        current = statements.get(current.references.first()?)?;
    }
    None
}

/// `NAME(..., x)` with its last argument (a number) multiplied by `factor`.
fn with_last_argument_scaled(body: &str, factor: f64) -> Option<String> {
    let close = body.rfind(')')?;
    let comma = body[..close].rfind(',')?;
    let value: f64 = body[comma + 1..close].trim().parse().ok()?;
    Some(format!(
        "{},{:?}{}",
        &body[..comma],
        value * factor,
        &body[close..]
    ))
}

/// The byte range of instance `#id`'s statement in `text`, from its `#` to before its `;`.
fn statement_span(text: &str, id: u64) -> Option<(usize, usize)> {
    let label = format!("#{id}");
    let mut from = 0;
    while let Some(found) = text[from..].find(&label) {
        let start = from + found;
        let after = &text[start + label.len()..];
        let before = text[..start].trim_end();
        let at_statement = before.is_empty() || before.ends_with(';') || before.ends_with("*/");
        if after.trim_start().starts_with('=') && at_statement {
            let end = start + after.find(';')? + label.len();
            return Some((start, end));
        }
        from = start + label.len();
    }
    None
}

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
fn convert_shells(
    table: &Table,
    shell_ids: &[u64],
    statements: &Statements,
    default_units: ContextUnits,
) -> Result<Vec<StepShell>, String> {
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
        if converted.faces.len() < declared.len() {
            return Err(cannot_read(declared.len() - converted.faces.len()));
        }
        let units = units_of(statements, id)?.unwrap_or(default_units);
        shells.push(scaled_shell(converted, units.millimetres));
    }
    Ok(shells)
}

/// The faces among `faces` whose surface or one of whose edges' curves is missing or of a kind
/// truck-stepio cannot read, described for an error message.
fn unreadable_faces(statements: &Statements, faces: &[u64]) -> Vec<String> {
    faces
        .iter()
        .filter_map(|&face| {
            let surface_unreadable = face_surface(statements, face)
                .is_none_or(|(_, names)| names.iter().any(|name| is_unsupported_geometry(name)));
            if surface_unreadable {
                return Some(describe_face(statements, face));
            }
            unreadable_edge(statements, face)
                .map(|edge| format!("{}: {edge}", describe_face(statements, face)))
        })
        .collect()
}

/// The first edge of a face whose curve truck-stepio cannot read, described (`edge
/// EDGE_CURVE #33 on OFFSET_CURVE_3D (#32)`).
fn unreadable_edge(statements: &Statements, face: u64) -> Option<String> {
    let mut statement = statements.get(&face)?;
    if statement.is("ORIENTED_FACE") {
        statement = statements.get(statement.references.last()?)?;
    }
    let bounds = statement
        .references
        .iter()
        .filter_map(|r| statements.get(r));
    let loops = bounds.filter_map(|bound| statements.get(bound.references.first()?));
    for edge_loop in loops.filter(|l| l.is("EDGE_LOOP")) {
        for oriented in edge_loop
            .references
            .iter()
            .filter_map(|r| statements.get(r))
        {
            let Some(&edge) = oriented.references.last() else {
                continue;
            };
            let Some(curve) = statements.get(&edge).and_then(|e| e.references.get(2)) else {
                return Some(format!("edge #{edge} is missing"));
            };
            if let Some(unreadable) = unreadable_curve(statements, curve) {
                return Some(format!("edge EDGE_CURVE #{edge} on {unreadable}"));
            }
        }
    }
    None
}

/// The curve (or the 3D curve of a surface curve, or the basis of a trimmed curve) truck-stepio
/// cannot read, described (`OFFSET_CURVE_3D (#32)`).
fn unreadable_curve(statements: &Statements, curve: u64) -> Option<String> {
    let Some(statement) = statements.get(&curve) else {
        return Some(format!("#{curve}, which is missing"));
    };
    let describe =
        |statement: &Statement, id: u64| format!("{} (#{id})", statement.names.join(" "));
    if statement.is("SURFACE_CURVE") || statement.is("SEAM_CURVE") {
        return unreadable_curve(statements, *statement.references.first()?);
    }
    if statement.is("TRIMMED_CURVE") {
        return match basis_curve(statements, curve) {
            Some(_) => unreadable_curve(statements, *statement.references.first()?),
            None => Some(describe(statement, curve)),
        };
    }
    statement
        .names
        .iter()
        .any(|name| is_unsupported_geometry(name))
        .then(|| describe(statement, curve))
}

/// The face entities a shell statement lists, in order.
fn shell_faces(statements: &Statements, shell: u64) -> Vec<u64> {
    statements.get(&shell).map_or(Vec::new(), |statement| {
        statement
            .references
            .iter()
            .copied()
            .filter(|r| {
                statements.get(r).is_some_and(|face| {
                    face.names
                        .iter()
                        .any(|name| FACE_ENTITIES.contains(&name.as_str()))
                })
            })
            .collect()
    })
}

/// A face's surface entity `(id, names)` (through an oriented face).
fn face_surface(statements: &Statements, face: u64) -> Option<(u64, Vec<String>)> {
    let statement = statements.get(&face)?;
    if statement.is("ORIENTED_FACE") {
        return face_surface(statements, *statement.references.last()?);
    }
    let surface = *statement.references.last()?;
    statements
        .get(&surface)
        .map(|found| (surface, found.names.clone()))
}

/// `ADVANCED_FACE #17 on CONICAL_SURFACE #31`.
fn describe_face(statements: &Statements, face: u64) -> String {
    let name = statements
        .get(&face)
        .and_then(|statement| statement.names.first())
        .map_or("face", String::as_str);
    match face_surface(statements, face) {
        Some((id, surface)) => format!("{name} #{face} on {} (#{id})", surface.join(" ")),
        None => format!("{name} #{face}"),
    }
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
fn loose_surfaces(
    table: &Table,
    statements: &Statements,
    default_units: ContextUnits,
) -> Result<Vec<(u64, PatchGeometry)>, String> {
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
        surfaces.push((id, PatchGeometry::Nurbs(surface)));
    }
    for id in sorted_ids(table.rational_b_spline_surface.keys()) {
        let holder = table.rational_b_spline_surface[&id].clone();
        let converted = convert_loose("RATIONAL_B_SPLINE_SURFACE", id, || {
            let owned = holder.into_owned(table).map_err(|e| e.to_string())?;
            NurbsSurface::<Vector4>::try_from(&owned).map_err(|e| e.to_string())
        })?;
        let scale = Matrix4::from_scale(millimetres(id)?);
        surfaces.push((id, PatchGeometry::Nurbs(converted.transformed(scale))));
    }
    Ok(surfaces)
}

/// Meshes loose surfaces over their whole parameter domains with the patch mesher
/// (millimetres); returns the mesh size and chord of the last surface.
fn append_loose_surfaces(
    soup: &mut TriangleSoup,
    surfaces: &[(u64, PatchGeometry)],
    options: &TessellateOptions,
) -> Result<(f64, f64), String> {
    let mut sizes = (0.0, 0.0);
    for (index, (id, geometry)) in surfaces.iter().enumerate() {
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

/// Whether a name is a geometric entity (`*_SURFACE`, `*_CURVE`) truck-stepio does not convert.
fn is_unsupported_geometry(name: &str) -> bool {
    (name.ends_with("_SURFACE") || name.ends_with("_CURVE") || name.ends_with("_CURVE_3D"))
        && !name.contains("STYLE")
        && !SUPPORTED_GEOMETRY.contains(&name)
}

/// Geometric entities truck-stepio does not convert, `(id, name)`.
fn unsupported_entities(statements: &Statements) -> BTreeSet<(u64, String)> {
    statements
        .iter()
        .flat_map(|(id, statement)| {
            statement
                .names
                .iter()
                .filter(|name| is_unsupported_geometry(name))
                .map(|name| (*id, name.clone()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsupported_geometry_is_named() {
        let text = "#10=OFFSET_SURFACE('',#11,2.,.F.);\n#11=PLANE('',#12);\n#12=SURFACE_STYLE_USAGE(.BOTH.,#13);";
        let found = unsupported_entities(&Statements::parse(text));
        assert_eq!(
            found.into_iter().collect::<Vec<_>>(),
            vec![(10, "OFFSET_SURFACE".to_string())]
        );
    }
}
