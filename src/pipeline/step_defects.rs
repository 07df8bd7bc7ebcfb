//! Mesh defects of a STEP file's tessellation named by the STEP faces they lie on: a refused
//! solid (two faces meeting a third along one edge, a face meshed onto itself) then says where
//! in the file to look, not only which mesh vertices.

use std::collections::BTreeSet;

use crate::cad::{Brep, TriangleSoup};
use crate::error::Error;
use crate::mesh::Defect;
use crate::tessellate::BrepError;

/// Faces named per defect, at most.
const FACES_SHOWN: usize = 4;

/// `error` with each mesh defect of `soup` (the tessellation of `brep`) followed by the STEP
/// faces of the triangles at it; any other error as it is.
pub fn with_step_faces(error: Error, brep: &Brep, soup: &TriangleSoup) -> Error {
    let Error::Mesh { path, defects } = error else {
        return error;
    };
    let lines: Vec<String> = defects
        .defects
        .iter()
        .map(|defect| {
            let faces = faces_at(defect, brep, soup);
            if faces.is_empty() {
                defect.to_string()
            } else {
                format!("{defect}, on {}", faces.join(" and "))
            }
        })
        .collect();
    Error::Brep {
        path,
        defect: BrepError {
            message: format!(
                "its tessellation is not a manifold surface ({} defect(s)):\n  - {}",
                lines.len(),
                lines.join("\n  - ")
            ),
        },
    }
}

/// The soup vertices a defect is at.
fn defect_vertices(defect: &Defect, soup: &TriangleSoup) -> Vec<u32> {
    match defect {
        Defect::NonManifoldEdge { vertices, .. } => vertices.to_vec(),
        Defect::NonManifoldVertex { vertex, .. } => vec![*vertex as u32],
        Defect::ZeroArea { triangle, .. } | Defect::RepeatedVertex { triangle } => soup
            .triangles
            .get(*triangle)
            .map_or(Vec::new(), |t| t.to_vec()),
        _ => Vec::new(),
    }
}

/// The STEP faces (described) of the triangles that hold every vertex of the defect.
fn faces_at(defect: &Defect, brep: &Brep, soup: &TriangleSoup) -> Vec<String> {
    let vertices = defect_vertices(defect, soup);
    if vertices.is_empty() {
        return Vec::new();
    }
    let sources: BTreeSet<u32> = soup
        .triangles
        .iter()
        .zip(&soup.face_sources)
        .filter(|(triangle, _)| vertices.iter().all(|v| triangle.contains(v)))
        .map(|(_, &source)| source)
        .collect();
    let mut named: Vec<String> = sources
        .iter()
        .filter_map(|&source| describe_source(brep, source as usize))
        .collect();
    if named.len() > FACES_SHOWN {
        let more = named.len() - FACES_SHOWN;
        named.truncate(FACES_SHOWN);
        named.push(format!("{more} more"));
    }
    named
}

/// The face a tessellation's face source numbers (shells' faces in order), described.
fn describe_source(brep: &Brep, mut source: usize) -> Option<String> {
    for shell in &brep.shells {
        let count = shell.shell.faces.len();
        if source < count {
            return Some(format!(
                "shell #{} {}",
                shell.id,
                shell.describe_face(source)
            ));
        }
        source -= count;
    }
    None
}
