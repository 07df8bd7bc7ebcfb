//! Errors of the ingest stage. Each names the file, and where it can, the line.

use std::path::PathBuf;

/// An input file that could not be read or understood.
#[derive(Debug, thiserror::Error)]
pub enum IngestError {
    /// The file could not be opened or read.
    #[error("{path}: cannot read the file: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The file is larger than flatcut reads (`limit`, `ingest::MAXIMUM_INPUT_BYTES`).
    #[error(
        "{path}: the file is {:.1} GiB, above the {} GiB flatcut reads; split or decimate it",
        *bytes as f64 / (1u64 << 30) as f64,
        limit >> 30
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size in bytes.
        bytes: u64,
        /// The largest size read, in bytes.
        limit: u64,
    },
    /// Neither the extension nor the content says what the file is.
    #[error(
        "{path}: unknown input kind; give a .obj, .stl, .ply or .off mesh, a .toml part file or a .step file"
    )]
    UnknownKind {
        /// The file.
        path: PathBuf,
    },
    /// A cut sidecar (`part.cut.json`) is malformed or does not fit the mesh.
    #[error("{path}: {message}")]
    Sidecar {
        /// The sidecar file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A part or STEP file was given where only a mesh is read.
    #[error("{path}: not a mesh file; part and STEP files are read with read_input")]
    NotAMesh {
        /// The file.
        path: PathBuf,
    },
    /// A STEP file cannot be used.
    #[error("{path}: {message}")]
    Step {
        /// The file.
        path: PathBuf,
        /// What is wrong, naming the entity.
        message: String,
    },
    /// A part file is malformed or describes impossible geometry.
    #[error(transparent)]
    Part(#[from] super::part::PartError),
    /// The content is malformed.
    #[error("{path}: {defect}")]
    Malformed {
        /// The file.
        path: PathBuf,
        /// What is wrong, and where.
        defect: FormatDefect,
    },
}

/// What is wrong with a file's content, before the file's name is known to the parser.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FormatDefect {
    /// The file holds no triangles.
    #[error("the file holds no triangles")]
    Empty,
    /// A line could not be parsed.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A binary file's size disagrees with its header.
    #[error("{0}")]
    Binary(String),
}

impl FormatDefect {
    /// Attaches the file name.
    pub fn in_file(self, path: &std::path::Path) -> IngestError {
        IngestError::Malformed {
            path: path.to_path_buf(),
            defect: self,
        }
    }
}
