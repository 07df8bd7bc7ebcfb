//! Re-triangulating the cavity a fold polyline crosses: the triangles it meets, unfolded into a
//! plane chart, meshed again by constrained Delaunay refinement with the polyline's pieces as
//! constraint edges, which are tagged as fold edges.

use std::collections::{BTreeMap, HashMap, VecDeque};

use glam::DVec2;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use super::face_mesh::FaceMesh;
use super::fold_locate::{
    BOUNDARY_SPLIT_RATIO, Located, PIECE_GRADING, locate, min3, position, segment_meets_triangle,
};
use super::options::TessellateError;
use super::patch::{classify_regions, insert_point, refine, surround_with_guard_box};
use crate::geometry::distance_to_segment;
use crate::geometry::tolerance::{CORNER_TOLERANCE, INSIDE_TOLERANCE, ON_POLYLINE_RATIO};

/// Refinement may add at most this many vertices per expected triangle of the cavity's hull.
const VERTEX_BUDGET_FACTOR: f64 = 20.0;

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// Triangles a polyline piece meets, and every triangle sharing a vertex with one of them.
pub fn cavity(
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
pub fn boundary_vertices(mesh: &FaceMesh) -> Vec<bool> {
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
pub fn edge_components(mesh: &FaceMesh, cavity: &[bool]) -> Vec<Vec<usize>> {
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
pub fn unfold(mesh: &FaceMesh, component: &[usize]) -> HashMap<u32, DVec2> {
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
pub fn retriangulate(
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
