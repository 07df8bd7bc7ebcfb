//! Export: the only stage that writes files. It writes patterns and layouts, never makes them:
//! cut files (DXF) a cutting shop accepts, sheet previews (PNG), energy reports (PNG), facet
//! models and patterns (OBJ), the JSON report, and atomic file writing for every output.
//!
//! Values in, bytes out: [`write_part_dxf`] and [`write_sheet_dxf`] return the DXF bytes and
//! [`render_sheet_png`] the PNG bytes; [`write_atomically`] puts bytes under a final name without
//! ever leaving a half-written file there. The contours drawn come from the pattern stage
//! ([`crate::pattern`]). See `docs/dxf.md` for the layers and entities.

mod atomic;
pub mod colormap;
mod drawing;
mod dxf;
mod dxf_options;
mod dxf_repair;
mod energy_layout;
mod energy_map;
mod energy_panel;
pub mod energy_png;
mod errors;
mod indexed_png;
mod legend;
pub mod nest_report;
pub mod obj;
pub mod part_files;
mod raster;
pub mod report;
mod sheet_png;
pub mod sheets;
mod text;

pub use atomic::{remove_stale_temporaries, write_atomically};
pub use drawing::{PlacedPart, SheetDrawing};
pub use dxf::{layers, write_part_dxf, write_sheet_dxf};
pub use dxf_options::{DxfOptions, DxfVersion};
pub use errors::ExportError;
pub use sheet_png::{DEFAULT_PREVIEW_PIXELS, render_sheet_png};
