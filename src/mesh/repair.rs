//! Repairs of real exports' connectivity (`--repair`), each reported as a warning that names
//! what it changed: vertices at the same point welded into one, and edges shared by more than
//! two triangles and vertices joining separate fans split apart, so that every edge has at most
//! two triangles and every vertex one fan. Positions never move.

use std::collections::BTreeMap;

use super::defects::Defect;
use crate::cad::TriangleSoup;

/// The soup with every vertex that lies exactly on an earlier one replaced by it in the
/// triangles (the duplicate is then used by no triangle and dropped by validation), and one
/// [`Defect::WeldedVertex`] per duplicate. Vertex numbers do not change.
pub fn weld_duplicates(soup: &TriangleSoup) -> (TriangleSoup, Vec<Defect>) {
    let mut first_at: BTreeMap<[u64; 3], u32> = BTreeMap::new();
    let mut representative: Vec<u32> = (0..soup.positions.len() as u32).collect();
    let mut warnings = Vec::new();
    for (v, p) in soup.positions.iter().enumerate() {
        // +0.0 for -0.0, so that the two zeros weld.
        let key = p.to_array().map(|c| (c + 0.0).to_bits());
        let first = *first_at.entry(key).or_insert(v as u32);
        if first != v as u32 && p.is_finite() {
            representative[v] = first;
            warnings.push(Defect::WeldedVertex {
                vertex: v,
                into: first as usize,
            });
        }
    }
    let mut welded = soup.clone();
    for triangle in &mut welded.triangles {
        *triangle = triangle.map(|v| representative.get(v as usize).copied().unwrap_or(v));
    }
    for edge in &mut welded.fold_edges {
        edge.vertices = edge
            .vertices
            .map(|v| representative.get(v as usize).copied().unwrap_or(v));
    }
    (welded, warnings)
}

/// The soup with its non-manifold edges and vertices split: triangles stop being neighbours
/// across an edge that more than two of them share, and each vertex gets one copy per fan of
/// triangles that meet there (neighbours across the vertex's other edges). Copies keep their
/// vertex's position and file line. Returns the warnings, one [`Defect::SplitEdge`] per edge
/// and one [`Defect::SplitVertex`] per vertex split.
pub fn split_non_manifold(soup: &TriangleSoup) -> (TriangleSoup, Vec<Defect>) {
    let faces_of_edge = edge_faces(&soup.triangles, soup.positions.len());
    let mut warnings: Vec<Defect> = faces_of_edge
        .iter()
        .filter(|(_, faces)| faces.len() > 2)
        .map(|(&(a, b), faces)| Defect::SplitEdge {
            vertices: [a, b],
            faces: faces.len(),
        })
        .collect();
    let fans = vertex_fans(soup, &faces_of_edge);
    let mut split = soup.clone();
    for (vertex, groups) in fans.iter().enumerate() {
        if groups.len() < 2 {
            continue;
        }
        warnings.push(Defect::SplitVertex {
            vertex,
            copies: groups.len(),
        });
        for group in &groups[1..] {
            let copy = split.positions.len() as u32;
            split.positions.push(soup.positions[vertex]);
            if let Some(line) = soup.source_lines.vertex(vertex) {
                split.source_lines.vertices.push(line);
            }
            for &face in group {
                for corner in &mut split.triangles[face as usize] {
                    if *corner == vertex as u32 {
                        *corner = copy;
                    }
                }
            }
        }
    }
    (split, warnings)
}

/// The triangles around each edge `(min, max)` of the soup (a triangle repeating a vertex or
/// naming one of the `vertex_count` vertices that does not exist is left out: validation drops
/// or refuses it).
fn edge_faces(triangles: &[[u32; 3]], vertex_count: usize) -> BTreeMap<(u32, u32), Vec<u32>> {
    let mut faces: BTreeMap<(u32, u32), Vec<u32>> = BTreeMap::new();
    for (f, t) in triangles.iter().enumerate() {
        let repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
        if repeated || t.iter().any(|&v| v as usize >= vertex_count) {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            faces
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push(f as u32);
        }
    }
    faces
}

/// Per vertex, its triangles grouped into fans: triangles joined through an edge of the vertex
/// that exactly two triangles share. Groups are ordered by their lowest triangle.
fn vertex_fans(
    soup: &TriangleSoup,
    faces_of_edge: &BTreeMap<(u32, u32), Vec<u32>>,
) -> Vec<Vec<Vec<u32>>> {
    let mut around: Vec<Vec<u32>> = vec![Vec::new(); soup.positions.len()];
    for faces in faces_of_edge.values() {
        for &f in faces {
            for v in soup.triangles[f as usize] {
                let list = &mut around[v as usize];
                if list.last() != Some(&f) && !list.contains(&f) {
                    list.push(f);
                }
            }
        }
    }
    around
        .iter()
        .enumerate()
        .map(|(v, faces)| fans_at(v as u32, faces, soup, faces_of_edge))
        .collect()
}

/// The fans of the triangles `faces` around vertex `v` (union-find over the manifold edges of
/// `v`).
fn fans_at(
    v: u32,
    faces: &[u32],
    soup: &TriangleSoup,
    faces_of_edge: &BTreeMap<(u32, u32), Vec<u32>>,
) -> Vec<Vec<u32>> {
    let mut sorted = faces.to_vec();
    sorted.sort_unstable();
    let mut parent: Vec<usize> = (0..sorted.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (i, &f) in sorted.iter().enumerate() {
        for w in soup.triangles[f as usize] {
            if w == v {
                continue;
            }
            let Some(pair) = faces_of_edge.get(&(v.min(w), v.max(w))) else {
                continue;
            };
            if let [a, b] = pair[..] {
                let other = if a == f { b } else { a };
                if let Ok(j) = sorted.binary_search(&other) {
                    let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                    parent[ri.max(rj)] = ri.min(rj);
                }
            }
        }
    }
    let mut groups: BTreeMap<usize, Vec<u32>> = BTreeMap::new();
    for (i, &f) in sorted.iter().enumerate() {
        let r = root(&mut parent, i);
        groups.entry(r).or_default().push(f);
    }
    groups.into_values().collect()
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::mesh::validate;

    /// Three triangles on one edge (0-1), like three panels sewn along one seam.
    fn three_panels() -> TriangleSoup {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, 1.0, 0.0),
            DVec3::new(0.5, -1.0, 0.0),
            DVec3::new(0.5, 0.0, 1.0),
        ];
        TriangleSoup::new(positions, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    }

    #[test]
    fn a_non_manifold_edge_is_split_and_the_mesh_then_validates() {
        let soup = three_panels();
        assert!(validate(&soup).is_err());
        let (split, warnings) = split_non_manifold(&soup);
        assert_eq!(
            warnings[0],
            Defect::SplitEdge {
                vertices: [0, 1],
                faces: 3
            }
        );
        assert!(warnings.iter().all(Defect::is_repaired));
        let validated = validate(&split).expect("valid after the split");
        assert_eq!(validated.components.len(), 3, "three separate panels");
        for (v, p) in split
            .positions
            .iter()
            .enumerate()
            .skip(soup.positions.len())
        {
            assert!(soup.positions[..2].contains(p), "copy {v} of an edge end");
        }
    }

    #[test]
    fn a_bow_tie_vertex_gets_one_copy_per_fan() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(-1.0, -1.0, 0.0),
        ];
        let soup = TriangleSoup::new(positions, vec![[0, 1, 2], [0, 3, 4]]);
        let (split, warnings) = split_non_manifold(&soup);
        assert_eq!(
            warnings,
            vec![Defect::SplitVertex {
                vertex: 0,
                copies: 2
            }]
        );
        assert_eq!(split.triangles, vec![[0, 1, 2], [5, 3, 4]]);
        assert_eq!(validate(&split).expect("valid").components.len(), 2);
    }

    #[test]
    fn a_triangle_naming_a_missing_vertex_is_left_for_validation_to_refuse() {
        let mut soup = three_panels();
        soup.triangles.push([0, 1, 99]);
        let (split, _) = split_non_manifold(&soup);
        assert_eq!(split.triangles[3], [0, 1, 99], "left as it was");
        assert!(
            validate(&split).is_err(),
            "the missing vertex is still refused"
        );
    }

    #[test]
    fn duplicates_are_welded_into_the_first_vertex_at_their_point() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, -0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let soup = TriangleSoup::new(positions, vec![[0, 1, 2], [3, 4, 5]]);
        let (welded, warnings) = weld_duplicates(&soup);
        assert_eq!(welded.triangles, vec![[0, 1, 2], [1, 4, 2]]);
        assert_eq!(
            warnings,
            vec![
                Defect::WeldedVertex { vertex: 3, into: 1 },
                Defect::WeldedVertex { vertex: 5, into: 2 }
            ]
        );
        assert_eq!(validate(&welded).expect("valid").components.len(), 1);
    }
}
