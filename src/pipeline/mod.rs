//! The pipeline: values in, values out. [`load_parts`] reads an input into parts (ingest,
//! tessellate, validate, stiffness), [`flatten_part`] flattens and cuts one; the binary writes the
//! files through [`crate::export`].

mod flatten_part;
mod load;

pub use flatten_part::flatten_part;
pub use load::{
    PartJob, PartResult, RunOptions, TessellationFigures, load_parts, tessellate_part,
};
