//! Cutting (paper §6.3): seams that open closed and ring surfaces, then crest-line cuts of the
//! energy map, each followed by a new flattening, until `E_S` and `E_C` are within tolerance or
//! the cut budget is spent.
//!
//! [`cut_and_flatten`] is the one-shot entry point:
//! 1. user seams ([`CutConstraints::seams`]) are laid on the mesh and cut;
//! 2. automatic seams ([`seam`], `cut_graph`) open the surface to a disk: one per ring loop; on a
//!    closed surface a tree–cotree cut graph first if it has handles, then a Steiner tree through
//!    the regions where its curvature concentrates, or, on a smooth one, around the bisector of
//!    its two farthest points but a hinge; the crest-line cut budget defaults to 8 per π of the
//!    curvature left ([`default_cut_budget`]);
//! 3. the part is flattened; while it is over tolerance and cuts are left, every candidate line of
//!    its energy map and of its tension map (stretched springs only: where a cut opens) (`crest`)
//!    is straightened across faces, the mesh refined along it ([`straighten`], `smooth_cut`: smooth
//!    cuts, not edge zig-zags; an extension carries straight on from its cut), cut and briefly
//!    flattened, warm-started from the current pattern, and the most promising
//!    are flattened on (`best_cut`, docs/cutting.md); among those that lower the error (`max(E_S, E_C)`, an
//!    overlapping pattern counting as worse than any other) the shortest that meets the tolerance
//!    is kept, or else the one of largest measured gain `ΔE / L^LENGTH_EXPONENT`; a line from the
//!    inner end of an earlier cut extends that cut (`crest_cuts`); a part of more than
//!    [`PLAN_ABOVE_TRIANGLES`] triangles plans its cuts on a coarse remesh of its pattern first
//!    and lays them on the part (`coarse`), the loop going on from there;
//! 4. the cut model, its pattern and every cut with its figures before and after come back.
//!
//! Cuts never run along or across a fold line (no vertex of a fold-line edge is crossed) nor
//! through a no-cut region; a developable part within tolerance gets no cut.

mod coarse;
mod crest;
mod crest_cuts;
mod cut_graph;
mod cut_loop;
mod density;
mod errors;
mod opening;
mod options;
pub mod paths;
mod piece;
mod pieces;
mod result;
pub mod seam;
mod smooth_cut;
pub mod split;
mod state;
pub mod straighten;
mod t_junctions;
mod trials;
mod union_start;

pub use coarse::{PLAN_ABOVE_TRIANGLES, PLAN_TRIANGLES};
pub use crest::{DEFAULT_CANDIDATES, DEFAULT_DART_FLOOR};
pub use cut_loop::{cut_and_flatten, default_cut_budget, total_absolute_curvature};
pub use errors::CutError;
pub use options::{
    CAP_CURVATURE, CUT_LOOP_ENERGY_TOLERANCE, CUTS_PER_CAP, CutConstraints, CutOptions,
    DEFAULT_MAX_CUTS, EXTENSIONS_PER_CUT, FULL_TRIALS, LENGTH_EXPONENT, NoCutRegion,
    PIECES_CURVATURE, SCREEN_ITERATIONS, TRIAL_BUDGET, TRIAL_STEP_TOLERANCE, WIDER_SEARCH,
};
pub use pieces::{
    GLUE_SCREEN_FACTOR, MAX_SECTIONS, MIN_BALANCE, MIN_PIECE_TRIANGLES, SCREEN_FACTOR, SHIFT,
    SMALLEST_PIECE, cut_into_pieces,
};
pub use result::{Cut, CutFigures, CutResult, CutStop, Seam, UncutPattern};
pub use seam::{FLAT_DEFICIT, SeamKind};
