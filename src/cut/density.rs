//! The maps crest lines are traced on: spring energy per unit area, smoothed over a length tied
//! to the part's size, so that the cuts planned on a part do not depend on its mesh.
//!
//! Eq. 1 gives each vertex the energy of the springs it ends. On a fine mesh that figure is a
//! poor map to plan cuts on: it sums a number of springs that varies with the vertex's valence
//! and its share of the surface, so it jumps from vertex to vertex by tens of percent while the
//! true field changes by an amount proportional to the edge length. A descent then stops at the
//! first spurious local minimum (on a 20k-triangle cap every dart branch ended after about 10
//! edges and the loop spent its budget on short extensions), and the stress peak at the tip of a
//! cut grows without bound as the mesh is refined. The planning map fixes both:
//!
//! - **density**: the vertex energy divided by the vertex's area (a third of its triangles' 3D
//!   areas), an energy per unit area that is the same on any mesh of the same pattern;
//! - **smoothing** over [`SMOOTHING_LENGTH`] times the square root of the part's area (its size
//!   as a surface, the same however it is bent in space): repeated
//!   averaging over each vertex's closed one-ring, weighted by vertex area (a discrete heat
//!   flow). A random walk of `k` such steps spreads by `√(k/2)` mean edge lengths along each
//!   axis, so `k = 2 (ℓ / h)²` steps give a standard deviation `ℓ` whatever the edge length `h`.
//!
//! Inputs: a facet model, its adjacency and per-vertex energies (model units). Output: a
//! per-vertex density (energy per unit area) and its area-weighted mean.

use super::paths::Adjacency;
use crate::mesh::FacetModel;

/// Length over which the planning map is smoothed (one standard deviation), as a fraction of the
/// square root of the part's area: 10.6 mm on the 60° cap of radius 100 mm, about 2.5 edges of
/// its 4k-triangle mesh and 6 of the 20k one; 15 mm on the hemisphere of radius 100 mm. With
/// 0.04 to 0.065 the caps and the hemisphere of 4k and 20k triangles end within 1 %, but the
/// greedy cut loop is sensitive to it (the cuts and their total length change by up to 20 %).
pub const SMOOTHING_LENGTH: f64 = 0.06;
/// Most smoothing steps (a mesh over 100 times finer than the smoothing length is smoothed less).
pub const MAX_SMOOTHING_STEPS: usize = 20_000;

/// A per-vertex map of energy per unit area.
#[derive(Debug, Clone, PartialEq)]
pub struct DensityMap {
    /// Energy per unit area at each vertex.
    pub values: Vec<f64>,
    /// The area-weighted mean of `values`.
    pub mean: f64,
}

/// The area of each vertex: a third of the 3D areas of its triangles.
pub fn vertex_areas(model: &FacetModel) -> Vec<f64> {
    let mut areas = vec![0.0; model.vertex_count()];
    for (f, triangle) in model.triangles().iter().enumerate() {
        let third = model.triangle_area(f) / 3.0;
        for &v in triangle {
            areas[v as usize] += third;
        }
    }
    areas
}

/// The planning map of per-vertex `energies`: their density over `areas`, smoothed over
/// [`SMOOTHING_LENGTH`] times the part's size.
pub fn planning_map(
    model: &FacetModel,
    adjacency: &Adjacency,
    areas: &[f64],
    energies: &[f64],
) -> DensityMap {
    let density: Vec<f64> = energies
        .iter()
        .zip(areas)
        .map(|(&energy, &area)| if area > 0.0 { energy / area } else { 0.0 })
        .collect();
    let steps = smoothing_steps(model, smoothing_length(model));
    let values = smoothed(adjacency, areas, density, steps);
    let total_area: f64 = areas.iter().sum();
    let mean = if total_area > 0.0 {
        values.iter().zip(areas).map(|(&d, &a)| d * a).sum::<f64>() / total_area
    } else {
        0.0
    };
    DensityMap { values, mean }
}

/// The length the planning map is smoothed over: [`SMOOTHING_LENGTH`] times the square root of
/// the part's area (its size as a surface, whatever its shape in space).
pub fn smoothing_length(model: &FacetModel) -> f64 {
    SMOOTHING_LENGTH * model.area().sqrt()
}

/// Steps of one-ring averaging that spread a value by `length` (one standard deviation along
/// each axis): `2 (length / h)²` for the root-mean-square rest length `h`.
fn smoothing_steps(model: &FacetModel, length: f64) -> usize {
    let lengths = model.rest_lengths();
    if lengths.is_empty() {
        return 0;
    }
    let mean_square = lengths.iter().map(|l| l * l).sum::<f64>() / lengths.len() as f64;
    if mean_square <= 0.0 {
        return 0;
    }
    let steps = (2.0 * length * length / mean_square).ceil();
    (steps as usize).min(MAX_SMOOTHING_STEPS)
}

/// `values` after `steps` rounds of replacing each by the area-weighted mean over its closed
/// one-ring (the vertex and its neighbours).
fn smoothed(adjacency: &Adjacency, areas: &[f64], mut values: Vec<f64>, steps: usize) -> Vec<f64> {
    let mut next = vec![0.0; values.len()];
    for _ in 0..steps {
        for (v, out) in next.iter_mut().enumerate() {
            let (mut sum, mut weight) = (areas[v] * values[v], areas[v]);
            for &(w, _) in adjacency.neighbours(v as u32) {
                sum += areas[w as usize] * values[w as usize];
                weight += areas[w as usize];
            }
            *out = if weight > 0.0 {
                sum / weight
            } else {
                values[v]
            };
        }
        std::mem::swap(&mut values, &mut next);
    }
    values
}

#[cfg(test)]
mod tests {
    use crate::cut::density::*;
    use crate::cut::paths::tests::grid;

    #[test]
    fn vertex_areas_add_up_to_the_surface_area() {
        let model = grid();
        let total: f64 = vertex_areas(&model).iter().sum();
        assert!((total - model.area()).abs() < 1e-12);
    }

    #[test]
    fn a_uniform_density_stays_uniform_whatever_the_vertex_areas() {
        // Energy proportional to area is a uniform density of 2 per unit area.
        let model = grid();
        let adjacency = Adjacency::new(&model);
        let areas = vertex_areas(&model);
        let energies: Vec<f64> = areas.iter().map(|a| 2.0 * a).collect();
        let map = planning_map(&model, &adjacency, &areas, &energies);
        assert!(map.values.iter().all(|d| (d - 2.0).abs() < 1e-12));
        assert!((map.mean - 2.0).abs() < 1e-12);
    }

    #[test]
    fn smoothing_spreads_a_spike_within_its_range() {
        let model = grid();
        let adjacency = Adjacency::new(&model);
        let areas = vertex_areas(&model);
        let mut spike = vec![0.0; model.vertex_count()];
        spike[5] = 1.0;
        let out = smoothed(&adjacency, &areas, spike, 3);
        assert!(out[5] < 1.0 && out[5] > 0.0);
        assert!(
            out.iter().all(|&d| d > 0.0),
            "three steps reach the far corner"
        );
        // Each step is a weighted mean: nothing leaves the range of the values.
        assert!(out.iter().all(|&d| d <= 1.0));
    }

    #[test]
    fn the_step_count_follows_the_length_over_the_edge_length() {
        let model = grid();
        // Rest lengths 1 and √2: mean square 4/3 over the 33 edges (24 sides, 9 diagonals).
        let mean_square = (24.0 + 9.0 * 2.0) / 33.0;
        assert_eq!(
            smoothing_steps(&model, 3.0),
            (18.0f64 / mean_square).ceil() as usize
        );
    }
}
