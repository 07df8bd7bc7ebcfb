//! The fast solver itself: precomputation (vertex-spring incidence, the factored Laplacian) and
//! the safeguarded, accelerated local-global iteration.

use faer::Mat;
use glam::DVec2;
use rayon::prelude::*;

use super::anderson::Anderson;
use super::chunked::{CHUNK, rms_distance};
use super::laplacian::{
    FastError, FillOrder, HELD_VERTEX, LaplacianFactor, factor_laplacian, unknown_vertex,
};
use super::options::{ENERGY_WINDOW, FastOptions};
use crate::flatten::accuracy::signed_area;
use crate::flatten::energy_release::StopReason;
use crate::flatten::springs::SpringSystem;
use crate::mesh::{FacetModel, compressed_rows};

/// Halvings of a blocked plain step before the orientation guard is declared to block it.
const MAX_STEP_HALVINGS: usize = 30;

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

/// Flag in [`FastSolver::incident`] for the spring's second end.
const SECOND_END: u32 = 1 << 31;

impl<'a> FastSolver<'a> {
    /// Precomputes the solver: the vertex-spring incidence and the factored spring Laplacian.
    pub fn new(
        model: &'a FacetModel,
        springs: &'a SpringSystem,
        options: FastOptions,
    ) -> Result<Self, FastError> {
        Self::in_order(model, springs, options, None)
    }

    /// As [`FastSolver::new`], the Laplacian factored in the elimination order `order` gives it
    /// when given (a model made from the order's by appending vertices: [`FillOrder`]).
    pub fn in_order(
        model: &'a FacetModel,
        springs: &'a SpringSystem,
        options: FastOptions,
        order: Option<&FillOrder>,
    ) -> Result<Self, FastError> {
        let (incident_offsets, incident) = vertex_springs(model.vertex_count(), springs);
        let factor = factor_laplacian(model.vertex_count(), springs, order)?;
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
            if self.options.deadline.passed() {
                return self.outcome(iteration, StopReason::TimeLimit, initial_energy, energy);
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

#[cfg(test)]
mod tests {
    use crate::flatten::accuracy::Accuracy;
    use crate::flatten::fast::options::DEFAULT_ANDERSON_DEPTH;
    use crate::flatten::fast::solver::*;
    use crate::flatten::init_flatten::{InitRelease, NEIGHBOURHOOD_SWEEPS, init_flatten};
    use crate::flatten::samples::{sample, uniform_springs};
    use crate::progress::NoProgress;

    /// Developable samples must come out isometric to this `E_S` and `E_C`.
    const DEVELOPABLE_ERROR: f64 = 1e-6;

    fn initial_pattern(model: &FacetModel, springs: &SpringSystem) -> Vec<DVec2> {
        let release = InitRelease::Neighbourhood {
            sweeps: NEIGHBOURHOOD_SWEEPS,
        };
        init_flatten(model, springs, release, &NoProgress)
    }

    /// Solves from the phase-one pattern and checks the invariants every run must keep.
    fn solve_sample(name: &str) -> (FacetModel, Vec<DVec2>, FastOutcome) {
        let model = sample(name);
        let springs = uniform_springs(&model);
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
        let accuracy = Accuracy::measure(&model, &positions);
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
            let accuracy = Accuracy::measure(&model, &positions);
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
        let springs = uniform_springs(&model);
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
        assert_eq!(Accuracy::measure(&model, &positions).flipped, 0);
    }

    #[test]
    fn the_solver_is_deterministic_and_reusable() {
        let model = sample("hemisphere.obj");
        let springs = uniform_springs(&model);
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
        let springs = uniform_springs(&model);
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
}
