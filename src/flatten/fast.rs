//! The fast solver of phase two: minimises the paper's spring energy (Eq. 1 and 3)
//! `E = Σ_edges ½ C_ij (|P_i P_j| − d_ij)²` over the flat positions, keeping every triangle
//! positively oriented.
//!
//! Inputs: a facet model, its [`SpringSystem`] (rest lengths `d_ij` in model units, constants
//! `C_ij > 0`) and an initial pattern (one 2D position per model vertex, model units), such as the
//! one [`super::init_flatten()`] builds. Output: the pattern, moved in place to a lower energy, and a
//! [`FastOutcome`] (iterations, why it stopped, energy before and after). Preconditions: the model
//! is connected (every [`FacetModel`] is); the constants are positive.
//!
//! Method: local-global iterations on the spring energy (the static case of "fast mass-spring",
//! Liu, Bargteil, O'Brien and Kavan 2013). The local step gives each spring the rest vector
//! `r_ij = d_ij (P_i − P_j) / |P_i − P_j|` (its current direction, its rest length); the global
//! step minimises `Σ ½ C_ij |P_i − P_j − r_ij|²` over the positions, a linear system `L P = b`
//! with the spring Laplacian `L` (weights `C_ij`), which is constant: it is factored once by
//! faer's sparse Cholesky with one vertex held (the energy does not change under translation),
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
//! Convergence: the solver stops ([`StopReason::Converged`]) when the energy fell by at most
//! [`FastOptions::energy_tolerance`] (relative, default 1e-4) over the last [`ENERGY_WINDOW`]
//! iterations, or when the plain step, a preconditioned gradient step
//! (`G(P) − P = −L⁻¹ ∇E(P)`), has a root-mean-square length of at most
//! [`FastOptions::step_tolerance`] times the mean rest length (this one ends developable and
//! already converged inputs, whose energy is near zero, at once). It also stops when the plain step
//! no longer lowers the energy in floating point ([`StopReason::EnergyStalled`]), when the
//! orientation guard blocks every step ([`StopReason::OrientationBlocked`]), or after
//! [`FastOptions::max_iterations`] ([`StepBudget`](StopReason::StepBudget)). The energy returned is
//! that of the pattern returned, never above the initial one. The paper's `E_S`/`E_C` tolerance
//! is not a stopping rule here: iterations are cheap, so the energy is minimised, not merely
//! brought within 1 %.
//!
//! Cost: the factorisation is done once per [`FastSolver`]; an iteration is linear in the mesh size
//! besides the substitutions (proportional to the factor's size), and runs its per-edge and
//! per-vertex loops on rayon, summed in a fixed order so results do not depend on the threads.
//! Memory: the factor (2.0 million values for the 50k vertices of the 100k-triangle fender, with
//! faer's AMD ordering), one rest vector per spring, and `2m + 6` position arrays.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::cholesky::{LltRef, SymbolicCholesky, factorize_symbolic_cholesky};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, Mat, Par, Side};
use glam::DVec2;
use rayon::prelude::*;

use super::StopReason;
use super::accuracy::signed_area;
use super::springs::SpringSystem;
use crate::mesh::{FacetModel, compressed_rows};

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

/// Halvings of a blocked plain step before the orientation guard is declared to block it.
const MAX_STEP_HALVINGS: usize = 30;
/// Relative Tikhonov term on the Anderson least-squares problem, against its own scale.
const ANDERSON_REGULARISATION: f64 = 1e-10;
/// Springs or vertices per rayon task; the partial sums are added in chunk order.
const CHUNK: usize = 4096;

/// Options of the fast solver. `Default` gives the documented defaults.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
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
}

impl Default for FastOptions {
    fn default() -> Self {
        Self {
            max_iterations: DEFAULT_MAX_ITERATIONS,
            step_tolerance: DEFAULT_STEP_TOLERANCE,
            energy_tolerance: DEFAULT_ENERGY_TOLERANCE,
            anderson_depth: DEFAULT_ANDERSON_DEPTH,
        }
    }
}

/// What a run of the fast solver did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastOutcome {
    /// Iterations taken (global solves after the first).
    pub iterations: usize,
    /// Why it stopped.
    pub stop_reason: StopReason,
    /// Spring energy of the initial pattern.
    pub initial_energy: f64,
    /// Spring energy of the returned pattern (never above `initial_energy`).
    pub energy: f64,
}

/// Errors of the fast solver's precomputation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FastError {
    /// The spring Laplacian could not be factored: a constant is not positive or not finite.
    #[error(
        "the spring system could not be factored ({reason}): every spring constant must be \
         positive and finite"
    )]
    Factorisation {
        /// What faer reported.
        reason: String,
    },
}

/// The precomputed fast solver of one spring system: reuse it to re-solve from new patterns.
#[derive(Debug)]
pub struct FastSolver<'a> {
    model: &'a FacetModel,
    springs: &'a SpringSystem,
    options: FastOptions,
    /// Cholesky factor of the spring Laplacian without the held vertex's row and column: its
    /// structure (with the fill-reducing ordering) and its values.
    factor: LaplacianFactor,
    /// Per vertex, the range of its entries in `incident`.
    incident_offsets: Vec<u32>,
    /// Springs at each vertex: the spring index, with [`SECOND_END`] set when the vertex is the
    /// spring's second end.
    incident: Vec<u32>,
    mean_rest_length: f64,
}

/// The vertex whose position the global step holds (the energy is translation invariant).
const HELD_VERTEX: usize = 0;
/// Flag in [`FastSolver::incident`] for the spring's second end.
const SECOND_END: u32 = 1 << 31;

impl<'a> FastSolver<'a> {
    /// Precomputes the solver: the vertex-spring incidence and the factored spring Laplacian.
    pub fn new(
        model: &'a FacetModel,
        springs: &'a SpringSystem,
        options: FastOptions,
    ) -> Result<Self, FastError> {
        let (incident_offsets, incident) = vertex_springs(model.vertex_count(), springs);
        let factor = factor_laplacian(model.vertex_count(), springs)?;
        let total: f64 = springs.rest_lengths.iter().sum();
        Ok(Self {
            model,
            springs,
            options,
            factor,
            incident_offsets,
            incident,
            mean_rest_length: total / springs.len().max(1) as f64,
        })
    }

    /// Minimises the spring energy from `positions` (one per model vertex), in place.
    pub fn solve(&self, positions: &mut [DVec2]) -> FastOutcome {
        assert_eq!(
            positions.len(),
            self.model.vertex_count(),
            "one position per vertex"
        );
        let mut targets = vec![DVec2::ZERO; self.springs.len()];
        let mut energy = self.local_step(positions, &mut targets);
        let initial_energy = energy;
        let mut positive = self.positive_triangles(positions);
        let mut plain = self.global_step(&targets, positions[HELD_VERTEX]);
        let mut anderson = Anderson::new(self.options.anderson_depth, positions.len());
        anderson.push(positions, &plain);
        let mut candidate = vec![DVec2::ZERO; positions.len()];
        let mut candidate_targets = vec![DVec2::ZERO; self.springs.len()];
        let threshold = self.options.step_tolerance * self.mean_rest_length;
        let mut history = vec![energy];
        for iteration in 0..self.options.max_iterations {
            let window_start = history[history.len().saturating_sub(ENERGY_WINDOW + 1)];
            let stalled = history.len() > ENERGY_WINDOW
                && window_start - energy <= self.options.energy_tolerance * energy;
            if stalled || rms_distance(positions, &plain) <= threshold {
                return self.outcome(iteration, StopReason::Converged, initial_energy, energy);
            }
            let extrapolated = anderson.extrapolate(&plain, &mut candidate);
            let accelerated_energy = (extrapolated && self.admissible(&candidate, &positive))
                .then(|| self.local_step(&candidate, &mut candidate_targets));
            let candidate_energy = match accelerated_energy {
                Some(accelerated) if accelerated < energy => accelerated,
                _ => {
                    if extrapolated {
                        anderson.clear();
                    }
                    let step = PlainStep {
                        positions,
                        plain: &plain,
                        positive: &positive,
                        energy,
                    };
                    match self.plain_step(step, &mut candidate, &mut candidate_targets) {
                        Ok(plain_energy) => plain_energy,
                        Err(stop_reason) => {
                            return self.outcome(iteration, stop_reason, initial_energy, energy);
                        }
                    }
                }
            };
            positions.copy_from_slice(&candidate);
            std::mem::swap(&mut targets, &mut candidate_targets);
            energy = candidate_energy;
            history.push(energy);
            positive = self.positive_triangles(positions);
            plain = self.global_step(&targets, positions[HELD_VERTEX]);
            anderson.push(positions, &plain);
        }
        self.outcome(
            self.options.max_iterations,
            StopReason::StepBudget,
            initial_energy,
            energy,
        )
    }

    fn outcome(
        &self,
        iterations: usize,
        stop_reason: StopReason,
        initial_energy: f64,
        energy: f64,
    ) -> FastOutcome {
        FastOutcome {
            iterations,
            stop_reason,
            initial_energy,
            energy,
        }
    }

    /// The local step: writes `C_ij r_ij` for every spring into `targets` and returns the spring
    /// energy at `positions`.
    fn local_step(&self, positions: &[DVec2], targets: &mut [DVec2]) -> f64 {
        let springs = self.springs;
        let partial: Vec<f64> = targets
            .par_chunks_mut(CHUNK)
            .enumerate()
            .map(|(chunk, out)| {
                let mut energy = 0.0;
                for (k, target) in out.iter_mut().enumerate() {
                    let e = chunk * CHUNK + k;
                    let [a, b] = springs.edges[e];
                    let delta = positions[a as usize] - positions[b as usize];
                    let length = delta.length();
                    let (rest, constant) = (springs.rest_lengths[e], springs.constants[e]);
                    let direction = if length > 0.0 {
                        delta / length
                    } else {
                        DVec2::X
                    };
                    *target = direction * (constant * rest);
                    energy += 0.5 * constant * (length - rest) * (length - rest);
                }
                energy
            })
            .collect();
        partial.iter().sum()
    }

    /// The global step: the positions minimising `Σ ½ C |P_i − P_j − r_ij|²` with the held vertex
    /// at `held`.
    fn global_step(&self, targets: &[DVec2], held: DVec2) -> Vec<DVec2> {
        let mut right: Vec<DVec2> = vec![DVec2::ZERO; self.model.vertex_count()];
        right.par_iter_mut().enumerate().for_each(|(v, sum)| {
            let range = self.incident_offsets[v] as usize..self.incident_offsets[v + 1] as usize;
            for &entry in &self.incident[range] {
                let e = (entry & !SECOND_END) as usize;
                let [a, b] = self.springs.edges[e];
                let other = if entry & SECOND_END == 0 { b } else { a } as usize;
                let sign = if entry & SECOND_END == 0 { 1.0 } else { -1.0 };
                *sum += targets[e] * sign;
                if other == HELD_VERTEX {
                    *sum += held * self.springs.constants[e];
                }
            }
        });
        let unknowns = right.len() - 1;
        let mut rhs = Mat::from_fn(unknowns, 2, |i, axis| right[unknown_vertex(i)][axis]);
        self.factor.solve_in_place(rhs.as_mut());
        let mut solved = vec![held; right.len()];
        for (i, position) in solved.iter_mut().enumerate().skip(1) {
            let row = i - 1;
            *position = DVec2::new(rhs[(row, 0)], rhs[(row, 1)]);
        }
        solved
    }

    /// Whether each triangle is positively oriented at `positions`.
    fn positive_triangles(&self, positions: &[DVec2]) -> Vec<bool> {
        self.model
            .triangles()
            .par_iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| positions[v as usize]);
                signed_area(a, b, c) > 0.0
            })
            .collect()
    }

    /// True if no triangle positive in `positive` is non-positive at `positions`.
    fn admissible(&self, positions: &[DVec2], positive: &[bool]) -> bool {
        !self
            .model
            .triangles()
            .par_iter()
            .zip(positive.par_iter())
            .any(|(t, &was_positive)| {
                let [a, b, c] = t.map(|v| positions[v as usize]);
                was_positive && signed_area(a, b, c) <= 0.0
            })
    }

    /// The safeguarded plain step: writes the (possibly shortened) step into `candidate` and its
    /// spring vectors into `targets`, and returns its energy; or why no step lowers the energy.
    fn plain_step(
        &self,
        step: PlainStep<'_>,
        candidate: &mut [DVec2],
        targets: &mut [DVec2],
    ) -> Result<f64, StopReason> {
        if !self.shortened_plain_step(step.positions, step.plain, step.positive, candidate) {
            return Err(StopReason::OrientationBlocked);
        }
        let energy = self.local_step(candidate, targets);
        if energy >= step.energy {
            return Err(StopReason::EnergyStalled);
        }
        Ok(energy)
    }

    /// Writes into `candidate` the plain step from `positions` toward `plain`, halved until it is
    /// admissible; false if it is still blocked after [`MAX_STEP_HALVINGS`].
    fn shortened_plain_step(
        &self,
        positions: &[DVec2],
        plain: &[DVec2],
        positive: &[bool],
        candidate: &mut [DVec2],
    ) -> bool {
        let mut fraction = 1.0;
        for _ in 0..=MAX_STEP_HALVINGS {
            candidate
                .par_iter_mut()
                .zip(positions.par_iter().zip(plain.par_iter()))
                .for_each(|(c, (&p, &g))| *c = p + (g - p) * fraction);
            if self.admissible(candidate, positive) {
                return true;
            }
            fraction *= 0.5;
        }
        false
    }
}

/// The current iterate, as the plain step sees it.
struct PlainStep<'a> {
    /// The current pattern.
    positions: &'a [DVec2],
    /// Its image under the plain iteration `G`.
    plain: &'a [DVec2],
    /// Which triangles are positively oriented in it.
    positive: &'a [bool],
    /// Its spring energy.
    energy: f64,
}

/// Minimises the spring energy from `positions` in place: [`FastSolver::new`] then
/// [`FastSolver::solve`].
pub fn fast_solve(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &mut [DVec2],
    options: FastOptions,
) -> Result<FastOutcome, FastError> {
    Ok(FastSolver::new(model, springs, options)?.solve(positions))
}

/// The model vertex of unknown `i` of the reduced system (every vertex but the held one).
fn unknown_vertex(i: usize) -> usize {
    i + 1
}

/// The springs at each vertex, in compressed rows: offsets and spring indices flagged with
/// [`SECOND_END`] at their second end.
fn vertex_springs(vertex_count: usize, springs: &SpringSystem) -> (Vec<u32>, Vec<u32>) {
    let entries = springs
        .edges
        .iter()
        .enumerate()
        .flat_map(|(e, &[a, b])| [(a, e as u32), (b, e as u32 | SECOND_END)]);
    compressed_rows(vertex_count, entries)
}

/// The Cholesky factor `L = U Uᵀ` of the reduced spring Laplacian.
#[derive(Debug)]
struct LaplacianFactor {
    symbolic: SymbolicCholesky<u32>,
    values: Vec<f64>,
}

impl LaplacianFactor {
    /// Solves `L X = B` in place for the columns of `rhs`, in one pass over the factor.
    /// Sequential: the substitutions are bound by reading the factor from memory (at 400k
    /// triangles, two columns in one pass took as long as one column per thread), and faer's
    /// fine-grained parallel substitution spent most of its time waiting on rayon latches.
    fn solve_in_place(&self, rhs: faer::MatMut<'_, f64>) {
        let factor = LltRef::new(&self.symbolic, &self.values);
        let scratch = self
            .symbolic
            .solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq);
        let mut buffer = MemBuffer::new(scratch);
        factor.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut buffer));
    }
}

/// Factors the spring Laplacian (weights `C_ij`) without the held vertex's row and column; the
/// lower triangle is given.
fn factor_laplacian(
    vertex_count: usize,
    springs: &SpringSystem,
) -> Result<LaplacianFactor, FastError> {
    let unknown = |v: u32| (v as usize).checked_sub(1);
    let mut entries = Vec::with_capacity(3 * springs.len());
    for (&[a, b], &constant) in springs.edges.iter().zip(&springs.constants) {
        let (ia, ib) = (unknown(a), unknown(b));
        for i in [ia, ib].into_iter().flatten() {
            entries.push(Triplet::new(i as u32, i as u32, constant));
        }
        if let (Some(i), Some(j)) = (ia, ib) {
            entries.push(Triplet::new(i.max(j) as u32, i.min(j) as u32, -constant));
        }
    }
    let unknowns = vertex_count - 1;
    let failure = |reason: String| FastError::Factorisation { reason };
    let matrix = SparseColMat::<u32, f64>::try_new_from_triplets(unknowns, unknowns, &entries)
        .map_err(|error| failure(format!("{error:?}")))?;
    let symbolic = factorize_symbolic_cholesky(
        matrix.symbolic(),
        Side::Lower,
        Default::default(),
        Default::default(),
    )
    .map_err(|error| failure(format!("{error:?}")))?;
    let mut values = vec![0.0; symbolic.len_val()];
    // Sequential, as the substitutions: on 2 shared cores faer's rayon factorisation was slower
    // (400k fender, whole flatten: 3.4-4.0 s sequential against 3.4-4.3 s with rayon).
    let parallelism = Par::Seq;
    let scratch = symbolic.factorize_numeric_llt_scratch::<f64>(parallelism, Default::default());
    symbolic
        .factorize_numeric_llt(
            &mut values,
            matrix.as_ref(),
            Side::Lower,
            Default::default(),
            parallelism,
            MemStack::new(&mut MemBuffer::new(scratch)),
            Default::default(),
        )
        .map_err(|error| failure(format!("{error:?}")))?;
    Ok(LaplacianFactor { symbolic, values })
}

/// Root-mean-square distance between two patterns.
fn rms_distance(first: &[DVec2], second: &[DVec2]) -> f64 {
    let partial: Vec<f64> = first
        .par_chunks(CHUNK)
        .zip(second.par_chunks(CHUNK))
        .map(|(p, q)| p.iter().zip(q).map(|(&p, &q)| p.distance_squared(q)).sum())
        .collect();
    (partial.iter().sum::<f64>() / first.len().max(1) as f64).sqrt()
}

/// Dot product of two position arrays seen as vectors, summed in chunk order.
fn dot(first: &[DVec2], second: &[DVec2]) -> f64 {
    let partial: Vec<f64> = first
        .par_chunks(CHUNK)
        .zip(second.par_chunks(CHUNK))
        .map(|(p, q)| p.iter().zip(q).map(|(&p, &q)| p.dot(q)).sum())
        .collect();
    partial.iter().sum()
}

/// Anderson acceleration (type II) of the fixed-point map `G`: from the last iterates `x_k`
/// and their images `g_k = G(x_k)`, the next iterate is `g_k − ΔG γ` with `γ` minimising
/// `|f_k − ΔF γ|`, `f = g − x`, `ΔF` and `ΔG` the differences of successive `f` and `g`.
struct Anderson {
    depth: usize,
    /// Differences of residuals and of images, oldest first.
    residual_differences: Vec<Vec<DVec2>>,
    image_differences: Vec<Vec<DVec2>>,
    /// Dot products of the residual differences with each other, in the same order.
    gram: Vec<Vec<f64>>,
    /// The last residual and image.
    residual: Vec<DVec2>,
    image: Vec<DVec2>,
    has_last: bool,
}

impl Anderson {
    fn new(depth: usize, size: usize) -> Self {
        Self {
            depth,
            residual_differences: Vec::with_capacity(depth),
            image_differences: Vec::with_capacity(depth),
            gram: Vec::with_capacity(depth),
            residual: vec![DVec2::ZERO; size],
            image: vec![DVec2::ZERO; size],
            has_last: false,
        }
    }

    /// Forgets the history (after a rejected accelerated step).
    fn clear(&mut self) {
        self.residual_differences.clear();
        self.image_differences.clear();
        self.gram.clear();
        self.has_last = false;
    }

    /// Records the iterate `x` and its image `g`.
    fn push(&mut self, x: &[DVec2], g: &[DVec2]) {
        if self.depth == 0 {
            return;
        }
        if self.has_last {
            let (mut residual_difference, mut image_difference) =
                if self.residual_differences.len() == self.depth {
                    self.gram.remove(0);
                    for row in &mut self.gram {
                        row.remove(0);
                    }
                    (
                        self.residual_differences.remove(0),
                        self.image_differences.remove(0),
                    )
                } else {
                    (vec![DVec2::ZERO; x.len()], vec![DVec2::ZERO; x.len()])
                };
            residual_difference
                .par_iter_mut()
                .zip(image_difference.par_iter_mut())
                .enumerate()
                .for_each(|(i, (df, dg))| {
                    *df = (g[i] - x[i]) - self.residual[i];
                    *dg = g[i] - self.image[i];
                });
            let mut row: Vec<f64> = self
                .residual_differences
                .iter()
                .map(|other| dot(other, &residual_difference))
                .collect();
            row.push(dot(&residual_difference, &residual_difference));
            for (existing, &value) in self.gram.iter_mut().zip(&row) {
                existing.push(value);
            }
            self.gram.push(row);
            self.residual_differences.push(residual_difference);
            self.image_differences.push(image_difference);
        }
        self.residual
            .par_iter_mut()
            .zip(self.image.par_iter_mut())
            .enumerate()
            .for_each(|(i, (f, image))| {
                *f = g[i] - x[i];
                *image = g[i];
            });
        self.has_last = true;
    }

    /// Writes the accelerated iterate into `out`; false when there is no history or the
    /// least-squares problem is singular (then `out` is not meaningful).
    fn extrapolate(&self, image: &[DVec2], out: &mut [DVec2]) -> bool {
        let m = self.residual_differences.len();
        if m == 0 {
            return false;
        }
        let gram = Mat::from_fn(m, m, |i, j| {
            dot(&self.residual_differences[i], &self.residual_differences[j])
        });
        let trace: f64 = (0..m).map(|i| gram[(i, i)]).sum();
        let regularised = Mat::from_fn(m, m, |i, j| {
            gram[(i, j)]
                + if i == j {
                    ANDERSON_REGULARISATION * trace
                } else {
                    0.0
                }
        });
        let mut gamma = Mat::from_fn(m, 1, |i, _| {
            dot(&self.residual_differences[i], &self.residual)
        });
        let Ok(factor) = regularised.llt(Side::Lower) else {
            return false;
        };
        factor.solve_in_place(gamma.as_mut());
        if !(0..m).all(|i| gamma[(i, 0)].is_finite()) {
            return false;
        }
        out.par_iter_mut().enumerate().for_each(|(v, x)| {
            let mut value = image[v];
            for (k, difference) in self.image_differences.iter().enumerate() {
                value -= difference[v] * gamma[(k, 0)];
            }
            *x = value;
        });
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flatten::{InitRelease, init_flatten};
    use crate::pipeline::{RunOptions, load_parts};
    use crate::progress::NoProgress;

    /// Developable samples must come out isometric to this `E_S` and `E_C`.
    const DEVELOPABLE_ERROR: f64 = 1e-6;

    fn sample(name: &str) -> FacetModel {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("samples")
            .join(name);
        let mut parts = load_parts(&path, &RunOptions::default()).expect("sample loads");
        assert_eq!(parts.len(), 1, "{name} is one part");
        parts.remove(0).model
    }

    fn springs(model: &FacetModel) -> SpringSystem {
        SpringSystem::new(
            model,
            &vec![1.0; model.edges().len()],
            crate::flatten::PAPER_SPRING_CONSTANT,
        )
    }

    fn initial_pattern(model: &FacetModel, springs: &SpringSystem) -> Vec<DVec2> {
        let release = InitRelease::Neighbourhood {
            sweeps: crate::flatten::init_flatten::NEIGHBOURHOOD_SWEEPS,
        };
        init_flatten(model, springs, release, &NoProgress)
    }

    /// Solves from the phase-one pattern and checks the invariants every run must keep.
    fn solve_sample(name: &str) -> (FacetModel, Vec<DVec2>, FastOutcome) {
        let model = sample(name);
        let springs = springs(&model);
        let mut positions = initial_pattern(&model, &springs);
        let before = springs.energy(&positions);
        let outcome =
            fast_solve(&model, &springs, &mut positions, FastOptions::default()).expect("factors");
        let after = springs.energy(&positions);
        assert!(
            after <= before,
            "{name}: energy rose from {before} to {after}"
        );
        assert!(
            (after - outcome.energy).abs() <= 1e-9 * before.max(1.0),
            "{name}: reported energy {} is not the pattern's {after}",
            outcome.energy
        );
        let accuracy = crate::flatten::Accuracy::measure(&model, &positions);
        assert_eq!(accuracy.flipped, 0, "{name}: flipped triangles");
        (model, positions, outcome)
    }

    #[test]
    fn hemisphere_lowers_the_energy_without_flips() {
        let (_, _, outcome) = solve_sample("hemisphere.obj");
        assert!(outcome.energy < 0.7 * outcome.initial_energy, "{outcome:?}");
    }

    #[test]
    fn saddle_lowers_the_energy_without_flips() {
        let (_, _, outcome) = solve_sample("saddle.obj");
        assert!(outcome.energy < 0.7 * outcome.initial_energy, "{outcome:?}");
        assert_eq!(outcome.stop_reason, StopReason::Converged);
    }

    #[test]
    fn developable_samples_stay_isometric() {
        for name in ["cone_frustum.obj", "cylinder_segment.obj"] {
            let (model, positions, _) = solve_sample(name);
            let accuracy = crate::flatten::Accuracy::measure(&model, &positions);
            assert!(
                accuracy.area_error <= DEVELOPABLE_ERROR
                    && accuracy.shape_error <= DEVELOPABLE_ERROR,
                "{name}: {accuracy:?}"
            );
        }
    }

    #[test]
    fn a_distorted_start_reaches_the_same_minimum() {
        let (model, _, undistorted) = solve_sample("saddle.obj");
        let springs = springs(&model);
        let mut positions = initial_pattern(&model, &springs);
        for p in &mut positions {
            *p = DVec2::new(1.1 * p.x, 0.95 * p.y);
        }
        let outcome =
            fast_solve(&model, &springs, &mut positions, FastOptions::default()).expect("factors");
        assert!(
            outcome.energy <= undistorted.energy * (1.0 + 1e-4),
            "{outcome:?} against {undistorted:?}"
        );
        assert_eq!(
            crate::flatten::Accuracy::measure(&model, &positions).flipped,
            0
        );
    }

    #[test]
    fn the_solver_is_deterministic_and_reusable() {
        let model = sample("hemisphere.obj");
        let springs = springs(&model);
        let start = initial_pattern(&model, &springs);
        let solver = FastSolver::new(&model, &springs, FastOptions::default()).expect("factors");
        let (mut first, mut second) = (start.clone(), start);
        solver.solve(&mut first);
        solver.solve(&mut second);
        assert!(
            first
                .iter()
                .zip(&second)
                .all(|(a, b)| a.to_array() == b.to_array())
        );
    }

    #[test]
    fn acceleration_reaches_the_plain_iteration_minimum_faster() {
        let model = sample("saddle.obj");
        let springs = springs(&model);
        let start = initial_pattern(&model, &springs);
        let run = |anderson_depth| {
            let mut positions = start.clone();
            let options = FastOptions {
                anderson_depth,
                ..FastOptions::default()
            };
            fast_solve(&model, &springs, &mut positions, options).expect("factors")
        };
        let (plain, accelerated) = (run(0), run(DEFAULT_ANDERSON_DEPTH));
        assert!(
            accelerated.iterations < plain.iterations,
            "{plain:?} {accelerated:?}"
        );
        assert!(accelerated.energy <= plain.energy * (1.0 + 1e-3));
    }

    #[test]
    fn fast_ends_at_or_below_the_paper_solvers_energy() {
        use crate::flatten::{FlattenOptions, Solver, Stiffness, flatten};
        for name in ["hemisphere.obj", "saddle.obj"] {
            let model = sample(name);
            let stiffness = Stiffness::uniform(&model);
            let run = |solver| {
                let options = FlattenOptions {
                    solver,
                    ..FlattenOptions::default()
                };
                flatten(&model, &stiffness, &options, &NoProgress).expect("flattens")
            };
            let (fast, paper) = (run(Solver::Fast).stats, run(Solver::Paper).stats);
            assert!(fast.energy <= paper.energy, "{name}: {fast:?} {paper:?}");
            assert!(
                fast.accuracy.shape_error <= paper.accuracy.shape_error,
                "{name}: {fast:?} {paper:?}"
            );
            assert_eq!(fast.accuracy.flipped + paper.accuracy.flipped, 0, "{name}");
        }
    }
}
