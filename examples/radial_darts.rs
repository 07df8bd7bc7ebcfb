//! Baseline for the cut loop: straight radial darts laid by hand on a spherical cap, flattened
//! once, for `n` darts and depths (fractions of the meridian from the rim to the pole).
//!
//! ```text
//! python3 /work/shared/bench/cap_mesh.py /tmp/cap60.obj
//! cargo run --release --example radial_darts -- /tmp/cap60.obj 100 60
//! ```
//!
//! Arguments: the cap mesh, its sphere radius and half-angle in degrees (centred on the z axis,
//! pole at `(0, 0, radius)`). Prints the total dart length in radii and `E_S`, `E_C` in percent.

use std::f64::consts::TAU;
use std::path::Path;

use anyhow::Context;
use flatcut::cut::paths::{Adjacency, path_edges, path_length};
use flatcut::cut::seam::lay_polyline;
use flatcut::cut::split::split_along_edges;
use flatcut::flatten::{FlattenOptions, Stiffness, flatten};
use flatcut::ingest::read_mesh;
use flatcut::mesh::{FacetModel, validate};
use flatcut::progress::NoProgress;
use flatcut::units::Units;
use glam::DVec3;

/// Points laid along each dart's meridian before they snap to the mesh.
const POINTS_PER_DART: usize = 20;

fn main() -> anyhow::Result<()> {
    let arguments: Vec<String> = std::env::args().collect();
    anyhow::ensure!(
        arguments.len() == 4,
        "usage: radial_darts CAP.obj RADIUS HALF_ANGLE_DEGREES"
    );
    let radius: f64 = arguments[2].parse().context("radius")?;
    let half_angle = arguments[3]
        .parse::<f64>()
        .context("half-angle")?
        .to_radians();
    let input = read_mesh(Path::new(&arguments[1]), Units::default())?;
    let cap = validate(&input.soup)
        .map_err(|defects| anyhow::anyhow!("{defects}"))?
        .components
        .remove(0);
    for darts in [4usize, 5, 6, 8] {
        for depth in [0.5, 0.6, 0.75] {
            let (model, total) = with_darts(&cap, radius, half_angle, darts, depth)?;
            let flat = flatten(
                &model,
                &Stiffness::uniform(&model),
                &FlattenOptions::default(),
                &NoProgress,
            )?;
            let accuracy = flat.stats.accuracy;
            println!(
                "{darts} darts, depth {depth}: total {:.2} R, E_S {:.3} %, E_C {:.3} %, overlap {}",
                total / radius,
                accuracy.area_error * 100.0,
                accuracy.shape_error * 100.0,
                accuracy.overlap
            );
        }
    }
    Ok(())
}

/// The cap cut by `darts` evenly spaced radial darts of the given depth, and their total length.
fn with_darts(
    cap: &FacetModel,
    radius: f64,
    half_angle: f64,
    darts: usize,
    depth: f64,
) -> anyhow::Result<(FacetModel, f64)> {
    let mut model = cap.clone();
    let mut total = 0.0;
    for dart in 0..darts {
        let azimuth = TAU * (dart as f64 + 0.5) / darts as f64;
        let end = half_angle * (1.0 - depth);
        let points: Vec<DVec3> = (0..=POINTS_PER_DART)
            .map(|i| {
                let polar = half_angle + (end - half_angle) * i as f64 / POINTS_PER_DART as f64;
                radius
                    * DVec3::new(
                        polar.sin() * azimuth.cos(),
                        polar.sin() * azimuth.sin(),
                        polar.cos(),
                    )
            })
            .collect();
        let adjacency = Adjacency::new(&model);
        let blocked = vec![false; model.vertex_count()];
        let path = lay_polyline(&model, &adjacency, &blocked, &points, dart)?;
        total += path_length(&model, &path);
        let edges = path_edges(&model, &path).context("path along edges")?;
        model = split_along_edges(&model, &edges)?.model;
    }
    Ok((model, total))
}
