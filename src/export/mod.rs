//! Export: the only stage that writes files. Cut files (DXF) a cutting shop accepts, sheet
//! previews (PNG), energy reports (PNG), facet models and patterns (OBJ), the JSON report, and atomic
//! file writing for every output.
//!
//! Values in, bytes out: [`write_part_dxf`] and [`write_sheet_dxf`] return the DXF bytes and
//! [`render_sheet_png`] the PNG bytes; [`write_atomically`] puts bytes under a final name without
//! ever leaving a half-written file there. See `docs/dxf.md` for the layers and entities.

mod atomic;
mod bulge;
pub mod colormap;
mod contour;
mod drawing;
mod dxf;
mod dxf_repair;
mod energy_layout;
pub mod energy_panel;
pub mod energy_png;
mod errors;
pub mod fold_polylines;
pub mod indexed_png;
pub mod legend;
pub mod obj;
mod part_contours;
pub mod part_files;
pub mod raster;
pub mod report;
mod seam;
mod sheet_png;
pub mod sheets;
pub mod text;

pub use atomic::write_atomically;
pub use bulge::{
    BulgeArc, BulgeVertex, STRAIGHT_BULGE, distance_to_line_segment, distance_to_segment,
    polyline_bounds, sample_closed, sample_open, segment_bounds, segment_length,
};
pub use contour::{
    DEFAULT_CHORD_TOLERANCE, DUPLICATE_FRACTION, MAX_ARC_SWEEP, MIN_SEGMENT_LENGTH_IN_TOLERANCES,
    fit_closed, fit_open, signed_area,
};
pub use drawing::{PartDrawing, PlacedPart, SheetDrawing, Units};
pub use dxf::{DxfOptions, DxfVersion, layers, write_part_dxf, write_sheet_dxf};
pub use errors::ExportError;
pub use part_contours::{PartContours, part_contours};
pub use sheet_png::{DEFAULT_PREVIEW_PIXELS, render_sheet_png};
