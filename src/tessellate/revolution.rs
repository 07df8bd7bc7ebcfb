//! Structured meshes of surfaces of revolution on parallels.
//!
//! Input: a [`RevolutionSurface`], a target edge length and a chord tolerance (part units).
//! Output: a [`FaceMesh`]. The profile is sampled (lines split to the mesh size, arcs also to the
//! chord tolerance); each profile point becomes a parallel whose piece count follows its radius by
//! doubling or halving the previous parallel's count (so triangles keep their shape from the rim
//! to a pole, and the stitch between two parallels is regular); a profile point on the axis
//! becomes a single pole vertex. Parallels of equal counts share meridians, so a profile of lines
//! (a cone) gives an exactly developable mesh. Consecutive parallels are stitched. A full turn is opened along
//! the parallel's start angle: seam vertices are duplicated, not shared.

use glam::{DVec2, DVec3};

use super::face_mesh::FaceMesh;
use super::strip::stitch_rows;
use crate::cad::{RevolutionSurface, pieces_for_arc};
use crate::geometry::tolerance::POLE_TOLERANCE_RATIO;

/// Meshes a surface of revolution.
pub fn mesh_revolution(surface: &RevolutionSurface, mesh_size: f64, chord: f64) -> FaceMesh {
    let [start, end] = surface.angles;
    let range = end - start;
    let mut mesh = FaceMesh::default();
    let mut previous: Option<Vec<u32>> = None;
    let mut previous_pieces: Option<usize> = None;
    let samples = surface.profile.sample(mesh_size, chord);
    for (index, &point) in samples.iter().enumerate() {
        let (radius, height) = (point.x, point.y);
        let row: Vec<u32> = if radius <= POLE_TOLERANCE_RATIO * mesh_size {
            vec![mesh.add_vertex(surface.frame.point(DVec3::new(0.0, 0.0, height)))]
        } else {
            let needed = parallel_pieces(&samples, index, range, mesh_size, chord);
            let pieces = previous_pieces.map_or(needed, |p| doubled_or_halved(p, needed));
            previous_pieces = Some(pieces);
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

/// Pieces parallel `index` needs: at most `mesh_size` long, and within `chord` of the surface.
/// A chord of a parallel of radius r leaves the surface by its sagitta times the radial part of
/// the surface normal, which is the profile tangent's axial part |t_z|: for the angular step the
/// parallel counts as a circle of radius r |t_z| (a flat disk not at all, a cylinder fully).
fn parallel_pieces(
    samples: &[DVec2],
    index: usize,
    range: f64,
    mesh_size: f64,
    chord: f64,
) -> usize {
    let radius = samples[index].x;
    let before = samples[index.saturating_sub(1)];
    let after = samples[(index + 1).min(samples.len() - 1)];
    let axial = (after - before).normalize_or_zero().y.abs();
    let by_length = pieces_for_arc(radius, range, mesh_size, f64::INFINITY);
    if axial <= 0.0 {
        return by_length;
    }
    by_length.max(pieces_for_arc(radius * axial, range, f64::INFINITY, chord))
}

/// The count reached from `previous` by doubling until it is at least `needed`, or by halving
/// while the half still is.
fn doubled_or_halved(previous: usize, needed: usize) -> usize {
    let mut pieces = previous.max(1);
    while pieces < needed {
        pieces *= 2;
    }
    while pieces.is_multiple_of(2) && pieces / 2 >= needed {
        pieces /= 2;
    }
    pieces
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{PI, TAU};

    use crate::cad::{Frame, Profile, ProfileSegment};
    use crate::tessellate::revolution::*;

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
