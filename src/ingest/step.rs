//! STEP files (AP203/AP214) through truck-stepio: every shell's faces (advanced faces of solids
//! and open shells) tessellated with truck-meshalgo into one triangle soup in millimetres.
//!
//! Input: the file's bytes and [`TessellateOptions`] (its chord tolerance bounds the distance
//! between faces and triangles; truck-meshalgo does not take a target edge length, so the mesh
//! size is not applied to STEP faces). Output: a [`StepInput`]. The length unit declared in the
//! file (`SI_UNIT` with its prefix, or a `CONVERSION_BASED_UNIT` of inch or foot) is applied:
//! the reader does not apply it. Each shell is converted and meshed under `catch_unwind`, so a
//! file that makes truck panic gives an error naming the shell entity and the geometric entities
//! of the file truck cannot read, never a crash. Vertices of one shell's faces are welded
//! (truck-meshalgo meshes each face on its own), so a closed face's seam is welded shut too.
//! A file with no shell (a surface-only export) has its loose B-spline and NURBS surfaces meshed
//! over their whole parameter domains by flatcut's own patch mesher (the mesh size applies).

use std::collections::BTreeSet;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_modeling::{BSplineSurface, NurbsSurface, Vector4};
use truck_stepio::r#in::Table;
use truck_stepio::r#in::ruststep::tables::IntoOwned;

use super::IngestError;
use crate::mesh::TriangleSoup;
use crate::tessellate::patch::mesh_patch;
use crate::tessellate::surface::{PatchGeometry, PatchSurface, Surface};
use crate::tessellate::{CadPart, DEFAULT_CHORD_RATIO, TessellateOptions, resolve_sizes};

/// Options of STEP ingest: the tessellation options (chord tolerance).
pub type StepOptions = TessellateOptions;

/// truck-meshalgo panics on a tolerance below this (file units).
pub const MINIMUM_MESHALGO_TOLERANCE: f64 = 1e-5;
/// Weld distance of face-boundary vertices, as a fraction of the shell's size.
pub const STEP_WELD_RATIO: f64 = 1e-7;

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

/// A STEP file's faces as a triangle soup.
#[derive(Debug, Clone)]
pub struct StepInput {
    /// Part name: the file stem.
    pub name: String,
    /// The faces, in millimetres; face sources number the shells' faces in file order.
    pub soup: TriangleSoup,
    /// Millimetres per file unit that were applied.
    pub unit_millimetres: f64,
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
    let unsupported = unsupported_entities(text);
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
    let table = catch_unwind(|| Table::from_step(text))
        .ok()
        .flatten()
        .ok_or_else(|| error("not a valid STEP exchange structure (ISO 10303-21); export it again from the CAD system".into()))?;
    let mut shell_ids: Vec<u64> = table.shell.keys().copied().collect();
    shell_ids.sort_unstable();
    let mut soup = TriangleSoup::default();
    if shell_ids.is_empty() {
        let surfaces = loose_surfaces(&table)
            .map_err(|message| error(format!("{message}{}", unsupported_note())))?;
        if surfaces.is_empty() {
            return Err(error(format!(
                "the file holds no shell, face or B-spline surface to read{}",
                unsupported_note()
            )));
        }
        append_loose_surfaces(&mut soup, &surfaces, options, unit_millimetres).map_err(error)?;
    }
    for id in shell_ids {
        let shell = &table.shell[&id];
        let converted = catch_unwind(AssertUnwindSafe(|| table.to_compressed_shell(shell)))
            .map_err(|_| {
                error(format!(
                    "shell #{id}: truck-stepio failed on it{}",
                    unsupported_note()
                ))
            })?
            .map_err(|e| error(format!("shell #{id}: {e}{}", unsupported_note())))?;
        let size = shell_size(&converted);
        let chord_in_file_units = options
            .chord
            .map_or(size * DEFAULT_CHORD_RATIO, |chord| chord / unit_millimetres);
        let tolerance = chord_in_file_units.clamp(
            MINIMUM_MESHALGO_TOLERANCE,
            size.max(MINIMUM_MESHALGO_TOLERANCE),
        );
        let polygon = catch_unwind(AssertUnwindSafe(|| {
            let mut polygon = converted.robust_triangulation(tolerance).to_polygon();
            polygon
                .put_together_same_attrs(size * STEP_WELD_RATIO)
                .remove_degenerate_faces()
                .remove_unused_attrs();
            polygon
        }))
        .map_err(|_| {
            error(format!(
                "shell #{id}: truck-meshalgo failed to tessellate it{}",
                unsupported_note()
            ))
        })?;
        append_polygon(&mut soup, &polygon, unit_millimetres);
    }
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
        soup,
        unit_millimetres,
    })
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

/// Meshes loose surfaces over their whole parameter domains with the patch mesher.
fn append_loose_surfaces(
    soup: &mut TriangleSoup,
    surfaces: &[(u64, PatchGeometry)],
    options: &StepOptions,
    unit_millimetres: f64,
) -> Result<(), String> {
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
        let file_units = TessellateOptions {
            mesh_size: options.mesh_size.map(|m| m / unit_millimetres),
            chord: options.chord.map(|c| c / unit_millimetres),
        };
        let (mesh_size, chord) =
            resolve_sizes(&part, &file_units).map_err(|e| format!("surface #{id}: {e}"))?;
        let mesh = catch_unwind(AssertUnwindSafe(|| {
            mesh_patch(&patch, &[], mesh_size, chord)
        }))
        .map_err(|_| format!("surface #{id}: the surface could not be tessellated"))?
        .map_err(|e| format!("surface #{id}: {e}"))?;
        let offset = soup.positions.len() as u32;
        soup.positions
            .extend(mesh.positions.iter().map(|&p| p * unit_millimetres));
        soup.triangles
            .extend(mesh.triangles.iter().map(|t| t.map(|v| v + offset)));
        soup.face_sources
            .extend(std::iter::repeat_n(index as u32, mesh.triangles.len()));
    }
    Ok(())
}

fn shell_size<C, S>(shell: &truck_topology::compress::CompressedShell<Point3, C, S>) -> f64 {
    let mut low = DVec3::splat(f64::INFINITY);
    let mut high = DVec3::splat(f64::NEG_INFINITY);
    for p in &shell.vertices {
        let p = DVec3::new(p.x, p.y, p.z);
        low = low.min(p);
        high = high.max(p);
    }
    let size = (high - low).length();
    if size.is_finite() { size } else { 0.0 }
}

fn append_polygon(soup: &mut TriangleSoup, polygon: &PolygonMesh, scale: f64) {
    let offset = soup.positions.len() as u32;
    soup.positions.extend(
        polygon
            .positions()
            .iter()
            .map(|p| DVec3::new(p.x, p.y, p.z) * scale),
    );
    let source = soup.face_sources.last().map_or(0, |s| s + 1);
    for triangle in polygon.faces().triangle_iter() {
        soup.triangles.push([
            offset + triangle[0].pos as u32,
            offset + triangle[1].pos as u32,
            offset + triangle[2].pos as u32,
        ]);
        soup.face_sources.push(source);
    }
}

/// Entity instances `#id = NAME(...)` of the data section, with complex instances'
/// constituent names, in file order.
fn entity_names(text: &str) -> Vec<(u64, String)> {
    let mut names = Vec::new();
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
        if let Some(complex) = body.strip_prefix('(') {
            let mut depth = 0usize;
            let mut word = String::new();
            for c in complex.chars() {
                match c {
                    '(' => {
                        if depth == 0 && !word.trim().is_empty() {
                            names.push((id, word.trim().to_string()));
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
            names.push((id, name.trim().to_string()));
        }
    }
    names
}

/// Geometric entities (`*_SURFACE`, `*_CURVE`) truck-stepio does not convert.
fn unsupported_entities(text: &str) -> BTreeSet<(u64, String)> {
    entity_names(text)
        .into_iter()
        .filter(|(_, name)| {
            (name.ends_with("_SURFACE") || name.ends_with("_CURVE") || name.ends_with("_CURVE_3D"))
                && !name.contains("STYLE")
                && !SUPPORTED_GEOMETRY.contains(&name.as_str())
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
        let found = unsupported_entities(text);
        assert_eq!(
            found.into_iter().collect::<Vec<_>>(),
            vec![(10, "OFFSET_SURFACE".to_string())]
        );
    }
}
