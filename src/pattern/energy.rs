//! Per-vertex energies of a pattern (Eq. 1), computed once for the energy map, with the energy
//! taken as negligible (the colour scale's floor).

use glam::DVec2;

use crate::flatten::SpringSystem;
use crate::flatten::stiffness::Stiffness;
use crate::mesh::FacetModel;

/// The per-vertex energies of one pattern.
#[derive(Debug, Clone, PartialEq)]
pub struct VertexEnergy {
    /// Energy (Eq. 1) of every vertex's springs.
    pub vertex: Vec<f64>,
    /// [`negligible_vertex_energy`] of the springs at [`NEGLIGIBLE_STRAIN`].
    pub negligible: f64,
}

impl VertexEnergy {
    /// The energies of `model`'s springs (stiffness factors, spring constant `C`) in the pattern
    /// `positions`.
    pub fn new(
        model: &FacetModel,
        stiffness: &Stiffness,
        positions: &[DVec2],
        spring_constant: f64,
    ) -> Self {
        let springs = SpringSystem::new(model, stiffness.factors(), spring_constant);
        Self {
            vertex: springs.vertex_energies(positions),
            negligible: negligible_vertex_energy(&springs, NEGLIGIBLE_STRAIN),
        }
    }
}

/// The strain taken as negligible for the colour scale's floor: one part per million, far below
/// any manufacturing tolerance and far above the round-off of an isometric flattening.
pub const NEGLIGIBLE_STRAIN: f64 = 1.0e-6;

/// The largest per-vertex energy (Eq. 1) the springs would hold if every one were strained by
/// `strain`: `max_i Σ_j ½ C_ij (strain · d_ij)²`.
pub fn negligible_vertex_energy(springs: &SpringSystem, strain: f64) -> f64 {
    let vertices = springs
        .edges
        .iter()
        .flatten()
        .map(|&v| v as usize + 1)
        .max()
        .unwrap_or(0);
    let mut energies = vec![0.0; vertices];
    for ((&[a, b], &rest), &constant) in springs
        .edges
        .iter()
        .zip(&springs.rest_lengths)
        .zip(&springs.constants)
    {
        let stretch = strain * rest;
        let energy = 0.5 * constant * stretch * stretch;
        energies[a as usize] += energy;
        energies[b as usize] += energy;
    }
    energies.into_iter().fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use crate::pattern::energy::*;

    #[test]
    fn negligible_energy_is_that_of_a_uniform_strain() {
        let springs = SpringSystem {
            edges: vec![[0, 1], [1, 2]],
            rest_lengths: vec![10.0, 20.0],
            constants: vec![0.5, 0.5],
        };
        // Vertex 1 ends both springs: ½·0.5·(0.1)² + ½·0.5·(0.2)² = 0.0125.
        let energy = negligible_vertex_energy(&springs, 0.01);
        assert!((energy - 0.0125).abs() < 1e-15, "{energy}");
    }
}
