//! The flip-free flattening of a part with a boundary: a pattern with every triangle positively
//! oriented, by construction.
//!
//! The fast solver never flips a triangle that is positive in its start, but it keeps the flips
//! of a start that has them (phase one folds strongly curved parts). This module builds a pattern
//! without any:
//! 1. an injective start, the Tutte embedding with the longest boundary loop on a circle by arc
//!    length, clamped cotangent weights, and each other loop (a hole) filled by a virtual fan for
//!    the start only ([`tutte_embedding`]);
//! 2. the paper's spring energy (with the part's per-edge constants, fold stiffness included)
//!    plus a barrier per triangle on its area ratio ([`Barrier`]: zero above a threshold,
//!    infinite at zero area), minimised by projected Newton in two stages, the
//!    [`SHAPING_BARRIER`] (every compressed triangle, so the pattern unfolds from the Tutte start
//!    instead of collapsing into slivers) and then the [`ORIENTATION_BARRIER`] (below a tenth of
//!    the rest area only): each spring's Hessian projected to be positive semi-definite, the
//!    barrier's Gauss-Newton part, one sparse Cholesky factorisation per iteration on a pattern
//!    analysed once;
//! 3. every step capped by the largest step that keeps all triangles positively oriented
//!    ([`max_flip_free_step`], Smith and Schaefer 2015), then shortened until the objective falls
//!    enough (Armijo): no iterate can flip a triangle.
//!
//! A pattern with only a few flipped triangles is first repaired where they are
//! ([`repaired_locally`]: the vertices near them placed afresh and relaxed, the rest held); the
//! whole flip-free flattening runs when that fails.
//!
//! See `docs/injective.md`.

mod barrier;
mod boundary;
mod errors;
mod local;
mod lscm;
mod solver;
mod sparse;
mod step;
mod tutte;

pub use barrier::{Barrier, OPENING_BARRIER, ORIENTATION_BARRIER, SHAPING_BARRIER, SLIVER_BARRIER};
pub use boundary::{BOUNDARY_REACH, BoundaryBarrier, Contact, point_segment_distance};
pub use errors::InjectiveError;
pub use local::{
    LOCAL_ITERATIONS, LOCAL_REPAIR_SHARE, REPAIR_RINGS, near_triangles, repaired_locally,
};
pub use lscm::conformal_map;
pub use solver::{
    FLIP_FREE_FRACTION, FlipFreeSettings, InjectiveOutcome, MAX_NEWTON_ITERATIONS,
    NEWTON_DECREMENT_TOLERANCE, NEWTON_ENERGY_TOLERANCE, NEWTON_WINDOW, Outline, flip_free_flatten,
    flip_free_solve, flip_free_solve_moving,
};
pub use step::{max_flip_free_step, smallest_positive_root, triangle_flip_step};
pub use tutte::{SMALLEST_WEIGHT, tutte_embedding};
