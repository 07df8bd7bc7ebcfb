//! Geodesic straightening of a cut path (issue 13, smooth cuts): the shortest path between the two
//! ends of an edge path, inside a strip of faces around it, crossing faces instead of following
//! edges.
//!
//! Input: a [`FacetModel`] and a simple vertex path (consecutive vertices share an edge, at least
//! two vertices), model units. Output: the straightened path as a sequence of [`SurfacePoint`]s
//! from the same first to the same last vertex: mesh vertices it passes through and points where
//! it crosses an edge (a parameter along the edge), consecutive points on one face.
//!
//! Method, in the spirit of edge-flip geodesics (Sharp and Crane 2020, "You Can Find Geodesic
//! Paths in Triangle Meshes by Just Flipping Edges") without changing the mesh: the faces on the
//! left of the path form a strip (each face shares an edge with the next); the strip is unfolded
//! into the plane face by face and the shortest path inside it is found by the funnel algorithm
//! (Lee and Preparata 1984; the "simple stupid funnel" of Mononen). Where that path bends around
//! a vertex of the strip, the fan of faces the strip takes around the vertex is swapped for the
//! fan on its other side, and the swap is kept when the path gets shorter; this is repeated until
//! no swap shortens it (a geodesic: every bend has at least π on both sides) or
//! [`MAX_FAN_SWAPS`] were tried. A crossing closer to an edge's end than [`SNAP_FRACTION`] of the
//! edge becomes that end ([`SurfacePoint::Near`], remembering the crossing), so the mesh split
//! along the path has no sliver triangles; the cut may then move the vertex onto the crossing.
//!
//! For a cut's extension, [`straight_on`] traces the straightest geodesic on from the cut's inner
//! end, [`turn_at_tip`] measures how far a direction turns from it, and [`largest_turn`] how far
//! an edge path bends (to keep an edge path that is already straight).

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};

use crate::mesh::{FacetModel, NONE};

/// A crossing closer to an end of its edge than this fraction of the edge's length is moved to
/// that end: splitting the edge there would make sliver triangles (with 12 %, their flat
/// triangles blocked the warm re-flattening of the torus, which stalled at 5 %; docs/cutting.md).
pub const SNAP_FRACTION: f64 = 0.2;

/// A crossing closer to an end of its edge than this fraction of the edge passes through that
/// end (round-off of a path through the vertex itself).
pub const ON_VERTEX: f64 = 1e-9;

/// At most this many fan swaps per path vertex are tried before the straightening stops.
pub const MAX_FAN_SWAPS: usize = 8;

/// A point of a path on the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SurfacePoint {
    /// A mesh vertex.
    Vertex(u32),
    /// A point inside edge `edge`, at `t` in `(0, 1)` from its first vertex to its second
    /// (`FacetModel::edges`).
    Edge {
        /// The edge's index.
        edge: usize,
        /// Where on it, from its first vertex (0) to its second (1).
        t: f64,
    },
    /// A mesh vertex standing for a crossing of one of its edges within [`SNAP_FRACTION`] of it:
    /// the path runs through `vertex`, and runs straight if the vertex moves onto the crossing,
    /// at `t` along `edge` as for [`SurfacePoint::Edge`].
    Near {
        /// The vertex the crossing snapped to.
        vertex: u32,
        /// The crossed edge, one of the vertex's.
        edge: usize,
        /// Where the crossing is on it, from its first vertex (0) to its second (1).
        t: f64,
    },
}

impl SurfacePoint {
    /// The mesh vertex the path runs through at this point, if any.
    pub fn vertex(self) -> Option<u32> {
        match self {
            SurfacePoint::Vertex(v) | SurfacePoint::Near { vertex: v, .. } => Some(v),
            SurfacePoint::Edge { .. } => None,
        }
    }
}

/// The geodesic straightening of the edge path `path` between its two ends; see the module
/// documentation. `None` when the path has fewer than two vertices, or a strip cannot be laid
/// along it (an edge of the path is a boundary edge, or the left fan of an inner vertex meets
/// the boundary).
pub fn straighten(model: &FacetModel, path: &[u32]) -> Option<Vec<SurfacePoint>> {
    if path.len() < 2 {
        return None;
    }
    let (start, end) = (path[0], path[path.len() - 1]);
    let mut strip = trimmed(model, left_strip(model, path)?, start, end)?;
    let mut corners = funnel(model, &strip, start, end)?;
    let mut swaps = 0;
    'shorten: while swaps < MAX_FAN_SWAPS * path.len() {
        for corner in &corners.points[1..corners.points.len() - 1] {
            let Some(swapped) = swap_fan(model, &strip, corner) else {
                continue;
            };
            swaps += 1;
            let Some(swapped) = trimmed(model, swapped, start, end) else {
                continue;
            };
            let Some(shorter) = funnel(model, &swapped, start, end) else {
                continue;
            };
            if shorter.length < corners.length * (1.0 - 1e-9) {
                strip = swapped;
                corners = shorter;
                continue 'shorten;
            }
        }
        break;
    }
    surface_points(model, &corners)
}

/// The faces on the left of the path, in order: the face left of the first edge, then at every
/// inner vertex the fan around it from the face left of the edge in to the face left of the edge
/// out.
fn left_strip(model: &FacetModel, path: &[u32]) -> Option<Vec<u32>> {
    let mut strip = vec![left_face(model, path[0], path[1])?];
    for window in path.windows(3) {
        let fan = left_fan(model, window[0], window[1], window[2])?;
        strip.extend_from_slice(&fan[1..]);
    }
    Some(strip)
}

/// The faces around `centre` on the left of a walk `previous → centre → next`, from the face on
/// the left of the edge in to the face on the left of the edge out.
fn left_fan(model: &FacetModel, previous: u32, centre: u32, next: u32) -> Option<Vec<u32>> {
    let target = left_face(model, centre, next)?;
    let mut fan = vec![left_face(model, previous, centre)?];
    let mut face = fan[0];
    while face != target {
        let corners = model.triangles()[face as usize];
        let after = corners[(corner_of(corners, centre)? + 1) % 3];
        face = across(model, face, centre, after)?;
        if fan.len() > model.vertex_faces(centre).len() {
            return None;
        }
        fan.push(face);
    }
    Some(fan)
}

/// The largest geodesic turn (radians) of an edge path at its inner vertices: at each, how far
/// the angle on its left is from half the angle around the vertex (a straight line on a
/// developable surface has π on each side). `None` if a vertex's left fan meets the boundary.
pub fn largest_turn(model: &FacetModel, path: &[u32]) -> Option<f64> {
    let positions = model.positions();
    let corner = |face: u32, at: u32| {
        let corners = model.triangles()[face as usize];
        let k = corner_of(corners, at).unwrap_or(0);
        let p = positions[at as usize];
        let (u, w) = (corners[(k + 1) % 3], corners[(k + 2) % 3]);
        (positions[u as usize] - p).angle_between(positions[w as usize] - p)
    };
    let mut largest: f64 = 0.0;
    for window in path.windows(3) {
        let (previous, centre, next) = (window[0], window[1], window[2]);
        let fan = left_fan(model, previous, centre, next)?;
        let around: f64 = model
            .vertex_faces(centre)
            .iter()
            .map(|&f| corner(f, centre))
            .sum();
        // Every face of the fan lies on the left with its whole corner at `centre`.
        let left: f64 = fan.iter().map(|&f| corner(f, centre)).sum();
        largest = largest.max((left - 0.5 * around).abs());
    }
    Some(largest)
}

/// The face holding the directed edge `a → b` in its counter-clockwise order (the face on the
/// left of a walk from `a` to `b`).
fn left_face(model: &FacetModel, a: u32, b: u32) -> Option<u32> {
    let edge = model.find_edge(a, b)?;
    model.edge_faces()[edge]
        .into_iter()
        .filter(|&f| f != NONE)
        .find(|&f| {
            let corners = model.triangles()[f as usize];
            (0..3).any(|k| corners[k] == a && corners[(k + 1) % 3] == b)
        })
}

/// The index of `vertex` among a face's corners.
fn corner_of(corners: [u32; 3], vertex: u32) -> Option<usize> {
    corners.iter().position(|&c| c == vertex)
}

/// The face on the other side of the edge `a`–`b` from `face`, or `None` on the boundary.
fn across(model: &FacetModel, face: u32, a: u32, b: u32) -> Option<u32> {
    let edge = model.find_edge(a, b)?;
    let [first, second] = model.edge_faces()[edge];
    let other = if first == face { second } else { first };
    (other != NONE).then_some(other)
}

/// The strip with its loops erased (where it comes back to a face, the faces in between are
/// dropped: a strip along a sharp turn of the path passes a face by the turn twice), cut down to
/// start at its last face holding `start` and to end at its first face (after that) holding
/// `end`, so that no portal holds either end; `None` if the strip misses an end.
fn trimmed(model: &FacetModel, strip: Vec<u32>, start: u32, end: u32) -> Option<Vec<u32>> {
    let strip = loop_erased(strip);
    let holds = |f: u32, v: u32| model.triangles()[f as usize].contains(&v);
    let first = strip.iter().rposition(|&f| holds(f, start))?;
    let last = first + strip[first..].iter().position(|&f| holds(f, end))?;
    Some(strip[first..=last].to_vec())
}

/// The faces in order with every loop (a stretch from a face back to itself) cut out; the faces
/// kept still follow each other across shared edges.
fn loop_erased(strip: Vec<u32>) -> Vec<u32> {
    let mut kept: Vec<u32> = Vec::with_capacity(strip.len());
    let mut index: BTreeMap<u32, usize> = BTreeMap::new();
    for face in strip {
        if let Some(&at) = index.get(&face) {
            for dropped in kept.drain(at + 1..) {
                index.remove(&dropped);
            }
        } else {
            index.insert(face, kept.len());
            kept.push(face);
        }
    }
    kept
}

/// An end of a portal: a vertex and where the unfolding put it.
#[derive(Debug, Clone, Copy)]
struct Placed {
    vertex: u32,
    at: DVec2,
}

/// The shortest path in an unfolded strip: its corners (the ends and the strip vertices it bends
/// around), each with the index of the portal it was found at, and its length.
struct Corners {
    points: Vec<(usize, Placed)>,
    portals: Vec<[Placed; 2]>,
    length: f64,
}

/// The strip unfolded into the plane: per portal (the edge between consecutive faces) its right
/// and left ends for a walk along the strip, with the start as the first portal and the end as
/// the last (both degenerate).
fn unfold(model: &FacetModel, strip: &[u32], start: u32, end: u32) -> Option<Vec<[Placed; 2]>> {
    let positions = model.positions();
    let first = model.triangles()[strip[0] as usize];
    let [a, b, c] = first.map(|v| positions[v as usize]);
    let mut placed: Vec<Placed> = vec![
        Placed {
            vertex: first[0],
            at: DVec2::ZERO,
        },
        Placed {
            vertex: first[1],
            at: DVec2::new(a.distance(b), 0.0),
        },
    ];
    placed.push(Placed {
        vertex: first[2],
        at: apex(placed[0].at, placed[1].at, a.distance(c), b.distance(c)),
    });
    let find = |placed: &[Placed], v: u32| placed.iter().rev().find(|p| p.vertex == v).copied();
    let mut portals = vec![[find(&placed, start)?; 2]];
    for pair in strip.windows(2) {
        let corners = model.triangles()[pair[0] as usize];
        let next = model.triangles()[pair[1] as usize];
        let k =
            (0..3).find(|&k| next.contains(&corners[k]) && next.contains(&corners[(k + 1) % 3]))?;
        let (right, left) = (corners[k], corners[(k + 1) % 3]);
        let (right, left) = (find(&placed, right)?, find(&placed, left)?);
        portals.push([right, left]);
        let third = *next
            .iter()
            .find(|&&v| v != right.vertex && v != left.vertex)?;
        let p = positions[third as usize];
        let at = apex(
            left.at,
            right.at,
            positions[left.vertex as usize].distance(p),
            positions[right.vertex as usize].distance(p),
        );
        placed.push(Placed { vertex: third, at });
    }
    portals.push([find(&placed, end)?; 2]);
    Some(portals)
}

/// The point `c` with `|ac| = to_a`, `|bc| = to_b`, on the left of `a → b` (so `a, b, c` run
/// counter-clockwise).
fn apex(a: DVec2, b: DVec2, to_a: f64, to_b: f64) -> DVec2 {
    let side = b - a;
    let length = side.length();
    let along = (to_a * to_a - to_b * to_b + length * length) / (2.0 * length);
    let height = (to_a * to_a - along * along).max(0.0).sqrt();
    let unit = side / length;
    a + unit * along + unit.perp() * height
}

/// Twice the signed area of `o, a, b`: positive when `b` is on the left of `o → a`.
fn cross(o: DVec2, a: DVec2, b: DVec2) -> f64 {
    (a - o).perp_dot(b - o)
}

/// The shortest path from `start` to `end` inside the unfolded strip (the funnel algorithm).
fn funnel(model: &FacetModel, strip: &[u32], start: u32, end: u32) -> Option<Corners> {
    let portals = unfold(model, strip, start, end)?;
    let mut points = vec![(0, portals[0][0])];
    let (mut left_index, mut right_index) = (0, 0);
    let mut apex = portals[0][0];
    let (mut left, mut right) = (apex, apex);
    let mut i = 1;
    while i < portals.len() {
        let [new_right, new_left] = portals[i];
        if cross(apex.at, right.at, new_right.at) >= 0.0 {
            if apex.at == right.at || cross(apex.at, left.at, new_right.at) < 0.0 {
                (right, right_index) = (new_right, i);
            } else {
                let index = left_index;
                apex = left;
                points.push((index, apex));
                (left, right, left_index, right_index) = (apex, apex, index, index);
                i = index + 1;
                continue;
            }
        }
        if cross(apex.at, left.at, new_left.at) <= 0.0 {
            if apex.at == left.at || cross(apex.at, right.at, new_left.at) > 0.0 {
                (left, left_index) = (new_left, i);
            } else {
                let index = right_index;
                apex = right;
                points.push((index, apex));
                (left, right, left_index, right_index) = (apex, apex, index, index);
                i = index + 1;
                continue;
            }
        }
        i += 1;
    }
    let last = portals.len() - 1;
    if points.last().is_none_or(|&(index, _)| index != last) {
        points.push((last, portals[last][0]));
    }
    let length = points
        .windows(2)
        .map(|pair| pair[0].1.at.distance(pair[1].1.at))
        .sum();
    Some(Corners {
        points,
        portals,
        length,
    })
}

/// The strip with the fan it takes around a corner's vertex swapped for the fan on the vertex's
/// other side, or `None` when that side meets the boundary.
fn swap_fan(model: &FacetModel, strip: &[u32], corner: &(usize, Placed)) -> Option<Vec<u32>> {
    let (portal, placed) = *corner;
    let vertex = placed.vertex;
    let holds = |f: u32| model.triangles()[f as usize].contains(&vertex);
    // Portal `portal` lies between faces `portal - 1` and `portal`; both hold the vertex.
    let mut first = portal.checked_sub(1)?;
    while first > 0 && holds(strip[first - 1]) {
        first -= 1;
    }
    let mut last = portal;
    if last >= strip.len() {
        return None;
    }
    while last + 1 < strip.len() && holds(strip[last + 1]) {
        last += 1;
    }
    let mut fan = Vec::new();
    let mut face = strip[first];
    let mut came_from = strip[first + 1];
    loop {
        let corners = model.triangles()[face as usize];
        let k = corner_of(corners, vertex)?;
        let sides = [corners[(k + 1) % 3], corners[(k + 2) % 3]];
        let next = sides
            .into_iter()
            .filter_map(|other| across(model, face, vertex, other))
            .find(|&f| f != came_from)?;
        if next == strip[last] {
            break;
        }
        if fan.len() > model.vertex_faces(vertex).len() {
            return None;
        }
        fan.push(next);
        (came_from, face) = (face, next);
    }
    let mut swapped = strip[..=first].to_vec();
    swapped.extend(fan);
    swapped.extend_from_slice(&strip[last..]);
    Some(swapped)
}

/// The path as surface points: its start, where it crosses each portal (a vertex when it passes
/// through one of the portal's ends or comes within [`SNAP_FRACTION`] of it), its end; repeated
/// vertices merged and crossings of edges at a vertex the path passes through dropped.
fn surface_points(model: &FacetModel, corners: &Corners) -> Option<Vec<SurfacePoint>> {
    let mut points = Vec::with_capacity(corners.portals.len());
    let mut segment = 0;
    for (i, &[right, left]) in corners.portals.iter().enumerate() {
        while segment + 1 < corners.points.len() - 1 && corners.points[segment + 1].0 <= i {
            segment += 1;
        }
        if i == 0 || i == corners.portals.len() - 1 {
            points.push(SurfacePoint::Vertex(right.vertex));
            continue;
        }
        let (from, to) = (corners.points[segment].1, corners.points[segment + 1].1);
        let through = [from, to]
            .into_iter()
            .find(|c| c.vertex == right.vertex || c.vertex == left.vertex);
        points.push(match through {
            Some(corner) => SurfacePoint::Vertex(corner.vertex),
            None => crossing(model, right, left, from.at, to.at)?,
        });
    }
    Some(simplified(model, points))
}

/// Where the segment `from → to` crosses the portal from `right` to `left`, snapped to an end
/// within [`SNAP_FRACTION`] ([`SurfacePoint::Near`]).
fn crossing(
    model: &FacetModel,
    right: Placed,
    left: Placed,
    from: DVec2,
    to: DVec2,
) -> Option<SurfacePoint> {
    let direction = to - from;
    let side = left.at - right.at;
    let denominator = side.perp_dot(direction);
    let t = if denominator.abs() > f64::EPSILON * side.length() * direction.length() {
        ((from - right.at).perp_dot(direction) / denominator).clamp(0.0, 1.0)
    } else {
        0.5
    };
    let edge = model.find_edge(right.vertex, left.vertex)?;
    Some(edge_point(model, edge, right.vertex, t))
}

/// The points with consecutive repeats of a vertex merged and every edge crossing next to a
/// vertex point of that edge dropped (the path passes through the vertex instead). Of repeated
/// [`SurfacePoint::Near`] points of one vertex the one whose crossing lies nearest the vertex
/// stays; a plain vertex point wins over them.
fn simplified(model: &FacetModel, points: Vec<SurfacePoint>) -> Vec<SurfacePoint> {
    let on = |point: &SurfacePoint, vertex: u32| match *point {
        SurfacePoint::Vertex(v) | SurfacePoint::Near { vertex: v, .. } => v == vertex,
        SurfacePoint::Edge { edge, .. } => model.edges()[edge].contains(&vertex),
    };
    let mut kept: Vec<SurfacePoint> = Vec::with_capacity(points.len());
    for mut point in points {
        if let Some(v) = point.vertex() {
            while let Some(&last) = kept.last().filter(|last| on(last, v)) {
                kept.pop();
                if last.vertex() == Some(v) {
                    point = nearer(model, point, last);
                }
            }
        } else if let Some(v) = kept.last().and_then(|last| last.vertex())
            && on(&point, v)
        {
            continue;
        }
        kept.push(point);
    }
    kept
}

/// Of two points at the same vertex, a plain vertex point, else the `Near` point whose crossing
/// is nearer the vertex (as a fraction of its edge).
fn nearer(model: &FacetModel, a: SurfacePoint, b: SurfacePoint) -> SurfacePoint {
    let offset = |point: SurfacePoint| match point {
        SurfacePoint::Near { vertex, edge, t } => {
            if model.edges()[edge][0] == vertex {
                t
            } else {
                1.0 - t
            }
        }
        _ => 0.0,
    };
    if offset(b) < offset(a) { b } else { a }
}

/// 3D position of a surface point (of a [`SurfacePoint::Near`] point, its crossing).
pub fn position(model: &FacetModel, point: SurfacePoint) -> DVec3 {
    let positions = model.positions();
    match point {
        SurfacePoint::Vertex(v) => positions[v as usize],
        SurfacePoint::Edge { edge, t } | SurfacePoint::Near { edge, t, .. } => {
            let [a, b] = model.edges()[edge];
            positions[a as usize].lerp(positions[b as usize], t)
        }
    }
}

/// The straightest geodesic (Polthier and Schmies 1998) of 3D length about `length` from `tip`,
/// the inner end of a cut: it leaves the tip with half the angle of the faces around it on each
/// side (so it carries straight on from the cut) and runs across faces, unfolded one by one,
/// until the edge crossing nearest `length`. `None` when the tip is not the end of a single slit
/// (it does not have exactly two boundary edges), or the geodesic meets the boundary first.
pub fn straight_on(model: &FacetModel, tip: u32, length: f64) -> Option<Vec<SurfacePoint>> {
    let (mut face, mut triangle, direction) = leaving_face(model, tip)?;
    // The ray starts at corner 0, so it leaves by side 1 (the sides at the tip give s = 0).
    let mut entry = None;
    let mut points = vec![SurfacePoint::Vertex(tip)];
    let mut travelled = 0.0;
    loop {
        let (exit, t, along) = exit_of(&triangle, entry, direction)?;
        let (a, b) = (triangle[exit].0, triangle[(exit + 1) % 3].0);
        let edge = model.find_edge(a, b)?;
        if along > length {
            if along - length < length - travelled || points.len() == 1 {
                points.push(edge_point(model, edge, a, t));
            }
            break;
        }
        travelled = along;
        points.push(edge_point(model, edge, a, t));
        if model.is_boundary_edge(edge) {
            return None;
        }
        let next = across(model, face, a, b)?;
        triangle = unfolded_across(model, &triangle, exit, next)?;
        (face, entry) = (next, Some(0));
    }
    Some(simplified(model, points))
}

/// An edge crossing at `t` from `a` to the edge's other end: that end within [`ON_VERTEX`],
/// snapped to it within [`SNAP_FRACTION`] ([`SurfacePoint::Near`]).
fn edge_point(model: &FacetModel, edge: usize, a: u32, t: f64) -> SurfacePoint {
    let [first, second] = model.edges()[edge];
    let t_first = if first == a { t } else { 1.0 - t };
    let (end, from_end) = if t_first <= 0.5 {
        (first, t_first)
    } else {
        (second, 1.0 - t_first)
    };
    if from_end < ON_VERTEX {
        SurfacePoint::Vertex(end)
    } else if from_end < SNAP_FRACTION {
        SurfacePoint::Near {
            vertex: end,
            edge,
            t: t_first,
        }
    } else {
        SurfacePoint::Edge { edge, t: t_first }
    }
}

/// Faces around a vertex in order, each as `(face, corner entered by, corner left by)`.
type Fan = Vec<(u32, u32, u32)>;

/// A face's corners unfolded into the plane, each with its vertex.
type Unfolded = [(u32, DVec2); 3];

/// The face around `tip` the straight continuation leaves it through, unfolded with the tip at
/// the origin and its next corner on the positive x axis, and the continuation's direction in
/// that unfolding: the direction with half the angle of the faces around the tip on each side.
fn leaving_face(model: &FacetModel, tip: u32) -> Option<(u32, Unfolded, DVec2)> {
    let (fan, total) = tip_fan(model, tip)?;
    let positions = model.positions();
    let at = positions[tip as usize];
    let mut turned = 0.0;
    for &(face, u, w) in &fan {
        let angle = corner_angle(model, tip, u, w);
        if turned + angle >= 0.5 * total {
            let triangle = [
                (tip, DVec2::ZERO),
                (u, DVec2::new(positions[u as usize].distance(at), 0.0)),
                (
                    w,
                    DVec2::from_angle(angle) * positions[w as usize].distance(at),
                ),
            ];
            return Some((face, triangle, DVec2::from_angle(0.5 * total - turned)));
        }
        turned += angle;
    }
    None
}

/// How far (radians) the direction from `tip` towards `towards`, a point of a face around the
/// tip, turns away from the straight continuation of the cut that ends at the tip (the
/// direction with half the angle around the tip on each side); `None` when the tip is not the
/// end of a single slit or the point is on no face around it.
pub fn turn_at_tip(model: &FacetModel, tip: u32, towards: DVec3) -> Option<f64> {
    let (fan, total) = tip_fan(model, tip)?;
    let positions = model.positions();
    let to = towards - positions[tip as usize];
    let mut turned = 0.0;
    for &(_, u, w) in &fan {
        let angle = corner_angle(model, tip, u, w);
        let from_u = (positions[u as usize] - positions[tip as usize]).angle_between(to);
        let to_w = (positions[w as usize] - positions[tip as usize]).angle_between(to);
        if (from_u + to_w - angle).abs() <= 1e-6 {
            return Some((turned + from_u - 0.5 * total).abs());
        }
        turned += angle;
    }
    None
}

/// The angle at `tip` of the face corner between its sides to `u` and `w`.
fn corner_angle(model: &FacetModel, tip: u32, u: u32, w: u32) -> f64 {
    let positions = model.positions();
    let at = positions[tip as usize];
    (positions[u as usize] - at).angle_between(positions[w as usize] - at)
}

/// The faces around the end `tip` of a single slit, from one of its two boundary edges round to
/// the other ([`fan_from`]), and the sum of their angles at the tip.
fn tip_fan(model: &FacetModel, tip: u32) -> Option<(Fan, f64)> {
    let mut ends: Vec<u32> = model
        .vertex_faces(tip)
        .iter()
        .flat_map(|&f| model.face_edges()[f as usize])
        .filter(|&e| model.is_boundary_edge(e as usize))
        .filter_map(|e| {
            let [a, b] = model.edges()[e as usize];
            (a == tip).then_some(b).or((b == tip).then_some(a))
        })
        .collect();
    ends.sort_unstable();
    ends.dedup();
    let [first_end, _] = ends[..] else {
        return None;
    };
    let fan = fan_from(model, tip, first_end)?;
    let total = fan
        .iter()
        .map(|&(_, u, w)| corner_angle(model, tip, u, w))
        .sum();
    Some((fan, total))
}

/// The faces around `tip` from the one on the boundary edge to `start` round to the other
/// boundary edge, each as `(face, u, w)`: the corner it is entered by and the one it is left by.
fn fan_from(model: &FacetModel, tip: u32, start: u32) -> Option<Fan> {
    let edge = model.find_edge(tip, start)?;
    let mut face = model.edge_faces()[edge].into_iter().find(|&f| f != NONE)?;
    let mut entered_by = start;
    let mut fan = Vec::new();
    loop {
        let corners = model.triangles()[face as usize];
        let left_by = *corners.iter().find(|&&c| c != tip && c != entered_by)?;
        fan.push((face, entered_by, left_by));
        match across(model, face, tip, left_by) {
            Some(next) => (face, entered_by) = (next, left_by),
            None => return Some(fan),
        }
        if fan.len() > model.vertex_faces(tip).len() {
            return None;
        }
    }
}

/// Where the ray `s · direction` from the origin leaves an unfolded face, not through side
/// `entry` (side `k` runs from corner `k` to corner `k + 1`): the side, the crossing's parameter
/// along it and the ray's parameter `s` there.
fn exit_of(
    triangle: &Unfolded,
    entry: Option<usize>,
    direction: DVec2,
) -> Option<(usize, f64, f64)> {
    let origin = DVec2::ZERO;
    (0..3)
        .filter(|&k| Some(k) != entry)
        .filter_map(|k| {
            let (a, b) = (triangle[k].1, triangle[(k + 1) % 3].1);
            let side = b - a;
            let denominator = direction.perp_dot(side);
            if denominator.abs() <= f64::EPSILON * side.length() {
                return None;
            }
            let s = (a - origin).perp_dot(side) / denominator;
            let t = (a - origin).perp_dot(direction) / denominator;
            ((-1e-9..=1.0 + 1e-9).contains(&t) && s > 1e-9).then_some((k, t.clamp(0.0, 1.0), s))
        })
        .max_by(|x, y| x.2.total_cmp(&y.2))
}

/// The face `next` across side `exit` of an unfolded face, unfolded on the other side of that
/// side, with the side shared (from its corner 0 to corner 1) first.
fn unfolded_across(
    model: &FacetModel,
    triangle: &Unfolded,
    exit: usize,
    next: u32,
) -> Option<Unfolded> {
    let (a, b) = (triangle[exit], triangle[(exit + 1) % 3]);
    let away = triangle[(exit + 2) % 3].1;
    let third = *model.triangles()[next as usize]
        .iter()
        .find(|&&v| v != a.0 && v != b.0)?;
    let positions = model.positions();
    let p = positions[third as usize];
    let (to_a, to_b) = (
        positions[a.0 as usize].distance(p),
        positions[b.0 as usize].distance(p),
    );
    let left = apex(a.1, b.1, to_a, to_b);
    let right = apex(b.1, a.1, to_b, to_a);
    let side = |q: DVec2| cross(a.1, b.1, q).signum();
    let at = if side(left) != side(away) {
        left
    } else {
        right
    };
    Some([a, b, (third, at)])
}

#[cfg(test)]
pub(crate) mod tests {
    use glam::DVec3;

    use crate::cut::split::split_along_edges;
    use crate::cut::straighten::*;
    use crate::mesh::{TriangleSoup, validate};

    /// A flat grid of `n × n` unit squares in z = 0, each split along its diagonal from
    /// `(x, y)` to `(x + 1, y + 1)`; vertex `(x, y)` is `y (n + 1) + x`.
    pub(crate) fn flat_grid(n: u32) -> FacetModel {
        let mut positions = Vec::new();
        for y in 0..=n {
            for x in 0..=n {
                positions.push(DVec3::new(f64::from(x), f64::from(y), 0.0));
            }
        }
        let mut triangles = Vec::new();
        for y in 0..n {
            for x in 0..n {
                let v = y * (n + 1) + x;
                triangles.push([v, v + 1, v + n + 2]);
                triangles.push([v, v + n + 2, v + n + 1]);
            }
        }
        let soup = TriangleSoup::new(positions, triangles);
        validate(&soup).expect("valid grid").components.remove(0)
    }

    /// Vertex `(x, y)` of [`flat_grid`]`(n)`.
    pub(crate) fn at(n: u32, x: u32, y: u32) -> u32 {
        y * (n + 1) + x
    }

    /// The L-shaped edge path from `(0, 1)` along `y = 1` to `(6, 1)` and up to `(6, 4)`.
    pub(crate) fn l_path(n: u32) -> Vec<u32> {
        let mut path: Vec<u32> = (0..=6).map(|x| at(n, x, 1)).collect();
        path.extend((2..=4).map(|y| at(n, 6, y)));
        path
    }

    #[test]
    fn an_l_shaped_edge_path_becomes_the_straight_line_between_its_ends() {
        let n = 8;
        let model = flat_grid(n);
        let points = straighten(&model, &l_path(n)).expect("straightened");
        assert_eq!(points[0], SurfacePoint::Vertex(at(n, 0, 1)));
        assert_eq!(points[points.len() - 1], SurfacePoint::Vertex(at(n, 6, 4)));
        // The line y = 1 + x / 2 runs through the vertices (2, 2) and (4, 3) and crosses the
        // diagonals between them at their midpoints: every point lies on it.
        for &point in &points {
            let p = position(&model, point);
            assert!((p.y - 1.0 - 0.5 * p.x).abs() < 1e-9, "{point:?}");
        }
        let crossings = points
            .iter()
            .filter(|p| matches!(p, SurfacePoint::Edge { .. }))
            .count();
        assert_eq!((points.len(), crossings), (7, 3), "{points:?}");
        let length: f64 = points
            .windows(2)
            .map(|pair| position(&model, pair[0]).distance(position(&model, pair[1])))
            .sum();
        assert!((length - 45f64.sqrt()).abs() < 1e-9, "{length}");
    }

    #[test]
    fn a_straight_edge_path_is_its_own_straightening() {
        let n = 6;
        let model = flat_grid(n);
        let path: Vec<u32> = (1..=5).map(|x| at(n, x, 3)).collect();
        let points = straighten(&model, &path).expect("straightened");
        let expected: Vec<SurfacePoint> = path.iter().map(|&v| SurfacePoint::Vertex(v)).collect();
        assert_eq!(points, expected);
    }

    /// The grid slit from `(4, 0)` on the boundary up to its tip `(4, 3)`.
    fn slit_grid(n: u32) -> FacetModel {
        let model = flat_grid(n);
        let path: Vec<u32> = (0..=3).map(|y| at(n, 4, y)).collect();
        let edges = crate::cut::paths::path_edges(&model, &path).expect("edge path");
        split_along_edges(&model, &edges).expect("slit").model
    }

    #[test]
    fn an_extension_carries_straight_on_from_the_slit() {
        let n = 8;
        let model = slit_grid(n);
        let tip = at(n, 4, 3);
        let points = straight_on(&model, tip, 3.0).expect("extension");
        let end = position(&model, points[points.len() - 1]);
        assert!(end.distance(DVec3::new(4.0, 6.0, 0.0)) < 1e-9, "{points:?}");
        for &point in &points {
            assert!((position(&model, point).x - 4.0).abs() < 1e-9, "{point:?}");
        }
    }

    #[test]
    fn the_turn_at_a_tip_is_measured_from_straight_on() {
        let n = 8;
        let model = slit_grid(n);
        let tip = at(n, 4, 3);
        let ahead = turn_at_tip(&model, tip, DVec3::new(4.0, 3.5, 0.0)).expect("ahead");
        let aside = turn_at_tip(&model, tip, DVec3::new(4.5, 3.0, 0.0)).expect("aside");
        let diagonal = turn_at_tip(&model, tip, DVec3::new(4.5, 3.5, 0.0)).expect("diagonal");
        assert!(ahead.abs() < 1e-9, "{ahead}");
        assert!(
            (aside - std::f64::consts::FRAC_PI_2).abs() < 1e-9,
            "{aside}"
        );
        assert!(
            (diagonal - std::f64::consts::FRAC_PI_4).abs() < 1e-9,
            "{diagonal}"
        );
    }

    #[test]
    fn the_largest_turn_of_an_edge_path_is_its_sharpest_corner() {
        let n = 8;
        let model = flat_grid(n);
        let turn = largest_turn(&model, &l_path(n)).expect("turn");
        assert!((turn - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "{turn}");
        let straight: Vec<u32> = (0..=6).map(|x| at(n, x, 1)).collect();
        assert!(largest_turn(&model, &straight).expect("turn") < 1e-9);
    }
}
