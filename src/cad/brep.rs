//! The boundary representation the STEP reader builds: shells of faces on exact surfaces, bounded
//! by edges on exact curves, in millimetres, each face named by its STEP entity.
//!
//! A shell is kept as truck's compressed shell ([`StepShell`]): vertices, edges with their 3D
//! curves (lines, conics, B-spline and NURBS curves) and faces with their boundary loops (edge
//! indices with orientations), their orientation and their surface with its exact parameters
//! (truck's plane, sphere, cylinder, cone and torus with their placement, surfaces of revolution
//! and extrusion with their curves, B-spline and NURBS surfaces with their control nets), not
//! samples. [`BrepShell`] adds what the file says about each face (its entity id and a
//! description for messages), reads each face's exact parameters ([`SurfaceGeometry`]) and
//! answers which faces share an edge. A file with no shell (a
//! surface-only export) gives loose NURBS surfaces ([`LooseSurface`]) instead.

use truck_meshalgo::prelude::Point3;
use truck_stepio::r#in::alias::{Curve3D, Surface as StepSurface};
use truck_topology::compress::CompressedShell;

use super::face_geometry::SurfaceGeometry;
use super::surface::PatchGeometry;

/// A shell as truck-stepio converts it: vertices, edges on 3D curves, faces on exact surfaces.
pub type StepShell = CompressedShell<Point3, Curve3D, StepSurface>;

/// The STEP entity a face of a shell comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaceSource {
    /// The face's entity id (`#17`).
    pub id: u64,
    /// The face described for messages: `ADVANCED_FACE #17 on CONICAL_SURFACE (#31)`.
    pub description: String,
}

/// One shell of a STEP file, in millimetres.
#[derive(Debug, Clone)]
pub struct BrepShell {
    /// The shell's entity id.
    pub id: u64,
    /// The topology and exact geometry.
    pub shell: StepShell,
    /// The entity of each face the shell lists, in the order of `shell.faces`.
    pub faces: Vec<FaceSource>,
}

impl BrepShell {
    /// Face `face`'s surface with its exact parameters.
    pub fn surface_geometry(&self, face: usize) -> SurfaceGeometry {
        SurfaceGeometry::of(&self.shell.faces[face].surface)
    }

    /// The description of face `face` for messages (`face N` when the file did not list it).
    pub fn describe_face(&self, face: usize) -> String {
        self.faces
            .get(face)
            .map(|source| source.description.clone())
            .unwrap_or_else(|| format!("face {}", face + 1))
    }

    /// Face adjacency: every pair of faces `[a, b]` (`a < b`) that share an edge, with the edge's
    /// index, sorted. A seam edge a face uses twice is not listed.
    pub fn adjacent_faces(&self) -> Vec<([usize; 2], usize)> {
        let mut uses: Vec<(usize, usize)> = self
            .shell
            .faces
            .iter()
            .enumerate()
            .flat_map(|(face, f)| {
                f.boundaries
                    .iter()
                    .flatten()
                    .map(move |edge| (edge.index, face))
            })
            .collect();
        uses.sort_unstable();
        uses.dedup();
        let mut pairs = Vec::new();
        for group in uses.chunk_by(|x, y| x.0 == y.0) {
            for (i, first) in group.iter().enumerate() {
                for second in &group[i + 1..] {
                    pairs.push(([first.1, second.1], first.0));
                }
            }
        }
        pairs.sort_unstable();
        pairs
    }
}

/// A surface of a file with no shell, in millimetres: a NURBS patch over its whole parameter
/// domain.
#[derive(Debug, Clone)]
pub struct LooseSurface {
    /// The surface's entity id.
    pub id: u64,
    /// The surface.
    pub geometry: PatchGeometry,
}

/// What a STEP file holds, read: its shells, or its loose surfaces when it has none.
#[derive(Debug, Clone)]
pub struct Brep {
    /// Part name: the file stem.
    pub name: String,
    /// Shells in entity order.
    pub shells: Vec<BrepShell>,
    /// Loose surfaces in entity order (only when there is no shell).
    pub loose: Vec<LooseSurface>,
    /// Geometric entities of the file flatcut cannot read, `NAME (#id)`, for messages.
    pub unsupported: Vec<String>,
}

impl Brep {
    /// The note appended to messages about a file holding entities flatcut cannot read (empty
    /// when it holds none).
    pub fn unsupported_note(&self) -> String {
        if self.unsupported.is_empty() {
            String::new()
        } else {
            format!(
                "; the file holds entities flatcut cannot read: {}",
                self.unsupported.join(", ")
            )
        }
    }
}
