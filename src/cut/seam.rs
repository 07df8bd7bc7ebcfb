//! Seams: the cuts that open a closed or ring-shaped surface into a disk before it is flattened,
//! and the user's own seams laid on the mesh.
//!
//! Inputs: a [`FacetModel`] (model units) and the vertices a cut may not pass (fold lines, no-cut
//! regions). Output: one seam path at a time (vertex indices of the current model); the caller
//! cuts along it and asks again until [`next_seam`] returns `None`, so every path is planned on
//! the model it cuts.
//!
//! - Several boundary loops (a duct ring, a transition as a closed ring): every loop but the
//!   outer one that could not lie flat as a hole gets the shortest edge path (Dijkstra on 3D edge
//!   lengths) from it to another loop. A loop is a hole that may stay when its total geodesic
//!   turning `Σ (π − Σθ)` over its vertices is within [`HOLE_TURNING_TOLERANCE`] of `−2π`, the
//!   turning of a hole in a flat sheet; the outer loop is the one that turns most.
//! - A closed surface is first opened by the caller along its curvature cut graph or its
//!   bisector (`cut_graph`); what follows is the fallback when neither gives a graph.
//! - A closed surface without handles (genus 0): the shortest path between two far-apart
//!   vertices (the vertex farthest from vertex 0, and the vertex farthest from that) opens it to a
//!   disk with a slit (a path of one edge goes on by one more edge: a one-edge slit duplicates no
//!   vertex and opens nothing). Corners where the surface concentrates its curvature (angle deficit at least
//!   [`CONE_ANGLE_DEFICIT`], like the corners of a box) are preferred as those two ends, and every
//!   further such corner is then joined to the opening by its shortest path, so the seams form a
//!   tree through the corners (a cut graph).
//! - Handles (genus > 0) of a closed surface are cut first by the caller along the tree–cotree
//!   cut graph (`cut_graph`); a surface with both handles and a boundary is refused with
//!   [`CutError::HigherGenus`].
//!
//! User seams ([`lay_polyline`]): each 3D point snaps to its nearest vertex and consecutive
//! vertices are joined by shortest edge paths through interior, unblocked vertices.

use std::f64::consts::{PI, TAU};

use glam::DVec3;

use super::errors::CutError;
use super::paths::{Adjacency, dijkstra};
use crate::mesh::FacetModel;

/// How far (radians) a loop's total geodesic turning may be from `−2π` for the loop to stay as a
/// hole without a seam: a quarter turn.
pub const HOLE_TURNING_TOLERANCE: f64 = PI / 2.0;
/// Smallest angle deficit `2π − Σθ` (radians) of a vertex of a closed surface that the seams of a
/// closed surface run through (45°: a box corner has 90°, a smooth sphere mesh a few degrees).
pub const CONE_ANGLE_DEFICIT: f64 = PI / 4.0;

/// Why a seam was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SeamKind {
    /// Given by the user.
    User,
    /// Joins two boundary loops (a ring).
    Ring,
    /// Opens a closed surface.
    Closed,
    /// Joins a corner of a closed surface to the seams made before.
    Corner,
    /// Part of the cut graph that opens the handles of a closed surface.
    Handle,
    /// Part of the tree through the curvature regions of a closed surface (its corners, rims
    /// and filleted corners; see `cut_graph::curvature_cut_graph`).
    Curvature,
    /// Part of the seam that halves a smooth closed surface along the bisector of its two
    /// farthest points (see `cut_graph::bisector_cut_graph`).
    Bisector,
    /// A plane section that cut the part into pieces (`--seams pieces`; see `pieces`).
    Section,
}

/// The next automatic seam to cut, or `None` when the model is a disk (one boundary loop, no
/// handles). `blocked[v]` marks vertices no seam may pass.
pub fn next_seam(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
    opened_closed_surface: bool,
) -> Result<Option<(SeamKind, Vec<u32>)>, CutError> {
    let loops = model.boundary_loops().len();
    let genus = genus(model);
    if genus > 0 {
        return Err(CutError::HigherGenus { genus });
    }
    if loops == 0 {
        return closed_surface_seam(model, adjacency, blocked).map(Some);
    }
    let corners = model.angle_deficits();
    if opened_closed_surface && let Some(path) = corner_seam(model, adjacency, blocked, &corners) {
        return Ok(Some((SeamKind::Corner, path)));
    }
    let Some(loop_index) = loop_needing_seam(model) else {
        return Ok(None);
    };
    ring_seam(model, adjacency, blocked, loop_index).map(|path| Some((SeamKind::Ring, path)))
}

/// Genus from the Euler characteristic `V − E + F = 2 − 2g − b`.
pub fn genus(model: &FacetModel) -> i64 {
    let euler =
        model.vertex_count() as i64 - model.edges().len() as i64 + model.triangle_count() as i64;
    (2 - euler - model.boundary_loops().len() as i64) / 2
}

/// An angle deficit (radians) at most this is flat: no plane of a section is laid through its
/// vertex, and no slit is left open at it when pieces are glued.
pub const FLAT_DEFICIT: f64 = 1e-6;

/// Total geodesic turning `Σ (π − Σθ)` of each boundary loop.
fn loop_turnings(model: &FacetModel) -> Vec<f64> {
    let sums = model.angle_sums();
    model
        .boundary_loops()
        .iter()
        .map(|ring| ring.iter().map(|&v| PI - sums[v as usize]).sum())
        .collect()
}

/// The first loop, other than the one that turns most, that cannot stay a hole.
fn loop_needing_seam(model: &FacetModel) -> Option<usize> {
    if model.boundary_loops().len() < 2 {
        return None;
    }
    let turnings = loop_turnings(model);
    let outer = outer_loop(&turnings)?;
    (0..turnings.len()).find(|&i| i != outer && (turnings[i] + TAU).abs() > HOLE_TURNING_TOLERANCE)
}

/// The loops that stay holes when the model is opened to a disk: every loop, other than the one
/// that turns most, whose geodesic turning is −2π (a hole in a flat region).
pub fn hole_loops(model: &FacetModel) -> Vec<usize> {
    if model.boundary_loops().len() < 2 {
        return Vec::new();
    }
    let turnings = loop_turnings(model);
    let outer = outer_loop(&turnings);
    (0..turnings.len())
        .filter(|&i| Some(i) != outer && (turnings[i] + TAU).abs() <= HOLE_TURNING_TOLERANCE)
        .collect()
}

/// The loop that turns most (the first of equals).
fn outer_loop(turnings: &[f64]) -> Option<usize> {
    (0..turnings.len()).max_by(|&a, &b| turnings[a].total_cmp(&turnings[b]).then(b.cmp(&a)))
}

/// Shortest path from loop `loop_index` to any other loop through interior, unblocked vertices.
fn ring_seam(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
    loop_index: usize,
) -> Result<Vec<u32>, CutError> {
    let mut loop_of = vec![usize::MAX; model.vertex_count()];
    for (i, ring) in model.boundary_loops().iter().enumerate() {
        for &v in ring {
            loop_of[v as usize] = i;
        }
    }
    let sources: Vec<u32> = model.boundary_loops()[loop_index]
        .iter()
        .copied()
        .filter(|&v| !blocked[v as usize])
        .collect();
    let other_loop =
        |v: u32| loop_of[v as usize] != usize::MAX && loop_of[v as usize] != loop_index;
    let passable =
        |v: u32| !blocked[v as usize] && (loop_of[v as usize] == usize::MAX || other_loop(v));
    let (paths, reached) = dijkstra(model, adjacency, &sources, passable, other_loop);
    reached
        .and_then(|target| paths.path_to(target))
        .ok_or(CutError::NoSeam)
}

/// The first seam of a closed surface: between the two corners farthest apart, or between two
/// far-apart vertices when it has fewer than two corners.
fn closed_surface_seam(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
) -> Result<(SeamKind, Vec<u32>), CutError> {
    let deficits = model.angle_deficits();
    let corners: Vec<u32> = (0..model.vertex_count() as u32)
        .filter(|&v| deficits[v as usize] >= CONE_ANGLE_DEFICIT && !blocked[v as usize])
        .collect();
    let candidates: Vec<u32> = if corners.len() >= 2 {
        corners
    } else {
        (0..model.vertex_count() as u32)
            .filter(|&v| !blocked[v as usize])
            .collect()
    };
    let passable = |v: u32| !blocked[v as usize];
    let start = candidates.first().copied().ok_or(CutError::NoSeam)?;
    let first = farthest_of(model, adjacency, start, &candidates, &passable);
    let second = farthest_of(model, adjacency, first, &candidates, &passable);
    let (paths, _) = dijkstra(model, adjacency, &[first], passable, |v| v == second);
    let mut path = paths.path_to(second).ok_or(CutError::NoSeam)?;
    if path.len() == 2 {
        // A slit of one edge cannot open a closed mesh (no vertex is duplicated): go on to the
        // neighbour of largest deficit.
        let next = adjacency
            .neighbours(second)
            .iter()
            .map(|&(w, _)| w)
            .filter(|&w| w != first && !blocked[w as usize])
            .max_by(|&a, &b| {
                deficits[a as usize]
                    .total_cmp(&deficits[b as usize])
                    .then(b.cmp(&a))
            })
            .ok_or(CutError::NoSeam)?;
        path.push(next);
    }
    if path.len() < 3 {
        return Err(CutError::NoSeam);
    }
    Ok((SeamKind::Closed, path))
}

/// The candidate farthest (along edges) from `start`; ties go to the lower index.
fn farthest_of(
    model: &FacetModel,
    adjacency: &Adjacency,
    start: u32,
    candidates: &[u32],
    passable: &impl Fn(u32) -> bool,
) -> u32 {
    let (paths, _) = dijkstra(model, adjacency, &[start], passable, |_| false);
    candidates
        .iter()
        .copied()
        .filter(|&v| paths.distances[v as usize].is_finite())
        .max_by(|&a, &b| {
            paths.distances[a as usize]
                .total_cmp(&paths.distances[b as usize])
                .then(b.cmp(&a))
        })
        .unwrap_or(start)
}

/// A path from the interior corner of largest deficit to the boundary (the seams cut so far), if
/// a corner is left.
fn corner_seam(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
    deficits: &[f64],
) -> Option<Vec<u32>> {
    let on_boundary = model.boundary_flags();
    let corner = (0..model.vertex_count() as u32)
        .filter(|&v| deficits[v as usize] >= CONE_ANGLE_DEFICIT && !blocked[v as usize])
        .max_by(|&a, &b| {
            deficits[a as usize]
                .total_cmp(&deficits[b as usize])
                .then(b.cmp(&a))
        })?;
    let passable = |v: u32| !blocked[v as usize];
    let (paths, reached) = dijkstra(model, adjacency, &[corner], passable, |v| {
        on_boundary[v as usize]
    });
    paths.path_to(reached?)
}

/// Lays a user polyline on the mesh: points snap to their nearest vertices, joined by shortest
/// paths through interior, unblocked vertices (the ends may be on the boundary). `seam` is the
/// seam's index, for errors.
pub fn lay_polyline(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
    points: &[DVec3],
    seam: usize,
) -> Result<Vec<u32>, CutError> {
    if points.len() < 2 {
        return Err(CutError::SeamTooShort {
            seam,
            points: points.len(),
        });
    }
    let snapped: Vec<u32> = points
        .iter()
        .map(|&p| nearest_vertex(model, p, |_| true).unwrap_or(0))
        .collect();
    let path =
        join_vertices(model, adjacency, blocked, &snapped[..1], &snapped[1..]).map_err(|from| {
            CutError::SeamNotLaid {
                seam,
                from,
                to: from + 1,
            }
        })?;
    if path.len() < 2 {
        return Err(CutError::SeamTooShort { seam, points: 1 });
    }
    Ok(path)
}

/// Joins a path from one of the vertices `from` through the vertices `to`, in order, by shortest
/// paths through interior, unblocked vertices not already on the path (the ends of each stretch
/// may be on the boundary; a vertex equal to the one before is skipped): the vertex path, or the
/// index of the first stretch that cannot be laid.
pub fn join_vertices(
    model: &FacetModel,
    adjacency: &Adjacency,
    blocked: &[bool],
    from: &[u32],
    to: &[u32],
) -> Result<Vec<u32>, usize> {
    let on_boundary = model.boundary_flags();
    let mut path: Vec<u32> = Vec::new();
    for (i, &target) in to.iter().enumerate() {
        let sources = match path.last() {
            Some(&last) => vec![last],
            None => from.to_vec(),
        };
        if sources == [target] {
            continue;
        }
        let passable = |v: u32| {
            v == target || (!blocked[v as usize] && !on_boundary[v as usize] && !path.contains(&v))
        };
        let (paths, _) = dijkstra(model, adjacency, &sources, passable, |v| v == target);
        let stretch = paths.path_to(target).ok_or(i)?;
        let skip = usize::from(!path.is_empty());
        path.extend_from_slice(&stretch[skip..]);
    }
    Ok(path)
}

/// The vertex nearest to `point` among those `eligible` (the lowest index among equals).
pub fn nearest_vertex(
    model: &FacetModel,
    point: DVec3,
    eligible: impl Fn(u32) -> bool,
) -> Option<u32> {
    model
        .positions()
        .iter()
        .enumerate()
        .filter(|&(v, _)| eligible(v as u32))
        .min_by(|(_, a), (_, b)| {
            a.distance_squared(point)
                .total_cmp(&b.distance_squared(point))
        })
        .map(|(v, _)| v as u32)
}

#[cfg(test)]
mod tests {
    use crate::cut::seam::*;
    use crate::mesh::{TriangleSoup, validate};

    /// A band of `segments` quads around the z axis between two circles: `(radius, z)` inner and
    /// outer. A flat washer when both z are equal, a cylinder when both radii are.
    fn band(inner: (f64, f64), outer: (f64, f64), segments: u32) -> FacetModel {
        let mut positions = Vec::new();
        for &(radius, z) in &[inner, outer] {
            for i in 0..segments {
                let angle = TAU * i as f64 / segments as f64;
                positions.push(DVec3::new(radius * angle.cos(), radius * angle.sin(), z));
            }
        }
        let mut triangles = Vec::new();
        for i in 0..segments {
            let next = (i + 1) % segments;
            let (a, b, c, d) = (i, next, segments + next, segments + i);
            triangles.push([a, d, c]);
            triangles.push([a, c, b]);
        }
        let soup = TriangleSoup::new(positions, triangles);
        validate(&soup).expect("valid band").components.remove(0)
    }

    #[test]
    fn a_flat_washer_keeps_its_hole() {
        let washer = band((50.0, 0.0), (100.0, 0.0), 24);
        assert_eq!(genus(&washer), 0);
        assert_eq!(loop_needing_seam(&washer), None);
    }

    #[test]
    fn a_cylinder_ring_gets_one_seam_across() {
        let ring = band((50.0, 0.0), (50.0, 80.0), 24);
        let adjacency = Adjacency::new(&ring);
        let blocked = vec![false; ring.vertex_count()];
        let (kind, path) = next_seam(&ring, &adjacency, &blocked, false)
            .expect("no error")
            .expect("a seam is needed");
        assert_eq!(kind, SeamKind::Ring);
        // One straight edge from one rim to the other.
        assert_eq!(path.len(), 2);
        let [a, b] = [path[0], path[1]].map(|v| ring.positions()[v as usize]);
        assert!((a.distance(b) - 80.0).abs() < 1e-9);
    }

    #[test]
    fn a_seam_avoids_blocked_vertices() {
        let ring = band((50.0, 0.0), (50.0, 80.0), 24);
        let adjacency = Adjacency::new(&ring);
        let blocked = vec![true; ring.vertex_count()];
        assert_eq!(
            next_seam(&ring, &adjacency, &blocked, false),
            Err(CutError::NoSeam)
        );
    }
}
