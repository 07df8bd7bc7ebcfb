//! Local stiffness (paper §3): "the higher the accuracy desired, the larger the value of the
//! spring constants". A factor per edge multiplies the spring constant; fold lines and user
//! regions raise it where their length or shape must be kept.

use glam::DVec3;

pub use crate::cad::DEFAULT_FOLD_STIFFNESS;
use crate::geometry::distance_to_segment_3d;
use crate::mesh::{FacetModel, NONE};

/// A stiffness factor per edge of a facet model (1 = the plain spring constant).
#[derive(Debug, Clone, PartialEq)]
pub struct Stiffness {
    factors: Vec<f64>,
}

impl Stiffness {
    /// Factor 1 on every edge.
    pub fn uniform(model: &FacetModel) -> Self {
        Self {
            factors: vec![1.0; model.edges().len()],
        }
    }

    /// Stiffness from explicit factors, one per edge of the model they are used with (a cut
    /// model carries its edges' factors over from the model it was cut from).
    pub fn from_factors(factors: Vec<f64>) -> Self {
        Self { factors }
    }

    /// The factors, one per edge of the model.
    pub fn factors(&self) -> &[f64] {
        &self.factors
    }

    /// Raises to `factor` (never lowers) every edge for which `selects(edge)` is true.
    pub fn raise_where(&mut self, factor: f64, mut selects: impl FnMut(usize) -> bool) {
        for (e, current) in self.factors.iter_mut().enumerate() {
            if selects(e) {
                *current = current.max(factor);
            }
        }
    }

    /// Raises to `factor` every edge whose midpoint lies within `half_width` (model units) of an
    /// edge of fold line `fold_line` (edges tagged with it on the model), and the fold edges
    /// themselves.
    pub fn raise_near_fold_line(
        &mut self,
        model: &FacetModel,
        fold_line: u32,
        half_width: f64,
        factor: f64,
    ) {
        let positions = model.positions();
        let fold_segments: Vec<[DVec3; 2]> = model
            .edges()
            .iter()
            .zip(model.edge_fold_lines())
            .filter(|&(_, &line)| line == fold_line && line != NONE)
            .map(|(&[a, b], _)| [positions[a as usize], positions[b as usize]])
            .collect();
        if fold_segments.is_empty() {
            return;
        }
        self.raise_where(factor, |e| {
            let [a, b] = model.edges()[e];
            let midpoint = (positions[a as usize] + positions[b as usize]) * 0.5;
            model.edge_fold_lines()[e] == fold_line
                || fold_segments
                    .iter()
                    .any(|&[p, q]| distance_to_segment_3d(midpoint, p, q) <= half_width)
        });
    }
}
