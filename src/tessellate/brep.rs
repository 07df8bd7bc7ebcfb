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
//!    equal parameter steps, as many as keep each piece shorter than `EDGE_PIECE_RATIO` of the
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

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;

use glam::{DVec2, DVec3};
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::Surface as StepSurface;
use truck_topology::compress::CompressedFace;

use super::collinear::{is_degenerate, remove_degenerate_triangles};
use super::edge_sampling::{
    edge_apexes, graded_at_vertices, sample_curve, sample_edge, sample_toward_apex, to_dvec,
};
use super::face_domain::{BoundaryLoop, FaceSurface, face_domain};
use super::patch::{Refinement, mesh_patch_as};
use super::pole_to_pole::PoleToPole;
use super::seamless::join_seamless_loops;
use crate::cad::{PatchGeometry, PatchSurface, StepShell, SurfaceGeometry, TriangleSoup};
use crate::geometry::tolerance::{LOOP_GAP_RATIO, SNAP_RATIO};
use crate::geometry::weld::PointWelder;

/// Probe samples per edge when the shells' size is measured.
const SIZE_SAMPLES: usize = 16;

/// A face that could not be meshed: its index in the shell and why.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceError {
    /// Index of the face in its shell.
    pub face: usize,
    /// What went wrong.
    pub message: String,
}

/// The bounding diagonal of the shells' edges (probe samples): the part's size.
pub fn shells_size<'a>(shells: impl IntoIterator<Item = &'a StepShell>) -> f64 {
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
/// sources continuing from `first_source`; `size` is the part's size. With
/// [`Refinement::ChordOnly`] the faces keep `mesh_size` (no smaller size where they curve), the
/// edges are not graded at their vertices and the faces are triangulated from their boundary
/// samples without refinement (see [`Refinement`]).
pub fn mesh_shell(
    soup: &mut TriangleSoup,
    shell: &StepShell,
    first_source: u32,
    (mesh_size, chord): (f64, f64),
    size: f64,
    refinement: Refinement,
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
    let face_sizes = match refinement {
        Refinement::Full => face_mesh_sizes(
            shell,
            &sample_all(&vec![mesh_size; shell.edges.len()]),
            mesh_size,
            chord,
            size,
        ),
        Refinement::ChordOnly => vec![mesh_size; shell.faces.len()],
    };
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
    let edges = match refinement {
        Refinement::Full => graded_at_vertices(shell, edges, &apexes, size),
        Refinement::ChordOnly => edges,
    };
    for (index, face) in shell.faces.iter().enumerate() {
        let error = |message: String| FaceError {
            face: index,
            message,
        };
        let pieces = face_pieces(face, &edges, face_sizes[index], chord, size).map_err(error)?;
        for loops in &pieces {
            let face_mesh = catch_unwind(AssertUnwindSafe(|| {
                mesh_face(face, loops, (face_sizes[index], chord), size, refinement)
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
    let mut welder = PointWelder::new(DVec3::ZERO, 0.0);
    let remap: Vec<u32> = soup.positions.iter().map(|&p| welder.insert(p)).collect();
    let positions = welder.into_points();
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
        .filter(|t| is_degenerate(t.map(|v| face.positions[v as usize])))
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

/// Whether a face has no boundary edge (STEP's vertex loop, which truck-stepio drops).
fn has_no_edge(face: &CompressedFace<StepSurface>) -> bool {
    face.boundaries.iter().all(|boundary| boundary.is_empty())
}

/// The boundary loops of each piece a face is meshed in: its own loops (the two end loops of a
/// cylinder or cone side without a seam edge joined along a ruling: [`join_seamless_loops`]),
/// or for a face with no
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
        let loops = face_loops(face, edges, size)?;
        return Ok(vec![match SurfaceGeometry::of(&face.surface) {
            SurfaceGeometry::Cylinder { origin, axis, .. }
            | SurfaceGeometry::Cone { origin, axis, .. } => {
                join_seamless_loops(loops, origin, axis, mesh_size)
            }
            _ => loops,
        }]);
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
    let gap_tolerance = LOOP_GAP_RATIO * size.max(f64::MIN_POSITIVE);
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
    (mesh_size, chord): (f64, f64),
    size: f64,
    refinement: Refinement,
) -> Result<MeshedFace, String> {
    let domain = face_domain(&face.surface, loops, size).map_err(|e| e.0)?;
    let (boundary, samples) = domain_boundary(&domain.loops, loops);
    let (outer, holes) = outer_and_holes(boundary);
    let patch = PatchSurface {
        geometry: PatchGeometry::Mapped(Arc::new(domain.surface.clone())),
        outer,
        holes,
    };
    let mesh =
        mesh_patch_as(&patch, &[], mesh_size, chord, refinement).map_err(|e| e.to_string())?;
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
    remove_degenerate_triangles(&positions, &mut triangles);
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
