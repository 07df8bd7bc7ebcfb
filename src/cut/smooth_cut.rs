//! Smooth cuts (issue 13): a candidate cut's edge path replaced by its geodesic straightening
//! ([`super::straighten`]) and the mesh refined so that the straightened path runs along edges.
//!
//! Input: the model being cut ([`CutState`]), a candidate's vertex path (its first vertex on the
//! boundary, at an earlier cut's end or inside for a slit, its last the dart's tip) and the
//! vertices no cut may pass. Output: the refined state, the path as a vertex path of it (same
//! first and last vertex, so a dart still ends in a point and a line from a cut's end still
//! extends that cut), and for every inserted vertex the edge of the state it splits and where,
//! so a pattern of the state gives the refined one its start.
//!
//! Refinement: every point where the path crosses an edge becomes a vertex (appended after the
//! state's vertices, whose indices stay), the edge is split there and each face it crossed is
//! split along the path: a face crossed from one edge to its opposite vertex into two, from edge
//! to edge into three (the quadrilateral left split along the diagonal of larger smallest
//! angle). What the state carries goes over edge by edge and face by face: the pieces of a split
//! edge keep its stiffness and share its rest length in proportion; an edge across a face gets
//! the face's mean stiffness and its 3D length scaled by the face's mean ratio of rest to 3D
//! length; faces keep their source face; fold-line edges are never split (the path may not cross
//! one). An inserted vertex has no input vertex: `original_vertex` gives it the nearer end of the
//! input edge it lies on (documented on [`super::CutResult::original_vertex`]).
//!
//! Where the path passes a vertex instead of crossing an edge near it (a crossing within
//! [`super::straighten::SNAP_FRACTION`] of the edge's end), the vertex moves onto the crossing so
//! that the cut does not turn there: an inner vertex with no fold line on its faces and no
//! other crossing on its edges, whose faces keep at least half their smallest angle and turn by
//! less than [`crate::mesh::MAX_MOVED_FACE_TURN`] ([`crate::mesh::can_move_vertex`]). It moves
//! along one of its own edges by at most a fifth of it, and the surface changes by about the
//! mesh's own chord error (at most about twice an edge's sagitta on the samples,
//! docs/cutting.md); the rest lengths of its edges scale with their 3D lengths.
//! Otherwise it stays and the cut turns there.
//!
//! The straightened path is refused, and the edge path kept, when it passes a blocked vertex or a
//! boundary vertex other than its ends (it would cut a piece off), crosses an edge with a
//! blocked end, or when the refined mesh fails validation.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};

use super::state::CutState;
use super::straighten::{
    SurfacePoint, largest_turn, position, straight_on, straighten, turn_at_tip,
};
use crate::flatten::Stiffness;
use crate::mesh::{
    FacetModel, FoldEdge, NONE, SourceLines, TriangleSoup, can_move_vertex, rebuild, smallest_angle,
};

/// The largest turn (radians) at a cut's inner end that an extension along its straightened
/// crest line may make (12°): the cut's sides then turn by less than the 20° a cutter follows
/// as one smooth line.
pub const MAX_EXTENSION_TURN: f64 = 12.0 * std::f64::consts::PI / 180.0;

/// The largest geodesic turn (radians) at a vertex of an edge path cut as it is when its
/// straightening cannot be cut (10°).
pub const MAX_EDGE_PATH_TURN: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// An inserted vertex: the edge of the state it splits, `[a, b]`, and where (`0` at `a`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Inserted {
    pub(super) ends: [u32; 2],
    pub(super) t: f64,
}

/// A candidate's path straightened, with the refined state it runs along.
#[derive(Debug, Clone)]
pub(super) struct SmoothCut {
    /// The state with the path's crossing points inserted.
    pub(super) state: CutState,
    /// The straightened path, a vertex path of `state`.
    pub(super) path: Vec<u32>,
    /// The inserted vertices, in order (vertex `n + k` of `state` is `inserted[k]`, `n` the
    /// vertex count before).
    pub(super) inserted: Vec<Inserted>,
}

impl SmoothCut {
    /// Start positions for the refined state from a pattern of the state before: old vertices
    /// where they were, inserted ones on their edge.
    pub(super) fn start_from(&self, positions: &[DVec2]) -> Vec<DVec2> {
        let mut start = positions.to_vec();
        start.extend(self.inserted.iter().map(|inserted| {
            let [a, b] = inserted.ends;
            positions[a as usize].lerp(positions[b as usize], inserted.t)
        }));
        start
    }
}

/// What straightening makes of a cut path.
#[derive(Debug, Clone)]
pub(super) enum Straightened {
    /// The path crossing faces, with the state refined along it.
    Smooth(Box<SmoothCut>),
    /// The edge path is already its own straightening.
    AlongEdges,
    /// The straightened path cannot be cut (see the module documentation).
    Refused,
}

/// The smooth version of the cut along `path` (see the module documentation).
pub(super) fn smooth_cut(state: &CutState, path: &[u32], blocked: &[bool]) -> Straightened {
    let model = &state.model;
    let Some(points) = straighten(model, path) else {
        return along_edges_if_straight(model, path);
    };
    let unchanged = points.len() == path.len()
        && points
            .iter()
            .zip(path)
            .all(|(point, &v)| *point == SurfacePoint::Vertex(v));
    if unchanged {
        return Straightened::AlongEdges;
    }
    if !allowed(model, &points[1..points.len() - 1], blocked) {
        return along_edges_if_straight(model, path);
    }
    refine(state, &points).map_or_else(
        || along_edges_if_straight(model, path),
        |smooth| Straightened::Smooth(Box::new(smooth)),
    )
}

/// When a path's straightening cannot be cut, the path along its edges if they turn by at most
/// [`MAX_EDGE_PATH_TURN`] at every vertex (on a coarse regular mesh a grid line is already
/// straight; the straightening near it may touch the boundary), else refused.
fn along_edges_if_straight(model: &FacetModel, path: &[u32]) -> Straightened {
    if largest_turn(model, path).is_some_and(|turn| turn <= MAX_EDGE_PATH_TURN) {
        Straightened::AlongEdges
    } else {
        Straightened::Refused
    }
}

/// The extension of the cut that ends at `path[0]` along the crest line `path`: its
/// straightening ([`smooth_cut`]) when that turns at the tip by at most
/// [`MAX_EXTENSION_TURN`], else a line of the same length straight on from the cut
/// ([`straight_extension`]): a crest line that turns further would leave a hooked dart.
pub(super) fn extension(
    state: &CutState,
    path: &[u32],
    length: f64,
    blocked: &[bool],
) -> Straightened {
    let tip = path[0];
    let turn_towards = |model: &FacetModel, next: u32| {
        turn_at_tip(model, tip, model.positions()[next as usize])
            .is_some_and(|turn| turn <= MAX_EXTENSION_TURN)
    };
    let straightened = smooth_cut(state, path, blocked);
    let smooth_enough = match &straightened {
        Straightened::Smooth(smooth) => turn_towards(&smooth.state.model, smooth.path[1]),
        Straightened::AlongEdges => turn_towards(&state.model, path[1]),
        Straightened::Refused => false,
    };
    if smooth_enough {
        straightened
    } else {
        straight_extension(state, tip, length, blocked)
    }
}

/// An extension of the cut that ends at `tip` by about `length`, straight on from the cut
/// ([`straight_on`]); refused when it cannot be laid (see the module documentation; its new
/// inner end may not be blocked or on the boundary either).
fn straight_extension(state: &CutState, tip: u32, length: f64, blocked: &[bool]) -> Straightened {
    let Some(points) = straight_on(&state.model, tip, length) else {
        return Straightened::Refused;
    };
    if points.len() < 2 || !allowed(&state.model, &points[1..], blocked) {
        return Straightened::Refused;
    }
    refine(state, &points).map_or(Straightened::Refused, |smooth| {
        Straightened::Smooth(Box::new(smooth))
    })
}

/// Whether the points of a path (its inner points, or all but its start for an extension) may be
/// cut: vertices neither blocked nor on the boundary, no crossed edge with a blocked end or on a
/// fold line.
fn allowed(model: &FacetModel, points: &[SurfacePoint], blocked: &[bool]) -> bool {
    let on_boundary = model.boundary_flags();
    points.iter().all(|&point| match point {
        SurfacePoint::Vertex(v) | SurfacePoint::Near { vertex: v, .. } => {
            !blocked[v as usize] && !on_boundary[v as usize]
        }
        SurfacePoint::Edge { edge, .. } => {
            let [a, b] = model.edges()[edge];
            model.edge_fold_lines()[edge] == NONE && !blocked[a as usize] && !blocked[b as usize]
        }
    })
}

/// The state with the path's edge crossings inserted, its crossed faces split and the vertices
/// it passes near moved onto it where they may be; `None` if an edge is crossed twice, a face is
/// crossed more than once or the result is not a valid mesh.
fn refine(state: &CutState, points: &[SurfacePoint]) -> Option<SmoothCut> {
    let model = &state.model;
    let count = model.vertex_count() as u32;
    let mut inserted = Vec::new();
    let mut on_edge: BTreeMap<usize, u32> = BTreeMap::new();
    let mut path = Vec::with_capacity(points.len());
    for &point in points {
        match point {
            SurfacePoint::Vertex(v) | SurfacePoint::Near { vertex: v, .. } => path.push(v),
            SurfacePoint::Edge { edge, t } => {
                let vertex = count + inserted.len() as u32;
                if on_edge.insert(edge, vertex).is_some() {
                    return None;
                }
                inserted.push(Inserted {
                    ends: model.edges()[edge],
                    t,
                });
                path.push(vertex);
            }
        }
    }
    let mut positions = model.positions().to_vec();
    for (vertex, to) in moves(model, points) {
        positions[vertex as usize] = to;
    }
    positions.extend(points.iter().filter_map(|&point| match point {
        SurfacePoint::Edge { .. } => Some(position(model, point)),
        SurfacePoint::Vertex(_) | SurfacePoint::Near { .. } => None,
    }));
    let (triangles, parents) = split_faces(model, &positions, &on_edge)?;
    let soup = TriangleSoup {
        positions,
        face_sources: parents
            .iter()
            .map(|&f| model.face_sources()[f as usize])
            .collect(),
        triangles,
        fold_edges: fold_edges(model),
        source_lines: SourceLines::default(),
        texture: None,
    };
    let mut refined = rebuild(soup).ok()?;
    let (rest_lengths, factors) = carried_edges(state, &refined, &parents, &inserted);
    refined.set_rest_lengths(rest_lengths);
    let mut original_vertex = state.original_vertex.clone();
    original_vertex.extend(inserted.iter().map(|inserted| {
        let nearer = inserted.ends[usize::from(inserted.t > 0.5)];
        state.original_vertex[nearer as usize]
    }));
    Some(SmoothCut {
        state: CutState {
            model: refined,
            stiffness: Stiffness::from_factors(factors),
            original_vertex,
        },
        path,
        inserted,
    })
}

/// The vertices of `points` that move onto the crossing they stand for, and where to (see the
/// module documentation; [`allowed`] has already kept the path off the boundary).
fn moves(model: &FacetModel, points: &[SurfacePoint]) -> Vec<(u32, DVec3)> {
    let crossed: Vec<[u32; 2]> = (points.iter())
        .filter_map(|point| match *point {
            SurfacePoint::Edge { edge, .. } => Some(model.edges()[edge]),
            _ => None,
        })
        .collect();
    let on_path = |v: u32| points.iter().filter(|p| p.vertex() == Some(v)).count();
    (points.iter())
        .filter_map(|&point| match point {
            SurfacePoint::Near { vertex, .. } => Some((vertex, position(model, point))),
            _ => None,
        })
        .filter(|&(vertex, to)| {
            on_path(vertex) == 1
                && !crossed.iter().any(|ends| ends.contains(&vertex))
                && can_move_vertex(model, vertex, to)
        })
        .collect()
}

/// The model's triangles with every face that has inserted vertices on its edges split (see the
/// module documentation), and for each triangle the face it comes from.
fn split_faces(
    model: &FacetModel,
    positions: &[DVec3],
    on_edge: &BTreeMap<usize, u32>,
) -> Option<(Vec<[u32; 3]>, Vec<u32>)> {
    let mut triangles = Vec::with_capacity(model.triangle_count() + 2 * on_edge.len());
    let mut parents = Vec::with_capacity(triangles.capacity());
    for (face, &corners) in model.triangles().iter().enumerate() {
        // The inserted vertex on the side from corner k to corner k + 1, if any.
        let sides = model.face_edges()[face].map(|edge| on_edge.get(&(edge as usize)).copied());
        let pieces: Vec<[u32; 3]> = match sides.iter().filter(|s| s.is_some()).count() {
            0 => {
                parents.push(face as u32);
                triangles.push(corners);
                continue;
            }
            1 => {
                let k = sides.iter().position(Option::is_some)?;
                let [x, y, z] = rotated(corners, k);
                let p = sides[k]?;
                vec![[x, p, z], [p, y, z]]
            }
            2 => {
                // Rotate so the sides x→y and y→z carry the points p and q.
                let k = (0..3).find(|&k| sides[k].is_some() && sides[(k + 1) % 3].is_some())?;
                let [x, y, z] = rotated(corners, k);
                let (p, q) = (sides[k]?, sides[(k + 1) % 3]?);
                let mut pieces = vec![[p, y, q]];
                pieces.extend(quadrilateral(positions, [x, p, q, z]));
                pieces
            }
            _ => return None,
        };
        parents.extend(std::iter::repeat_n(face as u32, pieces.len()));
        triangles.extend(pieces);
    }
    Some((triangles, parents))
}

/// A face's corners starting at corner `k`.
fn rotated(corners: [u32; 3], k: usize) -> [u32; 3] {
    [corners[k], corners[(k + 1) % 3], corners[(k + 2) % 3]]
}

/// The counter-clockwise quadrilateral `a, b, c, d` as two triangles, split along the diagonal
/// whose triangles have the larger smallest angle.
fn quadrilateral(positions: &[DVec3], [a, b, c, d]: [u32; 4]) -> [[u32; 3]; 2] {
    let along_ac = [[a, b, c], [a, c, d]];
    let along_bd = [[a, b, d], [b, c, d]];
    let smallest = |pair: &[[u32; 3]; 2]| {
        pair.iter()
            .map(|t| smallest_angle(t.map(|v| positions[v as usize])))
            .fold(f64::INFINITY, f64::min)
    };
    if smallest(&along_ac) >= smallest(&along_bd) {
        along_ac
    } else {
        along_bd
    }
}

/// The model's fold-line edges as soup fold edges.
fn fold_edges(model: &FacetModel) -> Vec<FoldEdge> {
    model
        .edges()
        .iter()
        .zip(model.edge_fold_lines())
        .filter(|&(_, &line)| line != NONE)
        .map(|(&vertices, &fold_line)| FoldEdge {
            vertices,
            fold_line,
        })
        .collect()
}

/// Rest length and stiffness factor of every edge of the refined model (see the module
/// documentation).
fn carried_edges(
    state: &CutState,
    refined: &FacetModel,
    parents: &[u32],
    inserted: &[Inserted],
) -> (Vec<f64>, Vec<f64>) {
    let model = &state.model;
    let factors = state.stiffness.factors();
    let count = model.vertex_count() as u32;
    let positions = refined.positions();
    let length = |a: u32, b: u32| positions[a as usize].distance(positions[b as usize]);
    let before = model.positions();
    let length_before = |a: u32, b: u32| before[a as usize].distance(before[b as usize]);
    let face_means = |face: u32| {
        let edges = model.face_edges()[face as usize];
        let (mut ratio, mut factor) = (0.0, 0.0);
        for &e in &edges {
            let [a, b] = model.edges()[e as usize];
            ratio += model.rest_lengths()[e as usize] / length_before(a, b) / 3.0;
            factor += factors[e as usize] / 3.0;
        }
        (ratio, factor)
    };
    // The refined model's edges come in the model's order (both sorted), so one pass along the
    // model's edges finds those it kept.
    let kept_edges = model.edges();
    let mut cursor = 0;
    let mut kept_edge = |key: [u32; 2]| {
        while kept_edges.get(cursor).is_some_and(|&edge| edge < key) {
            cursor += 1;
        }
        (kept_edges.get(cursor) == Some(&key)).then_some(cursor)
    };
    refined
        .edges()
        .iter()
        .zip(refined.edge_faces())
        .map(|(&[a, b], &[face, _])| {
            if b < count {
                if let Some(e) = kept_edge([a, b]) {
                    // An edge of a moved vertex: its rest length scales with its 3D length.
                    let scale = length(a, b) / length_before(a, b);
                    return (model.rest_lengths()[e] * scale, factors[e]);
                }
            } else {
                // `a < b`, so `b` is inserted: a piece of the edge it splits keeps its figures.
                let [x, y] = inserted[(b - count) as usize].ends;
                if let (true, Some(e)) = ([x, y].contains(&a), model.find_edge(x, y)) {
                    let share = length(a, b) / length(x, y);
                    return (model.rest_lengths()[e] * share, factors[e]);
                }
            }
            let (ratio, factor) = face_means(parents[face as usize]);
            (length(a, b) * ratio, factor)
        })
        .unzip()
}

#[cfg(test)]
mod tests {
    use crate::cut::paths::path_edges;
    use crate::cut::smooth_cut::*;
    use crate::cut::straighten::tests::{at, flat_grid, l_path};

    fn state(model: FacetModel) -> CutState {
        let edges = model.edges().len();
        CutState {
            original_vertex: (0..model.vertex_count() as u32).collect(),
            stiffness: Stiffness::from_factors(vec![2.0; edges]),
            model,
        }
    }

    fn smoothed(state: &CutState, path: &[u32]) -> SmoothCut {
        let blocked = vec![false; state.model.vertex_count()];
        match smooth_cut(state, path, &blocked) {
            Straightened::Smooth(smooth) => *smooth,
            other => panic!("not smoothed: {other:?}"),
        }
    }

    #[test]
    fn the_refined_mesh_is_the_same_surface_with_the_path_along_its_edges() {
        let n = 8;
        let before = state(flat_grid(n));
        let smooth = smoothed(&before, &l_path(n));
        let model = &smooth.state.model;
        assert!((model.area() - before.model.area()).abs() < 1e-9);
        assert!(
            path_edges(model, &smooth.path).is_some(),
            "{:?}",
            smooth.path
        );
        assert_eq!(smooth.path[0], at(n, 0, 1));
        assert_eq!(smooth.path[smooth.path.len() - 1], at(n, 6, 4));
        let count = before.model.vertex_count();
        assert_eq!(model.vertex_count(), count + smooth.inserted.len());
        for (k, inserted) in smooth.inserted.iter().enumerate() {
            let [a, b] = inserted.ends.map(|v| before.model.positions()[v as usize]);
            let p = model.positions()[count + k];
            assert!((p.distance(a) + p.distance(b) - a.distance(b)).abs() < 1e-9);
            let original = smooth.state.original_vertex[count + k];
            let given = before.model.positions()[original as usize];
            assert!(inserted.ends.contains(&original));
            assert!(p.distance(given) <= 0.5 * a.distance(b) + 1e-9);
        }
        // Flat: every rest length is the 3D length, and the stiffness is carried over.
        for (e, &[a, b]) in model.edges().iter().enumerate() {
            let length = model.positions()[a as usize].distance(model.positions()[b as usize]);
            assert!((model.rest_lengths()[e] - length).abs() < 1e-9);
            assert!((smooth.state.stiffness.factors()[e] - 2.0).abs() < 1e-12);
        }
        assert!(smooth.state.cut_along(&smooth.path).is_ok());
    }

    /// The straight line from (0, 1) to (7, 4) crosses the edge below the vertex (2, 2) at
    /// y = 1.857, within a fifth of the edge: the vertex moves there (the grid stays flat) and
    /// the cut runs straight instead of turning through the vertex.
    #[test]
    fn a_vertex_next_to_the_straight_line_moves_onto_it() {
        let n = 8;
        let before = state(flat_grid(n));
        let mut path: Vec<u32> = (0..=7).map(|x| at(n, x, 1)).collect();
        path.extend((2..=4).map(|y| at(n, 7, y)));
        let smooth = smoothed(&before, &path);
        let model = &smooth.state.model;
        let positions = model.positions();
        let (start, end) = (DVec3::new(0.0, 1.0, 0.0), DVec3::new(7.0, 4.0, 0.0));
        let along = (end - start).normalize();
        for &v in &smooth.path {
            let offset = positions[v as usize] - start;
            let off_line = (offset - along * offset.dot(along)).length();
            assert!(off_line < 1e-9, "vertex {v} lies {off_line} off the line");
        }
        let corner = at(n, 2, 2) as usize;
        let moved_to = start + along * (2.0 / along.x);
        assert!(positions[corner].distance(moved_to) < 1e-9);
        assert!((model.area() - before.model.area()).abs() < 1e-9);
        for (e, &[a, b]) in model.edges().iter().enumerate() {
            let length = positions[a as usize].distance(positions[b as usize]);
            assert!((model.rest_lengths()[e] - length).abs() < 1e-9);
        }
        assert!(smooth.state.cut_along(&smooth.path).is_ok());
    }

    #[test]
    fn a_path_through_a_blocked_vertex_is_not_straightened_across_it() {
        let n = 8;
        let before = state(flat_grid(n));
        let mut blocked = vec![false; before.model.vertex_count()];
        // Every vertex strictly inside the L's corner region: the straight line must cross it.
        for y in 2..=4 {
            for x in 1..=5 {
                blocked[at(n, x, y) as usize] = true;
            }
        }
        assert!(matches!(
            smooth_cut(&before, &l_path(n), &blocked),
            Straightened::Refused
        ));
    }

    #[test]
    fn warm_start_positions_put_inserted_vertices_on_their_edges() {
        let n = 8;
        let before = state(flat_grid(n));
        let smooth = smoothed(&before, &l_path(n));
        let flat: Vec<DVec2> = before
            .model
            .positions()
            .iter()
            .map(|p| DVec2::new(2.0 * p.x, 2.0 * p.y))
            .collect();
        let start = smooth.start_from(&flat);
        for (v, p) in smooth.state.model.positions().iter().enumerate() {
            assert!(start[v].distance(DVec2::new(2.0 * p.x, 2.0 * p.y)) < 1e-9);
        }
    }
}
