//! Part files: a part described as CAD surfaces in TOML (`docs/part-format.md`), read into the
//! CAD model's [`crate::cad::PartModel`]: the part's name, units, quantity, attributes, surfaces,
//! fold lines with their stiffness and stiffness regions. Every defect names the file, the line
//! and the field.

mod bspline;
mod build;
mod checks;
mod errors;
mod features;
mod locate;
mod loops;
mod profile;
mod reader;
mod spec;

pub use errors::{PartError, SpecDefect};
pub use reader::{looks_like_part, parse_part, read_part_text};
