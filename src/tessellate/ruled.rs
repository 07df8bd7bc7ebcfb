//! Structured meshes of ruled surfaces along their rulings.
//!
//! Input: a [`RuledSurface`], a target edge length `mesh_size` and a chord tolerance (part units).
//! Output: a [`FaceMesh`] whose every vertex lies on a ruling and whose every triangle lies between
//! two consecutive rulings. For a developable surface (cylinder, cone, the convex hull of two
//! sections in parallel planes, an extrusion) the quadrilateral between two consecutive rulings of
//! the sampled sections is planar, so the mesh is exactly developable: it flattens with no strain,
//! which is how E_S and E_C reach round-off on these kinds. A closed section (a full turn) is
//! opened along its first ruling: the seam's vertices are duplicated, not shared. Fold
//! polylines come as [`RulingFolds`] (points on rulings, segments between consecutive rulings),
//! which keep that property.
//!
//! The loft correspondence follows the classical construction of a developable transition: each
//! ruling joins the points of the two sections whose tangents are parallel, found by merging the
//! sections' edge directions in angular order (a polygon corner becomes the apex of a cone fan,
//! a polygon side the base of a plane triangle or trapezoid).

use glam::DVec3;

use super::face_mesh::FaceMesh;
use super::fan::mesh_cone_fan;
use super::ruled_plane::{graded_sides, mesh_plane, newell_normal, plane_boundary};
use super::strip::stitch_rows;
use crate::cad::{RuledSurface, Rulings, pieces_for_length, rulings};
use crate::geometry::tolerance::COPLANAR_TOLERANCE;

/// Fold polylines carried by the rulings ([`super::ruled_folds`] builds them): the points that
/// must be vertices on each ruling and the fold segments that must be mesh edges. Every segment
/// joins two points of one ruling or of two consecutive rulings, so a mesh that has them as
/// edges still has every triangle between two consecutive rulings.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RulingFolds {
    /// Per ruling: fractions along it (0 at its bottom end, 1 at its top end) that must be
    /// vertices, in increasing order (empty for a ruling no fold meets).
    pub stations: Vec<Vec<f64>>,
    /// The fold segments.
    pub segments: Vec<FoldSegment>,
}

/// A piece of a fold polyline between two ruling points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoldSegment {
    /// The fold line's index.
    pub line: u32,
    /// Start: ruling index and fraction along it.
    pub from: (usize, f64),
    /// End: the same ruling (a stretch along it) or the next one.
    pub to: (usize, f64),
}

impl RulingFolds {
    fn stations_of(&self, ruling: usize) -> &[f64] {
        self.stations.get(ruling).map_or(&[], Vec::as_slice)
    }

    /// The fractions from the apex of the fold stations on the rulings `first..=last` of a cone
    /// fan (apex at their bottom ends when `at_bottom`).
    fn fan_rows(&self, first: usize, last: usize, at_bottom: bool) -> Vec<f64> {
        let mut rows: Vec<f64> = (first..=last)
            .flat_map(|r| self.stations_of(r))
            .filter(|&&f| f > 0.0 && f < 1.0)
            .map(|&f| if at_bottom { f } else { 1.0 - f })
            .collect();
        rows.sort_by(f64::total_cmp);
        rows
    }

    /// The segments across the wedge after ruling `wedge`.
    fn across(&self, wedge: usize) -> impl Iterator<Item = &FoldSegment> {
        self.segments
            .iter()
            .filter(move |s| s.from.0 == wedge && s.to.0 == wedge + 1)
    }
}

/// Meshes a ruled surface along its rulings.
pub fn mesh_ruled(surface: &RuledSurface, mesh_size: f64, chord: f64) -> FaceMesh {
    mesh_rulings(
        &rulings(surface, mesh_size, chord),
        &RulingFolds::default(),
        mesh_size,
    )
}

/// How consecutive wedges (the pieces between two consecutive rulings) are meshed.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Piece {
    /// One wedge, its two rulings stitched.
    Strip(usize),
    /// Wedges `first..last` (rulings `first..=last`) in one plane: one planar polygon.
    Plane(usize, usize),
    /// Wedges `first..last` whose rulings all meet at one end (`bottom`: at the bottom section),
    /// not in one plane: a cone fan.
    Fan(usize, usize, bool),
}

/// Meshes rulings. Consecutive rulings in one plane are meshed together as a planar polygon
/// (refined to well-shaped triangles, exact since the piece is flat), cone fans by
/// [`super::fan`], every other wedge by splitting its two rulings to the mesh size and
/// stitching them. Section points shared by consecutive rulings become shared vertices. The
/// stations of `folds` are vertices of their rulings, and its segments are mesh edges, tagged
/// as fold edges (a strip is stitched piecewise between them, a planar piece takes them as
/// constraint edges); a cone fan lays a row along the stations of its rulings (the caller checks
/// that they are the same fractions on each of them, [`fan_wedges`]).
pub fn mesh_rulings(rulings: &Rulings, folds: &RulingFolds, mesh_size: f64) -> FaceMesh {
    let mut mesh = FaceMesh::default();
    let bottom: Vec<u32> = rulings.bottom.iter().map(|&p| mesh.add_vertex(p)).collect();
    let top: Vec<u32> = rulings.top.iter().map(|&p| mesh.add_vertex(p)).collect();
    let pieces = pieces(rulings);
    let mut on_ruling: Vec<Option<Vec<u32>>> = vec![None; rulings.pairs.len()];
    for &piece in &pieces {
        if let Piece::Fan(first, last, at_bottom) = piece {
            let [b, t] = rulings.pairs[first];
            let apex = if at_bottom { bottom[b] } else { top[t] };
            let far: Vec<u32> = rulings.pairs[first..=last]
                .iter()
                .map(|&[b, t]| if at_bottom { top[t] } else { bottom[b] })
                .collect();
            let fold_rows = folds.fan_rows(first, last, at_bottom);
            let vertices = mesh_cone_fan(&mut mesh, apex, &far, at_bottom, &fold_rows, mesh_size);
            for (k, mut row) in vertices.into_iter().enumerate() {
                if !at_bottom {
                    row.reverse();
                }
                on_ruling[first + k] = Some(row);
            }
        }
    }
    let rows: Vec<Vec<u32>> = on_ruling
        .into_iter()
        .zip(&rulings.pairs)
        .enumerate()
        .map(|(k, (row, &[b, t]))| {
            row.unwrap_or_else(|| {
                split_ruling(
                    &mut mesh,
                    bottom[b],
                    top[t],
                    folds.stations_of(k),
                    mesh_size,
                )
            })
        })
        .collect();
    let station_vertex = |mesh: &FaceMesh, (ruling, fraction): (usize, f64)| {
        let row = &rows[ruling];
        let (start, end) = (
            mesh.positions[row[0] as usize],
            mesh.positions[row[row.len() - 1] as usize],
        );
        let along = |v: u32| {
            (mesh.positions[v as usize] - start).dot(end - start) / start.distance_squared(end)
        };
        row.iter()
            .enumerate()
            .min_by(|a, b| {
                (along(*a.1) - fraction)
                    .abs()
                    .total_cmp(&(along(*b.1) - fraction).abs())
            })
            .map_or(0, |(k, _)| k)
    };
    let mut plane_rulings = vec![false; rulings.pairs.len()];
    let mut plane_wedges = vec![false; rulings.pairs.len()];
    for piece in pieces {
        match piece {
            Piece::Strip(wedge) => {
                let mut splits: Vec<(usize, usize)> = folds
                    .across(wedge)
                    .map(|s| (station_vertex(&mesh, s.from), station_vertex(&mesh, s.to)))
                    .collect();
                splits.sort_unstable();
                splits.dedup();
                let (left, right) = (&rows[wedge], &rows[wedge + 1]);
                let mut from = (0, 0);
                for &(i, j) in splits.iter().chain([&(left.len() - 1, right.len() - 1)]) {
                    let (l, r) = (&left[from.0..=i], &right[from.1..=j]);
                    stitch_rows(l, r, &mesh.positions, &mut mesh.triangles);
                    from = (i, j);
                }
            }
            Piece::Plane(first, last) => {
                plane_rulings[first + 1..last].fill(true);
                plane_wedges[first..last].fill(true);
                let boundary = plane_boundary(rulings, &rows, &bottom, &top, first, last);
                let boundary = graded_sides(&mut mesh, &boundary);
                let inside = |s: &FoldSegment| {
                    (first..last).contains(&s.from.0)
                        && (s.to.0 > s.from.0 || (first + 1..last).contains(&s.from.0))
                };
                let point = |mesh: &FaceMesh, at: (usize, f64)| {
                    mesh.positions[rows[at.0][station_vertex(mesh, at)] as usize]
                };
                let constraints: Vec<(u32, [DVec3; 2])> = folds
                    .segments
                    .iter()
                    .filter(|s| inside(s))
                    .map(|s| (s.line, [point(&mesh, s.from), point(&mesh, s.to)]))
                    .collect();
                if !mesh_plane(&mut mesh, &boundary, &constraints, mesh_size) {
                    for wedge in first..last {
                        let (left, right) = (&rows[wedge], &rows[wedge + 1]);
                        stitch_rows(left, right, &mesh.positions, &mut mesh.triangles);
                    }
                }
            }
            Piece::Fan(..) => {}
        }
    }
    // Planar pieces tag their fold edges themselves; elsewhere a fold segment joins two row
    // vertices of consecutive rulings (a strip's forced edge, an edge of a fan's fold row) or
    // runs along a ruling's row.
    for segment in &folds.segments {
        let (from, to) = (segment.from.0, segment.to.0);
        if to > from && !plane_wedges[from] {
            let (i, j) = (
                station_vertex(&mesh, segment.from),
                station_vertex(&mesh, segment.to),
            );
            mesh.fold_edges
                .push(([rows[from][i], rows[to][j]], segment.line));
        }
    }
    for segment in folds.segments.iter().filter(|s| s.from.0 == s.to.0) {
        if plane_rulings[segment.from.0] {
            continue;
        }
        let row = &rows[segment.from.0];
        let (i, j) = (
            station_vertex(&mesh, segment.from),
            station_vertex(&mesh, segment.to),
        );
        for k in i.min(j)..i.max(j) {
            mesh.fold_edges.push(([row[k], row[k + 1]], segment.line));
        }
    }
    mesh
}

/// Per wedge (the piece between rulings `k` and `k + 1`): whether it is part of a cone fan.
pub fn fan_wedges(rulings: &Rulings) -> Vec<bool> {
    let mut fan = vec![false; rulings.pairs.len().saturating_sub(1)];
    for piece in pieces(rulings) {
        if let Piece::Fan(first, last, _) = piece {
            fan[first..last].fill(true);
        }
    }
    fan
}

/// The vertices of the ruling from `bottom` to `top`: its ends, the points at `stations`
/// (fractions along it, increasing), and each gap between them split into pieces of at most
/// `mesh_size`.
fn split_ruling(
    mesh: &mut FaceMesh,
    bottom: u32,
    top: u32,
    stations: &[f64],
    mesh_size: f64,
) -> Vec<u32> {
    let (start, end) = (
        mesh.positions[bottom as usize],
        mesh.positions[top as usize],
    );
    let length = start.distance(end);
    let inner = stations.iter().copied().filter(|&f| f > 0.0 && f < 1.0);
    let stops: Vec<f64> = std::iter::once(0.0).chain(inner).chain([1.0]).collect();
    let mut row = vec![bottom];
    for gap in stops.windows(2) {
        let pieces = pieces_for_length((gap[1] - gap[0]) * length, mesh_size);
        for k in 1..=pieces {
            let fraction = gap[0] + (gap[1] - gap[0]) * k as f64 / pieces as f64;
            if fraction < 1.0 {
                row.push(mesh.add_vertex(start.lerp(end, fraction)));
            }
        }
    }
    row.push(top);
    row
}

/// The wedges grouped into pieces (see [`Piece`]).
fn pieces(rulings: &Rulings) -> Vec<Piece> {
    let wedges = rulings.pairs.len().saturating_sub(1);
    let corners = |w: usize| {
        let ([b0, t0], [b1, t1]) = (rulings.pairs[w], rulings.pairs[w + 1]);
        [
            rulings.bottom[b0],
            rulings.bottom[b1],
            rulings.top[t1],
            rulings.top[t0],
        ]
    };
    let normals: Vec<DVec3> = (0..wedges)
        .map(|w| newell_normal(&corners(w)).normalize_or_zero())
        .collect();
    let size = rulings
        .bottom
        .iter()
        .chain(&rulings.top)
        .map(|p| p.distance(rulings.bottom[0]))
        .fold(0.0, f64::max);
    let coplanar = |w: usize| {
        let (n, m) = (normals[w], normals[w + 1]);
        n.cross(m).length() <= COPLANAR_TOLERANCE
            && n.dot(m) > 0.0
            && corners(w + 1)
                .iter()
                .all(|p| n.dot(*p - corners(w)[0]).abs() <= COPLANAR_TOLERANCE * size)
    };
    let apex = |w: usize| {
        let ([b0, t0], [b1, t1]) = (rulings.pairs[w], rulings.pairs[w + 1]);
        match (b0 == b1, t0 == t1) {
            (true, false) => Some((true, b0)),
            (false, true) => Some((false, t0)),
            _ => None,
        }
    };
    let mut pieces = Vec::new();
    let mut w = 0;
    while w < wedges {
        let mut end = w;
        while end + 1 < wedges && coplanar(end) {
            end += 1;
        }
        if end > w || apex(w).is_some_and(|_| w + 1 >= wedges || apex(w + 1) != apex(w)) {
            pieces.push(Piece::Plane(w, end + 1));
            w = end + 1;
            continue;
        }
        if let Some(shared) = apex(w) {
            while end + 1 < wedges && apex(end + 1) == Some(shared) && !coplanar(end) {
                end += 1;
            }
            pieces.push(Piece::Fan(w, end + 1, shared.0));
            w = end + 1;
            continue;
        }
        pieces.push(Piece::Strip(w));
        w += 1;
    }
    pieces
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use glam::DVec2;

    use crate::cad::RuledCircle;
    use crate::cad::{Frame, Section};
    use crate::tessellate::ruled::*;
    use crate::tessellate::ruled_plane::graded_side;

    #[test]
    fn a_cylinder_strip_has_the_area_of_its_polygon() {
        let surface = RuledSurface::Circular {
            frame: Frame::WORLD,
            bottom: RuledCircle {
                center: DVec3::ZERO,
                radius: 50.0,
                tilt: 0.0,
            },
            top: RuledCircle {
                center: DVec3::new(0.0, 0.0, 100.0),
                radius: 50.0,
                tilt: 0.0,
            },
            angles: [0.0, TAU],
        };
        let mesh = mesh_ruled(&surface, 5.0, 0.05);
        let analytic = TAU * 50.0 * 100.0;
        assert!((mesh.area() - analytic).abs() / analytic < 1e-3);
    }

    #[test]
    fn a_side_next_to_a_short_edge_is_graded_over_its_pieces() {
        // A side of ten pieces of 10 after an edge of 0.01: gaps grow from about 0.01 by about
        // the grading, over several pieces, and every piece keeps its end points.
        let side: Vec<DVec3> = (0..=10)
            .map(|k| DVec3::new(10.0 * k as f64, 0.0, 0.0))
            .collect();
        let added = graded_side(&side, 0.01, 10.0);
        let mut xs = vec![0.0];
        for (piece, points) in added.iter().enumerate() {
            xs.extend(points.iter().map(|p| p.x));
            xs.push(side[piece + 1].x);
        }
        let gaps: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(gaps[0] < 0.02, "first gap {}", gaps[0]);
        assert!(!added[1].is_empty(), "the grading reaches the second piece");
        assert!(gaps.iter().all(|&g| g <= 10.0 + 1e-9));
        // Within a piece gaps grow by the grading (with rounding); from one piece to the next
        // the whole number of gaps per piece allows a larger step, below 2.
        let growth = |gaps: &[f64]| gaps.windows(2).map(|w| w[1] / w[0]).fold(0.0, f64::max);
        let first_piece = added[0].len() + 1;
        assert!(growth(&gaps[..first_piece]) < 1.25, "{gaps:?}");
        assert!(growth(&gaps) < 2.0, "{gaps:?}");
    }

    #[test]
    fn square_to_round_rulings_fan_from_the_corners() {
        let surface = RuledSurface::Loft {
            frame: Frame::WORLD,
            bottom: Section::Polygon {
                corners: vec![
                    DVec2::new(-100.0, -100.0),
                    DVec2::new(100.0, -100.0),
                    DVec2::new(100.0, 100.0),
                    DVec2::new(-100.0, 100.0),
                ],
                z: 0.0,
            },
            top: Section::Circle {
                center: DVec2::ZERO,
                radius: 60.0,
                z: 150.0,
            },
            seam: 0.0,
        };
        let rulings = rulings(&surface, 10.0, 0.1);
        // Each side of 200 is split into 20 pieces of 10; the last point closes the loop.
        assert_eq!(rulings.bottom.len(), 81);
        assert!(rulings.bottom[80].distance(rulings.bottom[0]) < 1e-12);
        // Rulings advance one or both ends by one point at a time, and some stay on a square
        // corner while the circle turns: the cone fans.
        assert!(rulings.pairs.windows(2).all(|w| {
            let step = [w[1][0] - w[0][0], w[1][1] - w[0][1]];
            step[0] <= 1 && step[1] <= 1 && step[0] + step[1] >= 1
        }));
        let fan_steps = rulings
            .pairs
            .windows(2)
            .filter(|w| w[0][0] == w[1][0])
            .count();
        assert!(fan_steps >= 4);
        // Top points lie on the circle or on a chord of it split to match a parallel side.
        assert!(rulings.top.iter().all(|p| {
            let radius = p.truncate().length();
            (59.0..=60.0 + 1e-9).contains(&radius)
        }));
        assert_eq!(rulings.pairs.last(), Some(&[80, rulings.top.len() - 1]));
    }
}
