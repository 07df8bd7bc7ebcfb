//! T-junctions on a shared section curve: a later section crossed the curve two pieces share on
//! one side only, so one side has a point inside an edge of the other. Glued as they are, the
//! two edges there would not match and the union would keep a crack of no width along them,
//! which a flattening may open or fold over. Each side's section edges are split at the other
//! side's points inside them first, so the curve has the same points on both sides and glues
//! whole.

use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use super::piece::{
    EdgeAttributes, FoldLines, Piece, attributes_of, edge_records, fold_edge_list, ordered,
};
use super::state::point_key;
use crate::cad::TriangleSoup;
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
    let mut splitting = Splitting {
        positions: model.positions().to_vec(),
        part_vertex: piece.part_vertex.clone(),
        triangles: model.triangles().to_vec(),
        face_sources: model.face_sources().to_vec(),
        attributes: EdgeAttributes::new(),
        folds: FoldLines::new(),
        face_parts: BTreeMap::new(),
    };
    for (ends, attribute, line) in edge_records(piece, |v| v) {
        splitting.attributes.insert(ends, attribute);
        if line != NONE {
            splitting.folds.insert(ends, line);
        }
    }
    for (&e, points) in splits {
        let chain: Vec<u32> = (points.iter())
            .map(|&(_, v)| splitting.add_vertex(other, v))
            .collect();
        splitting.split(piece, e, chain)?;
    }
    let mut soup = TriangleSoup::new(splitting.positions, splitting.triangles);
    soup.face_sources = splitting.face_sources;
    soup.fold_edges = fold_edge_list(splitting.folds);
    let model = rebuild(soup).ok()?;
    let (stiffness, section_edges) = attributes_of(&model, &splitting.attributes);
    Some(Piece {
        model,
        stiffness,
        part_vertex: splitting.part_vertex,
        section_edges,
        depth: piece.depth,
    })
}

/// A piece's soup and edge attributes while its edges are split.
struct Splitting {
    positions: Vec<DVec3>,
    part_vertex: Vec<u32>,
    triangles: Vec<[u32; 3]>,
    face_sources: Vec<u32>,
    attributes: EdgeAttributes,
    folds: FoldLines,
    /// The triangles each face split so far has become.
    face_parts: BTreeMap<usize, Vec<usize>>,
}

impl Splitting {
    /// A new vertex at `other`'s vertex `v`.
    fn add_vertex(&mut self, other: &Piece, v: u32) -> u32 {
        self.positions.push(other.model.positions()[v as usize]);
        self.part_vertex.push(other.part_vertex[v as usize]);
        (self.positions.len() - 1) as u32
    }

    /// Splits the piece's edge `e` at the `inner` vertices (in order from its lower-numbered
    /// end): the triangle now holding the edge is fanned from its opposite corner. `None` when
    /// no triangle holds it.
    fn split(&mut self, piece: &Piece, e: usize, inner: Vec<u32>) -> Option<()> {
        let edge = piece.model.edges()[e];
        let face = piece.model.edge_faces()[e][0] as usize;
        let parts = self.face_parts.entry(face).or_insert_with(|| vec![face]);
        let (t, corner) = (parts.iter())
            .find_map(|&t| directed_edge_corner(self.triangles[t], edge).map(|k| (t, k)))?;
        let triangle = self.triangles[t];
        let apex = triangle[(corner + 2) % 3];
        let mut chain = [vec![edge[0]], inner, vec![edge[1]]].concat();
        if triangle[corner] != chain[0] {
            chain.reverse();
        }
        let attribute = self.attributes.remove(&edge)?;
        let line = self.folds.remove(&edge);
        for (k, pair) in chain.windows(2).enumerate() {
            let (from, to) = (pair[0], pair[1]);
            self.attributes.insert(ordered([from, to]), attribute);
            if let Some(line) = line {
                self.folds.insert(ordered([from, to]), line);
            }
            if k == 0 {
                self.triangles[t] = [from, to, apex];
            } else {
                self.attributes
                    .insert(ordered([from, apex]), (attribute.0, None));
                parts.push(self.triangles.len());
                self.triangles.push([from, to, apex]);
                self.face_sources.push(piece.model.face_sources()[face]);
            }
        }
        Some(())
    }
}

/// The corner of `triangle` where it runs along `edge` (either way round), if it has that edge.
fn directed_edge_corner(triangle: [u32; 3], [a, b]: [u32; 2]) -> Option<usize> {
    (0..3).find(|&k| {
        let (from, to) = (triangle[k], triangle[(k + 1) % 3]);
        (from, to) == (a, b) || (from, to) == (b, a)
    })
}
