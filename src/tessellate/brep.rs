//! The faces of boundary-representation shells (STEP solids and open shells) meshed into one
//! welded triangle soup.
//!
//! Input: truck-stepio's compressed shells (file units) and the target edge length and chord
//! tolerance (file units). Output: a [`TriangleSoup`] whose `face_sources` number the faces in
//! order (so face boundaries are the edges between triangles of different sources), one manifold
//! surface where faces share edges.
//!
//! Method:
//! 1. Each face gets a mesh size: the target, or less where the face curves so much that the
//!    chord tolerance needs smaller triangles (`face_mesh_sizes`: `√(6 chord / κ)` for the
//!    face's largest principal curvature `κ`), so the refinement reaches the chord without
//!    late Steiner points near the boundary. Every edge is then sampled once (`sample_edge`):
//!    equal parameter steps, as many as keep each piece shorter than [`EDGE_PIECE_RATIO`] of the
//!    smaller mesh size of its faces and within the chord tolerance of the curve, the ends
//!    exactly at the edge's vertices; an edge ending at a cone's apex is graded toward it
//!    (`sample_toward_apex`). A face with no edge on a surface closed from pole to pole (a full
//!    sphere) is meshed as two caps ([`PoleToPole`]).
//! 2. Each face's boundary loops (its edges' samples, in loop order) are mapped into a domain in
//!    which lengths approximate surface lengths ([`super::face_domain`]: cones developed,
//!    cylinders unrolled, poles in polar coordinates, surfaces of revolution in Mercator
//!    coordinates, other surfaces in their own parameters, periodic parameters unwrapped).
//! 3. The trimmed domain is meshed by the patch mesher ([`super::patch::mesh_patch`]: spade's
//!    constrained Delaunay refinement to the mesh size, the chord and a 25° minimum angle, the
//!    boundary samples kept as constraint edges).
//! 4. Boundary vertices are snapped to their edge samples, so vertices of a shared edge are the
//!    same points on both faces (and on both sides of a closed face's seam), and vertices at the
//!    same position are welded: a closed cone's side face becomes a ring.
//! 5. Each face's triangles are oriented along the face's normal (its surface's normal, reversed
//!    when the face is), so a consistently oriented shell gives a consistently oriented soup.

use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::{Curve3D, Surface as StepSurface};
use truck_topology::compress::{CompressedFace, CompressedShell};

use super::face_domain::{BoundaryLoop, FaceSurface, PoleToPole, apex_curvature, face_domain};
use super::patch::mesh_patch;
use super::surface::{PatchGeometry, PatchSurface};
use crate::mesh::{DEGENERATE_AREA_RATIO, TriangleSoup};

/// A shell as truck-stepio converts it.
pub type StepShell = CompressedShell<Point3, Curve3D, StepSurface>;

/// Edge pieces are at most this fraction of the mesh size, so the patch mesher never splits a
/// boundary piece again (its length on the surface stays under the mesh size).
pub const EDGE_PIECE_RATIO: f64 = 0.8;
/// Probe samples per edge when the shells' size is measured.
const SIZE_SAMPLES: usize = 16;
/// At most this many pieces per edge (a runaway count means a broken curve).
const MAX_EDGE_PIECES: usize = 200_000;
/// Bisection steps placing a sample at its distance from a cone's apex.
const APEX_BISECTION_STEPS: usize = 60;
/// Rounds of the edge piece count search.
const EDGE_ROUNDS: usize = 12;
/// Boundary vertices within this fraction of the face's domain size of a boundary sample are
/// that sample.
const SNAP_RATIO: f64 = 1e-9;

/// A face that could not be meshed: its index in the shell and why.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceError {
    /// Index of the face in its shell.
    pub face: usize,
    /// What went wrong.
    pub message: String,
}

/// The bounding diagonal of the shells' edges (probe samples): the part's size.
pub fn shells_size(shells: &[StepShell]) -> f64 {
    let mut low = DVec3::splat(f64::INFINITY);
    let mut high = DVec3::splat(f64::NEG_INFINITY);
    for shell in shells {
        for p in &shell.vertices {
            low = low.min(to_dvec(*p));
            high = high.max(to_dvec(*p));
        }
        for edge in &shell.edges {
            let (start, end) = edge.curve.range_tuple();
            for k in 0..=SIZE_SAMPLES {
                let t = start + (end - start) * k as f64 / SIZE_SAMPLES as f64;
                let p = to_dvec(edge.curve.subs(t));
                if p.is_finite() {
                    low = low.min(p);
                    high = high.max(p);
                }
            }
        }
        let closed_faces = shell.faces.iter().filter(|face| has_no_edge(face));
        for closed in closed_faces.filter_map(|face| PoleToPole::of(&face.surface)) {
            for p in closed.grid_points().into_iter().filter(|p| p.is_finite()) {
                low = low.min(p);
                high = high.max(p);
            }
        }
    }
    let size = (high - low).length();
    if size.is_finite() { size } else { 0.0 }
}

/// Meshes every face of `shell` (see the module documentation) and appends them to `soup`, face
/// sources continuing from `first_source`; `size` is the part's size.
pub fn mesh_shell(
    soup: &mut TriangleSoup,
    shell: &StepShell,
    first_source: u32,
    mesh_size: f64,
    chord: f64,
    size: f64,
) -> Result<(), FaceError> {
    let vertices = |edge: usize| {
        let (a, b) = shell.edges[edge].vertices;
        (to_dvec(shell.vertices[a]), to_dvec(shell.vertices[b]))
    };
    let sample_all = |sizes: &[f64]| -> Vec<Vec<DVec3>> {
        (0..shell.edges.len())
            .map(|e| sample_edge(&shell.edges[e].curve, vertices(e), sizes[e], chord))
            .collect()
    };
    let face_sizes = face_mesh_sizes(
        shell,
        &sample_all(&vec![mesh_size; shell.edges.len()]),
        mesh_size,
        chord,
        size,
    );
    let mut edge_sizes = vec![mesh_size; shell.edges.len()];
    for (face, &face_size) in shell.faces.iter().zip(&face_sizes) {
        for edge in face.boundaries.iter().flatten() {
            if let Some(edge_size) = edge_sizes.get_mut(edge.index) {
                *edge_size = edge_size.min(face_size);
            }
        }
    }
    let apexes = edge_apexes(shell, size);
    let edges: Vec<Vec<DVec3>> = (0..shell.edges.len())
        .map(|e| match apexes[e] {
            Some(apex) => sample_toward_apex(
                &shell.edges[e].curve,
                vertices(e),
                apex,
                edge_sizes[e],
                chord,
            ),
            None => sample_edge(&shell.edges[e].curve, vertices(e), edge_sizes[e], chord),
        })
        .collect();
    let edges = graded_at_vertices(shell, edges, &apexes, size);
    for (index, face) in shell.faces.iter().enumerate() {
        let error = |message: String| FaceError {
            face: index,
            message,
        };
        let pieces = face_pieces(face, &edges, face_sizes[index], chord, size).map_err(error)?;
        for loops in &pieces {
            let face_mesh = catch_unwind(AssertUnwindSafe(|| {
                mesh_face(face, loops, face_sizes[index], chord, size)
            }))
            .map_err(|_| error("the face could not be tessellated".into()))?
            .map_err(error)?;
            if face_mesh.triangles.is_empty() {
                return Err(error(
                    "its mesh has no triangle: flatcut cannot mesh this face's layout yet (a face \
                     bounded by meridians through both poles of a sphere)"
                        .into(),
                ));
            }
            let degenerate = degenerate_triangles(&face_mesh);
            if degenerate > 0 {
                return Err(error(format!(
                    "its mesh has {degenerate} zero-area triangle(s): flatcut cannot mesh this \
                     face's layout yet (a face bounded by meridians through both poles of a \
                     sphere, or two faces of a cone that both reach its apex)"
                )));
            }
            append_face(soup, &face_mesh, first_source + index as u32);
        }
    }
    Ok(())
}

/// Each face's mesh size: the mesh size, or less where the face curves so much that triangles of
/// the mesh size would stray farther than the chord from it (a triangle of side `h` on a surface
/// of curvature `κ` strays about `κ h² / 6` at its centre). `edges` are coarse edge samples
/// (for the faces' domains only); a face whose domain cannot be built keeps the mesh size (its
/// error is reported when it is meshed).
fn face_mesh_sizes(
    shell: &StepShell,
    edges: &[Vec<DVec3>],
    mesh_size: f64,
    chord: f64,
    size: f64,
) -> Vec<f64> {
    shell
        .faces
        .iter()
        .map(|face| {
            let curvature = face_pieces(face, edges, mesh_size, chord, size)
                .unwrap_or_default()
                .iter()
                .filter_map(|loops| {
                    catch_unwind(AssertUnwindSafe(|| face_domain(&face.surface, loops, size)))
                        .ok()?
                        .ok()
                })
                .map(|domain| domain.curvature)
                .fold(0.0, f64::max);
            if curvature > 0.0 {
                mesh_size.min((6.0 * chord / curvature).sqrt())
            } else {
                mesh_size
            }
        })
        .collect()
}

/// Welds vertices at exactly the same position (shared edge samples, both sides of a seam) and
/// drops the triangles that collapse.
pub fn weld_coincident(soup: &mut TriangleSoup) {
    let mut index_of: BTreeMap<[u64; 3], u32> = BTreeMap::new();
    let mut positions = Vec::new();
    let remap: Vec<u32> = soup
        .positions
        .iter()
        .map(|p| {
            *index_of
                .entry([p.x, p.y, p.z].map(|c| (c + 0.0).to_bits()))
                .or_insert_with(|| {
                    positions.push(*p);
                    (positions.len() - 1) as u32
                })
        })
        .collect();
    let mut triangles = Vec::with_capacity(soup.triangles.len());
    let mut face_sources = Vec::with_capacity(soup.triangles.len());
    for (triangle, source) in soup.triangles.iter().zip(&soup.face_sources) {
        let [a, b, c] = triangle.map(|v| remap[v as usize]);
        if a != b && b != c && c != a {
            triangles.push([a, b, c]);
            face_sources.push(*source);
        }
    }
    soup.positions = positions;
    soup.triangles = triangles;
    soup.face_sources = face_sources;
}

/// A face's mesh: positions (boundary vertices exactly on their edge samples) and triangles.
struct MeshedFace {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

/// Triangles of a face's mesh that the mesh check would refuse as having zero area (see
/// [`DEGENERATE_AREA_RATIO`]); triangles with two corners at the same position are not counted
/// (welding drops them).
fn degenerate_triangles(face: &MeshedFace) -> usize {
    face.triangles
        .iter()
        .filter(|t| {
            let [a, b, c] = t.map(|v| face.positions[v as usize]);
            if a == b || b == c || c == a {
                return false;
            }
            let longest = (b - a)
                .length_squared()
                .max((c - b).length_squared())
                .max((a - c).length_squared());
            0.5 * (b - a).cross(c - a).length() <= DEGENERATE_AREA_RATIO * longest
        })
        .count()
}

fn append_face(soup: &mut TriangleSoup, face: &MeshedFace, source: u32) {
    let offset = soup.positions.len() as u32;
    soup.positions.extend_from_slice(&face.positions);
    soup.triangles
        .extend(face.triangles.iter().map(|t| t.map(|v| v + offset)));
    soup.face_sources
        .extend(std::iter::repeat_n(source, face.triangles.len()));
}

/// An edge end at a cone's apex: which end (`true` the first vertex) and the cone's `κ d`
/// (see [`apex_curvature`]).
type EdgeApex = (bool, f64);

/// For each edge, the end at which it meets the apex of one of its faces' cones, if any.
fn edge_apexes(shell: &StepShell, size: f64) -> Vec<Option<EdgeApex>> {
    let mut apexes = vec![None; shell.edges.len()];
    for face in &shell.faces {
        for edge in face.boundaries.iter().flatten() {
            let Some(slot) = apexes.get_mut(edge.index) else {
                continue;
            };
            let (a, b) = shell.edges[edge.index].vertices;
            let (a, b) = (to_dvec(shell.vertices[a]), to_dvec(shell.vertices[b]));
            let found = catch_unwind(AssertUnwindSafe(|| {
                apex_curvature(&face.surface, a, b, size)
                    .map(|product| (true, product))
                    .or_else(|| apex_curvature(&face.surface, b, a, size).map(|p| (false, p)))
            }))
            .ok()
            .flatten();
            if let Some((at_start, product)) = found {
                let largest = slot.map_or(product, |(_, other): EdgeApex| other.max(product));
                *slot = Some((at_start, largest));
            }
        }
    }
    apexes
}

/// Samples an edge that ends at a cone's apex with pieces graded to the cone's curvature: a
/// triangle of side `h` at distance `d` from the apex strays `κ h² / 6` with `κ = (κ d) / d`,
/// so pieces there are at most [`EDGE_PIECE_RATIO`] of `√(6 chord d / (κ d))` (and of the mesh
/// size), placed at equal steps of `∫ 1 / size` along the distance from the apex. Both sides of
/// the cone's seam use these points, so the mesher meets pieces as small as its triangles at the
/// apex.
fn sample_toward_apex(
    curve: &Curve3D,
    ends: (DVec3, DVec3),
    (at_start, product): EdgeApex,
    mesh_size: f64,
    chord: f64,
) -> Vec<DVec3> {
    let (start, end) = edge_range(curve, ends, mesh_size);
    let (apex, far, t_apex, t_far) = if at_start {
        (ends.0, ends.1, start, end)
    } else {
        (ends.1, ends.0, end, start)
    };
    let longest = EDGE_PIECE_RATIO * mesh_size;
    let slope = EDGE_PIECE_RATIO * (6.0 * chord / product).sqrt();
    // Pieces `slope √d` up to `d_c`, then `longest`; `w` is ∫ 1 / size over the distance.
    let d_c = (longest / slope).powi(2);
    let w_c = 2.0 * d_c.sqrt() / slope;
    let weight = |d: f64| {
        if d < d_c {
            2.0 * d.sqrt() / slope
        } else {
            w_c + (d - d_c) / longest
        }
    };
    let distance_of = |w: f64| {
        if w < w_c {
            (0.5 * slope * w).powi(2)
        } else {
            d_c + (w - w_c) * longest
        }
    };
    let total = far.distance(apex);
    let pieces = (weight(total).ceil() as usize).clamp(1, MAX_EDGE_PIECES);
    let parameter_at = |d: f64| {
        // The distance from the apex grows along the edge (a ruling): bisection.
        let (mut low, mut high) = (t_apex, t_far);
        for _ in 0..APEX_BISECTION_STEPS {
            let middle = 0.5 * (low + high);
            if to_dvec(curve.subs(middle)).distance(apex) < d {
                low = middle;
            } else {
                high = middle;
            }
        }
        0.5 * (low + high)
    };
    let mut points: Vec<DVec3> = (0..=pieces)
        .map(|k| {
            let d = distance_of(weight(total) * k as f64 / pieces as f64);
            to_dvec(curve.subs(parameter_at(d)))
        })
        .collect();
    points[0] = apex;
    points[pieces] = far;
    if !at_start {
        points.reverse();
    }
    points
}

/// Edges whose pieces are more than this times longer than the shortest piece at one of their
/// vertices are resampled graded toward that vertex.
const GRADE_TRIGGER: f64 = 1.5;
/// Growth of the piece length per unit of length along a graded edge (pieces grow by about
/// 20 % from one to the next).
const GRADE_SLOPE: f64 = 0.2;
/// Dense samples per uniform piece of an edge's arc-length table.
const ARC_SAMPLES_PER_PIECE: usize = 16;

/// Edge samples graded at the vertices: where an edge with long pieces meets, at a vertex, an
/// edge with much shorter pieces (a long side of a sheet next to a small hole or bend radius),
/// the face between them would get a sliver triangle at the corner, since its boundary pieces
/// stay as they are. Such an edge is resampled with pieces growing from the shortest piece at
/// each of its vertices by [`GRADE_SLOPE`] per unit length up to its own piece length (equal
/// steps of `∫ ds / size(s)` along its arc length). Edges that end at a cone's apex keep their
/// own grading.
fn graded_at_vertices(
    shell: &StepShell,
    mut edges: Vec<Vec<DVec3>>,
    apexes: &[Option<EdgeApex>],
    size: f64,
) -> Vec<Vec<DVec3>> {
    let degenerate = 1e-9 * size.max(f64::MIN_POSITIVE);
    let mut shortest = vec![f64::INFINITY; shell.vertices.len()];
    for (edge, samples) in shell.edges.iter().zip(&edges) {
        let (a, b) = edge.vertices;
        if let [first, second, ..] = samples.as_slice() {
            let piece = first.distance(*second);
            if piece > degenerate {
                shortest[a] = shortest[a].min(piece);
            }
        }
        if let [.., before, last] = samples.as_slice() {
            let piece = before.distance(*last);
            if piece > degenerate {
                shortest[b] = shortest[b].min(piece);
            }
        }
    }
    for (index, edge) in shell.edges.iter().enumerate() {
        let samples = &edges[index];
        if apexes[index].is_some() || samples.len() < 2 {
            continue;
        }
        let longest = samples
            .windows(2)
            .map(|w| w[0].distance(w[1]))
            .fold(0.0, f64::max);
        let (a, b) = edge.vertices;
        let ends = (shortest[a].min(longest), shortest[b].min(longest));
        if longest <= GRADE_TRIGGER * ends.0.min(ends.1) {
            continue;
        }
        let range = edge_range(
            &edge.curve,
            (samples[0], samples[samples.len() - 1]),
            longest,
        );
        edges[index] = sample_graded(
            |t| to_dvec(edge.curve.subs(t)),
            range,
            (samples[0], samples[samples.len() - 1]),
            (samples.len() - 1, longest),
            ends,
        );
    }
    edges
}

/// Samples `point` over the parameter `range` with pieces `min(longest, h₀ + k s, h₁ + k (L −
/// s))` long at arc length `s` (`k` = [`GRADE_SLOPE`], `L` the length, `(h₀, h₁)` = `ends`),
/// the ends exactly `ends_at`; `(pieces, longest)` is the edge's uniform sampling.
fn sample_graded(
    point: impl Fn(f64) -> DVec3,
    (start, end): (f64, f64),
    ends_at: (DVec3, DVec3),
    (pieces, longest): (usize, f64),
    ends: (f64, f64),
) -> Vec<DVec3> {
    let dense = (pieces * ARC_SAMPLES_PER_PIECE).max(64);
    let parameters: Vec<f64> = (0..=dense)
        .map(|k| start + (end - start) * k as f64 / dense as f64)
        .collect();
    let mut arc = vec![0.0];
    let mut previous = point(start);
    for &t in &parameters[1..] {
        let next = point(t);
        arc.push(arc[arc.len() - 1] + previous.distance(next));
        previous = next;
    }
    let length = arc[dense];
    let piece_at = |s: f64| {
        longest
            .min(ends.0 + GRADE_SLOPE * s)
            .min(ends.1 + GRADE_SLOPE * (length - s))
    };
    // Cumulative ∫ ds / size at the dense samples (trapezoids).
    let mut weight = vec![0.0];
    for k in 1..=dense {
        let step = arc[k] - arc[k - 1];
        let mean = 0.5 * (1.0 / piece_at(arc[k - 1]) + 1.0 / piece_at(arc[k]));
        weight.push(weight[k - 1] + step * mean);
    }
    let count = (weight[dense].ceil() as usize).clamp(1, MAX_EDGE_PIECES);
    let mut points = Vec::with_capacity(count + 1);
    points.push(ends_at.0);
    let mut k = 0;
    for j in 1..count {
        let target = weight[dense] * j as f64 / count as f64;
        while k + 1 < dense && weight[k + 1] < target {
            k += 1;
        }
        let span = weight[k + 1] - weight[k];
        let fraction = if span > 0.0 {
            (target - weight[k]) / span
        } else {
            0.0
        };
        points.push(point(
            parameters[k] + (parameters[k + 1] - parameters[k]) * fraction,
        ));
    }
    points.push(ends_at.1);
    points
}

/// Samples an edge's curve from `ends.0` to `ends.1` (see the module documentation).
fn sample_edge(curve: &Curve3D, ends: (DVec3, DVec3), mesh_size: f64, chord: f64) -> Vec<DVec3> {
    let range = edge_range(curve, ends, mesh_size);
    sample_curve(|t| to_dvec(curve.subs(t)), range, ends, mesh_size, chord)
}

/// Samples `point` over the parameter `range` in equal steps, each piece at most
/// [`EDGE_PIECE_RATIO`] of the mesh size and within the chord, the ends exactly `ends`.
fn sample_curve(
    point: impl Fn(f64) -> DVec3,
    (start, end): (f64, f64),
    ends: (DVec3, DVec3),
    mesh_size: f64,
    chord: f64,
) -> Vec<DVec3> {
    let closed = ends.0.distance(ends.1) <= f64::EPSILON * ends.0.length().max(1.0);
    let minimum = if closed { 3 } else { 1 };
    let longest = EDGE_PIECE_RATIO * mesh_size;
    let mut pieces = minimum;
    for _ in 0..EDGE_ROUNDS {
        let parameter = |k: f64| start + (end - start) * k / pieces as f64;
        let (mut length_ratio, mut chord_ratio) = (0.0_f64, 0.0_f64);
        for k in 0..pieces {
            let (a, b) = (point(parameter(k as f64)), point(parameter(k as f64 + 1.0)));
            let middle = point(parameter(k as f64 + 0.5));
            length_ratio = length_ratio.max(a.distance(b) / longest);
            chord_ratio = chord_ratio.max(middle.distance((a + b) * 0.5) / chord);
        }
        if length_ratio <= 1.0 && chord_ratio <= 1.0 {
            break;
        }
        let wanted = pieces as f64 * length_ratio.max(chord_ratio.sqrt()).max(1.0);
        let next = (wanted.ceil() as usize + 1).max(pieces + 1);
        if next > MAX_EDGE_PIECES {
            break;
        }
        pieces = next;
    }
    let mut points: Vec<DVec3> = (0..=pieces)
        .map(|k| point(start + (end - start) * k as f64 / pieces as f64))
        .collect();
    points[0] = ends.0;
    points[pieces] = ends.1;
    points
}

/// The curve's parameter range between the edge's vertices: its own range when its ends are the
/// vertices, else the parameters nearest the vertices (a vertex within a fraction of the mesh
/// size of the curve's end is that end).
fn edge_range(curve: &Curve3D, ends: (DVec3, DVec3), mesh_size: f64) -> (f64, f64) {
    let (start, end) = curve.range_tuple();
    let tolerance = 1e-6 * mesh_size;
    let nearest = |vertex: DVec3, own: f64| {
        if to_dvec(curve.subs(own)).distance(vertex) <= tolerance {
            return own;
        }
        curve
            .search_nearest_parameter(Point3::new(vertex.x, vertex.y, vertex.z), None, 100)
            .unwrap_or(own)
    };
    (nearest(ends.0, start), nearest(ends.1, end))
}

/// Whether a face has no boundary edge (STEP's vertex loop, which truck-stepio drops).
fn has_no_edge(face: &CompressedFace<StepSurface>) -> bool {
    face.boundaries.iter().all(|boundary| boundary.is_empty())
}

/// The boundary loops of each piece a face is meshed in: its own loops, or for a face with no
/// edge on a surface closed from pole to pole (a full sphere) the two caps of [`PoleToPole`],
/// their middle parallel and seam meridians sampled like edges to `mesh_size` and the chord.
fn face_pieces(
    face: &CompressedFace<StepSurface>,
    edges: &[Vec<DVec3>],
    mesh_size: f64,
    chord: f64,
    size: f64,
) -> Result<Vec<Vec<BoundaryLoop>>, String> {
    if !has_no_edge(face) {
        return Ok(vec![face_loops(face, edges, size)?]);
    }
    let closed = PoleToPole::of(&face.surface).ok_or_else(|| {
        "it has no boundary edge (only a vertex loop) and its surface is not closed from pole \
         to pole (flatcut meshes a boundary-less face only on a full sphere or closed surface of \
         revolution)"
            .to_string()
    })?;
    let seam = closed.parallel(0.0);
    let parallel = sample_curve(
        |s| closed.parallel(s),
        (0.0, 1.0),
        (seam, seam),
        mesh_size,
        chord,
    );
    let caps = (0..2).map(|pole| {
        let tip = closed.meridian(pole, 1.0);
        let meridian = sample_curve(
            |s| closed.meridian(pole, s),
            (0.0, 1.0),
            (seam, tip),
            mesh_size,
            chord,
        );
        // The parallel (its last point is the seam again), out along the meridian to the pole
        // and back.
        let mut points = parallel.clone();
        points.extend_from_slice(&meridian[1..]);
        points.extend(meridian[1..meridian.len() - 1].iter().rev());
        let edge_starts = vec![0, parallel.len() - 1, parallel.len() + meridian.len() - 2];
        vec![BoundaryLoop {
            points,
            edge_starts,
        }]
    });
    Ok(caps.collect())
}

/// The face's boundary loops as points on the surface, each point once (a loop does not repeat
/// its first point).
fn face_loops(
    face: &CompressedFace<StepSurface>,
    edges: &[Vec<DVec3>],
    size: f64,
) -> Result<Vec<BoundaryLoop>, String> {
    let gap_tolerance = 1e-6 * size.max(f64::MIN_POSITIVE);
    let mut loops = Vec::with_capacity(face.boundaries.len());
    for boundary in &face.boundaries {
        let mut points: Vec<DVec3> = Vec::new();
        let mut edge_starts = Vec::with_capacity(boundary.len());
        for edge in boundary {
            let samples = edges
                .get(edge.index)
                .ok_or_else(|| "a boundary edge could not be read".to_string())?;
            let oriented: Vec<DVec3> = if edge.orientation {
                samples.clone()
            } else {
                samples.iter().rev().copied().collect()
            };
            if let Some(&last) = points.last() {
                if last.distance(oriented[0]) > gap_tolerance {
                    return Err(
                        "its boundary loop is not closed (an edge could not be read or \
                                the edges are out of order)"
                            .into(),
                    );
                }
                points.pop();
            }
            edge_starts.push(points.len());
            points.extend(oriented);
        }
        if points.len() > 1 && points[0].distance(points[points.len() - 1]) <= gap_tolerance {
            points.pop();
        } else if points.len() > 1 {
            return Err("its boundary loop is not closed".into());
        }
        if points.len() >= 2 {
            loops.push(BoundaryLoop {
                points,
                edge_starts,
            });
        }
    }
    if loops.is_empty() {
        return Err("it has no boundary loop".into());
    }
    Ok(loops)
}

/// One face meshed in its mapped domain, its boundary vertices snapped onto the shared edge
/// samples and its triangles turned to follow the face's normal.
fn mesh_face(
    face: &CompressedFace<StepSurface>,
    loops: &[BoundaryLoop],
    mesh_size: f64,
    chord: f64,
    size: f64,
) -> Result<MeshedFace, String> {
    let domain = face_domain(&face.surface, loops, size).map_err(|e| e.0)?;
    let (boundary, samples) = domain_boundary(&domain.loops, loops);
    let (outer, holes) = outer_and_holes(boundary);
    let patch = PatchSurface {
        geometry: PatchGeometry::Mapped(Arc::new(domain.surface.clone())),
        outer,
        holes,
    };
    let mesh = mesh_patch(&patch, &[], mesh_size, chord).map_err(|e| e.to_string())?;
    let positions = snap_to_samples(&mesh.positions, &mesh.parameters, &samples);
    let mut triangles = mesh.triangles;
    if !follows_face_normal(
        face,
        &domain.surface,
        &positions,
        &mesh.parameters,
        &triangles,
    ) {
        for triangle in &mut triangles {
            triangle.swap(1, 2);
        }
    }
    Ok(MeshedFace {
        positions,
        triangles,
    })
}

/// A boundary sample: its point in the face's domain and on the edge in 3D.
type BoundarySample = (DVec2, DVec3);

/// Domain loops without repeated consecutive points, and every boundary sample.
fn domain_boundary(
    domain_loops: &[Vec<DVec2>],
    loops: &[BoundaryLoop],
) -> (Vec<Vec<DVec2>>, Vec<BoundarySample>) {
    let mut cleaned = Vec::with_capacity(domain_loops.len());
    let mut samples = Vec::new();
    for (domain, points) in domain_loops.iter().zip(loops) {
        let extent = domain
            .iter()
            .fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
        let tolerance = SNAP_RATIO * extent.max(f64::MIN_POSITIVE);
        let mut kept: Vec<DVec2> = Vec::with_capacity(domain.len());
        for (&p, &q) in domain.iter().zip(&points.points) {
            samples.push((p, q));
            if kept.last().is_none_or(|last| last.distance(p) > tolerance) {
                kept.push(p);
            }
        }
        remove_slits(&mut kept, tolerance);
        if kept.len() >= 3 {
            cleaned.push(kept);
        }
    }
    (cleaned, samples)
}

/// Removes repeated consecutive points (cyclically) and slits: a loop that runs out along a
/// line and back along it (a seam through a smooth pole, which the polar map puts on one ray)
/// loses the slit, so the face is meshed across its seam.
fn remove_slits(points: &mut Vec<DVec2>, tolerance: f64) {
    loop {
        while points.len() > 1 && points[0].distance(points[points.len() - 1]) <= tolerance {
            points.pop();
        }
        let count = points.len();
        if count < 3 {
            return;
        }
        let tip = (0..count).find(|&k| {
            points[(k + count - 1) % count].distance(points[(k + 1) % count]) <= tolerance
        });
        let Some(tip) = tip else { return };
        // Drop the tip and the point after it (the way back duplicates the way out).
        let after = (tip + 1) % count;
        let (first, second) = (tip.max(after), tip.min(after));
        points.remove(first);
        points.remove(second);
        points.dedup_by(|a, b| a.distance(*b) <= tolerance);
    }
}

/// The loop of largest area is the outer one (made counter-clockwise), the others are holes.
fn outer_and_holes(mut loops: Vec<Vec<DVec2>>) -> (Vec<DVec2>, Vec<Vec<DVec2>>) {
    let largest = (0..loops.len())
        .max_by(|&a, &b| {
            crate::geometry::signed_area(&loops[a])
                .abs()
                .total_cmp(&crate::geometry::signed_area(&loops[b]).abs())
        })
        .unwrap_or(0);
    let mut outer = if loops.is_empty() {
        Vec::new()
    } else {
        loops.remove(largest)
    };
    if crate::geometry::signed_area(&outer) < 0.0 {
        outer.reverse();
    }
    (outer, loops)
}

/// Positions with every vertex at a boundary sample's domain point moved exactly onto the
/// sample's 3D point.
fn snap_to_samples(
    positions: &[DVec3],
    parameters: &[DVec2],
    samples: &[BoundarySample],
) -> Vec<DVec3> {
    let extent = samples
        .iter()
        .fold(0.0_f64, |m, (p, _)| m.max(p.abs().max_element()));
    let tolerance = SNAP_RATIO * extent.max(f64::MIN_POSITIVE) * 10.0;
    let mut sorted: Vec<BoundarySample> = samples.to_vec();
    sorted.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
    positions
        .iter()
        .zip(parameters)
        .map(|(&position, &parameter)| {
            let from = sorted.partition_point(|(p, _)| p.x < parameter.x - tolerance);
            sorted[from..]
                .iter()
                .take_while(|(p, _)| p.x <= parameter.x + tolerance)
                .find(|(p, _)| p.distance(parameter) <= tolerance)
                .map_or(position, |&(_, exact)| exact)
        })
        .collect()
}

/// Whether most triangles (by area) turn like the face's normal.
fn follows_face_normal(
    face: &CompressedFace<StepSurface>,
    surface: &FaceSurface,
    positions: &[DVec3],
    parameters: &[DVec2],
    triangles: &[[u32; 3]],
) -> bool {
    let sign = if face.orientation { 1.0 } else { -1.0 };
    let agreement: f64 = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| positions[v as usize]);
            let centre = t.iter().map(|&v| parameters[v as usize]).sum::<DVec2>() / 3.0;
            let normal = surface.native_normal(surface.native(centre));
            (b - a).cross(c - a).dot(normal.normalize_or_zero())
        })
        .sum();
    sign * agreement >= 0.0
}

fn to_dvec(p: Point3) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn graded_samples_grow_from_the_short_ends_to_the_edge_piece_length() {
        let line = |t: f64| DVec3::new(100.0 * t, 0.0, 0.0);
        let ends = (DVec3::ZERO, DVec3::new(100.0, 0.0, 0.0));
        let points = sample_graded(line, (0.0, 1.0), ends, (10, 10.0), (0.5, 2.0));
        let pieces: Vec<f64> = points.windows(2).map(|w| w[0].distance(w[1])).collect();
        assert_eq!(points[0], ends.0);
        assert_eq!(points[points.len() - 1], ends.1);
        assert!((pieces[0] - 0.5).abs() < 0.1, "{pieces:?}");
        assert!((pieces[pieces.len() - 1] - 2.0).abs() < 0.3, "{pieces:?}");
        assert!(pieces.iter().all(|&p| p <= 10.0 + 1e-9), "{pieces:?}");
        for pair in pieces.windows(2) {
            let ratio = pair[1].max(pair[0]) / pair[1].min(pair[0]);
            assert!(ratio < 1.3, "{pieces:?}");
        }
    }
}
