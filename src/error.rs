//! The library's top-level error: what went wrong, naming the file or part and the defect.

use std::path::PathBuf;

use crate::cut::CutError;
use crate::export::ExportError;
use crate::export::energy_png::EnergyPngError;
use crate::flatten::FlattenError;
use crate::ingest::IngestError;
use crate::mesh::MeshDefects;

/// An error of a flatcut run.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An input file could not be read or parsed.
    #[error(transparent)]
    Ingest(#[from] IngestError),
    /// An input mesh has defects that stop it from being flattened.
    #[error("{path}: the mesh cannot be used: {defects}")]
    Mesh {
        /// The input file.
        path: PathBuf,
        /// Every defect found.
        defects: MeshDefects,
    },
    /// A part's surfaces could not be tessellated.
    #[error("{path}: cannot tessellate: {defect}")]
    Tessellate {
        /// The input file.
        path: PathBuf,
        /// Why.
        defect: crate::tessellate::TessellateError,
    },
    /// A STEP file's B-rep could not be tessellated.
    #[error("{path}: {defect}")]
    Brep {
        /// The input file.
        path: PathBuf,
        /// Why, naming the shell and face or the surface.
        defect: crate::tessellate::BrepError,
    },
    /// A part could not be flattened.
    #[error("{path}: part '{part}': {source}")]
    Flatten {
        /// The input file.
        path: PathBuf,
        /// The part's name.
        part: String,
        /// Why.
        source: FlattenError,
    },
    /// A part could not be opened by seams, cut or flattened after cutting.
    #[error("{path}: part '{part}': {reason}")]
    Cut {
        /// The input file.
        path: PathBuf,
        /// The part's name.
        part: String,
        /// Why (in the message, not repeated as a source).
        reason: CutError,
    },
    /// An output file could not be written.
    #[error("{path}: cannot write: {source}")]
    Write {
        /// The output file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A part's cut file (or a sheet's) could not be drawn.
    #[error("{path}: part '{part}': cannot write its DXF: {source}")]
    Export {
        /// The input file the part came from (the sheet's file for a sheet).
        path: PathBuf,
        /// The part's name.
        part: String,
        /// Why.
        source: ExportError,
    },
    /// A part's energy map could not be drawn.
    #[error("{path}: part '{part}': cannot draw its energy map: {source}")]
    EnergyMap {
        /// The input file the part came from.
        path: PathBuf,
        /// The part's name.
        part: String,
        /// Why.
        source: EnergyPngError,
    },
}
