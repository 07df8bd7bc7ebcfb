//! The CAD model both readers produce and the tessellator consumes: surfaces with their kinds and
//! exact parameters, a part's features (fold lines with their stiffness, stiffness regions) and
//! attributes, the B-rep of a STEP file (shells, faces on exact surfaces, edges on exact curves,
//! face adjacency, the STEP entity of every face), and the raw triangle soup with its fold-edge
//! tags that mesh files are read into and the tessellator produces.
//!
//! Nothing here reads a file or meshes a surface: [`crate::ingest`] builds these values,
//! [`crate::tessellate`] meshes them, [`crate::mesh`] validates soups.

mod brep;
mod face_geometry;
mod features;
mod frame;
mod parameter_region;
mod part;
mod profile;
mod rulings;
mod soup;
mod surface;
mod surface_domain;

pub use brep::{Brep, BrepShell, FaceSource, LooseSurface, StepShell};
pub use face_geometry::SurfaceGeometry;
pub use features::{
    DEFAULT_FOLD_STIFFNESS, FoldBend, FoldLineGeometry, FoldStiffness, RegionShape, SheetSide,
    StiffnessRegion,
};
pub use frame::Frame;
pub use parameter_region::ParameterRegion;
pub use part::{CadPart, PartAttributes, PartModel};
pub use profile::{
    Fraction, Profile, ProfileSegment, fractions_through, pieces_for_arc, pieces_for_length,
};
pub use rulings::{MINIMUM_CIRCLE_PIECES, Rulings, rulings, rulings_through};
pub use soup::{FoldEdge, NO_SOURCE_FACE, SourceLines, SourceUnit, TextureCorners, TriangleSoup};
pub use surface::{
    MappedSurface, PatchGeometry, PatchSurface, RevolutionSurface, RuledCircle, RuledSurface,
    Section, Surface,
};
pub use surface_domain::{HeightBounds, SurfaceDomain};
