//! The cut graph of a closed surface with handles (genus `g > 0`), by tree–cotree
//! decomposition (Eppstein 2003; Erickson and Whittlesey 2005): cutting along it opens the surface
//! to a disk.
//!
//! Input: a closed [`FacetModel`] (no boundary). Output: the edges of the graph and the graph
//! split into chains (vertex paths between its branch points) for reporting.
//!
//! Method: `T` is the shortest-path tree of the vertices from the vertex of most negative angle
//! deficit over its one-ring (Dijkstra on 3D edge lengths, so the cut runs along short paths); `C` is a spanning tree of the faces across the
//! edges not in `T` (breadth first from face 0). The `2g` edges in neither close one loop each
//! with `T`; the union of `T` and those edges, with every dangling branch of `T` pruned, is the
//! cut graph. On a genus-0 surface it is empty (no loop to cut).
//!
//! A closed surface also gets the **curvature cut graph** ([`curvature_cut_graph`]), in the spirit
//! of Seamster (Sheffer and Hart 2002) and of cone-singularity parametrisations: a surface that
//! concentrates its Gaussian curvature (angle deficit `2π − Σθ`) in a few regions (the corners of
//! a box, filleted or not, the rims of a capped cylinder, the floor rim of a pocket) develops
//! exactly, or nearly, once the seams pass through those regions. The regions are the connected
//! sets of vertices whose curvature density `|2π − Σθ| / area` is at least
//! [`REGION_DENSITY_FACTOR`] times that of a sphere of the part's area (or whose deficit alone is
//! at least [`REGION_VERTEX_DEFICIT`], for coarse meshes), holding together at least
//! [`REGION_MIN_DEFICIT`] (negative curvature only on request, see [`RegionSigns`]); the seams are a shortest-path Steiner tree (Prim's heuristic) from the
//! seams cut so far (or from the strongest region) through every vertex of those regions, along
//! edge costs that make routes along creases, fillets and the regions themselves cheaper (where a
//! seam shows least and releases most). Prim's tree never closes a loop, so a ring-shaped region
//! (a rim) is cut all around but one edge: a can opens to its side and two lids, each hinged on
//! one edge.

use std::collections::VecDeque;
use std::f64::consts::{PI, TAU};

use super::paths::{Adjacency, GrowingSearch, dijkstra};
use crate::mesh::{FacetModel, NONE};

/// A curvature region's vertices have a curvature density `|2π − Σθ| / area` (area: a third of
/// the triangles around the vertex) of at least this multiple of `4π / A`, the density of a sphere
/// of the part's area `A`: the surface is there curved at least as a sphere of half that sphere's
/// radius. A smooth sphere or torus has no region; a box corner, sharp or filleted, and the rim of
/// a can are one each.
pub const REGION_DENSITY_FACTOR: f64 = 4.0;
/// A vertex whose own angle deficit is at least this (20°) belongs to a curvature region whatever
/// its density: on a coarse mesh a rim's vertices are too large for the density to show (a can
/// with 16 segments has 22.5° at each rim vertex).
pub const REGION_VERTEX_DEFICIT: f64 = PI / 9.0;
/// Smallest total angle deficit `|Σ (2π − Σθ)|` (radians) of a curvature region (30°: a box corner
/// holds 90°, a rim 360°).
pub const REGION_MIN_DEFICIT: f64 = PI / 6.0;
/// Dihedral angle (radians) at which an edge costs half its length to cut along (10°): seams
/// prefer creases and the rulings of fillets.
pub const BEND_SCALE: f64 = PI / 18.0;
/// Cost factor of an edge with both ends in a curvature region.
pub const REGION_ROUTE_FACTOR: f64 = 0.5;

/// A cut graph: its edges, and the same edges as chains of vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct CutGraph {
    /// Edge indices, ascending.
    pub edges: Vec<usize>,
    /// Vertex paths that cover the edges once each, split at branch points.
    pub chains: Vec<Vec<u32>>,
}

/// The tree–cotree cut graph of a closed model; see the module documentation.
pub fn tree_cotree_cut_graph(model: &FacetModel, adjacency: &Adjacency) -> CutGraph {
    let in_tree = shortest_path_tree(model, adjacency, most_saddle_like_vertex(model, adjacency));
    let in_cotree = dual_spanning_tree(model, &in_tree);
    let mut in_graph: Vec<bool> = (0..model.edges().len())
        .map(|e| in_tree[e] || !in_cotree[e])
        .collect();
    prune_dangling(model, adjacency, &mut in_graph);
    let edges: Vec<usize> = (0..in_graph.len()).filter(|&e| in_graph[e]).collect();
    let chains = chains(model, adjacency, &in_graph);
    CutGraph { edges, chains }
}

/// The curvature cut graph of a closed surface, or of a closed surface already opened by earlier
/// seams (their boundary is where the tree starts); see the module documentation. `None` when it
/// has no curvature region to reach, or the graph would be a single edge of a closed surface
/// (which opens nothing). Vertices marked in `blocked` are never crossed; `signs` says which
/// curvature makes regions.
pub fn curvature_cut_graph(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
    signs: RegionSigns,
) -> Option<CutGraph> {
    let deficits = model.angle_deficits();
    let regions = curvature_regions(model, adjacency, &deficits, signs);
    let on_boundary = model.boundary_flags();
    let mut terminal = vec![false; model.vertex_count()];
    for &v in regions.iter().flatten() {
        terminal[v as usize] = !blocked[v as usize] && !on_boundary[v as usize];
    }
    let root = strongest_vertex(&regions, &deficits, &terminal);
    steiner_tree(model, adjacency, blocked, &terminal, root)
}

/// The cut graph of a smooth closed surface without handles that has no curvature region (a
/// sphere, an ellipsoid, a pebble): the bisector of its two farthest-apart vertices `p` and `q`
/// (the vertices nearer to `p` with a neighbour nearer to `q`), cut all around but one hinge edge
/// by the same Steiner tree as [`curvature_cut_graph`]. It halves the surface into two caps of
/// about `2π` of curvature each (two hemispheres of a sphere), which crest-line darts bring to
/// tolerance as they do a hemisphere;
/// a single slit between `p` and `q` leaves a pattern whose outline is far too short for its
/// area (a UV sphere stalled at 4.5 %). `None` for a surface with a boundary or when the
/// bisector gives no graph.
pub fn bisector_cut_graph(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
) -> Option<CutGraph> {
    if !model.is_closed() {
        return None;
    }
    let passable = |v: u32| !blocked[v as usize];
    let start = (0..model.vertex_count() as u32).find(|&v| passable(v))?;
    let farthest = |from: u32| {
        let (paths, _) = dijkstra(model, adjacency, &[from], passable, |_| false);
        let far = (0..model.vertex_count() as u32)
            .filter(|&v| paths.distances[v as usize].is_finite())
            .max_by(|&a, &b| {
                paths.distances[a as usize]
                    .total_cmp(&paths.distances[b as usize])
                    .then(b.cmp(&a))
            })
            .unwrap_or(from);
        (far, paths.distances)
    };
    let (p, _) = farthest(start);
    let (q, from_p) = farthest(p);
    let (from_q, _) = dijkstra(model, adjacency, &[q], passable, |_| false);
    let from_q = from_q.distances;
    let nearer_p = |v: u32| from_p[v as usize] <= from_q[v as usize];
    let terminal: Vec<bool> = (0..model.vertex_count() as u32)
        .map(|v| {
            passable(v)
                && from_p[v as usize].is_finite()
                && nearer_p(v)
                && adjacency
                    .neighbours(v)
                    .iter()
                    .any(|&(w, _)| from_q[w as usize].is_finite() && !nearer_p(w))
        })
        .collect();
    let root = terminal.iter().position(|&t| t).map(|v| v as u32);
    steiner_tree(model, adjacency, blocked, &terminal, root)
}

/// A shortest-path Steiner tree (Prim's heuristic) from the model's boundary, or from `root` on a
/// closed model, through every `terminal` vertex it can reach, along [`route_costs`]. `None` when
/// it has no edge, or a single edge on a closed model (which opens nothing).
fn steiner_tree(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
    terminal: &[bool],
    root: Option<u32>,
) -> Option<CutGraph> {
    let on_boundary = model.boundary_flags();
    let mut in_tree: Vec<bool> = (0..model.vertex_count())
        .map(|v| on_boundary[v] && !blocked[v])
        .collect();
    if !in_tree.contains(&true) {
        in_tree[root? as usize] = true;
    }
    let cost = route_costs(model, terminal);
    let mut in_graph = vec![false; model.edges().len()];
    let mut search = GrowingSearch::new(model.vertex_count(), adjacency);
    for v in (0..model.vertex_count() as u32).filter(|&v| in_tree[v as usize]) {
        search.add_source(v);
    }
    loop {
        let reached = search.next_reached(
            |v| !blocked[v as usize],
            |v| terminal[v as usize] && !in_tree[v as usize],
            |edge| cost[edge as usize],
        );
        let Some(target) = reached else {
            break;
        };
        for pair in search.path_to(target).windows(2) {
            in_graph[model.find_edge(pair[0], pair[1])?] = true;
            in_tree[pair[1] as usize] = true;
            search.add_source(pair[1]);
        }
    }
    let edges: Vec<usize> = (0..in_graph.len()).filter(|&e| in_graph[e]).collect();
    if edges.is_empty() || (model.is_closed() && edges.len() < 2) {
        return None;
    }
    let chains = chains(model, adjacency, &in_graph);
    Some(CutGraph { edges, chains })
}

/// A third of the area of the triangles around each vertex.
fn vertex_areas(model: &FacetModel) -> Vec<f64> {
    let mut areas = vec![0.0; model.vertex_count()];
    for (face, triangle) in model.triangles().iter().enumerate() {
        let third = model.triangle_area(face) / 3.0;
        for &v in triangle {
            areas[v as usize] += third;
        }
    }
    areas
}

/// Which signs of Gaussian curvature make curvature regions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RegionSigns {
    /// Positive only (corners, rims of lids, domes).
    Positive,
    /// Positive and negative (also the rim of a pocket or of a hole's collar, the inside of a
    /// torus): a seam there frees the material around it, which then often has nowhere to lie but
    /// over its neighbours.
    Both,
}

/// The curvature regions: connected sets of vertices of one sign of angle deficit (positive only,
/// or either, as `signs` says) whose curvature density is at least
/// [`REGION_DENSITY_FACTOR`]` × 4π / A` or whose deficit is at least [`REGION_VERTEX_DEFICIT`],
/// holding at least [`REGION_MIN_DEFICIT`] in all (in
/// absolute value). Each region's vertices ascend.
pub fn curvature_regions(
    model: &FacetModel,
    adjacency: &Adjacency,
    deficits: &[f64],
    signs: RegionSigns,
) -> Vec<Vec<u32>> {
    let areas = vertex_areas(model);
    let threshold = REGION_DENSITY_FACTOR * 2.0 * TAU / model.area();
    let sign: Vec<i8> = (0..model.vertex_count())
        .map(|v| {
            let counted = signs == RegionSigns::Both || deficits[v] > 0.0;
            let dense = (areas[v] > 0.0 && deficits[v].abs() >= threshold * areas[v])
                || deficits[v].abs() >= REGION_VERTEX_DEFICIT;
            if counted && dense {
                deficits[v].signum() as i8
            } else {
                0
            }
        })
        .collect();
    let mut seen = vec![false; model.vertex_count()];
    let mut regions = Vec::new();
    for start in 0..model.vertex_count() as u32 {
        if sign[start as usize] == 0 || seen[start as usize] {
            continue;
        }
        seen[start as usize] = true;
        let mut region = vec![start];
        let mut queue = VecDeque::from([start]);
        while let Some(v) = queue.pop_front() {
            for &(w, _) in adjacency.neighbours(v) {
                if sign[w as usize] == sign[start as usize] && !seen[w as usize] {
                    seen[w as usize] = true;
                    region.push(w);
                    queue.push_back(w);
                }
            }
        }
        let total: f64 = region.iter().map(|&v| deficits[v as usize]).sum();
        if total.abs() >= REGION_MIN_DEFICIT {
            region.sort_unstable();
            regions.push(region);
        }
    }
    regions
}

/// The root of the curvature tree of a closed surface: the terminal of largest `|deficit|` in the
/// region holding the largest `|Σ deficit|` (ties to the lower index).
fn strongest_vertex(regions: &[Vec<u32>], deficits: &[f64], terminal: &[bool]) -> Option<u32> {
    let held = |region: &Vec<u32>| {
        region
            .iter()
            .map(|&v| deficits[v as usize])
            .sum::<f64>()
            .abs()
    };
    let mut order: Vec<&Vec<u32>> = regions.iter().collect();
    order.sort_by(|a, b| held(b).total_cmp(&held(a)));
    order.into_iter().find_map(|region| {
        region
            .iter()
            .copied()
            .filter(|&v| terminal[v as usize])
            .max_by(|&a, &b| {
                deficits[a as usize]
                    .abs()
                    .total_cmp(&deficits[b as usize].abs())
                    .then(b.cmp(&a))
            })
    })
}

/// The cost of cutting along each edge: its length, divided by `1 + dihedral / BEND_SCALE`, and
/// times [`REGION_ROUTE_FACTOR`] when both its ends are region vertices (`in_region`).
fn route_costs(model: &FacetModel, in_region: &[bool]) -> Vec<f64> {
    let positions = model.positions();
    let normal = |face: u32| {
        let [a, b, c] = model.triangles()[face as usize].map(|v| positions[v as usize]);
        (b - a).cross(c - a).normalize_or_zero()
    };
    model
        .edges()
        .iter()
        .zip(model.edge_faces())
        .map(|(&[a, b], &[first, second])| {
            let length = positions[a as usize].distance(positions[b as usize]);
            let dihedral = if second == NONE {
                0.0
            } else {
                normal(first).angle_between(normal(second))
            };
            let bent = length / (1.0 + dihedral.max(0.0) / BEND_SCALE);
            if in_region[a as usize] && in_region[b as usize] {
                bent * REGION_ROUTE_FACTOR
            } else {
                bent
            }
        })
        .collect()
}

/// The vertex whose angle deficit plus its neighbours' is most negative (the lowest index among
/// equals; the neighbours smooth out the triangulation's bias): on the inside of a handle, where
/// the loops around it are shortest. Rooted there, the cut graph of a torus runs
/// along its inner equator, the pattern's outline is where the material is shortest, and the
/// crest-line darts cut from it taper outwards into a fishbone instead of fanning into each other
/// (rooted on the outer equator, 8 cuts left the outline crossing itself).
fn most_saddle_like_vertex(model: &FacetModel, adjacency: &Adjacency) -> u32 {
    let deficit = model.angle_deficits();
    let deficits: Vec<f64> = (0..model.vertex_count() as u32)
        .map(|v| {
            let ring: f64 = adjacency
                .neighbours(v)
                .iter()
                .map(|&(w, _)| deficit[w as usize])
                .sum();
            deficit[v as usize] + ring
        })
        .collect();
    (0..model.vertex_count() as u32)
        .min_by(|&a, &b| {
            deficits[a as usize]
                .total_cmp(&deficits[b as usize])
                .then(a.cmp(&b))
        })
        .unwrap_or(0)
}

/// Edges of the shortest-path tree from `root`.
fn shortest_path_tree(model: &FacetModel, adjacency: &Adjacency, root: u32) -> Vec<bool> {
    let (paths, _) = dijkstra(model, adjacency, &[root], |_| true, |_| false);
    let mut in_tree = vec![false; model.edges().len()];
    for v in 0..model.vertex_count() as u32 {
        if let Some(parent) = paths.predecessor(v)
            && let Some(edge) = model.find_edge(v, parent)
        {
            in_tree[edge] = true;
        }
    }
    in_tree
}

/// Edges crossed by a breadth-first spanning tree of the faces that never crosses a tree edge.
fn dual_spanning_tree(model: &FacetModel, in_tree: &[bool]) -> Vec<bool> {
    let mut in_cotree = vec![false; model.edges().len()];
    let mut reached = vec![false; model.triangle_count()];
    let mut queue = VecDeque::from([0u32]);
    reached[0] = true;
    while let Some(face) = queue.pop_front() {
        for &edge in &model.face_edges()[face as usize] {
            let edge = edge as usize;
            if in_tree[edge] {
                continue;
            }
            let [first, second] = model.edge_faces()[edge];
            let other = if first == face { second } else { first };
            if other != NONE && !reached[other as usize] {
                reached[other as usize] = true;
                in_cotree[edge] = true;
                queue.push_back(other);
            }
        }
    }
    in_cotree
}

/// Removes, repeatedly, the graph edges at vertices of graph degree one.
fn prune_dangling(model: &FacetModel, adjacency: &Adjacency, in_graph: &mut [bool]) {
    let mut degree = vec![0usize; model.vertex_count()];
    for (edge, &[a, b]) in model.edges().iter().enumerate() {
        if in_graph[edge] {
            degree[a as usize] += 1;
            degree[b as usize] += 1;
        }
    }
    let mut leaves: Vec<u32> = (0..model.vertex_count() as u32)
        .filter(|&v| degree[v as usize] == 1)
        .collect();
    while let Some(leaf) = leaves.pop() {
        let Some(&(other, edge)) = adjacency
            .neighbours(leaf)
            .iter()
            .find(|&&(_, edge)| in_graph[edge as usize])
        else {
            continue;
        };
        in_graph[edge as usize] = false;
        degree[leaf as usize] -= 1;
        degree[other as usize] -= 1;
        if degree[other as usize] == 1 {
            leaves.push(other);
        }
    }
}

/// The graph's edges as vertex chains between vertices of degree other than two (or around a
/// cycle of degree-two vertices).
fn chains(model: &FacetModel, adjacency: &Adjacency, in_graph: &[bool]) -> Vec<Vec<u32>> {
    let graph_neighbours = |v: u32| {
        adjacency
            .neighbours(v)
            .iter()
            .filter(|&&(_, edge)| in_graph[edge as usize])
            .copied()
            .collect::<Vec<_>>()
    };
    let mut used = vec![false; model.edges().len()];
    let mut chains = Vec::new();
    let branch_first: Vec<u32> = {
        let (mut branches, mut others): (Vec<u32>, Vec<u32>) = (0..model.vertex_count() as u32)
            .filter(|&v| !graph_neighbours(v).is_empty())
            .partition(|&v| graph_neighbours(v).len() != 2);
        branches.append(&mut others);
        branches
    };
    for start in branch_first {
        for (first, edge) in graph_neighbours(start) {
            if used[edge as usize] {
                continue;
            }
            used[edge as usize] = true;
            let mut chain = vec![start, first];
            let mut current = first;
            while current != start && graph_neighbours(current).len() == 2 {
                let Some((next, next_edge)) = graph_neighbours(current)
                    .into_iter()
                    .find(|&(_, e)| !used[e as usize])
                else {
                    break;
                };
                used[next_edge as usize] = true;
                chain.push(next);
                current = next;
            }
            chains.push(chain);
        }
    }
    chains
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::cut::cut_graph::*;
    use crate::cut::split::split_along_edges;
    use crate::mesh::{TriangleSoup, validate};

    /// A torus of `n × n` quads, each split in two.
    fn torus(n: u32) -> FacetModel {
        let mut positions = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let (u, v) = (
                    std::f64::consts::TAU * i as f64 / n as f64,
                    std::f64::consts::TAU * j as f64 / n as f64,
                );
                let radius = 50.0 + 20.0 * v.cos();
                positions.push(DVec3::new(
                    radius * u.cos(),
                    radius * u.sin(),
                    20.0 * v.sin(),
                ));
            }
        }
        let id = |i: u32, j: u32| (i % n) * n + (j % n);
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..n {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let soup = TriangleSoup::new(positions, triangles);
        validate(&soup).expect("valid torus").components.remove(0)
    }

    #[test]
    fn a_torus_has_curvature_regions_only_on_its_inside() {
        // Outside, K = 1 / (20 × 70) is below 4 × 4π / A; inside, K = −1 / (20 × 30) is not.
        let model = torus(16);
        let adjacency = Adjacency::new(&model);
        let deficits = model.angle_deficits();
        let positive = curvature_regions(&model, &adjacency, &deficits, RegionSigns::Positive);
        assert!(positive.is_empty(), "{positive:?}");
        let both = curvature_regions(&model, &adjacency, &deficits, RegionSigns::Both);
        assert!(!both.is_empty());
        for &v in both.iter().flatten() {
            let p = model.positions()[v as usize];
            assert!(p.truncate().length() < 50.0, "{p} is not inside");
            assert!(deficits[v as usize] < 0.0);
        }
    }

    #[test]
    fn a_closed_torus_is_rooted_on_its_inside() {
        let model = torus(16);
        let adjacency = Adjacency::new(&model);
        let root = most_saddle_like_vertex(&model, &adjacency);
        let p = model.positions()[root as usize];
        assert!(p.truncate().length() < 35.0, "{p}");
    }

    #[test]
    fn a_torus_opens_to_a_disk() {
        let model = torus(10);
        let adjacency = Adjacency::new(&model);
        let graph = tree_cotree_cut_graph(&model, &adjacency);
        let chained: usize = graph.chains.iter().map(|chain| chain.len() - 1).sum();
        assert_eq!(chained, graph.edges.len());
        let split = split_along_edges(&model, &graph.edges).expect("cut");
        assert_eq!(split.model.boundary_loops().len(), 1);
        let euler = split.model.vertex_count() as i64 - split.model.edges().len() as i64
            + split.model.triangle_count() as i64;
        assert_eq!(euler, 1, "a disk");
    }
}
