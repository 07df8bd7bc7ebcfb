//! Options of the flatten stage: the solver and its parameters, with their defaults.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::accuracy::DEFAULT_TOLERANCE;
use super::energy_release::{PAPER_ENERGY_VARIATION, PAPER_STEP_BUDGET, PAPER_TIME_STEP};
use super::fast::{FastOptions, FillOrder};
use super::init_flatten::PAPER_INIT_RELEASE_STEPS;
use super::springs::PAPER_SPRING_CONSTANT;
use crate::progress::Deadline;

/// Which procedure minimises the energy.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Solver {
    /// Near-linear initial pattern, then a fast minimiser of the same energy.
    #[default]
    Fast,
    /// The paper's procedure, step by step (quadratic phase one).
    Paper,
}

/// Options of [`flatten`](crate::flatten::flatten). `Default` is the only source of defaults.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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
    /// When phase two stops, whichever solver runs ([`super::StopReason::TimeLimit`]): set by
    /// the pipeline from a part's time limit; none by default, and never echoed.
    #[serde(skip)]
    pub deadline: Deadline,
    /// The fast solver's elimination order, for models made from the order's model by appending
    /// vertices (the cut loop's candidates: [`FillOrder`]); faer's AMD orders each model afresh
    /// when none is given (the default) or the model has fewer vertices. Never echoed.
    #[serde(skip)]
    pub fill_order: Option<Arc<FillOrder>>,
}

impl Default for FlattenOptions {
    fn default() -> Self {
        Self {
            solver: Solver::default(),
            tolerance: DEFAULT_TOLERANCE,
            spring_constant: PAPER_SPRING_CONSTANT,
            max_steps: PAPER_STEP_BUDGET,
            energy_variation: PAPER_ENERGY_VARIATION,
            time_step: PAPER_TIME_STEP,
            init_release_steps: PAPER_INIT_RELEASE_STEPS,
            fast: FastOptions::default(),
            deadline: Deadline::NONE,
            fill_order: None,
        }
    }
}
