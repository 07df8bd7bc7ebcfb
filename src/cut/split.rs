//! Cutting a facet model open along a set of its edges (the mesh operation behind crest-line cuts,
//! §6.3, and seams).
//!
//! Input: a [`FacetModel`] and the interior edges to cut (not boundary edges, not fold-line
//! edges). Output: a new facet model whose cut edges appear twice, once on each side, and a map
//! from every new vertex and edge to the original one.
//!
//! Method: around each vertex touched by the cut, its faces are grouped into wedges, two faces
//! being in one wedge when they share an edge at the vertex that is not cut. The wedge holding the
//! vertex's lowest face keeps the vertex; every other wedge gets a copy at the same 3D position
//! (new indices appended in vertex order, so the result is deterministic). A path from the
//! boundary into the interior thus duplicates every path vertex but its inner tip; a closed path
//! or a tree cuts a closed surface open. The result is rebuilt through [`TriangleSoup`] and
//! [`rebuild_split`], which checks that it is still connected (every other facet model invariant
//! holds by construction); rest lengths, face sources and fold lines
//! are carried over, so `E_S` and `E_C` of the cut model measure the same surface.
//!
//! A cut that would separate the part into pieces is refused ([`CutError::Disconnects`]), and so
//! is one that duplicates no vertex ([`CutError::OpensNothing`]: a single interior edge, whose two
//! sides cannot be told apart in an indexed mesh).

use crate::mesh::{
    FacetModel, FoldEdge, NONE, RebuildError, SourceLines, TriangleSoup, rebuild_split,
};

use super::errors::CutError;

/// A model after a cut, with the way back to the model before it.
#[derive(Debug, Clone, PartialEq)]
pub struct SplitModel {
    /// The cut model.
    pub model: FacetModel,
    /// For each vertex of the cut model, the vertex of the original it copies.
    pub original_vertex: Vec<u32>,
    /// For each edge of the cut model, the edge of the original it comes from.
    pub original_edge: Vec<usize>,
}

/// Cuts `model` open along `cut_edges` (edge indices); see the module documentation.
pub fn split_along_edges(model: &FacetModel, cut_edges: &[usize]) -> Result<SplitModel, CutError> {
    let is_cut = cut_mask(model, cut_edges)?;
    let mut original_vertex: Vec<u32> = (0..model.vertex_count() as u32).collect();
    let mut triangles = model.triangles().to_vec();
    let mut touched: Vec<u32> = cut_edges.iter().flat_map(|&e| model.edges()[e]).collect();
    touched.sort_unstable();
    touched.dedup();
    for &vertex in &touched {
        let wedges = vertex_wedges(model, vertex, &is_cut);
        for wedge in wedges.iter().skip(1) {
            let copy = original_vertex.len() as u32;
            original_vertex.push(vertex);
            for &face in wedge {
                for corner in &mut triangles[face as usize] {
                    if *corner == vertex {
                        *corner = copy;
                    }
                }
            }
        }
    }
    if original_vertex.len() == model.vertex_count() {
        return Err(CutError::OpensNothing);
    }
    let positions = original_vertex
        .iter()
        .map(|&v| model.positions()[v as usize])
        .collect();
    let soup = TriangleSoup {
        positions,
        triangles,
        face_sources: model.face_sources().to_vec(),
        fold_edges: copied_fold_edges(model, &original_vertex),
        source_lines: SourceLines::default(),
        texture: None,
    };
    let mut cut_model = rebuild_split(soup).map_err(|error| match error {
        RebuildError::Disconnected => CutError::Disconnects,
        RebuildError::Defect(what) => CutError::InvalidResult(what),
    })?;
    let original_edge = original_edges(model, &cut_model, &original_vertex)?;
    let rest_lengths = original_edge
        .iter()
        .map(|&e| model.rest_lengths()[e])
        .collect();
    cut_model.set_rest_lengths(rest_lengths);
    Ok(SplitModel {
        model: cut_model,
        original_vertex,
        original_edge,
    })
}

/// A per-edge flag of the edges to cut, after checking each one may be cut.
fn cut_mask(model: &FacetModel, cut_edges: &[usize]) -> Result<Vec<bool>, CutError> {
    let mut is_cut = vec![false; model.edges().len()];
    for &edge in cut_edges {
        let Some(&[a, b]) = model.edges().get(edge) else {
            return Err(CutError::InvalidResult(format!(
                "edge {edge} does not exist"
            )));
        };
        if model.is_boundary_edge(edge) {
            return Err(CutError::BoundaryEdge { vertices: [a, b] });
        }
        if model.edge_fold_lines()[edge] != NONE {
            return Err(CutError::FoldLine { vertices: [a, b] });
        }
        is_cut[edge] = true;
    }
    Ok(is_cut)
}

/// The faces around `vertex` grouped into wedges separated by cut edges, each wedge sorted, the
/// wedges ordered by their lowest face.
fn vertex_wedges(model: &FacetModel, vertex: u32, is_cut: &[bool]) -> Vec<Vec<u32>> {
    let faces = model.vertex_faces(vertex);
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    for (i, &face) in faces.iter().enumerate() {
        for &edge in &model.face_edges()[face as usize] {
            let edge = edge as usize;
            if is_cut[edge] || !model.edges()[edge].contains(&vertex) {
                continue;
            }
            let [first, second] = model.edge_faces()[edge];
            let other = if first == face { second } else { first };
            if other == NONE {
                continue;
            }
            if let Ok(j) = faces.binary_search(&other) {
                let (root_i, root_j) = (find_root(&mut parent, i), find_root(&mut parent, j));
                parent[root_i.max(root_j)] = root_i.min(root_j);
            }
        }
    }
    let mut wedges: Vec<Vec<u32>> = Vec::new();
    let mut wedge_of_root = vec![usize::MAX; faces.len()];
    for (i, &face) in faces.iter().enumerate() {
        let root = find_root(&mut parent, i);
        if wedge_of_root[root] == usize::MAX {
            wedge_of_root[root] = wedges.len();
            wedges.push(Vec::new());
        }
        wedges[wedge_of_root[root]].push(face);
    }
    wedges
}

/// Union-find root with path halving.
fn find_root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Fold edges of the original, repeated for every pair of copies of their ends (pairs that are
/// not edges of the cut model are ignored when it is built).
fn copied_fold_edges(model: &FacetModel, original_vertex: &[u32]) -> Vec<FoldEdge> {
    let mut copies: Vec<Vec<u32>> = vec![Vec::new(); model.vertex_count()];
    for (new, &old) in original_vertex.iter().enumerate() {
        copies[old as usize].push(new as u32);
    }
    let mut fold_edges = Vec::new();
    for (&[a, b], &fold_line) in model.edges().iter().zip(model.edge_fold_lines()) {
        if fold_line == NONE {
            continue;
        }
        for &x in &copies[a as usize] {
            for &y in &copies[b as usize] {
                fold_edges.push(FoldEdge {
                    vertices: [x, y],
                    fold_line,
                });
            }
        }
    }
    fold_edges
}

/// For each edge of the cut model, the original edge between the vertices it copies.
fn original_edges(
    model: &FacetModel,
    cut_model: &FacetModel,
    original_vertex: &[u32],
) -> Result<Vec<usize>, CutError> {
    cut_model
        .edges()
        .iter()
        .map(|&[a, b]| {
            model
                .find_edge(original_vertex[a as usize], original_vertex[b as usize])
                .ok_or_else(|| {
                    CutError::InvalidResult(format!("edge {a}-{b} has no original edge"))
                })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::cut::paths::path_edges;
    use crate::cut::paths::tests::grid;
    use crate::cut::split::*;

    #[test]
    fn a_dart_from_the_boundary_duplicates_all_but_its_tip() {
        let model = grid();
        // From boundary vertex 1 up to the interior vertices 5 and 9 (9 is the tip).
        let edges = path_edges(&model, &[1, 5, 9]).expect("path on the grid");
        let split = split_along_edges(&model, &edges).expect("cut");
        assert_eq!(split.model.vertex_count(), model.vertex_count() + 2);
        assert_eq!(split.model.boundary_loops().len(), 1);
        assert_eq!(split.original_vertex[16..], [1, 5]);
        assert_eq!(split.model.edges().len(), model.edges().len() + 2);
    }

    #[test]
    fn rest_lengths_are_the_original_ones() {
        let model = grid();
        let edges = path_edges(&model, &[2, 6, 5]).expect("path on the grid");
        let split = split_along_edges(&model, &edges).expect("cut");
        for (e, &rest) in split.model.rest_lengths().iter().enumerate() {
            let expected = model.rest_lengths()[split.original_edge[e]];
            assert!((rest - expected).abs() < 1e-12);
        }
        let total: f64 = split.model.triangles().len() as f64;
        assert!((total - model.triangle_count() as f64).abs() < 0.5);
        assert!((split.model.area() - model.area()).abs() < 1e-9);
    }

    #[test]
    fn a_cut_across_the_part_is_refused() {
        let model = grid();
        let edges = path_edges(&model, &[1, 5, 9, 13]).expect("path on the grid");
        assert_eq!(
            split_along_edges(&model, &edges),
            Err(CutError::Disconnects)
        );
    }

    #[test]
    fn boundary_edges_cannot_be_cut() {
        let model = grid();
        let edge = model.find_edge(0, 1).expect("edge");
        assert!(matches!(
            split_along_edges(&model, &[edge]),
            Err(CutError::BoundaryEdge { .. })
        ));
    }
}
