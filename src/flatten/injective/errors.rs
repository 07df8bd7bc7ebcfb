//! Why the flip-free flattening could not run.

/// Errors of [`flip_free_flatten`](super::solver::flip_free_flatten) and
/// [`flip_free_solve`](super::solver::flip_free_solve).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InjectiveError {
    /// The model is closed: the Tutte start needs a boundary loop to place on a circle.
    #[error("a flip-free start needs a boundary; the part is closed")]
    Closed,
    /// The start has flipped or degenerate triangles: the barrier is infinite there.
    #[error("the start of a flip-free minimisation has {flipped} flipped triangles")]
    StartNotInjective {
        /// Its flipped or degenerate triangles.
        flipped: usize,
    },
    /// A sparse system could not be factored.
    #[error("a sparse system of the flip-free flattening could not be factored ({reason})")]
    Factorisation {
        /// What faer reported.
        reason: String,
    },
}

impl InjectiveError {
    /// A factorisation error with faer's report.
    pub(super) fn factorisation(reason: String) -> Self {
        Self::Factorisation { reason }
    }
}
