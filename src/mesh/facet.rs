//! The facet model: a validated, connected, manifold, consistently oriented triangle mesh with
//! edge adjacency and boundary loops, in f64 model units.
//!
//! Only [`crate::mesh::validate`] builds one from outside input, so every `FacetModel` satisfies:
//! every edge has one or two faces, every vertex has a single fan of faces, orientations agree
//! across shared edges, every vertex is referenced, coordinates are finite, no triangle has zero
//! area, and all faces form one connected component.
//!
//! Besides positions the model carries what later stages fill in: a source tag per face (which
//! CAD face it came from), a rest length per edge (the 3D length unless bend allowance changes
//! it) and the fold line each edge lies on, if any.

use std::f64::consts::TAU;

use glam::DVec3;

use super::rows::compressed_rows;

/// Sentinel for "no face" (the missing side of a boundary edge) and "no fold line".
pub const NONE: u32 = u32::MAX;

/// A validated triangle mesh with adjacency. See the module documentation for its invariants.
#[derive(Debug, Clone, PartialEq)]
pub struct FacetModel {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    face_sources: Vec<u32>,
    edges: Vec<[u32; 2]>,
    edge_faces: Vec<[u32; 2]>,
    face_edges: Vec<[u32; 3]>,
    edge_fold_lines: Vec<u32>,
    rest_lengths: Vec<f64>,
    boundary_loops: Vec<Vec<u32>>,
    vertex_face_offsets: Vec<u32>,
    vertex_faces: Vec<u32>,
}

impl FacetModel {
    /// Builds the adjacency of a mesh that is already known to be manifold, consistently oriented,
    /// connected and free of unreferenced vertices (the caller, `validate`, has checked it).
    /// `fold_edges` lists `(a, b, fold_line)` for edges on fold lines; pairs that are not edges of
    /// the mesh are ignored.
    pub(crate) fn from_checked(
        positions: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
        face_sources: Vec<u32>,
        fold_edges: &[(u32, u32, u32)],
    ) -> Self {
        let (edges, edge_faces, face_edges) = build_edges(positions.len(), &triangles);
        let mut edge_fold_lines = vec![NONE; edges.len()];
        for &(a, b, line) in fold_edges {
            let key = [a.min(b), a.max(b)];
            if let Ok(e) = edges.binary_search(&key) {
                edge_fold_lines[e] = line;
            }
        }
        let rest_lengths = edges
            .iter()
            .map(|&[a, b]| positions[a as usize].distance(positions[b as usize]))
            .collect();
        let (vertex_face_offsets, vertex_faces) = build_vertex_faces(positions.len(), &triangles);
        let boundary_loops = trace_boundary_loops(&triangles, &edge_faces, &face_edges, &edges);
        Self {
            positions,
            triangles,
            face_sources,
            edges,
            edge_faces,
            face_edges,
            edge_fold_lines,
            rest_lengths,
            boundary_loops,
            vertex_face_offsets,
            vertex_faces,
        }
    }

    /// Vertex positions in model units.
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }

    /// Triangles, counter-clockwise seen from the front.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Per-face tag of the CAD face each triangle came from.
    pub fn face_sources(&self) -> &[u32] {
        &self.face_sources
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Undirected edges as `[a, b]` with `a < b`, sorted.
    pub fn edges(&self) -> &[[u32; 2]] {
        &self.edges
    }

    /// The one or two faces of each edge; the second is [`NONE`] on the boundary.
    pub fn edge_faces(&self) -> &[[u32; 2]] {
        &self.edge_faces
    }

    /// For each face, its edges: entry `k` joins corner `k` to corner `k + 1`.
    pub fn face_edges(&self) -> &[[u32; 3]] {
        &self.face_edges
    }

    /// The fold line each edge lies on, or [`NONE`].
    pub fn edge_fold_lines(&self) -> &[u32] {
        &self.edge_fold_lines
    }

    /// Rest length of each edge: the length the flat pattern should give it (model units).
    pub fn rest_lengths(&self) -> &[f64] {
        &self.rest_lengths
    }

    /// Replaces the rest lengths (bend allowance, for instance). Panics if the length differs
    /// from the edge count, which is a programming error.
    pub fn set_rest_lengths(&mut self, rest_lengths: Vec<f64>) {
        assert_eq!(
            rest_lengths.len(),
            self.edges.len(),
            "one rest length per edge"
        );
        self.rest_lengths = rest_lengths;
    }

    /// Closed loops of boundary vertices, each in the order that keeps the surface on its left
    /// (the faces' orientation). Empty for a closed surface.
    pub fn boundary_loops(&self) -> &[Vec<u32>] {
        &self.boundary_loops
    }

    /// The corners of `face` starting at its corner `v`, in the face's orientation; `None` when
    /// `v` is not one of them.
    pub fn corners_from(&self, face: u32, v: u32) -> Option<[u32; 3]> {
        let corners = self.triangles[face as usize];
        let k = corners.iter().position(|&w| w == v)?;
        Some([corners[k], corners[(k + 1) % 3], corners[(k + 2) % 3]])
    }

    /// Sum of the 3D corner angles at vertex `v` of the triangles around it (radians).
    pub fn angle_sum(&self, v: u32) -> f64 {
        (self.vertex_faces(v).iter())
            .filter_map(|&face| self.corners_from(face, v))
            .map(|corners| {
                let [a, b, c] = corners.map(|w| self.positions[w as usize]);
                (b - a).angle_between(c - a)
            })
            .sum()
    }

    /// Sum of the 3D corner angles of the triangles around each vertex (radians).
    pub fn angle_sums(&self) -> Vec<f64> {
        (0..self.positions.len() as u32)
            .map(|v| self.angle_sum(v))
            .collect()
    }

    /// Angle deficit `2π − Σθ` of every interior vertex (its discrete Gaussian curvature; 0 on
    /// the boundary).
    pub fn angle_deficits(&self) -> Vec<f64> {
        let on_boundary = self.boundary_flags();
        (self.angle_sums().into_iter().enumerate())
            .map(|(v, sum)| if on_boundary[v] { 0.0 } else { TAU - sum })
            .collect()
    }

    /// Per vertex, true when it lies on a boundary loop.
    pub fn boundary_flags(&self) -> Vec<bool> {
        let mut flags = vec![false; self.positions.len()];
        for &v in self.boundary_loops.iter().flatten() {
            flags[v as usize] = true;
        }
        flags
    }

    /// The sides of the boundary loops, each `[from, to]` in its loop's order.
    pub fn boundary_sides(&self) -> impl Iterator<Item = [u32; 2]> + '_ {
        self.boundary_loops
            .iter()
            .flat_map(|ring| (0..ring.len()).map(move |i| [ring[i], ring[(i + 1) % ring.len()]]))
    }

    /// True when the surface has no boundary and must be cut open before it can be flattened.
    pub fn is_closed(&self) -> bool {
        self.boundary_loops.is_empty()
    }

    /// The faces around vertex `v`, in ascending order.
    pub fn vertex_faces(&self, v: u32) -> &[u32] {
        let start = self.vertex_face_offsets[v as usize] as usize;
        let end = self.vertex_face_offsets[v as usize + 1] as usize;
        &self.vertex_faces[start..end]
    }

    /// True if the edge has a single face.
    pub fn is_boundary_edge(&self, edge: usize) -> bool {
        self.edge_faces[edge][1] == NONE
    }

    /// Index of the edge joining `a` and `b`, if there is one.
    pub fn find_edge(&self, a: u32, b: u32) -> Option<usize> {
        self.edges.binary_search(&[a.min(b), a.max(b)]).ok()
    }

    /// Area of triangle `f` in 3D.
    pub fn triangle_area(&self, f: usize) -> f64 {
        let [a, b, c] = self.triangles[f].map(|v| self.positions[v as usize]);
        0.5 * (b - a).cross(c - a).length()
    }

    /// Total surface area.
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|f| self.triangle_area(f))
            .sum()
    }

    /// The diagonal of the axis-aligned bounding box: the part's size.
    pub fn bounding_diagonal(&self) -> f64 {
        let mut min = DVec3::splat(f64::INFINITY);
        let mut max = DVec3::splat(f64::NEG_INFINITY);
        for &p in &self.positions {
            min = min.min(p);
            max = max.max(p);
        }
        (max - min).length()
    }
}

/// The edge tables of a mesh: unique edges (sorted), the faces of each edge, the edges of each
/// face.
type EdgeTables = (Vec<[u32; 2]>, Vec<[u32; 2]>, Vec<[u32; 3]>);

/// Builds the [`EdgeTables`]: the half-edges grouped by their lower vertex (compressed rows,
/// linear), each group sorted by its higher vertex and then by half-edge (face, corner), which
/// orders them as one sort of every half-edge by (edge, face, corner) would.
fn build_edges(vertex_count: usize, triangles: &[[u32; 3]]) -> EdgeTables {
    let ends = |half_edge: u32| {
        let (face, corner) = ((half_edge / 3) as usize, (half_edge % 3) as usize);
        let t = triangles[face];
        let (a, b) = (t[corner], t[(corner + 1) % 3]);
        (a.min(b), a.max(b))
    };
    let half_edges = 0..3 * triangles.len() as u32;
    let (offsets, grouped) = compressed_rows(vertex_count, half_edges.map(|h| (ends(h).0, h)));
    // Each half-edge with its higher vertex, so the sort compares plain pairs.
    let mut keyed: Vec<(u32, u32)> = grouped.iter().map(|&h| (ends(h).1, h)).collect();
    let mut edges = Vec::with_capacity(grouped.len() / 2 + 1);
    let mut edge_faces: Vec<[u32; 2]> = Vec::with_capacity(grouped.len() / 2 + 1);
    let mut face_edges = vec![[NONE; 3]; triangles.len()];
    for (low, row) in offsets.windows(2).enumerate() {
        let group = &mut keyed[row[0] as usize..row[1] as usize];
        group.sort_unstable();
        for &(high, h) in group.iter() {
            let key = [low as u32, high];
            let face = h / 3;
            if edges.last() != Some(&key) {
                edges.push(key);
                edge_faces.push([face, NONE]);
            } else {
                edge_faces.last_mut().expect("edge pushed above")[1] = face;
            }
            face_edges[face as usize][(h % 3) as usize] = (edges.len() - 1) as u32;
        }
    }
    (edges, edge_faces, face_edges)
}

/// Vertex-to-face incidence in compressed rows.
fn build_vertex_faces(vertex_count: usize, triangles: &[[u32; 3]]) -> (Vec<u32>, Vec<u32>) {
    let entries = triangles
        .iter()
        .enumerate()
        .flat_map(|(f, t)| t.iter().map(move |&v| (v, f as u32)));
    compressed_rows(vertex_count, entries)
}

/// Boundary loops, each following the directed boundary half-edges (surface on the left).
fn trace_boundary_loops(
    triangles: &[[u32; 3]],
    edge_faces: &[[u32; 2]],
    face_edges: &[[u32; 3]],
    edges: &[[u32; 2]],
) -> Vec<Vec<u32>> {
    // Directed boundary half-edge a -> b for each boundary edge, keyed by its start vertex.
    let mut next: Vec<(u32, u32)> = Vec::new();
    for (e, faces) in edge_faces.iter().enumerate() {
        if faces[1] != NONE {
            continue;
        }
        let f = faces[0] as usize;
        let k = face_edges[f]
            .iter()
            .position(|&x| x as usize == e)
            .expect("face owns its edge");
        next.push((triangles[f][k], triangles[f][(k + 1) % 3]));
        debug_assert!(edges[e].contains(&triangles[f][k]));
    }
    next.sort_unstable();
    let mut used = vec![false; next.len()];
    let mut loops = Vec::new();
    for start in 0..next.len() {
        if used[start] {
            continue;
        }
        let mut current = start;
        let mut ring = Vec::new();
        loop {
            used[current] = true;
            ring.push(next[current].0);
            let to = next[current].1;
            // Manifold vertices have exactly one outgoing boundary half-edge.
            match next.binary_search_by(|probe| probe.0.cmp(&to)) {
                Ok(i) if !used[i] => current = i,
                _ => break,
            }
        }
        loops.push(ring);
    }
    loops
}
