//! The fast solver of phase two: minimises the paper's spring energy (Eq. 1 and 3)
//! `E = Σ_edges ½ C_ij (|P_i P_j| − d_ij)²` over the flat positions, keeping every triangle
//! positively oriented.
//!
//! Inputs: a facet model, its [`SpringSystem`](crate::flatten::SpringSystem) (rest lengths `d_ij` in model units, constants
//! `C_ij > 0`) and an initial pattern (one 2D position per model vertex, model units), such as the
//! one [`super::init_flatten()`] builds. Output: the pattern, moved in place to a lower energy, and a
//! [`FastOutcome`] (iterations, why it stopped, energy before and after). Preconditions: the model
//! is connected (every [`FacetModel`](crate::mesh::FacetModel) is); the constants are positive.
//!
//! Method: local-global iterations on the spring energy (the static case of "fast mass-spring",
//! Liu, Bargteil, O'Brien and Kavan 2013). The local step gives each spring the rest vector
//! `r_ij = d_ij (P_i − P_j) / |P_i − P_j|` (its current direction, its rest length); the global
//! step minimises `Σ ½ C_ij |P_i − P_j − r_ij|²` over the positions, a linear system `L P = b`
//! with the spring Laplacian `L` (weights `C_ij`), which is constant: it is factored once by
//! faer's sparse Cholesky with one vertex held (the energy does not change under translation;
//! AMD ordering, or a [`FillOrder`] handed down from a model this one was cut from),
//! and each iteration costs one forward and back substitution for the two coordinates. The local
//! step can only lower the energy (it is the minimum over the directions) and so can the global
//! step, so the plain iteration `G` never raises it. Anderson acceleration (type II, depth `m`,
//! Walker and Ni 2011) extrapolates from the last `m` iterates, with the safeguard of Peng et al.
//! (2018): an accelerated iterate is kept only if its energy is below the current one and it
//! flips no triangle; otherwise the plain step is taken and the history is cleared.
//!
//! Orientation: a candidate pattern that makes a positively oriented triangle non-positive is
//! never accepted. The plain step is then shortened (halved, toward the current pattern) until no
//! triangle flips; the spring energy along that segment stays at or below the current energy (it is
//! bounded by the global step's convex quadratic, which equals the energy at the current pattern),
//! so the guard never raises the energy. Triangles already flipped in the initial pattern are
//! allowed to unflip but are not forced to: a triangle, once positive, stays positive.
//!
//! Convergence: the solver stops ([`StopReason::Converged`](crate::flatten::StopReason::Converged)) when the energy fell by at most
//! [`FastOptions::energy_tolerance`] (relative, default 1e-4) over the last [`ENERGY_WINDOW`]
//! iterations, or when the plain step, a preconditioned gradient step
//! (`G(P) − P = −L⁻¹ ∇E(P)`), has a root-mean-square length of at most
//! [`FastOptions::step_tolerance`] times the mean rest length (this one ends developable and
//! already converged inputs, whose energy is near zero, at once). It also stops when the plain step
//! no longer lowers the energy in floating point ([`StopReason::EnergyStalled`](crate::flatten::StopReason::EnergyStalled)), when the
//! orientation guard blocks every step ([`StopReason::OrientationBlocked`](crate::flatten::StopReason::OrientationBlocked)), or after
//! [`FastOptions::max_iterations`] ([`StepBudget`](crate::flatten::StopReason::StepBudget)). The energy returned is
//! that of the pattern returned, never above the initial one. The paper's `E_S`/`E_C` tolerance
//! is not a stopping rule here: iterations are cheap, so the energy is minimised, not merely
//! brought within 1 %.
//!
//! Cost: the factorisation is done once per [`FastSolver`]; an iteration is linear in the mesh size
//! besides the substitutions (proportional to the factor's size), and runs its per-edge and
//! per-vertex loops on rayon, summed in a fixed order so results do not depend on the threads.
//! Memory: the factor (2.0 million values for the 50k vertices of the 100k-triangle fender, with
//! faer's AMD ordering), one rest vector per spring, and `2m + 6` position arrays.

mod anderson;
mod chunked;
mod laplacian;
mod options;
mod solver;

pub use laplacian::{FastError, FillOrder};
pub use options::{
    DEFAULT_ANDERSON_DEPTH, DEFAULT_ENERGY_TOLERANCE, DEFAULT_MAX_ITERATIONS,
    DEFAULT_STEP_TOLERANCE, ENERGY_WINDOW, FastOptions,
};
pub use solver::{FastOutcome, FastSolver, fast_solve};
