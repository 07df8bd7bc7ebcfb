//! The planar pieces of a ruled surface (consecutive rulings in one plane) meshed as one polygon
//! by the patch mesher, their straight section sides graded next to much shorter boundary edges.

use glam::{DVec2, DVec3};

use super::face_mesh::FaceMesh;
use super::patch::mesh_patch;
use crate::cad::{Frame, PatchGeometry, PatchSurface, Rulings};
use crate::geometry::tolerance::SLIVER_AREA_RATIO;
use crate::geometry::tolerance::{COLLINEAR_TOLERANCE, PLANE_MATCH_RATIO, PLANE_SIDE_MARGIN};

pub fn newell_normal(points: &[DVec3]) -> DVec3 {
    let count = points.len();
    (0..count)
        .map(|k| points[k].cross(points[(k + 1) % count]))
        .sum()
}

/// The boundary of the planar piece of rulings `first..=last`, counter-clockwise in the chart
/// (ruling index, height): along the bottom section, up the last ruling, back along the top
/// section, down the first ruling. Each vertex comes with whether the edge leaving it lies on a
/// section (true) or on a ruling shared with the next piece (false). Repeated vertices (an apex)
/// appear once.
pub fn plane_boundary(
    rulings: &Rulings,
    rows: &[Vec<u32>],
    bottom: &[u32],
    top: &[u32],
    first: usize,
    last: usize,
) -> Vec<(u32, bool)> {
    let [b0, t0] = rulings.pairs[first];
    let [b1, t1] = rulings.pairs[last];
    let chains: [(Vec<u32>, bool); 4] = [
        (bottom[b0..=b1].to_vec(), true),
        (rows[last].clone(), false),
        (top[t0..=t1].iter().rev().copied().collect(), true),
        (rows[first].iter().rev().copied().collect(), false),
    ];
    let mut boundary: Vec<(u32, bool)> = Vec::new();
    for (chain, on_section) in chains {
        let count = chain.len();
        for (k, v) in chain.into_iter().enumerate() {
            // A chain's last vertex starts the next chain: the next chain says where its edge is.
            let leaving = on_section && k + 1 < count;
            match boundary.last_mut() {
                Some(previous) if previous.0 == v => previous.1 = leaving,
                _ => boundary.push((v, leaving)),
            }
        }
    }
    if boundary.len() > 1 && boundary.first().map(|f| f.0) == boundary.last().map(|l| l.0) {
        boundary.pop();
    }
    boundary
}

/// Growth of consecutive gaps between the points added on a section side, from a much shorter
/// neighbouring boundary edge towards the side's own spacing.
const SIDE_GRADING: f64 = 1.2;

/// Integration step of the graded spacing, as a fraction of the local size.
const GRADING_STEP: f64 = 0.05;

/// Adds points on the straight section sides of `boundary` next to a much shorter boundary edge
/// (a fan's ruling graded towards its apex), so that the corner can be meshed with well-shaped
/// triangles: along a side (a run of collinear section edges) the gaps grow by
/// [`SIDE_GRADING`] from the neighbouring edge's length up to the side's own spacing, over as
/// many of its pieces as that takes. The side's points are kept (each piece gets points of its
/// own), and so are ruling sides, which are shared with the neighbouring piece.
pub fn graded_sides(mesh: &mut FaceMesh, boundary: &[(u32, bool)]) -> Vec<u32> {
    let count = boundary.len();
    let position = |k: usize, mesh: &FaceMesh| mesh.positions[boundary[k % count].0 as usize];
    let direction =
        |k: usize, mesh: &FaceMesh| (position(k + 1, mesh) - position(k, mesh)).normalize_or_zero();
    let continues_side = |k: usize, mesh: &FaceMesh| {
        let previous = (k + count - 1) % count;
        boundary[k].1
            && boundary[previous].1
            && direction(previous, mesh).cross(direction(k, mesh)).length() <= COLLINEAR_TOLERANCE
            && direction(previous, mesh).dot(direction(k, mesh)) > 0.0
    };
    let Some(start) = (0..count).find(|&k| !continues_side(k, mesh)) else {
        return boundary.iter().map(|&(v, _)| v).collect();
    };
    let mut graded = Vec::with_capacity(count);
    let mut k = start;
    while k < start + count {
        if !boundary[k % count].1 {
            graded.push(boundary[k % count].0);
            k += 1;
            continue;
        }
        let mut end = k + 1;
        while end < start + count && continues_side(end % count, mesh) {
            end += 1;
        }
        let side: Vec<DVec3> = (k..=end).map(|j| position(j, mesh)).collect();
        let before = position(k + count - 1, mesh).distance(side[0]);
        let after = side[side.len() - 1].distance(position(end + 1, mesh));
        for (piece, points) in graded_side(&side, before, after).into_iter().enumerate() {
            graded.push(boundary[(k + piece) % count].0);
            graded.extend(points.into_iter().map(|p| mesh.add_vertex(p)));
        }
        k = end;
    }
    graded
}

/// The points to add inside each piece of the straight side `side` (its points in order), whose
/// neighbouring boundary edges are `before` and `after` long: spread by the size
/// `min(piece, before + (g − 1) x, after + (g − 1) (L − x))` at distance `x` along the side
/// (`g` the grading, `L` the side's length), each piece getting the rounded integral of
/// `1 / size` as its number of gaps.
pub fn graded_side(side: &[DVec3], before: f64, after: f64) -> Vec<Vec<DVec3>> {
    let lengths: Vec<f64> = side.windows(2).map(|w| w[0].distance(w[1])).collect();
    let total: f64 = lengths.iter().sum();
    let growth = SIDE_GRADING - 1.0;
    let mut offset = 0.0;
    let mut added = Vec::with_capacity(lengths.len());
    for (piece, &length) in lengths.iter().enumerate() {
        let size = |x: f64| {
            length
                .min(before + growth * x)
                .min(after + growth * (total - x))
        };
        // Cumulative integral of 1 / size over the piece (midpoint rule, steps a fraction of
        // the size so that the graded end is resolved).
        let mut samples = vec![(0.0, 0.0)];
        while let Some(&(x, integral)) = samples.last().filter(|s| s.0 < length) {
            let step = (GRADING_STEP * size(offset + x)).min(length - x);
            let next = integral + step / size(offset + x + 0.5 * step);
            samples.push((x + step, next));
        }
        let integral = samples[samples.len() - 1].1;
        let gaps = (integral.round() as usize).max(1);
        let mut points = Vec::with_capacity(gaps - 1);
        let mut s = 0;
        for gap in 1..gaps {
            let target = integral * gap as f64 / gaps as f64;
            while samples[s + 1].1 < target {
                s += 1;
            }
            let ((x0, i0), (x1, i1)) = (samples[s], samples[s + 1]);
            let x = x0 + (x1 - x0) * (target - i0) / (i1 - i0);
            points.push(side[piece].lerp(side[piece + 1], x / length));
        }
        added.push(points);
        offset += length;
    }
    added
}

/// Meshes the planar polygon `boundary` (vertices of `mesh`, counter-clockwise seen from the side
/// the ruled meshes' normals point to) by the patch mesher on its plane, keeping the boundary's
/// vertices (nothing is added on the boundary, so neighbouring pieces stay conforming), with the
/// fold segments `folds` (fold line, ends in the plane) as constraint edges, tagged as fold
/// edges. False when the polygon has no plane or the patch mesher refuses it (the caller
/// stitches it instead).
pub fn mesh_plane(
    mesh: &mut FaceMesh,
    boundary: &[u32],
    folds: &[(u32, [DVec3; 2])],
    mesh_size: f64,
) -> bool {
    let points: Vec<DVec3> = boundary
        .iter()
        .map(|&v| mesh.positions[v as usize])
        .collect();
    let normal = newell_normal(&points);
    let longest_side = (0..points.len())
        .map(|k| points[k].distance(points[(k + 1) % points.len()]))
        .fold(0.0, f64::max);
    let Some(frame) = Frame::new(points[0], normal, points[1] - points[0]) else {
        return false;
    };
    let local = |p: DVec3| {
        DVec2::new(
            (p - frame.origin).dot(frame.x),
            (p - frame.origin).dot(frame.y),
        )
    };
    let outer: Vec<DVec2> = points.iter().map(|&p| local(p)).collect();
    let fold_polylines: Vec<(u32, Vec<DVec2>)> = folds
        .iter()
        .map(|&(line, ends)| (line, ends.map(local).to_vec()))
        .collect();
    let patch = PatchSurface {
        geometry: PatchGeometry::Plane(frame),
        outer: outer.clone(),
        holes: Vec::new(),
    };
    // Sides are at most the mesh size already: the patch mesher must not split them again.
    let split_above = longest_side.max(mesh_size) * (1.0 + PLANE_SIDE_MARGIN);
    let Ok(plane) = mesh_patch(&patch, &fold_polylines, split_above, f64::INFINITY) else {
        return false;
    };
    let tolerance = PLANE_MATCH_RATIO * longest_side;
    let mut index: Vec<Option<u32>> = vec![None; plane.positions.len()];
    for triangle in plane
        .triangles
        .iter()
        .filter(|t| !is_sliver(t, &plane.positions))
    {
        let corners = triangle.map(|v| {
            let v = v as usize;
            *index[v].get_or_insert_with(|| {
                match outer
                    .iter()
                    .position(|corner| corner.distance(plane.parameters[v]) <= tolerance)
                {
                    Some(k) => boundary[k],
                    None => mesh.add_vertex(plane.positions[v]),
                }
            })
        });
        mesh.triangles.push(corners);
    }
    for &([a, b], line) in &plane.fold_edges {
        if let (Some(a), Some(b)) = (index[a as usize], index[b as usize]) {
            mesh.fold_edges.push(([a, b], line));
        }
    }
    true
}

/// True for a sliver the planar mesher leaves between nearly collinear points of a straight
/// side (outside the piece, between the side and its convex hull; interior triangles are
/// refined to the minimum angle and are never this thin).
fn is_sliver(triangle: &[u32; 3], positions: &[DVec3]) -> bool {
    let [a, b, c] = triangle.map(|v| positions[v as usize]);
    let longest = a
        .distance_squared(b)
        .max(b.distance_squared(c))
        .max(c.distance_squared(a));
    0.5 * (b - a).cross(c - a).length() < SLIVER_AREA_RATIO * longest
}
