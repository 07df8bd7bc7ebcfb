//! The facet model: raw triangle soups, their validation, and the validated mesh with adjacency.

mod chains;
mod facet;
mod rows;
mod soup;
mod validate;

pub use chains::chain_edges;
pub use facet::{FacetModel, NONE};
pub use rows::compressed_rows;
pub use soup::{FoldEdge, NO_SOURCE_FACE, TriangleSoup};
pub use validate::{DEGENERATE_AREA_RATIO, Defect, MeshDefects, ValidatedMesh, validate};
