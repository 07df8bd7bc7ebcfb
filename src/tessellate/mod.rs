//! Tessellation: the CAD model ([`crate::cad`]) into one triangle soup fit for the spring model,
//! with fold lines tagged on mesh edges and the figures a user checks (mesh size, chord, worst
//! angle), for part files ([`tessellate_part`]) and STEP files ([`tessellate_brep`]) alike.
//!
//! Part files: each surface is meshed by the algorithm that suits it (ruled surfaces along their
//! rulings, surfaces of revolution on parallels, patches by constrained Delaunay refinement in
//! their parameter domain), fold polylines carried along rulings or inserted by a constrained
//! re-triangulation, faces welded along their shared edges. STEP files: every edge sampled once,
//! each face meshed in a domain with (nearly) its surface's metric, shared edges and seams
//! welded.
//!
//! Mesh size and chord tolerance default from the part's size (the diagonal of its bounding box):
//! [`DEFAULT_DIVISIONS`] edges along the diagonal, a chord of [`DEFAULT_CHORD_RATIO`] of it.

mod brep;
mod collinear;
mod crossings;
mod curvature;
mod domain_map;
mod edge_sampling;
mod face_domain;
mod face_mesh;
mod fan;
mod figures;
mod fold_cavity;
mod fold_insert;
mod fold_locate;
mod inversion;
mod native;
mod options;
mod part;
mod patch;
mod pole_to_pole;
mod region_vertices;
mod revolution;
mod ruled;
mod ruled_folds;
mod ruled_plane;
mod seamless;
mod step;
mod strip;
mod weld;

pub use figures::{Tessellation, TessellationFigures};
pub use options::{
    BrepError, DEFAULT_CHORD_RATIO, DEFAULT_DIVISIONS, MINIMUM_CHORD_RATIO,
    MINIMUM_MESH_SIZE_RATIO, TessellateError, TessellateOptions,
};
pub use part::tessellate_part;
pub use region_vertices::vertices_inside;
pub use step::{tessellate_brep, tessellate_brep_for_unfold};
pub use weld::Welded;
