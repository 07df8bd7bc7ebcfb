//! Errors of the flatten stage.

use super::fast::FastError;

/// Errors of the flatten stage.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FlattenError {
    /// The surface has no boundary.
    #[error(
        "the surface is closed (it has no boundary): it must be cut open before it can be flattened; \
         open it in the CAD system or give a mesh with a seam"
    )]
    ClosedSurface,
    /// The warm-start positions do not match the model.
    #[error("the initial pattern has {found} positions but the model has {expected} vertices")]
    InitialMismatch {
        /// Vertices of the model.
        expected: usize,
        /// Positions given.
        found: usize,
    },
    /// The stiffness map does not match the model.
    #[error("the stiffness map has {found} factors but the model has {expected} edges")]
    StiffnessMismatch {
        /// Edges of the model.
        expected: usize,
        /// Factors given.
        found: usize,
    },
    /// The fast solver could not be set up.
    #[error(transparent)]
    Fast(#[from] FastError),
}
