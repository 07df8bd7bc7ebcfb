//! The pattern stage (after cut, before nest): a flattened part's flat outline, holes, fold and
//! cut lines, grain line and label anchor ([`part_pattern`]), and its cut contours: lines and
//! true arcs fitted within the chord tolerance, offset by the seam allowance
//! ([`part_contours`]). Nesting takes the contours that will be cut; export draws them. A
//! [`PatternFile`] is what nesting needs of a pattern, as written to `<part>.pattern.json`.
//!
//! Contours are bulge polylines ([`BulgeVertex`]): a point and the bulge (`tan(θ/4)` of the arc
//! to the next vertex, 0 for a line).

mod bulge;
mod contour;
mod contours;
mod drawing;
mod energy;
mod errors;
mod fold_polylines;
mod label;
mod options;
mod part_pattern;
mod pattern_file;
mod seam_allowance;

pub use bulge::{
    BulgeArc, BulgeVertex, STRAIGHT_BULGE, closed_length, distance_to_line_segment,
    distance_to_segment, polyline_bounds, sample_closed, sample_open, segment_bounds,
    segment_length,
};
pub use contour::{
    DEFAULT_CHORD_TOLERANCE, DUPLICATE_FRACTION, MAX_ARC_SWEEP, MIN_SEGMENT_LENGTH_IN_TOLERANCES,
    fit_closed, fit_open, signed_area,
};
pub use contours::{PartContours, part_contours};
pub use drawing::{LABEL_CHARACTER_WIDTH, PartDrawing};
pub use energy::{NEGLIGIBLE_STRAIN, VertexEnergy, negligible_vertex_energy};
pub use errors::PatternError;
pub use fold_polylines::fold_polylines;
pub use label::LabelPlacement;
pub use options::PatternOptions;
pub use part_pattern::{FlatShape, Pattern, PatternSource, part_pattern};
pub use pattern_file::{
    PATTERN_FILE_ENDING, PATTERN_FILE_FORMAT, PATTERN_FILE_VERSION, PatternFile, PatternFileError,
    REJECTED_MARK,
};
