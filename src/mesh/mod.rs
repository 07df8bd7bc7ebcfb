//! The facet model: raw triangle soups ([`crate::cad::TriangleSoup`]) validated into checked
//! facet models with adjacency, one per connected component.

mod chains;
mod defects;
mod facet;
mod rebuild;
mod repair;
mod rows;
mod section;
mod section_fairing;
mod slivers;
mod texture_seams;
mod validate;
mod vertex_move;

pub use crate::cad::{FoldEdge, NO_SOURCE_FACE, SourceLines, TextureCorners, TriangleSoup};
pub use crate::geometry::tolerance::DEGENERATE_AREA_RATIO;
pub use chains::chain_edges;
pub use defects::{Defect, MAXIMUM_COORDINATE, MeshDefects};
pub use facet::{FacetModel, NONE};
pub use rebuild::{RebuildError, rebuild, rebuild_split};
pub use repair::{NAMED_WELDS, cut_open_non_orientable, split_non_manifold, weld_duplicates};
pub use rows::compressed_rows;
#[cfg(test)]
pub(crate) use section::tests::grid as test_grid;
pub use section::{
    EdgeOrigin, MAX_FAN_AREA_CHANGE, Plane, SECTION_SNAP, SectionPiece, VertexOrigin,
    principal_axes, section,
};
pub use slivers::repair_degenerate_triangles;
pub use texture_seams::{SeamSource, split_at_texture_seams};
pub use validate::{UNWELDED_SHARE, ValidatedMesh, check_welded, validate};
pub use vertex_move::{MAX_MOVED_FACE_TURN, can_move_vertex, smallest_angle};
