//! Welding the faces of a part into one surface.
//!
//! Input: per-face meshes whose shared edges were sampled at the same points (part units) and a
//! weld tolerance. Output: one [`TriangleSoup`] in which vertices of *different* faces closer
//! than the tolerance are one vertex, every vertex referenced, with per-triangle face sources
//! (the face index) and the faces' fold edges renumbered. Vertices of the same face are never
//! merged, so a seam that a face keeps open (a full turn) stays open. Deterministic: vertices are
//! visited in a sorted order and merged into the lowest index.

use glam::DVec2;

use super::face_mesh::FaceMesh;
use crate::cad::{FoldEdge, SourceLines, TriangleSoup};
use crate::geometry::weld::merge_close_points;

/// A welded soup and, per soup vertex, the faces it came from with its parameter-domain
/// position on each.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Welded {
    /// The soup.
    pub soup: TriangleSoup,
    /// `(soup vertex, face, parameters on that face)` for every face vertex welded into a soup
    /// vertex (a vertex on an edge two faces share has two), sorted by vertex then face.
    pub vertex_sources: Vec<(u32, u32, DVec2)>,
}

impl Welded {
    /// The parameter-domain coordinates of soup vertex `vertex` on face `face`, if that face
    /// produced it (patches carry real parameters; structured meshes zero).
    pub fn parameters_on(&self, vertex: usize, face: u32) -> Option<DVec2> {
        let key = (vertex as u32, face);
        let index = self
            .vertex_sources
            .partition_point(|&(v, f, _)| (v, f) < key);
        self.vertex_sources
            .get(index)
            .filter(|&&(v, f, _)| (v, f) == key)
            .map(|&(_, _, parameters)| parameters)
    }
}

/// Welds `faces` (see the module documentation); `weld` says, per face, whether it may be welded
/// to other faces at all.
pub fn weld_faces(faces: &[FaceMesh], weld: bool, tolerance: f64) -> Welded {
    let mut positions = Vec::new();
    let mut owners = Vec::new();
    let mut parameters = Vec::new();
    let mut offsets = Vec::with_capacity(faces.len());
    for (index, face) in faces.iter().enumerate() {
        offsets.push(positions.len() as u32);
        positions.extend_from_slice(&face.positions);
        parameters.extend_from_slice(&face.parameters);
        owners.extend(std::iter::repeat_n(index as u32, face.positions.len()));
    }
    let representative = if weld {
        merge_close_points(&positions, &owners, tolerance)
    } else {
        (0..positions.len() as u32).collect()
    };
    let mut triangles = Vec::new();
    let mut face_sources = Vec::new();
    let mut fold_edges = Vec::new();
    for (index, face) in faces.iter().enumerate() {
        let map = |v: u32| representative[(offsets[index] + v) as usize];
        for t in &face.triangles {
            triangles.push(t.map(map));
            face_sources.push(index as u32);
        }
        for &(vertices, fold_line) in &face.fold_edges {
            fold_edges.push(FoldEdge {
                vertices: vertices.map(map),
                fold_line,
            });
        }
    }
    compact(
        TriangleSoup {
            positions,
            triangles,
            face_sources,
            fold_edges,
            source_lines: SourceLines::default(),
            texture: None,
        },
        &representative,
        &owners,
        &parameters,
    )
}

/// `(soup vertex, face, parameters)` of every input vertex that reached the soup, sorted, one per
/// soup vertex and face (the first of a face's vertices welded into one).
fn vertex_sources(
    representative: &[u32],
    new_index: &[u32],
    owners: &[u32],
    parameters: &[DVec2],
) -> Vec<(u32, u32, DVec2)> {
    let mut sources: Vec<(u32, u32, DVec2)> = (0..representative.len())
        .filter_map(|v| {
            let kept = new_index[representative[v] as usize];
            (kept != u32::MAX).then_some((kept, owners[v], parameters[v]))
        })
        .collect();
    sources.sort_by_key(|&(vertex, face, _)| (vertex, face));
    sources.dedup_by_key(|&mut (vertex, face, _)| (vertex, face));
    sources
}

/// Drops unreferenced vertices, renumbering in ascending order; `representative` maps each input
/// vertex to the vertex it was welded into.
fn compact(
    soup: TriangleSoup,
    representative: &[u32],
    owners: &[u32],
    parameters: &[DVec2],
) -> Welded {
    let mut new_index = vec![u32::MAX; soup.positions.len()];
    for t in &soup.triangles {
        for &v in t {
            new_index[v as usize] = 0;
        }
    }
    let mut kept = Vec::new();
    for (v, slot) in new_index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = kept.len() as u32;
            kept.push(v);
        }
    }
    let remap = |v: u32| new_index[v as usize];
    let fold_edges = soup
        .fold_edges
        .iter()
        .filter(|e| {
            e.vertices
                .iter()
                .all(|&v| new_index[v as usize] != u32::MAX)
        })
        .map(|e| FoldEdge {
            vertices: e.vertices.map(remap),
            fold_line: e.fold_line,
        })
        .collect();
    Welded {
        soup: TriangleSoup {
            positions: kept.iter().map(|&v| soup.positions[v]).collect(),
            triangles: soup.triangles.iter().map(|t| t.map(remap)).collect(),
            face_sources: soup.face_sources,
            fold_edges,
            source_lines: SourceLines::default(),
            texture: None,
        },
        vertex_sources: vertex_sources(representative, &new_index, owners, parameters),
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::tessellate::weld::*;

    fn square(x: f64) -> FaceMesh {
        let mut face = FaceMesh::default();
        for p in [[x, 0.0], [x + 1.0, 0.0], [x + 1.0, 1.0], [x, 1.0]] {
            face.add_vertex(DVec3::new(p[0], p[1], 0.0));
        }
        face.triangles = vec![[0, 1, 2], [0, 2, 3]];
        face
    }

    #[test]
    fn two_faces_sharing_an_edge_share_its_vertices() {
        let welded = weld_faces(&[square(0.0), square(1.0)], true, 1e-9);
        assert_eq!(welded.soup.positions.len(), 6);
        assert_eq!(welded.soup.face_sources, vec![0, 0, 1, 1]);
        let shared = (0..6)
            .filter(|&v| {
                welded.parameters_on(v, 0).is_some() && welded.parameters_on(v, 1).is_some()
            })
            .count();
        assert_eq!(
            shared, 2,
            "the shared edge's two vertices come from both faces"
        );
    }

    #[test]
    fn a_face_is_never_welded_to_itself() {
        let mut face = square(0.0);
        face.add_vertex(DVec3::ZERO);
        face.triangles.push([4, 1, 2]);
        let welded = weld_faces(&[face], true, 1e-9);
        assert_eq!(welded.soup.positions.len(), 5);
    }
}
