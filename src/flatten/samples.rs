//! Facet models for the stage's unit tests: the bundled mesh samples, read and validated directly
//! (ingest and mesh, both left of flatten), without the pipeline, and generated ones.

use std::f64::consts::PI;

use glam::DVec3;

use super::springs::{PAPER_SPRING_CONSTANT, SpringSystem};
use crate::cad::TriangleSoup;
use crate::mesh::FacetModel;

/// The springs of `model` at the paper's constant, every edge of unit stiffness.
pub(crate) fn uniform_springs(model: &FacetModel) -> SpringSystem {
    SpringSystem::new(
        model,
        &vec![1.0; model.edges().len()],
        PAPER_SPRING_CONSTANT,
    )
}

/// The first component of the bundled sample mesh `name` (an OBJ or STL in `samples/`).
pub(crate) fn sample(name: &str) -> FacetModel {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("samples")
        .join(name);
    let soup = crate::ingest::read_mesh(&path, Default::default())
        .expect("sample reads")
        .soup;
    crate::mesh::validate(&soup)
        .expect("sample is valid")
        .components
        .remove(0)
}

/// A sphere of radius 50 with a small hole at its south pole: polar angle from 0 to
/// `reach` (a disk whose curvature no flat pattern can hold without folding when grown
/// triangle by triangle), `rings` rings of `sectors` quads, a fan at the north pole.
pub(crate) fn deep_bowl(reach: f64, rings: u32, sectors: u32) -> FacetModel {
    bowl(reach, rings, sectors, true)
}

/// [`deep_bowl`] without its north pole and fan: a second boundary loop (a hole).
pub(crate) fn deep_bowl_with_hole(reach: f64, rings: u32, sectors: u32) -> FacetModel {
    bowl(reach, rings, sectors, false)
}

fn bowl(reach: f64, rings: u32, sectors: u32, pole: bool) -> FacetModel {
    let mut positions = Vec::new();
    if pole {
        positions.push(DVec3::new(0.0, 0.0, 50.0));
    }
    for ring in 1..=rings {
        let polar = reach * ring as f64 / rings as f64;
        for sector in 0..sectors {
            let azimuth = 2.0 * PI * sector as f64 / sectors as f64;
            positions.push(
                50.0 * DVec3::new(
                    polar.sin() * azimuth.cos(),
                    polar.sin() * azimuth.sin(),
                    polar.cos(),
                ),
            );
        }
    }
    let first = u32::from(pole);
    let vertex = |ring: u32, sector: u32| first + (ring - 1) * sectors + sector % sectors;
    let mut triangles = Vec::new();
    if pole {
        for sector in 0..sectors {
            triangles.push([0, vertex(1, sector), vertex(1, sector + 1)]);
        }
    }
    for ring in 1..rings {
        for sector in 0..sectors {
            let (a, b) = (vertex(ring, sector), vertex(ring, sector + 1));
            let (c, d) = (vertex(ring + 1, sector), vertex(ring + 1, sector + 1));
            triangles.push([a, c, d]);
            triangles.push([a, d, b]);
        }
    }
    let soup = TriangleSoup::new(positions, triangles);
    crate::mesh::validate(&soup)
        .expect("the bowl is a valid mesh")
        .components
        .remove(0)
}
