//! Ingest: the only stage that reads files, into the CAD model ([`crate::cad`]): mesh files (OBJ,
//! STL, PLY, OFF) into raw triangle soups in the part's units, part files (TOML) into CAD surfaces with
//! their features, STEP files into a B-rep in millimetres, and a mesh's cut sidecar (user seams,
//! no-cut regions). Nothing here meshes a surface ([`crate::tessellate`] does) or validates a
//! mesh ([`crate::mesh`] does).

mod cut_sidecar;
mod errors;
mod input;
mod obj;
mod off;
mod part;
mod ply;
mod polygon;
mod step;
mod stl;
mod text;

pub use crate::geometry::tolerance::STL_WELD_TOLERANCE;
pub use cut_sidecar::{
    CutSidecar, SidecarRegion, cut_sidecar_path, parse_cut_sidecar, read_cut_sidecar,
};
pub use errors::{FormatDefect, IngestError};
pub use input::{Input, InputKind, MAXIMUM_INPUT_BYTES, MeshInput, read_input, read_mesh};
pub use obj::parse_obj;
pub use off::parse_off;
pub use part::{PartError, SpecDefect, parse_part, read_part_text};
pub use ply::parse_ply;
pub use step::read_step;
pub use stl::parse_stl;
