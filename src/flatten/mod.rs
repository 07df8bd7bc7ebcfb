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
//!   [`fast`] and `docs/solver.md`).

pub mod accuracy;
pub mod energy_release;
pub mod fast;
pub mod fold_lines;
pub mod grain;
pub mod init_flatten;
pub mod isolines;
pub mod orient;
pub mod outline;
pub mod springs;
pub mod stiffness;

use std::time::Instant;

use glam::DVec2;
use serde::Serialize;

pub use accuracy::Accuracy;
pub use energy_release::{EnergyRelease, ReleaseOutcome, ReleaseParameters, StopReason};
pub use fast::{FastError, FastOptions, FastOutcome, FastSolver, fast_solve};
pub use init_flatten::{InitRelease, init_flatten};
pub use springs::{PAPER_SPRING_CONSTANT, SpringSystem};
pub use stiffness::Stiffness;

use crate::mesh::FacetModel;
use crate::progress::Progress;

/// Default permissible `E_S` and `E_C` (1 %, the paper's).
pub const DEFAULT_TOLERANCE: f64 = 0.01;

/// Which procedure minimises the energy.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Solver {
    /// Near-linear initial pattern, then a fast minimiser of the same energy.
    #[default]
    Fast,
    /// The paper's procedure, step by step (quadratic phase one).
    Paper,
}

/// Options of [`flatten`]. `Default` is the only source of defaults.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FlattenOptions {
    /// The solver.
    pub solver: Solver,
    /// Permissible `E_S` and `E_C` (fractions); default [`DEFAULT_TOLERANCE`].
    pub tolerance: f64,
    /// Spring constant `C` before stiffness factors; default [`PAPER_SPRING_CONSTANT`].
    pub spring_constant: f64,
    /// Step budget of phase two; default 1000 (the paper's).
    pub max_steps: usize,
    /// Permissible relative energy variation `ε`; default 0.05 % (the paper's).
    pub energy_variation: f64,
    /// Time step `Δt` of the explicit integration; default 0.01 (the paper's).
    pub time_step: f64,
    /// Steps of EnergyRelease after each triangle in the paper's phase one; default 50.
    pub init_release_steps: usize,
    /// Options of the fast solver's phase two (the step budget there is its own).
    pub fast: FastOptions,
}

impl Default for FlattenOptions {
    fn default() -> Self {
        Self {
            solver: Solver::default(),
            tolerance: DEFAULT_TOLERANCE,
            spring_constant: PAPER_SPRING_CONSTANT,
            max_steps: energy_release::PAPER_STEP_BUDGET,
            energy_variation: energy_release::PAPER_ENERGY_VARIATION,
            time_step: energy_release::PAPER_TIME_STEP,
            init_release_steps: init_flatten::PAPER_INIT_RELEASE_STEPS,
            fast: FastOptions::default(),
        }
    }
}

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

/// What a flattening produced besides the pattern.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FlattenStats {
    /// Accuracy of the final pattern.
    pub accuracy: Accuracy,
    /// Accuracy of the initial pattern (after phase one).
    pub initial_accuracy: Accuracy,
    /// Spring energy `Σ ½ C (l − d)²` of the final pattern.
    pub energy: f64,
    /// Iterations of phase two.
    pub iterations: usize,
    /// Why phase two stopped.
    pub stop_reason: StopReason,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// A flat pattern: `positions[v]` is the flat position of model vertex `v`.
#[derive(Debug, Clone, PartialEq)]
pub struct Flattened {
    /// Flat positions, model units, bounding box starting at the origin.
    pub positions: Vec<DVec2>,
    /// Figures.
    pub stats: FlattenStats,
}

/// Flattens a facet model with per-edge stiffness factors.
pub fn flatten(
    model: &FacetModel,
    stiffness: &Stiffness,
    options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<Flattened, FlattenError> {
    let started = Instant::now();
    check_input(model, stiffness)?;
    let springs = SpringSystem::new(model, stiffness.factors(), options.spring_constant);
    let release = match options.solver {
        Solver::Paper => InitRelease::WholeSystem {
            steps: options.init_release_steps,
            time_step: options.time_step,
        },
        Solver::Fast => InitRelease::Neighbourhood {
            sweeps: init_flatten::NEIGHBOURHOOD_SWEEPS,
        },
    };
    let positions = init_flatten(model, &springs, release, progress);
    finish(model, &springs, positions, options, started)
}

/// Flattens a facet model from given flat positions (a warm start: phase one is skipped), for
/// the cut → re-flatten loop, where the pattern before a cut is a good start for the cut model.
/// `initial[v]` is the start of vertex `v`; a missing or extra entry is an error.
pub fn flatten_from(
    model: &FacetModel,
    stiffness: &Stiffness,
    initial: &[DVec2],
    options: &FlattenOptions,
) -> Result<Flattened, FlattenError> {
    let started = Instant::now();
    check_input(model, stiffness)?;
    if initial.len() != model.vertex_count() {
        return Err(FlattenError::InitialMismatch {
            expected: model.vertex_count(),
            found: initial.len(),
        });
    }
    let springs = SpringSystem::new(model, stiffness.factors(), options.spring_constant);
    finish(model, &springs, initial.to_vec(), options, started)
}

/// Refuses closed surfaces and stiffness maps of another model.
fn check_input(model: &FacetModel, stiffness: &Stiffness) -> Result<(), FlattenError> {
    if model.is_closed() {
        return Err(FlattenError::ClosedSurface);
    }
    if stiffness.factors().len() != model.edges().len() {
        return Err(FlattenError::StiffnessMismatch {
            expected: model.edges().len(),
            found: stiffness.factors().len(),
        });
    }
    Ok(())
}

/// Phase two from the initial pattern `positions`, then the figures.
fn finish(
    model: &FacetModel,
    springs: &SpringSystem,
    mut positions: Vec<DVec2>,
    options: &FlattenOptions,
    started: Instant,
) -> Result<Flattened, FlattenError> {
    let initial_accuracy = Accuracy::measure(model, &positions);
    let (iterations, stop_reason) = match options.solver {
        Solver::Paper => {
            let outcome = relax(model, springs, &mut positions, options);
            (outcome.steps, outcome.stop_reason)
        }
        Solver::Fast => minimise(model, springs, &mut positions, options)?,
    };
    orient::move_to_origin(&mut positions);
    let stats = FlattenStats {
        accuracy: Accuracy::measure(model, &positions),
        initial_accuracy,
        energy: springs.energy(&positions),
        iterations,
        stop_reason,
        seconds: started.elapsed().as_secs_f64(),
    };
    Ok(Flattened { positions, stats })
}

/// Phase two of the paper's solver: EnergyRelease over the whole model.
fn relax(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &mut [DVec2],
    options: &FlattenOptions,
) -> ReleaseOutcome {
    let energy = EnergyRelease::new(model, springs);
    let system = energy.whole_system();
    let parameters = ReleaseParameters {
        time_step: options.time_step,
        energy_variation: options.energy_variation,
        tolerance: options.tolerance,
        max_steps: options.max_steps,
    };
    energy.release(&system, positions, &parameters, true)
}

/// Phase two of the fast solver: the spring energy minimised by [`FastSolver`]; returns the
/// iterations and why it stopped.
fn minimise(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &mut [DVec2],
    options: &FlattenOptions,
) -> Result<(usize, StopReason), FlattenError> {
    let outcome = fast_solve(model, springs, positions, options.fast)?;
    Ok((outcome.iterations, outcome.stop_reason))
}
