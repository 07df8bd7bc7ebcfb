//! Fold lines of a facet model as flat polylines: the mesh edges tagged with each fold line
//! (`FacetModel::edge_fold_lines`), chained end to end, mapped onto the flat pattern.
//!
//! Input: the model and its flat positions (one per vertex, model units). Output: one or more
//! polylines per fold line (more when its edges do not form one chain), fold lines in ascending
//! order, each chain starting at its lowest-numbered free end (or vertex, for a closed chain), so
//! the result is deterministic.

use glam::DVec2;

use crate::mesh::{FacetModel, NONE};

/// The fold lines of `model` drawn on the flat pattern `positions`.
pub fn fold_polylines(model: &FacetModel, positions: &[DVec2]) -> Vec<Vec<DVec2>> {
    let mut tagged: Vec<(u32, [u32; 2])> = model
        .edge_fold_lines()
        .iter()
        .zip(model.edges())
        .filter(|(line, _)| **line != NONE)
        .map(|(&line, &edge)| (line, edge))
        .collect();
    tagged.sort_unstable();
    tagged
        .chunk_by(|a, b| a.0 == b.0)
        .flat_map(|group| chain_edges(&group.iter().map(|(_, edge)| *edge).collect::<Vec<_>>()))
        .map(|chain| {
            chain
                .iter()
                .filter_map(|&v| positions.get(v as usize).copied())
                .collect()
        })
        .collect()
}

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
    use super::*;

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

    #[test]
    fn fold_edges_of_a_model_become_flat_polylines() {
        let positions = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .map(|[x, y]| glam::DVec3::new(x, y, 0.0))
            .to_vec();
        let model = FacetModel::from_checked(
            positions,
            vec![[0, 1, 2], [0, 2, 3]],
            vec![0, 0],
            &[(2, 0, 7)],
        );
        let flat = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]
            .map(DVec2::from)
            .to_vec();
        let lines = fold_polylines(&model, &flat);
        assert_eq!(lines, vec![vec![DVec2::ZERO, DVec2::new(2.0, 2.0)]]);
    }
}
