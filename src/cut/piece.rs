//! A piece of a part cut by plane sections (`--seams pieces`), before it is flattened, and the
//! gluing of two neighbouring pieces back together along the section curve they share.

use std::collections::BTreeMap;

use glam::DVec3;

use super::seam::FLAT_DEFICIT;
use super::state::{PointKey, point_key};
use crate::cad::{FoldEdge, TriangleSoup};
use crate::flatten::Stiffness;
use crate::mesh::{FacetModel, NONE, Plane, rebuild};

/// A piece of the part, before it is flattened.
#[derive(Debug, Clone)]
pub(super) struct Piece {
    /// Its facet model.
    pub model: FacetModel,
    /// Its edges' stiffness.
    pub stiffness: Stiffness,
    /// For each vertex, the part's vertex it copies (or, for a section point, the nearer end of
    /// the part's edge it lies on).
    pub part_vertex: Vec<u32>,
    /// Per edge, the section it lies on, if any.
    pub section_edges: Vec<Option<SectionId>>,
    /// How many sections made it.
    pub depth: usize,
}

/// The section an edge lies on, named by its plane (the bits of its normal and offset, mixed), so
/// that every piece names a section alike whatever order the pieces are made in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(super) struct SectionId(u64);

impl SectionId {
    /// The section along `plane`.
    pub fn of(plane: Plane) -> Self {
        let words = [plane.normal.x, plane.normal.y, plane.normal.z, plane.offset];
        Self(words.iter().fold(0x9e37_79b9_7f4a_7c15, |hash: u64, word| {
            let mixed = (hash ^ word.to_bits()).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            mixed ^ (mixed >> 31)
        }))
    }
}

/// An edge by its ends' [`PointKey`]s, in order.
pub(super) type SideKey = [PointKey; 2];

/// The key of the edge from vertex `a` to vertex `b` of a model with these `positions`.
pub(super) fn side_key(positions: &[DVec3], a: u32, b: u32) -> SideKey {
    let mut key = [a, b].map(|v| point_key(positions[v as usize]));
    key.sort();
    key
}

/// The length of the edge of `key`.
pub(super) fn side_length(key: &SideKey) -> f64 {
    let [a, b] = key.map(|p| DVec3::from_array(p.map(f64::from_bits)));
    a.distance(b)
}

impl Piece {
    /// The whole part as one piece.
    pub fn whole(model: &FacetModel, stiffness: &Stiffness) -> Self {
        Self {
            model: model.clone(),
            stiffness: stiffness.clone(),
            part_vertex: (0..model.vertex_count() as u32).collect(),
            section_edges: vec![None; model.edges().len()],
            depth: 0,
        }
    }

    /// Its boundary edges on a section, by their ends' positions, with their edge.
    pub fn section_sides(&self) -> BTreeMap<SideKey, usize> {
        let positions = self.model.positions();
        (self.model.edges().iter().enumerate())
            .filter(|&(e, _)| self.section_edges[e].is_some() && self.model.is_boundary_edge(e))
            .map(|(e, &[a, b])| (side_key(positions, a, b), e))
            .collect()
    }

    /// The piece and `other` glued along the section edges they share into one piece, or `None`
    /// when they share none, when a point of the shared curve is not one vertex on either side
    /// (a vertex the section touched, split per fan), or when the union is not a facet model.
    /// The shared edges are no longer section edges; stiffness, fold lines and the part's
    /// vertices carry over.
    pub fn glued(&self, other: &Piece) -> Option<Piece> {
        self.glued_along(other, &self.shared_sides(other))
    }

    /// The piece and `other` glued as by [`Piece::glued`], but with a slit: the shared curve's
    /// vertex of largest absolute angle deficit in `union` (their union by [`Piece::glued`];
    /// a point where the union's surface closes around a cone, which a flattening must stretch
    /// open) stays on the boundary, and the shorter of the curve's two runs from it to an end
    /// stays unglued, a section on both of its sides, as a dart ending in that point. `None`
    /// when no such vertex is more than flat ([`FLAT_DEFICIT`]), when both runs end where the
    /// curve branches or closes, or when `union` or the slit one is not bounded by one loop (a
    /// slit in a union with holes can leave a hole of no area).
    pub fn slit_glued(&self, other: &Piece, union: &Piece) -> Option<Piece> {
        if union.model.boundary_loops().len() != 1 {
            return None;
        }
        let shared = self.shared_sides(other);
        let ends = |&(e, _): &(usize, usize)| self.model.edges()[e];
        let mut degree: BTreeMap<u32, usize> = BTreeMap::new();
        for pair in &shared {
            for v in ends(pair) {
                *degree.entry(v).or_default() += 1;
            }
        }
        // The union keeps the piece's vertex numbers (its own vertices come first).
        let deficits = union.model.angle_deficits();
        let (&tip, _) = (degree.iter())
            .filter(|&(&v, &count)| count == 2 && deficits[v as usize].abs() > FLAT_DEFICIT)
            .max_by(|a, b| {
                let (da, db) = (deficits[*a.0 as usize].abs(), deficits[*b.0 as usize].abs());
                da.total_cmp(&db).then(b.0.cmp(a.0))
            })?;
        let positions = self.model.positions();
        let mut runs: Vec<(Vec<usize>, f64)> = (0..shared.len())
            .filter(|&i| ends(&shared[i]).contains(&tip))
            .filter_map(|first| run_to_end(&shared, first, tip, &degree, &|i| ends(&shared[i])))
            .map(|run| {
                let length = (run.iter())
                    .map(|&i| {
                        let [a, b] = ends(&shared[i]);
                        positions[a as usize].distance(positions[b as usize])
                    })
                    .sum();
                (run, length)
            })
            .collect();
        runs.sort_by(|a, b| a.1.total_cmp(&b.1));
        let slit = &runs.first()?.0;
        let kept: Vec<(usize, usize)> = (0..shared.len())
            .filter(|i| !slit.contains(i))
            .map(|i| shared[i])
            .collect();
        self.glued_along(other, &kept)
            .filter(|slit_union| slit_union.model.boundary_loops().len() == 1)
    }

    /// The section edges this piece shares with `other`, as (this piece's edge, theirs) pairs.
    fn shared_sides(&self, other: &Piece) -> Vec<(usize, usize)> {
        let theirs = other.section_sides();
        (self.section_sides().iter())
            .filter_map(|(key, &e)| theirs.get(key).map(|&f| (e, f)))
            .collect()
    }

    /// The piece and `other` glued along the `shared` (this piece's edge, theirs) pairs.
    fn glued_along(&self, other: &Piece, shared: &[(usize, usize)]) -> Option<Piece> {
        let welds = welds(self, other, shared)?;
        let count = self.model.vertex_count() as u32;
        let mut next = count;
        let their_vertex: Vec<u32> = (0..other.model.vertex_count() as u32)
            .map(|v| {
                welds.get(&v).copied().unwrap_or_else(|| {
                    next += 1;
                    next - 1
                })
            })
            .collect();
        let mut positions = self.model.positions().to_vec();
        let mut part_vertex = self.part_vertex.clone();
        for (v, &to) in their_vertex.iter().enumerate() {
            if to >= count {
                positions.push(other.model.positions()[v]);
                part_vertex.push(other.part_vertex[v]);
            }
        }
        let mut soup = TriangleSoup::new(positions, self.model.triangles().to_vec());
        soup.triangles
            .extend((other.model.triangles().iter()).map(|t| t.map(|v| their_vertex[v as usize])));
        soup.face_sources = [self.model.face_sources(), other.model.face_sources()].concat();
        let identity: Vec<u32> = (0..count).collect();
        let sides = [(self, &identity[..]), (other, &their_vertex[..])];
        soup.fold_edges = fold_edges(&sides);
        let model = rebuild(soup).ok()?;
        let glued_edges: Vec<[u32; 2]> = (shared.iter())
            .map(|&(e, _)| self.model.edges()[e])
            .collect();
        let (stiffness, section_edges) = edge_attributes(&model, &sides, &glued_edges);
        Some(Piece {
            model,
            stiffness,
            part_vertex,
            section_edges,
            depth: self.depth.max(other.depth),
        })
    }
}

/// Each of `other`'s vertices on the shared section edges (`(mine, theirs)` edge pairs) and the
/// vertex of `piece` at the same point; `None` when there is no shared edge or a point is not
/// one vertex on either side.
fn welds(piece: &Piece, other: &Piece, shared: &[(usize, usize)]) -> Option<BTreeMap<u32, u32>> {
    if shared.is_empty() {
        return None;
    }
    let mut welds = BTreeMap::new();
    let mut welded_to = BTreeMap::new();
    for &(e, f) in shared {
        let [a, b] = piece.model.edges()[e];
        let their_ends = other.model.edges()[f];
        for theirs in their_ends {
            let at = point_key(other.model.positions()[theirs as usize]);
            let mine = if point_key(piece.model.positions()[a as usize]) == at {
                a
            } else {
                b
            };
            if *welds.entry(theirs).or_insert(mine) != mine
                || *welded_to.entry(mine).or_insert(theirs) != theirs
            {
                return None;
            }
        }
    }
    Some(welds)
}

/// The shared edges (indices into the shared list, whose ends `ends` gives) from `first`, an
/// edge at `tip`, along the curve away from `tip` to its end: `None` when the curve branches
/// (a vertex on more than two shared edges) or comes back to `tip` before it ends.
fn run_to_end(
    shared: &[(usize, usize)],
    first: usize,
    tip: u32,
    degree: &BTreeMap<u32, usize>,
    ends: &dyn Fn(usize) -> [u32; 2],
) -> Option<Vec<usize>> {
    let mut run = vec![first];
    let mut at = tip;
    loop {
        let [a, b] = ends(*run.last()?);
        at = if a == at { b } else { a };
        match degree.get(&at) {
            Some(1) => return Some(run),
            Some(2) if at != tip => {
                let last = *run.last()?;
                let next = (0..shared.len()).find(|&i| i != last && ends(i).contains(&at))?;
                run.push(next);
            }
            _ => return None,
        }
    }
}

/// An edge's stiffness factor and the section it lies on, by its ends in increasing order.
pub(super) type EdgeAttributes = BTreeMap<[u32; 2], (f64, Option<SectionId>)>;

/// The fold line of each fold-line edge, by its ends in increasing order.
pub(super) type FoldLines = BTreeMap<[u32; 2], u32>;

/// The ends of an edge in increasing order.
pub(super) fn ordered([a, b]: [u32; 2]) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// Each edge of the piece with its ends renumbered by `number` (in increasing order), its
/// stiffness factor and section, and its fold line ([`NONE`] for none).
pub(super) fn edge_records<'a>(
    piece: &'a Piece,
    number: impl Fn(u32) -> u32 + 'a,
) -> impl Iterator<Item = ([u32; 2], (f64, Option<SectionId>), u32)> + 'a {
    let factors = piece.stiffness.factors();
    let lines = piece.model.edge_fold_lines();
    (piece.model.edges().iter().enumerate()).map(move |(e, &[a, b])| {
        let factor = factors.get(e).copied().unwrap_or(1.0);
        let ends = ordered([number(a), number(b)]);
        (ends, (factor, piece.section_edges[e]), lines[e])
    })
}

/// The fold-line edges of a soup, from their fold lines.
pub(super) fn fold_edge_list(folds: FoldLines) -> Vec<FoldEdge> {
    (folds.into_iter())
        .map(|(vertices, fold_line)| FoldEdge {
            vertices,
            fold_line,
        })
        .collect()
}

/// The stiffness and sections of `model`'s edges from `attributes` (an edge not there: factor 1,
/// no section).
pub(super) fn attributes_of(
    model: &FacetModel,
    attributes: &EdgeAttributes,
) -> (Stiffness, Vec<Option<SectionId>>) {
    let (factors, sections) = (model.edges().iter())
        .map(|&edge| {
            attributes
                .get(&ordered(edge))
                .copied()
                .unwrap_or((1.0, None))
        })
        .unzip();
    (Stiffness::from_factors(factors), sections)
}

/// The fold-line edges of the pieces, each piece's vertices renumbered by its map.
fn fold_edges(sides: &[(&Piece, &[u32])]) -> Vec<FoldEdge> {
    let folds = (sides.iter())
        .flat_map(|&(piece, number)| edge_records(piece, |v| number[v as usize]))
        .filter(|&(_, _, line)| line != NONE)
        .map(|(ends, _, line)| (ends, line))
        .collect();
    fold_edge_list(folds)
}

/// The glued model's stiffness and sections, from the pieces' edges (each piece's vertices
/// renumbered by its map): the stiffer where both have an edge, and no section on the `glued`
/// edges (numbered as the first piece's).
fn edge_attributes(
    model: &FacetModel,
    sides: &[(&Piece, &[u32])],
    glued: &[[u32; 2]],
) -> (Stiffness, Vec<Option<SectionId>>) {
    let mut attributes = EdgeAttributes::new();
    for &(piece, number) in sides {
        for (ends, (factor, on_section), _) in edge_records(piece, |v| number[v as usize]) {
            let entry = attributes.entry(ends).or_insert((factor, None));
            entry.0 = entry.0.max(factor);
            entry.1 = entry.1.or(on_section);
        }
    }
    for &edge in glued {
        if let Some(entry) = attributes.get_mut(&ordered(edge)) {
            entry.1 = None;
        }
    }
    attributes_of(model, &attributes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Plane, section, test_grid as grid};

    /// The grid's two halves across `x = 10`, as pieces.
    fn halves() -> (FacetModel, Vec<Piece>) {
        let model = grid(20, 4);
        let plane = Plane::through(DVec3::new(10.0, 2.0, 0.0), DVec3::X);
        let pieces = sides(&model, plane);
        (model, pieces)
    }

    /// The model's sides of the plane, as pieces of stiffness 2.
    fn sides(model: &FacetModel, plane: Plane) -> Vec<Piece> {
        let mut stiffness = Stiffness::uniform(model);
        stiffness.raise_where(2.0, |_| true);
        let whole = Piece::whole(model, &stiffness);
        let sides = section(model, plane).expect("two sides");
        (sides.into_iter())
            .map(|side| {
                let part_vertex = (side.vertex_origins.iter())
                    .map(|origin| origin.nearer_vertex(model))
                    .collect();
                Piece {
                    stiffness: Stiffness::from_factors(vec![2.0; side.model.edges().len()]),
                    section_edges: (side.on_section.iter())
                        .map(|&on| on.then(|| SectionId::of(plane)))
                        .collect(),
                    part_vertex,
                    model: side.model,
                    depth: whole.depth + 1,
                }
            })
            .collect()
    }

    #[test]
    fn a_cone_point_on_the_shared_curve_stays_open_as_a_slit() {
        let flat = grid(4, 4);
        let apex = DVec3::new(2.0, 2.0, 1.5);
        let mut positions = flat.positions().to_vec();
        positions[12] = apex;
        let model = rebuild(TriangleSoup::new(positions, flat.triangles().to_vec())).unwrap();
        let normal = DVec3::new(1.0, 0.3, 0.0).normalize();
        let pieces = sides(&model, Plane::through(apex, normal));
        assert_eq!(pieces.len(), 2);
        let at_apex = |piece: &Piece| {
            (piece.model.positions().iter())
                .position(|&p| p == apex)
                .expect("the apex")
        };
        let union = pieces[0].glued(&pieces[1]).expect("they share the section");
        let deficit = union.model.angle_deficits()[at_apex(&union)];
        assert!(deficit > 0.5, "the union closes around the cone: {deficit}");

        let slit = (pieces[0].slit_glued(&pieces[1], &union)).expect("a slit from the apex");
        assert_eq!(slit.model.triangle_count(), union.model.triangle_count());
        assert_eq!(slit.model.boundary_loops().len(), 1);
        assert!(
            slit.model.vertex_count() > union.model.vertex_count(),
            "the slit's side is two curves"
        );
        let apex_vertex = at_apex(&slit) as u32;
        let rim = &slit.model.boundary_loops()[0];
        assert!(rim.contains(&apex_vertex), "the apex is the slit's end");
        assert!(
            !slit.section_sides().is_empty(),
            "the slit is still a section"
        );

        let flat_halves = halves().1;
        let flat_union = flat_halves[0].glued(&flat_halves[1]).unwrap();
        assert!(
            flat_halves[0]
                .slit_glued(&flat_halves[1], &flat_union)
                .is_none(),
            "no slit where the union is flat"
        );
    }

    #[test]
    fn two_halves_glue_back_into_the_whole() {
        let (model, pieces) = halves();
        let glued = pieces[0].glued(&pieces[1]).expect("they share the section");
        assert_eq!(glued.model.triangle_count(), model.triangle_count());
        assert_eq!(glued.model.vertex_count(), model.vertex_count());
        assert_eq!(glued.model.edges().len(), model.edges().len());
        assert!((glued.model.area() - model.area()).abs() < 1e-9);
        assert!(
            glued.section_edges.iter().all(Option::is_none),
            "no section left"
        );
        assert!(glued.section_sides().is_empty());
        assert!(glued.stiffness.factors().iter().all(|&f| f == 2.0));
        let mut vertices = glued.part_vertex.clone();
        vertices.sort();
        vertices.dedup();
        assert_eq!(
            vertices.len(),
            model.vertex_count(),
            "each part vertex once"
        );
        assert_eq!(glued.depth, 1);
    }

    #[test]
    fn a_piece_does_not_glue_to_itself_or_to_a_stranger() {
        let (model, pieces) = halves();
        assert!(
            pieces[0].glued(&pieces[0]).is_none(),
            "its own section edges are not a shared curve with two sides"
        );
        let stranger = Piece::whole(&model, &Stiffness::uniform(&model));
        assert!(pieces[0].glued(&stranger).is_none(), "no shared section");
    }
}
