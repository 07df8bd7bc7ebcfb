//! The objective of the search and its comparisons: the area left out (strip shrinking), the
//! sheets used, then the length used on the last, with the tolerances that make two equal.

use super::problem::{LENGTH_TOLERANCE_RELATIVE, Problem};
use super::solution::Solution;
use crate::nest::collision::JaguaEngine;

/// The objective, compared lexicographically: net area of the copies left out (strip shrinking
/// only), sheets used, then the length used on the last.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Cost {
    pub(super) unplaced: f64,
    pub(super) bins: usize,
    pub(super) length: f64,
}

impl Problem<'_> {
    /// The cost of a solution: the area left out, the bins used, the length used on the last.
    pub(super) fn cost(&self, solution: &Solution<JaguaEngine>) -> Cost {
        let bins = solution.bins_in_use();
        let length = solution
            .placed
            .iter()
            .flatten()
            .filter(|placed| placed.bin + 1 == bins)
            .map(|placed| placed.right)
            .fold(0.0, f64::max);
        let unplaced = (solution.placed.iter().zip(&solution.order))
            .filter(|(placed, _)| placed.is_none())
            .map(|(_, &copy)| self.items[self.copies[copy].item].area())
            .sum();
        Cost {
            unplaced,
            bins,
            length,
        }
    }

    /// Threshold accepting: whether a neighbour costing `candidate` replaces the current solution
    /// costing `current`: it must use no more sheets and be at most `threshold` longer.
    pub(super) fn acceptable(&self, candidate: Cost, current: Cost, threshold: f64) -> bool {
        candidate.bins < current.bins
            || (candidate.bins == current.bins && candidate.length <= current.length + threshold)
    }

    /// Two areas closer than this are equal.
    fn area_tolerance(&self) -> f64 {
        LENGTH_TOLERANCE_RELATIVE * self.scale * self.scale
    }

    /// Whether `a` leaves strictly less area out than `b` (strip shrinking).
    pub(super) fn less_left_out(&self, a: Cost, b: Cost) -> bool {
        a.unplaced < b.unplaced - self.area_tolerance()
    }

    /// Whether `a` is strictly better than `b`.
    pub(super) fn better(&self, a: Cost, b: Cost) -> bool {
        if (a.unplaced - b.unplaced).abs() > self.area_tolerance() {
            return a.unplaced < b.unplaced;
        }
        a.bins < b.bins
            || (a.bins == b.bins && a.length < b.length - LENGTH_TOLERANCE_RELATIVE * self.scale)
    }
}
