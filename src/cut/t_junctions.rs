//! T-junctions on a shared section curve: a later section crossed the curve two pieces share on
//! one side only, so one side has a point inside an edge of the other. Glued as they are, the
//! two edges there would not match and the union would keep a crack of no width along them,
//! which a flattening may open or fold over. Each side's section edges are split at the other
//! side's points inside them first, so the curve has the same points on both sides and glues
//! whole.

use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use super::piece::Piece;
use super::state::point_key;
use crate::cad::{FoldEdge, TriangleSoup};
use crate::flatten::Stiffness;
use crate::mesh::{NONE, rebuild};

/// How close to an edge, as a fraction of its length (and of the point's distance from the
/// origin, for rounding), a point must lie to be on it.
const ON_EDGE: f64 = 1e-9;

/// The two pieces, each with its section edges split at the other's section points inside them
/// ([`conformed_to`]).
pub(super) fn conformed_pair<'a>(a: &'a Piece, b: &'a Piece) -> (Cow<'a, Piece>, Cow<'a, Piece>) {
    (conformed_to(a, b), conformed_to(b, a))
}

/// The piece with each of its section edges on the boundary split at the section points of
/// `other` on the boundary that lie inside it; borrowed when there is none, or when the split
/// piece would not be a facet model.
pub(super) fn conformed_to<'a>(piece: &'a Piece, other: &Piece) -> Cow<'a, Piece> {
    let splits = points_inside_edges(piece, other);
    if splits.is_empty() {
        return Cow::Borrowed(piece);
    }
    match split_edges(piece, other, &splits) {
        Some(split) => Cow::Owned(split),
        None => Cow::Borrowed(piece),
    }
}

/// For each section edge of `piece` on its boundary with points of `other` inside it, those
/// points: `other`'s vertex and its parameter along the edge (from its lower-numbered end),
/// in order along the edge.
fn points_inside_edges(piece: &Piece, other: &Piece) -> BTreeMap<usize, Vec<(f64, u32)>> {
    let mine = piece.section_sides();
    let my_points: BTreeSet<_> = mine.keys().flatten().copied().collect();
    let candidates: BTreeSet<u32> = (other.section_sides().values())
        .flat_map(|&e| other.model.edges()[e])
        .filter(|&v| !my_points.contains(&point_key(other.model.positions()[v as usize])))
        .collect();
    let mut splits: BTreeMap<usize, Vec<(f64, u32)>> = BTreeMap::new();
    if candidates.is_empty() {
        return splits;
    }
    let positions = piece.model.positions();
    let ends = |e: usize| piece.model.edges()[e].map(|v| positions[v as usize]);
    let grid = EdgeGrid::new(mine.values().map(|&e| (e, ends(e))));
    for v in candidates {
        let point = other.model.positions()[v as usize];
        for e in grid.near(point) {
            if let Some(t) = parameter_inside(ends(e), point) {
                splits.entry(e).or_default().push((t, v));
            }
        }
    }
    for points in splits.values_mut() {
        points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    }
    splits
}

/// The parameter of `point` along the segment `[a, b]` when it lies inside it (not at an end),
/// within [`ON_EDGE`].
fn parameter_inside([a, b]: [DVec3; 2], point: DVec3) -> Option<f64> {
    let along = b - a;
    let length_squared = along.length_squared();
    if length_squared == 0.0 {
        return None;
    }
    let t = (point - a).dot(along) / length_squared;
    let slack = ON_EDGE * (length_squared.sqrt() + point.length());
    let inside = t * length_squared.sqrt() > slack && (1.0 - t) * length_squared.sqrt() > slack;
    (inside && point.distance(a + t * along) <= slack).then_some(t)
}

/// Segments hashed into cubes as large as the longest of them, for finding those near a point.
struct EdgeGrid {
    /// The cube's side.
    cell: f64,
    /// The segments (their indices) whose bounding box meets each cube.
    cells: BTreeMap<[i64; 3], Vec<usize>>,
}

impl EdgeGrid {
    /// The grid of these (index, ends) segments.
    fn new(segments: impl Iterator<Item = (usize, [DVec3; 2])> + Clone) -> Self {
        let longest = (segments.clone())
            .map(|(_, [a, b])| a.distance(b))
            .fold(0.0, f64::max);
        let cell = if longest > 0.0 { longest } else { 1.0 };
        let mut cells: BTreeMap<[i64; 3], Vec<usize>> = BTreeMap::new();
        for (index, [a, b]) in segments {
            let slack = DVec3::splat(ON_EDGE * (cell + a.length().max(b.length())));
            let (low, high) = (
                Self::cube(a.min(b) - slack, cell),
                Self::cube(a.max(b) + slack, cell),
            );
            for x in low[0]..=high[0] {
                for y in low[1]..=high[1] {
                    for z in low[2]..=high[2] {
                        cells.entry([x, y, z]).or_default().push(index);
                    }
                }
            }
        }
        Self { cell, cells }
    }

    /// The cube holding a point.
    fn cube(point: DVec3, cell: f64) -> [i64; 3] {
        (point / cell).floor().to_array().map(|c| c as i64)
    }

    /// The segments whose bounding box meets the cube of `point`.
    fn near(&self, point: DVec3) -> impl Iterator<Item = usize> + '_ {
        (self.cells.get(&Self::cube(point, self.cell)).into_iter())
            .flatten()
            .copied()
    }
}

/// The piece with each edge of `splits` split at its points (`other`'s vertices, which become
/// new vertices of the piece after its own), its one face fanned from the opposite corner; the
/// halves carry the edge's stiffness, section flag and fold line, the new inner edges its
/// stiffness. `None` when the result is not a facet model.
fn split_edges(
    piece: &Piece,
    other: &Piece,
    splits: &BTreeMap<usize, Vec<(f64, u32)>>,
) -> Option<Piece> {
    let model = &piece.model;
    let mut positions = model.positions().to_vec();
    let mut part_vertex = piece.part_vertex.clone();
    let mut triangles = model.triangles().to_vec();
    let mut face_sources = model.face_sources().to_vec();
    let factors = piece.stiffness.factors();
    let ordered = |[a, b]: [u32; 2]| [a.min(b), a.max(b)];
    // Stiffness and section flag by vertex pair; fold lines likewise.
    let mut attributes: BTreeMap<[u32; 2], (f64, bool)> = (model.edges().iter().enumerate())
        .map(|(e, &edge)| {
            (
                edge,
                (
                    factors.get(e).copied().unwrap_or(1.0),
                    piece.section_edges[e],
                ),
            )
        })
        .collect();
    let lines = model.edge_fold_lines();
    let mut folds: BTreeMap<[u32; 2], u32> = (model.edges().iter().enumerate())
        .filter(|&(e, _)| lines[e] != NONE)
        .map(|(e, &edge)| (edge, lines[e]))
        .collect();
    // The triangles each face has become, as splits of its edges fan it.
    let mut face_parts: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (&e, points) in splits {
        let edge = model.edges()[e];
        let mut chain = vec![edge[0]];
        for &(_, v) in points {
            chain.push(positions.len() as u32);
            positions.push(other.model.positions()[v as usize]);
            part_vertex.push(other.part_vertex[v as usize]);
        }
        chain.push(edge[1]);
        let face = model.edge_faces()[e][0] as usize;
        let parts = face_parts.entry(face).or_insert_with(|| vec![face]);
        let (slot, corner) = (parts.iter().enumerate())
            .find_map(|(slot, &t)| directed_edge_corner(triangles[t], edge).map(|k| (slot, k)))?;
        let t = parts[slot];
        let triangle = triangles[t];
        let (from, apex) = (triangle[corner], triangle[(corner + 2) % 3]);
        if from != chain[0] {
            chain.reverse();
        }
        let attribute = attributes[&edge];
        for (k, pair) in chain.windows(2).enumerate() {
            let fan = [pair[0], pair[1], apex];
            attributes.insert(ordered([pair[0], pair[1]]), attribute);
            if let Some(&line) = folds.get(&edge) {
                folds.insert(ordered([pair[0], pair[1]]), line);
            }
            if k > 0 {
                attributes.insert(ordered([pair[0], apex]), (attribute.0, false));
            }
            if k == 0 {
                triangles[t] = fan;
            } else {
                parts.push(triangles.len());
                triangles.push(fan);
                face_sources.push(model.face_sources()[face]);
            }
        }
        attributes.remove(&edge);
        folds.remove(&edge);
    }
    let mut soup = TriangleSoup::new(positions, triangles);
    soup.face_sources = face_sources;
    soup.fold_edges = (folds.into_iter())
        .map(|(vertices, fold_line)| FoldEdge {
            vertices,
            fold_line,
        })
        .collect();
    let model = rebuild(soup).ok()?;
    let (factors, section_edges) = (model.edges().iter())
        .map(|edge| attributes.get(edge).copied().unwrap_or((1.0, false)))
        .unzip();
    Some(Piece {
        model,
        stiffness: Stiffness::from_factors(factors),
        part_vertex,
        section_edges,
        depth: piece.depth,
    })
}

/// The corner of `triangle` where it runs along `edge` (either way round), if it has that edge.
fn directed_edge_corner(triangle: [u32; 3], [a, b]: [u32; 2]) -> Option<usize> {
    (0..3).find(|&k| {
        let (from, to) = (triangle[k], triangle[(k + 1) % 3]);
        (from, to) == (a, b) || (from, to) == (b, a)
    })
}
