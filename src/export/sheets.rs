//! Nested sheets as drawings and files: `sheets/sheet-NNN.dxf` with the sheet outline and every
//! placed part, and `sheets/sheet-NNN.png`, a preview. Sheets are drawn in millimetres.

use std::path::{Path, PathBuf};

use glam::DVec2;

use super::atomic::write_atomically;
use super::drawing::{PlacedPart, SheetDrawing};
use super::dxf::write_sheet_dxf;
use super::dxf_options::DxfOptions;
use super::errors::ExportError;
use super::sheet_png::{DEFAULT_PREVIEW_PIXELS, render_sheet_png};
use crate::nest::{NestLayout, Placement};
use crate::pattern::PartDrawing;
use crate::units::Units;

/// The drawing of every sheet of a layout; `drawings[i]` is the part of nesting item `i`.
pub fn sheet_drawings(drawings: &[PartDrawing], layout: &NestLayout) -> Vec<SheetDrawing> {
    layout
        .sheets
        .iter()
        .enumerate()
        .map(|(index, sheet)| SheetDrawing {
            index: index + 1,
            units: Units::Millimetres,
            width: sheet.width,
            height: sheet.height,
            parts: sheet
                .placements
                .iter()
                .map(|placement| PlacedPart {
                    drawing: placed(&drawings[placement.item], placement),
                })
                .collect(),
        })
        .collect()
}

/// A part drawing in millimetres, moved to where the placement puts it.
fn placed(drawing: &PartDrawing, placement: &Placement) -> PartDrawing {
    let scale = drawing.units.millimetres();
    let ring = |ring: &Vec<DVec2>| {
        let millimetres: Vec<DVec2> = ring.iter().map(|&p| p * scale).collect();
        placement.transform_ring(&millimetres)
    };
    let point = |p: DVec2| placement.transform_point(p * scale);
    PartDrawing {
        units: Units::Millimetres,
        quantity: 1,
        outer: ring(&drawing.outer),
        holes: drawing.holes.iter().map(ring).collect(),
        fold_lines: drawing
            .fold_lines
            .iter()
            .map(|line| line.iter().map(|&p| point(p)).collect())
            .collect(),
        grain: drawing.grain.map(|[tail, head]| [point(tail), point(head)]),
        bends: drawing
            .bends
            .iter()
            .map(|bend| bend.placed(point, placement.mirrored))
            .collect(),
        ..drawing.clone()
    }
}

/// The folder, in an output folder, that a run's sheet files go in.
pub const SHEETS_FOLDER: &str = "sheets";

/// Writes `sheet-NNN.dxf` and `.png` for every sheet into `directory/folder` (`folder` is
/// [`SHEETS_FOLDER`] for a run, or a folder inside it), and returns the DXF paths relative to
/// `directory`.
pub fn write_sheet_files(
    directory: &Path,
    folder: &Path,
    sheets: &[SheetDrawing],
    options: &DxfOptions,
) -> Result<Vec<PathBuf>, ExportError> {
    let relative = folder;
    let folder = directory.join(relative);
    std::fs::create_dir_all(&folder).map_err(|source| ExportError::Write {
        path: folder.clone(),
        source,
    })?;
    let mut files = Vec::with_capacity(sheets.len());
    for sheet in sheets {
        let stem = format!("sheet-{:03}", sheet.index);
        let export_error = |source| ExportError::Drawing {
            path: folder.join(format!("{stem}.dxf")),
            part: stem.clone(),
            source: Box::new(source),
        };
        let dxf = write_sheet_dxf(sheet, options).map_err(export_error)?;
        let png = render_sheet_png(sheet, options, DEFAULT_PREVIEW_PIXELS).map_err(export_error)?;
        for (extension, bytes) in [("dxf", &dxf), ("png", &png)] {
            let path = folder.join(format!("{stem}.{extension}"));
            write_atomically(&path, bytes).map_err(|source| ExportError::Write { path, source })?;
        }
        files.push(relative.join(format!("{stem}.dxf")));
    }
    Ok(files)
}
