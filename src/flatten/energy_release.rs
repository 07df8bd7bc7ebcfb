//! EnergyRelease (paper §5): the planar spring-mass system relaxed by explicit integration.
//!
//! Masses from areas (Eq. 10): `m_i = ρ/3 Σ A_k` over the 3D triangles around vertex `i`, with
//! `ρ = 1 / min_i(Σ A_k / 3)` so that the lightest vertex weighs 1. Each step (Eq. 11-13):
//! `a_i = f_i / m_i`, `q_i ← q_i + Δt v_i + ½ Δt² a_i`, `v_i ← v_i + Δt a_i`, with the spring
//! forces of Eq. 2, then the overlap penalty of Eq. 14-15 moves every vertex that came closer to
//! an opposite edge than its 3D distance `h*` back by the shortfall, along the edge's normal.
//!
//! Damping. The paper drops the damping term of Eq. 8, and an undamped explicit integrator never
//! settles: it trades potential for kinetic energy forever, and the explicit scheme of Eq. 12-13
//! even gains energy in the fast modes. We use kinetic damping (dynamic relaxation, Cundall 1976)
//! at two scales: a vertex whose velocity points against its force (it is climbing) loses its
//! velocity before the step, and whenever the total kinetic energy `Σ ½ m_i |v_i|²` falls, the
//! system has just passed an energy minimum along its path and every velocity is set to zero.
//! Between resets the motion is the paper's. With the global reset alone the hemisphere's energy
//! fell for 3000 steps and then rose again; with both it falls monotonically (the unit test
//! below samples it every 500 steps).
//!
//! Stopping rule (the paper's): stop when `E_S` and `E_C` are both within the tolerance, or when
//! the relative variation of the energy falls below `ε` (0.05 %), or after the step budget. The
//! variation is measured from one velocity reset to the next (one relaxation cycle), not between
//! two steps: with the paper's `Δt = 0.01` a step taken from rest changes the energy by far less
//! than 0.05 %, so a per-step test stops every run after its second step, before anything moved.

use glam::DVec2;

use super::accuracy::{DEFAULT_TOLERANCE, area_error, shape_error};
use super::springs::SpringSystem;
use crate::mesh::{FacetModel, NONE};
use crate::progress::Deadline;

/// The paper's time step `Δt` (§5: "usually we use Δt = 0.01").
pub const PAPER_TIME_STEP: f64 = 0.01;
/// The paper's permissible relative energy variation `ε` (0.05 %).
pub const PAPER_ENERGY_VARIATION: f64 = 0.0005;
/// The paper's step budget for phase two (§6.2: "the permissible iteration steps is 1000").
pub const PAPER_STEP_BUDGET: usize = 1000;

/// Why a relaxation stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// `E_S` and `E_C` are both within the tolerance.
    ToleranceMet,
    /// The relative energy variation fell below `ε`.
    EnergyStalled,
    /// The step budget was used up.
    StepBudget,
    /// The solver converged on its own criterion (gradient or energy decrease).
    Converged,
    /// The time limit was reached.
    TimeLimit,
    /// Every further step would have flipped a triangle (the fast solver's orientation guard).
    OrientationBlocked,
    /// Not relaxed at all: a sheet-metal part unfolded exactly on its B-rep
    /// ([`crate::sheet`]).
    ExactUnfold,
}

/// Parameters of the explicit relaxation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReleaseParameters {
    /// Time step `Δt`.
    pub time_step: f64,
    /// Stop when the relative energy variation between steps is below this.
    pub energy_variation: f64,
    /// Stop when `E_S` and `E_C` are both at most this.
    pub tolerance: f64,
    /// Largest number of steps.
    pub max_steps: usize,
    /// No step starts after it (phase two stops with [`StopReason::TimeLimit`]).
    pub deadline: Deadline,
}

impl Default for ReleaseParameters {
    fn default() -> Self {
        Self {
            time_step: PAPER_TIME_STEP,
            energy_variation: PAPER_ENERGY_VARIATION,
            tolerance: DEFAULT_TOLERANCE,
            max_steps: PAPER_STEP_BUDGET,
            deadline: Deadline::NONE,
        }
    }
}

/// What a relaxation did.
#[derive(Debug, Clone, PartialEq)]
pub struct ReleaseOutcome {
    /// Steps taken.
    pub steps: usize,
    /// Why it stopped.
    pub stop_reason: StopReason,
    /// The spring energy at the start and at the end of every relaxation cycle (each velocity
    /// reset): the record that kinetic damping releases energy.
    pub cycle_energies: Vec<f64>,
}

/// The precomputed spring-mass system of a facet model: masses and the 3D heights `h*` used by
/// the penalty. Reused across calls (phase one calls it once per triangle).
#[derive(Debug, Clone)]
pub struct EnergyRelease<'a> {
    model: &'a FacetModel,
    springs: &'a SpringSystem,
    /// `ρ/3` times each triangle's 3D area: a triangle's contribution to each corner's mass.
    corner_mass: Vec<f64>,
    /// Per triangle, the 3D distance from corner `k` to the opposite edge.
    rest_heights: Vec<[f64; 3]>,
}

/// The part of the system that moves: for phase two the whole model, for phase one the
/// triangles flattened so far (the paper's system `Ψ`).
#[derive(Debug, Clone, Default)]
pub struct Subsystem {
    /// Triangles in the system.
    pub triangles: Vec<u32>,
    /// Springs in the system (edges of those triangles).
    pub springs: Vec<u32>,
    /// Vertices in the system.
    pub vertices: Vec<u32>,
    /// Mass of each model vertex from the system's triangles (Eq. 10); 0 outside the system.
    pub masses: Vec<f64>,
    /// Whether each model triangle is in the system.
    pub contains_triangle: Vec<bool>,
}

impl<'a> EnergyRelease<'a> {
    /// Precomputes masses and rest heights.
    pub fn new(model: &'a FacetModel, springs: &'a SpringSystem) -> Self {
        let mut vertex_area = vec![0.0; model.vertex_count()];
        for (f, t) in model.triangles().iter().enumerate() {
            for &v in t {
                vertex_area[v as usize] += model.triangle_area(f) / 3.0;
            }
        }
        let lightest = vertex_area.iter().copied().fold(f64::INFINITY, f64::min);
        let density = 1.0 / lightest;
        let corner_mass = (0..model.triangle_count())
            .map(|f| density * model.triangle_area(f) / 3.0)
            .collect();
        let rest_heights = (0..model.triangle_count())
            .map(|f| {
                let t = model.triangles()[f];
                let area = model.triangle_area(f);
                [0, 1, 2].map(|k| {
                    let [b, c] =
                        [t[(k + 1) % 3], t[(k + 2) % 3]].map(|v| model.positions()[v as usize]);
                    2.0 * area / b.distance(c)
                })
            })
            .collect();
        Self {
            model,
            springs,
            corner_mass,
            rest_heights,
        }
    }

    /// The whole model as one system.
    pub fn whole_system(&self) -> Subsystem {
        let mut system = self.empty_system();
        for f in 0..self.model.triangle_count() as u32 {
            self.add_triangle(&mut system, f);
        }
        system.springs = (0..self.springs.len() as u32).collect();
        system.vertices = (0..self.model.vertex_count() as u32).collect();
        system
    }

    /// An empty system over this model, to grow with [`EnergyRelease::add_triangle`].
    pub fn empty_system(&self) -> Subsystem {
        Subsystem {
            masses: vec![0.0; self.model.vertex_count()],
            contains_triangle: vec![false; self.model.triangle_count()],
            ..Subsystem::default()
        }
    }

    /// Adds triangle `f` to a system: its mass goes to its corners, and its springs and vertices
    /// that were not yet in the system join it.
    pub fn add_triangle(&self, system: &mut Subsystem, f: u32) {
        let t = self.model.triangles()[f as usize];
        for (k, &v) in t.iter().enumerate() {
            if system.masses[v as usize] == 0.0 {
                system.vertices.push(v);
            }
            system.masses[v as usize] += self.corner_mass[f as usize];
            let e = self.model.face_edges()[f as usize][k];
            let other = self.model.edge_faces()[e as usize]
                .into_iter()
                .find(|&g| g != f);
            let already = other.is_some_and(|g| g != NONE && system.contains_triangle[g as usize]);
            if !already {
                system.springs.push(e);
            }
        }
        system.triangles.push(f);
        system.contains_triangle[f as usize] = true;
    }

    /// Relaxes the system from `positions` with zero initial velocity, by the paper's stopping
    /// rule. Only vertices of `system` move. `measure_errors` turns the `E_S`/`E_C` test on
    /// (phase two); phase one runs its fixed number of steps.
    pub fn release(
        &self,
        system: &Subsystem,
        positions: &mut [DVec2],
        parameters: &ReleaseParameters,
        measure_errors: bool,
    ) -> ReleaseOutcome {
        let mut velocities = vec![DVec2::ZERO; positions.len()];
        let mut forces = vec![DVec2::ZERO; positions.len()];
        let mut energy_at_last_reset = self.system_energy(system, positions);
        let mut cycle_energies = vec![energy_at_last_reset];
        let mut kinetic = 0.0;
        for step in 1..=parameters.max_steps {
            if measure_errors
                && area_error(self.model, positions) <= parameters.tolerance
                && shape_error(self.model, positions) <= parameters.tolerance
            {
                return ReleaseOutcome {
                    steps: step - 1,
                    stop_reason: StopReason::ToleranceMet,
                    cycle_energies,
                };
            }
            if measure_errors && parameters.deadline.passed() {
                return ReleaseOutcome {
                    steps: step - 1,
                    stop_reason: StopReason::TimeLimit,
                    cycle_energies,
                };
            }
            self.step(
                system,
                positions,
                &mut velocities,
                &mut forces,
                parameters.time_step,
            );
            let new_kinetic: f64 = system
                .vertices
                .iter()
                .map(|&v| 0.5 * system.masses[v as usize] * velocities[v as usize].length_squared())
                .sum();
            if new_kinetic >= kinetic {
                kinetic = new_kinetic;
                continue;
            }
            // The kinetic energy peaked: the end of a relaxation cycle.
            for &v in &system.vertices {
                velocities[v as usize] = DVec2::ZERO;
            }
            kinetic = 0.0;
            let energy = self.system_energy(system, positions);
            let variation = if energy_at_last_reset > 0.0 {
                (energy - energy_at_last_reset).abs() / energy_at_last_reset
            } else {
                0.0
            };
            energy_at_last_reset = energy;
            cycle_energies.push(energy);
            if measure_errors && variation < parameters.energy_variation {
                return ReleaseOutcome {
                    steps: step,
                    stop_reason: StopReason::EnergyStalled,
                    cycle_energies,
                };
            }
        }
        ReleaseOutcome {
            steps: parameters.max_steps,
            stop_reason: StopReason::StepBudget,
            cycle_energies,
        }
    }

    /// One explicit step (Eq. 11-13) followed by the penalty (Eq. 14-15).
    fn step(
        &self,
        system: &Subsystem,
        positions: &mut [DVec2],
        velocities: &mut [DVec2],
        forces: &mut [DVec2],
        dt: f64,
    ) {
        self.system_forces(system, positions, forces);
        for &v in &system.vertices {
            let v = v as usize;
            let acceleration = forces[v] / system.masses[v];
            if velocities[v].dot(forces[v]) < 0.0 {
                velocities[v] = DVec2::ZERO;
            }
            positions[v] += dt * velocities[v] + 0.5 * dt * dt * acceleration;
            velocities[v] += dt * acceleration;
        }
        self.apply_penalty(system, positions);
    }

    /// Spring energy of the system's springs.
    pub fn system_energy(&self, system: &Subsystem, positions: &[DVec2]) -> f64 {
        system
            .springs
            .iter()
            .map(|&e| self.springs.spring_energy(e as usize, positions))
            .sum()
    }

    fn system_forces(&self, system: &Subsystem, positions: &[DVec2], forces: &mut [DVec2]) {
        for &v in &system.vertices {
            forces[v as usize] = DVec2::ZERO;
        }
        for &e in &system.springs {
            if let Some(force) = self.springs.spring_force(e as usize, positions) {
                let [a, b] = self.springs.edges[e as usize];
                forces[a as usize] += force;
                forces[b as usize] -= force;
            }
        }
    }

    /// Eq. 14-15: a vertex whose signed distance `h` to an opposite edge is at most its 3D
    /// distance `h*` is moved away from that edge by `|h − h*|`. The displacements of all of a
    /// vertex's opposite edges are summed, computed from the positions before any is applied.
    fn apply_penalty(&self, system: &Subsystem, positions: &mut [DVec2]) {
        let mut displacement: Vec<(u32, DVec2)> = Vec::new();
        for &f in &system.triangles {
            let t = self.model.triangles()[f as usize];
            for k in 0..3 {
                let [p, a, b] = [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
                let (pp, pa, pb) = (
                    positions[p as usize],
                    positions[a as usize],
                    positions[b as usize],
                );
                let edge = pb - pa;
                let length = edge.length();
                if length <= 0.0 {
                    continue;
                }
                let away = edge.perp() / length;
                let height = (pp - pa).dot(away);
                let rest = self.rest_heights[f as usize][k];
                if height <= rest * PENALTY_REACH {
                    displacement.push((p, away * (rest * PENALTY_REACH - height)));
                }
            }
        }
        for (v, shift) in displacement {
            positions[v as usize] += shift;
        }
    }
}

/// Fraction of the 3D height `h*` below which the penalty acts, and to which it restores the
/// height. The paper's Eq. 14 acts whenever `h ≤ h*` (a reach of 1): taken literally, every vertex
/// of a slightly compressed triangle is pushed back by the full shortfall, the pushes of a
/// vertex's several opposite edges add up and overshoot, and the system diverges (NaN within
/// phase one on the paper's 150-triangle cone, see docs/algorithms.md). Acting only when a vertex
/// has come within a quarter of its 3D distance keeps the penalty's purpose, stopping a triangle
/// before it folds over, without fighting the springs.
pub const PENALTY_REACH: f64 = 0.25;

#[cfg(test)]
mod tests {
    use crate::flatten::energy_release::*;
    use crate::flatten::samples::sample;
    use crate::flatten::stiffness::Stiffness;

    #[test]
    fn masses_follow_equation_10() {
        let model = sample("cone_frustum.obj");
        let springs = SpringSystem::new(&model, Stiffness::uniform(&model).factors(), 0.5);
        let release = EnergyRelease::new(&model, &springs);
        let system = release.whole_system();
        let lightest = system.masses.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            (lightest - 1.0).abs() < 1e-12,
            "ρ = 1 / min m_i makes the lightest mass 1"
        );
        let total: f64 = system.masses.iter().sum();
        let expected = model.area() / (lightest_vertex_area(&model));
        assert!((total - expected).abs() < 1e-9 * expected);
    }

    fn lightest_vertex_area(model: &FacetModel) -> f64 {
        let mut areas = vec![0.0; model.vertex_count()];
        for (f, t) in model.triangles().iter().enumerate() {
            for &v in t {
                areas[v as usize] += model.triangle_area(f) / 3.0;
            }
        }
        areas.into_iter().fold(f64::INFINITY, f64::min)
    }
}
