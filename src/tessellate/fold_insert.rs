//! Fold polylines carried onto a structured mesh by a constrained re-triangulation around them:
//! surfaces of revolution, and ruled surfaces where [`super::ruled_folds`] cannot carry them
//! along the rulings (a section welded to another surface, a fold across a cone fan other than
//! along one of its rows). The re-triangulated band spans several rulings, so it is not exactly
//! developable.
//!
//! Input: a [`FaceMesh`] made by a structured mesher, its surface's [`SurfaceDomain`], fold
//! polylines in that domain and the mesh size. Output: the same mesh, re-triangulated near each
//! polyline so that mesh edges follow it exactly, those edges tagged as fold edges.
//!
//! Method, the same for every kind of surface:
//! 1. Each triangle corner gets its domain coordinates (periodic `u` unwrapped within the
//!    triangle, a pole's `u` that of its neighbours), so a domain point is located in a triangle
//!    and mapped onto the mesh linearly. The polylines are split to the mesh size (lengths on
//!    the mesh).
//! 2. The cavity is every triangle a polyline piece meets, and every triangle sharing a vertex
//!    with one (room for well-shaped triangles). Each edge-connected part of it is unfolded into
//!    the plane triangle by triangle from its 3D edge lengths (exact on a developable surface,
//!    nearly so on a narrow band of a doubly curved one): a chart in part units.
//! 3. In the chart, the cavity's boundary edges and the polyline pieces are constraint edges of a
//!    Delaunay triangulation refined like a patch ([`super::patch`]: 25°, triangles of the mesh
//!    size, constraint edges kept, so the cavity's boundary still matches the mesh around it).
//! 4. The refined triangles inside the cavity replace it; each new vertex is mapped back onto
//!    the old mesh (its chart triangle's barycentric coordinates), so it lies on the old mesh,
//!    within the chord tolerance of the surface.

use std::collections::{BTreeMap, HashMap, VecDeque};

use glam::{DVec2, DVec3};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use super::TessellateError;
use super::face_mesh::FaceMesh;
use super::patch::{classify_regions, insert_point, refine, surround_with_guard_box};
use super::surface_domain::SurfaceDomain;
use crate::geometry::distance_to_segment;

/// Samples of a polyline segment when its length on the mesh is measured.
const LENGTH_SAMPLES: usize = 256;
/// Near a boundary vertex, polyline pieces are at most this many times the distance to it.
const BOUNDARY_SPLIT_RATIO: f64 = 2.5;
/// Consecutive pieces of a split polyline grow by at most this ratio.
const PIECE_GRADING: f64 = 1.5;
/// A point whose smallest barycentric coordinate is above minus this is inside a triangle.
const INSIDE_TOLERANCE: f64 = 1e-9;
/// A barycentric coordinate above one minus this puts a point on that corner.
const CORNER_TOLERANCE: f64 = 1e-9;
/// A chart vertex within this fraction of the mesh size of a polyline piece is on it.
const ON_POLYLINE_RATIO: f64 = 1e-7;
/// Refinement may add at most this many vertices per expected triangle of the cavity's hull.
const VERTEX_BUDGET_FACTOR: f64 = 20.0;

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// A polyline point located on the mesh: its triangle and barycentric coordinates there.
#[derive(Debug, Clone, Copy)]
struct Located {
    triangle: usize,
    weights: [f64; 3],
}

/// Inserts fold polylines `(fold line index, domain points)` into `mesh` (see the module
/// documentation).
pub fn insert_fold_polylines(
    mesh: &mut FaceMesh,
    domain: &SurfaceDomain,
    folds: &[(u32, Vec<DVec2>)],
    mesh_size: f64,
) -> Result<(), TessellateError> {
    if folds.is_empty() {
        return Ok(());
    }
    let corners = corner_domains(mesh, domain);
    let on_boundary = boundary_vertices(mesh);
    let mut polylines = Vec::with_capacity(folds.len());
    for (line, points) in with_crossings(folds) {
        let split = split_polyline(mesh, &corners, &on_boundary, &points, mesh_size)?;
        polylines.push((line, split));
    }
    let cavity = cavity(mesh, &corners, &polylines);
    let mut removed = vec![false; mesh.triangles.len()];
    let mut added = Vec::new();
    for component in edge_components(mesh, &cavity) {
        let chart = unfold(mesh, &component);
        added.extend(retriangulate(
            mesh, &component, &chart, &polylines, mesh_size,
        )?);
        for &t in &component {
            removed[t] = true;
        }
    }
    let kept = mesh
        .triangles
        .iter()
        .zip(&removed)
        .filter(|&(_, &r)| !r)
        .map(|(t, _)| *t);
    mesh.triangles = kept.chain(added).collect();
    Ok(())
}

/// Each triangle's corners in the domain: a periodic `u` unwrapped within the triangle and the
/// triangle moved by whole periods so that its mean `u` is in the domain's range; a pole's `u`
/// is the mean of the other corners'.
fn corner_domains(mesh: &FaceMesh, domain: &SurfaceDomain) -> Vec<[DVec2; 3]> {
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

/// Barycentric coordinates of `point` in the triangle `corners` (None when degenerate).
fn barycentric(corners: [DVec2; 3], point: DVec2) -> Option<[f64; 3]> {
    let [a, b, c] = corners;
    let area = (b - a).perp_dot(c - a);
    if area.abs() <= f64::MIN_POSITIVE {
        return None;
    }
    let wb = (point - a).perp_dot(c - a) / area;
    let wc = (b - a).perp_dot(point - a) / area;
    Some([1.0 - wb - wc, wb, wc])
}

/// The triangle of `candidates` that contains `point` best (largest smallest weight).
fn locate(
    candidates: impl Iterator<Item = usize>,
    corners: impl Fn(usize) -> [DVec2; 3],
    point: DVec2,
) -> Option<Located> {
    candidates
        .filter_map(|t| barycentric(corners(t), point).map(|w| (t, w)))
        .max_by(|a, b| min3(a.1).total_cmp(&min3(b.1)).then(b.0.cmp(&a.0)))
        .map(|(triangle, weights)| Located { triangle, weights })
}

fn min3(w: [f64; 3]) -> f64 {
    w[0].min(w[1]).min(w[2])
}

/// The mesh point at a located position.
fn position(mesh: &FaceMesh, at: Located) -> DVec3 {
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

/// The polylines with the points where they cross each other added to both (in the domain):
/// each crossing is computed once and is the same point of both, so that it becomes one vertex
/// and no short piece is left next to it.
pub(super) fn with_crossings(folds: &[(u32, Vec<DVec2>)]) -> Vec<(u32, Vec<DVec2>)> {
    let side = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    // Per polyline and segment: the crossings on it as (fraction along it, point).
    let mut found: Vec<Vec<Vec<(f64, DVec2)>>> = folds
        .iter()
        .map(|(_, points)| vec![Vec::new(); points.len().saturating_sub(1)])
        .collect();
    for first in 0..folds.len() {
        for second in first + 1..folds.len() {
            for (i, s) in folds[first].1.windows(2).enumerate() {
                for (j, o) in folds[second].1.windows(2).enumerate() {
                    let (d1, d2) = (side(o[0], o[1], s[0]), side(o[0], o[1], s[1]));
                    let (d3, d4) = (side(s[0], s[1], o[0]), side(s[0], s[1], o[1]));
                    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
                        let (t, t_other) = (d1 / (d1 - d2), d3 / (d3 - d4));
                        let point = s[0].lerp(s[1], t);
                        found[first][i].push((t, point));
                        found[second][j].push((t_other, point));
                    }
                }
            }
        }
    }
    folds
        .iter()
        .zip(found)
        .map(|((line, points), mut crossings)| {
            let mut result = vec![points[0]];
            for (k, q) in points.iter().skip(1).enumerate() {
                crossings[k].sort_by(|a, b| a.0.total_cmp(&b.0));
                result.extend(crossings[k].iter().map(|c| c.1));
                result.push(*q);
            }
            (*line, result)
        })
        .collect()
}

/// A polyline's points split into pieces of at most the mesh size and at most the local size of
/// the mesh (lengths on the mesh), located. The local size at a point is the shortest edge of its
/// triangle and, near a vertex on the surface's boundary (a fold line ending on an edge), 2.5
/// times the distance to it. Each segment is split from both ends towards its middle, pieces
/// growing by at most [`PIECE_GRADING`]. Pieces are kept through refinement, so a piece much
/// longer than the mesh next to it (a rim sampled to the chord, the rows of a fan, a short bit
/// of a boundary edge the fold line split) would leave thin triangles.
fn split_polyline(
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
fn segment_meets_triangle(p: DVec2, q: DVec2, corners: [DVec2; 3]) -> bool {
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

/// Triangles a polyline piece meets, and every triangle sharing a vertex with one of them.
fn cavity(
    mesh: &FaceMesh,
    corners: &[[DVec2; 3]],
    polylines: &[(u32, Vec<(DVec2, Located)>)],
) -> Vec<bool> {
    let mut met = vec![false; mesh.triangles.len()];
    for (_, points) in polylines {
        for pair in points.windows(2) {
            let (p, q) = (pair[0].0, pair[1].0);
            let (low, high) = (p.min(q), p.max(q));
            for (t, c) in corners.iter().enumerate() {
                let (c_low, c_high) = (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]));
                if c_low.cmple(high).all()
                    && c_high.cmpge(low).all()
                    && segment_meets_triangle(p, q, *c)
                {
                    met[t] = true;
                }
            }
        }
    }
    let mut touched = vec![false; mesh.positions.len()];
    for (t, _) in met.iter().enumerate().filter(|&(_, &m)| m) {
        for v in mesh.triangles[t] {
            touched[v as usize] = true;
        }
    }
    mesh.triangles
        .iter()
        .map(|t| t.iter().any(|&v| touched[v as usize]))
        .collect()
}

/// Whether each vertex is on the mesh's boundary (an edge of one triangle).
fn boundary_vertices(mesh: &FaceMesh) -> Vec<bool> {
    let mut uses: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            *uses.entry(edge_key(t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    let mut on_boundary = vec![false; mesh.positions.len()];
    for (&(a, b), _) in uses.iter().filter(|&(_, &count)| count == 1) {
        on_boundary[a as usize] = true;
        on_boundary[b as usize] = true;
    }
    on_boundary
}

fn edge_key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// The cavity's triangles grouped into parts connected across edges, in index order.
fn edge_components(mesh: &FaceMesh, cavity: &[bool]) -> Vec<Vec<usize>> {
    let mut by_edge: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    for (t, triangle) in mesh
        .triangles
        .iter()
        .enumerate()
        .filter(|&(t, _)| cavity[t])
    {
        for k in 0..3 {
            by_edge
                .entry(edge_key(triangle[k], triangle[(k + 1) % 3]))
                .or_default()
                .push(t);
        }
    }
    let mut component = vec![usize::MAX; mesh.triangles.len()];
    let mut components = Vec::new();
    for seed in (0..mesh.triangles.len()).filter(|&t| cavity[t]) {
        if component[seed] != usize::MAX {
            continue;
        }
        let label = components.len();
        component[seed] = label;
        let mut members = vec![seed];
        let mut stack = vec![seed];
        while let Some(t) = stack.pop() {
            let triangle = mesh.triangles[t];
            for k in 0..3 {
                for &n in &by_edge[&edge_key(triangle[k], triangle[(k + 1) % 3])] {
                    if component[n] == usize::MAX {
                        component[n] = label;
                        members.push(n);
                        stack.push(n);
                    }
                }
            }
        }
        members.sort_unstable();
        components.push(members);
    }
    components
}

/// The component unfolded into the plane from its 3D edge lengths, triangle by triangle across
/// shared edges (each vertex placed once), orientation kept: chart position per mesh vertex.
fn unfold(mesh: &FaceMesh, component: &[usize]) -> HashMap<u32, DVec2> {
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for &t in component {
        let triangle = mesh.triangles[t];
        for k in 0..3 {
            by_edge
                .entry(edge_key(triangle[k], triangle[(k + 1) % 3]))
                .or_default()
                .push(t);
        }
    }
    let at = |v: u32| mesh.positions[v as usize];
    let mut chart = HashMap::new();
    let [a, b, _] = mesh.triangles[component[0]];
    chart.insert(a, DVec2::ZERO);
    chart.insert(b, DVec2::new(at(a).distance(at(b)), 0.0));
    let mut visited: HashMap<usize, ()> = HashMap::new();
    let mut queue = VecDeque::from([component[0]]);
    visited.insert(component[0], ());
    while let Some(t) = queue.pop_front() {
        let triangle = mesh.triangles[t];
        place_missing_corner(mesh, triangle, &mut chart);
        for k in 0..3 {
            for &n in &by_edge[&edge_key(triangle[k], triangle[(k + 1) % 3])] {
                if visited.insert(n, ()).is_none() {
                    queue.push_back(n);
                }
            }
        }
    }
    chart
}

/// Places the one unplaced corner of `triangle` (if any) from the two placed ones, on the side
/// that keeps the triangle counter-clockwise.
fn place_missing_corner(mesh: &FaceMesh, triangle: [u32; 3], chart: &mut HashMap<u32, DVec2>) {
    let Some(k) = (0..3).find(|&k| !chart.contains_key(&triangle[k])) else {
        return;
    };
    let (corner, a, b) = (triangle[k], triangle[(k + 1) % 3], triangle[(k + 2) % 3]);
    let at = |v: u32| mesh.positions[v as usize];
    let (pa, pb) = (chart[&a], chart[&b]);
    let base = pa.distance(pb);
    let (da, db) = (at(corner).distance(at(a)), at(corner).distance(at(b)));
    let along = (da * da - db * db + base * base) / (2.0 * base);
    let height = (da * da - along * along).max(0.0).sqrt();
    let direction = (pb - pa) / base;
    chart.insert(corner, pa + direction * along + direction.perp() * height);
}

/// Re-triangulates one cavity component in its chart; returns the new triangles (mesh vertex
/// indices, new vertices added to the mesh) and records the fold edges.
fn retriangulate(
    mesh: &mut FaceMesh,
    component: &[usize],
    chart: &HashMap<u32, DVec2>,
    polylines: &[(u32, Vec<(DVec2, Located)>)],
    mesh_size: f64,
) -> Result<Vec<[u32; 3]>, TessellateError> {
    let charted: HashMap<usize, [DVec2; 3]> = component
        .iter()
        .map(|&t| (t, mesh.triangles[t].map(|v| chart[&v])))
        .collect();
    let chart_corners = |t: usize| charted[&t];
    let in_component = |t: usize| component.binary_search(&t).is_ok();
    let mut boundary: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for &t in component {
        let triangle = mesh.triangles[t];
        for k in 0..3 {
            *boundary
                .entry(edge_key(triangle[k], triangle[(k + 1) % 3]))
                .or_default() += 1;
        }
    }
    boundary.retain(|_, count| *count == 1);
    // Polyline points in chart coordinates; a point on a corner is that vertex, a point on a
    // boundary edge is put exactly on it and splits it.
    let mut on_boundary: BTreeMap<(u32, u32), Vec<(f64, DVec2)>> = BTreeMap::new();
    let mut chart_polylines = Vec::new();
    for (line, points) in polylines {
        let mut chart_points = Vec::new();
        for &(domain_point, at) in points.iter().filter(|p| in_component(p.1.triangle)) {
            let triangle = mesh.triangles[at.triangle];
            let place = chart_place(triangle, at.weights, chart, &boundary);
            if let ChartPlace::OnEdge { edge, along, point } = place {
                on_boundary.entry(edge).or_default().push((along, point));
            }
            chart_points.push((domain_point, place));
        }
        chart_polylines.push((*line, chart_points));
    }
    let mut cdt = Cdt::new();
    let mut vertex_of: HashMap<usize, u32> = HashMap::new();
    for &(a, b) in boundary.keys() {
        let chain = boundary_chain(chart[&a], chart[&b], on_boundary.get_mut(&(a, b)));
        let mut handles = Vec::with_capacity(chain.len());
        for &(_, point) in &chain {
            handles.push(insert_point(&mut cdt, point)?);
        }
        vertex_of.insert(handles[0].index(), a);
        vertex_of.insert(handles[handles.len() - 1].index(), b);
        for (pair, link) in handles.windows(2).zip(chain.windows(2)) {
            if pair[0] != pair[1] && cdt.try_add_constraint(pair[0], pair[1]).is_empty() {
                let p = link[1].1;
                return Err(TessellateError::CrossingConstraints { u: p.x, v: p.y });
            }
        }
    }
    let mut fold_charts = Vec::new();
    for (line, points) in &chart_polylines {
        let mut previous = None;
        let mut chart_points = Vec::with_capacity(points.len());
        for &(domain_point, place) in points {
            let point = place.point();
            let handle = insert_point(&mut cdt, point)?;
            if let ChartPlace::Corner { vertex, .. } = place {
                vertex_of.insert(handle.index(), vertex);
            }
            // Fold polylines may cross each other: a crossing becomes a vertex of both.
            if let Some(from) = previous
                && from != handle
                && cdt.add_constraint_and_split(from, handle, |p| p).is_empty()
            {
                return Err(TessellateError::CrossingConstraints {
                    u: domain_point.x,
                    v: domain_point.y,
                });
            }
            previous = Some(handle);
            chart_points.push(point);
        }
        fold_charts.push((*line, chart_points));
    }
    surround_with_guard_box(&mut cdt, mesh_size)?;
    let hull_area: f64 = cdt.inner_faces().map(|f| f.area()).sum();
    let expected = 4.0 * hull_area / (3f64.sqrt() * mesh_size * mesh_size);
    refine(
        &mut cdt,
        mesh_size,
        (VERTEX_BUDGET_FACTOR * expected.max(1.0)) as usize,
        false,
    );
    let contains = |corners: [DVec2; 3]| {
        let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
        locate(component.iter().copied(), chart_corners, centroid)
            .is_some_and(|at| min3(at.weights) >= -INSIDE_TOLERANCE)
    };
    let inside = classify_regions(&cdt, contains);
    let mut triangles = Vec::new();
    for face in cdt.inner_faces().filter(|f| inside[f.fix().index()]) {
        let mut corners = [0; 3];
        for (corner, v) in corners.iter_mut().zip(face.vertices()) {
            let index = v.fix().index();
            *corner = match vertex_of.get(&index) {
                Some(&vertex) => vertex,
                None => {
                    let point = DVec2::new(v.position().x, v.position().y);
                    let at = locate(component.iter().copied(), chart_corners, point).ok_or(
                        TessellateError::BadParameterPoint {
                            u: point.x,
                            v: point.y,
                        },
                    )?;
                    let vertex = mesh.add_vertex(position(mesh, at));
                    vertex_of.insert(index, vertex);
                    vertex
                }
            };
        }
        triangles.push(corners);
    }
    tag_fold_edges(mesh, &cdt, &vertex_of, &fold_charts, mesh_size);
    Ok(triangles)
}

/// The points of a cavity boundary edge from `a` to `b`: its ends, the polyline points on it (a
/// fold line ending on the surface's boundary) and, on each side of such a point, points graded
/// from [`BOUNDARY_SPLIT_RATIO`] times its nearer neighbour's distance by [`PIECE_GRADING`]:
/// boundary edges are kept through refinement, and a long bit of one next to the polyline's first
/// short piece would leave a thin triangle.
fn boundary_chain(
    a: DVec2,
    b: DVec2,
    fold_points: Option<&mut Vec<(f64, DVec2)>>,
) -> Vec<(f64, DVec2)> {
    let Some(points) = fold_points else {
        return vec![(0.0, a), (1.0, b)];
    };
    points.sort_by(|p, q| p.0.total_cmp(&q.0));
    let mut stops = vec![(0.0, false)];
    stops.extend(points.iter().map(|p| (p.0, true)));
    stops.push((1.0, false));
    let first_step = |k: usize| {
        let before = if k > 0 {
            stops[k].0 - stops[k - 1].0
        } else {
            1.0
        };
        let after = stops.get(k + 1).map_or(1.0, |s| s.0 - stops[k].0);
        BOUNDARY_SPLIT_RATIO * before.min(after)
    };
    let mut chain = vec![(0.0, a)];
    for k in 0..stops.len() - 1 {
        let ((t0, fold0), (t1, fold1)) = (stops[k], stops[k + 1]);
        let start = fold0.then(|| first_step(k));
        let end = fold1.then(|| first_step(k + 1));
        for d in graded_points(t1 - t0, start, end) {
            chain.push((t0 + d, a.lerp(b, t0 + d)));
        }
        let point = if fold1 { points[k].1 } else { b };
        chain.push((t1, point));
    }
    chain
}

/// Points inside a gap of `length`, graded from its start (first step `start`) and from its
/// end (first step `end`) by [`PIECE_GRADING`], meeting in its middle; no piece left shorter
/// than the step before it.
fn graded_points(length: f64, start: Option<f64>, end: Option<f64>) -> Vec<f64> {
    let limit = if start.is_some() && end.is_some() {
        length / 2.0
    } else {
        length
    };
    let march = |first: Option<f64>| {
        let mut distances = Vec::new();
        if let Some(mut step) = first {
            let mut done = step;
            while limit - done >= step {
                distances.push(done);
                step *= PIECE_GRADING;
                done += step;
            }
        }
        distances
    };
    let mut points = march(start);
    points.extend(march(end).iter().rev().map(|d| length - d));
    points
}

/// Where a polyline point goes in the chart.
#[derive(Debug, Clone, Copy)]
enum ChartPlace {
    /// On a mesh vertex.
    Corner {
        /// The vertex.
        vertex: u32,
        /// Its chart position.
        point: DVec2,
    },
    /// On a boundary edge of the cavity, at fraction `along` from its lower-numbered vertex.
    OnEdge {
        /// The edge (vertices in increasing order).
        edge: (u32, u32),
        /// Fraction along it.
        along: f64,
        /// Chart position, exactly on the edge's chart segment.
        point: DVec2,
    },
    /// Anywhere else.
    Inside(DVec2),
}

impl ChartPlace {
    fn point(&self) -> DVec2 {
        match *self {
            ChartPlace::Corner { point, .. }
            | ChartPlace::OnEdge { point, .. }
            | ChartPlace::Inside(point) => point,
        }
    }
}

/// The chart place of the point with barycentric `weights` in `triangle`.
fn chart_place(
    triangle: [u32; 3],
    weights: [f64; 3],
    chart: &HashMap<u32, DVec2>,
    boundary: &BTreeMap<(u32, u32), usize>,
) -> ChartPlace {
    if let Some(k) = (0..3).find(|&k| weights[k] >= 1.0 - CORNER_TOLERANCE) {
        return ChartPlace::Corner {
            vertex: triangle[k],
            point: chart[&triangle[k]],
        };
    }
    for k in 0..3 {
        let (a, b) = (triangle[(k + 1) % 3], triangle[(k + 2) % 3]);
        let edge = edge_key(a, b);
        if weights[k].abs() <= CORNER_TOLERANCE && boundary.contains_key(&edge) {
            let (wa, wb) = (weights[(k + 1) % 3], weights[(k + 2) % 3]);
            let along_from_a = wb / (wa + wb);
            let along = if a < b {
                along_from_a
            } else {
                1.0 - along_from_a
            };
            let point = chart[&edge.0].lerp(chart[&edge.1], along);
            return ChartPlace::OnEdge { edge, along, point };
        }
    }
    ChartPlace::Inside((0..3).map(|k| chart[&triangle[k]] * weights[k]).sum())
}

/// Records the constraint edges that lie on a polyline as fold edges.
fn tag_fold_edges(
    mesh: &mut FaceMesh,
    cdt: &Cdt,
    vertex_of: &HashMap<usize, u32>,
    chart_polylines: &[(u32, Vec<DVec2>)],
    mesh_size: f64,
) {
    let tolerance = ON_POLYLINE_RATIO * mesh_size.max(1.0);
    let on = |polyline: &[DVec2], point: DVec2| {
        polyline
            .windows(2)
            .any(|s| distance_to_segment(point, s[0], s[1]) <= tolerance)
    };
    for edge in cdt.undirected_edges() {
        if !cdt.is_constraint_edge(edge.fix()) {
            continue;
        }
        let [a, b] = edge
            .vertices()
            .map(|v| DVec2::new(v.position().x, v.position().y));
        let Some(vertices) = edge
            .vertices()
            .map(|v| vertex_of.get(&v.fix().index()).copied())
            .into_iter()
            .collect::<Option<Vec<u32>>>()
        else {
            continue;
        };
        for (line, polyline) in chart_polylines {
            if on(polyline, a) && on(polyline, b) && on(polyline, (a + b) * 0.5) {
                mesh.fold_edges.push(([vertices[0], vertices[1]], *line));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tessellate::ruled::mesh_ruled;
    use crate::tessellate::surface::{Frame, RuledCircle, RuledSurface, Surface};

    fn cylinder_panel() -> Surface {
        Surface::Ruled(RuledSurface::Circular {
            frame: Frame::WORLD,
            bottom: RuledCircle {
                center: DVec3::ZERO,
                radius: 150.0,
                tilt: 0.0,
            },
            top: RuledCircle {
                center: DVec3::new(0.0, 0.0, 200.0),
                radius: 150.0,
                tilt: 0.0,
            },
            angles: [0.0, 120f64.to_radians()],
        })
    }

    #[test]
    fn a_generator_fold_becomes_mesh_edges_and_keeps_the_area_and_the_shape() {
        let surface = cylinder_panel();
        let Surface::Ruled(ruled) = &surface else {
            unreachable!("a cylinder is ruled")
        };
        let mut mesh = mesh_ruled(ruled, 6.0, 0.03);
        let before = mesh.area();
        let domain = SurfaceDomain::new(&surface);
        let folds = vec![(0, vec![DVec2::new(61.3, 0.0), DVec2::new(61.3, 200.0)])];
        insert_fold_polylines(&mut mesh, &domain, &folds, 6.0).expect("inserts");
        assert!((mesh.area() - before).abs() / before < 1e-5);
        let length: f64 = mesh
            .fold_edges
            .iter()
            .map(|(e, _)| mesh.positions[e[0] as usize].distance(mesh.positions[e[1] as usize]))
            .sum();
        assert!((length - 200.0).abs() < 1e-9, "{length}");
        let worst = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
                [(a, b, c), (b, c, a), (c, a, b)]
                    .map(|(p, q, r)| (q - p).angle_between(r - p).to_degrees())
                    .into_iter()
                    .fold(180.0, f64::min)
            })
            .fold(180.0, f64::min);
        // The fold ends 0.44 mm from a rim vertex on both rims; the rims' edges are kept, which
        // leaves 13.1° there (every other triangle is above 20°).
        assert!(worst >= 13.0, "worst angle {worst}");
    }
}
