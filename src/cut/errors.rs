//! Errors of the cut stage: every variant says what was asked and what to do about it.

use crate::flatten::FlattenError;

/// An error of cutting, seaming or re-flattening a part.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CutError {
    /// A cut was asked along a boundary edge, which is open already.
    #[error("edge {}-{} is on the boundary and cannot be cut", vertices[0], vertices[1])]
    BoundaryEdge {
        /// The edge's vertices.
        vertices: [u32; 2],
    },
    /// A cut was asked along a fold-line edge.
    #[error(
        "edge {}-{} lies on a fold line, which is never cut; move the seam off the fold line",
        vertices[0],
        vertices[1]
    )]
    FoldLine {
        /// The edge's vertices.
        vertices: [u32; 2],
    },
    /// The cut would separate the part into pieces.
    #[error("the cut would separate the part into pieces")]
    Disconnects,
    /// The cut duplicates no vertex, so it opens nothing (a single edge inside the surface).
    #[error("the cut opens nothing: a slit of one interior edge cannot be represented")]
    OpensNothing,
    /// Rebuilding the cut model failed (an internal inconsistency).
    #[error("the cut model is invalid: {0}")]
    InvalidResult(String),
    /// `--seams pieces` was asked of a part with a cut sidecar.
    #[error(
        "--seams pieces cuts the part along plane sections and keeps no user seam or no-cut \
         region: remove the part's cut sidecar, or use --seams auto"
    )]
    PiecesWithSidecar,
    /// The surface has handles: no seam graph for it is built automatically.
    #[error(
        "the surface has genus {genus} (it has handles, like a torus): automatic seams handle only \
         surfaces without handles (closed like a sphere, or with boundaries like a ring); give seams \
         that cut every handle, or cut it into pieces with --seams pieces"
    )]
    HigherGenus {
        /// Number of handles.
        genus: i64,
    },
    /// A user seam could not be laid on the surface.
    #[error(
        "seam {seam} cannot be laid on the surface between its points {from} and {to} without \
         crossing a fold line or a no-cut region, or it would separate the part; move it"
    )]
    SeamNotLaid {
        /// Index of the seam among those given.
        seam: usize,
        /// Index of the seam point the failing stretch starts at.
        from: usize,
        /// Index of the seam point it ends at.
        to: usize,
    },
    /// No automatic seam avoids the fold lines and no-cut regions.
    #[error(
        "the surface must be opened by a seam, but every seam path crosses a fold line or a no-cut \
         region; give a seam"
    )]
    NoSeam,
    /// A user seam has fewer than two points.
    #[error("seam {seam} has {points} point(s); a seam needs at least two")]
    SeamTooShort {
        /// Index of the seam.
        seam: usize,
        /// Its point count.
        points: usize,
    },
    /// Flattening the (cut) part failed.
    #[error(transparent)]
    Flatten(#[from] FlattenError),
}
