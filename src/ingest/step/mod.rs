//! STEP files (AP203/AP214) read through truck-stepio into the CAD model's B-rep
//! ([`crate::cad::Brep`]): every shell (advanced faces of solids and open shells) with its faces
//! on their exact surfaces, its edges on their curves and the STEP entity of each face, in
//! millimetres; [`crate::tessellate`] meshes it.
//!
//! Input: the file's bytes, in any encoding exporters use (`text.rs`: UTF-8, or ISO 8859-1 raw
//! bytes in names; comments anywhere). The units of the context each shell's representation is in are
//! applied (`units.rs`: a length unit `SI_UNIT` with its prefix or a `CONVERSION_BASED_UNIT`
//! such as the inch, and degrees for cone angles): truck-stepio applies neither. Each shell is
//! converted and scaled to millimetres under `catch_unwind`, so a file that makes truck panic
//! gives an error naming the shell, never a crash; a face truck-stepio drops (its surface is of
//! a kind it cannot read) is an error naming the face and its surface entity. A file with no
//! shell (a surface-only export) gives its loose B-spline and NURBS surfaces, which are meshed
//! over their whole parameter domains.

mod convert;
mod entities;
mod reader;
mod rewrite;
mod statements;
mod text;
mod units;

pub use reader::read_step;
pub use text::looks_like_step;
