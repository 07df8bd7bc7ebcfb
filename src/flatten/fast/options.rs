//! Options of the fast solver and their defaults.

/// Default iteration budget.
pub const DEFAULT_MAX_ITERATIONS: usize = 400;
/// Default stopping threshold on the plain step's root-mean-square length, as a fraction of the
/// mean rest length.
pub const DEFAULT_STEP_TOLERANCE: f64 = 1e-6;
/// Default stopping threshold on the relative energy decrease over the last
/// [`ENERGY_WINDOW`] iterations.
pub const DEFAULT_ENERGY_TOLERANCE: f64 = 1e-4;
/// Iterations over which the energy decrease is measured for [`FastOptions::energy_tolerance`].
pub const ENERGY_WINDOW: usize = 5;
/// Default Anderson depth `m` (iterates remembered); 0 turns the acceleration off.
pub const DEFAULT_ANDERSON_DEPTH: usize = 5;

/// Options of the fast solver. `Default` gives the documented defaults.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FastOptions {
    /// Largest number of iterations; default [`DEFAULT_MAX_ITERATIONS`].
    pub max_iterations: usize,
    /// Stop when the plain step's root-mean-square length is at most this fraction of the mean
    /// rest length; default [`DEFAULT_STEP_TOLERANCE`].
    pub step_tolerance: f64,
    /// Stop when the energy fell by at most this fraction of itself over the last
    /// [`ENERGY_WINDOW`] iterations; default [`DEFAULT_ENERGY_TOLERANCE`].
    pub energy_tolerance: f64,
    /// Anderson depth `m`; default [`DEFAULT_ANDERSON_DEPTH`].
    pub anderson_depth: usize,
    /// When the solver stops ([`crate::flatten::StopReason::TimeLimit`]); none by default.
    #[serde(skip)]
    pub deadline: crate::progress::Deadline,
}

impl Default for FastOptions {
    fn default() -> Self {
        Self {
            max_iterations: DEFAULT_MAX_ITERATIONS,
            step_tolerance: DEFAULT_STEP_TOLERANCE,
            energy_tolerance: DEFAULT_ENERGY_TOLERANCE,
            anderson_depth: DEFAULT_ANDERSON_DEPTH,
            deadline: crate::progress::Deadline::NONE,
        }
    }
}
