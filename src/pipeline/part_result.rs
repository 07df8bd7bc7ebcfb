//! A flattened part: its job, the cut model's pattern and figures, its seams and cuts with the
//! way back to the input's vertices, and its pattern (outline, fold and cut lines, grain,
//! energies).

use crate::cut::{Cut, CutStop, Seam, UncutPattern};
use crate::flatten::Flattened;
use crate::pattern::{Pattern, PatternFile, PatternOptions, part_contours};

use super::load::PartJob;
use super::rejection::rejection_reasons;

/// A flattened part.
#[derive(Debug, Clone)]
pub struct PartResult {
    /// What was flattened: its model and stiffness are those after seams and cuts.
    pub job: PartJob,
    /// The pattern of the cut model and its figures.
    pub flattened: Flattened,
    /// Seams made to open the part.
    pub seams: Vec<Seam>,
    /// Crest-line cuts made.
    pub cuts: Vec<Cut>,
    /// Why cutting stopped.
    pub cut_stop: CutStop,
    /// The part before its first crest-line cut, when one was made.
    pub uncut: Option<UncutPattern>,
    /// For each vertex of the cut model, the vertex of the loaded model it copies (for a vertex a
    /// smoothed cut inserted, a nearby one: see [`crate::cut::CutResult::original_vertex`]).
    pub original_vertex: Vec<u32>,
    /// Edges of the cut model that are sides of a crest-line cut.
    pub cut_edges: Vec<usize>,
    /// The part's pattern: what is cut, drawn and nested.
    pub pattern: Pattern,
}

impl PartResult {
    /// The part's pattern file (`<part>.pattern.json`): its drawing and grain direction, its
    /// thickness in mm, the pattern `options` its cut contours are made with, and whether it is
    /// rejected at `tolerance` ([`Self::rejection_reasons`]).
    pub fn pattern_file(&self, options: &PatternOptions, tolerance: f64) -> PatternFile {
        let job = &self.job;
        PatternFile {
            drawing: self.pattern.drawing.clone(),
            grain_degrees: self.pattern.grain_degrees,
            thickness_mm: job
                .attributes
                .thickness
                .map(|thickness| thickness * job.units.millimetres()),
            options: *options,
            rejected: !self.rejection_reasons(tolerance, options).is_empty(),
        }
    }

    /// Every reason to reject this part at `tolerance` ([`rejection_reasons`]), the time
    /// limit if it ended the cut loop ([`CutStop::TimeLimit`]), and a cut contour that cannot
    /// be drawn with the pattern `options` (a hole collapsed below the chord tolerance, a seam
    /// allowance that closes a hole): such a part gets no cut file, the others are written. A
    /// sheet-metal part's E_S and E_C compare its flat pattern with its skin, whose bends
    /// differ from the flat by their allowance by design: only flipped triangles and overlap
    /// reject it.
    pub fn rejection_reasons(&self, tolerance: f64, options: &PatternOptions) -> Vec<String> {
        let tolerance = if self.job.sheet.is_some() {
            f64::INFINITY
        } else {
            tolerance
        };
        let mut reasons = rejection_reasons(&self.flattened.stats.accuracy, tolerance);
        if self.cut_stop == CutStop::TimeLimit {
            reasons.push(format!(
                "the time limit was reached after {:.0} s (--time-limit)",
                self.flattened.stats.seconds
            ));
        }
        if let Err(error) = part_contours(&self.pattern.drawing, options) {
            reasons.push(format!("its cut contour cannot be drawn: {error}"));
        }
        reasons
    }

    /// Whether the part meets `tolerance`: E_S and E_C within it (any error for a sheet-metal
    /// part, see [`Self::rejection_reasons`]) and no overlap.
    pub fn tolerance_met(&self, tolerance: f64) -> bool {
        let accuracy = &self.flattened.stats.accuracy;
        if self.job.sheet.is_some() {
            !accuracy.overlap
        } else {
            accuracy.within(tolerance)
        }
    }
}
