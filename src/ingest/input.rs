//! Input files by kind: detection from the extension and the content, and the reading of each
//! kind into the CAD model.

use std::path::Path;

use super::errors::IngestError;
use super::obj::{looks_like_obj, parse_obj};
use super::off::{looks_like_off, parse_off};
use super::part::{looks_like_part, read_part_text};
use super::ply::{looks_like_ply, parse_ply};
use super::step::{looks_like_step, read_step};
use super::stl::{looks_like_stl, parse_stl};
use crate::cad::{Brep, PartModel, TriangleSoup};
use crate::units::Units;

/// The kinds of input file flatcut reads, detected from the extension and the content.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputKind {
    /// Wavefront OBJ mesh.
    Obj,
    /// STL mesh, ASCII or binary.
    Stl,
    /// PLY mesh, ASCII or binary.
    Ply,
    /// OFF mesh.
    Off,
    /// A part file (TOML) describing CAD surfaces.
    Part,
    /// A STEP file (AP203/AP214).
    Step,
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
            Some("ply") => Ok(Self::Ply),
            Some("off") => Ok(Self::Off),
            Some("toml") => Ok(Self::Part),
            Some("step" | "stp") => Ok(Self::Step),
            _ if looks_like_step(bytes) => Ok(Self::Step),
            _ if looks_like_ply(bytes) => Ok(Self::Ply),
            _ if looks_like_off(bytes) => Ok(Self::Off),
            _ if looks_like_part(bytes) => Ok(Self::Part),
            _ if looks_like_stl(bytes) => Ok(Self::Stl),
            _ if looks_like_obj(bytes) => Ok(Self::Obj),
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

/// Largest input file read, in bytes (2 GiB: an OBJ of some 30 million triangles, far beyond
/// what can be flattened; a bigger file is almost surely not a part).
pub const MAXIMUM_INPUT_BYTES: u64 = 2 << 30;

/// The bytes of an input file, refused before reading when larger than [`MAXIMUM_INPUT_BYTES`].
fn read_bytes(path: &Path) -> Result<Vec<u8>, IngestError> {
    let read_error = |source| IngestError::Read {
        path: path.to_path_buf(),
        source,
    };
    let size = std::fs::metadata(path).map_err(read_error)?.len();
    if size > MAXIMUM_INPUT_BYTES {
        return Err(IngestError::TooLarge {
            path: path.to_path_buf(),
            bytes: size,
            limit: MAXIMUM_INPUT_BYTES,
        });
    }
    std::fs::read(path).map_err(read_error)
}

/// Reads a mesh file (OBJ, STL, PLY or OFF) whose coordinates are in `units`.
pub fn read_mesh(path: &Path, units: Units) -> Result<MeshInput, IngestError> {
    let bytes = read_bytes(path)?;
    let kind = InputKind::detect(path, &bytes)?;
    mesh_from_bytes(path, kind, &bytes, units)
}

fn mesh_from_bytes(
    path: &Path,
    kind: InputKind,
    bytes: &[u8],
    units: Units,
) -> Result<MeshInput, IngestError> {
    let soup = match kind {
        InputKind::Obj => parse_obj(bytes),
        InputKind::Stl => parse_stl(bytes),
        InputKind::Ply => parse_ply(bytes),
        InputKind::Off => parse_off(bytes),
        InputKind::Part | InputKind::Step => {
            return Err(IngestError::NotAMesh {
                path: path.to_path_buf(),
            });
        }
    }
    .map_err(|defect| defect.in_file(path))?;
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("part")
        .to_string();
    Ok(MeshInput { name, units, soup })
}

/// Any input file, read according to its kind into the CAD model.
#[derive(Debug, Clone)]
pub enum Input {
    /// A triangle mesh.
    Mesh(MeshInput),
    /// A part file's surfaces and features.
    Part(Box<PartModel>),
    /// A STEP file's B-rep.
    Step(Brep),
}

/// Reads any input: meshes in `units`; part and STEP files carry their own units.
pub fn read_input(path: &Path, units: Units) -> Result<Input, IngestError> {
    let bytes = read_bytes(path)?;
    match InputKind::detect(path, &bytes)? {
        InputKind::Part => Ok(Input::Part(Box::new(read_part_text(path, &bytes)?))),
        InputKind::Step => Ok(Input::Step(read_step(path, &bytes)?)),
        kind => mesh_from_bytes(path, kind, &bytes, units).map(Input::Mesh),
    }
}

#[cfg(test)]
mod tests {
    use crate::ingest::input::*;

    #[test]
    fn kinds_are_detected_from_extension_then_content() {
        let detect = |name: &str, bytes: &[u8]| InputKind::detect(Path::new(name), bytes).ok();
        assert_eq!(detect("a.toml", b""), Some(InputKind::Part));
        assert_eq!(detect("a.STP", b""), Some(InputKind::Step));
        assert_eq!(detect("a.step", b""), Some(InputKind::Step));
        assert_eq!(
            detect("a", b"ISO-10303-21;\nHEADER;"),
            Some(InputKind::Step)
        );
        assert_eq!(
            detect("a", b"name = \"x\"\n[[surface]]\nkind = \"cone\"\n"),
            Some(InputKind::Part)
        );
        assert_eq!(detect("a", b"hello"), None);
    }
}
