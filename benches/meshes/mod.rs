//! Meshes generated in Rust for the benchmarks, so they need nothing else: a hemisphere (radius
//! 100 mm, strongly non-developable) and a fender-like bicubic patch (about 600 x 400 mm, gently
//! curved both ways), each as a square grid of `cells` x `cells` cells (2 triangles per cell).

use flatcut::mesh::{FacetModel, TriangleSoup, validate};
use glam::DVec3;

/// A square grid of `cells` x `cells` cells over `[0, 1]²`, counter-clockwise triangles, mapped
/// to 3D by `surface`.
fn grid_mesh(cells: usize, surface: impl Fn(f64, f64) -> DVec3) -> FacetModel {
    let side = cells + 1;
    let positions = (0..side * side)
        .map(|k| {
            surface(
                (k % side) as f64 / cells as f64,
                (k / side) as f64 / cells as f64,
            )
        })
        .collect();
    let mut triangles = Vec::with_capacity(2 * cells * cells);
    for row in 0..cells {
        for column in 0..cells {
            let corner = (row * side + column) as u32;
            let (right, up) = (corner + 1, corner + side as u32);
            triangles.push([corner, right, up + 1]);
            triangles.push([corner, up + 1, up]);
        }
    }
    let mut components = validate(&TriangleSoup::new(positions, triangles))
        .expect("a generated grid is a valid mesh")
        .components;
    components.remove(0)
}

/// Hemisphere of radius 100 mm: the square mapped to the unit disk (elliptical grid mapping),
/// the disk to the hemisphere by the azimuthal equidistant map (disk radius 1 at the equator).
pub fn hemisphere(cells: usize) -> FacetModel {
    const RADIUS: f64 = 100.0;
    grid_mesh(cells, |u, v| {
        let (x, y) = (2.0 * u - 1.0, 2.0 * v - 1.0);
        let disk_x = x * (1.0 - 0.5 * y * y).sqrt();
        let disk_y = y * (1.0 - 0.5 * x * x).sqrt();
        let polar = (disk_x.hypot(disk_y)).min(1.0) * std::f64::consts::FRAC_PI_2;
        let azimuth = disk_y.atan2(disk_x);
        RADIUS
            * DVec3::new(
                polar.sin() * azimuth.cos(),
                polar.sin() * azimuth.sin(),
                polar.cos(),
            )
    })
}

/// Fender-like patch: a bicubic Bézier surface over 600 x 400 mm, crowned by up to about 90 mm
/// along its length and 40 mm across, with a slight skew.
pub fn fender(cells: usize) -> FacetModel {
    const CROWN_ALONG: [f64; 4] = [0.0, 85.0, 75.0, 10.0];
    const CROWN_ACROSS: [f64; 4] = [0.0, 40.0, 40.0, 5.0];
    let bernstein = |t: f64| {
        let s = 1.0 - t;
        [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
    };
    grid_mesh(cells, |u, v| {
        let (bu, bv) = (bernstein(u), bernstein(v));
        let mut point = DVec3::ZERO;
        for i in 0..4 {
            for j in 0..4 {
                let skew = if i == 1 || i == 2 {
                    6.0 * j as f64
                } else {
                    0.0
                };
                let control = DVec3::new(
                    200.0 * i as f64 + skew,
                    400.0 * j as f64 / 3.0,
                    CROWN_ALONG[i] + CROWN_ACROSS[j],
                );
                point += bu[i] * bv[j] * control;
            }
        }
        point
    })
}
