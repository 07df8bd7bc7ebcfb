//! STEP files (AP203/AP214) read through truck-stepio: every shell's faces (advanced faces of
//! solids and open shells) tessellated by flatcut's own B-rep mesher into one welded triangle
//! soup in millimetres.
//!
//! Input: the file's bytes and [`TessellateOptions`] (mesh size and chord tolerance in
//! millimetres, defaults from the part's size). Output: a [`StepInput`]. The length unit declared
//! in the file (`SI_UNIT` with its prefix, or a `CONVERSION_BASED_UNIT` of inch or foot) is
//! applied: the reader does not apply it. Each shell is converted and meshed under
//! `catch_unwind`, so a file that makes truck panic gives an error naming the shell, never a
//! crash; a face truck-stepio drops (its surface is of a kind it cannot read) is an error naming
//! the face and its surface entity. Faces are meshed by [`crate::tessellate::brep`] (each edge
//! sampled once, each face's trimmed domain refined by spade, shared edges and seams welded). A
//! file with no shell (a surface-only export) has its loose B-spline and NURBS surfaces meshed
//! over their whole parameter domains by the patch mesher.

use std::collections::{BTreeMap, BTreeSet};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use glam::DVec2;
use truck_meshalgo::prelude::*;
use truck_modeling::{BSplineSurface, NurbsSurface, Vector4};
use truck_stepio::r#in::Table;
use truck_stepio::r#in::ruststep::tables::IntoOwned;

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

/// Geometric entities truck-stepio converts; other `*_SURFACE` and `*_CURVE` entities are not.
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
    /// Millimetres per file unit that were applied.
    pub unit_millimetres: f64,
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
    let unit_millimetres = length_unit_millimetres(text).map_err(error)?;
    let statements = statements(text);
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
    let table = catch_unwind(|| Table::from_step(text))
        .ok()
        .flatten()
        .ok_or_else(|| error("not a valid STEP exchange structure (ISO 10303-21); export it again from the CAD system".into()))?;
    let file_units = TessellateOptions {
        mesh_size: options.mesh_size.map(|m| m / unit_millimetres),
        chord: options.chord.map(|c| c / unit_millimetres),
    };
    let mut shell_ids: Vec<u64> = table.shell.keys().copied().collect();
    shell_ids.sort_unstable();
    let mut soup = TriangleSoup::default();
    let (mesh_size, chord) = if shell_ids.is_empty() {
        let surfaces = loose_surfaces(&table)
            .map_err(|message| error(format!("{message}{}", unsupported_note())))?;
        if surfaces.is_empty() {
            return Err(error(format!(
                "the file holds no shell, face or B-spline surface to read{}",
                unsupported_note()
            )));
        }
        append_loose_surfaces(&mut soup, &surfaces, &file_units).map_err(error)?
    } else {
        let shells = convert_shells(&table, &shell_ids, &statements)
            .map_err(|message| error(format!("{message}{}", unsupported_note())))?;
        let size = shells_size(&shells);
        let (mesh_size, chord) =
            sizes_for_diagonal(size, &file_units).map_err(|e| error(e.to_string()))?;
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
    for p in &mut soup.positions {
        *p *= unit_millimetres;
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
        unit_millimetres,
        mesh_size: mesh_size * unit_millimetres,
        chord: chord * unit_millimetres,
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

/// Converts the shells with truck-stepio; a face it drops (an unreadable surface) is an error
/// naming the face. Faces on surfaces flatcut knows truck-stepio cannot read are named before
/// truck-stepio is called: it would print `Lookup failed for #N` on stderr for each (it
/// reports a failed lookup of a referenced entity on stderr and drops the face).
fn convert_shells(
    table: &Table,
    shell_ids: &[u64],
    statements: &Statements,
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
        shells.push(converted);
    }
    Ok(shells)
}

/// The faces among `faces` whose surface is missing or of a kind truck-stepio cannot read,
/// described for an error message.
fn unreadable_faces(statements: &Statements, faces: &[u64]) -> Vec<String> {
    faces
        .iter()
        .filter(|&&face| {
            face_surface(statements, face)
                .is_none_or(|(_, names)| names.iter().any(|name| is_unsupported_geometry(name)))
        })
        .map(|&face| describe_face(statements, face))
        .collect()
}

/// The face entities a shell statement lists, in order.
fn shell_faces(statements: &Statements, shell: u64) -> Vec<u64> {
    statements
        .get(&shell)
        .map_or(Vec::new(), |(_, references)| {
            references
                .iter()
                .copied()
                .filter(|r| {
                    statements.get(r).is_some_and(|(names, _)| {
                        names
                            .iter()
                            .any(|name| FACE_ENTITIES.contains(&name.as_str()))
                    })
                })
                .collect()
        })
}

/// A face's surface entity `(id, names)` (through an oriented face).
fn face_surface(statements: &Statements, face: u64) -> Option<(u64, Vec<String>)> {
    let (names, references) = statements.get(&face)?;
    if names.iter().any(|name| name == "ORIENTED_FACE") {
        return face_surface(statements, *references.last()?);
    }
    let surface = *references.last()?;
    statements
        .get(&surface)
        .map(|(names, _)| (surface, names.clone()))
}

/// `ADVANCED_FACE #17 on CONICAL_SURFACE #31`.
fn describe_face(statements: &Statements, face: u64) -> String {
    let name = statements
        .get(&face)
        .and_then(|(names, _)| names.first())
        .map_or("face", String::as_str);
    match face_surface(statements, face) {
        Some((id, surface)) => format!("{name} #{face} on {} (#{id})", surface.join(" ")),
        None => format!("{name} #{face}"),
    }
}

/// The B-spline and NURBS surfaces of a file with no shell (a surface-only export), each with
/// its entity id, as truck-geometry NURBS patches.
fn loose_surfaces(table: &Table) -> Result<Vec<(u64, PatchGeometry)>, String> {
    let mut surfaces = Vec::new();
    let mut ids: Vec<u64> = table.b_spline_surface_with_knots.keys().copied().collect();
    ids.sort_unstable();
    for id in ids {
        let holder = table.b_spline_surface_with_knots[&id].clone();
        let converted = catch_unwind(AssertUnwindSafe(|| {
            let owned = holder.into_owned(table).map_err(|e| e.to_string())?;
            BSplineSurface::<Point3>::try_from(&owned).map_err(|e| e.to_string())
        }))
        .map_err(|_| format!("B_SPLINE_SURFACE_WITH_KNOTS #{id}: truck-stepio failed on it"))?
        .map_err(|e| format!("B_SPLINE_SURFACE_WITH_KNOTS #{id}: {e}"))?;
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
        surfaces.push((id, PatchGeometry::nurbs(surface)));
    }
    let mut ids: Vec<u64> = table.rational_b_spline_surface.keys().copied().collect();
    ids.sort_unstable();
    for id in ids {
        let holder = table.rational_b_spline_surface[&id].clone();
        let converted = catch_unwind(AssertUnwindSafe(|| {
            let owned = holder.into_owned(table).map_err(|e| e.to_string())?;
            NurbsSurface::<Vector4>::try_from(&owned).map_err(|e| e.to_string())
        }))
        .map_err(|_| format!("RATIONAL_B_SPLINE_SURFACE #{id}: truck-stepio failed on it"))?
        .map_err(|e| format!("RATIONAL_B_SPLINE_SURFACE #{id}: {e}"))?;
        surfaces.push((id, PatchGeometry::Nurbs(converted)));
    }
    Ok(surfaces)
}

/// Meshes loose surfaces over their whole parameter domains with the patch mesher (file units);
/// returns the mesh size and chord of the last surface.
fn append_loose_surfaces(
    soup: &mut TriangleSoup,
    surfaces: &[(u64, PatchGeometry)],
    file_units: &TessellateOptions,
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
            resolve_sizes(&part, file_units).map_err(|e| format!("surface #{id}: {e}"))?;
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

/// Each entity instance of the data section: its names (several for a complex instance) and
/// the instances it refers to, in order.
type Statements = BTreeMap<u64, (Vec<String>, Vec<u64>)>;

/// Entity instances `#id = NAME(...)` of the data section (see [`Statements`]).
fn statements(text: &str) -> Statements {
    let mut statements = Statements::new();
    for statement in text.split(';') {
        let statement = statement.trim();
        let Some(rest) = statement.strip_prefix('#') else {
            continue;
        };
        let Some((id, body)) = rest.split_once('=') else {
            continue;
        };
        let Ok(id) = id.trim().parse::<u64>() else {
            continue;
        };
        let body = body.trim();
        let mut names = Vec::new();
        if let Some(complex) = body.strip_prefix('(') {
            let mut depth = 0usize;
            let mut word = String::new();
            for c in complex.chars() {
                match c {
                    '(' => {
                        if depth == 0 && !word.trim().is_empty() {
                            names.push(word.trim().to_string());
                        }
                        word.clear();
                        depth += 1;
                    }
                    ')' => depth = depth.saturating_sub(1),
                    _ if depth == 0 => word.push(c),
                    _ => {}
                }
            }
        } else if let Some((name, _)) = body.split_once('(') {
            names.push(name.trim().to_string());
        }
        statements.insert(id, (names, references(body)));
    }
    statements
}

/// The `#id` references of a statement's body, in order.
fn references(body: &str) -> Vec<u64> {
    body.split('#')
        .skip(1)
        .filter_map(|rest| {
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            digits.parse().ok()
        })
        .collect()
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
        .flat_map(|(id, (names, _))| {
            names
                .iter()
                .filter(|name| is_unsupported_geometry(name))
                .map(|name| (*id, name.clone()))
        })
        .collect()
}

/// Millimetres per length unit of the file: its `LENGTH_UNIT` (SI metre with a prefix, or a
/// conversion-based inch or foot). Millimetres when the file declares none.
pub fn length_unit_millimetres(text: &str) -> Result<f64, String> {
    let compact: String = text
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    let length_units: Vec<&str> = compact
        .split(';')
        .filter(|statement| statement.contains("LENGTH_UNIT("))
        .collect();
    // A conversion-based unit refers to an SI unit of its own: it is the file's unit.
    let marker = "CONVERSION_BASED_UNIT('";
    if let Some(statement) = length_units.iter().find(|s| s.contains(marker)) {
        let start = statement.find(marker).map_or(0, |i| i + marker.len());
        let name = statement[start..].split('\'').next().unwrap_or_default();
        return match name {
            "INCH" | "IN" => Ok(25.4),
            "FOOT" | "FT" => Ok(304.8),
            "MILLIMETRE" | "MM" => Ok(1.0),
            other => Err(format!(
                "the length unit '{other}' is not supported; export in millimetres, metres, inches or feet"
            )),
        };
    }
    let si = length_units
        .iter()
        .find(|s| s.contains("SI_UNIT(") && s.contains(".METRE."));
    Ok(match si {
        Some(statement) if statement.contains(".MILLI.") => 1.0,
        Some(statement) if statement.contains(".CENTI.") => 10.0,
        Some(statement) if statement.contains(".MICRO.") => 1e-3,
        Some(statement) if statement.contains(".KILO.") => 1e6,
        Some(_) => 1000.0,
        None => 1.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_are_read_from_the_length_unit() {
        let millimetres = "#1=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));";
        let metres = "#1=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );";
        let inches = "#3=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n#2=(CONVERSION_BASED_UNIT('INCH',#3)LENGTH_UNIT()NAMED_UNIT(#4));";
        let feet = "#2=(CONVERSION_BASED_UNIT('FOOT',#3)LENGTH_UNIT()NAMED_UNIT(#4));";
        assert_eq!(length_unit_millimetres(millimetres), Ok(1.0));
        assert_eq!(length_unit_millimetres(metres), Ok(1000.0));
        assert_eq!(length_unit_millimetres(inches), Ok(25.4));
        assert_eq!(length_unit_millimetres(feet), Ok(304.8));
    }

    #[test]
    fn unsupported_geometry_is_named() {
        let text = "#10=OFFSET_SURFACE('',#11,2.,.F.);\n#11=PLANE('',#12);\n#12=SURFACE_STYLE_USAGE(.BOTH.,#13);";
        let found = unsupported_entities(&statements(text));
        assert_eq!(
            found.into_iter().collect::<Vec<_>>(),
            vec![(10, "OFFSET_SURFACE".to_string())]
        );
    }
}
