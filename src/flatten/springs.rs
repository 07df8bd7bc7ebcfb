//! The planar spring-mass system of the paper (§3): one spring per mesh edge, with rest length
//! `d_ij` (the edge's 3D length, or a rest length set on the facet model) and spring constant
//! `C_ij` (uniform by default, raised near fold lines and in marked regions).
//!
//! Energy of one vertex (Eq. 1): `E(P_i) = Σ_j ½ C_ij (|P_i P_j| − d_ij)²`; force on it (Eq. 2):
//! `f(P_i) = Σ_j C_ij (|P_i P_j| − d_ij) n_ij`, with `n_ij` the unit vector from `P_i` to `P_j`.
//! The system energy used by the solvers is `E = Σ_edges ½ C_ij (|P_i P_j| − d_ij)²`; the paper's
//! Eq. 3 sums Eq. 1 over vertices and so counts each spring twice (`E_Eq3 = 2 E`), which changes
//! no minimiser and no relative variation.

use glam::DVec2;

use crate::mesh::FacetModel;

/// The paper's spring constant `C` (§5: "ρ = 1/min{m_i} and C = 0.5").
pub const PAPER_SPRING_CONSTANT: f64 = 0.5;

/// Springs along every edge of a facet model.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringSystem {
    /// The springs' end vertices (the model's edges, `a < b`).
    pub edges: Vec<[u32; 2]>,
    /// Rest length `d_ij` of each spring, in model units.
    pub rest_lengths: Vec<f64>,
    /// Spring constant `C_ij` of each spring.
    pub constants: Vec<f64>,
}

impl SpringSystem {
    /// Springs on the model's edges with constants `constant × stiffness[e]` (the per-edge
    /// stiffness factors, see [`crate::flatten::Stiffness`]).
    pub fn new(model: &FacetModel, stiffness: &[f64], constant: f64) -> Self {
        assert_eq!(
            stiffness.len(),
            model.edges().len(),
            "one stiffness factor per edge"
        );
        Self {
            edges: model.edges().to_vec(),
            rest_lengths: model.rest_lengths().to_vec(),
            constants: stiffness.iter().map(|&s| s * constant).collect(),
        }
    }

    /// Number of springs.
    pub fn len(&self) -> usize {
        self.edges.len()
    }

    /// True when there are no springs.
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
    }

    /// Energy of spring `e` at the given positions: `½ C (l − d)²`.
    pub fn spring_energy(&self, e: usize, positions: &[DVec2]) -> f64 {
        let [a, b] = self.edges[e];
        let stretch = positions[a as usize].distance(positions[b as usize]) - self.rest_lengths[e];
        0.5 * self.constants[e] * stretch * stretch
    }

    /// System energy `Σ_edges ½ C (l − d)²`.
    pub fn energy(&self, positions: &[DVec2]) -> f64 {
        (0..self.edges.len())
            .map(|e| self.spring_energy(e, positions))
            .sum()
    }

    /// Per-vertex energy of Eq. 1: each vertex gets the full energy of every spring it ends.
    pub fn vertex_energies(&self, positions: &[DVec2]) -> Vec<f64> {
        self.vertex_energies_of(positions, |_| true)
    }

    /// Per-vertex energy of the stretched springs only (`|P_i P_j| > d_ij`): the energy a cut can
    /// release by opening. A compressed spring holds material the pattern has too much of; a cut
    /// across it would make its sides overlap, so it releases nothing.
    pub fn tension_energies(&self, positions: &[DVec2]) -> Vec<f64> {
        self.vertex_energies_of(positions, |stretch| stretch > 0.0)
    }

    /// Per-vertex sums of the energies of the springs whose stretch `|P_i P_j| − d_ij` passes
    /// `counts`.
    fn vertex_energies_of(&self, positions: &[DVec2], counts: impl Fn(f64) -> bool) -> Vec<f64> {
        let mut energies = vec![0.0; positions.len()];
        for e in 0..self.edges.len() {
            let [a, b] = self.edges[e];
            let stretch =
                positions[a as usize].distance(positions[b as usize]) - self.rest_lengths[e];
            if !counts(stretch) {
                continue;
            }
            let energy = self.spring_energy(e, positions);
            energies[a as usize] += energy;
            energies[b as usize] += energy;
        }
        energies
    }

    /// Spring forces of Eq. 2 on every vertex, written into `forces` (the negative gradient of
    /// [`SpringSystem::energy`]).
    pub fn forces(&self, positions: &[DVec2], forces: &mut [DVec2]) {
        forces.fill(DVec2::ZERO);
        for e in 0..self.edges.len() {
            let [a, b] = self.edges[e];
            if let Some(force) = self.spring_force(e, positions) {
                forces[a as usize] += force;
                forces[b as usize] -= force;
            }
        }
    }

    /// Force of spring `e` on its first vertex (the second gets the opposite), or `None` when
    /// its ends coincide and the direction is undefined.
    pub fn spring_force(&self, e: usize, positions: &[DVec2]) -> Option<DVec2> {
        let [a, b] = self.edges[e];
        let delta = positions[b as usize] - positions[a as usize];
        let length = delta.length();
        (length > 0.0)
            .then(|| delta * (self.constants[e] * (length - self.rest_lengths[e]) / length))
    }
}

#[cfg(test)]
mod tests {
    use crate::flatten::springs::*;

    fn two_springs() -> SpringSystem {
        SpringSystem {
            edges: vec![[0, 1], [1, 2]],
            rest_lengths: vec![1.0, 2.0],
            constants: vec![0.5, 2.0],
        }
    }

    #[test]
    fn forces_are_the_negative_gradient_of_the_energy() {
        let springs = two_springs();
        let positions = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.3, 0.2),
            DVec2::new(2.0, 1.9),
        ];
        let mut forces = vec![DVec2::ZERO; 3];
        springs.forces(&positions, &mut forces);
        let step = 1e-6;
        for v in 0..3 {
            for axis in 0..2 {
                let mut moved = positions.clone();
                moved[v][axis] += step;
                let plus = springs.energy(&moved);
                moved[v][axis] -= 2.0 * step;
                let minus = springs.energy(&moved);
                let gradient = (plus - minus) / (2.0 * step);
                assert!(
                    (forces[v][axis] + gradient).abs() < 1e-6,
                    "vertex {v} axis {axis}"
                );
            }
        }
    }

    #[test]
    fn vertex_energies_count_each_spring_twice() {
        let springs = two_springs();
        let positions = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.5, 0.0),
            DVec2::new(1.5, 3.0),
        ];
        let total: f64 = springs.vertex_energies(&positions).iter().sum();
        assert!((total - 2.0 * springs.energy(&positions)).abs() < 1e-12);
    }
}
