//! What flattening produces: the flat pattern, one position per model vertex, and its figures.

use glam::DVec2;
use serde::Serialize;

use super::accuracy::Accuracy;
use super::energy_release::StopReason;

/// What a flattening produced besides the pattern.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FlattenStats {
    /// Accuracy of the final pattern.
    pub accuracy: Accuracy,
    /// Accuracy of the initial pattern (after phase one).
    pub initial_accuracy: Accuracy,
    /// Spring energy `Σ ½ C (l − d)²` of the final pattern.
    pub energy: f64,
    /// Iterations of phase two.
    pub iterations: usize,
    /// Why phase two stopped.
    pub stop_reason: StopReason,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// A flat pattern: `positions[v]` is the flat position of model vertex `v`.
#[derive(Debug, Clone, PartialEq)]
pub struct Flattened {
    /// Flat positions, model units, bounding box starting at the origin.
    pub positions: Vec<DVec2>,
    /// Figures.
    pub stats: FlattenStats,
}
