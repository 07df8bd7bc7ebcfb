//! What cutting returns: the cut part, its pattern, its seams and cuts with their figures, why
//! the loop stopped and the part before its first crest-line cut.

use glam::DVec3;
use serde::Serialize;

use super::seam::SeamKind;
use crate::flatten::{Flattened, Stiffness};
use crate::mesh::FacetModel;

/// Energy and errors of a pattern, before or after a cut.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CutFigures {
    /// Spring energy of the pattern.
    pub energy: f64,
    /// `E_S` (Eq. 4), a fraction.
    pub area_error: f64,
    /// `E_C` (Eq. 6), a fraction.
    pub shape_error: f64,
}

impl CutFigures {
    /// The figures of a pattern.
    pub(super) fn of(flattened: &Flattened) -> Self {
        Self {
            energy: flattened.stats.energy,
            area_error: flattened.stats.accuracy.area_error,
            shape_error: flattened.stats.accuracy.shape_error,
        }
    }
}

/// One crest-line cut.
#[derive(Debug, Clone, PartialEq)]
pub struct Cut {
    /// The cut as a 3D polyline, model units.
    pub points: Vec<DVec3>,
    /// The vertices of the input model the polyline runs through, one per point. A cut crosses
    /// faces (it is straightened, docs/cutting.md): a point where it crosses an edge is a vertex
    /// the cut inserted, given here as in [`CutResult::original_vertex`].
    pub vertices: Vec<u32>,
    /// Its 3D length.
    pub length: f64,
    /// The pattern before the cut.
    pub before: CutFigures,
    /// The pattern after the cut.
    pub after: CutFigures,
}

/// One seam.
#[derive(Debug, Clone, PartialEq)]
pub struct Seam {
    /// Why it was made.
    pub kind: SeamKind,
    /// The seam as a 3D polyline, model units.
    pub points: Vec<DVec3>,
    /// Its 3D length.
    pub length: f64,
}

/// Why the cutting stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CutStop {
    /// `E_S` and `E_C` are within tolerance (and the pattern does not overlap).
    ToleranceMet,
    /// [`super::options::CutOptions::max_cuts`] cuts were made.
    CutBudget,
    /// No candidate cut lowered the error, or the last cut steps did not release enough of the
    /// spring energy together (4 steps, 1 %: see `docs/cutting.md`).
    NoBetterCut,
    /// The part's time limit passed ([`crate::flatten::FlattenOptions::deadline`]) before it
    /// was within tolerance: the pattern is the last one made.
    TimeLimit,
}

/// The cut part and its pattern.
#[derive(Debug, Clone)]
pub struct CutResult {
    /// The facet model after every seam and cut.
    pub model: FacetModel,
    /// Its stiffness factors (carried over from the input's edges).
    pub stiffness: Stiffness,
    /// For each vertex of `model`, the input vertex it copies. A vertex a smoothed cut inserted
    /// where it crosses an edge (docs/cutting.md, "Smooth cuts") copies no input vertex: it gives
    /// the input vertex of the nearer end of the edge it split (a nearby input vertex, not one at
    /// its position).
    pub original_vertex: Vec<u32>,
    /// Edges of `model` (indices, ascending) that are sides of a crest-line cut: boundary edges
    /// both of whose ends copy a vertex of a cut.
    pub cut_edges: Vec<usize>,
    /// The pattern of `model`.
    pub flattened: Flattened,
    /// Seams, in the order they were cut.
    pub seams: Vec<Seam>,
    /// Crest-line cuts, in the order they were made.
    pub cuts: Vec<Cut>,
    /// Why cutting stopped.
    pub stop: CutStop,
    /// The part as it was before the first crest-line cut, when one was made.
    pub uncut: Option<UncutPattern>,
}

/// A part opened by its seams and flattened, before any crest-line cut: what the energy report
/// shows as "before cutting".
#[derive(Debug, Clone)]
pub struct UncutPattern {
    /// The facet model after its seams.
    pub model: FacetModel,
    /// Its stiffness factors.
    pub stiffness: Stiffness,
    /// Its pattern.
    pub flattened: Flattened,
}

impl CutResult {
    /// Total 3D length of the crest-line cuts.
    pub fn total_cut_length(&self) -> f64 {
        self.cuts.iter().fold(0.0, |total, cut| total + cut.length)
    }
}
