//! Tessellation: a part's CAD surfaces into one triangle soup fit for the spring model.
//!
//! Input: a [`CadPart`] (surfaces, fold lines) in part units and [`TessellateOptions`]. Output: a
//! [`Tessellation`]: a [`TriangleSoup`] whose `face_sources` name the surface of each triangle
//! and whose `fold_edges` carry every fold line onto mesh edges, with the figures a user checks
//! (triangles, worst angle). Each surface is meshed by the algorithm that suits it (see
//! [`surface`]); faces are then welded along their shared edges ([`weld`]); a fold line given as
//! the edge between two surfaces becomes the mesh edges those surfaces share.
//!
//! Mesh size and chord tolerance default from the part's size (the diagonal of its bounding box):
//! [`DEFAULT_DIVISIONS`] edges along the diagonal, a chord of [`DEFAULT_CHORD_RATIO`] of
//! it.

pub mod brep;
pub mod face_domain;
pub mod face_mesh;
pub mod fan;
pub mod fold_insert;
pub mod parameter_region;
pub mod patch;
pub mod revolution;
pub mod ruled;
pub mod ruled_folds;
pub mod strip;
pub mod surface;
pub mod surface_domain;
pub mod weld;

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};
use serde::Serialize;

use crate::mesh::{FoldEdge, TriangleSoup};
use face_mesh::FaceMesh;
use surface::{FoldLineGeometry, Surface};
pub use weld::Welded;

/// Default mesh size: the part's bounding diagonal divided by this.
pub const DEFAULT_DIVISIONS: f64 = 50.0;
/// Default chord tolerance, as a fraction of the part's bounding diagonal. A cone frustum's rim
/// is an inscribed polygon whose development subtends a little less than the analytic sector:
/// at 2e-4 the seam end of a 100/50/80 mm frustum is 0.065 mm off the analytic development when
/// the other end is pinned, at 1e-4 0.037 mm.
pub const DEFAULT_CHORD_RATIO: f64 = 1e-4;
/// The smallest mesh size accepted, as a fraction of the bounding diagonal (bounds the
/// triangle count near four million).
pub const MINIMUM_MESH_SIZE_RATIO: f64 = 1.0 / 2000.0;
/// The smallest chord tolerance accepted, as a fraction of the bounding diagonal: on a curve of
/// radius half the diagonal it asks for edges near the smallest mesh size (a chord of 1e-12 mm
/// refined without end).
pub const MINIMUM_CHORD_RATIO: f64 = 1e-7;
/// Vertices of different faces closer than this fraction of the diagonal are welded.
pub const WELD_TOLERANCE_RATIO: f64 = 1e-7;
/// Angular samples of a circle when the part's size is estimated.
const SIZE_SAMPLES: usize = 16;

/// Options of [`tessellate`]. `Default` is the only source of defaults.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct TessellateOptions {
    /// Target edge length (part units); default the bounding diagonal / [`DEFAULT_DIVISIONS`].
    pub mesh_size: Option<f64>,
    /// Largest distance between the surface and a triangle (part units); default the bounding
    /// diagonal × [`DEFAULT_CHORD_RATIO`].
    pub chord: Option<f64>,
}

/// Errors of tessellation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TessellateError {
    /// The mesh size or chord tolerance is not a positive length, or too small for the part.
    #[error(
        "the mesh size {mesh_size} and chord {chord} must be positive, the mesh size at least \
         {minimum} and the chord at least {minimum_chord} for a part of this size; give a larger \
         --mesh-size or --chord"
    )]
    BadSize {
        /// The mesh size used.
        mesh_size: f64,
        /// The chord tolerance used.
        chord: f64,
        /// The smallest mesh size accepted.
        minimum: f64,
        /// The smallest chord tolerance accepted.
        minimum_chord: f64,
    },
    /// A patch's derivatives vanish: it has no area.
    #[error("a patch is degenerate (its derivatives vanish); check its control points")]
    DegenerateSurface,
    /// A parameter point could not be triangulated (NaN or huge).
    #[error("the parameter point ({u}, {v}) cannot be triangulated")]
    BadParameterPoint {
        /// u.
        u: f64,
        /// v.
        v: f64,
    },
    /// A fold line crosses a trim loop or another fold line.
    #[error(
        "a fold line or trim loop crosses another near parameters ({u}, {v}); fold lines must \
         stay inside the trimmed domain"
    )]
    CrossingConstraints {
        /// u.
        u: f64,
        /// v.
        v: f64,
    },
    /// A fold polyline point is not on its surface.
    #[error("the fold polyline point ({u}, {v}) is not on its surface")]
    FoldOffSurface {
        /// u.
        u: f64,
        /// v.
        v: f64,
    },
    /// A surface produced no triangles.
    #[error("surface {surface} produced no triangles; check its dimensions")]
    EmptySurface {
        /// Surface index.
        surface: usize,
    },
}

/// A part's geometry as the tessellator needs it.
#[derive(Debug, Clone)]
pub struct CadPart {
    /// Surfaces in file order.
    pub surfaces: Vec<Surface>,
    /// Fold lines in file order.
    pub fold_lines: Vec<FoldLineGeometry>,
    /// Whether surfaces are welded along shared edges (false: each surface its own part).
    pub weld: bool,
}

/// A tessellated part.
#[derive(Debug, Clone)]
pub struct Tessellation {
    /// The welded soup.
    pub welded: Welded,
    /// The mesh size used.
    pub mesh_size: f64,
    /// The chord tolerance used.
    pub chord: f64,
    /// The smallest triangle angle, degrees.
    pub minimum_angle: f64,
}

impl Tessellation {
    /// The soup.
    pub fn soup(&self) -> &TriangleSoup {
        &self.welded.soup
    }
}

impl CadPart {
    /// The diagonal of a bounding box of sample points of every surface: the part's size.
    pub fn size(&self) -> f64 {
        let mut low = DVec3::splat(f64::INFINITY);
        let mut high = DVec3::splat(f64::NEG_INFINITY);
        for surface in &self.surfaces {
            for p in outline_points(surface) {
                low = low.min(p);
                high = high.max(p);
            }
        }
        (high - low).length()
    }
}

/// Sample points spanning a surface (for its size).
fn outline_points(surface: &Surface) -> Vec<DVec3> {
    match surface {
        Surface::Ruled(ruled) => {
            let rulings = ruled::rulings(ruled, f64::INFINITY, 0.0);
            let mut points = rulings.bottom;
            points.extend(rulings.top);
            if let surface::RuledSurface::Circular {
                frame,
                bottom,
                top,
                angles,
            } = ruled
            {
                for k in 0..=SIZE_SAMPLES {
                    let angle =
                        angles[0] + (angles[1] - angles[0]) * k as f64 / SIZE_SAMPLES as f64;
                    points.push(frame.point(bottom.point(angle)));
                    points.push(frame.point(top.point(angle)));
                }
            }
            points
        }
        Surface::Revolution(revolution) => {
            let mut points = Vec::new();
            for p in revolution.profile.sample(f64::INFINITY, 0.0) {
                for k in 0..SIZE_SAMPLES {
                    let angle = TAU * k as f64 / SIZE_SAMPLES as f64;
                    let local = DVec3::new(p.x * angle.cos(), p.x * angle.sin(), p.y);
                    points.push(revolution.frame.point(local));
                }
            }
            points
        }
        Surface::Patch(patch) => {
            let (low, high) = patch
                .outer
                .iter()
                .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(l, h), &p| {
                    (l.min(p), h.max(p))
                });
            let grid = (0..=SIZE_SAMPLES)
                .flat_map(|i| (0..=SIZE_SAMPLES).map(move |j| DVec2::new(i as f64, j as f64)));
            grid.map(|t| {
                patch
                    .geometry
                    .point(low + (high - low) * t / SIZE_SAMPLES as f64)
            })
            .collect()
        }
    }
}

/// The mesh size and chord tolerance for a part, defaults filled in and checked.
pub fn resolve_sizes(
    part: &CadPart,
    options: &TessellateOptions,
) -> Result<(f64, f64), TessellateError> {
    sizes_for_diagonal(part.size(), options)
}

/// The mesh size and chord tolerance for a part whose bounding diagonal is `size`, defaults
/// filled in and checked.
pub fn sizes_for_diagonal(
    size: f64,
    options: &TessellateOptions,
) -> Result<(f64, f64), TessellateError> {
    let mesh_size = options.mesh_size.unwrap_or(size / DEFAULT_DIVISIONS);
    let chord = options.chord.unwrap_or(size * DEFAULT_CHORD_RATIO);
    let minimum = size * MINIMUM_MESH_SIZE_RATIO;
    let minimum_chord = size * MINIMUM_CHORD_RATIO;
    if !(mesh_size.is_finite()
        && mesh_size >= minimum
        && chord.is_finite()
        && chord > 0.0
        && chord >= minimum_chord)
    {
        return Err(TessellateError::BadSize {
            mesh_size,
            chord,
            minimum,
            minimum_chord,
        });
    }
    Ok((mesh_size, chord))
}

/// Tessellates a part (see the module documentation).
pub fn tessellate(
    part: &CadPart,
    options: &TessellateOptions,
) -> Result<Tessellation, TessellateError> {
    let (mesh_size, chord) = resolve_sizes(part, options)?;
    let weld_tolerance = part.size() * WELD_TOLERANCE_RATIO;
    let folds: Vec<Vec<(u32, Vec<DVec2>)>> = (0..part.surfaces.len())
        .map(|index| surface_folds(part, index))
        .collect();
    // Structured meshes first without their fold polylines: a ruled surface's polylines may add
    // rulings, which must not add points on a section another surface is welded to.
    let mut faces = Vec::with_capacity(part.surfaces.len());
    for (index, surface) in part.surfaces.iter().enumerate() {
        let face = match surface {
            Surface::Ruled(ruled) => ruled::mesh_ruled(ruled, mesh_size, chord),
            Surface::Revolution(revolution) => {
                revolution::mesh_revolution(revolution, mesh_size, chord)
            }
            Surface::Patch(patch) => patch::mesh_patch(patch, &folds[index], mesh_size, chord)?,
        };
        faces.push(face);
    }
    for (index, surface) in part.surfaces.iter().enumerate() {
        if folds[index].is_empty() || matches!(surface, Surface::Patch(_)) {
            continue;
        }
        // A section is welded when one of its edges is shared (both ends on another face).
        let shared = |p: &DVec3| {
            faces.iter().enumerate().any(|(other, face)| {
                other != index
                    && face
                        .positions
                        .iter()
                        .any(|q| p.distance(*q) <= weld_tolerance)
            })
        };
        let welded =
            |points: &[DVec3]| part.weld && points.windows(2).any(|pair| pair.iter().all(shared));
        let face = mesh_with_folds(surface, &folds[index], mesh_size, chord, welded)?;
        faces[index] = face;
    }
    if let Some(index) = faces.iter().position(|face| face.triangles.is_empty()) {
        return Err(TessellateError::EmptySurface { surface: index });
    }
    let mut welded = weld::weld_faces(&faces, part.weld, weld_tolerance);
    add_shared_edge_folds(part, &mut welded.soup);
    let minimum_angle = minimum_angle(&welded.soup);
    Ok(Tessellation {
        welded,
        mesh_size,
        chord,
        minimum_angle,
    })
}

/// The fold polylines `(fold line index, domain points)` on surface `index`.
fn surface_folds(part: &CadPart, index: usize) -> Vec<(u32, Vec<DVec2>)> {
    part.fold_lines
        .iter()
        .enumerate()
        .filter_map(|(line, fold)| match fold {
            FoldLineGeometry::OnSurface { surface, points } if *surface == index => {
                Some((line as u32, points.clone()))
            }
            _ => None,
        })
        .collect()
}

/// The structured mesh of a ruled surface or a surface of revolution with its fold polylines.
/// A ruled surface carries them along its rulings ([`ruled_folds`]: the mesh stays exactly
/// developable) unless that would add a point on a section `welded` says another surface shares
/// an edge of (given the section's points), or a polyline crosses a cone fan other than along
/// one of its rows; then, and on surfaces of
/// revolution, they are inserted by a constrained re-triangulation around them ([`fold_insert`]).
fn mesh_with_folds(
    surface: &Surface,
    folds: &[(u32, Vec<DVec2>)],
    mesh_size: f64,
    chord: f64,
    welded: impl Fn(&[DVec3]) -> bool,
) -> Result<FaceMesh, TessellateError> {
    let domain = surface_domain::SurfaceDomain::new(surface);
    let mut mesh = match surface {
        Surface::Ruled(ruled) => {
            let plain = ruled::rulings(ruled, mesh_size, chord);
            let sections = [welded(&plain.bottom), welded(&plain.top)];
            // Rulings through the polylines' vertices where the sections may get new points.
            let rulings = if sections.contains(&true) {
                plain
            } else {
                let through: Vec<f64> = fold_insert::with_crossings(folds)
                    .iter()
                    .flat_map(|(_, points)| points.iter().map(|p| p.x))
                    .collect();
                ruled::rulings_through(ruled, mesh_size, chord, &through)
            };
            if let Some((rulings, ruling_folds)) =
                ruled_folds::fold_rulings(&rulings, &domain, folds, sections, mesh_size, chord)
            {
                return Ok(ruled::mesh_rulings(&rulings, &ruling_folds, mesh_size));
            }
            ruled::mesh_rulings(&rulings, &ruled::RulingFolds::default(), mesh_size)
        }
        Surface::Revolution(revolution) => {
            revolution::mesh_revolution(revolution, mesh_size, chord)
        }
        Surface::Patch(patch) => return patch::mesh_patch(patch, folds, mesh_size, chord),
    };
    fold_insert::insert_fold_polylines(&mut mesh, &domain, folds, mesh_size)?;
    Ok(mesh)
}

/// Tags the edges shared by the two surfaces of each `Between` fold line.
fn add_shared_edge_folds(part: &CadPart, soup: &mut TriangleSoup) {
    let mut half_edges: Vec<([u32; 2], u32)> = Vec::with_capacity(soup.triangles.len() * 3);
    for (t, source) in soup.triangles.iter().zip(&soup.face_sources) {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            half_edges.push(([a.min(b), a.max(b)], *source));
        }
    }
    half_edges.sort_unstable();
    for (line, fold) in part.fold_lines.iter().enumerate() {
        let FoldLineGeometry::Between { surfaces } = fold else {
            continue;
        };
        let wanted = [
            surfaces[0].min(surfaces[1]) as u32,
            surfaces[0].max(surfaces[1]) as u32,
        ];
        for pair in half_edges.windows(2) {
            let (first, second) = (pair[0], pair[1]);
            if first.0 == second.0 && [first.1, second.1] == wanted {
                soup.fold_edges.push(FoldEdge {
                    vertices: first.0,
                    fold_line: line as u32,
                });
            }
        }
    }
}

/// The smallest interior angle over all triangles, degrees.
pub fn minimum_angle(soup: &TriangleSoup) -> f64 {
    soup.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| soup.positions[v as usize]);
            [(a, b, c), (b, c, a), (c, a, b)]
                .iter()
                .map(|&(p, q, r)| (q - p).angle_between(r - p).to_degrees())
                .fold(180.0, f64::min)
        })
        .fold(180.0, f64::min)
}
