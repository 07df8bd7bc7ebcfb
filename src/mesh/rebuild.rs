//! Rebuilding a facet model after an edit of one (a cut opened along edges, faces split along a
//! smooth cut): the edited triangles are checked for the facet model's invariants on the
//! adjacency built once, in linear time besides that build, instead of through [`validate`]
//! (which repairs and relabels outside input, and sorts the half-edges three times).
//!
//! An edit keeps the vertex numbering and the face order, so nothing is relabelled: the rebuilt
//! model has the soup's vertices and faces in the soup's order, or the edit is refused. Refused:
//! an unreferenced vertex, a repeated corner or a zero-area triangle, an edge of more than two
//! faces, two faces that disagree in orientation across their edge, a vertex whose faces form
//! more than one fan, and faces in more than one connected piece ([`RebuildError::Disconnected`],
//! which a cut that separates the part gives).
//!
//! [`validate`]: super::validate

use std::fmt;

use super::facet::{FacetModel, NONE};
use crate::cad::TriangleSoup;
use crate::geometry::tolerance::has_zero_area;

/// Why an edited mesh is not a facet model.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RebuildError {
    /// Its faces form more than one connected piece.
    Disconnected,
    /// It breaks another invariant; the text names the element.
    Defect(String),
}

impl fmt::Display for RebuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Disconnected => write!(f, "the faces form more than one piece"),
            Self::Defect(what) => write!(f, "{what}"),
        }
    }
}

impl std::error::Error for RebuildError {}

/// The facet model of an edited mesh, its vertices and faces in the soup's order; see the
/// module documentation.
pub fn rebuild(soup: TriangleSoup) -> Result<FacetModel, RebuildError> {
    check_triangles(&soup)?;
    let model = with_adjacency(soup);
    check_edges(&model)?;
    check_fans(&model)?;
    check_connected(model)
}

/// The facet model of a facet model's faces with the vertices of some of them split: the faces
/// around a vertex grouped into wedges (joined across edges at the vertex), each wedge but one
/// given its own copy of the vertex at the same position, as a cut along edges does. The faces
/// keep their corners' order and shape, every copy holds one wedge (one fan) and no edge gains
/// a face, so every invariant but connectedness holds by construction: only that is checked
/// (the rest too in debug builds). The model is in the soup's order, as [`rebuild`]'s.
pub fn rebuild_split(soup: TriangleSoup) -> Result<FacetModel, RebuildError> {
    let model = with_adjacency(soup);
    debug_assert!(check_edges(&model).is_ok() && check_fans(&model).is_ok());
    check_connected(model)
}

/// The soup's facet model, its invariants taken as checked.
fn with_adjacency(soup: TriangleSoup) -> FacetModel {
    let folds: Vec<(u32, u32, u32)> = (soup.fold_edges.iter())
        .map(|e| (e.vertices[0], e.vertices[1], e.fold_line))
        .collect();
    FacetModel::from_checked(soup.positions, soup.triangles, soup.face_sources, &folds)
}

/// Every corner is a vertex, no triangle repeats one or has zero area, every vertex is used.
fn check_triangles(soup: &TriangleSoup) -> Result<(), RebuildError> {
    let count = soup.positions.len();
    let mut used = vec![false; count];
    for (face, t) in soup.triangles.iter().enumerate() {
        if t.iter().any(|&v| v as usize >= count) || t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            return Err(defect(format!("triangle {face} has corners {t:?}")));
        }
        if has_zero_area(t.map(|v| soup.positions[v as usize])) {
            return Err(defect(format!("triangle {face} has zero area")));
        }
        t.iter().for_each(|&v| used[v as usize] = true);
    }
    match used.iter().position(|&u| !u) {
        Some(vertex) => Err(defect(format!("vertex {vertex} is in no triangle"))),
        None => Ok(()),
    }
}

/// Every edge has one or two faces, and two faces run along it in opposite directions.
fn check_edges(model: &FacetModel) -> Result<(), RebuildError> {
    let sides: usize = (model.edge_faces().iter())
        .map(|faces| if faces[1] == NONE { 1 } else { 2 })
        .sum();
    if sides != 3 * model.triangle_count() {
        return Err(defect("an edge has more than two faces".to_string()));
    }
    for (edge, &[f, g]) in model.edge_faces().iter().enumerate() {
        if g != NONE && direction(model, f, edge) == direction(model, g, edge) {
            let [a, b] = model.edges()[edge];
            return Err(defect(format!(
                "faces {f} and {g} disagree in orientation across edge {a}-{b}"
            )));
        }
    }
    Ok(())
}

/// Whether face `face` runs along `edge` from its lower to its higher vertex.
fn direction(model: &FacetModel, face: u32, edge: usize) -> bool {
    let t = model.triangles()[face as usize];
    let k = (model.face_edges()[face as usize].iter())
        .position(|&e| e as usize == edge)
        .expect("a face owns its edges");
    t[k] < t[(k + 1) % 3]
}

/// The faces around every vertex form a single fan: walking from one of them across the edges
/// at the vertex reaches all of them.
fn check_fans(model: &FacetModel) -> Result<(), RebuildError> {
    for vertex in 0..model.vertex_count() as u32 {
        let faces = model.vertex_faces(vertex);
        let mut reached = 1;
        // Turn one way from the first face, then the other way if the fan is open.
        for turn in [0, 2] {
            let mut face = faces[0];
            loop {
                let next = across(model, face, vertex, turn);
                if next == NONE || next == faces[0] {
                    break;
                }
                reached += 1;
                if reached > faces.len() {
                    break;
                }
                face = next;
            }
            if reached == faces.len() {
                break;
            }
        }
        if reached != faces.len() {
            return Err(defect(format!(
                "the faces of vertex {vertex} form more than one fan"
            )));
        }
    }
    Ok(())
}

/// The face beyond `face` across its edge at `vertex` that leaves the vertex (`turn` 0) or
/// arrives at it (`turn` 2), or [`NONE`] on the boundary.
fn across(model: &FacetModel, face: u32, vertex: u32, turn: usize) -> u32 {
    let t = model.triangles()[face as usize];
    let k = t
        .iter()
        .position(|&v| v == vertex)
        .expect("a face of the vertex");
    let edge = model.face_edges()[face as usize][(k + turn) % 3] as usize;
    let [f, g] = model.edge_faces()[edge];
    if f == face { g } else { f }
}

/// All faces are reached from the first across shared edges.
fn check_connected(model: FacetModel) -> Result<FacetModel, RebuildError> {
    let mut seen = vec![false; model.triangle_count()];
    let mut stack = vec![0u32];
    seen[0] = true;
    let mut reached = 1;
    while let Some(face) = stack.pop() {
        for &edge in &model.face_edges()[face as usize] {
            for other in model.edge_faces()[edge as usize] {
                if other != NONE && !seen[other as usize] {
                    seen[other as usize] = true;
                    reached += 1;
                    stack.push(other);
                }
            }
        }
    }
    if reached == model.triangle_count() {
        Ok(model)
    } else {
        Err(RebuildError::Disconnected)
    }
}

fn defect(what: String) -> RebuildError {
    RebuildError::Defect(what)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::mesh::rebuild::*;
    use crate::mesh::validate;

    /// A 2 x 2 grid of squares, each split into two triangles, counter-clockwise.
    fn grid() -> TriangleSoup {
        let positions = (0..9)
            .map(|i| DVec3::new((i % 3) as f64, (i / 3) as f64, 0.0))
            .collect();
        let mut triangles = Vec::new();
        for row in 0..2u32 {
            for column in 0..2u32 {
                let a = row * 3 + column;
                triangles.push([a, a + 1, a + 4]);
                triangles.push([a, a + 4, a + 3]);
            }
        }
        TriangleSoup::new(positions, triangles)
    }

    #[test]
    fn an_intact_mesh_rebuilds_to_what_validation_gives() {
        let soup = grid();
        let rebuilt = rebuild(soup.clone()).expect("a valid grid");
        let validated = validate(&soup).expect("a valid grid").components.remove(0);
        assert_eq!(rebuilt, validated);
    }

    /// The grid with the corners `vertices` of faces `faces` replaced by copies of them.
    fn with_copies(mut soup: TriangleSoup, vertices: &[u32], faces: &[usize]) -> TriangleSoup {
        let first_copy = soup.positions.len() as u32;
        for &v in vertices {
            soup.positions.push(soup.positions[v as usize]);
        }
        for &face in faces {
            for corner in &mut soup.triangles[face] {
                if let Some(k) = vertices.iter().position(|v| v == corner) {
                    *corner = first_copy + k as u32;
                }
            }
        }
        soup
    }

    #[test]
    fn a_slit_rebuilds_as_the_checked_rebuild_does() {
        // A slit along edge 3-4 from the left side: vertex 3 is split between face 1 and faces
        // 4 and 5; the tip, vertex 4, is not.
        let slit = with_copies(grid(), &[3], &[4, 5]);
        let rebuilt = rebuild(slit.clone()).expect("a slit grid is a facet model");
        assert_eq!(rebuild_split(slit), Ok(rebuilt));
    }

    #[test]
    fn a_split_that_cuts_the_grid_in_two_is_refused_as_disconnected() {
        // A cut along the middle row, 3-4-5, from side to side.
        let halves = with_copies(grid(), &[3, 4, 5], &[4, 5, 6, 7]);
        assert_eq!(rebuild_split(halves), Err(RebuildError::Disconnected));
    }

    #[test]
    fn a_flipped_face_is_refused() {
        let mut soup = grid();
        soup.triangles[3].swap(1, 2);
        assert!(matches!(rebuild(soup), Err(RebuildError::Defect(_))));
    }

    #[test]
    fn an_edge_of_three_faces_is_refused() {
        let mut soup = grid();
        soup.positions.push(DVec3::new(0.5, 0.5, 1.0));
        soup.triangles.push([0, 4, 9]);
        soup.face_sources.push(0);
        assert!(matches!(rebuild(soup), Err(RebuildError::Defect(_))));
    }

    #[test]
    fn two_fans_at_a_vertex_are_refused() {
        // Two triangles touching only at vertex 0.
        let positions = vec![
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(-1.0, -1.0, 0.0),
        ];
        let soup = TriangleSoup::new(positions, vec![[0, 1, 2], [0, 3, 4]]);
        assert!(matches!(rebuild(soup), Err(RebuildError::Defect(_))));
    }

    #[test]
    fn separate_pieces_are_refused_as_disconnected() {
        let mut soup = grid();
        let shift = soup.positions.len() as u32;
        let copy: Vec<DVec3> = (soup.positions.iter())
            .map(|p| *p + DVec3::new(5.0, 0.0, 0.0))
            .collect();
        let copied: Vec<[u32; 3]> = (soup.triangles.iter())
            .map(|t| t.map(|v| v + shift))
            .collect();
        soup.positions.extend(copy);
        soup.triangles.extend(copied);
        soup.face_sources.resize(soup.triangles.len(), 0);
        assert_eq!(rebuild(soup), Err(RebuildError::Disconnected));
    }

    #[test]
    fn an_unused_vertex_and_a_zero_area_triangle_are_refused() {
        let mut soup = grid();
        soup.positions.push(DVec3::new(9.0, 9.0, 0.0));
        assert!(matches!(rebuild(soup), Err(RebuildError::Defect(_))));
        let mut soup = grid();
        soup.positions[4] = DVec3::new(0.5, 0.5, 0.0);
        soup.positions[0] = DVec3::new(0.0, 0.0, 0.0);
        soup.positions[1] = DVec3::new(0.25, 0.25, 0.0);
        assert!(matches!(rebuild(soup), Err(RebuildError::Defect(_))));
    }
}
