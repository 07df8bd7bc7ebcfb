//! Fold lines of a facet model as flat polylines: the mesh edges tagged with each fold line
//! (`FacetModel::edge_fold_lines`), chained end to end, mapped onto the flat pattern.
//!
//! Input: the model and its flat positions (one per vertex, model units). Output: one or more
//! polylines per fold line (more when its edges do not form one chain), fold lines in ascending
//! order, each chain starting at its lowest-numbered free end (or vertex, for a closed chain), so
//! the result is deterministic.

use glam::DVec2;

use crate::mesh::{FacetModel, NONE, chain_edges};

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

#[cfg(test)]
mod tests {
    use crate::pattern::fold_polylines::*;

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
