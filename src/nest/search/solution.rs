//! A solution of the search: the sequence of copies, where each went, and the collision engine of
//! each bin (sheet, or the one roll).

use glam::DVec2;

use crate::nest::collision::Pose;

/// A copy as placed in a solution.
#[derive(Debug, Clone, Copy)]
pub(super) struct Placed {
    pub(super) bin: usize,
    pub(super) pose: Pose,
    pub(super) translation: DVec2,
    /// Right edge of the inflated shape.
    pub(super) right: f64,
}

/// A full or partial solution: the sequence, where each copy went, and the engines per bin.
#[derive(Clone)]
pub(super) struct Solution<E> {
    pub(super) order: Vec<usize>,
    /// Parallel to the first positions of `order`; `None` for a copy left out (strip shrinking).
    pub(super) placed: Vec<Option<Placed>>,
    pub(super) bins: Vec<E>,
}

impl<E> Solution<E> {
    /// Sheets (bins) that hold at least one placed copy: one past the highest bin used.
    pub(super) fn bins_in_use(&self) -> usize {
        self.placed
            .iter()
            .flatten()
            .map(|placed| placed.bin + 1)
            .max()
            .unwrap_or(0)
    }

    /// A solution with nothing placed yet.
    pub(super) fn empty(order: Vec<usize>) -> Self {
        Self {
            order,
            placed: Vec::new(),
            bins: Vec::new(),
        }
    }
}
