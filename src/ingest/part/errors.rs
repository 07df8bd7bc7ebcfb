//! Errors of part files: each names the file, the line (when the field can be located) and the
//! field, and says what to change.

use std::fmt;
use std::path::PathBuf;

/// A part file that cannot be turned into surfaces.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{path}:{location}{field}: {message}", path = path.display(), location = LineDisplay(*line), field = FieldDisplay(field))]
pub struct PartError {
    /// The part file.
    pub path: PathBuf,
    /// 1-based line of the offending field, when known.
    pub line: Option<usize>,
    /// Dotted path of the offending field (`surface[2].radius`), when known.
    pub field: String,
    /// What is wrong and what to do.
    pub message: String,
}

struct LineDisplay(Option<usize>);

impl fmt::Display for LineDisplay {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(line) => write!(f, "{line}: "),
            None => write!(f, " "),
        }
    }
}

struct FieldDisplay<'a>(&'a String);

impl fmt::Display for FieldDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            write!(f, "part file")
        } else {
            write!(f, "field '{}'", self.0)
        }
    }
}

/// A defect found while building geometry, before the file and line are attached.
#[derive(Debug, Clone, PartialEq)]
pub struct SpecDefect {
    /// Dotted path of the field, relative to the table that was being built (`radius`).
    pub field: String,
    /// What is wrong and what to do.
    pub message: String,
}

impl SpecDefect {
    /// A defect of `field`.
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            message: message.into(),
        }
    }
}
