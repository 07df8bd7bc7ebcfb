//! What stops a batch as a whole (a part's own failure is its status, not an error).

use std::io;
use std::path::PathBuf;

use thiserror::Error;

/// Why a batch cannot run.
#[derive(Debug, Error)]
pub enum BatchError {
    /// A file could not be read.
    #[error("cannot read `{path}`: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: io::Error,
    },
    /// A file or folder could not be written.
    #[error("cannot write `{path}`: {source}")]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        source: io::Error,
    },
    /// A manifest line is wrong.
    #[error("{path}: line {line}: {reason}")]
    Manifest {
        /// The manifest.
        path: PathBuf,
        /// Its line (1-based).
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// An input given on the command line cannot be a part of a batch.
    #[error("`{path}`: {reason}")]
    Input {
        /// The input.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// Two parts have one name.
    #[error("two parts named {name:?} (`{first}` and `{second}`): give them distinct names")]
    DuplicateName {
        /// The name.
        name: String,
        /// The first part's input.
        first: String,
        /// The second part's input.
        second: String,
    },
    /// A part's options are invalid.
    #[error("part {name:?}: {source}")]
    Options {
        /// The part.
        name: String,
        /// What is wrong.
        source: Box<crate::Error>,
    },
    /// A worker process could not be started.
    #[error("cannot start the worker `{program}`: {source}")]
    Worker {
        /// The program.
        program: PathBuf,
        /// Why.
        source: io::Error,
    },
    /// The part's worker was stopped by a signal: its folder keeps its previous run.
    #[error("interrupted: the part's folder keeps its previous run")]
    Interrupted,
    /// A task file handed to a worker is not one.
    #[error("not a batch task: {0}")]
    Task(String),
}
