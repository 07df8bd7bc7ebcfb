//! Export: the only stage that writes files. Every file is written to a temporary name in its
//! directory and renamed, so a failure never leaves a half-written file under a final name.

pub mod atomic;
pub mod colormap;
mod energy_layout;
pub mod energy_panel;
pub mod energy_png;
pub mod fold_polylines;
pub mod legend;
pub mod obj;
pub mod raster;
pub mod report;
pub mod text;

pub use atomic::write_atomically;
