//! Planning a large part's cuts on a coarse remesh (issue 13, "Scale"): every step of the cut
//! loop cuts and re-flattens the part for each of its candidates, which on a part of 100k
//! triangles is a second or more each; the same crest lines show on a coarse mesh of the same
//! surface, where a step costs a few milliseconds.
//!
//! Input: the opened part (a disk) and its first pattern, over tolerance, with more than
//! [`PLAN_ABOVE_TRIANGLES`] triangles, uniform stiffness, no fold line and rest lengths equal to
//! its 3D lengths. Output ([`Planned`]): the part cut along the planned cuts and re-flattened,
//! for the cut loop to go on from; or, when the plan ended short of the tolerance (no cut
//! lowered the remesh's error further, or the cut budget was spent), the part cut along the
//! planned cuts where they give it a valid pattern of lower error, and left there: the same
//! search on the part itself ended where the plan did, and took 9-35 s to (`--seams whole` on
//! the README's real meshes: the spot head, bimba, armadillo, cow head and Hencky all ended with
//! no cut); or nothing to go by, when the remesh cannot be made, the plan runs out of time, or
//! its cuts do not give the part a valid pattern of lower error (the cut loop then plans on the
//! part itself, as for a small part).
//!
//! Remesh: the pattern is a valid flattening, so its plane is a parameter domain of the surface.
//! The pattern's outline is sampled at the coarse spacing (outline vertices of the part, so the
//! remesh's boundary lies on the part's), its interior meshed by constrained Delaunay refinement
//! (spade) to the spacing [`PLAN_TRIANGLES`] sets, and each new vertex placed on the surface
//! where the part's triangle that holds it in the pattern maps it. The remesh is flattened from
//! its own coordinates and cut by the cut loop to the tolerance. A coarse mesh measures a curved
//! surface's errors a little high, so the fine part cut along the whole plan meets the
//! tolerance with room to spare (0.90 % on the 20k hemisphere, 0.93 % on the 100k one): the plan
//! over-cuts.
//!
//! Transfer: each planned cut (a 3D polyline on the remesh) is laid on the part: its points snap
//! to the nearest vertices (the first to the boundary, or an earlier cut's side, when it started
//! there), joined by shortest edge paths, and the path is cut along its geodesic straightening
//! ([`smooth_cut`]), as the loop cuts; a cut whose straightening would touch the boundary, or
//! that starts on a cut left out, is left out. The part cut along the planned cuts is flattened afresh,
//! as a part is first flattened. A plan that met the tolerance is laid first with each cut
//! shortened by [`PLAN_TRIM`] at its inner end, and the cut loop goes on from there on the part
//! while it is over tolerance (extensions from the laid cuts' tips, or new cuts): the part
//! finishes the cuts at its own, lower, error. Should that not bring it within tolerance, the
//! whole plan is laid and the loop goes on from there.

use glam::{DVec2, DVec3};
use spade::handles::FixedVertexHandle;
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};

use super::crest_cuts::{Cutting, Plan, cut_along_crest_lines};
use super::errors::CutError;
use super::options::NoCutRegion;
use super::paths::{Adjacency, path_length};
use super::result::{Cut, CutFigures, CutStop};
use super::seam::{join_vertices, nearest_vertex};
use super::smooth_cut::{Straightened, smooth_cut};
use super::state::{CutState, point_key, polyline};
use super::trials::{is_better, uncuttable};
use crate::flatten::{Stiffness, flatten, flatten_from};
use crate::geometry::{
    barycentric, distance_to_segment, inside, polyline_prefix, segment_fraction, segments_intersect,
};
use crate::mesh::{FacetModel, NONE, TriangleSoup, validate};
use crate::progress::Progress;

/// Parts of more triangles than this plan their crest-line cuts on a coarse remesh.
pub const PLAN_ABOVE_TRIANGLES: usize = 6000;
/// The coarse remesh's spacing is the side of an equilateral triangle of the pattern's area
/// divided by this; Delaunay refinement to that spacing gives about 1.5 times as many triangles
/// (the 20k hemisphere's remesh has 2333). Fewer plan longer cuts (the fine pattern meets the
/// tolerance with room to spare: with 1000, 857 mm at 0.86 % on the 100k hemisphere, against
/// 791 mm at 0.93 %), more take longer (with 2000, 4.6 s instead of 2.9 s on the 20k one).
pub const PLAN_TRIANGLES: usize = 1500;
/// A plan that met the tolerance on its remesh is laid on the part with each cut shortened by
/// this fraction of its length, at its inner end; the cut loop then extends the cuts on the part
/// itself while it is over tolerance. The remesh measures a curved surface's errors a little
/// high, so the whole plan over-cuts: on the 100k hemisphere it met the tolerance at 0.93 % with
/// 791 mm of cuts, shortened by a tenth and extended it meets it with 729 mm (20k: 799 → 741 mm).
/// Shortened by 0.07 and 0.15 it took 751 and 749 mm (20k: 742 and 736 mm), by 0.15 and 0.2
/// 26 s and 25 s instead of 12 s on the 100k one (more extensions).
pub const PLAN_TRIM: f64 = 0.1;
/// An outline vertex where the pattern's outline turns by more than this (radians, 30°) is kept
/// in the remesh's outline whatever the spacing.
const CORNER_TURN: f64 = std::f64::consts::PI / 6.0;
/// Refinement may add at most this many vertices per planned triangle.
const REFINEMENT_BUDGET: usize = 4;
/// The smallest triangle angle refinement aims for, degrees.
const MINIMUM_ANGLE_DEGREES: f64 = 25.0;

/// What planning a part's cuts on its coarse remesh came to.
pub(super) enum Planned {
    /// The part cut along the planned cuts, re-flattened and cut on by the cut loop while it was
    /// over tolerance ([`cut_along_plan`]), with the loop's reason to stop.
    Cut(Box<Cutting>, CutStop),
    /// The plan ended short of the tolerance, for this reason (no cut lowered the remesh's
    /// error further, or the cut budget was spent): the same search on the part itself would end
    /// there too (see the module documentation). The part is left there: cut along the planned
    /// cuts when they give it a valid pattern of lower error (given here), else as it was.
    Short(Option<Box<Cutting>>, CutStop),
    /// No plan to go by: the remesh could not be made, the plan ran out of time, or its cuts,
    /// within the tolerance on the remesh, did not give the part a valid pattern of lower error
    /// (the cut loop then plans on the part itself, as for a small part).
    Nothing,
}

/// Plans the part's cuts on a coarse remesh and lays them on the part (see the module
/// documentation and [`Planned`]).
pub(super) fn plan_cuts(
    cutting: &Cutting,
    plan: &Plan<'_>,
    progress: &dyn Progress,
) -> Result<Planned, CutError> {
    let Some(remesh) = coarse_remesh(&cutting.state, &cutting.flattened.positions) else {
        return Ok(Planned::Nothing);
    };
    let flattened = flatten_from(
        &remesh.state.model,
        &remesh.state.stiffness,
        &remesh.start,
        plan.flatten_options,
    )?;
    let coarse = Cutting::uncut(remesh.state, flattened);
    let (coarse, stop) = cut_along_crest_lines(coarse, plan, "plan cuts", progress)?;
    let planned: Vec<Vec<DVec3>> = coarse.cuts.iter().map(|cut| cut.points.clone()).collect();
    Ok(match stop {
        CutStop::ToleranceMet => {
            match cut_along_plan(cutting, &planned, remesh.spacing, plan, progress)? {
                Some((cut, stop)) => Planned::Cut(Box::new(cut), stop),
                None => Planned::Nothing,
            }
        }
        CutStop::NoBetterCut | CutStop::CutBudget => {
            let laid = lay_planned_cuts(cutting, &planned, remesh.spacing, plan, progress)?;
            Planned::Short(laid.map(Box::new), stop)
        }
        CutStop::TimeLimit => Planned::Nothing,
    })
}

/// The part cut along a plan that met the tolerance on its remesh (`planned`: 3D polylines on
/// the remesh of spacing `spacing`) and cut on by the cut loop while it is over tolerance, with
/// the loop's reason to stop. The plan is laid with each cut shortened by [`PLAN_TRIM`] first;
/// when that cannot be laid or the loop does not bring it within tolerance, the whole plan is
/// laid. `None` when the whole plan cannot be laid either ([`lay_planned_cuts`]).
fn cut_along_plan(
    cutting: &Cutting,
    planned: &[Vec<DVec3>],
    spacing: f64,
    plan: &Plan<'_>,
    progress: &dyn Progress,
) -> Result<Option<(Cutting, CutStop)>, CutError> {
    let shortened: Vec<Vec<DVec3>> = planned
        .iter()
        .map(|points| polyline_prefix(points, 1.0 - PLAN_TRIM))
        .collect();
    if let Some(laid) = lay_planned_cuts(cutting, &shortened, spacing, plan, progress)? {
        let (cut, stop) = cut_along_crest_lines(laid, plan, "cut", progress)?;
        if matches!(stop, CutStop::ToleranceMet | CutStop::TimeLimit) {
            return Ok(Some((cut, stop)));
        }
    }
    let Some(laid) = lay_planned_cuts(cutting, planned, spacing, plan, progress)? else {
        return Ok(None);
    };
    cut_along_crest_lines(laid, plan, "cut", progress).map(Some)
}

/// The coarse remesh of a part, with its start pattern (its vertices' places in the part's
/// pattern) and its spacing (model units).
struct Remesh {
    state: CutState,
    start: Vec<DVec2>,
    spacing: f64,
}

/// The coarse remesh of the part whose pattern is `pattern` (see the module documentation), or
/// `None` when the part is not a disk of uniform stiffness, no fold line and rest lengths equal
/// to its 3D lengths, or its sampled outline crosses itself.
fn coarse_remesh(state: &CutState, pattern: &[DVec2]) -> Option<Remesh> {
    let model = &state.model;
    if !is_plain(state) {
        return None;
    }
    let [outline] = model.boundary_loops() else {
        return None;
    };
    let area: f64 = model
        .triangles()
        .iter()
        .map(|t| pattern_area(pattern, *t))
        .sum();
    let spacing = (4.0 * area / (3f64.sqrt() * PLAN_TRIANGLES as f64)).sqrt();
    let sampled = sample_outline(outline, pattern, spacing);
    let polygon: Vec<DVec2> = sampled.iter().map(|&v| pattern[v as usize]).collect();
    if polygon.len() < 3 || !is_simple(&polygon) {
        return None;
    }
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let handles: Vec<FixedVertexHandle> = polygon
        .iter()
        .map(|p| cdt.insert(Point2::new(p.x, p.y)).ok())
        .collect::<Option<_>>()?;
    // Two outline points at one place (spade keeps one vertex) cannot bound the remesh.
    if cdt.num_vertices() != handles.len() {
        return None;
    }
    for (k, &from) in handles.iter().enumerate() {
        let to = handles[(k + 1) % handles.len()];
        if cdt.try_add_constraint(from, to).is_empty() {
            return None;
        }
    }
    cdt.refine(
        RefinementParameters::<f64>::new()
            .keep_constraint_edges()
            .exclude_outer_faces(true)
            .with_angle_limit(AngleLimit::from_deg(MINIMUM_ANGLE_DEGREES))
            .with_max_allowed_area(3f64.sqrt() / 4.0 * spacing * spacing)
            .with_max_additional_vertices(REFINEMENT_BUDGET * PLAN_TRIANGLES),
    );
    let coordinates: Vec<DVec2> = cdt
        .vertices()
        .map(|v| DVec2::new(v.position().x, v.position().y))
        .collect();
    let locator = PatternLocator::new(state, pattern, outline);
    let mut positions: Vec<DVec3> = coordinates.iter().map(|&p| locator.point(p)).collect();
    for (&handle, &v) in handles.iter().zip(&sampled) {
        positions[handle.index()] = model.positions()[v as usize];
    }
    let triangles: Vec<[u32; 3]> = cdt
        .inner_faces()
        .map(|face| face.vertices().map(|v| v.fix().index() as u32))
        .filter(|t| {
            let centroid = t.iter().map(|&v| coordinates[v as usize]).sum::<DVec2>() / 3.0;
            inside(centroid, &polygon)
        })
        .collect();
    let mut validated = validate(&TriangleSoup::new(positions, triangles)).ok()?;
    if validated.components.len() != 1 {
        return None;
    }
    let model = validated.components.remove(0);
    let start = validated.soup_vertices[0]
        .iter()
        .map(|&v| coordinates[v as usize])
        .collect();
    let state = CutState {
        stiffness: Stiffness::uniform(&model),
        original_vertex: (0..model.vertex_count() as u32).collect(),
        model,
    };
    Some(Remesh {
        state,
        start,
        spacing,
    })
}

/// Whether a part's springs are those of its surface alone: no fold line, uniform stiffness,
/// rest lengths equal to the 3D lengths (a remesh of the surface has the same springs).
fn is_plain(state: &CutState) -> bool {
    let model = &state.model;
    let positions = model.positions();
    let no_fold_line = model.edge_fold_lines().iter().all(|&line| line == NONE);
    let uniform = state.stiffness.factors().iter().all(|&f| f == 1.0);
    let rest_is_3d = model
        .edges()
        .iter()
        .zip(model.rest_lengths())
        .all(|(&[a, b], &rest)| {
            let length = positions[a as usize].distance(positions[b as usize]);
            (rest - length).abs() <= 1e-9 * length.max(f64::MIN_POSITIVE)
        });
    no_fold_line && uniform && rest_is_3d
}

/// Signed area of a triangle in the pattern.
fn pattern_area(pattern: &[DVec2], [a, b, c]: [u32; 3]) -> f64 {
    let [a, b, c] = [a, b, c].map(|v| pattern[v as usize]);
    0.5 * (b - a).perp_dot(c - a)
}

/// The outline vertices the remesh keeps, in order: the first, then each at least `spacing`
/// along the outline (in the pattern) from the last kept, and every corner ([`CORNER_TURN`]); a
/// last one closer than half the spacing to the first is dropped unless it is a corner.
fn sample_outline(outline: &[u32], pattern: &[DVec2], spacing: f64) -> Vec<u32> {
    let count = outline.len();
    let at = |k: usize| pattern[outline[k % count] as usize];
    let is_corner = |k: usize| {
        let (before, here, after) = (at(k + count - 1), at(k), at(k + 1));
        (here - before).angle_to(after - here).abs() > CORNER_TURN
    };
    let mut kept = vec![0];
    let mut run = 0.0;
    for k in 1..count {
        run += at(k).distance(at(k - 1));
        if run >= spacing || is_corner(k) {
            kept.push(k);
            run = 0.0;
        }
    }
    let closing = at(count - 1).distance(at(0));
    if let Some(&last) = kept.last()
        && last != 0
        && run + closing < 0.5 * spacing
        && !is_corner(last)
    {
        kept.pop();
    }
    kept.iter().map(|&k| outline[k]).collect()
}

/// True when no two sides of the closed polygon meet but neighbours at their shared corner.
fn is_simple(polygon: &[DVec2]) -> bool {
    let count = polygon.len();
    let side = |k: usize| (polygon[k], polygon[(k + 1) % count]);
    (0..count).all(|i| {
        (i + 2..count).filter(|&j| (j + 1) % count != i).all(|j| {
            let ((p, q), (r, s)) = (side(i), side(j));
            !segments_intersect(p, q, r, s)
        })
    })
}

/// Finds where a point of the pattern's plane lies on the part: in the triangle that holds it in
/// the pattern (a grid of buckets over the pattern), or at the nearest point of the outline.
struct PatternLocator<'a> {
    state: &'a CutState,
    pattern: &'a [DVec2],
    outline: &'a [u32],
    low: DVec2,
    cell: f64,
    columns: usize,
    rows: usize,
    buckets: Vec<Vec<u32>>,
}

impl<'a> PatternLocator<'a> {
    fn new(state: &'a CutState, pattern: &'a [DVec2], outline: &'a [u32]) -> Self {
        let (low, high) = crate::geometry::bounding_box(pattern);
        let triangles = state.model.triangles();
        let side = (triangles.len() as f64).sqrt().ceil().max(1.0);
        let cell = ((high - low).max_element() / side).max(f64::MIN_POSITIVE);
        let columns = ((high.x - low.x) / cell) as usize + 1;
        let rows = ((high.y - low.y) / cell) as usize + 1;
        let mut locator = Self {
            state,
            pattern,
            outline,
            low,
            cell,
            columns,
            rows,
            buckets: vec![Vec::new(); columns * rows],
        };
        for (f, t) in triangles.iter().enumerate() {
            let corners = t.map(|v| pattern[v as usize]);
            let (x0, y0) = locator.cell_of(corners[0].min(corners[1]).min(corners[2]));
            let (x1, y1) = locator.cell_of(corners[0].max(corners[1]).max(corners[2]));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    locator.buckets[y * columns + x].push(f as u32);
                }
            }
        }
        locator
    }

    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let clamp = |value: f64, count: usize| (value.max(0.0) as usize).min(count - 1);
        let relative = (p - self.low) / self.cell;
        (
            clamp(relative.x, self.columns),
            clamp(relative.y, self.rows),
        )
    }

    /// The part's point at pattern point `p`.
    fn point(&self, p: DVec2) -> DVec3 {
        let (x, y) = self.cell_of(p);
        let model = &self.state.model;
        let holding = self.buckets[y * self.columns + x].iter().find_map(|&f| {
            let t = model.triangles()[f as usize];
            let weights = weights_inside(t.map(|v| self.pattern[v as usize]), p)?;
            Some(
                (0..3)
                    .map(|k| model.positions()[t[k] as usize] * weights[k])
                    .sum(),
            )
        });
        holding.unwrap_or_else(|| self.nearest_on_outline(p))
    }

    /// The part's point at the outline point nearest to pattern point `p`.
    fn nearest_on_outline(&self, p: DVec2) -> DVec3 {
        let count = self.outline.len();
        let (a, b) = (0..count)
            .map(|k| (self.outline[k], self.outline[(k + 1) % count]))
            .min_by(|&(a, b), &(c, d)| {
                let distance = |a: u32, b: u32| {
                    distance_to_segment(p, self.pattern[a as usize], self.pattern[b as usize])
                };
                distance(a, b).total_cmp(&distance(c, d))
            })
            .unwrap_or((self.outline[0], self.outline[0]));
        let t = segment_fraction(p, self.pattern[a as usize], self.pattern[b as usize]);
        let positions = self.state.model.positions();
        positions[a as usize].lerp(positions[b as usize], t)
    }
}

/// Barycentric weights of `p` in the triangle `corners`, when it lies in it (within rounding).
fn weights_inside(corners: [DVec2; 3], p: DVec2) -> Option<[f64; 3]> {
    let weights = barycentric(corners, p)?;
    weights.iter().all(|&w| w >= -1e-12).then_some(weights)
}

/// The part cut along the planned cuts (3D polylines on the remesh of spacing `spacing`) and
/// flattened afresh, as a part is first flattened (warm-started from the uncut pattern, whose cut
/// sides lie on each other, the solver stalls far from the minimum: the 20k hemisphere with 12
/// planned cuts stopped at 5 % `E_S`, overlapping); `None` when no cut can be laid or the
/// pattern is not valid with a lower error than the part's. A planned cut that cannot be laid
/// (its straightening would touch the boundary, or it starts on one that was not laid) is left
/// out: the loop goes on from the others (the FreeCAD quarter torus: 4 of 5 laid, within
/// tolerance).
fn lay_planned_cuts(
    cutting: &Cutting,
    planned: &[Vec<DVec3>],
    spacing: f64,
    plan: &Plan<'_>,
    progress: &dyn Progress,
) -> Result<Option<Cutting>, CutError> {
    let mut state = cutting.state.clone();
    let mut paths = Vec::new();
    for points in planned {
        if let Some((next, path)) = lay_cut(&state, points, spacing, plan.regions)? {
            state = next;
            paths.push(path);
        }
    }
    if paths.is_empty() {
        return Ok(None);
    }
    let flattened = flatten(
        &state.model,
        &state.stiffness,
        plan.flatten_options,
        progress,
    )?;
    let accuracy = &flattened.stats.accuracy;
    let valid = accuracy.flipped == 0 && !accuracy.overlap;
    if !valid || !is_better(accuracy, &cutting.flattened.stats.accuracy) {
        return Ok(None);
    }
    // The cuts were made together: each carries the figures of the pattern before them all
    // and after them all.
    let (before, after) = (
        CutFigures::of(&cutting.flattened),
        CutFigures::of(&flattened),
    );
    let cuts = paths
        .iter()
        .map(|path| Cut {
            points: polyline(&state.model, path),
            vertices: path
                .iter()
                .map(|&v| state.original_vertex[v as usize])
                .collect(),
            length: path_length(&state.model, path),
            before,
            after,
        })
        .collect();
    let tips = paths.iter().map(|path| path[path.len() - 1]).collect();
    Ok(Some(Cutting {
        uncut: Some(cutting.as_uncut()),
        state,
        flattened,
        cuts,
        tips,
    }))
}

/// The state cut along one planned cut (a 3D polyline) and the cut's vertex path in it (the
/// indices of a state's vertices hold in the states cut from it); `None` when the cut cannot be
/// laid or cut.
fn lay_cut(
    state: &CutState,
    points: &[DVec3],
    spacing: f64,
    regions: &[NoCutRegion],
) -> Result<Option<(CutState, Vec<u32>)>, CutError> {
    let model = &state.model;
    let blocked = state.blocked(regions);
    let Some(path) = edge_path(model, &blocked, points, spacing) else {
        return Ok(None);
    };
    let (cut, path) = match smooth_cut(state, &path, &blocked) {
        Straightened::Refused => return Ok(None),
        Straightened::AlongEdges => (state.cut_along(&path), path),
        Straightened::Smooth(smooth) => (smooth.state.cut_along(&smooth.path), smooth.path),
    };
    match cut {
        Ok((next, _)) => Ok(Some((next, path))),
        Err(error) if uncuttable(&error) => Ok(None),
        Err(error) => Err(error),
    }
}

/// An edge path of `model` along the polyline `points`: its points snapped to their nearest
/// vertices, joined by shortest paths. It starts at the boundary (the outline or an earlier
/// cut's side), from every copy of the boundary vertex nearest to the polyline's first point, so
/// that it enters the side it came from; `None` when no boundary vertex is within half the
/// remesh `spacing` of that point (the plan's cut started on a cut that was not laid, or inside),
/// or the path cannot be laid or passes a vertex twice.
fn edge_path(
    model: &FacetModel,
    blocked: &[bool],
    points: &[DVec3],
    spacing: f64,
) -> Option<Vec<u32>> {
    let on_boundary = model.boundary_flags();
    let open = |v: u32| !blocked[v as usize] && !on_boundary[v as usize];
    let (&first, rest) = points.split_first()?;
    let start = nearest_vertex(model, first, |v| {
        on_boundary[v as usize] && !blocked[v as usize]
    })
    .filter(|&v| model.positions()[v as usize].distance(first) <= 0.5 * spacing)?;
    let key = point_key(model.positions()[start as usize]);
    let sources: Vec<u32> = (0..model.vertex_count() as u32)
        .filter(|&w| on_boundary[w as usize] && point_key(model.positions()[w as usize]) == key)
        .collect();
    let mut snapped: Vec<u32> = Vec::new();
    for &point in rest {
        let v = nearest_vertex(model, point, open)?;
        if !snapped.contains(&v) && !sources.contains(&v) {
            snapped.push(v);
        }
    }
    let adjacency = Adjacency::new(model);
    let path = join_vertices(model, &adjacency, blocked, &sources, &snapped).ok()?;
    let mut distinct = path.clone();
    distinct.sort_unstable();
    distinct.dedup();
    (path.len() >= 2 && distinct.len() == path.len()).then_some(path)
}

#[cfg(test)]
mod tests {
    use crate::cut::coarse::*;
    use crate::cut::options::CutOptions;
    use crate::cut::straighten::tests::flat_grid;
    use crate::flatten::FlattenOptions;
    use crate::progress::NoProgress;

    const RADIUS: f64 = 100.0;

    /// The point at flat point `p` of a sheet rolled onto the cylinder of radius [`RADIUS`] whose
    /// axis is the line `x = 0, z = RADIUS`: `x` runs around it, `y` along it.
    fn rolled(p: DVec2) -> DVec3 {
        let angle = p.x / RADIUS;
        DVec3::new(RADIUS * angle.sin(), p.y, RADIUS * (1.0 - angle.cos()))
    }

    /// A 120 mm square sheet of 7200 triangles rolled onto the cylinder, and its exact
    /// development.
    fn rolled_sheet() -> (CutState, Vec<DVec2>) {
        let grid = flat_grid(60);
        let pattern: Vec<DVec2> = grid
            .positions()
            .iter()
            .map(|p| 2.0 * p.truncate())
            .collect();
        let soup = TriangleSoup::new(
            pattern.iter().map(|&p| rolled(p)).collect(),
            grid.triangles().to_vec(),
        );
        let model = validate(&soup).expect("valid sheet").components.remove(0);
        let state = CutState {
            stiffness: Stiffness::uniform(&model),
            original_vertex: (0..model.vertex_count() as u32).collect(),
            model,
        };
        (state, pattern)
    }

    #[test]
    fn the_remesh_of_a_rolled_sheet_lies_on_it_where_its_development_says() {
        let (state, pattern) = rolled_sheet();
        let remesh = coarse_remesh(&state, &pattern).expect("remeshed");
        let model = &remesh.state.model;
        let count = model.triangle_count();
        assert!(
            (PLAN_TRIANGLES..3 * PLAN_TRIANGLES).contains(&count),
            "{count} triangles"
        );
        assert_eq!(model.boundary_loops().len(), 1);
        // The sheet's facets stray from the cylinder by their sagitta, 0.005 mm.
        for (p, &flat) in model.positions().iter().zip(&remesh.start) {
            assert!(p.distance(rolled(flat)) < 0.01, "{p} from {flat}");
        }
        let area: f64 = (0..count).map(|f| model.triangle_area(f)).sum();
        assert!((area / (120.0 * 120.0) - 1.0).abs() < 1e-3, "area {area}");
        assert!(is_plain(&remesh.state));
    }

    /// The rolled sheet's square pressed onto a sphere of radius 60 mm instead (each flat point
    /// at its distance from the square's centre along the sphere's great circles): a cap of 81°
    /// at the square's corners.
    fn domed_sheet() -> CutState {
        const SPHERE_RADIUS: f64 = 60.0;
        let (state, pattern) = rolled_sheet();
        let positions: Vec<DVec3> = pattern
            .iter()
            .map(|&p| {
                let from_centre = p - DVec2::splat(60.0);
                let angle = from_centre.length() / SPHERE_RADIUS;
                let direction = from_centre.normalize_or_zero();
                let across = SPHERE_RADIUS * angle.sin();
                DVec3::new(
                    across * direction.x,
                    across * direction.y,
                    SPHERE_RADIUS * angle.cos(),
                )
            })
            .collect();
        let soup = TriangleSoup::new(positions, state.model.triangles().to_vec());
        let model = validate(&soup).expect("valid dome").components.remove(0);
        CutState {
            stiffness: Stiffness::uniform(&model),
            original_vertex: (0..model.vertex_count() as u32).collect(),
            model,
        }
    }

    #[test]
    fn a_plan_that_spends_its_cut_budget_short_of_the_tolerance_is_laid_and_ends_there() {
        let state = domed_sheet();
        let options = FlattenOptions::default();
        let flattened =
            flatten(&state.model, &state.stiffness, &options, &NoProgress).expect("flattened");
        let uncut_error = flattened.stats.accuracy.larger_error();
        assert!(uncut_error > 2.0 * options.tolerance, "{uncut_error}");
        let cutting = Cutting::uncut(state, flattened);
        let cut_options = CutOptions::default();
        let plan = Plan {
            max_cuts: 1,
            regions: &[],
            flatten_options: &options,
            options: &cut_options,
        };
        let planned = plan_cuts(&cutting, &plan, &NoProgress).expect("plan");
        let Planned::Short(Some(left), stop) = planned else {
            panic!("one cut leaves the dome over tolerance, and lowers its error ({uncut_error})");
        };
        assert_eq!(stop, CutStop::CutBudget);
        assert_eq!(left.cuts.len(), 1, "the planned cut, laid");
        let accuracy = left.flattened.stats.accuracy;
        assert!(accuracy.larger_error() < uncut_error, "{accuracy:?}");
        assert!(accuracy.flipped == 0 && !accuracy.overlap, "{accuracy:?}");
    }

    #[test]
    fn a_part_with_a_fold_line_or_stiffer_springs_is_not_remeshed() {
        let (mut state, pattern) = rolled_sheet();
        state.stiffness.raise_where(10.0, |edge| edge == 0);
        assert!(coarse_remesh(&state, &pattern).is_none());
    }

    #[test]
    fn the_sampled_outline_keeps_the_corners() {
        let (state, pattern) = rolled_sheet();
        let outline = &state.model.boundary_loops()[0];
        let kept = sample_outline(outline, &pattern, 9.0);
        let corners = [(0.0, 0.0), (120.0, 0.0), (120.0, 120.0), (0.0, 120.0)];
        for (x, y) in corners {
            let corner = DVec2::new(x, y);
            assert!(
                kept.iter().any(|&v| pattern[v as usize] == corner),
                "{corner}"
            );
        }
        // Outline vertices every 2 mm: one kept every 10 mm, and the corners.
        assert!((48..=52).contains(&kept.len()), "{} kept", kept.len());
        for k in 0..kept.len() {
            let next = kept[(k + 1) % kept.len()];
            let gap = pattern[kept[k] as usize].distance(pattern[next as usize]);
            assert!(gap <= 10.0 + 1e-9, "gap {gap}");
        }
    }

    #[test]
    fn a_bow_tie_is_not_simple() {
        let v = |x, y| DVec2::new(x, y);
        assert!(is_simple(&[v(0., 0.), v(1., 0.), v(1., 1.), v(0., 1.)]));
        assert!(!is_simple(&[v(0., 0.), v(1., 1.), v(1., 0.), v(0., 1.)]));
    }

    #[test]
    fn weights_inside_a_triangle_rebuild_the_point() {
        let corners = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let weights = weights_inside(corners, DVec2::new(0.25, 0.5)).expect("inside");
        assert!((weights[0] - 0.25).abs() < 1e-12 && (weights[2] - 0.5).abs() < 1e-12);
        assert!(weights_inside(corners, DVec2::new(1.0, 1.0)).is_none());
    }
}
