//! Shortest edge paths on a facet model: vertex adjacency and a multi-source Dijkstra over 3D
//! edge lengths, used by seams (between boundary loops, across closed surfaces, along user
//! polylines) and by crest lines (to finish a line that can no longer descend).
//!
//! Input: a [`FacetModel`] (model units) and a predicate on vertices that may be crossed.
//! Output: vertex paths, first vertex a source, last a target. Deterministic: ties are broken by
//! vertex index, never by hash order.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::mesh::FacetModel;

/// The neighbours of every vertex, each with the edge that joins them, sorted by vertex index.
#[derive(Debug, Clone, PartialEq)]
pub struct Adjacency {
    neighbours: Vec<Vec<(u32, u32)>>,
}

impl Adjacency {
    /// Builds the adjacency of the model's edges.
    pub fn new(model: &FacetModel) -> Self {
        let mut neighbours = vec![Vec::new(); model.vertex_count()];
        for (edge, &[a, b]) in model.edges().iter().enumerate() {
            neighbours[a as usize].push((b, edge as u32));
            neighbours[b as usize].push((a, edge as u32));
        }
        for list in &mut neighbours {
            list.sort_unstable();
        }
        Self { neighbours }
    }

    /// `(neighbour, edge)` pairs of vertex `v`, by ascending neighbour.
    pub fn neighbours(&self, v: u32) -> &[(u32, u32)] {
        &self.neighbours[v as usize]
    }
}

/// A vertex in the Dijkstra queue, ordered so that the smallest distance (then the smallest
/// index) pops first from the max-heap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Queued {
    distance: f64,
    vertex: u32,
}

impl Eq for Queued {}

impl Ord for Queued {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .distance
            .total_cmp(&self.distance)
            .then_with(|| other.vertex.cmp(&self.vertex))
    }
}

impl PartialOrd for Queued {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Shortest-path distances and predecessors from a set of sources.
#[derive(Debug, Clone)]
pub struct ShortestPaths {
    /// Distance of each vertex from the nearest source (infinite if unreached).
    pub distances: Vec<f64>,
    predecessors: Vec<u32>,
}

impl ShortestPaths {
    /// The vertex before `v` on its shortest path, or `None` for a source or an unreached vertex.
    pub fn predecessor(&self, v: u32) -> Option<u32> {
        let parent = self.predecessors[v as usize];
        (parent != u32::MAX).then_some(parent)
    }

    /// The path from the nearest source to `target` (source first), or `None` if unreached.
    pub fn path_to(&self, target: u32) -> Option<Vec<u32>> {
        if !self.distances[target as usize].is_finite() {
            return None;
        }
        Some(path_back(&self.predecessors, target))
    }
}

/// The path to `target` along `predecessors` (`u32::MAX` at a source), source first.
fn path_back(predecessors: &[u32], target: u32) -> Vec<u32> {
    let mut path = vec![target];
    let mut current = target;
    while predecessors[current as usize] != u32::MAX {
        current = predecessors[current as usize];
        path.push(current);
    }
    path.reverse();
    path
}

/// Dijkstra over 3D edge lengths from `sources`. A vertex is entered only if `passable(v)`;
/// sources are always entered. The search stops early once `stop_at(v)` holds for a popped
/// non-source vertex, which it returns.
pub fn dijkstra(
    model: &FacetModel,
    adjacency: &Adjacency,
    sources: &[u32],
    passable: impl Fn(u32) -> bool,
    stop_at: impl Fn(u32) -> bool,
) -> (ShortestPaths, Option<u32>) {
    let positions = model.positions();
    let length = |edge: u32| {
        let [a, b] = model.edges()[edge as usize];
        positions[a as usize].distance(positions[b as usize])
    };
    let mut search = GrowingSearch::new(model.vertex_count(), adjacency);
    for &source in sources {
        search.add_source(source);
    }
    let reached = search.next_reached(passable, stop_at, length);
    (search.into_paths(), reached)
}

/// A Dijkstra from sources that may be added while it runs ([`dijkstra`] runs one with fixed
/// sources), for growing a tree one shortest path at a time (Prim's Steiner heuristic): each path found joins the sources, and the search goes
/// on from the labels it has instead of starting again, so growing a tree through `k` targets
/// costs about one search of the model, not `k` (on a noisy 320k-triangle scan, thousands of
/// targets took 80 s searched afresh each time). The labels stay exact: a source added later only
/// lowers them, and every lowered label is queued again. The vertex reached first is the same as a
/// fresh search from all the sources would reach (nearest, then lowest index).
#[derive(Debug, Clone)]
pub struct GrowingSearch<'a> {
    adjacency: &'a Adjacency,
    distances: Vec<f64>,
    predecessors: Vec<u32>,
    is_source: Vec<bool>,
    heap: BinaryHeap<Queued>,
}

impl<'a> GrowingSearch<'a> {
    /// A search over the model of this adjacency (`vertex_count` vertices), with no source yet.
    pub fn new(vertex_count: usize, adjacency: &'a Adjacency) -> Self {
        Self {
            adjacency,
            distances: vec![f64::INFINITY; vertex_count],
            predecessors: vec![u32::MAX; vertex_count],
            is_source: vec![false; vertex_count],
            heap: BinaryHeap::new(),
        }
    }

    /// Makes `v` a source (a no-op for one already).
    pub fn add_source(&mut self, v: u32) {
        if self.is_source[v as usize] {
            return;
        }
        self.is_source[v as usize] = true;
        self.distances[v as usize] = 0.0;
        self.predecessors[v as usize] = u32::MAX;
        self.heap.push(Queued {
            distance: 0.0,
            vertex: v,
        });
    }

    /// The nearest non-source vertex for which `stop_at` holds (its path: [`Self::path_to`]),
    /// entering only vertices that are `passable` and crossing each edge at `cost(edge)`
    /// (non-negative); `None` when no such vertex is reachable. The search resumes from here on
    /// the next call.
    pub fn next_reached(
        &mut self,
        passable: impl Fn(u32) -> bool,
        stop_at: impl Fn(u32) -> bool,
        cost: impl Fn(u32) -> f64,
    ) -> Option<u32> {
        while let Some(Queued { distance, vertex }) = self.heap.pop() {
            if distance > self.distances[vertex as usize] {
                continue;
            }
            if !self.is_source[vertex as usize] && stop_at(vertex) {
                return Some(vertex);
            }
            for &(next, edge) in self.adjacency.neighbours(vertex) {
                if self.is_source[next as usize] || !passable(next) {
                    continue;
                }
                let candidate = distance + cost(edge);
                if candidate < self.distances[next as usize] {
                    self.distances[next as usize] = candidate;
                    self.predecessors[next as usize] = vertex;
                    self.heap.push(Queued {
                        distance: candidate,
                        vertex: next,
                    });
                }
            }
        }
        None
    }

    /// The shortest path found to `target` (one [`Self::next_reached`] returned), source first.
    pub fn path_to(&self, target: u32) -> Vec<u32> {
        path_back(&self.predecessors, target)
    }

    /// The distances and predecessors found so far.
    pub fn into_paths(self) -> ShortestPaths {
        ShortestPaths {
            distances: self.distances,
            predecessors: self.predecessors,
        }
    }
}

/// 3D length of a vertex path.
pub fn path_length(model: &FacetModel, path: &[u32]) -> f64 {
    let positions = model.positions();
    path.windows(2)
        .map(|pair| positions[pair[0] as usize].distance(positions[pair[1] as usize]))
        .sum()
}

/// The model's edges along a vertex path, or `None` if two consecutive vertices share no edge.
pub fn path_edges(model: &FacetModel, path: &[u32]) -> Option<Vec<usize>> {
    path.windows(2)
        .map(|pair| model.find_edge(pair[0], pair[1]))
        .collect()
}

#[cfg(test)]
pub(crate) mod tests {
    use glam::DVec3;

    use crate::cut::paths::*;
    use crate::mesh::{TriangleSoup, validate};

    /// A 3 × 3 grid of unit squares, split into triangles.
    pub(crate) fn grid() -> FacetModel {
        let mut positions = Vec::new();
        for y in 0..4 {
            for x in 0..4 {
                positions.push(DVec3::new(x as f64, y as f64, 0.0));
            }
        }
        let mut triangles = Vec::new();
        for y in 0..3u32 {
            for x in 0..3u32 {
                let v = y * 4 + x;
                triangles.push([v, v + 1, v + 5]);
                triangles.push([v, v + 5, v + 4]);
            }
        }
        let soup = TriangleSoup::new(positions, triangles);
        validate(&soup).expect("valid grid").components.remove(0)
    }

    #[test]
    fn shortest_path_follows_the_diagonal() {
        let model = grid();
        let adjacency = Adjacency::new(&model);
        let (paths, reached) = dijkstra(&model, &adjacency, &[0], |_| true, |v| v == 15);
        assert_eq!(reached, Some(15));
        assert_eq!(paths.path_to(15), Some(vec![0, 5, 10, 15]));
        assert!((paths.distances[15] - 3.0 * 2f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn a_growing_search_reaches_what_a_fresh_search_from_all_its_sources_reaches() {
        let model = grid();
        let adjacency = Adjacency::new(&model);
        let positions = model.positions();
        let length = |edge: u32| {
            let [a, b] = model.edges()[edge as usize];
            positions[a as usize].distance(positions[b as usize])
        };
        let targets = [15, 3, 12, 6, 9];
        let mut search = GrowingSearch::new(model.vertex_count(), &adjacency);
        search.add_source(0);
        let mut sources = vec![0];
        let mut reached_count = 0;
        loop {
            let is_target = |v: u32| targets.contains(&v) && !sources.contains(&v);
            let (fresh, reached) = dijkstra(&model, &adjacency, &sources, |_| true, is_target);
            let grown = search.next_reached(|_| true, is_target, length);
            assert_eq!(grown, reached, "the same nearest target");
            let Some(target) = reached else {
                break;
            };
            let path = search.path_to(target);
            assert_eq!(path.last(), Some(&target));
            assert!(sources.contains(&path[0]), "the path starts at a source");
            assert!((path_length(&model, &path) - fresh.distances[target as usize]).abs() < 1e-12);
            assert!(path_edges(&model, &path).is_some());
            for &v in &path[1..] {
                search.add_source(v);
                sources.push(v);
            }
            reached_count += 1;
        }
        assert!(reached_count >= 2, "several targets joined");
        assert!(targets.iter().all(|t| sources.contains(t)));
    }

    #[test]
    fn blocked_vertices_are_avoided() {
        let model = grid();
        let adjacency = Adjacency::new(&model);
        let (paths, _) = dijkstra(&model, &adjacency, &[0], |v| v != 5 && v != 10, |_| false);
        let path = paths.path_to(15).expect("reachable around the block");
        assert!(!path.contains(&5) && !path.contains(&10));
        assert!(path_edges(&model, &path).is_some());
    }
}
