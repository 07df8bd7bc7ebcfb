//! Errors of the nesting stage. Every variant says what was wrong with the input and what to do.

use thiserror::Error;

/// Why nesting could not start or could not place every part.
#[derive(Debug, Error)]
pub enum NestError {
    /// Nothing to place: no items, or every quantity is zero.
    #[error("nothing to nest: give at least one part with a quantity of 1 or more")]
    EmptyInput,
    /// The stock has a zero, negative, non-finite or absurdly large dimension.
    #[error(
        "the stock {dimension} is {value}: give a positive size in mm, at most {} mm",
        super::stock::MAXIMUM_STOCK_MM
    )]
    InvalidStock {
        /// Which dimension (`sheet width`, `sheet height`, `roll width`).
        dimension: &'static str,
        /// The value given.
        value: f64,
    },
    /// The gap is negative or not finite.
    #[error("the gap is {0} mm: give a gap of 0 mm or more")]
    InvalidGap(f64),
    /// The rotation step is below [`crate::nest::MINIMUM_ROTATION_STEP_DEGREES`], not finite, or
    /// larger than a full turn.
    #[error(
        "part '{item}': rotation step {step} degrees is invalid: give a step in [{}, 360]",
        super::rotations::MINIMUM_ROTATION_STEP_DEGREES
    )]
    InvalidRotationStep {
        /// The part's name.
        item: String,
        /// The step given, in degrees.
        step: f64,
    },
    /// A fixed list of rotations is empty or holds a non-finite angle.
    #[error(
        "part '{item}': its list of allowed rotations is empty or not finite: list at least one angle in degrees"
    )]
    InvalidRotationList {
        /// The part's name.
        item: String,
    },
    /// The grain direction is not a finite angle.
    #[error("part '{item}': its grain direction {degrees} degrees is not a finite angle")]
    InvalidGrain {
        /// The part's name.
        item: String,
        /// The grain direction given, degrees.
        degrees: f64,
    },
    /// The outline is not a usable simple polygon.
    #[error(
        "part '{item}': {defect}: give a closed, non-self-intersecting outline with at least 3 distinct points"
    )]
    InvalidOutline {
        /// The part's name.
        item: String,
        /// What is wrong with it.
        defect: String,
    },
    /// The part does not fit on the stock in any allowed rotation, even alone.
    #[error(
        "part '{item}' ({width:.3} x {height:.3} mm in its best allowed rotation, gap included) does not fit on the stock \
         ({stock}): use larger sheets or a wider roll, a smaller gap, or allow more rotations"
    )]
    PartTooLarge {
        /// The part's name.
        item: String,
        /// Width of its smallest allowed-rotation bounding box plus twice the gap.
        width: f64,
        /// Height of that bounding box plus twice the gap.
        height: f64,
        /// The stock, described for the user.
        stock: String,
    },
    /// The collision engine refused a shape (for example a sliver too thin for its f32 geometry).
    #[error(
        "part '{item}': the collision engine rejected its outline ({reason}): simplify or clean the outline"
    )]
    CollisionShape {
        /// The part's name.
        item: String,
        /// The engine's message.
        reason: String,
    },
    /// The search found no position for a part that fits the stock on its own. Not expected:
    /// it points to a degenerate outline or a defect in the search.
    #[error(
        "the search found no position for a part that fits the stock: check for degenerate outlines and report the input"
    )]
    NoPosition,
    /// An instance file could not be read or parsed.
    #[error("{path}: {reason}")]
    Instance {
        /// The file.
        path: String,
        /// What is wrong, with the field, line and column where known.
        reason: String,
    },
}
