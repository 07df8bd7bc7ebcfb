//! Trimmed patches meshed by constrained Delaunay refinement in the parameter domain (spade).
//!
//! Input: a [`PatchSurface`] (a plane or a NURBS patch with trim loops in `(u, v)`), fold-line
//! polylines in the same domain, a target edge length `mesh_size` and a chord tolerance (part
//! units). Output: a [`FaceMesh`] whose triangles are counter-clockwise in `(u, v)` (so their
//! normals follow `∂S/∂u × ∂S/∂v`) and whose fold edges follow the fold polylines exactly.
//!
//! Method: the domain is scaled by the surface's mean speeds `|∂S/∂u|`, `|∂S/∂v|` so that lengths
//! in the scaled domain approximate lengths on the surface; the trim loops and fold polylines
//! are split to the mesh size and inserted as constraint edges; spade's Ruppert-Chew refinement
//! then bounds the smallest angle ([`MINIMUM_ANGLE_DEGREES`]) and the triangle area (that of an
//! equilateral triangle of side `mesh_size`). Triangles whose centroid lies farther than the
//! chord tolerance from the surface get a Steiner point at the centroid, and refinement runs
//! again, a bounded number of rounds. Preconditions: loops simple and nested (checked when the
//! part is built).

use glam::{DVec2, DVec3};
use spade::handles::FixedVertexHandle;
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};

use super::crossings::with_crossings;
use super::face_mesh::FaceMesh;
use super::options::TessellateError;
use crate::cad::{PatchSurface, pieces_for_length};
use crate::geometry::tolerance::{ON_POLYLINE_RATIO, SLIVER_AREA_RATIO};
use crate::geometry::{bounding_box, distance_to_segment, inside};

/// The smallest triangle angle refinement aims for, degrees.
pub const MINIMUM_ANGLE_DEGREES: f64 = 25.0;
/// Rounds of Steiner points for the chord tolerance.
pub const CHORD_ROUNDS: usize = 6;
/// Samples per side of the grid on which the mean surface speeds are measured.
const SPEED_SAMPLES: usize = 9;
/// Sub-samples of a boundary segment when its length on the surface is measured.
const LENGTH_SAMPLES: usize = 8;
/// The guard box around a triangulation is this many mesh sizes away from it.
const GUARD_MARGIN: f64 = 2.0;
/// Refinement may add at most this many vertices per expected triangle of the patch.
const VERTEX_BUDGET_FACTOR: f64 = 20.0;

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// The map between the parameter domain and the scaled domain the triangulation works in.
#[derive(Debug, Clone, Copy)]
struct DomainScale(DVec2);

impl DomainScale {
    fn scaled(&self, parameters: DVec2) -> DVec2 {
        parameters * self.0
    }

    fn parameters(&self, scaled: DVec2) -> DVec2 {
        scaled / self.0
    }
}

/// Meshes a trimmed patch; `fold_lines` are `(fold line index, polyline)` in the domain.
pub fn mesh_patch(
    patch: &PatchSurface,
    fold_lines: &[(u32, Vec<DVec2>)],
    mesh_size: f64,
    chord: f64,
) -> Result<FaceMesh, TessellateError> {
    mesh_patch_as(patch, fold_lines, mesh_size, chord, Refinement::Full)
}

/// How far a patch's triangulation is refined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refinement {
    /// To the mesh size and the minimum angle, then to the chord.
    Full,
    /// To the chord only: the boundary's constrained Delaunay triangulation, with Steiner points
    /// only where a triangle strays farther than the chord from the surface (a plane gets none).
    /// For an exact unfold, which needs the boundary and points on the surface, not well-shaped
    /// triangles.
    ChordOnly,
}

/// Meshes a trimmed patch with the given refinement (see [`mesh_patch`]).
pub fn mesh_patch_as(
    patch: &PatchSurface,
    fold_lines: &[(u32, Vec<DVec2>)],
    mesh_size: f64,
    chord: f64,
    refinement: Refinement,
) -> Result<FaceMesh, TessellateError> {
    let refined = refinement == Refinement::Full;
    let scale = domain_scale(patch)?;
    let mut cdt = Cdt::new();
    let loops = std::iter::once(&patch.outer).chain(&patch.holes);
    for boundary in loops {
        let closed: Vec<DVec2> = boundary.iter().chain(boundary.first()).copied().collect();
        insert_polyline(
            &mut cdt,
            patch,
            scale,
            &closed,
            mesh_size,
            Crossings::Refused,
        )?;
    }
    let mut fold_polylines = Vec::new();
    for (line, points) in &with_crossings(fold_lines) {
        insert_polyline(&mut cdt, patch, scale, points, mesh_size, Crossings::Split)?;
        let scaled: Vec<DVec2> = points.iter().map(|&p| scale.scaled(p)).collect();
        fold_polylines.push((*line, scaled));
    }
    let expected_triangles =
        4.0 * patch_area_estimate(&cdt) / (3f64.sqrt() * mesh_size * mesh_size);
    if !fold_lines.is_empty() {
        surround_with_guard_box(&mut cdt, mesh_size)?;
    }
    let budget = (VERTEX_BUDGET_FACTOR * expected_triangles.max(1.0)) as usize;
    // Spade tells inner from outer faces by the parity of constraint edges crossed, which an
    // interior fold polyline would flip: with fold lines the whole hull is refined and faces
    // are kept by a point-in-domain test of their centroids.
    let domain = ScaledDomain::new(patch, scale);
    let exclude_outer = fold_lines.is_empty();
    if refined {
        refine(&mut cdt, mesh_size, budget, exclude_outer);
    }
    for _ in 0..CHORD_ROUNDS {
        let steiner = chord_violations(&cdt, &domain, patch, scale, chord);
        if steiner.is_empty() {
            break;
        }
        for point in steiner {
            insert_point(&mut cdt, point)?;
        }
        if refined {
            refine(&mut cdt, mesh_size, budget, exclude_outer);
        }
    }
    Ok(extract_mesh(
        &cdt,
        &domain,
        patch,
        scale,
        &fold_polylines,
        mesh_size,
    ))
}

/// The trimmed domain in scaled coordinates, for telling inner triangles from outer ones.
struct ScaledDomain {
    outer: Vec<DVec2>,
    holes: Vec<Vec<DVec2>>,
}

impl ScaledDomain {
    fn new(patch: &PatchSurface, scale: DomainScale) -> Self {
        let scaled = |points: &Vec<DVec2>| points.iter().map(|&p| scale.scaled(p)).collect();
        Self {
            outer: scaled(&patch.outer),
            holes: patch.holes.iter().map(scaled).collect(),
        }
    }

    /// True when the face with these corners lies in the domain (its centroid does).
    fn contains_face(&self, corners: [DVec2; 3]) -> bool {
        let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
        inside(centroid, &self.outer) && !self.holes.iter().any(|h| inside(centroid, h))
    }

    /// For each inner face (by index), whether it lies in the domain (see [`classify_regions`]).
    fn classify(&self, cdt: &Cdt) -> Vec<bool> {
        classify_regions(cdt, |corners| self.contains_face(corners))
    }
}

/// For each inner face of `cdt` (by index), whether it lies in the region `contains` tells.
/// Faces are grouped into regions that constraint edges bound, and each region is judged by its
/// largest face, so a sliver along a boundary goes with its neighbours whatever its rounded
/// centroid says.
pub(super) fn classify_regions(cdt: &Cdt, contains: impl Fn([DVec2; 3]) -> bool) -> Vec<bool> {
    let size = cdt
        .inner_faces()
        .map(|f| f.fix().index() + 1)
        .max()
        .unwrap_or(0);
    let mut region = vec![usize::MAX; size];
    let mut region_inside = Vec::new();
    for seed in cdt.inner_faces() {
        if region[seed.fix().index()] != usize::MAX {
            continue;
        }
        let label = region_inside.len();
        region[seed.fix().index()] = label;
        let mut stack = vec![seed];
        let mut largest = (seed.area(), face_corners(seed));
        while let Some(face) = stack.pop() {
            if face.area() > largest.0 {
                largest = (face.area(), face_corners(face));
            }
            for edge in face.adjacent_edges() {
                if cdt.is_constraint_edge(edge.as_undirected().fix()) {
                    continue;
                }
                if let Some(next) = edge.rev().face().as_inner()
                    && region[next.fix().index()] == usize::MAX
                {
                    region[next.fix().index()] = label;
                    stack.push(next);
                }
            }
        }
        region_inside.push(contains(largest.1));
    }
    region
        .iter()
        .map(|&label| label != usize::MAX && region_inside[label])
        .collect()
}

fn is_degenerate_ear(cdt: &Cdt, face: FaceHandle<'_>, positions: &[DVec3]) -> bool {
    let [a, b, c] = face.vertices().map(|v| positions[v.fix().index()]);
    let longest = a
        .distance_squared(b)
        .max(b.distance_squared(c))
        .max(c.distance_squared(a));
    let area = 0.5 * (b - a).cross(c - a).length();
    let constrained = face
        .adjacent_edges()
        .iter()
        .filter(|edge| cdt.is_constraint_edge(edge.as_undirected().fix()))
        .count();
    area < SLIVER_AREA_RATIO * longest && constrained >= 2
}

type FaceHandle<'a> = spade::handles::FaceHandle<
    'a,
    spade::handles::InnerTag,
    Point2<f64>,
    (),
    spade::CdtEdge<()>,
    (),
>;

fn face_corners(face: FaceHandle<'_>) -> [DVec2; 3] {
    face.vertices().map(|v| {
        let p = v.position();
        DVec2::new(p.x, p.y)
    })
}

/// Mean speeds `|∂S/∂u|`, `|∂S/∂v|` over the outer loop's bounding box.
fn domain_scale(patch: &PatchSurface) -> Result<DomainScale, TessellateError> {
    let (low, high) = bounding_box(&patch.outer);
    let mut sum = DVec2::ZERO;
    for i in 0..SPEED_SAMPLES {
        for j in 0..SPEED_SAMPLES {
            let t = DVec2::new(i as f64, j as f64) / (SPEED_SAMPLES - 1) as f64;
            let (du, dv) = patch.geometry.derivatives(low + (high - low) * t);
            sum += DVec2::new(du.length(), dv.length());
        }
    }
    let mean = sum / (SPEED_SAMPLES * SPEED_SAMPLES) as f64;
    if !(mean.x > 0.0 && mean.y > 0.0 && mean.is_finite()) {
        return Err(TessellateError::DegenerateSurface);
    }
    Ok(DomainScale(mean))
}

/// Inserts a domain point. A coordinate whose magnitude is below spade's smallest
/// ([`spade::MIN_ALLOWED_VALUE`], 2⁻¹⁴²: exporters write parameters such as 1e-50 for 0) is
/// taken as zero, which spade accepts, instead of refusing the point.
pub(super) fn insert_point(
    cdt: &mut Cdt,
    point: DVec2,
) -> Result<FixedVertexHandle, TessellateError> {
    cdt.insert(spade::mitigate_underflow(Point2::new(point.x, point.y)))
        .map_err(|_| TessellateError::BadParameterPoint {
            u: point.x,
            v: point.y,
        })
}

/// What a polyline's constraint edges do where they cross earlier ones.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Crossings {
    /// An error (trim loops must not cross).
    Refused,
    /// Both are split at the crossing, which becomes a vertex of both (fold polylines).
    Split,
}

/// Inserts a polyline (parameter domain) split to the mesh size as constraint edges.
fn insert_polyline(
    cdt: &mut Cdt,
    patch: &PatchSurface,
    scale: DomainScale,
    points: &[DVec2],
    mesh_size: f64,
    crossings: Crossings,
) -> Result<(), TessellateError> {
    for pair in points.windows(2) {
        let (from, to) = (pair[0], pair[1]);
        let length = surface_length(patch, from, to);
        let pieces = pieces_for_length(length, mesh_size);
        let mut previous = insert_point(cdt, scale.scaled(from))?;
        for k in 1..=pieces {
            let point = from.lerp(to, k as f64 / pieces as f64);
            let next = insert_point(cdt, scale.scaled(point))?;
            let added = match crossings {
                _ if previous == next => true,
                Crossings::Refused => !cdt.try_add_constraint(previous, next).is_empty(),
                Crossings::Split => !cdt
                    .add_constraint_and_split(previous, next, |p| p)
                    .is_empty(),
            };
            if !added {
                return Err(TessellateError::CrossingConstraints {
                    u: point.x,
                    v: point.y,
                });
            }
            previous = next;
        }
    }
    Ok(())
}

/// Adds the corners of a box around everything inserted so far. The domain's boundary then is
/// no hull edge: refinement would split a hull edge, and one between boundary vertices that are
/// collinear but for round-off would add vertices without end in the sliver it leaves.
pub(super) fn surround_with_guard_box(
    cdt: &mut Cdt,
    mesh_size: f64,
) -> Result<(), TessellateError> {
    let (low, high) =
        cdt.vertices()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(low, high), v| {
                let p = DVec2::new(v.position().x, v.position().y);
                (low.min(p), high.max(p))
            });
    let margin = GUARD_MARGIN * mesh_size;
    let (low, high) = (low - margin, high + margin);
    for corner in [
        low,
        DVec2::new(high.x, low.y),
        high,
        DVec2::new(low.x, high.y),
    ] {
        insert_point(cdt, corner)?;
    }
    Ok(())
}

/// Length on the surface of the straight parameter segment `from`-`to`.
fn surface_length(patch: &PatchSurface, from: DVec2, to: DVec2) -> f64 {
    (0..LENGTH_SAMPLES)
        .map(|k| {
            let a = from.lerp(to, k as f64 / LENGTH_SAMPLES as f64);
            let b = from.lerp(to, (k + 1) as f64 / LENGTH_SAMPLES as f64);
            patch.geometry.point(a).distance(patch.geometry.point(b))
        })
        .sum()
}

/// Area of the triangulated convex hull in the scaled domain: an upper bound of the patch's.
fn patch_area_estimate(cdt: &Cdt) -> f64 {
    cdt.inner_faces().map(|face| face.area()).sum()
}

/// Refines to the angle limit and the area of an equilateral triangle of side `mesh_size`.
pub(super) fn refine(cdt: &mut Cdt, mesh_size: f64, budget: usize, exclude_outer: bool) {
    let max_area = 3f64.sqrt() / 4.0 * mesh_size * mesh_size;
    let parameters = RefinementParameters::<f64>::new()
        .keep_constraint_edges()
        .exclude_outer_faces(exclude_outer)
        .with_angle_limit(AngleLimit::from_deg(MINIMUM_ANGLE_DEGREES))
        .with_max_allowed_area(max_area)
        .with_max_additional_vertices(budget);
    cdt.refine(parameters);
}

/// Centroids (scaled domain) of inner triangles farther than `chord` from the surface.
fn chord_violations(
    cdt: &Cdt,
    domain: &ScaledDomain,
    patch: &PatchSurface,
    scale: DomainScale,
    chord: f64,
) -> Vec<DVec2> {
    let inside = domain.classify(cdt);
    cdt.inner_faces()
        .filter(|face| inside[face.fix().index()])
        .map(face_corners)
        .filter_map(|corners| {
            let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
            let flat = corners
                .iter()
                .map(|&c| patch.geometry.point(scale.parameters(c)))
                .sum::<DVec3>()
                / 3.0;
            let on_surface = patch.geometry.point(scale.parameters(centroid));
            (on_surface.distance(flat) > chord).then_some(centroid)
        })
        .collect()
}

fn extract_mesh(
    cdt: &Cdt,
    domain: &ScaledDomain,
    patch: &PatchSurface,
    scale: DomainScale,
    fold_polylines: &[(u32, Vec<DVec2>)],
    mesh_size: f64,
) -> FaceMesh {
    let mut mesh = FaceMesh::default();
    for vertex in cdt.vertices() {
        let p = vertex.position();
        let parameters = scale.parameters(DVec2::new(p.x, p.y));
        mesh.positions.push(patch.geometry.point(parameters));
        mesh.parameters.push(parameters);
    }
    let inside = domain.classify(cdt);
    mesh.triangles = cdt
        .inner_faces()
        .filter(|face| {
            inside[face.fix().index()] && !is_degenerate_ear(cdt, *face, &mesh.positions)
        })
        .map(|face| face.vertices().map(|v| v.fix().index() as u32))
        .collect();
    let tolerance = ON_POLYLINE_RATIO * mesh_size.max(1.0);
    for edge in cdt.undirected_edges() {
        if !cdt.is_constraint_edge(edge.fix()) {
            continue;
        }
        let [a, b] = edge.vertices().map(|v| {
            let p = v.position();
            DVec2::new(p.x, p.y)
        });
        let midpoint = (a + b) * 0.5;
        let on = |polyline: &[DVec2], point: DVec2| {
            polyline
                .windows(2)
                .any(|s| distance_to_segment(point, s[0], s[1]) <= tolerance)
        };
        for (line, polyline) in fold_polylines {
            if on(polyline, a) && on(polyline, b) && on(polyline, midpoint) {
                let [va, vb] = edge.vertices().map(|v| v.fix().index() as u32);
                mesh.fold_edges.push(([va, vb], *line));
            }
        }
    }
    mesh
}
