//! Locating fold polylines on a face mesh: each polyline point's triangle and barycentric
//! coordinates (through the triangles' corners in the surface's domain), and the polylines split
//! where they cross triangle edges.

use glam::{DVec2, DVec3};

use super::face_mesh::FaceMesh;
use super::options::TessellateError;
use crate::cad::SurfaceDomain;
use crate::geometry::barycentric;
use crate::geometry::tolerance::{CORNER_TOLERANCE, INSIDE_TOLERANCE};

/// Samples of a polyline segment when its length on the mesh is measured.
const LENGTH_SAMPLES: usize = 256;

/// Near a boundary vertex, polyline pieces are at most this many times the distance to it.
pub const BOUNDARY_SPLIT_RATIO: f64 = 2.5;

/// Consecutive pieces of a split polyline grow by at most this ratio.
pub const PIECE_GRADING: f64 = 1.5;

/// A polyline point located on the mesh: its triangle and barycentric coordinates there.
#[derive(Debug, Clone, Copy)]
pub struct Located {
    /// The triangle.
    pub triangle: usize,
    /// Barycentric coordinates in it.
    pub weights: [f64; 3],
}

/// Each triangle's corners in the domain: a periodic `u` unwrapped within the triangle and the
/// triangle moved by whole periods so that its mean `u` is in the domain's range; a pole's `u`
/// is the mean of the other corners'.
pub fn corner_domains(mesh: &FaceMesh, domain: &SurfaceDomain) -> Vec<[DVec2; 3]> {
    let parameters: Vec<(Option<f64>, f64)> = mesh
        .positions
        .iter()
        .map(|&p| domain.parameters(p))
        .collect();
    let period = domain.period().map(|(_, period)| period);
    mesh.triangles
        .iter()
        .map(|t| {
            let corner = t.map(|v| parameters[v as usize]);
            let reference = corner.iter().find_map(|c| c.0).unwrap_or(0.0);
            let unwrapped = corner.map(|(u, v)| {
                let u = u.map(|u| match period {
                    Some(p) => reference + (u - reference + p / 2.0).rem_euclid(p) - p / 2.0,
                    None => u,
                });
                (u, v)
            });
            let defined: Vec<f64> = unwrapped.iter().filter_map(|c| c.0).collect();
            let mean = defined.iter().sum::<f64>() / defined.len().max(1) as f64;
            let shift = domain.wrapped(mean) - mean;
            unwrapped.map(|(u, v)| DVec2::new(u.unwrap_or(mean) + shift, v))
        })
        .collect()
}

/// The triangle of `candidates` that contains `point` best (largest smallest weight).
pub fn locate(
    candidates: impl Iterator<Item = usize>,
    corners: impl Fn(usize) -> [DVec2; 3],
    point: DVec2,
) -> Option<Located> {
    candidates
        .filter_map(|t| barycentric(corners(t), point).map(|w| (t, w)))
        .max_by(|a, b| min3(a.1).total_cmp(&min3(b.1)).then(b.0.cmp(&a.0)))
        .map(|(triangle, weights)| Located { triangle, weights })
}

pub fn min3(w: [f64; 3]) -> f64 {
    w[0].min(w[1]).min(w[2])
}

/// The mesh point at a located position.
pub fn position(mesh: &FaceMesh, at: Located) -> DVec3 {
    let t = mesh.triangles[at.triangle];
    (0..3)
        .map(|k| mesh.positions[t[k] as usize] * at.weights[k])
        .sum()
}

/// Locates a domain point on the mesh, or the error that it is off the surface.
fn locate_on_mesh(
    mesh: &FaceMesh,
    corners: &[[DVec2; 3]],
    point: DVec2,
) -> Result<Located, TessellateError> {
    locate(0..mesh.triangles.len(), |t| corners[t], point)
        .filter(|at| min3(at.weights) >= -INSIDE_TOLERANCE)
        .ok_or(TessellateError::FoldOffSurface {
            u: point.x,
            v: point.y,
        })
}

/// A polyline's points split into pieces of at most the mesh size and at most the local size of
/// the mesh (lengths on the mesh), located. The local size at a point is the shortest edge of its
/// triangle and, near a vertex on the surface's boundary (a fold line ending on an edge), 2.5
/// times the distance to it. Each segment is split from both ends towards its middle, pieces
/// growing by at most [`PIECE_GRADING`]. Pieces are kept through refinement, so a piece much
/// longer than the mesh next to it (a rim sampled to the chord, the rows of a fan, a short bit
/// of a boundary edge the fold line split) would leave thin triangles.
pub fn split_polyline(
    mesh: &FaceMesh,
    corners: &[[DVec2; 3]],
    on_boundary: &[bool],
    points: &[DVec2],
    mesh_size: f64,
) -> Result<Vec<(DVec2, Located)>, TessellateError> {
    let on_mesh = |p: DVec2| locate_on_mesh(mesh, corners, p).map(|at| (p, at));
    let local_size = |at: Located| {
        let triangle = mesh.triangles[at.triangle];
        let t = triangle.map(|v| mesh.positions[v as usize]);
        let point = position(mesh, at);
        let shortest = t[0]
            .distance(t[1])
            .min(t[1].distance(t[2]))
            .min(t[2].distance(t[0]));
        let near_boundary = (0..3)
            .filter(|&k| on_boundary[triangle[k] as usize])
            .map(|k| point.distance(t[k]))
            .filter(|&d| d > CORNER_TOLERANCE * shortest)
            .fold(f64::INFINITY, f64::min);
        shortest
            .min(BOUNDARY_SPLIT_RATIO * near_boundary)
            .min(mesh_size)
    };
    let mut split = vec![on_mesh(points[0])?];
    for pair in points.windows(2) {
        let samples = (0..=LENGTH_SAMPLES)
            .map(|k| on_mesh(pair[0].lerp(pair[1], k as f64 / LENGTH_SAMPLES as f64)))
            .collect::<Result<Vec<_>, _>>()?;
        let mut cumulative = vec![0.0];
        for w in samples.windows(2) {
            let length = position(mesh, w[0].1).distance(position(mesh, w[1].1));
            cumulative.push(cumulative[cumulative.len() - 1] + length);
        }
        let total = cumulative[LENGTH_SAMPLES];
        let at_length = |s: f64| {
            let k = cumulative
                .partition_point(|&c| c <= s)
                .clamp(1, LENGTH_SAMPLES);
            let span = (cumulative[k] - cumulative[k - 1]).max(f64::MIN_POSITIVE);
            let fraction =
                ((k - 1) as f64 + (s - cumulative[k - 1]) / span) / LENGTH_SAMPLES as f64;
            pair[0].lerp(pair[1], fraction.clamp(0.0, 1.0))
        };
        // Distances from one end towards the middle, each step the local size, growing slowly.
        let march = |from_start: bool| -> Result<Vec<(f64, f64)>, TessellateError> {
            let length_at = |d: f64| if from_start { d } else { total - d };
            let mut steps = Vec::new();
            let (mut done, mut previous) = (0.0, f64::INFINITY);
            loop {
                let here = on_mesh(at_length(length_at(done)))?.1;
                let step = local_size(here).min(previous * PIECE_GRADING);
                if done + step >= total / 2.0 {
                    return Ok(steps);
                }
                done += step;
                previous = step;
                steps.push((done, step));
            }
        };
        let forward = march(true)?;
        let backward = march(false)?;
        let mut lengths: Vec<f64> = forward.iter().map(|s| s.0).collect();
        let mut ends: Vec<f64> = backward.iter().rev().map(|s| total - s.0).collect();
        // The middle gap: dropped into one piece, or split in two when it is too long.
        let last_step = |steps: &[(f64, f64)]| steps.last().map_or(f64::INFINITY, |s| s.1);
        let allowed = last_step(&forward).min(last_step(&backward)) * PIECE_GRADING;
        let (low, high) = (
            lengths.last().copied().unwrap_or(0.0),
            ends.first().copied().unwrap_or(total),
        );
        if high - low > allowed.min(mesh_size) {
            lengths.push((low + high) / 2.0);
        }
        lengths.append(&mut ends);
        for s in lengths {
            split.push(on_mesh(at_length(s))?);
        }
        split.push(on_mesh(pair[1])?);
    }
    Ok(split)
}

/// Whether the segment `p`-`q` meets the closed triangle `corners`.
pub fn segment_meets_triangle(p: DVec2, q: DVec2, corners: [DVec2; 3]) -> bool {
    let inside = |x: DVec2| barycentric(corners, x).is_some_and(|w| min3(w) >= -INSIDE_TOLERANCE);
    if inside(p) || inside(q) {
        return true;
    }
    let side = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    (0..3).any(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % 3]);
        side(a, b, p) * side(a, b, q) <= 0.0 && side(p, q, a) * side(p, q, b) <= 0.0
    })
}
