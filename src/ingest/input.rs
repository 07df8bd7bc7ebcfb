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
use super::text::without_byte_order_mark;
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
    /// Detects the kind from the file's extension, then its first bytes (after a UTF-8
    /// byte-order mark).
    pub fn detect(path: &Path, bytes: &[u8]) -> Result<Self, IngestError> {
        let text = without_byte_order_mark(bytes);
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
            _ if looks_like_step(text) => Ok(Self::Step),
            _ if looks_like_ply(text) => Ok(Self::Ply),
            _ if looks_like_off(text) => Ok(Self::Off),
            _ if looks_like_part(text) => Ok(Self::Part),
            _ if looks_like_stl(bytes) || looks_like_stl(text) => Ok(Self::Stl),
            _ if looks_like_obj(text) => Ok(Self::Obj),
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
    let text = without_byte_order_mark(bytes);
    let soup = match kind {
        InputKind::Obj => parse_obj(text),
        InputKind::Stl => parse_stl(bytes),
        InputKind::Ply => parse_ply(text),
        InputKind::Off => parse_off(text),
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
        InputKind::Part => Ok(Input::Part(Box::new(read_part_text(
            path,
            without_byte_order_mark(&bytes),
        )?))),
        InputKind::Step => Ok(Input::Step(read_step(
            path,
            without_byte_order_mark(&bytes),
        )?)),
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

    /// A UTF-8 byte-order mark before the first statement is not part of it: an OBJ keeps its
    /// first vertex, OFF and PLY their keyword, an ASCII STL (here in upper case) its `solid`;
    /// each reads as the same square of two triangles, detected by content too.
    #[test]
    fn a_byte_order_mark_is_not_read_as_text() {
        let files: [(&str, &str); 4] = [
            ("obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"),
            ("off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"),
            (
                "ply",
                "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
            ),
            (
                "stl",
                "SOLID SQUARE\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\nVERTEX 1 1 0\nENDLOOP\nENDFACET\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 1 0\nVERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID\n",
            ),
        ];
        let directory = std::env::temp_dir().join(format!("flatcut-bom-{}", std::process::id()));
        std::fs::create_dir_all(&directory).unwrap();
        for (extension, text) in files {
            let bytes = [b"\xEF\xBB\xBF".as_slice(), text.as_bytes()].concat();
            for name in [format!("square.{extension}"), format!("square-{extension}")] {
                let path = directory.join(name);
                std::fs::write(&path, &bytes).unwrap();
                let mesh = read_mesh(&path, Units::Millimetres)
                    .unwrap_or_else(|error| panic!("{}: {error}", path.display()));
                assert_eq!(mesh.soup.positions.len(), 4, "{}", path.display());
                assert_eq!(mesh.soup.triangles.len(), 2, "{}", path.display());
            }
        }
        std::fs::remove_dir_all(&directory).unwrap();
    }
}
