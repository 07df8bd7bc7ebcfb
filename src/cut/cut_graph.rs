//! The cut graph of a closed surface with handles (genus `g > 0`), by tree–cotree
//! decomposition (Eppstein 2003; Erickson and Whittlesey 2005): cutting along it opens the surface
//! to a disk.
//!
//! Input: a closed [`FacetModel`] (no boundary). Output: the edges of the graph and the graph
//! split into chains (vertex paths between its branch points) for reporting.
//!
//! Method: `T` is the shortest-path tree of the vertices from vertex 0 (Dijkstra on 3D edge
//! lengths, so the cut runs along short paths); `C` is a spanning tree of the faces across the
//! edges not in `T` (breadth first from face 0). The `2g` edges in neither close one loop each
//! with `T`; the union of `T` and those edges, with every dangling branch of `T` pruned, is the
//! cut graph. On a genus-0 surface it is empty (no loop to cut).

use std::collections::VecDeque;

use super::paths::{Adjacency, dijkstra};
use crate::mesh::{FacetModel, NONE};

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
    let in_tree = shortest_path_tree(model, adjacency);
    let in_cotree = dual_spanning_tree(model, &in_tree);
    let mut in_graph: Vec<bool> = (0..model.edges().len())
        .map(|e| in_tree[e] || !in_cotree[e])
        .collect();
    prune_dangling(model, adjacency, &mut in_graph);
    let edges: Vec<usize> = (0..in_graph.len()).filter(|&e| in_graph[e]).collect();
    let chains = chains(model, adjacency, &in_graph);
    CutGraph { edges, chains }
}

/// Edges of the shortest-path tree from vertex 0.
fn shortest_path_tree(model: &FacetModel, adjacency: &Adjacency) -> Vec<bool> {
    let (paths, _) = dijkstra(model, adjacency, &[0], |_| true, |_| false);
    let mut in_tree = vec![false; model.edges().len()];
    for v in 1..model.vertex_count() as u32 {
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

    use super::*;
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
