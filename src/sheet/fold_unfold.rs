//! The exact unfold of a part file's polygons joined at folds, with a bend allowance at each fold
//! that has a bend radius.
//!
//! The part's surfaces are one face of the sheet (inner, mid or outer, per fold) drawn with sharp
//! folds: each fold's edge is that face's virtual sharp. The real bend starts at the setback
//! `SB = (R + s) · tan(θ/2)` from the sharp on each flange (`s` = 0, t/2 or t, the face's
//! depth from the inside) and its flat length is the allowance `BA` of the bend rule. So the
//! flanges are unfolded rigidly about their shared edges, each flange beyond a bend moved on by
//! `BA − 2 · SB`, and the strip of width `SB` beside the edge on either flange is scaled into half
//! of the bend zone (`BA / 2`), so that the edge itself lands on the bend's centre line.

use std::f64::consts::PI;

use glam::{DVec2, DVec3};

use super::bend::{BendDirection, BendLine};
use super::bend_rule::{AllowanceRule, BendGeometry, allowance_by_rule};
use super::face_map::PlaneMap;
use super::options::SheetOptions;
use super::unfold::{rest_position, wound_clockwise};
use crate::cad::{FoldBend, TriangleSoup};

/// Angles below this (radians) are no bend: the two polygons continue each other.
const FLAT_ANGLE: f64 = 1e-9;

/// A bend must open at least this much (radians) for its flanges' virtual sharp to exist.
const MINIMUM_OPENING: f64 = 1e-3;

/// A part of polygons welded along shared edges, with its folds.
#[derive(Debug, Clone, Copy)]
pub struct FoldedPart<'a> {
    /// The welded soup, each triangle's face source its surface.
    pub soup: &'a TriangleSoup,
    /// How many surfaces.
    pub surfaces: usize,
    /// The folds declared between two surfaces, with their bend when they have a radius.
    pub folds: &'a [([usize; 2], Option<FoldBend>)],
    /// The sheet's thickness, part units.
    pub thickness: f64,
    /// Millimetres per part unit (bend rules work in mm).
    pub millimetres: f64,
}

/// The flat pattern of a folded part: a position per soup vertex and the bends.
#[derive(Debug, Clone, PartialEq)]
pub struct FoldUnfold {
    /// The flat position of every vertex of the soup, its smallest bounding rectangle
    /// axis-aligned and starting at the origin.
    pub flat: Vec<DVec2>,
    /// The bends (folds at an angle), in the order the unfold met them.
    pub bends: Vec<BendLine>,
    /// The surface the unfold started from (the largest).
    pub base_surface: usize,
}

/// One surface: its plane (unit normal from its triangles' winding), centroid and vertices.
#[derive(Debug, Clone)]
struct Facet {
    normal: DVec3,
    centroid: DVec3,
    area: f64,
    vertices: Vec<u32>,
}

/// A strip beside a fold edge on one flange, scaled into half the bend zone.
#[derive(Debug, Clone, Copy)]
struct Strip {
    /// A point of the edge.
    point: DVec3,
    /// Unit direction into the flange, perpendicular to the edge.
    inward: DVec3,
    /// The setback: the strip's width.
    setback: f64,
    /// The bend allowance.
    allowance: f64,
}

impl Strip {
    /// How far a point at `depth` from the edge moves towards the edge (negative: away).
    fn pull(&self, depth: f64) -> f64 {
        if depth >= self.setback {
            return 0.0;
        }
        let beyond_tangent = if self.setback > 0.0 {
            (self.setback - depth) / self.setback * self.allowance / 2.0
        } else {
            self.allowance / 2.0
        };
        beyond_tangent - (self.setback - depth)
    }
}

/// Unfolds `part` with the bend rule of `options` (a table's rows picked by `material`): an
/// error when two polygons share an edge that is not straight, the folds close a loop that does
/// not unfold flat, a bend is 180° or the rule does not cover one.
pub fn unfold_folds(
    part: &FoldedPart,
    options: &SheetOptions,
    material: Option<&str>,
) -> Result<FoldUnfold, String> {
    let facets = facets(part);
    let base = (0..facets.len())
        .filter(|&s| !facets[s].vertices.is_empty())
        .fold(None, |best: Option<usize>, s| match best {
            Some(b) if facets[b].area >= facets[s].area => Some(b),
            _ => Some(s),
        })
        .ok_or("the part has no triangles")?;
    let mut maps: Vec<Option<(PlaneMap, DVec3)>> = vec![None; facets.len()];
    let mut strips: Vec<Vec<Strip>> = vec![Vec::new(); facets.len()];
    let mut bends = Vec::new();
    maps[base] = Some((base_map(&facets[base]), facets[base].normal));
    let mut queue = vec![base];
    let mut next = 0;
    let mut closing = Vec::new();
    while next < queue.len() {
        let a = queue[next];
        next += 1;
        for b in 0..facets.len() {
            if a == b || facets[b].vertices.is_empty() {
                continue;
            }
            let Some(edge) = shared_edge(part.soup, &facets[a], &facets[b])? else {
                continue;
            };
            if maps[b].is_some() {
                closing.push((a, b, edge));
                continue;
            }
            let fold = Fold {
                part,
                options,
                material,
                bend: declared_bend(part.folds, a, b),
            };
            let placed = maps[a].ok_or("a surface unfolded before its parent")?;
            let hinge = fold.hinge([&facets[a], &facets[b]], edge, placed)?;
            let Hinge {
                map,
                viewer,
                strips: [strip_a, strip_b],
                line,
            } = hinge;
            maps[b] = Some((map, viewer));
            strips[a].extend(strip_a);
            strips[b].extend(strip_b);
            bends.extend(line);
            queue.push(b);
        }
    }
    let mut flat = flat_positions(part.soup, &maps, &strips);
    check_closing(&closing, &maps, &strips)?;
    if wound_clockwise(part.soup, &flat) {
        for p in &mut flat {
            p.x = -p.x;
        }
        for bend in &mut bends {
            bend.line = bend.line.map(|p| DVec2::new(-p.x, p.y));
            bend.direction = bend.direction.mirrored();
        }
    }
    rest_position(&mut flat, &mut bends);
    Ok(FoldUnfold {
        flat,
        bends,
        base_surface: base,
    })
}

/// Each surface's plane, centroid, area and vertices.
fn facets(part: &FoldedPart) -> Vec<Facet> {
    let mut facets = vec![
        Facet {
            normal: DVec3::ZERO,
            centroid: DVec3::ZERO,
            area: 0.0,
            vertices: Vec::new(),
        };
        part.surfaces
    ];
    for (&[a, b, c], &face) in part.soup.triangles.iter().zip(&part.soup.face_sources) {
        let Some(facet) = facets.get_mut(face as usize) else {
            continue;
        };
        let [pa, pb, pc] = [a, b, c].map(|v| part.soup.positions[v as usize]);
        let cross = (pb - pa).cross(pc - pa);
        facet.normal += cross;
        facet.area += cross.length() / 2.0;
        facet.centroid += (pa + pb + pc) / 3.0 * (cross.length() / 2.0);
        facet.vertices.extend([a, b, c]);
    }
    for facet in &mut facets {
        facet.normal = facet.normal.normalize_or_zero();
        facet.centroid /= facet.area.max(f64::MIN_POSITIVE);
        facet.vertices.sort_unstable();
        facet.vertices.dedup();
    }
    facets
}

/// The base surface's map: its plane seen from its normal's side.
fn base_map(facet: &Facet) -> PlaneMap {
    let first = facet.normal.any_orthonormal_vector();
    PlaneMap {
        origin: facet.centroid,
        axes: [first, facet.normal.cross(first)],
        flat_origin: DVec2::ZERO,
        flat_axes: [DVec2::X, DVec2::Y],
    }
}

/// The straight edge two surfaces share (its two ends), `None` when they share fewer than two
/// vertices; an error when the shared vertices are not on one line.
fn shared_edge(soup: &TriangleSoup, a: &Facet, b: &Facet) -> Result<Option<[DVec3; 2]>, String> {
    let shared: Vec<DVec3> = a
        .vertices
        .iter()
        .filter(|v| b.vertices.binary_search(v).is_ok())
        .map(|&v| soup.positions[v as usize])
        .collect();
    if shared.len() < 2 {
        return Ok(None);
    }
    let first = shared[0];
    let far = shared
        .iter()
        .copied()
        .max_by(|p, q| p.distance(first).total_cmp(&q.distance(first)))
        .unwrap_or(first);
    let other = shared
        .iter()
        .copied()
        .max_by(|p, q| p.distance(far).total_cmp(&q.distance(far)))
        .unwrap_or(first);
    let direction = (other - far).normalize_or_zero();
    let length = far.distance(other);
    let off_line = shared
        .iter()
        .map(|&p| (p - far).reject_from_normalized(direction).length())
        .fold(0.0, f64::max);
    if off_line > 1e-6 * length.max(1.0) {
        return Err(format!(
            "two polygons share an edge that is not straight ({off_line:.6} off the line): a bend is a straight fold"
        ));
    }
    Ok(Some([far, other]))
}

/// The bend declared on the fold between surfaces `a` and `b` (either order).
fn declared_bend(folds: &[([usize; 2], Option<FoldBend>)], a: usize, b: usize) -> Option<FoldBend> {
    folds
        .iter()
        .find(|(pair, _)| *pair == [a, b] || *pair == [b, a])
        .and_then(|(_, bend)| *bend)
}

/// How a surface hangs on its parent across a fold: its map, its viewer normal (the normal
/// towards the viewer of the flat), the strips on either side and the bend's line.
struct Hinge {
    map: PlaneMap,
    viewer: DVec3,
    strips: [Option<Strip>; 2],
    line: Option<BendLine>,
}

/// A fold between two surfaces as the unfold crosses it.
struct Fold<'a> {
    part: &'a FoldedPart<'a>,
    options: &'a SheetOptions,
    material: Option<&'a str>,
    bend: Option<FoldBend>,
}

impl Fold<'_> {
    /// Surface `b` unfolded about the edge it shares with surface `a` (placed by `placed`),
    /// with the allowance of the fold's bend when it has one (a sharp fold otherwise).
    fn hinge(
        &self,
        [a, b]: [&Facet; 2],
        edge: [DVec3; 2],
        placed: (PlaneMap, DVec3),
    ) -> Result<Hinge, String> {
        let (map_a, viewer_a) = placed;
        let [p, q] = edge;
        let along = (q - p).normalize();
        let side = |facet: &Facet, towards: bool| {
            let direction = facet.normal.cross(along).normalize_or_zero();
            let into = (facet.centroid - p).dot(direction) > 0.0;
            if into == towards {
                direction
            } else {
                -direction
            }
        };
        let outward = side(a, false);
        let inward_b = side(b, true);
        let angle = outward.dot(inward_b).clamp(-1.0, 1.0).acos();
        let sigma = viewer_a.dot(along.cross(outward)).signum();
        let flat_outward = map_a.direction(outward).normalize();
        let mut hinge = Hinge {
            map: PlaneMap {
                origin: p,
                axes: [along, inward_b],
                flat_origin: map_a.point(p),
                flat_axes: [map_a.direction(along).normalize(), flat_outward],
            },
            viewer: along.cross(inward_b) * sigma,
            strips: [None, None],
            line: None,
        };
        if angle <= FLAT_ANGLE {
            return Ok(hinge);
        }
        let figures = self.figures(angle)?;
        hinge.map.flat_origin += flat_outward * (figures.allowance - 2.0 * figures.setback);
        let strip = |inward| Strip {
            point: p,
            inward,
            setback: figures.setback,
            allowance: figures.allowance,
        };
        hinge.strips = [Some(strip(-outward)), Some(strip(inward_b))];
        let centre = flat_outward * (figures.allowance / 2.0 - figures.setback);
        hinge.line = Some(BendLine {
            line: [map_a.point(p) + centre, map_a.point(q) + centre],
            direction: if inward_b.dot(viewer_a) > 0.0 {
                BendDirection::Up
            } else {
                BendDirection::Down
            },
            angle_degrees: angle.to_degrees(),
            inner_radius: figures.inner_radius,
            allowance: figures.allowance,
            rule: figures.rule,
            conical: None,
        });
        Ok(hinge)
    }

    /// The fold's allowance and setback (part units) at `angle`: by the bend rule when it has a
    /// bend radius, none for a sharp fold.
    fn figures(&self, angle: f64) -> Result<BendFigures, String> {
        let Some(bend) = self.bend else {
            return Ok(BendFigures {
                allowance: 0.0,
                setback: 0.0,
                inner_radius: 0.0,
                rule: None,
            });
        };
        if angle > PI - MINIMUM_OPENING {
            return Err(format!(
                "a fold of {:.3}° (a hem) has no virtual sharp to measure the flanges from: model the hem's bend or give a smaller angle",
                angle.to_degrees()
            ));
        }
        let part = self.part;
        let millimetres = part.millimetres;
        let geometry = BendGeometry {
            thickness: part.thickness * millimetres,
            inner_radius: bend.inner_radius * millimetres,
            angle,
        };
        let allowance = allowance_by_rule(
            &self.options.rule,
            self.options.k_factor,
            geometry,
            self.material,
        )?;
        Ok(BendFigures {
            allowance: allowance.allowance / millimetres,
            setback: (bend.inner_radius + bend.side.depth() * part.thickness) * (angle / 2.0).tan(),
            inner_radius: bend.inner_radius,
            rule: Some(allowance.rule),
        })
    }
}

/// A fold's allowance, setback and inner radius (part units) and the rule that gave them.
struct BendFigures {
    allowance: f64,
    setback: f64,
    inner_radius: f64,
    rule: Option<AllowanceRule>,
}

/// Every soup vertex's flat position, from the first surface that uses it: its surface's rigid
/// map, each strip of that surface pulling it into the bend zone.
fn flat_positions(
    soup: &TriangleSoup,
    maps: &[Option<(PlaneMap, DVec3)>],
    strips: &[Vec<Strip>],
) -> Vec<DVec2> {
    let mut flat = vec![None; soup.positions.len()];
    for (triangle, &face) in soup.triangles.iter().zip(&soup.face_sources) {
        let face = face as usize;
        let Some(Some((map, _))) = maps.get(face) else {
            continue;
        };
        for &vertex in triangle {
            let slot = &mut flat[vertex as usize];
            if slot.is_none() {
                *slot = Some(place(map, &strips[face], soup.positions[vertex as usize]));
            }
        }
    }
    flat.into_iter().map(|p| p.unwrap_or(DVec2::ZERO)).collect()
}

/// A point of a surface on the flat: its rigid image, pulled by the surface's strips.
fn place(map: &PlaneMap, strips: &[Strip], point: DVec3) -> DVec2 {
    let mut flat = map.point(point);
    for strip in strips {
        let depth = (point - strip.point).dot(strip.inward);
        let pull = strip.pull(depth);
        if pull != 0.0 {
            flat -= map.direction(strip.inward).normalize() * pull;
        }
    }
    flat
}

/// Checks that a shared edge the unfold did not cross (a loop of folds) lands in one place
/// from both of its surfaces.
fn check_closing(
    closing: &[(usize, usize, [DVec3; 2])],
    maps: &[Option<(PlaneMap, DVec3)>],
    strips: &[Vec<Strip>],
) -> Result<(), String> {
    for &(a, b, edge) in closing {
        let (Some((map_a, _)), Some((map_b, _))) = (maps[a], maps[b]) else {
            continue;
        };
        for point in edge {
            let gap = place(&map_a, &strips[a], point).distance(place(&map_b, &strips[b], point));
            if gap > 1e-6 {
                return Err(format!(
                    "surfaces {a} and {b} share an edge the unfold would tear ({gap:.4} apart): the folds close a loop; give the part a gap or join = \"separate\""
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_strip_lands_on_half_the_bend_zone() {
        let strip = Strip {
            point: DVec3::ZERO,
            inward: DVec3::X,
            setback: 3.0,
            allowance: 4.0,
        };
        // The edge lands on the centre line: 2 beyond the tangent line, which is 3 in.
        assert!((strip.pull(0.0) - (2.0 - 3.0)).abs() < 1e-12);
        assert_eq!(strip.pull(3.0), 0.0);
        assert_eq!(strip.pull(5.0), 0.0);
        assert!((strip.pull(1.5) - (1.0 - 1.5)).abs() < 1e-12);
    }
}
