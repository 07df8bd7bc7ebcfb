//! Flattening by the energy model of Wang, Smith and Yuen (2002): a facet model in, a flat
//! pattern (one 2D position per vertex, same indexing) and its accuracy out.
//!
//! Two solvers minimise the same spring energy (Eq. 1-3):
//! - [`Solver::Paper`] follows the paper step by step: InitFlatten with EnergyRelease over the
//!   growing system after each triangle (N = 50), then EnergyRelease by explicit integration
//!   (Eq. 10-15) with the paper's stopping rule. For reproduction, on small meshes.
//! - [`Solver::Fast`] (the default) builds the initial pattern with a neighbourhood release (near
//!   linear) and minimises the energy with [`FastSolver`]: local-global iterations on the
//!   prefactored spring Laplacian with Anderson acceleration and an orientation guard (see
//!   [`fast`] and `docs/solver.md`). When its pattern has flipped triangles, the part is
//!   flattened again without any by [`injective`] (a Tutte start, the same energy plus an
//!   orientation barrier, projected Newton with flip-free steps; `docs/injective.md`).

mod accuracy;
pub mod energy_release;
mod entry;
mod errors;
pub mod fast;
mod flattened;
pub mod fold_lines;
pub mod grain;
pub mod init_flatten;
pub mod injective;
pub mod isolines;
mod options;
pub mod orient;
pub mod outline;
#[cfg(test)]
mod samples;
mod springs;
pub mod stiffness;

pub use accuracy::{Accuracy, DEFAULT_TOLERANCE, boundary_comes_within};
pub use energy_release::{EnergyRelease, ReleaseOutcome, ReleaseParameters, StopReason};
pub use entry::{
    flatten, flatten_from, flatten_unrepaired, flatten_unrepaired_from, overlap_free_flatten,
    with_squeezed_triangles_opened,
};
pub use errors::FlattenError;
pub use fast::{FastError, FastOptions, FastOutcome, FastSolver, FillOrder, fast_solve};
pub use flattened::{FlattenStats, Flattened};
pub use init_flatten::{InitRelease, init_flatten};
pub use options::{FlattenOptions, Solver};
pub use springs::{PAPER_SPRING_CONSTANT, SpringSystem};
pub use stiffness::Stiffness;
