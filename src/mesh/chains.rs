//! Chains of undirected edges: the paths that a set of edges (vertex index pairs) forms when
//! joined end to end, as fold lines, cut lines and isolines need them for drawing and export.
//!
//! Input: edges as `[a, b]` vertex pairs, in any order and direction. Output: vertex paths,
//! every edge used exactly once; open chains start at a free end (a vertex of odd degree), closed
//! ones repeat their first vertex at the end. Deterministic: starts are taken in ascending vertex
//! order and at each vertex the unused edge to the lowest-numbered neighbour is followed.

/// Chains undirected edges into vertex paths: open chains from their free ends first, then
/// closed ones (which repeat their first vertex at the end). Every edge is used once.
pub fn chain_edges(edges: &[[u32; 2]]) -> Vec<Vec<u32>> {
    // Directed copies, sorted by start vertex, so a vertex's edges are one binary search away.
    let mut directed: Vec<(u32, u32, usize)> = edges
        .iter()
        .enumerate()
        .flat_map(|(e, &[a, b])| [(a, b, e), (b, a, e)])
        .collect();
    directed.sort_unstable();
    let neighbours = |v: u32| {
        let start = directed.partition_point(|d| d.0 < v);
        let end = directed.partition_point(|d| d.0 <= v);
        &directed[start..end]
    };
    let mut used = vec![false; edges.len()];
    let mut chains = Vec::new();
    let free_ends: Vec<u32> = {
        let mut ends: Vec<u32> = directed.iter().map(|d| d.0).collect();
        ends.dedup();
        ends.into_iter()
            .filter(|&v| neighbours(v).len() % 2 == 1)
            .collect()
    };
    let all_starts = free_ends.iter().chain(directed.iter().map(|d| &d.0));
    for &start in all_starts {
        while let Some(chain) = walk(start, &neighbours, &mut used) {
            chains.push(chain);
        }
    }
    chains
}

/// Walks from `start` along unused edges until it is stuck; `None` if no edge at `start` is
/// unused.
fn walk<'a>(
    start: u32,
    neighbours: &impl Fn(u32) -> &'a [(u32, u32, usize)],
    used: &mut [bool],
) -> Option<Vec<u32>> {
    let mut chain = vec![start];
    let mut current = start;
    while let Some(&(_, next, edge)) = neighbours(current).iter().find(|d| !used[d.2]) {
        used[edge] = true;
        chain.push(next);
        current = next;
    }
    (chain.len() > 1).then_some(chain)
}

#[cfg(test)]
mod tests {
    use crate::mesh::chains::*;

    #[test]
    fn a_path_in_any_order_becomes_one_chain() {
        let chains = chain_edges(&[[2, 3], [0, 1], [1, 2]]);
        assert_eq!(chains, vec![vec![0, 1, 2, 3]]);
    }

    #[test]
    fn separate_pieces_and_loops_are_kept_apart() {
        let chains = chain_edges(&[[5, 6], [0, 1], [10, 11], [11, 12], [12, 10]]);
        assert_eq!(chains, vec![vec![0, 1], vec![5, 6], vec![10, 11, 12, 10]]);
    }

    #[test]
    fn every_edge_is_used_once() {
        // A cross: four arms meeting at vertex 0.
        let edges = [[0, 1], [0, 2], [0, 3], [0, 4]];
        let chains = chain_edges(&edges);
        let used: usize = chains.iter().map(|c| c.len() - 1).sum();
        assert_eq!(used, edges.len());
    }
}
