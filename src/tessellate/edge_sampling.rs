//! Sampling the edges of a B-rep shell once for all its faces: equal parameter steps within the
//! piece length and the chord tolerance, graded toward a cone's apex and toward the short pieces
//! of a neighbouring edge at a vertex.

use std::panic::{AssertUnwindSafe, catch_unwind};

use glam::DVec3;
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::Curve3D;

use super::curvature::apex_curvature;
use crate::cad::StepShell;
use crate::geometry::tolerance::{DEGENERATE_PIECE_RATIO, EDGE_END_RATIO};

/// Edge pieces are at most this fraction of the mesh size, so the patch mesher never splits a
/// boundary piece again (its length on the surface stays under the mesh size).
pub const EDGE_PIECE_RATIO: f64 = 0.8;
/// At most this many pieces per edge (a runaway count means a broken curve).
const MAX_EDGE_PIECES: usize = 200_000;
/// Bisection steps placing a sample at its distance from a cone's apex.
const APEX_BISECTION_STEPS: usize = 60;
/// Rounds of the edge piece count search.
const EDGE_ROUNDS: usize = 12;

/// An edge end at a cone's apex: which end (`true` the first vertex) and the cone's `κ d`
/// (see [`apex_curvature`]).
pub type EdgeApex = (bool, f64);

/// For each edge, the end at which it meets the apex of one of its faces' cones, if any.
pub fn edge_apexes(shell: &StepShell, size: f64) -> Vec<Option<EdgeApex>> {
    let mut apexes = vec![None; shell.edges.len()];
    for face in &shell.faces {
        for edge in face.boundaries.iter().flatten() {
            let Some(slot) = apexes.get_mut(edge.index) else {
                continue;
            };
            let (a, b) = shell.edges[edge.index].vertices;
            let (a, b) = (to_dvec(shell.vertices[a]), to_dvec(shell.vertices[b]));
            let found = catch_unwind(AssertUnwindSafe(|| {
                apex_curvature(&face.surface, a, b, size)
                    .map(|product| (true, product))
                    .or_else(|| apex_curvature(&face.surface, b, a, size).map(|p| (false, p)))
            }))
            .ok()
            .flatten();
            if let Some((at_start, product)) = found {
                let largest = slot.map_or(product, |(_, other): EdgeApex| other.max(product));
                *slot = Some((at_start, largest));
            }
        }
    }
    apexes
}

/// Samples an edge that ends at a cone's apex with pieces graded to the cone's curvature: a
/// triangle of side `h` at distance `d` from the apex strays `κ h² / 6` with `κ = (κ d) / d`,
/// so pieces there are at most [`EDGE_PIECE_RATIO`] of `√(6 chord d / (κ d))` (and of the mesh
/// size), placed at equal steps of `∫ 1 / size` along the distance from the apex. Both sides of
/// the cone's seam use these points, so the mesher meets pieces as small as its triangles at the
/// apex.
pub fn sample_toward_apex(
    curve: &Curve3D,
    ends: (DVec3, DVec3),
    (at_start, product): EdgeApex,
    mesh_size: f64,
    chord: f64,
) -> Vec<DVec3> {
    let (start, end) = edge_range(curve, ends, mesh_size);
    let (apex, far, t_apex, t_far) = if at_start {
        (ends.0, ends.1, start, end)
    } else {
        (ends.1, ends.0, end, start)
    };
    let longest = EDGE_PIECE_RATIO * mesh_size;
    let slope = EDGE_PIECE_RATIO * (6.0 * chord / product).sqrt();
    // Pieces `slope √d` up to `d_c`, then `longest`; `w` is ∫ 1 / size over the distance.
    let d_c = (longest / slope).powi(2);
    let w_c = 2.0 * d_c.sqrt() / slope;
    let weight = |d: f64| {
        if d < d_c {
            2.0 * d.sqrt() / slope
        } else {
            w_c + (d - d_c) / longest
        }
    };
    let distance_of = |w: f64| {
        if w < w_c {
            (0.5 * slope * w).powi(2)
        } else {
            d_c + (w - w_c) * longest
        }
    };
    let total = far.distance(apex);
    let pieces = (weight(total).ceil() as usize).clamp(1, MAX_EDGE_PIECES);
    let parameter_at = |d: f64| {
        // The distance from the apex grows along the edge (a ruling): bisection.
        let (mut low, mut high) = (t_apex, t_far);
        for _ in 0..APEX_BISECTION_STEPS {
            let middle = 0.5 * (low + high);
            if to_dvec(curve.subs(middle)).distance(apex) < d {
                low = middle;
            } else {
                high = middle;
            }
        }
        0.5 * (low + high)
    };
    let mut points: Vec<DVec3> = (0..=pieces)
        .map(|k| {
            let d = distance_of(weight(total) * k as f64 / pieces as f64);
            to_dvec(curve.subs(parameter_at(d)))
        })
        .collect();
    points[0] = apex;
    points[pieces] = far;
    if !at_start {
        points.reverse();
    }
    points
}

/// Edges whose pieces are more than this times longer than the shortest piece at one of their
/// vertices are resampled graded toward that vertex.
const GRADE_TRIGGER: f64 = 1.5;
/// Growth of the piece length per unit of length along a graded edge (pieces grow by about
/// 20 % from one to the next).
const GRADE_SLOPE: f64 = 0.2;
/// Dense samples per uniform piece of an edge's arc-length table.
const ARC_SAMPLES_PER_PIECE: usize = 16;

/// Edge samples graded at the vertices: where an edge with long pieces meets, at a vertex, an
/// edge with much shorter pieces (a long side of a sheet next to a small hole or bend radius),
/// the face between them would get a sliver triangle at the corner, since its boundary pieces
/// stay as they are. Such an edge is resampled with pieces growing from the shortest piece at
/// each of its vertices by [`GRADE_SLOPE`] per unit length up to its own piece length (equal
/// steps of `∫ ds / size(s)` along its arc length). Edges that end at a cone's apex keep their
/// own grading.
pub fn graded_at_vertices(
    shell: &StepShell,
    mut edges: Vec<Vec<DVec3>>,
    apexes: &[Option<EdgeApex>],
    size: f64,
) -> Vec<Vec<DVec3>> {
    let degenerate = DEGENERATE_PIECE_RATIO * size.max(f64::MIN_POSITIVE);
    let mut shortest = vec![f64::INFINITY; shell.vertices.len()];
    for (edge, samples) in shell.edges.iter().zip(&edges) {
        let (a, b) = edge.vertices;
        if let [first, second, ..] = samples.as_slice() {
            let piece = first.distance(*second);
            if piece > degenerate {
                shortest[a] = shortest[a].min(piece);
            }
        }
        if let [.., before, last] = samples.as_slice() {
            let piece = before.distance(*last);
            if piece > degenerate {
                shortest[b] = shortest[b].min(piece);
            }
        }
    }
    for (index, edge) in shell.edges.iter().enumerate() {
        let samples = &edges[index];
        if apexes[index].is_some() || samples.len() < 2 {
            continue;
        }
        let longest = samples
            .windows(2)
            .map(|w| w[0].distance(w[1]))
            .fold(0.0, f64::max);
        let (a, b) = edge.vertices;
        let ends = (shortest[a].min(longest), shortest[b].min(longest));
        if longest <= GRADE_TRIGGER * ends.0.min(ends.1) {
            continue;
        }
        let range = edge_range(
            &edge.curve,
            (samples[0], samples[samples.len() - 1]),
            longest,
        );
        edges[index] = sample_graded(
            |t| to_dvec(edge.curve.subs(t)),
            range,
            (samples[0], samples[samples.len() - 1]),
            (samples.len() - 1, longest),
            ends,
        );
    }
    edges
}

/// Samples `point` over the parameter `range` with pieces `min(longest, h₀ + k s, h₁ + k (L −
/// s))` long at arc length `s` (`k` = [`GRADE_SLOPE`], `L` the length, `(h₀, h₁)` = `ends`),
/// the ends exactly `ends_at`; `(pieces, longest)` is the edge's uniform sampling.
fn sample_graded(
    point: impl Fn(f64) -> DVec3,
    (start, end): (f64, f64),
    ends_at: (DVec3, DVec3),
    (pieces, longest): (usize, f64),
    ends: (f64, f64),
) -> Vec<DVec3> {
    let dense = (pieces * ARC_SAMPLES_PER_PIECE).max(64);
    let parameters: Vec<f64> = (0..=dense)
        .map(|k| start + (end - start) * k as f64 / dense as f64)
        .collect();
    let mut arc = vec![0.0];
    let mut previous = point(start);
    for &t in &parameters[1..] {
        let next = point(t);
        arc.push(arc[arc.len() - 1] + previous.distance(next));
        previous = next;
    }
    let length = arc[dense];
    let piece_at = |s: f64| {
        longest
            .min(ends.0 + GRADE_SLOPE * s)
            .min(ends.1 + GRADE_SLOPE * (length - s))
    };
    // Cumulative ∫ ds / size at the dense samples (trapezoids).
    let mut weight = vec![0.0];
    for k in 1..=dense {
        let step = arc[k] - arc[k - 1];
        let mean = 0.5 * (1.0 / piece_at(arc[k - 1]) + 1.0 / piece_at(arc[k]));
        weight.push(weight[k - 1] + step * mean);
    }
    let count = (weight[dense].ceil() as usize).clamp(1, MAX_EDGE_PIECES);
    let mut points = Vec::with_capacity(count + 1);
    points.push(ends_at.0);
    let mut k = 0;
    for j in 1..count {
        let target = weight[dense] * j as f64 / count as f64;
        while k + 1 < dense && weight[k + 1] < target {
            k += 1;
        }
        let span = weight[k + 1] - weight[k];
        let fraction = if span > 0.0 {
            (target - weight[k]) / span
        } else {
            0.0
        };
        points.push(point(
            parameters[k] + (parameters[k + 1] - parameters[k]) * fraction,
        ));
    }
    points.push(ends_at.1);
    points
}

/// Samples an edge's curve from `ends.0` to `ends.1` (see the module documentation).
pub fn sample_edge(
    curve: &Curve3D,
    ends: (DVec3, DVec3),
    mesh_size: f64,
    chord: f64,
) -> Vec<DVec3> {
    let range = edge_range(curve, ends, mesh_size);
    sample_curve(|t| to_dvec(curve.subs(t)), range, ends, mesh_size, chord)
}

/// Samples `point` over the parameter `range` in equal steps, each piece at most
/// [`EDGE_PIECE_RATIO`] of the mesh size and within the chord, the ends exactly `ends`.
pub fn sample_curve(
    point: impl Fn(f64) -> DVec3,
    (start, end): (f64, f64),
    ends: (DVec3, DVec3),
    mesh_size: f64,
    chord: f64,
) -> Vec<DVec3> {
    let closed = ends.0.distance(ends.1) <= f64::EPSILON * ends.0.length().max(1.0);
    let minimum = if closed { 3 } else { 1 };
    let longest = EDGE_PIECE_RATIO * mesh_size;
    let mut pieces = minimum;
    for _ in 0..EDGE_ROUNDS {
        let parameter = |k: f64| start + (end - start) * k / pieces as f64;
        let (mut length_ratio, mut chord_ratio) = (0.0_f64, 0.0_f64);
        for k in 0..pieces {
            let (a, b) = (point(parameter(k as f64)), point(parameter(k as f64 + 1.0)));
            let middle = point(parameter(k as f64 + 0.5));
            length_ratio = length_ratio.max(a.distance(b) / longest);
            chord_ratio = chord_ratio.max(middle.distance((a + b) * 0.5) / chord);
        }
        if length_ratio <= 1.0 && chord_ratio <= 1.0 {
            break;
        }
        let wanted = pieces as f64 * length_ratio.max(chord_ratio.sqrt()).max(1.0);
        let next = (wanted.ceil() as usize + 1).max(pieces + 1);
        if next > MAX_EDGE_PIECES {
            break;
        }
        pieces = next;
    }
    let mut points: Vec<DVec3> = (0..=pieces)
        .map(|k| point(start + (end - start) * k as f64 / pieces as f64))
        .collect();
    points[0] = ends.0;
    points[pieces] = ends.1;
    points
}

/// The curve's parameter range between the edge's vertices: its own range when its ends are the
/// vertices, else the parameters nearest the vertices (a vertex within a fraction of the mesh
/// size of the curve's end is that end).
fn edge_range(curve: &Curve3D, ends: (DVec3, DVec3), mesh_size: f64) -> (f64, f64) {
    let (start, end) = curve.range_tuple();
    let tolerance = EDGE_END_RATIO * mesh_size;
    let nearest = |vertex: DVec3, own: f64| {
        if to_dvec(curve.subs(own)).distance(vertex) <= tolerance {
            return own;
        }
        curve
            .search_nearest_parameter(Point3::new(vertex.x, vertex.y, vertex.z), None, 100)
            .unwrap_or(own)
    };
    (nearest(ends.0, start), nearest(ends.1, end))
}

/// A truck point as a glam vector.
pub fn to_dvec(p: Point3) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}

#[cfg(test)]
mod tests {
    use crate::tessellate::edge_sampling::*;

    #[test]
    fn graded_samples_grow_from_the_short_ends_to_the_edge_piece_length() {
        let line = |t: f64| DVec3::new(100.0 * t, 0.0, 0.0);
        let ends = (DVec3::ZERO, DVec3::new(100.0, 0.0, 0.0));
        let points = sample_graded(line, (0.0, 1.0), ends, (10, 10.0), (0.5, 2.0));
        let pieces: Vec<f64> = points.windows(2).map(|w| w[0].distance(w[1])).collect();
        assert_eq!(points[0], ends.0);
        assert_eq!(points[points.len() - 1], ends.1);
        assert!((pieces[0] - 0.5).abs() < 0.1, "{pieces:?}");
        assert!((pieces[pieces.len() - 1] - 2.0).abs() < 0.3, "{pieces:?}");
        assert!(pieces.iter().all(|&p| p <= 10.0 + 1e-9), "{pieces:?}");
        for pair in pieces.windows(2) {
            let ratio = pair[1].max(pair[0]) / pair[1].min(pair[0]);
            assert!(ratio < 1.3, "{pieces:?}");
        }
    }
}
