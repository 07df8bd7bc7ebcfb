//! Ingest: the only stage that reads files. Turns mesh files (OBJ, STL) into raw
//! [`TriangleSoup`]s in the part's units, and reads a mesh's cut sidecar (user seams, no-cut
//! regions); validation happens in [`crate::mesh`].

mod cut_sidecar;
mod errors;
mod obj;
mod stl;

use std::path::Path;

pub use cut_sidecar::{cut_sidecar_path, read_cut_sidecar};
pub use errors::{FormatDefect, IngestError};
pub use obj::parse_obj;
pub use stl::{STL_WELD_TOLERANCE, parse_stl};

use crate::mesh::TriangleSoup;
use crate::units::Units;

/// The kinds of input file flatcut reads, detected from the extension and the content.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputKind {
    /// Wavefront OBJ mesh.
    Obj,
    /// STL mesh, ASCII or binary.
    Stl,
}

impl InputKind {
    /// Detects the kind from the file's extension, then its first bytes.
    pub fn detect(path: &Path, bytes: &[u8]) -> Result<Self, IngestError> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("obj") => Ok(Self::Obj),
            Some("stl") => Ok(Self::Stl),
            _ if stl::looks_like_stl(bytes) => Ok(Self::Stl),
            _ if obj::looks_like_obj(bytes) => Ok(Self::Obj),
            _ => Err(IngestError::UnknownKind {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// A mesh read from a file, with the name and units it carries.
#[derive(Debug, Clone)]
pub struct MeshInput {
    /// Part name: the file stem.
    pub name: String,
    /// Units of the coordinates.
    pub units: Units,
    /// The triangles as read.
    pub soup: TriangleSoup,
}

/// Reads a mesh file (OBJ or STL) whose coordinates are in `units`.
pub fn read_mesh(path: &Path, units: Units) -> Result<MeshInput, IngestError> {
    let bytes = std::fs::read(path).map_err(|source| IngestError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let soup = match InputKind::detect(path, &bytes)? {
        InputKind::Obj => parse_obj(&bytes),
        InputKind::Stl => parse_stl(&bytes),
    }
    .map_err(|defect| defect.in_file(path))?;
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("part")
        .to_string();
    Ok(MeshInput { name, units, soup })
}
