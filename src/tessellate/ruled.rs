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

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::face_mesh::FaceMesh;
use super::fan::mesh_cone_fan;
use super::patch::mesh_patch;
use super::strip::stitch_rows;
use super::surface::{
    Frame, PatchGeometry, PatchSurface, RuledSurface, Section, fractions_through, pieces_for_arc,
    pieces_for_length,
};

/// Two edge directions closer than this (radians) are parallel: both sections advance together.
pub const PARALLEL_ANGLE_TOLERANCE: f64 = 1e-9;

/// A circle section of a loft has at least this many corners.
pub const MINIMUM_CIRCLE_PIECES: usize = 8;

/// The rulings of a surface: section points (in part coordinates) and which pairs they join.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Rulings {
    /// Points of the first curve.
    pub bottom: Vec<DVec3>,
    /// Points of the second curve.
    pub top: Vec<DVec3>,
    /// Each ruling as `[bottom index, top index]`; consecutive rulings advance one or both.
    pub pairs: Vec<[usize; 2]>,
}

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

/// The rulings of `surface`, sections sampled at `mesh_size` and `chord`.
pub fn rulings(surface: &RuledSurface, mesh_size: f64, chord: f64) -> Rulings {
    rulings_through(surface, mesh_size, chord, &[])
}

/// [`rulings`] with a ruling at each domain `u` of `through` (the angle in degrees of a cylinder
/// or a cone, the arc length along an extrusion's profile; see [`super::surface_domain`]): the
/// stretches of the sections between them are sampled each on its own, so that the rulings next
/// to them keep about their usual spacing. A loft's rulings are fixed by its sections' tangents
/// and ignore `through`.
pub fn rulings_through(
    surface: &RuledSurface,
    mesh_size: f64,
    chord: f64,
    through: &[f64],
) -> Rulings {
    match surface {
        RuledSurface::Circular {
            frame,
            bottom,
            top,
            angles,
        } => {
            let range = angles[1] - angles[0];
            let radius = bottom.radius.max(top.radius);
            let stations: Vec<f64> = through
                .iter()
                .map(|u| (u.to_radians() - angles[0]) / range)
                .collect();
            let fractions = fractions_through(&stations, |span| {
                pieces_for_arc(radius, range * span, mesh_size, chord)
            });
            let angle =
                std::iter::once(angles[0]).chain(fractions.iter().map(|t| angles[0] + t.of(range)));
            let (bottom, top) = angle
                .map(|a| (frame.point(bottom.point(a)), frame.point(top.point(a))))
                .unzip();
            same_index_rulings(bottom, top)
        }
        RuledSurface::Extrusion {
            frame,
            profile,
            direction,
        } => {
            let points = profile.sample_through(mesh_size, chord, through);
            let bottom: Vec<DVec3> = points.iter().map(|p| frame.point(p.extend(0.0))).collect();
            let offset = frame.vector(*direction);
            let top = bottom.iter().map(|&p| p + offset).collect();
            same_index_rulings(bottom, top)
        }
        RuledSurface::Loft {
            frame,
            bottom,
            top,
            seam,
        } => loft_rulings(frame, bottom, top, *seam, mesh_size, chord),
    }
}

fn same_index_rulings(bottom: Vec<DVec3>, top: Vec<DVec3>) -> Rulings {
    let pairs = (0..bottom.len()).map(|k| [k, k]).collect();
    Rulings { bottom, top, pairs }
}

/// A closed convex polygon sampled from a section, starting at its support point for the seam
/// direction, with the direction of each outgoing edge measured from the seam in `[0, 2π)`.
struct SampledSection {
    corners: Vec<DVec2>,
    directions: Vec<f64>,
}

/// Samples a section; circles get `circle_pieces` corners (the same for both sections of a loft,
/// so that two circles pair corner for corner).
fn sample_section(section: &Section, seam: f64, circle_pieces: usize) -> SampledSection {
    match section {
        Section::Circle { center, radius, .. } => {
            let pieces = circle_pieces;
            // Corner k has tangent direction seam + 2πk/n: corner 0 is the support point of the
            // seam direction; edge k turns halfway between its corners.
            let corners = (0..pieces)
                .map(|k| {
                    let tangent = seam + TAU * k as f64 / pieces as f64;
                    *center + DVec2::from_angle(tangent - TAU / 4.0) * *radius
                })
                .collect();
            let directions = (0..pieces)
                .map(|k| TAU * (k as f64 + 0.5) / pieces as f64)
                .collect();
            SampledSection {
                corners,
                directions,
            }
        }
        Section::Polygon { corners, .. } => {
            let count = corners.len();
            let direction = |k: usize| {
                let edge = corners[(k + 1) % count] - corners[k];
                (edge.y.atan2(edge.x) - seam).rem_euclid(TAU)
            };
            let start = (0..count)
                .min_by(|&a, &b| direction(a).total_cmp(&direction(b)))
                .unwrap_or(0);
            let order: Vec<usize> = (0..count).map(|k| (start + k) % count).collect();
            SampledSection {
                corners: order.iter().map(|&k| corners[k]).collect(),
                directions: order.iter().map(|&k| direction(k)).collect(),
            }
        }
    }
}

fn loft_rulings(
    frame: &Frame,
    bottom: &Section,
    top: &Section,
    seam: f64,
    mesh_size: f64,
    chord: f64,
) -> Rulings {
    let radius = [bottom, top]
        .iter()
        .filter_map(|section| match section {
            Section::Circle { radius, .. } => Some(*radius),
            Section::Polygon { .. } => None,
        })
        .fold(0.0, f64::max);
    let circle_pieces = pieces_for_arc(radius, TAU, mesh_size, chord).max(MINIMUM_CIRCLE_PIECES);
    let lower = sample_section(bottom, seam, circle_pieces);
    let upper = sample_section(top, seam, circle_pieces);
    let lower_point =
        |k: usize| frame.point(lower.corners[k % lower.corners.len()].extend(bottom.z()));
    let upper_point =
        |k: usize| frame.point(upper.corners[k % upper.corners.len()].extend(top.z()));
    let mut rulings = Rulings {
        bottom: vec![lower_point(0)],
        top: vec![upper_point(0)],
        pairs: vec![[0, 0]],
    };
    let (mut i, mut j) = (0, 0);
    let (lower_count, upper_count) = (lower.directions.len(), upper.directions.len());
    while i < lower_count || j < upper_count {
        let lower_next = lower.directions.get(i).copied().unwrap_or(f64::INFINITY);
        let upper_next = upper.directions.get(j).copied().unwrap_or(f64::INFINITY);
        let both = (lower_next - upper_next).abs() <= PARALLEL_ANGLE_TOLERANCE;
        let advance_lower = both || lower_next < upper_next;
        let advance_upper = both || !advance_lower;
        let lower_edge = [lower_point(i), lower_point(i + 1)];
        let upper_edge = [upper_point(j), upper_point(j + 1)];
        // A long side is split into pieces of at most the mesh size. Two parallel sides are split
        // each to its own length, their points paired along a monotone path: every ruling
        // between them stays in their common plane, which is meshed as one planar piece.
        let count = |advance: bool, edge: [DVec3; 2]| {
            if advance {
                pieces_for_length(edge[0].distance(edge[1]), mesh_size)
            } else {
                0
            }
        };
        let (lower_pieces, upper_pieces) = (
            count(advance_lower, lower_edge),
            count(advance_upper, upper_edge),
        );
        let steps = lower_pieces.max(upper_pieces);
        let (mut lower_done, mut upper_done) = (0, 0);
        for k in 1..=steps {
            if lower_done < k * lower_pieces / steps {
                lower_done += 1;
                let t = lower_done as f64 / lower_pieces as f64;
                rulings.bottom.push(lower_edge[0].lerp(lower_edge[1], t));
            }
            if upper_done < k * upper_pieces / steps {
                upper_done += 1;
                let t = upper_done as f64 / upper_pieces as f64;
                rulings.top.push(upper_edge[0].lerp(upper_edge[1], t));
            }
            rulings
                .pairs
                .push([rulings.bottom.len() - 1, rulings.top.len() - 1]);
        }
        i += usize::from(advance_lower);
        j += usize::from(advance_upper);
    }
    rulings
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

/// Two wedge normals closer than this (sine of the angle) are parallel.
const COPLANAR_TOLERANCE: f64 = 1e-9;

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

fn newell_normal(points: &[DVec3]) -> DVec3 {
    let count = points.len();
    (0..count)
        .map(|k| points[k].cross(points[(k + 1) % count]))
        .sum()
}

/// The boundary of the planar piece of rulings `first..=last`, counter-clockwise in the chart
/// (ruling index, height): along the bottom section, up the last ruling, back along the top
/// section, down the first ruling. Each vertex comes with whether the edge leaving it lies on a
/// section (true) or on a ruling shared with the next piece (false). Repeated vertices (an apex)
/// appear once.
fn plane_boundary(
    rulings: &Rulings,
    rows: &[Vec<u32>],
    bottom: &[u32],
    top: &[u32],
    first: usize,
    last: usize,
) -> Vec<(u32, bool)> {
    let [b0, t0] = rulings.pairs[first];
    let [b1, t1] = rulings.pairs[last];
    let chains: [(Vec<u32>, bool); 4] = [
        (bottom[b0..=b1].to_vec(), true),
        (rows[last].clone(), false),
        (top[t0..=t1].iter().rev().copied().collect(), true),
        (rows[first].iter().rev().copied().collect(), false),
    ];
    let mut boundary: Vec<(u32, bool)> = Vec::new();
    for (chain, on_section) in chains {
        let count = chain.len();
        for (k, v) in chain.into_iter().enumerate() {
            // A chain's last vertex starts the next chain: the next chain says where its edge is.
            let leaving = on_section && k + 1 < count;
            match boundary.last_mut() {
                Some(previous) if previous.0 == v => previous.1 = leaving,
                _ => boundary.push((v, leaving)),
            }
        }
    }
    if boundary.len() > 1 && boundary.first().map(|f| f.0) == boundary.last().map(|l| l.0) {
        boundary.pop();
    }
    boundary
}

/// Growth of consecutive gaps between the points added on a section side, from a much shorter
/// neighbouring boundary edge towards the side's own spacing.
const SIDE_GRADING: f64 = 1.2;
/// Integration step of the graded spacing, as a fraction of the local size.
const GRADING_STEP: f64 = 0.05;
/// Two consecutive section edges whose directions differ by less than this (sine) are one side.
const COLLINEAR_TOLERANCE: f64 = 1e-9;

/// Adds points on the straight section sides of `boundary` next to a much shorter boundary edge
/// (a fan's ruling graded towards its apex), so that the corner can be meshed with well-shaped
/// triangles: along a side (a run of collinear section edges) the gaps grow by
/// [`SIDE_GRADING`] from the neighbouring edge's length up to the side's own spacing, over as
/// many of its pieces as that takes. The side's points are kept (each piece gets points of its
/// own), and so are ruling sides, which are shared with the neighbouring piece.
fn graded_sides(mesh: &mut FaceMesh, boundary: &[(u32, bool)]) -> Vec<u32> {
    let count = boundary.len();
    let position = |k: usize, mesh: &FaceMesh| mesh.positions[boundary[k % count].0 as usize];
    let direction =
        |k: usize, mesh: &FaceMesh| (position(k + 1, mesh) - position(k, mesh)).normalize_or_zero();
    let continues_side = |k: usize, mesh: &FaceMesh| {
        let previous = (k + count - 1) % count;
        boundary[k].1
            && boundary[previous].1
            && direction(previous, mesh).cross(direction(k, mesh)).length() <= COLLINEAR_TOLERANCE
            && direction(previous, mesh).dot(direction(k, mesh)) > 0.0
    };
    let Some(start) = (0..count).find(|&k| !continues_side(k, mesh)) else {
        return boundary.iter().map(|&(v, _)| v).collect();
    };
    let mut graded = Vec::with_capacity(count);
    let mut k = start;
    while k < start + count {
        if !boundary[k % count].1 {
            graded.push(boundary[k % count].0);
            k += 1;
            continue;
        }
        let mut end = k + 1;
        while end < start + count && continues_side(end % count, mesh) {
            end += 1;
        }
        let side: Vec<DVec3> = (k..=end).map(|j| position(j, mesh)).collect();
        let before = position(k + count - 1, mesh).distance(side[0]);
        let after = side[side.len() - 1].distance(position(end + 1, mesh));
        for (piece, points) in graded_side(&side, before, after).into_iter().enumerate() {
            graded.push(boundary[(k + piece) % count].0);
            graded.extend(points.into_iter().map(|p| mesh.add_vertex(p)));
        }
        k = end;
    }
    graded
}

/// The points to add inside each piece of the straight side `side` (its points in order), whose
/// neighbouring boundary edges are `before` and `after` long: spread by the size
/// `min(piece, before + (g − 1) x, after + (g − 1) (L − x))` at distance `x` along the side
/// (`g` the grading, `L` the side's length), each piece getting the rounded integral of
/// `1 / size` as its number of gaps.
fn graded_side(side: &[DVec3], before: f64, after: f64) -> Vec<Vec<DVec3>> {
    let lengths: Vec<f64> = side.windows(2).map(|w| w[0].distance(w[1])).collect();
    let total: f64 = lengths.iter().sum();
    let growth = SIDE_GRADING - 1.0;
    let mut offset = 0.0;
    let mut added = Vec::with_capacity(lengths.len());
    for (piece, &length) in lengths.iter().enumerate() {
        let size = |x: f64| {
            length
                .min(before + growth * x)
                .min(after + growth * (total - x))
        };
        // Cumulative integral of 1 / size over the piece (midpoint rule, steps a fraction of
        // the size so that the graded end is resolved).
        let mut samples = vec![(0.0, 0.0)];
        while let Some(&(x, integral)) = samples.last().filter(|s| s.0 < length) {
            let step = (GRADING_STEP * size(offset + x)).min(length - x);
            let next = integral + step / size(offset + x + 0.5 * step);
            samples.push((x + step, next));
        }
        let integral = samples[samples.len() - 1].1;
        let gaps = (integral.round() as usize).max(1);
        let mut points = Vec::with_capacity(gaps - 1);
        let mut s = 0;
        for gap in 1..gaps {
            let target = integral * gap as f64 / gaps as f64;
            while samples[s + 1].1 < target {
                s += 1;
            }
            let ((x0, i0), (x1, i1)) = (samples[s], samples[s + 1]);
            let x = x0 + (x1 - x0) * (target - i0) / (i1 - i0);
            points.push(side[piece].lerp(side[piece + 1], x / length));
        }
        added.push(points);
        offset += length;
    }
    added
}

/// Meshes the planar polygon `boundary` (vertices of `mesh`, counter-clockwise seen from the side
/// the ruled meshes' normals point to) by the patch mesher on its plane, keeping the boundary's
/// vertices (nothing is added on the boundary, so neighbouring pieces stay conforming), with the
/// fold segments `folds` (fold line, ends in the plane) as constraint edges, tagged as fold
/// edges. False when the polygon has no plane or the patch mesher refuses it (the caller
/// stitches it instead).
fn mesh_plane(
    mesh: &mut FaceMesh,
    boundary: &[u32],
    folds: &[(u32, [DVec3; 2])],
    mesh_size: f64,
) -> bool {
    let points: Vec<DVec3> = boundary
        .iter()
        .map(|&v| mesh.positions[v as usize])
        .collect();
    let normal = newell_normal(&points);
    let longest_side = (0..points.len())
        .map(|k| points[k].distance(points[(k + 1) % points.len()]))
        .fold(0.0, f64::max);
    let Some(frame) = Frame::new(points[0], normal, points[1] - points[0]) else {
        return false;
    };
    let local = |p: DVec3| {
        DVec2::new(
            (p - frame.origin).dot(frame.x),
            (p - frame.origin).dot(frame.y),
        )
    };
    let outer: Vec<DVec2> = points.iter().map(|&p| local(p)).collect();
    let fold_polylines: Vec<(u32, Vec<DVec2>)> = folds
        .iter()
        .map(|&(line, ends)| (line, ends.map(local).to_vec()))
        .collect();
    let patch = PatchSurface {
        geometry: PatchGeometry::Plane(frame),
        outer: outer.clone(),
        holes: Vec::new(),
    };
    // Sides are at most the mesh size already: the patch mesher must not split them again.
    let split_above = longest_side.max(mesh_size) * (1.0 + PLANE_SIDE_MARGIN);
    let Ok(plane) = mesh_patch(&patch, &fold_polylines, split_above, f64::INFINITY) else {
        return false;
    };
    let tolerance = PLANE_MATCH_RATIO * longest_side;
    let mut index: Vec<Option<u32>> = vec![None; plane.positions.len()];
    for triangle in plane
        .triangles
        .iter()
        .filter(|t| !is_sliver(t, &plane.positions))
    {
        let corners = triangle.map(|v| {
            let v = v as usize;
            *index[v].get_or_insert_with(|| {
                match outer
                    .iter()
                    .position(|corner| corner.distance(plane.parameters[v]) <= tolerance)
                {
                    Some(k) => boundary[k],
                    None => mesh.add_vertex(plane.positions[v]),
                }
            })
        });
        mesh.triangles.push(corners);
    }
    for &([a, b], line) in &plane.fold_edges {
        if let (Some(a), Some(b)) = (index[a as usize], index[b as usize]) {
            mesh.fold_edges.push(([a, b], line));
        }
    }
    true
}

/// A triangle whose area is below this fraction of its longest edge squared is a sliver.
const SLIVER_AREA_RATIO: f64 = 1e-10;

/// True for a sliver the planar mesher leaves between nearly collinear points of a straight
/// side (outside the piece, between the side and its convex hull; interior triangles are
/// refined to the minimum angle and are never this thin).
fn is_sliver(triangle: &[u32; 3], positions: &[DVec3]) -> bool {
    let [a, b, c] = triangle.map(|v| positions[v as usize]);
    let longest = a
        .distance_squared(b)
        .max(b.distance_squared(c))
        .max(c.distance_squared(a));
    0.5 * (b - a).cross(c - a).length() < SLIVER_AREA_RATIO * longest
}

/// Relative margin on the longest side of a planar piece, so that the patch mesher splits none.
const PLANE_SIDE_MARGIN: f64 = 1e-6;
/// A patch vertex this close to a boundary corner (fraction of the longest side) is that corner.
const PLANE_MATCH_RATIO: f64 = 1e-9;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tessellate::surface::RuledCircle;

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
