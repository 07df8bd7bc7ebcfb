//! flatcut: flat cut patterns from 3D surfaces, by the spring-mass energy model of Wang, Smith
//! and Yuen (Computer-Aided Design, 2002).
//!
//! The pipeline runs one way, each stage a module that takes values and returns values:
//! `ingest` (files to the `cad` model: surfaces, B-reps, triangle soups) → `tessellate` (CAD
//! model to triangle soup) → `mesh` (validated facet models) → `flatten` (the paper's energy
//! model; a thin STEP solid goes to `sheet` instead, unfolded exactly with a bend allowance) → `cut`
//! → `pattern` (outlines, cut contours, bend lines) → `nest` → `export` (the only module that
//! writes files); `pipeline` owns the whole run, and `batch` runs many parts, each in a worker
//! process. `docs/architecture.md` draws the stages.

#![warn(missing_docs)]

pub mod batch;
pub mod cad;
pub mod cut;
pub mod error;
pub mod export;
pub mod flatten;
pub mod geometry;
pub mod ingest;
pub mod mesh;
pub mod nest;
pub mod pattern;
pub mod pipeline;
pub mod progress;
pub mod sheet;
pub mod tessellate;
pub mod units;

pub use error::Error;
