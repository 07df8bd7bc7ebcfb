//! Fold-line length error: how well a pattern keeps each fold line's length.
//!
//! Input: a facet model whose edges are tagged with fold lines, its flat pattern (one 2D
//! position per vertex, model units) and the number of fold lines. Output: per fold line the sum
//! of its edges' 3D lengths, the sum of their flat lengths and the relative difference
//! `|flat − 3D| / 3D` (0 for a fold line with no edge on this model).

use glam::DVec2;
use serde::Serialize;

use crate::mesh::FacetModel;

/// Lengths of one fold line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FoldLineLength {
    /// Length on the surface (model units).
    pub length_3d: f64,
    /// Length in the pattern (model units).
    pub length_flat: f64,
    /// `|length_flat − length_3d| / length_3d`.
    pub error: f64,
}

/// The lengths of fold lines `0..count` (see the module documentation).
pub fn fold_line_lengths(model: &FacetModel, flat: &[DVec2], count: u32) -> Vec<FoldLineLength> {
    let mut sums = vec![(0.0, 0.0); count as usize];
    for (edge, &line) in model.edges().iter().zip(model.edge_fold_lines()) {
        if let Some(sum) = sums.get_mut(line as usize) {
            let [a, b] = edge.map(|v| v as usize);
            sum.0 += model.positions()[a].distance(model.positions()[b]);
            sum.1 += flat[a].distance(flat[b]);
        }
    }
    sums.into_iter()
        .map(|(length_3d, length_flat)| FoldLineLength {
            length_3d,
            length_flat,
            error: if length_3d > 0.0 {
                (length_flat - length_3d).abs() / length_3d
            } else {
                0.0
            },
        })
        .collect()
}
