//! Which vertices of a welded tessellation lie in a stiffness region given in a surface's
//! parameter domain: a vertex is on the surface when that surface's mesher produced it (a vertex
//! of an edge two surfaces share is on both); its domain coordinates are the patch's own
//! parameters, or those of its position on the structured kinds.

use super::weld::Welded;
use crate::cad::{ParameterRegion, SurfaceDomain};

/// For each vertex of `welded`, whether it is on surface `surface` and in `region`.
pub fn vertices_inside(region: &ParameterRegion, welded: &Welded, surface: u32) -> Vec<bool> {
    (0..welded.soup.positions.len())
        .map(|vertex| {
            vertex_coordinates(region.domain(), welded, surface, vertex)
                .is_some_and(|(u, v)| region.contains(u, v))
        })
        .collect()
}

/// The domain coordinates of a welded vertex on surface `surface`; `None` when that surface did
/// not produce it.
fn vertex_coordinates(
    domain: &SurfaceDomain,
    welded: &Welded,
    surface: u32,
    vertex: usize,
) -> Option<(Option<f64>, f64)> {
    let parameters = welded.parameters_on(vertex, surface)?;
    Some(match domain {
        SurfaceDomain::Patch(_) => (Some(parameters.x), parameters.y),
        _ => domain.parameters(welded.soup.positions[vertex]),
    })
}
