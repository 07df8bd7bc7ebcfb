//! Validation: turns a raw [`TriangleSoup`] into one [`FacetModel`] per connected component, or
//! reports every defect at once, each naming the element (vertex or triangle index, 0-based).
//!
//! Repairs that cannot change the geometry are made with a warning: triangles that repeat a
//! vertex index (zero area, no neighbours to lose) are dropped, unreferenced vertices are dropped,
//! and an orientable surface whose faces disagree in orientation is reoriented to agree with its
//! lowest-numbered face. Everything else is an error: non-finite coordinates, indices out of
//! range, zero-area triangles with three distinct vertices, edges with more than two faces,
//! vertices whose faces form more than one fan, non-orientable surfaces, and a triangle soup (most
//! triangles with vertices of their own, lying on other triangles' vertices: `--repair` welds it).

use std::collections::HashMap;

use glam::DVec3;

use super::defects::{Defect, MAXIMUM_COORDINATE, MeshDefects};
use super::facet::{FacetModel, NONE};
use crate::cad::TriangleSoup;
use crate::geometry::tolerance::{MESH_WELD_RATIO, has_zero_area};
use crate::geometry::weld::{PointWelder, finite_bounds};

/// Share of the triangles that, sharing no edge with another but a point with another's vertex,
/// make a mesh a triangle soup to refuse (a few such triangles are pieces of their own, as a
/// texture chart of one triangle is).
pub const UNWELDED_SHARE: f64 = 0.5;

/// A validated mesh: its connected components and the repairs made on the way.
#[derive(Debug, Clone)]
pub struct ValidatedMesh {
    /// One facet model per connected component, ordered by their lowest input triangle.
    pub components: Vec<FacetModel>,
    /// Per component, the soup vertex of each model vertex (model vertices are the component's
    /// soup vertices in ascending order): the identity of a vertex through validation.
    pub soup_vertices: Vec<Vec<u32>>,
    /// Repairs made (each [`Defect::is_repaired`]).
    pub warnings: Vec<Defect>,
}

/// The defects that stop `soup`, with its lines.
fn refusal(soup: &TriangleSoup, defects: Vec<Defect>) -> MeshDefects {
    MeshDefects {
        defects,
        lines: soup.source_lines.clone(),
    }
}

/// Checks a soup and splits it into facet models; see the module documentation.
pub fn validate(soup: &TriangleSoup) -> Result<ValidatedMesh, MeshDefects> {
    let mut errors = Vec::new();
    let mut warnings = Vec::new();
    if soup.triangles.is_empty() {
        return Err(refusal(soup, vec![Defect::NoTriangles]));
    }
    check_coordinates_and_indices(soup, &mut errors);
    if !errors.is_empty() {
        return Err(refusal(soup, errors));
    }
    let kept = drop_repeated_vertices(soup, &mut warnings);
    if kept.is_empty() {
        errors.push(Defect::NoTriangles);
        return Err(refusal(soup, errors));
    }
    check_areas(soup, &kept, &mut errors);
    let repeats = repeated_triangles(soup, &kept);
    let mut triangles: Vec<[u32; 3]> = kept.iter().map(|&t| soup.triangles[t]).collect();
    let half_edges = sorted_half_edges(&triangles);
    if repeats.is_empty() {
        check_edge_valence(&half_edges, &mut errors);
    } else {
        // The edges of a duplicate face are reported through it, not as three non-manifold edges.
        let unique: Vec<[u32; 3]> = (kept.iter())
            .filter(|&&t| repeats.binary_search_by_key(&t, |repeat| repeat.0).is_err())
            .map(|&t| soup.triangles[t])
            .collect();
        check_edge_valence(&sorted_half_edges(&unique), &mut errors);
        let defects = repeats
            .iter()
            .map(|&(triangle, of)| Defect::RepeatedTriangle { triangle, of });
        errors.extend(defects);
    }
    if !errors.is_empty() {
        return Err(refusal(soup, errors));
    }
    let component_of = orient_and_label(&mut triangles, &half_edges, &mut errors, &mut warnings);
    check_vertex_fans(soup.positions.len(), &triangles, &mut errors);
    if !errors.is_empty() {
        return Err(refusal(soup, errors));
    }
    let (components, soup_vertices) =
        split_components(soup, &kept, &triangles, &component_of, &mut warnings);
    Ok(ValidatedMesh {
        components,
        soup_vertices,
        warnings,
    })
}

fn check_coordinates_and_indices(soup: &TriangleSoup, errors: &mut Vec<Defect>) {
    for (vertex, p) in soup.positions.iter().enumerate() {
        if !p.is_finite() {
            errors.push(Defect::NonFiniteVertex { vertex });
        } else if p.abs().max_element() > MAXIMUM_COORDINATE {
            let value = p.abs().max_element();
            errors.push(Defect::TooLargeVertex { vertex, value });
        }
    }
    let vertex_count = soup.positions.len();
    for (triangle, t) in soup.triangles.iter().enumerate() {
        for &index in t {
            if index as usize >= vertex_count {
                errors.push(Defect::IndexOutOfRange {
                    triangle,
                    index,
                    vertex_count,
                });
            }
        }
    }
}

/// Indices of the triangles kept: those with three distinct vertex indices.
fn drop_repeated_vertices(soup: &TriangleSoup, warnings: &mut Vec<Defect>) -> Vec<usize> {
    let mut kept = Vec::with_capacity(soup.triangles.len());
    for (triangle, &[a, b, c]) in soup.triangles.iter().enumerate() {
        if a == b || b == c || a == c {
            warnings.push(Defect::RepeatedVertex { triangle });
        } else {
            kept.push(triangle);
        }
    }
    kept
}

/// The `kept` triangles (of three distinct vertices) with the same three vertices as an earlier
/// one, in either winding, with that one, by increasing index: the duplicate faces that
/// validation refuses and `--repair` drops.
pub(super) fn repeated_triangles(soup: &TriangleSoup, kept: &[usize]) -> Vec<(usize, usize)> {
    let mut first_of: HashMap<[u32; 3], usize> = HashMap::with_capacity(kept.len());
    let mut repeats = Vec::new();
    for &triangle in kept {
        let mut key = soup.triangles[triangle];
        key.sort_unstable();
        let first = *first_of.entry(key).or_insert(triangle);
        if first != triangle {
            repeats.push((triangle, first));
        }
    }
    repeats
}

fn check_areas(soup: &TriangleSoup, kept: &[usize], errors: &mut Vec<Defect>) {
    for &triangle in kept {
        let corners = soup.triangles[triangle].map(|v| soup.positions[v as usize]);
        // A non-finite or too large vertex is reported as such, not as a zero area.
        let usable =
            (corners.iter()).all(|p| p.is_finite() && p.abs().max_element() <= MAXIMUM_COORDINATE);
        if usable && has_zero_area(corners) {
            let [a, b, c] = corners;
            let area = 0.5 * (b - a).cross(c - a).length();
            errors.push(Defect::ZeroArea { triangle, area });
        }
    }
}

/// A triangle's side as [`sorted_half_edges`] lists it: lower vertex, higher vertex, triangle,
/// and whether the triangle runs from the lower to the higher.
pub(super) type HalfEdge = (u32, u32, u32, bool);

/// Half-edges `(min, max, face, forward)` sorted by edge; `forward` is true when the face runs
/// from `min` to `max`.
pub(super) fn sorted_half_edges(triangles: &[[u32; 3]]) -> Vec<HalfEdge> {
    let mut half_edges = Vec::with_capacity(triangles.len() * 3);
    for (f, t) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            half_edges.push((a.min(b), a.max(b), f as u32, a < b));
        }
    }
    half_edges.sort_unstable();
    half_edges
}

/// Groups of half-edges that share an undirected edge.
pub(super) fn edge_groups(half_edges: &[HalfEdge]) -> impl Iterator<Item = &[HalfEdge]> {
    half_edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1))
}

fn check_edge_valence(half_edges: &[HalfEdge], errors: &mut Vec<Defect>) {
    for group in edge_groups(half_edges) {
        if group.len() > 2 {
            errors.push(Defect::NonManifoldEdge {
                vertices: [group[0].0, group[0].1],
                faces: group.len(),
            });
        }
    }
}

/// True for a triangle of three distinct vertices, each one of the `vertex_count` there are: one
/// the repairs work on (validation drops or refuses the others).
pub(super) fn is_usable([a, b, c]: [u32; 3], vertex_count: usize) -> bool {
    a != b && b != c && a != c && [a, b, c].iter().all(|&v| (v as usize) < vertex_count)
}

/// Refuses a file's soup most of whose triangles ([`UNWELDED_SHARE`]) share no edge with
/// another while a corner of each lies at the same point as another triangle's vertex: a
/// triangle soup whose every triangle would be a part of its own ([`Defect::Unwelded`];
/// `--repair` welds it first). Checked on the file as read, before any repair or split, which
/// make such copies on purpose.
pub fn check_welded(soup: &TriangleSoup) -> Result<(), MeshDefects> {
    let count = soup.positions.len();
    let usable: Vec<usize> = (0..soup.triangles.len())
        .filter(|&t| is_usable(soup.triangles[t], count))
        .collect();
    let triangles: Vec<[u32; 3]> = usable.iter().map(|&t| soup.triangles[t]).collect();
    let mut has_neighbour = vec![false; triangles.len()];
    let half_edges = sorted_half_edges(&triangles);
    for group in edge_groups(&half_edges).filter(|group| group.len() > 1) {
        for half in group {
            has_neighbour[half.2 as usize] = true;
        }
    }
    let lone = has_neighbour.iter().filter(|&&has| !has).count();
    if (lone as f64) < UNWELDED_SHARE * triangles.len() as f64 {
        // Too few triangles without a neighbour for a soup, whatever their vertices.
        return Ok(());
    }
    let mut points = PointsNearlyEqual::new(&soup.positions);
    let mut shared = vec![false; count];
    for &vertex in triangles.iter().flatten() {
        let first = points.first_at(vertex);
        if first != vertex {
            shared[vertex as usize] = true;
            shared[first as usize] = true;
        }
    }
    let isolated: Vec<usize> = (0..triangles.len())
        .filter(|&t| !has_neighbour[t] && triangles[t].iter().any(|&v| shared[v as usize]))
        .collect();
    if isolated.is_empty() || (isolated.len() as f64) < UNWELDED_SHARE * triangles.len() as f64 {
        return Ok(());
    }
    let unwelded = Defect::Unwelded {
        isolated: isolated.len(),
        triangles: triangles.len(),
        first: usable[isolated[0]],
    };
    Err(refusal(soup, vec![unwelded]))
}

/// The vertices of a mesh by point: two vertices closer than [`MESH_WELD_RATIO`] times the
/// diagonal of the finite positions' bounding box are at one point, represented by the first one
/// asked about (a vertex with a non-finite position is its own point).
pub(crate) struct PointsNearlyEqual<'a> {
    positions: &'a [DVec3],
    welder: PointWelder,
    /// The vertex representing each point of the welder.
    firsts: Vec<u32>,
    /// Each vertex's point in the welder, once asked about ([`UNASKED`] before).
    point_of: Vec<u32>,
}

/// A vertex not asked about yet, in [`PointsNearlyEqual`].
const UNASKED: u32 = u32::MAX;

impl<'a> PointsNearlyEqual<'a> {
    /// The points of `positions`, none asked about yet.
    pub(crate) fn new(positions: &'a [DVec3]) -> Self {
        let (origin, diagonal) = finite_bounds(positions)
            .map_or((DVec3::ZERO, 0.0), |(min, max)| (min, (max - min).length()));
        let tolerance = (MESH_WELD_RATIO * diagonal).max(f64::MIN_POSITIVE);
        Self {
            positions,
            welder: PointWelder::new(origin, tolerance),
            firsts: Vec::new(),
            point_of: vec![UNASKED; positions.len()],
        }
    }

    /// The first vertex asked about at `vertex`'s point (`vertex` itself if it is the first).
    pub(crate) fn first_at(&mut self, vertex: u32) -> u32 {
        let slot = &mut self.point_of[vertex as usize];
        if *slot == UNASKED {
            *slot = self.welder.insert(self.positions[vertex as usize]);
            if *slot as usize == self.firsts.len() {
                self.firsts.push(vertex);
            }
        }
        self.firsts[*slot as usize]
    }
}

/// Propagates a consistent orientation over each component (breadth first from its lowest face),
/// flipping faces as needed, and returns the component label of every face.
fn orient_and_label(
    triangles: &mut [[u32; 3]],
    half_edges: &[HalfEdge],
    errors: &mut Vec<Defect>,
    warnings: &mut Vec<Defect>,
) -> Vec<u32> {
    let pairs: Vec<[HalfEdge; 2]> = manifold_pairs(half_edges).collect();
    let (flipped, component) = breadth_first_orientation(triangles.len(), &pairs);
    if let Some([x, _]) = (pairs.iter()).find(|pair| !orientations_agree(pair, &flipped)) {
        errors.push(Defect::NonOrientable {
            vertices: [x.0, x.1],
        });
    }
    let count = flipped.iter().filter(|&&x| x).count();
    if count > 0 && errors.is_empty() {
        for (t, &flip) in triangles.iter_mut().zip(&flipped) {
            if flip {
                t.swap(1, 2);
            }
        }
        warnings.push(Defect::Reoriented { count });
    }
    component
}

/// Per face, whether it is flipped when each component (faces joined across the neighbour
/// `pairs`, from [`manifold_pairs`]) is oriented breadth first from its lowest face, which keeps
/// its orientation; and each face's component label, numbered in the order of those faces.
pub(super) fn breadth_first_orientation(
    triangle_count: usize,
    pairs: &[[HalfEdge; 2]],
) -> (Vec<bool>, Vec<u32>) {
    let mut neighbours: Vec<Vec<(u32, bool)>> = vec![Vec::new(); triangle_count];
    for [x, y] in pairs {
        let same = x.3 == y.3;
        neighbours[x.2 as usize].push((y.2, same));
        neighbours[y.2 as usize].push((x.2, same));
    }
    let mut flipped = vec![false; triangle_count];
    let mut component = vec![NONE; triangle_count];
    let mut label = 0;
    let mut queue = std::collections::VecDeque::new();
    for seed in 0..triangle_count {
        if component[seed] != NONE {
            continue;
        }
        component[seed] = label;
        queue.push_back(seed);
        while let Some(f) = queue.pop_front() {
            for &(g, same) in &neighbours[f] {
                if component[g as usize] == NONE {
                    component[g as usize] = label;
                    flipped[g as usize] = flipped[f] ^ same;
                    queue.push_back(g as usize);
                }
            }
        }
        label += 1;
    }
    (flipped, component)
}

/// True when the two faces of a neighbour pair, each flipped as `flipped` says, agree: they run
/// over their shared edge in opposite directions.
pub(super) fn orientations_agree([x, y]: &[HalfEdge; 2], flipped: &[bool]) -> bool {
    (x.3 ^ flipped[x.2 as usize]) != (y.3 ^ flipped[y.2 as usize])
}

/// Flags vertices whose faces form several fans: corners are joined across shared edges, and a
/// vertex must end with all its corners in one group.
fn check_vertex_fans(vertex_count: usize, triangles: &[[u32; 3]], errors: &mut Vec<Defect>) {
    let fans = corner_fans(triangles, manifold_pairs(&sorted_half_edges(triangles)));
    let mut roots_of_vertex: Vec<Vec<u32>> = vec![Vec::new(); vertex_count];
    for (f, t) in triangles.iter().enumerate() {
        for (k, &v) in t.iter().enumerate() {
            roots_of_vertex[v as usize].push(fans[f * 3 + k]);
        }
    }
    for (vertex, roots) in roots_of_vertex.iter_mut().enumerate() {
        roots.sort_unstable();
        roots.dedup();
        if roots.len() > 1 {
            errors.push(Defect::NonManifoldVertex {
                vertex,
                fans: roots.len(),
            });
        }
    }
}

/// The pairs of half-edges (from [`sorted_half_edges`]) of the edges that exactly two triangles
/// share: the triangles that are neighbours.
pub(super) fn manifold_pairs(half_edges: &[HalfEdge]) -> impl Iterator<Item = [HalfEdge; 2]> + '_ {
    edge_groups(half_edges).filter_map(|group| match group {
        [x, y] => Some([*x, *y]),
        _ => None,
    })
}

/// The fan of every triangle corner (corner `3 f + k` is corner `k` of triangle `f`), as one
/// representative corner per fan: a vertex's corners are joined across the edge of each pair of
/// neighbour half-edges (`neighbours`, such as [`manifold_pairs`]). Triangles repeat no vertex.
pub(super) fn corner_fans(
    triangles: &[[u32; 3]],
    neighbours: impl IntoIterator<Item = [HalfEdge; 2]>,
) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..triangles.len() as u32 * 3).collect();
    fn root(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    for [x, y] in neighbours {
        for v in [x.0, x.1] {
            let (ra, rb) = (
                root(&mut parent, corner(triangles, &x, v) as u32),
                root(&mut parent, corner(triangles, &y, v) as u32),
            );
            parent[ra as usize] = rb;
        }
    }
    (0..parent.len() as u32)
        .map(|c| root(&mut parent, c))
        .collect()
}

/// The corner (`3 f + k`) of a half-edge's triangle `f` at one of the edge's vertices.
pub(super) fn corner(triangles: &[[u32; 3]], half: &HalfEdge, vertex: u32) -> usize {
    let face = half.2 as usize;
    let k = triangles[face]
        .iter()
        .position(|&v| v == vertex)
        .expect("an edge's vertex is a corner of its triangle");
    face * 3 + k
}

/// One facet model per component label, vertices renumbered in ascending input order, each with
/// its model-to-soup vertex map.
fn split_components(
    soup: &TriangleSoup,
    kept: &[usize],
    triangles: &[[u32; 3]],
    component_of: &[u32],
    warnings: &mut Vec<Defect>,
) -> (Vec<FacetModel>, Vec<Vec<u32>>) {
    let component_count = component_of.iter().max().map_or(0, |&m| m as usize + 1);
    let mut referenced = vec![false; soup.positions.len()];
    let mut models = Vec::with_capacity(component_count);
    let mut soup_vertices = Vec::with_capacity(component_count);
    for label in 0..component_count as u32 {
        let faces: Vec<usize> = (0..triangles.len())
            .filter(|&f| component_of[f] == label)
            .collect();
        let mut vertices: Vec<u32> = faces.iter().flat_map(|&f| triangles[f]).collect();
        vertices.sort_unstable();
        vertices.dedup();
        let mut new_index = vec![NONE; soup.positions.len()];
        for (i, &v) in vertices.iter().enumerate() {
            new_index[v as usize] = i as u32;
            referenced[v as usize] = true;
        }
        let positions: Vec<DVec3> = vertices
            .iter()
            .map(|&v| soup.positions[v as usize])
            .collect();
        let local: Vec<[u32; 3]> = faces
            .iter()
            .map(|&f| triangles[f].map(|v| new_index[v as usize]))
            .collect();
        let sources = faces
            .iter()
            .map(|&f| soup.face_sources.get(kept[f]).copied().unwrap_or(0))
            .collect();
        let folds: Vec<(u32, u32, u32)> = soup
            .fold_edges
            .iter()
            .filter_map(|e| {
                let [a, b] = e
                    .vertices
                    .map(|v| new_index.get(v as usize).copied().unwrap_or(NONE));
                (a != NONE && b != NONE).then_some((a, b, e.fold_line))
            })
            .collect();
        models.push(FacetModel::from_checked(positions, local, sources, &folds));
        soup_vertices.push(vertices);
    }
    let unreferenced: Vec<usize> = (0..referenced.len()).filter(|&v| !referenced[v]).collect();
    if let Some(&first) = unreferenced.first() {
        warnings.push(Defect::UnreferencedVertices {
            count: unreferenced.len(),
            first,
        });
    }
    (models, soup_vertices)
}

#[cfg(test)]
mod tests {
    use crate::mesh::defects::Defect;
    use crate::mesh::validate::*;

    fn soup(positions: &[[f64; 3]], triangles: &[[u32; 3]]) -> TriangleSoup {
        TriangleSoup::new(
            positions.iter().map(|&p| DVec3::from_array(p)).collect(),
            triangles.to_vec(),
        )
    }

    const SQUARE: [[f64; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];

    #[test]
    fn a_clean_square_gives_one_model_with_one_boundary_loop() {
        let validated = validate(&soup(&SQUARE, &[[0, 1, 2], [0, 2, 3]])).expect("valid");
        assert!(validated.warnings.is_empty());
        let model = &validated.components[0];
        assert_eq!(
            (
                model.vertex_count(),
                model.triangle_count(),
                model.edges().len()
            ),
            (4, 2, 5)
        );
        assert_eq!(model.boundary_loops(), &[vec![0, 1, 2, 3]]);
        assert!((model.area() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn every_defect_is_reported_at_once() {
        let mut positions = SQUARE.to_vec();
        positions.push([f64::NAN, 0.0, 0.0]);
        let defects =
            validate(&soup(&positions, &[[0, 1, 2], [0, 2, 9], [0, 2, 4]])).expect_err("defects");
        assert!(
            defects
                .defects
                .contains(&Defect::NonFiniteVertex { vertex: 4 })
        );
        assert!(
            !defects
                .defects
                .iter()
                .any(|defect| matches!(defect, Defect::ZeroArea { .. })),
            "{defects}"
        );
        assert!(defects.defects.contains(&Defect::IndexOutOfRange {
            triangle: 1,
            index: 9,
            vertex_count: 5
        }));
    }

    /// A face listed twice (in either winding) is named as a duplicate, not as the three
    /// non-manifold edges it makes; a third triangle on one of its edges is still non-manifold.
    #[test]
    fn a_duplicate_face_is_named_as_such() {
        let defects = validate(&soup(&SQUARE, &[[0, 1, 2], [0, 2, 3], [2, 1, 0]]))
            .expect_err("a duplicate face");
        assert_eq!(
            defects.defects,
            vec![Defect::RepeatedTriangle { triangle: 2, of: 0 }]
        );
        let mut positions = SQUARE.to_vec();
        positions.push([0.5, 0.5, 1.0]);
        let triangles = [[0, 1, 2], [0, 2, 3], [0, 1, 2], [0, 2, 4]];
        let defects = validate(&soup(&positions, &triangles)).expect_err("defects");
        assert_eq!(
            defects.defects,
            vec![
                Defect::NonManifoldEdge {
                    vertices: [0, 2],
                    faces: 3
                },
                Defect::RepeatedTriangle { triangle: 2, of: 0 }
            ]
        );
    }

    #[test]
    fn bow_tie_vertex_is_non_manifold() {
        let positions = [
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [-1., 0., 0.],
            [0., -1., 0.],
        ];
        let defects = validate(&soup(&positions, &[[0, 1, 2], [0, 3, 4]])).expect_err("bow-tie");
        assert_eq!(
            defects.defects,
            vec![Defect::NonManifoldVertex { vertex: 0, fans: 2 }]
        );
    }

    #[test]
    fn flipped_face_is_reoriented_and_repeated_vertex_dropped() {
        let validated =
            validate(&soup(&SQUARE, &[[0, 1, 2], [0, 3, 2], [1, 1, 2]])).expect("repairable");
        assert!(
            validated
                .warnings
                .contains(&Defect::Reoriented { count: 1 })
        );
        assert!(
            validated
                .warnings
                .contains(&Defect::RepeatedVertex { triangle: 2 })
        );
        assert_eq!(validated.components[0].triangles()[1], [0, 2, 3]);
    }

    /// A lone triangle on a square's corners (a texture chart of one triangle, cut apart) is a
    /// part of its own, not a triangle soup: one of three triangles is under the share refused.
    #[test]
    fn a_few_lone_triangles_on_other_vertices_are_parts_of_their_own() {
        let mut positions = SQUARE.to_vec();
        positions.extend([SQUARE[0], SQUARE[1], [0.5, -1., 0.]]);
        let soup = soup(&positions, &[[0, 1, 2], [0, 2, 3], [4, 6, 5]]);
        assert!(check_welded(&soup).is_ok());
        assert_eq!(validate(&soup).expect("valid").components.len(), 2);
    }

    #[test]
    fn components_are_split_and_unreferenced_vertices_dropped() {
        let mut positions = SQUARE.to_vec();
        positions.extend([[5., 0., 0.], [6., 0., 0.], [5., 1., 0.], [9., 9., 9.]]);
        let validated =
            validate(&soup(&positions, &[[0, 1, 2], [4, 5, 6], [0, 2, 3]])).expect("valid");
        assert_eq!(validated.components.len(), 2);
        assert_eq!(validated.components[0].triangle_count(), 2);
        assert_eq!(
            validated.components[1].positions()[0],
            DVec3::new(5., 0., 0.)
        );
        assert!(
            validated
                .warnings
                .contains(&Defect::UnreferencedVertices { count: 1, first: 7 })
        );
    }

    #[test]
    fn mobius_strip_is_not_orientable() {
        // A strip of 4 quads whose ends are glued with a half twist.
        let positions: Vec<[f64; 3]> = (0..4)
            .flat_map(|i| {
                let angle = i as f64 * std::f64::consts::FRAC_PI_2;
                let twist = angle / 2.0;
                let (radial, height) = (0.3 * twist.cos(), 0.3 * twist.sin());
                [-1.0, 1.0].map(|s| {
                    [
                        (1.0 + s * radial) * angle.cos(),
                        (1.0 + s * radial) * angle.sin(),
                        s * height,
                    ]
                })
            })
            .collect();
        let mut triangles = Vec::new();
        for i in 0..4u32 {
            let (a, b) = (2 * i, 2 * i + 1);
            let (c, d) = if i == 3 {
                (1, 0)
            } else {
                (2 * i + 2, 2 * i + 3)
            };
            triangles.extend([[a, c, b], [b, c, d]]);
        }
        let defects = validate(&soup(&positions, &triangles)).expect_err("non-orientable");
        assert!(
            defects
                .defects
                .iter()
                .any(|d| matches!(d, Defect::NonOrientable { .. })),
            "{defects}"
        );
    }
}
