//! Repairs of real exports' degenerate triangles (`--repair`), each reported as a warning that
//! names what it changed: a triangle that repeats another one's three vertices is dropped, and a
//! triangle of zero area ([`has_zero_area`]) is mended by the cheapest change that removes it:
//! where its third vertex lies on its longest edge (a cap, which fills the gap between that edge
//! on one side and the two shorter edges on the other), that edge is flipped with the
//! neighbouring triangle across it; where the edge is on the boundary, the triangle is dropped
//! (the boundary then runs along the two shorter edges, which it already did in all but name);
//! where the flip would leave a triangle of zero area too (a needle: two of its vertices nearly
//! at one point), its shortest edge is collapsed into its lower-numbered end, the only repair
//! that moves a vertex, by that edge's length. Anything else is left for validation to refuse.

use std::collections::BTreeMap;

use glam::DVec3;

use super::defects::Defect;
use super::validate::{is_usable, repeated_triangles};
use crate::cad::TriangleSoup;
use crate::geometry::tolerance::has_zero_area;

/// The soup with its duplicate and zero-area triangles repaired (see the module documentation),
/// and one warning per repair. Triangles that repeat a vertex or name a missing one are left for
/// validation; a collapsed edge's triangles then repeat a vertex and validation drops them.
pub fn repair_degenerate_triangles(soup: &TriangleSoup) -> (TriangleSoup, Vec<Defect>) {
    let mended = soup.clone();
    let mut warnings = Vec::new();
    let usable = |t: [u32; 3]| is_usable(t, soup.positions.len());
    let mut dropped = vec![false; soup.triangles.len()];
    let kept: Vec<usize> = (0..soup.triangles.len())
        .filter(|&t| usable(soup.triangles[t]))
        .collect();
    for (triangle, first) in repeated_triangles(soup, &kept) {
        dropped[triangle] = true;
        warnings.push(Defect::DuplicateTriangle {
            triangle,
            of: first,
        });
    }
    let edges = EdgeFaces::new(&mended.triangles, &dropped, usable);
    let mut mending = Mending {
        soup: mended,
        dropped,
        edges,
        collapse_into: BTreeMap::new(),
        warnings,
    };
    for triangle in 0..mending.soup.triangles.len() {
        let corners = mending.soup.triangles[triangle];
        if usable(corners) {
            mending.mend(triangle, corners);
        }
    }
    let Mending {
        soup: mut mended,
        dropped,
        collapse_into,
        warnings,
        ..
    } = mending;
    collapse(&mut mended, &collapse_into);
    drop_triangles(&mut mended, &dropped);
    (mended, warnings)
}

/// The soup being mended, with what is known of it so far.
struct Mending {
    soup: TriangleSoup,
    /// Per triangle, true once it is to be dropped.
    dropped: Vec<bool>,
    edges: EdgeFaces,
    /// Vertices to be replaced by others once every triangle is mended.
    collapse_into: BTreeMap<u32, u32>,
    warnings: Vec<Defect>,
}

impl Mending {
    /// Mends `triangle` (of three distinct vertices, `corners`) when it has zero area: its
    /// longest edge flipped, the triangle dropped on the boundary, or its shortest edge marked to
    /// collapse.
    fn mend(&mut self, triangle: usize, corners: [u32; 3]) {
        if self.dropped[triangle] || !has_zero_area(points(&self.soup, corners)) {
            return;
        }
        let [a, b, _] = longest_edge_first(&self.soup, corners);
        match self.edges.across(triangle, [a, b]) {
            Across::Boundary => {
                self.dropped[triangle] = true;
                self.edges.remove(triangle, corners);
                self.warnings.push(Defect::DroppedSliver { triangle });
            }
            Across::One(neighbour)
                if flip(&mut self.soup, &mut self.edges, triangle, neighbour) =>
            {
                self.warnings.push(Defect::FlippedEdge {
                    triangle,
                    vertices: [a, b],
                });
            }
            _ => {
                let [u, v] = shortest_edge(&self.soup, corners);
                let [u_end, v_end] = [u, v].map(|w| collapsed(&self.collapse_into, w));
                if u_end != v_end {
                    self.collapse_into
                        .insert(u_end.max(v_end), u_end.min(v_end));
                }
                self.warnings.push(Defect::CollapsedEdge {
                    triangle,
                    vertices: [u, v],
                });
            }
        }
    }
}

/// The corners' positions.
fn points(soup: &TriangleSoup, corners: [u32; 3]) -> [DVec3; 3] {
    corners.map(|v| soup.positions[v as usize])
}

/// The triangle's corners turned so that its longest edge runs from the first to the second.
fn longest_edge_first(soup: &TriangleSoup, corners: [u32; 3]) -> [u32; 3] {
    let p = points(soup, corners);
    let length = |k: usize| p[k].distance_squared(p[(k + 1) % 3]);
    let k = (0..3)
        .max_by(|&i, &j| length(i).total_cmp(&length(j)))
        .unwrap_or(0);
    [corners[k], corners[(k + 1) % 3], corners[(k + 2) % 3]]
}

/// The triangle's shortest edge.
fn shortest_edge(soup: &TriangleSoup, corners: [u32; 3]) -> [u32; 2] {
    let p = points(soup, corners);
    let length = |k: usize| p[k].distance_squared(p[(k + 1) % 3]);
    let k = (0..3)
        .min_by(|&i, &j| length(i).total_cmp(&length(j)))
        .unwrap_or(0);
    [corners[k], corners[(k + 1) % 3]]
}

/// Flips the edge that `triangle` (its longest edge first, `a → b`, then `m`) shares with
/// `neighbour` (`b → a`, then `c`): the two become `a, c, m` and `c, b, m`, each corner keeping
/// its texture point. False, and nothing changed, when the neighbour does not run the other way
/// along the edge or either new triangle would have zero area too.
fn flip(soup: &mut TriangleSoup, edges: &mut EdgeFaces, triangle: usize, neighbour: usize) -> bool {
    let [a, b, m] = longest_edge_first(soup, soup.triangles[triangle]);
    let theirs = soup.triangles[neighbour];
    let Some(k) = (0..3).find(|&k| theirs[k] == b && theirs[(k + 1) % 3] == a) else {
        return false;
    };
    let c = theirs[(k + 2) % 3];
    let new = [[a, c, m], [c, b, m]];
    if c == m || new.iter().any(|&t| has_zero_area(points(soup, t))) {
        return false;
    }
    if let Some(texture) = &mut soup.texture {
        let point_of = |t: usize, v: u32| {
            let k = soup.triangles[t].iter().position(|&w| w == v);
            k.map(|k| texture.corners[t][k])
        };
        let corners = new.map(|t| {
            t.map(|v| {
                point_of(neighbour, v)
                    .or_else(|| point_of(triangle, v))
                    .unwrap_or_default()
            })
        });
        texture.corners[triangle] = corners[0];
        texture.corners[neighbour] = corners[1];
    }
    edges.remove(triangle, soup.triangles[triangle]);
    edges.remove(neighbour, theirs);
    soup.triangles[triangle] = new[0];
    soup.triangles[neighbour] = new[1];
    edges.add(triangle, new[0]);
    edges.add(neighbour, new[1]);
    true
}

/// The vertex `v` is collapsed into: `into`'s value for it, followed to the end (each maps a
/// vertex to a lower-numbered one, so the chain ends).
fn collapsed(into: &BTreeMap<u32, u32>, mut v: u32) -> u32 {
    while let Some(&next) = into.get(&v) {
        v = next;
    }
    v
}

/// Every vertex of `into`'s keys replaced by the vertex it is collapsed into ([`collapsed`]) in
/// the triangles and fold edges.
fn collapse(soup: &mut TriangleSoup, into: &BTreeMap<u32, u32>) {
    for triangle in &mut soup.triangles {
        *triangle = triangle.map(|v| collapsed(into, v));
    }
    for edge in &mut soup.fold_edges {
        edge.vertices = edge.vertices.map(|v| collapsed(into, v));
    }
    soup.fold_edges
        .retain(|edge| edge.vertices[0] != edge.vertices[1]);
}

/// The soup without its `dropped` triangles (and their sources, texture corners and lines).
fn drop_triangles(soup: &mut TriangleSoup, dropped: &[bool]) {
    retain_kept(&mut soup.triangles, dropped);
    retain_kept(&mut soup.face_sources, dropped);
    retain_kept(&mut soup.source_lines.triangles, dropped);
    if let Some(texture) = &mut soup.texture {
        retain_kept(&mut texture.corners, dropped);
    }
}

/// The items (one per triangle) of the triangles not `dropped`.
fn retain_kept<T>(items: &mut Vec<T>, dropped: &[bool]) {
    let mut index = 0;
    items.retain(|_| {
        index += 1;
        !dropped.get(index - 1).copied().unwrap_or(false)
    });
}

/// The triangles on each edge (its ends in increasing order), kept up to date as triangles are
/// dropped and flipped.
struct EdgeFaces {
    faces: BTreeMap<[u32; 2], Vec<usize>>,
}

/// What lies across an edge from a triangle.
enum Across {
    /// Nothing: the edge is on the boundary.
    Boundary,
    /// One triangle.
    One(usize),
    /// More than one: a non-manifold edge.
    Several,
}

impl EdgeFaces {
    /// The edges of the triangles that are not dropped and are `usable`.
    fn new(triangles: &[[u32; 3]], dropped: &[bool], usable: impl Fn([u32; 3]) -> bool) -> Self {
        let mut edges = Self {
            faces: BTreeMap::new(),
        };
        for (triangle, &corners) in triangles.iter().enumerate() {
            if !dropped[triangle] && usable(corners) {
                edges.add(triangle, corners);
            }
        }
        edges
    }

    /// The key of the edge from `a` to `b`.
    fn key([a, b]: [u32; 2]) -> [u32; 2] {
        [a.min(b), a.max(b)]
    }

    /// Registers `triangle`'s edges.
    fn add(&mut self, triangle: usize, corners: [u32; 3]) {
        for k in 0..3 {
            let key = Self::key([corners[k], corners[(k + 1) % 3]]);
            self.faces.entry(key).or_default().push(triangle);
        }
    }

    /// Forgets `triangle`'s edges.
    fn remove(&mut self, triangle: usize, corners: [u32; 3]) {
        for k in 0..3 {
            let key = Self::key([corners[k], corners[(k + 1) % 3]]);
            if let Some(faces) = self.faces.get_mut(&key) {
                faces.retain(|&f| f != triangle);
            }
        }
    }

    /// What lies across `edge` from `triangle`.
    fn across(&self, triangle: usize, edge: [u32; 2]) -> Across {
        let others: Vec<usize> = (self.faces.get(&Self::key(edge)).into_iter())
            .flatten()
            .copied()
            .filter(|&f| f != triangle)
            .collect();
        match others[..] {
            [] => Across::Boundary,
            [one] => Across::One(one),
            _ => Across::Several,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::validate;

    /// The soup of these triangles.
    fn soup(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> TriangleSoup {
        TriangleSoup::new(positions, triangles)
    }

    /// The strip ([`strip`]) with vertex 6 at `extra` on the left square's right edge 1-4,
    /// belonging to the left square only: triangles `0 1 6`, `0 6 4`, `0 4 3`, then the zero-area
    /// triangle `1 4 6` (triangle 3) filling the gap to the right square (`1 2 5`, `1 5 4`).
    fn strip_with_a_sliver_at(extra: DVec3) -> TriangleSoup {
        let mut positions = strip();
        positions.push(extra);
        let triangles = vec![
            [0, 1, 6],
            [0, 6, 4],
            [0, 4, 3],
            [1, 4, 6],
            [1, 2, 5],
            [1, 5, 4],
        ];
        soup(positions, triangles)
    }

    /// The corners of a 2 x 1 strip of two unit squares, bottom row first.
    fn strip() -> Vec<DVec3> {
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
        ]
    }

    #[test]
    fn a_cap_between_two_triangles_is_flipped_away() {
        // Vertex 6 in the middle of edge 1-4: the cap 1-4-6 is flipped with the right square's
        // triangle across 1-4.
        let input = strip_with_a_sliver_at(DVec3::new(1.0, 0.5, 0.0));
        assert!(validate(&input).is_err(), "the cap has zero area");
        let (mended, warnings) = repair_degenerate_triangles(&input);
        assert_eq!(
            warnings,
            [Defect::FlippedEdge {
                triangle: 3,
                vertices: [1, 4]
            }]
        );
        let model = validate(&mended).expect("valid").components.remove(0);
        assert_eq!(model.triangle_count(), 6);
        assert!((model.area() - 2.0).abs() < 1e-12);
        assert_eq!(model.boundary_loops().len(), 1);
    }

    #[test]
    fn a_cap_on_the_boundary_is_dropped_and_a_duplicate_triangle_too() {
        let mut positions = strip();
        positions.push(DVec3::new(0.5, 0.0, 0.0));
        // Vertex 6 at the middle of the bottom edge 0-1, used by the left square's lower half.
        let triangles = vec![
            [0, 6, 4],
            [6, 1, 4],
            [0, 4, 3],
            [0, 1, 6],
            [1, 2, 5],
            [1, 5, 4],
            [1, 5, 4],
        ];
        let (mended, warnings) = repair_degenerate_triangles(&soup(positions, triangles));
        assert_eq!(
            warnings,
            [
                Defect::DuplicateTriangle { triangle: 6, of: 5 },
                Defect::DroppedSliver { triangle: 3 }
            ]
        );
        let model = validate(&mended).expect("valid").components.remove(0);
        assert_eq!(model.triangle_count(), 5);
        assert!((model.area() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_needle_has_its_shortest_edge_collapsed() {
        // Vertex 6 a hair below vertex 4: the cap 1-4-6 and the sliver 0-6-4 would stay
        // degenerate if flipped, so their short edge 4-6 is collapsed into vertex 4.
        let input = strip_with_a_sliver_at(DVec3::new(1.0, 1.0 - 1e-13, 0.0));
        let (mended, warnings) = repair_degenerate_triangles(&input);
        assert_eq!(warnings.len(), 2, "{warnings:?}");
        for (warning, at) in warnings.iter().zip([1, 3]) {
            let Defect::CollapsedEdge {
                triangle,
                vertices: [u, v],
            } = *warning
            else {
                panic!("{warning:?}");
            };
            assert_eq!((triangle, u.min(v), u.max(v)), (at, 4, 6));
        }
        let validated = validate(&mended).expect("valid");
        let model = &validated.components[0];
        assert_eq!(model.triangle_count(), 4, "the two slivers are gone");
        assert!((model.area() - 2.0).abs() < 1e-12);
    }
}
