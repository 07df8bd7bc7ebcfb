//! Structured meshes of surfaces of revolution on parallels.
//!
//! Input: a [`RevolutionSurface`], a target edge length and a chord tolerance (part units).
//! Output: a [`FaceMesh`]. The profile is sampled (lines split to the mesh size, arcs also to the
//! chord tolerance); each profile point becomes a parallel split into as many pieces as its own
//! radius needs, so triangles keep their shape from the rim to a pole; a profile point on the axis
//! becomes a single pole vertex. Consecutive parallels are stitched. A full turn is opened along
//! the parallel's start angle: seam vertices are duplicated, not shared.

use glam::DVec3;

use super::strip::{FaceMesh, stitch_rows};
use super::surface::{RevolutionSurface, pieces_for_arc};

/// A profile point closer to the axis than this fraction of the mesh size is on the axis (a pole).
pub const POLE_TOLERANCE_RATIO: f64 = 1e-9;

/// Meshes a surface of revolution.
pub fn mesh_revolution(surface: &RevolutionSurface, mesh_size: f64, chord: f64) -> FaceMesh {
    let [start, end] = surface.angles;
    let range = end - start;
    let mut mesh = FaceMesh::default();
    let mut previous: Option<Vec<u32>> = None;
    for point in surface.profile.sample(mesh_size, chord) {
        let (radius, height) = (point.x, point.y);
        let row: Vec<u32> = if radius <= POLE_TOLERANCE_RATIO * mesh_size {
            vec![mesh.add_vertex(surface.frame.point(DVec3::new(0.0, 0.0, height)))]
        } else {
            let pieces = pieces_for_arc(radius, range, mesh_size, chord);
            (0..=pieces)
                .map(|k| {
                    let angle = start + range * k as f64 / pieces as f64;
                    let (sin, cos) = angle.sin_cos();
                    let local = DVec3::new(radius * cos, radius * sin, height);
                    mesh.add_vertex(surface.frame.point(local))
                })
                .collect()
        };
        if let Some(left) = &previous {
            // Parallels run with the angle and the profile goes from `left` to `row`: stitching
            // the new row first keeps the normal on the side of (angle × profile direction).
            stitch_rows(&row, left, &mesh.positions, &mut mesh.triangles);
        }
        previous = Some(row);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{PI, TAU};

    use glam::DVec2;

    use super::*;
    use crate::tessellate::surface::{Frame, Profile, ProfileSegment};

    #[test]
    fn a_spherical_cap_has_its_analytic_area() {
        let radius = 100.0;
        let cap_angle = PI / 3.0;
        let rim = DVec2::new(radius * cap_angle.sin(), radius * cap_angle.cos());
        let surface = RevolutionSurface {
            frame: Frame::WORLD,
            profile: Profile {
                start: DVec2::new(0.0, radius),
                segments: vec![ProfileSegment::Arc {
                    to: rim,
                    center: DVec2::ZERO,
                    sweep: -cap_angle,
                }],
            },
            angles: [0.0, TAU],
        };
        let mesh = mesh_revolution(&surface, 4.0, 0.01);
        let area: f64 = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum();
        let analytic = TAU * radius * radius * (1.0 - cap_angle.cos());
        assert!(
            (area - analytic).abs() / analytic < 1e-3,
            "{area} vs {analytic}"
        );
    }
}
