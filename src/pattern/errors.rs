//! Errors of the pattern stage. Every variant names the part and says what to change.

/// Why a part's contours could not be made.
#[derive(Debug, thiserror::Error)]
pub enum PatternError {
    /// A coordinate is NaN or infinite.
    #[error(
        "part `{part}`: the {contour} has a non-finite coordinate (NaN or infinity); the flat pattern is broken upstream, re-run flattening"
    )]
    NonFiniteCoordinate {
        /// Name of the part.
        part: String,
        /// Which contour ("outer contour", "hole 2", "fold line 1", ...).
        contour: String,
    },
    /// A contour collapsed: a closed one has fewer than three distinct points or no area, an open
    /// one fewer than two distinct points.
    #[error(
        "part `{part}`: the {contour} is degenerate (too few distinct points or no area); remove it or fix the pattern"
    )]
    DegenerateContour {
        /// Name of the part.
        part: String,
        /// Which contour ("outer contour", "hole 2", "fold line 1", ...).
        contour: String,
    },
    /// The chord tolerance is not a positive finite length.
    #[error("chord tolerance {value} mm is not a positive length; pass e.g. --dxf-chord 0.01")]
    InvalidChordTolerance {
        /// The rejected value, in mm.
        value: f64,
    },
    /// The seam allowance is not a positive finite length.
    #[error("seam allowance {value} mm is not a positive length; pass e.g. --seam-allowance 10")]
    InvalidSeamAllowance {
        /// The rejected value, in mm.
        value: f64,
    },
    /// The seam allowance fills a hole completely, so the hole would not be cut.
    #[error(
        "part `{part}`: a seam allowance of {allowance} mm closes hole {hole}; use a smaller --seam-allowance or remove the hole"
    )]
    SeamAllowanceClosesHole {
        /// Name of the part.
        part: String,
        /// Index of the hole (from 1).
        hole: usize,
        /// The seam allowance, in mm.
        allowance: f64,
    },
    /// Offsetting the outer contour did not give exactly one closed contour (the outline crosses
    /// itself).
    #[error(
        "part `{part}`: offsetting the outline by the seam allowance gave {pieces} contours instead of one; the outline crosses itself, fix the pattern"
    )]
    SeamOffsetFailed {
        /// Name of the part.
        part: String,
        /// How many contours the offset gave.
        pieces: usize,
    },
}
