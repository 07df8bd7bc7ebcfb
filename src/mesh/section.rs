//! Plane sections of a facet model (`--seams pieces`): the model cut in two along the curve
//! where a plane crosses it, the crossed faces split at the crossing points, and each side taken
//! apart into its connected pieces.
//!
//! A crossing within [`SECTION_SNAP`] of an edge's end passes through that end instead, so no
//! sliver triangle is made. An inner vertex a crossing passes through moves onto that crossing
//! (along its edge, by at most a fifth of it), so that the section curve does not turn there,
//! where its faces stay well shaped ([`can_move_vertex`]), their area changes by at most
//! [`MAX_FAN_AREA_CHANGE`] and no neighbour moved before it; the pieces then differ from the
//! model's surface by about its chord error near those vertices. An inner vertex that does not
//! move (one on a wrinkle's crest, whose faces would change area) takes only a crossing within
//! [`HELD_SNAP`] of it, so that the curve jogs by at most a tenth of an edge there, unless it
//! holds curvature ([`HELD_DEFICIT`]) and the plane parts its faces evenly ([`MAX_HELD_TURN`]); a
//! crossing farther from it splits the edge. A boundary vertex takes every crossing within
//! [`SECTION_SNAP`]. The crossing points are then slid along their edges until the curve turns
//! as evenly as it can ([`super::section_fairing`]).

use std::collections::BTreeSet;
use std::f64::consts::TAU;

use glam::DVec3;

use super::facet::{FacetModel, NONE};
use super::repair::split_non_manifold;
use super::section_fairing::fair_crossings;
use super::validate::validate;
use super::vertex_move::can_move_vertex;
use crate::cad::{FoldEdge, TriangleSoup};

/// A crossing within this fraction of an edge's length from one of its ends passes through that
/// end (the rule of the cut stage's refinement).
pub const SECTION_SNAP: f64 = 0.2;

/// An inner vertex that does not move onto its crossing still takes it when it is within this
/// fraction of the edge, so the section curve jogs by at most this much there; a crossing
/// farther away (up to [`SECTION_SNAP`]) splits the edge, the thinnest triangle made being this
/// fraction of it, unless the vertex holds curvature ([`HELD_DEFICIT`]).
pub const HELD_SNAP: f64 = 0.1;

/// An inner vertex that does not move and whose angle deficit is at least this (radians) takes
/// every crossing within [`SECTION_SNAP`] where the plane parts it evenly ([`MAX_HELD_TURN`]): on
/// the section it is on the boundary of both sides,
/// whose flattenings leave its curvature open there, where a section beside it leaves it inside
/// one side, whose flattening must take it up. Before the held-turn bound, splitting beside
/// every vertex gave 1,590 pieces instead of 1,305 over the real-mesh table's fourteen meshes;
/// with this bound, 1,352.
pub const HELD_DEFICIT: f64 = 0.02;

/// A curved vertex ([`HELD_DEFICIT`]) takes a crossing farther than [`HELD_SNAP`] only when the
/// section through it would turn there by at most this (radians, 20°): where the plane parts
/// its faces unevenly (a slanted plane through a sharp vertex), the curve turns there by up to
/// 60° and sliding the crossings beside it cannot take that up, so the edge is split instead
/// and the curve passes beside the vertex, where it can be faired.
pub const MAX_HELD_TURN: f64 = 20.0 * std::f64::consts::PI / 180.0;

/// The largest change of the area of a vertex's faces, as a fraction of it, that moving the
/// vertex onto the section may make. The faces of two moved vertices are never the same (no two
/// neighbours move), so a section changes the surface's area by at most this fraction.
pub const MAX_FAN_AREA_CHANGE: f64 = 1e-3;

/// A plane: the points `p` with `normal · p = offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// Unit normal; its side is the positive one.
    pub normal: DVec3,
    /// Signed distance of the plane from the origin along `normal`.
    pub offset: f64,
}

impl Plane {
    /// The plane through `point` with the (unit) `normal`.
    pub fn through(point: DVec3, normal: DVec3) -> Self {
        Self {
            normal,
            offset: normal.dot(point),
        }
    }

    /// Signed distance of `point` from the plane.
    pub fn distance(&self, point: DVec3) -> f64 {
        self.normal.dot(point) - self.offset
    }
}

/// Where a vertex of a piece comes from in the model that was cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VertexOrigin {
    /// A vertex of the model.
    Vertex(u32),
    /// The point at `t` along the model's edge `edge`, from its first vertex to its second.
    Crossing {
        /// The edge crossed.
        edge: u32,
        /// Where along it, in (0, 1).
        t: f64,
    },
}

impl VertexOrigin {
    /// The model vertex at the origin, or the nearer end of the edge it crosses.
    pub fn nearer_vertex(&self, model: &FacetModel) -> u32 {
        match *self {
            Self::Vertex(v) => v,
            Self::Crossing { edge, t } => model.edges()[edge as usize][usize::from(t >= 0.5)],
        }
    }

    /// True if the origin is `vertex` or lies on an edge ending there.
    fn touches(&self, model: &FacetModel, vertex: u32) -> bool {
        match *self {
            Self::Vertex(v) => v == vertex,
            Self::Crossing { edge, .. } => model.edges()[edge as usize].contains(&vertex),
        }
    }
}

/// Where an edge of a piece comes from in the model that was cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeOrigin {
    /// It is the model's edge, or the part of it on one side of the section.
    OnEdge(u32),
    /// It crosses a face of the model, between the crossings of these model edges (one of
    /// them [`NONE`] when the edge ends at a vertex of the face).
    InFace([u32; 2]),
}

/// One connected piece of one side of a section.
#[derive(Debug, Clone)]
pub struct SectionPiece {
    /// Its facet model.
    pub model: FacetModel,
    /// Where each of its vertices comes from.
    pub vertex_origins: Vec<VertexOrigin>,
    /// Where each of its edges comes from.
    pub edge_origins: Vec<EdgeOrigin>,
    /// Per edge, true where it runs along the section curve (both ends on the plane, and not
    /// along the model's own boundary).
    pub on_section: Vec<bool>,
}

/// The model cut by `plane` into the connected pieces of its two sides (the positive side's
/// first), or `None` when the plane leaves one side empty or a side cannot be made a valid facet
/// model.
pub fn section(model: &FacetModel, plane: Plane) -> Option<Vec<SectionPiece>> {
    let sides = SidedVertices::new(model, plane);
    let mut triangles: [Vec<[u32; 3]>; 2] = [Vec::new(), Vec::new()];
    let mut sources: [Vec<u32>; 2] = [Vec::new(), Vec::new()];
    for (face, &corners) in model.triangles().iter().enumerate() {
        for (side, triangle) in sides.split_face(model, face, corners) {
            triangles[side].push(triangle);
            sources[side].push(model.face_sources()[face]);
        }
    }
    if triangles.iter().any(Vec::is_empty) {
        return None;
    }
    let mut pieces = Vec::new();
    for (side_triangles, side_sources) in triangles.into_iter().zip(sources) {
        pieces.extend(side_pieces(model, &sides, side_triangles, side_sources)?);
    }
    Some(pieces)
}

/// The model's vertices and the crossing points, with the side of the plane each lies on.
struct SidedVertices {
    /// Every model vertex, then one point per crossed edge.
    positions: Vec<DVec3>,
    origins: Vec<VertexOrigin>,
    /// `+1`, `-1`, or `0` on the plane (crossings and snapped vertices).
    signs: Vec<i8>,
    /// Per model edge, its crossing point's index, or [`NONE`].
    crossing: Vec<u32>,
}

impl SidedVertices {
    fn new(model: &FacetModel, plane: Plane) -> Self {
        let mut distances: Vec<f64> = (model.positions().iter())
            .map(|&p| plane.distance(p))
            .collect();
        let along = |d: &[f64], [a, b]: [u32; 2]| d[a as usize] / (d[a as usize] - d[b as usize]);
        let crosses = |d: &[f64], [a, b]: [u32; 2]| d[a as usize] * d[b as usize] < 0.0;
        // Each vertex within SECTION_SNAP of a crossing on one of its edges, how far (as a
        // fraction of the edge) and where the crossing is.
        let mut snapped: Vec<(u32, f64, DVec3)> = Vec::new();
        for &edge in model.edges() {
            if crosses(&distances, edge) {
                let t = along(&distances, edge);
                let [a, b] = edge.map(|v| model.positions()[v as usize]);
                if t < SECTION_SNAP {
                    snapped.push((edge[0], t, a.lerp(b, t)));
                } else if t > 1.0 - SECTION_SNAP {
                    snapped.push((edge[1], 1.0 - t, a.lerp(b, t)));
                }
            }
        }
        let mut positions = model.positions().to_vec();
        let on_boundary = model.boundary_flags();
        let moved = move_onto_crossings(model, &mut positions, &snapped, &on_boundary);
        // The vertices the curve passes through instead of their crossings: the moved ones,
        // those on the boundary, and those held where they are that are near the crossing or
        // curved (the angle deficit of an inner vertex, found only for the few held ones) and
        // parted evenly by the plane.
        let plane_distances = distances.clone();
        for &(v, t, _) in &snapped {
            let curved = || {
                let angle_sum = model.angle_sum(v);
                (TAU - angle_sum).abs() >= HELD_DEFICIT
                    && turn_through(model, &plane_distances, v, angle_sum).abs() <= MAX_HELD_TURN
            };
            let v = v as usize;
            if moved[v] || on_boundary[v] || t < HELD_SNAP || curved() {
                distances[v] = 0.0;
            }
        }
        let mut origins: Vec<VertexOrigin> = (0..positions.len() as u32)
            .map(VertexOrigin::Vertex)
            .collect();
        let mut signs: Vec<i8> = distances.iter().map(|&d| sign(d)).collect();
        let crossed: Vec<u32> = (0..model.edges().len() as u32)
            .filter(|&e| crosses(&distances, model.edges()[e as usize]))
            .collect();
        let mut ts: Vec<f64> = (crossed.iter())
            .map(|&e| along(&distances, model.edges()[e as usize]))
            .collect();
        let on_curve: Vec<bool> = signs.iter().map(|&s| s == 0).collect();
        fair_crossings(
            model,
            &positions,
            &on_curve,
            &crossed,
            &mut ts,
            SECTION_SNAP,
        );
        let mut crossing = vec![NONE; model.edges().len()];
        for (&e, &t) in crossed.iter().zip(&ts) {
            let [a, b] = model.edges()[e as usize].map(|v| model.positions()[v as usize]);
            crossing[e as usize] = positions.len() as u32;
            positions.push(a.lerp(b, t));
            origins.push(VertexOrigin::Crossing { edge: e, t });
            signs.push(0);
        }
        Self {
            positions,
            origins,
            signs,
            crossing,
        }
    }

    /// The triangles face `face` (corners `corners`) becomes, each with its side (0 positive, 1
    /// negative); a face with no corner on the negative side is positive.
    fn split_face(
        &self,
        model: &FacetModel,
        face: usize,
        corners: [u32; 3],
    ) -> Vec<(usize, [u32; 3])> {
        let signs = corners.map(|v| self.signs[v as usize]);
        let side_of = |s: i8| usize::from(s < 0);
        if !signs.contains(&-1) || !signs.contains(&1) {
            let side = usize::from(signs.contains(&-1));
            return vec![(side, corners)];
        }
        let crossing_of = |a: u32, b: u32| {
            let edge = (model.face_edges()[face].iter())
                .find(|&&e| {
                    let [p, q] = model.edges()[e as usize];
                    (p, q) == (a.min(b), a.max(b))
                })
                .copied()
                .unwrap_or(NONE);
            self.crossing.get(edge as usize).copied().unwrap_or(NONE)
        };
        if let Some(k) = signs.iter().position(|&s| s == 0) {
            // The plane passes through corner k and crosses the opposite edge.
            let [z, b, c] = rotated(corners, k);
            let x = crossing_of(b, c);
            let sb = self.signs[b as usize];
            return vec![(side_of(sb), [z, b, x]), (side_of(-sb), [z, x, c])];
        }
        // One corner alone on its side: a triangle there, a quad on the other.
        let k = (0..3)
            .find(|&k| signs[(k + 1) % 3] == signs[(k + 2) % 3])
            .unwrap_or(0);
        let [a, b, c] = rotated(corners, k);
        let (xab, xac) = (crossing_of(a, b), crossing_of(a, c));
        let lone = side_of(signs[k]);
        let other = 1 - lone;
        let p = |v: u32| self.positions[v as usize];
        let quad = if p(xab).distance(p(c)) <= p(b).distance(p(xac)) {
            [[xab, b, c], [xab, c, xac]]
        } else {
            [[xab, b, xac], [b, c, xac]]
        };
        vec![(lone, [a, xab, xac]), (other, quad[0]), (other, quad[1])]
    }
}

/// Moves each inner vertex of `snapped` (vertex, fraction of the edge, crossing point) onto its
/// nearest crossing, in vertex order, where [`can_move_vertex`] allows it, the area of its faces
/// changes by at most [`MAX_FAN_AREA_CHANGE`] and none of its neighbours moved before it (two
/// neighbours moved at once would change their shared faces more than each check saw; so every
/// check sees the model's own positions around the vertex). Returns, per vertex, whether it
/// moved.
fn move_onto_crossings(
    model: &FacetModel,
    positions: &mut [DVec3],
    snapped: &[(u32, f64, DVec3)],
    on_boundary: &[bool],
) -> Vec<bool> {
    let at = model.positions();
    let mut nearest = snapped.to_vec();
    nearest.sort_by(|p, q| p.0.cmp(&q.0).then(p.1.total_cmp(&q.1)));
    nearest.dedup_by_key(|p| p.0);
    let mut moved = vec![false; positions.len()];
    for (v, _, to) in nearest {
        let neighbour_moved = (model.vertex_faces(v).iter()).any(|&f| {
            model.triangles()[f as usize]
                .iter()
                .any(|&w| moved[w as usize])
        });
        let before = fan_area(model, v, at[v as usize]);
        let keeps_area = (fan_area(model, v, to) - before).abs() <= MAX_FAN_AREA_CHANGE * before;
        if !neighbour_moved
            && keeps_area
            && !on_boundary[v as usize]
            && can_move_vertex(model, v, to)
        {
            positions[v as usize] = to;
            moved[v as usize] = true;
        }
    }
    moved
}

/// How much a plane curve through inner vertex `v` (angle sum `angle_sum`) turns there: the
/// angle round the vertex on the plane's positive side (`distances` from it per vertex, `v`'s
/// own taken as 0), less half the angle sum.
fn turn_through(model: &FacetModel, distances: &[f64], v: u32, angle_sum: f64) -> f64 {
    let at = |w: u32| model.positions()[w as usize];
    let positive_angle: f64 = (model.vertex_faces(v).iter())
        .filter_map(|&face| model.corners_from(face, v))
        .map(|[_, a, b]| {
            let [da, db] = [a, b].map(|w| distances[w as usize]);
            let angle = |p: DVec3, q: DVec3| (p - at(v)).angle_between(q - at(v));
            let crossing = || at(a).lerp(at(b), da / (da - db));
            match (da >= 0.0, db >= 0.0) {
                (true, true) => angle(at(a), at(b)),
                (false, false) => 0.0,
                (true, false) => angle(at(a), crossing()),
                (false, true) => angle(crossing(), at(b)),
            }
        })
        .sum();
    positive_angle - 0.5 * angle_sum
}

/// The area of the faces around `vertex` of `model`, with the vertex at `at`.
fn fan_area(model: &FacetModel, vertex: u32, at: DVec3) -> f64 {
    (model.vertex_faces(vertex).iter())
        .map(|&face| {
            let [a, b, c] = model.triangles()[face as usize].map(|w| {
                if w == vertex {
                    at
                } else {
                    model.positions()[w as usize]
                }
            });
            0.5 * (b - a).cross(c - a).length()
        })
        .sum()
}

/// `-1`, `0` or `1`.
fn sign(d: f64) -> i8 {
    if d > 0.0 {
        1
    } else if d < 0.0 {
        -1
    } else {
        0
    }
}

/// The corners starting at corner `k`, orientation kept.
fn rotated(corners: [u32; 3], k: usize) -> [u32; 3] {
    [corners[k], corners[(k + 1) % 3], corners[(k + 2) % 3]]
}

/// The connected pieces of one side: its triangles (over [`SidedVertices`]' numbering) made a
/// soup of the vertices they use, a vertex where two fans of the side meet (the plane touches the
/// surface there from one side) split into one copy per fan, validated into components; `None`
/// when validation fails.
fn side_pieces(
    model: &FacetModel,
    sides: &SidedVertices,
    triangles: Vec<[u32; 3]>,
    face_sources: Vec<u32>,
) -> Option<Vec<SectionPiece>> {
    let used: BTreeSet<u32> = triangles.iter().flatten().copied().collect();
    let mut local = vec![NONE; sides.positions.len()];
    let global: Vec<u32> = used.into_iter().collect();
    for (i, &g) in global.iter().enumerate() {
        local[g as usize] = i as u32;
    }
    let mut soup = TriangleSoup::new(
        global
            .iter()
            .map(|&g| sides.positions[g as usize])
            .collect(),
        (triangles.iter())
            .map(|t| t.map(|g| local[g as usize]))
            .collect(),
    );
    soup.face_sources = face_sources;
    // Two fans of one side meeting at a vertex on the plane (the plane touches the surface there
    // from one side) get a copy of the vertex each.
    let (split, _) = split_non_manifold(&soup);
    // The global vertex of every split soup vertex (copies come after the originals).
    let mut of_split: Vec<u32> = global.clone();
    of_split.resize(split.positions.len(), NONE);
    for (before, after) in soup.triangles.iter().zip(&split.triangles) {
        for k in 0..3 {
            of_split[after[k] as usize] = global[before[k] as usize];
        }
    }
    let mut split = split;
    split.fold_edges = fold_edges(model, sides, &split.triangles, &of_split);
    let validated = validate(&split).ok()?;
    let pieces = (validated.components.into_iter())
        .zip(validated.soup_vertices)
        .map(|(piece, soup_vertices)| {
            let vertices: Vec<u32> = soup_vertices
                .iter()
                .map(|&s| of_split[s as usize])
                .collect();
            described_piece(model, sides, piece, &vertices)
        })
        .collect();
    Some(pieces)
}

/// The fold-line edges of the model that the soup's edges lie on.
fn fold_edges(
    model: &FacetModel,
    sides: &SidedVertices,
    triangles: &[[u32; 3]],
    global: &[u32],
) -> Vec<FoldEdge> {
    let mut folds = BTreeSet::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let origins = [a, b].map(|v| sides.origins[global[v as usize] as usize]);
            if let EdgeOrigin::OnEdge(e) = edge_origin(model, origins) {
                let line = model.edge_fold_lines()[e as usize];
                if line != NONE {
                    folds.insert((a.min(b), a.max(b), line));
                }
            }
        }
    }
    (folds.into_iter())
        .map(|(a, b, fold_line)| FoldEdge {
            vertices: [a, b],
            fold_line,
        })
        .collect()
}

/// The edge of the model two origins lie on together, or the crossed edges of the face between
/// them.
fn edge_origin(model: &FacetModel, ends: [VertexOrigin; 2]) -> EdgeOrigin {
    let crossed = |origin: VertexOrigin| match origin {
        VertexOrigin::Crossing { edge, .. } => edge,
        VertexOrigin::Vertex(_) => NONE,
    };
    match ends {
        [VertexOrigin::Vertex(a), VertexOrigin::Vertex(b)] => match model.find_edge(a, b) {
            Some(e) => EdgeOrigin::OnEdge(e as u32),
            None => EdgeOrigin::InFace([NONE, NONE]),
        },
        [VertexOrigin::Vertex(a), crossing] | [crossing, VertexOrigin::Vertex(a)]
            if crossing.touches(model, a) =>
        {
            EdgeOrigin::OnEdge(crossed(crossing))
        }
        [p, q] => EdgeOrigin::InFace([crossed(p), crossed(q)]),
    }
}

/// A piece with the origins of its vertices and edges and its section edges.
fn described_piece(
    model: &FacetModel,
    sides: &SidedVertices,
    piece: FacetModel,
    global: &[u32],
) -> SectionPiece {
    let vertex_origins: Vec<VertexOrigin> =
        global.iter().map(|&g| sides.origins[g as usize]).collect();
    let on_plane = |v: u32| sides.signs[global[v as usize] as usize] == 0;
    let mut edge_origins = Vec::with_capacity(piece.edges().len());
    let mut on_section = Vec::with_capacity(piece.edges().len());
    for &[a, b] in piece.edges() {
        let origin = edge_origin(model, [a, b].map(|v| vertex_origins[v as usize]));
        let along_boundary =
            matches!(origin, EdgeOrigin::OnEdge(e) if model.is_boundary_edge(e as usize));
        on_section.push(on_plane(a) && on_plane(b) && !along_boundary);
        edge_origins.push(origin);
    }
    SectionPiece {
        model: piece,
        vertex_origins,
        edge_origins,
        on_section,
    }
}

/// The principal axes of the model's surface (area-weighted, about its area centroid), the
/// axis of largest spread first, with the centroid.
pub fn principal_axes(model: &FacetModel) -> (DVec3, [DVec3; 3]) {
    let positions = model.positions();
    let mut total = 0.0;
    let mut centroid = DVec3::ZERO;
    let mut second = [[0.0; 3]; 3];
    for (f, t) in model.triangles().iter().enumerate() {
        let area = model.triangle_area(f);
        let corners = t.map(|v| positions[v as usize]);
        total += area;
        centroid += area * (corners[0] + corners[1] + corners[2]) / 3.0;
        // The second moment of a triangle: (sum of p pᵀ over corners + c cᵀ with c the
        // corner sum) · area / 12.
        let sum = corners[0] + corners[1] + corners[2];
        for i in 0..3 {
            for j in 0..3 {
                let corner_terms: f64 = corners.iter().map(|p| p[i] * p[j]).sum();
                second[i][j] += area * (corner_terms + sum[i] * sum[j]) / 12.0;
            }
        }
    }
    if total <= 0.0 {
        return (DVec3::ZERO, [DVec3::X, DVec3::Y, DVec3::Z]);
    }
    centroid /= total;
    let mut covariance = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            covariance[i][j] = second[i][j] / total - centroid[i] * centroid[j];
        }
    }
    (centroid, symmetric_eigenvectors(covariance))
}

/// The eigenvectors of a symmetric 3×3 matrix, by cyclic Jacobi rotations, ordered by
/// decreasing eigenvalue.
fn symmetric_eigenvectors(mut a: [[f64; 3]; 3]) -> [DVec3; 3] {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..50 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        let scale = a[0][0].powi(2) + a[1][1].powi(2) + a[2][2].powi(2);
        if off <= 1e-30 * scale.max(f64::MIN_POSITIVE) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for row in &mut a {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let (row_p, row_q) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| c * row_p[k] - s * row_q[k]);
            a[q] = std::array::from_fn(|k| s * row_p[k] + c * row_q[k]);
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| a[j][j].total_cmp(&a[i][i]));
    order.map(|k| DVec3::new(v[0][k], v[1][k], v[2][k]).normalize_or(DVec3::X))
}

#[cfg(test)]
pub(crate) mod tests {
    use std::f64::consts::PI;

    use super::*;

    /// A flat grid of `columns` × `rows` unit squares in the xy plane, two triangles each.
    pub(crate) fn grid(columns: u32, rows: u32) -> FacetModel {
        let mut positions = Vec::new();
        for j in 0..=rows {
            for i in 0..=columns {
                positions.push(DVec3::new(i as f64, j as f64, 0.0));
            }
        }
        let at = |i: u32, j: u32| j * (columns + 1) + i;
        let mut triangles = Vec::new();
        for j in 0..rows {
            for i in 0..columns {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let soup = TriangleSoup::new(positions, triangles);
        validate(&soup).unwrap().components.remove(0)
    }

    #[test]
    fn a_plane_across_a_grid_cuts_it_into_two_pieces_of_the_right_areas() {
        let model = grid(10, 10);
        let plane = Plane::through(DVec3::new(3.5, 0.0, 0.0), DVec3::X);
        let pieces = section(&model, plane).expect("both sides have faces");
        assert_eq!(pieces.len(), 2);
        let areas: Vec<f64> = pieces.iter().map(|p| p.model.area()).collect();
        assert!((areas[0] - 65.0).abs() < 1e-9, "{areas:?}");
        assert!((areas[1] - 35.0).abs() < 1e-9, "{areas:?}");
        for piece in &pieces {
            let section_length: f64 = (piece.model.edges().iter())
                .zip(&piece.on_section)
                .filter(|&(_, &on)| on)
                .map(|(&[a, b], _)| {
                    let p = piece.model.positions();
                    p[a as usize].distance(p[b as usize])
                })
                .sum();
            assert!((section_length - 10.0).abs() < 1e-9, "{section_length}");
            for (v, origin) in piece.vertex_origins.iter().enumerate() {
                let nearer = origin.nearer_vertex(&model);
                let distance =
                    piece.model.positions()[v].distance(model.positions()[nearer as usize]);
                assert!(distance <= 0.5 * 2f64.sqrt() + 1e-12);
            }
        }
    }

    #[test]
    fn a_crossing_near_a_vertex_passes_through_it_and_makes_no_sliver() {
        let model = grid(4, 4);
        let plane = Plane::through(DVec3::new(2.05, 0.0, 0.0), DVec3::X);
        let pieces = section(&model, plane).unwrap();
        for piece in &pieces {
            for f in 0..piece.model.triangle_count() {
                assert!(piece.model.triangle_area(f) >= 0.2 * 0.5 * 0.5 - 1e-12);
            }
        }
        let total: f64 = pieces.iter().map(|p| p.model.area()).sum();
        assert!((total - 16.0).abs() < 1e-9);
    }

    /// The plane x = 2.1 passes within a tenth of an edge of the grid's column x = 2: its inner
    /// vertex (2, 1) moves onto the plane, the boundary vertices (2, 0) and (2, 2) stay, so the
    /// left piece is the 2 × 2 square plus the triangle (2, 0), (2.1, 1), (2, 2) of area 0.1.
    #[test]
    fn an_inner_vertex_the_section_passes_through_moves_onto_the_plane() {
        let model = grid(4, 2);
        let plane = Plane::through(DVec3::new(2.1, 0.0, 0.0), DVec3::X);
        let pieces = section(&model, plane).unwrap();
        assert_eq!(pieces.len(), 2);
        let left = (pieces.iter())
            .find(|piece| piece.model.positions().iter().all(|p| p.x <= 2.1 + 1e-12))
            .expect("a piece left of the plane");
        assert!(
            (left.model.area() - 4.1).abs() < 1e-12,
            "{}",
            left.model.area()
        );
        let total: f64 = pieces.iter().map(|p| p.model.area()).sum();
        assert!((total - 8.0).abs() < 1e-12);
        let on_plane: Vec<DVec3> = (left.model.positions().iter())
            .copied()
            .filter(|p| p.x > 1.5)
            .collect();
        assert_eq!(on_plane.len(), 3);
        assert!(on_plane.contains(&DVec3::new(2.1, 1.0, 0.0)));
        assert!(on_plane.contains(&DVec3::new(2.0, 0.0, 0.0)));
        assert!(on_plane.contains(&DVec3::new(2.0, 2.0, 0.0)));
    }

    /// The same grid with its vertex (2, 1) raised by 0.5: moving it onto the plane x = 2.1
    /// (along its edge to (3, 1)) keeps its faces well shaped, but changes their area by more
    /// than [`MAX_FAN_AREA_CHANGE`], so it stays, and the section passes through it (a tenth of
    /// the edge away) because it holds curvature ([`HELD_DEFICIT`]).
    #[test]
    fn a_vertex_whose_faces_would_change_area_stays_where_it_is() {
        let flat = grid(4, 2);
        let raised = DVec3::new(2.0, 1.0, 0.5);
        let mut positions = flat.positions().to_vec();
        let vertex = (positions.iter())
            .position(|p| *p == DVec3::new(2.0, 1.0, 0.0))
            .expect("the grid's vertex (2, 1)");
        positions[vertex] = raised;
        let soup = TriangleSoup::new(positions, flat.triangles().to_vec());
        let model = validate(&soup).unwrap().components.remove(0);
        let to = raised.lerp(DVec3::new(3.0, 1.0, 0.0), 0.1);
        assert!(can_move_vertex(&model, vertex as u32, to));
        let change = fan_area(&model, vertex as u32, to) / fan_area(&model, vertex as u32, raised);
        assert!((change - 1.0).abs() > MAX_FAN_AREA_CHANGE, "{change}");
        assert!(model.angle_deficits()[vertex] >= HELD_DEFICIT);
        let plane = Plane::through(DVec3::new(2.1, 0.0, 0.0), DVec3::X);
        let pieces = section(&model, plane).unwrap();
        assert!(
            pieces
                .iter()
                .all(|piece| !piece.model.positions().contains(&to))
        );
        assert!(
            pieces
                .iter()
                .any(|piece| piece.model.positions().contains(&raised))
        );
    }

    /// The grid with its column x = 2 raised by 0.3 into a crease (a fold line's worth of
    /// bending, no curvature at its inner vertex): that vertex (2, 1) may not move onto the plane
    /// x = 2.15 (its faces' area would change), and its crossing is more than [`HELD_SNAP`] of
    /// its edge away, so the edge is split beside it and the curve runs past it.
    #[test]
    fn a_crossing_beside_a_vertex_on_a_crease_splits_the_edge() {
        let flat = grid(4, 2);
        let positions: Vec<DVec3> = (flat.positions().iter())
            .map(|&p| if p.x == 2.0 { p + 0.3 * DVec3::Z } else { p })
            .collect();
        let soup = TriangleSoup::new(positions, flat.triangles().to_vec());
        let model = validate(&soup).unwrap().components.remove(0);
        let crest = DVec3::new(2.0, 1.0, 0.3);
        let vertex = model.positions().iter().position(|&p| p == crest).unwrap();
        assert!(model.angle_deficits()[vertex].abs() < 1e-12);
        let plane = Plane::through(DVec3::new(2.15, 0.0, 0.0), DVec3::X);
        let pieces = section(&model, plane).unwrap();
        let positions = || {
            pieces
                .iter()
                .flat_map(|piece| piece.model.positions().iter())
        };
        assert!(
            positions().any(|&p| p == crest),
            "the crest vertex stays where it is"
        );
        // The edge from the crest is split at a point of its own, at least a tenth of it away
        // (where the fairing of the curve puts it).
        let across = DVec3::new(3.0, 1.0, 0.0) - crest;
        let split = positions().any(|&p| {
            let s = (p - crest).dot(across) / across.length_squared();
            (p - crest - s * across).length() < 1e-12 && (HELD_SNAP..=1.0 - HELD_SNAP).contains(&s)
        });
        assert!(split, "the edge is split beside the crest vertex");
    }

    /// An open tube of `sides` flat faces around the z axis (circumradius 1, so a side is 1 long
    /// for six) from z = 0 to `height`, each side two triangles.
    fn prism(sides: u32, height: f64) -> FacetModel {
        let corner = |k: u32, z: f64| {
            let angle = TAU * f64::from(k) / f64::from(sides);
            DVec3::new(angle.cos(), angle.sin(), z)
        };
        let positions = (0..sides)
            .flat_map(|k| [corner(k, 0.0), corner(k, height)])
            .collect();
        let triangles = (0..sides)
            .flat_map(|k| {
                let next = (k + 1) % sides;
                let (b0, t0, b1, t1) = (2 * k, 2 * k + 1, 2 * next, 2 * next + 1);
                [[b0, b1, t1], [b0, t1, t0]]
            })
            .collect();
        validate(&TriangleSoup::new(positions, triangles))
            .unwrap()
            .components
            .remove(0)
    }

    /// A slanted plane crosses a hexagonal tube along a curve that, unrolled, zig-zags: it turns
    /// at every vertical edge (by up to 27.5° here, found from the unrolled tube). Its crossing
    /// points slide along their edges until the curve turns by less than a quarter of that (about
    /// 5°; it would run straight round the tube with more sweeps); the surface and its area stay
    /// exactly the model's, and every point stays on its edge, at least a fifth of it from
    /// either end.
    #[test]
    fn a_slanted_section_of_a_coarse_tube_is_faired_to_a_curve_that_hardly_turns() {
        let model = prism(6, 3.0);
        let slant = 0.6;
        let plane = Plane::through(
            DVec3::new(0.0, 0.0, 1.5),
            DVec3::new(0.0, slant, 1.0).normalize(),
        );
        // The plane's curve unrolled: straight across each side, so it turns only at the
        // vertical edges, by the change of its slope there (each side is 1 long).
        let height = |k: i32| {
            let angle = TAU * f64::from(k) / 6.0;
            1.5 - slant * angle.sin()
        };
        let plane_turn = (0..6)
            .map(|k| {
                ((height(k + 1) - height(k)).atan() - (height(k) - height(k - 1)).atan()).abs()
            })
            .fold(0.0, f64::max);
        assert!(
            plane_turn > 25f64.to_radians(),
            "{}",
            plane_turn.to_degrees()
        );

        let pieces = section(&model, plane).unwrap();
        let area: f64 = pieces.iter().map(|p| p.model.area()).sum();
        assert!((area - model.area()).abs() < 1e-9 * model.area());
        let mut largest_turn: f64 = 0.0;
        for piece in &pieces {
            let m = &piece.model;
            for (v, origin) in piece.vertex_origins.iter().enumerate() {
                if let VertexOrigin::Crossing { edge, t } = *origin {
                    let [a, b] =
                        model.edges()[edge as usize].map(|w| model.positions()[w as usize]);
                    assert!(m.positions()[v].distance(a.lerp(b, t)) < 1e-12);
                    assert!((SECTION_SNAP..=1.0 - SECTION_SNAP).contains(&t), "{t}");
                }
                let on_section = (m.edges().iter().zip(&piece.on_section))
                    .any(|(edge, &on)| on && edge.contains(&(v as u32)));
                if on_section {
                    largest_turn = largest_turn.max((PI - m.angle_sum(v as u32)).abs());
                }
            }
        }
        assert!(
            largest_turn < 0.25 * plane_turn,
            "{} against {}",
            largest_turn.to_degrees(),
            plane_turn.to_degrees()
        );
    }

    #[test]
    fn a_plane_missing_the_model_is_no_section() {
        let model = grid(3, 3);
        assert!(section(&model, Plane::through(DVec3::new(5.0, 0.0, 0.0), DVec3::X)).is_none());
    }

    #[test]
    fn the_principal_axes_of_a_long_strip_start_along_it() {
        let model = grid(20, 2);
        let (centroid, axes) = principal_axes(&model);
        assert!(centroid.distance(DVec3::new(10.0, 1.0, 0.0)) < 1e-9);
        assert!(axes[0].dot(DVec3::X).abs() > 1.0 - 1e-9);
        assert!(axes[1].dot(DVec3::Y).abs() > 1.0 - 1e-9);
        assert!(axes[2].dot(DVec3::Z).abs() > 1.0 - 1e-9);
    }
}
