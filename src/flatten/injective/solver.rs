//! The flip-free minimiser: projected Newton on the spring energy plus the orientation barrier,
//! each step capped by the flip-free bound and shortened until the energy falls enough.

use faer::Mat;
use glam::DVec2;

use super::barrier::{Barrier, ORIENTATION_BARRIER, SHAPING_BARRIER};
use super::boundary::{BoundaryBarrier, Contact};
use super::errors::InjectiveError;
use super::lscm::conformal_map;
use super::sparse::{Factor, SparsePattern};
use super::step::max_flip_free_step;
use super::tutte::tutte_embedding;
use crate::flatten::accuracy::{boundary_self_intersects, flipped_triangles, signed_area};
use crate::flatten::energy_release::StopReason;
use crate::flatten::springs::SpringSystem;
use crate::mesh::FacetModel;
use crate::progress::Deadline;

/// Newton iterations allowed at most (callers may allow fewer).
pub const MAX_NEWTON_ITERATIONS: usize = 300;
/// Converged when the objective fell by at most this fraction of itself over the last
/// [`NEWTON_WINDOW`] iterations.
pub const NEWTON_ENERGY_TOLERANCE: f64 = 1e-4;
/// Iterations over which [`NEWTON_ENERGY_TOLERANCE`] is measured.
pub const NEWTON_WINDOW: usize = 5;
/// Converged when the Newton decrement `−∇E·D` is at most this fraction of the objective.
pub const NEWTON_DECREMENT_TOLERANCE: f64 = 1e-10;
/// Every step starts at this fraction of the flip-free bound (or at the full Newton step if it
/// is shorter), so that no triangle reaches zero area even in round-off.
pub const FLIP_FREE_FRACTION: f64 = 0.8;
/// The sufficient decrease (Armijo) constant of the backtracking line search.
const ARMIJO: f64 = 1e-4;
/// Halvings of a step before the line search gives up.
const MAX_HALVINGS: usize = 60;
/// Diagonal damping added to the Hessian, relative to its mean diagonal entry: the objective
/// does not change under rotation, so the Hessian is singular at the minimum.
const DAMPING: f64 = 1e-9;
/// Factor by which the damping grows when the Hessian cannot be factored.
const DAMPING_GROWTH: f64 = 100.0;
/// Attempts at factoring one Hessian, the damping growing between them.
const FACTOR_ATTEMPTS: usize = 6;
/// The vertex held in place (the objective does not change under translation).
const HELD_VERTEX: usize = 0;

/// What a run of the flip-free minimiser did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InjectiveOutcome {
    /// Newton iterations taken.
    pub iterations: usize,
    /// Why it stopped: [`StopReason::Converged`], [`StopReason::EnergyStalled`] (no step along
    /// the Newton direction lowered the objective), [`StopReason::StepBudget`] or
    /// [`StopReason::TimeLimit`] (the deadline passed).
    pub stop_reason: StopReason,
    /// Objective (spring energy plus barrier) of the start of the last stage.
    pub initial_objective: f64,
    /// Objective of the returned pattern (never above `initial_objective`).
    pub objective: f64,
    /// Spring energy `Σ ½ C (l − d)²` of the returned pattern.
    pub energy: f64,
}

/// The flip-free flattening of a part with a boundary, from two starts: its Tutte embedding
/// ([`tutte_embedding`]) and, when it has no flipped triangle (nor, with [`Outline::Kept`], a
/// crossing outline), its least-squares conformal map ([`conformal_map`]), which follows a long,
/// narrow part's shape where the Tutte start puts it on a circle. Each is minimised by
/// [`flip_free_solve`] in two stages of at most `max_iterations` Newton iterations each, with the
/// [`SHAPING_BARRIER`] (the Tutte start is far too small in places: the pattern unfolds without
/// collapsing triangles) and then the [`ORIENTATION_BARRIER`] (the spring energy's own minimum,
/// triangles kept from degenerating); the pattern of lower spring energy is kept (the Tutte one
/// on a tie). Every triangle of the returned pattern is positively oriented; the outcome's
/// iterations count every stage of both starts, its objectives are the kept pattern's last
/// stage's.
pub fn flip_free_flatten(
    model: &FacetModel,
    springs: &SpringSystem,
    max_iterations: usize,
    deadline: Deadline,
    outline: Outline,
) -> Result<(Vec<DVec2>, InjectiveOutcome), InjectiveError> {
    let minimise =
        |start: Vec<DVec2>| two_stages(model, springs, start, max_iterations, deadline, outline);
    let mut best = minimise(tutte_embedding(model)?)?;
    if let Some(start) = conformal_start(model, outline) {
        // A conformal start that does not factor or stalls leaves the Tutte pattern.
        if let Ok(other) = minimise(start) {
            let iterations = best.1.iterations + other.1.iterations;
            if other.1.energy < best.1.energy {
                best = other;
            }
            best.1.iterations = iterations;
        }
    }
    Ok(best)
}

/// The shaping then the orientation stage of [`flip_free_flatten`] from `positions`.
fn two_stages(
    model: &FacetModel,
    springs: &SpringSystem,
    mut positions: Vec<DVec2>,
    max_iterations: usize,
    deadline: Deadline,
    outline: Outline,
) -> Result<(Vec<DVec2>, InjectiveOutcome), InjectiveError> {
    let mut iterations = 0;
    let mut outcome = None;
    for barrier in [SHAPING_BARRIER, ORIENTATION_BARRIER] {
        let stage = flip_free_solve(
            model,
            springs,
            &mut positions,
            barrier,
            max_iterations,
            deadline,
            outline,
        )?;
        iterations += stage.iterations;
        outcome = Some(InjectiveOutcome {
            iterations,
            ..stage
        });
    }
    Ok((positions, outcome.expect("two stages")))
}

/// The least-squares conformal map of `model` ([`conformal_map`]) when it can start the flip-free
/// minimiser: no flipped or degenerate triangle (and, with [`Outline::Kept`], an outline that
/// does not cross itself).
fn conformal_start(model: &FacetModel, outline: Outline) -> Option<Vec<DVec2>> {
    let map = conformal_map(model).ok()?;
    let valid = map.iter().all(|p| p.is_finite())
        && flipped_triangles(model, &map) == 0
        && (outline == Outline::Free || !boundary_self_intersects(model, &map));
    valid.then_some(map)
}

/// Whether the flip-free minimiser also keeps the pattern's outline from crossing itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outline {
    /// Only triangles are kept from flipping (the outline may cross itself).
    Free,
    /// The [`BoundaryBarrier`] keeps the outline, holes included, from crossing itself too (the
    /// start must not cross itself).
    Kept,
}

/// Minimises the spring energy plus `barrier` (and the [`BoundaryBarrier`] with
/// [`Outline::Kept`]) from `positions` (every triangle positively oriented, else
/// [`InjectiveError::StartNotInjective`]), in place, with at most `max_iterations` (and
/// [`MAX_NEWTON_ITERATIONS`]) Newton iterations, none started after `deadline`; no triangle of
/// any iterate is flipped or degenerate (nor does its outline cross itself, with
/// [`Outline::Kept`] and a start whose outline does not).
pub fn flip_free_solve(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &mut [DVec2],
    barrier: Barrier,
    max_iterations: usize,
    deadline: Deadline,
    outline: Outline,
) -> Result<InjectiveOutcome, InjectiveError> {
    let mut moving = vec![true; model.vertex_count()];
    moving[HELD_VERTEX] = false;
    let settings = FlipFreeSettings {
        barrier,
        max_iterations,
        deadline,
        outline,
    };
    flip_free_solve_moving(model, springs, positions, &moving, settings)
}

/// What a flip-free solve minimises and for how long.
#[derive(Debug, Clone, Copy)]
pub struct FlipFreeSettings {
    /// The barrier on the triangles' area ratios.
    pub barrier: Barrier,
    /// Newton iterations at most (and [`MAX_NEWTON_ITERATIONS`]).
    pub max_iterations: usize,
    /// No iteration starts after it.
    pub deadline: Deadline,
    /// Whether the outline is kept from crossing itself.
    pub outline: Outline,
}

/// [`flip_free_solve`] moving only the vertices `v` with `moving[v]` (the others stay where they
/// are: a local repair).
pub fn flip_free_solve_moving(
    model: &FacetModel,
    springs: &SpringSystem,
    positions: &mut [DVec2],
    moving: &[bool],
    settings: FlipFreeSettings,
) -> Result<InjectiveOutcome, InjectiveError> {
    let FlipFreeSettings {
        barrier,
        max_iterations,
        deadline,
        outline,
    } = settings;
    let max_iterations = max_iterations.min(MAX_NEWTON_ITERATIONS);
    let flipped = flipped_triangles(model, positions);
    if flipped > 0 {
        return Err(InjectiveError::StartNotInjective { flipped });
    }
    let boundary = match outline {
        Outline::Free => None,
        Outline::Kept => BoundaryBarrier::new(model, springs),
    };
    let objective = Objective::new(model, springs, barrier, boundary);
    let layout = Layout::new(model, moving);
    if layout.unknowns == 0 {
        return Ok(InjectiveOutcome {
            iterations: 0,
            stop_reason: StopReason::Converged,
            initial_objective: objective.value(positions),
            objective: objective.value(positions),
            energy: springs.energy(positions),
        });
    }
    let pattern = SparsePattern::new(layout.unknowns, &layout.positions)?;
    let mut value = objective.value(positions);
    let initial_objective = value;
    let mut history = vec![value];
    let mut gradient = vec![DVec2::ZERO; positions.len()];
    let mut direction = vec![DVec2::ZERO; positions.len()];
    let mut candidate = positions.to_vec();
    let mut hessian = vec![0.0; layout.positions.len()];
    let mut stop_reason = StopReason::StepBudget;
    let mut iterations = max_iterations;
    for iteration in 0..max_iterations {
        if deadline.passed() {
            (stop_reason, iterations) = (StopReason::TimeLimit, iteration);
            break;
        }
        let contacts = objective.contacts(positions);
        objective.gradient(positions, &contacts, &mut gradient);
        objective.hessian(positions, &contacts, &layout, &mut hessian);
        let factor = factor_damped(&pattern, &layout, &mut hessian)?;
        newton_direction(&factor, &layout, &gradient, &mut direction);
        let descent: f64 = gradient
            .iter()
            .zip(&direction)
            .map(|(g, d)| g.dot(*d))
            .sum();
        if -descent <= NEWTON_DECREMENT_TOLERANCE * value.max(f64::MIN_POSITIVE) {
            (stop_reason, iterations) = (StopReason::Converged, iteration);
            break;
        }
        let mut bound = max_flip_free_step(model, positions, &direction);
        if let Some(boundary) = &objective.boundary {
            bound = bound.min(boundary.max_contact_free_step(positions, &direction));
        }
        let mut step = (FLIP_FREE_FRACTION * bound).min(1.0);
        let mut accepted = None;
        for _ in 0..MAX_HALVINGS {
            for ((c, &p), &d) in candidate.iter_mut().zip(positions.iter()).zip(&direction) {
                *c = p + d * step;
            }
            let next = objective.value(&candidate);
            if next <= value + ARMIJO * step * descent {
                accepted = Some(next);
                break;
            }
            step *= 0.5;
        }
        let Some(next) = accepted else {
            (stop_reason, iterations) = (StopReason::EnergyStalled, iteration);
            break;
        };
        positions.copy_from_slice(&candidate);
        value = next;
        history.push(value);
        let window_start = history[history.len().saturating_sub(NEWTON_WINDOW + 1)];
        if history.len() > NEWTON_WINDOW && window_start - value <= NEWTON_ENERGY_TOLERANCE * value
        {
            (stop_reason, iterations) = (StopReason::Converged, iteration + 1);
            break;
        }
    }
    Ok(InjectiveOutcome {
        iterations,
        stop_reason,
        initial_objective,
        objective: value,
        energy: springs.energy(positions),
    })
}

/// Factors the Hessian values with diagonal damping, growing the damping until it factors.
fn factor_damped<'a>(
    pattern: &'a SparsePattern,
    layout: &Layout,
    hessian: &mut [f64],
) -> Result<Factor<'a>, InjectiveError> {
    let diagonal = |hessian: &[f64]| {
        (0..layout.unknowns / 2)
            .map(|u| hessian[3 * u] + hessian[3 * u + 2])
            .sum::<f64>()
            / layout.unknowns.max(1) as f64
    };
    let mut damping = DAMPING * diagonal(hessian).max(f64::MIN_POSITIVE);
    let mut added = 0.0;
    let mut failure = None;
    for _ in 0..FACTOR_ATTEMPTS {
        for u in 0..layout.unknowns / 2 {
            hessian[3 * u] += damping - added;
            hessian[3 * u + 2] += damping - added;
        }
        added = damping;
        match pattern.factor(hessian) {
            Ok(factor) => return Ok(factor),
            Err(error) => failure = Some(error),
        }
        damping *= DAMPING_GROWTH;
    }
    Err(failure.expect("at least one attempt"))
}

/// Solves `H D = −∇E` for the unknowns; the held vertices do not move.
fn newton_direction(
    factor: &Factor<'_>,
    layout: &Layout,
    gradient: &[DVec2],
    direction: &mut [DVec2],
) {
    let vertex = |u: usize| layout.vertex_of[u] as usize;
    let mut rhs = Mat::from_fn(layout.unknowns, 1, |i, _| -gradient[vertex(i / 2)][i % 2]);
    factor.solve_in_place(rhs.as_mut());
    direction.fill(DVec2::ZERO);
    for u in 0..layout.unknowns / 2 {
        direction[vertex(u)] = DVec2::new(rhs[(2 * u, 0)], rhs[(2 * u + 1, 0)]);
    }
}

/// The objective: the spring energy plus the orientation barrier of every triangle.
struct Objective<'a> {
    model: &'a FacetModel,
    springs: &'a SpringSystem,
    barrier: Barrier,
    /// Rest area of each triangle.
    rest_areas: Vec<f64>,
    /// Barrier weight of each triangle: the barrier's weight times its edges' mean spring
    /// constant times its rest area.
    weights: Vec<f64>,
    /// The boundary barrier, when the outline is kept from crossing itself.
    boundary: Option<BoundaryBarrier>,
}

impl<'a> Objective<'a> {
    fn new(
        model: &'a FacetModel,
        springs: &'a SpringSystem,
        barrier: Barrier,
        boundary: Option<BoundaryBarrier>,
    ) -> Self {
        let rest_areas: Vec<f64> = (0..model.triangle_count())
            .map(|f| model.triangle_area(f))
            .collect();
        let weights = model
            .face_edges()
            .iter()
            .zip(&rest_areas)
            .map(|(edges, &area)| {
                let constant: f64 = edges
                    .iter()
                    .map(|&e| springs.constants[e as usize])
                    .sum::<f64>()
                    / 3.0;
                barrier.weight * constant * area
            })
            .collect();
        Self {
            model,
            springs,
            barrier,
            rest_areas,
            weights,
            boundary,
        }
    }

    /// The area ratio `A' / A` of triangle `f` and the gradient of `A'` at its corners.
    fn area_ratio(&self, f: usize, positions: &[DVec2]) -> (f64, [DVec2; 3]) {
        let corners = self.model.triangles()[f].map(|v| positions[v as usize]);
        let ratio = signed_area(corners[0], corners[1], corners[2]) / self.rest_areas[f];
        let gradient = [0, 1, 2].map(|i| {
            let (next, previous) = (corners[(i + 1) % 3], corners[(i + 2) % 3]);
            0.5 * DVec2::new(next.y - previous.y, previous.x - next.x)
        });
        (ratio, gradient)
    }

    /// The boundary barrier's contacts at `positions` (none without the barrier), for the
    /// gradient and the Hessian of one iteration.
    fn contacts(&self, positions: &[DVec2]) -> Vec<Contact> {
        self.boundary
            .as_ref()
            .map_or_else(Vec::new, |boundary| boundary.contacts(positions))
    }

    /// The objective at `positions`; infinite if a triangle is flipped or degenerate.
    fn value(&self, positions: &[DVec2]) -> f64 {
        let mut total = self.springs.energy(positions);
        for f in 0..self.rest_areas.len() {
            let corners = self.model.triangles()[f].map(|v| positions[v as usize]);
            let ratio = signed_area(corners[0], corners[1], corners[2]) / self.rest_areas[f];
            total += self.weights[f] * self.barrier.at(ratio)[0];
        }
        if let Some(boundary) = &self.boundary {
            total += boundary.value(positions);
        }
        total
    }

    /// The objective's gradient at `positions` (every triangle positively oriented).
    fn gradient(&self, positions: &[DVec2], contacts: &[Contact], gradient: &mut [DVec2]) {
        gradient.fill(DVec2::ZERO);
        for e in 0..self.springs.len() {
            let [a, b] = self.springs.edges[e];
            if let Some(force) = self.springs.spring_force(e, positions) {
                gradient[a as usize] -= force;
                gradient[b as usize] += force;
            }
        }
        for (f, t) in self.model.triangles().iter().enumerate() {
            let (ratio, area_gradient) = self.area_ratio(f, positions);
            let slope = self.barrier.at(ratio)[1];
            if slope == 0.0 {
                continue;
            }
            let scale = self.weights[f] * slope / self.rest_areas[f];
            for (&v, g) in t.iter().zip(area_gradient) {
                gradient[v as usize] += g * scale;
            }
        }
        if let Some(boundary) = &self.boundary {
            for contact in contacts {
                let slope = boundary.at(contact.distance)[1];
                let [a, b] = contact.edge;
                for (v, g) in [contact.vertex, a, b].into_iter().zip(contact.gradient) {
                    gradient[v as usize] += g * slope;
                }
            }
        }
    }

    /// The Hessian's lower-triangle values in `layout`'s order: each spring's Hessian projected
    /// to be positive semi-definite, and the barrier's Gauss-Newton part `w b''(x) ∇x ∇xᵀ`
    /// (positive semi-definite since the barrier is convex; its term in `b'(x) ∇²x` is
    /// indefinite and left out).
    fn hessian(
        &self,
        positions: &[DVec2],
        contacts: &[Contact],
        layout: &Layout,
        values: &mut [f64],
    ) {
        values.fill(0.0);
        for (e, &[a, b]) in self.springs.edges.iter().enumerate() {
            let delta = positions[b as usize] - positions[a as usize];
            let length = delta.length();
            let constant = self.springs.constants[e];
            let normal = if length > 0.0 {
                delta / length
            } else {
                DVec2::X
            };
            let tangential = if length > 0.0 {
                (1.0 - self.springs.rest_lengths[e] / length).max(0.0)
            } else {
                0.0
            };
            let block = |i: usize, j: usize| {
                let along = normal[i] * normal[j];
                let identity = if i == j { 1.0 } else { 0.0 };
                constant * (along + tangential * (identity - along))
            };
            let k = [[block(0, 0), block(0, 1)], [block(1, 0), block(1, 1)]];
            layout.add_diagonal(values, a, k);
            layout.add_diagonal(values, b, k);
            layout.add_edge(values, e, [[-k[0][0], -k[0][1]], [-k[1][0], -k[1][1]]]);
        }
        for (f, t) in self.model.triangles().iter().enumerate() {
            let (ratio, area_gradient) = self.area_ratio(f, positions);
            let curvature = self.barrier.at(ratio)[2];
            if curvature == 0.0 {
                continue;
            }
            let scale = self.weights[f] * curvature / (self.rest_areas[f] * self.rest_areas[f]);
            let outer = |p: DVec2, q: DVec2| {
                [
                    [scale * p.x * q.x, scale * p.x * q.y],
                    [scale * p.y * q.x, scale * p.y * q.y],
                ]
            };
            for i in 0..3 {
                layout.add_diagonal(values, t[i], outer(area_gradient[i], area_gradient[i]));
                let j = (i + 1) % 3;
                let (high, low) = if t[i] > t[j] { (i, j) } else { (j, i) };
                let e = self.model.face_edges()[f]
                    .into_iter()
                    .find(|&e| {
                        let [a, b] = self.model.edges()[e as usize];
                        (a == t[low] && b == t[high]) || (a == t[high] && b == t[low])
                    })
                    .expect("a triangle's sides are edges") as usize;
                layout.add_edge(values, e, outer(area_gradient[high], area_gradient[low]));
            }
        }
        if let Some(boundary) = &self.boundary {
            for contact in contacts {
                let curvature = boundary.at(contact.distance)[2];
                let [a, b] = contact.edge;
                for (v, g) in [contact.vertex, a, b].into_iter().zip(contact.gradient) {
                    let block = [
                        [curvature * g.x * g.x, curvature * g.x * g.y],
                        [curvature * g.y * g.x, curvature * g.y * g.y],
                    ];
                    layout.add_diagonal(values, v, block);
                }
            }
        }
    }
}

/// Where the Hessian's values go: the lower triangle of the unknowns (x and y of every moving
/// vertex, interleaved, in vertex order), as a list of positions: per moving vertex its 2×2
/// diagonal block's three lower entries, then per edge between moving vertices the 2×2 block in
/// the rows of its higher vertex and the columns of its lower one.
struct Layout {
    /// Twice the number of moving vertices.
    unknowns: usize,
    positions: Vec<(u32, u32)>,
    /// Per edge, the index of its first entry in `positions`, or `None` if it ends at a held
    /// vertex.
    edge_entries: Vec<Option<usize>>,
    /// Per vertex, its index among the moving vertices (`None` when it is held).
    unknown_of: Vec<Option<u32>>,
    /// Per moving vertex, the vertex.
    vertex_of: Vec<u32>,
}

impl Layout {
    fn new(model: &FacetModel, moving: &[bool]) -> Self {
        let vertex_of: Vec<u32> = (0..model.vertex_count() as u32)
            .filter(|&v| moving[v as usize])
            .collect();
        let mut unknown_of = vec![None; model.vertex_count()];
        for (u, &v) in vertex_of.iter().enumerate() {
            unknown_of[v as usize] = Some(u as u32);
        }
        let vertices = vertex_of.len() as u32;
        let mut positions = Vec::with_capacity(3 * vertices as usize + 4 * model.edges().len());
        for u in 0..vertices {
            positions.extend([(2 * u, 2 * u), (2 * u + 1, 2 * u), (2 * u + 1, 2 * u + 1)]);
        }
        let edge_entries = model
            .edges()
            .iter()
            .map(|&[a, b]| {
                let (low, high) = (unknown_of[a as usize]?, unknown_of[b as usize]?);
                let (low, high) = (low.min(high), low.max(high));
                let first = positions.len();
                for (row, col) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    positions.push((2 * high + row, 2 * low + col));
                }
                Some(first)
            })
            .collect();
        Self {
            unknowns: 2 * vertex_of.len(),
            positions,
            edge_entries,
            unknown_of,
            vertex_of,
        }
    }

    /// Adds the symmetric block `block` to vertex `v`'s diagonal block.
    fn add_diagonal(&self, values: &mut [f64], v: u32, block: [[f64; 2]; 2]) {
        if let Some(u) = self.unknown_of[v as usize] {
            let u = u as usize;
            values[3 * u] += block[0][0];
            values[3 * u + 1] += block[1][0];
            values[3 * u + 2] += block[1][1];
        }
    }

    /// Adds `block` to edge `e`'s block, given in the rows of its higher vertex and the
    /// columns of its lower one.
    fn add_edge(&self, values: &mut [f64], e: usize, block: [[f64; 2]; 2]) {
        if let Some(first) = self.edge_entries[e] {
            values[first] += block[0][0];
            values[first + 1] += block[0][1];
            values[first + 2] += block[1][0];
            values[first + 3] += block[1][1];
        }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use crate::flatten::accuracy::flipped_triangles;
    use crate::flatten::fast::{FastOptions, fast_solve};
    use crate::flatten::init_flatten::{InitRelease, NEIGHBOURHOOD_SWEEPS, init_flatten};
    use crate::flatten::injective::solver::*;
    use crate::flatten::injective::tutte::tutte_embedding;
    use crate::flatten::samples::{deep_bowl, deep_bowl_with_hole, uniform_springs};
    use crate::progress::NoProgress;

    /// The Tutte start, which has no flipped triangle, and the flip-free flattening, which has
    /// none either.
    fn flattened_from_tutte(
        model: &FacetModel,
        springs: &SpringSystem,
    ) -> (Vec<DVec2>, Vec<DVec2>, InjectiveOutcome) {
        let start = tutte_embedding(model).expect("a boundary");
        assert_eq!(flipped_triangles(model, &start), 0, "the Tutte start");
        let (pattern, outcome) = flip_free_flatten(
            model,
            springs,
            MAX_NEWTON_ITERATIONS,
            Deadline::NONE,
            Outline::Free,
        )
        .expect("flattens");
        assert_eq!(flipped_triangles(model, &pattern), 0, "{outcome:?}");
        (start, pattern, outcome)
    }

    #[test]
    fn the_fast_solver_folds_a_deep_bowl_and_the_flip_free_flattening_does_not() {
        let model = deep_bowl(0.85 * PI, 16, 48);
        let springs = uniform_springs(&model);
        let release = InitRelease::Neighbourhood {
            sweeps: NEIGHBOURHOOD_SWEEPS,
        };
        let mut plain = init_flatten(&model, &springs, release, &NoProgress);
        fast_solve(&model, &springs, &mut plain, FastOptions::default()).expect("factors");
        let plain_flipped = flipped_triangles(&model, &plain);
        assert!(plain_flipped > 0, "the plain solver must fold this bowl");

        let (start, pattern, outcome) = flattened_from_tutte(&model, &springs);
        assert!(
            outcome.objective <= outcome.initial_objective,
            "{outcome:?}"
        );
        assert!((outcome.energy - springs.energy(&pattern)).abs() <= 1e-9 * outcome.energy);
        assert!(
            outcome.energy < 0.5 * springs.energy(&start),
            "the spring energy must fall well below the Tutte start's: {outcome:?}"
        );
    }

    #[test]
    fn each_stage_lowers_its_objective_and_no_iterate_flips() {
        let model = deep_bowl(0.8 * PI, 10, 32);
        let springs = uniform_springs(&model);
        let mut positions = tutte_embedding(&model).expect("a boundary");
        let mut energy = springs.energy(&positions);
        // One Newton iteration at a time: every iterate is checked.
        for barrier in [SHAPING_BARRIER, ORIENTATION_BARRIER] {
            for _ in 0..15 {
                let outcome = flip_free_solve(
                    &model,
                    &springs,
                    &mut positions,
                    barrier,
                    1,
                    Deadline::NONE,
                    Outline::Free,
                )
                .expect("solves");
                assert!(
                    outcome.objective <= outcome.initial_objective,
                    "{outcome:?}"
                );
                assert_eq!(flipped_triangles(&model, &positions), 0);
                energy = outcome.energy;
            }
        }
        assert!(energy < springs.energy(&tutte_embedding(&model).expect("a boundary")));
    }

    #[test]
    fn a_flipped_start_is_refused() {
        let model = deep_bowl(0.5 * PI, 4, 12);
        let springs = uniform_springs(&model);
        let mut positions = tutte_embedding(&model).expect("a boundary");
        for p in &mut positions {
            p.x = -p.x;
        }
        let refused = flip_free_solve(
            &model,
            &springs,
            &mut positions,
            ORIENTATION_BARRIER,
            10,
            Deadline::NONE,
            Outline::Free,
        );
        assert_eq!(
            refused,
            Err(InjectiveError::StartNotInjective {
                flipped: model.triangle_count()
            })
        );
    }

    #[test]
    fn a_part_with_a_hole_starts_and_ends_without_flips() {
        let model = deep_bowl_with_hole(0.85 * PI, 16, 48);
        assert_eq!(model.boundary_loops().len(), 2);
        let springs = uniform_springs(&model);
        let (start, _, outcome) = flattened_from_tutte(&model, &springs);
        assert!(outcome.energy < springs.energy(&start), "{outcome:?}");
    }
}
