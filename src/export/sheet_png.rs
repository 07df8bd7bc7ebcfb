//! PNG preview of a nested sheet: the sheet outline, every part filled light with its cut contours,
//! holes left open, fold and sew lines dashed, grain lines with their arrowheads, and each part's
//! name at its label anchor where it fits inside the part.
//!
//! Input: a [`SheetDrawing`] and the same [`DxfOptions`] as its DXF, so the preview shows the
//! contours that will be cut (fitted arcs, seam allowance). Output: PNG bytes, the longer side
//! `pixels` wide, y pointing up as in the DXF.

use super::drawing::SheetDrawing;
use super::dxf::check_sheet;
use super::dxf_options::DxfOptions;
use super::errors::ExportError;
use super::text::{Align, Label, Typeface};
use crate::geometry::bounding_box;
use crate::pattern::{BulgeVertex, PartDrawing, part_contours, sample_closed, sample_open};
use glam::DVec2;
use tiny_skia::{Color, FillRule, Paint, Path, PathBuilder, Pixmap, Stroke, StrokeDash, Transform};

/// Default size of the preview's longer side, in pixels.
pub const DEFAULT_PREVIEW_PIXELS: u32 = 1600;

/// Smallest and largest accepted preview size, in pixels (8192 x 8192 RGBA is 256 MiB).
const PREVIEW_PIXEL_RANGE: (u32, u32) = (16, 8192);

/// Blank border around the sheet, in pixels.
const MARGIN_PIXELS: f64 = 8.0;

/// Largest distance between points drawn along an arc, in pixels.
const ARC_STEP_PIXELS: f64 = 1.0;

/// Largest and smallest size of a part's name, in pixels: a name that would be smaller is left
/// out.
const NAME_PIXELS: (f32, f32) = (14.0, 7.0);

/// Colour of the parts' names (sRGB).
const NAME_COLOUR: [u8; 3] = [20, 30, 60];

/// Dash and gap of fold and sew lines, in pixels.
const DASH_PIXELS: [f32; 2] = [6.0, 4.0];

/// Colours: background, sheet, part fill, cut line, fold line, sew line, grain line (RGBA).
const BACKGROUND: [u8; 4] = [255, 255, 255, 255];
const SHEET_FILL: [u8; 4] = [240, 240, 236, 255];
const SHEET_LINE: [u8; 4] = [110, 110, 110, 255];
const PART_FILL: [u8; 4] = [190, 215, 240, 255];
const CUT_LINE: [u8; 4] = [20, 60, 140, 255];
const FOLD_LINE: [u8; 4] = [30, 140, 60, 255];
const SEW_LINE: [u8; 4] = [170, 40, 150, 255];
const GRAIN_LINE: [u8; 4] = [200, 120, 0, 255];

/// Renders the sheet preview as PNG bytes, its longer side `pixels` wide.
pub fn render_sheet_png(
    sheet: &SheetDrawing,
    options: &DxfOptions,
    pixels: u32,
) -> Result<Vec<u8>, ExportError> {
    check_sheet(sheet)?;
    let (smallest, largest) = PREVIEW_PIXEL_RANGE;
    if !(smallest..=largest).contains(&pixels) {
        return Err(ExportError::InvalidPreviewSize { pixels });
    }
    let view = View::fit(sheet, pixels);
    let mut pixmap =
        Pixmap::new(view.width, view.height).ok_or(ExportError::InvalidPreviewSize { pixels })?;
    pixmap.fill(colour(BACKGROUND));
    if let Some(outline) = view.path(&[sheet.corners().to_vec()], true) {
        fill(&mut pixmap, &outline, SHEET_FILL);
        stroke(&mut pixmap, &outline, SHEET_LINE, None);
    }
    for placed in &sheet.parts {
        let contours = part_contours(&placed.drawing, &options.pattern)?;
        let step = ARC_STEP_PIXELS / view.scale;
        let cut: Vec<Vec<DVec2>> = std::iter::once(&contours.outer)
            .chain(&contours.holes)
            .map(|contour| sample_closed(contour, step))
            .collect();
        if let Some(path) = view.path(&cut, true) {
            fill(&mut pixmap, &path, PART_FILL);
            stroke(&mut pixmap, &path, CUT_LINE, None);
        }
        draw_dashed(&mut pixmap, &view, &contours.sew_lines, true, SEW_LINE);
        draw_dashed(&mut pixmap, &view, &contours.fold_lines, false, FOLD_LINE);
        if let Some((line, arrowhead)) = placed.drawing.grain_arrow()
            && let Some(path) = view.path(&[line.to_vec(), arrowhead.to_vec()], false)
        {
            stroke(&mut pixmap, &path, GRAIN_LINE, None);
        }
    }
    let typeface = Typeface::embedded()
        .map_err(|error| ExportError::Png(format!("embedded font: {error}")))?;
    for placed in &sheet.parts {
        draw_name(&mut pixmap, &view, &typeface, &placed.drawing);
    }
    pixmap
        .encode_png()
        .map_err(|error| ExportError::Png(error.to_string()))
}

/// The part's name, centred on its label anchor, as large as fits in 80 % of the part's width
/// (up to [`NAME_PIXELS`]); left out when it would be too small to read.
fn draw_name(pixmap: &mut Pixmap, view: &View, typeface: &Typeface, drawing: &PartDrawing) {
    let Some(anchor) = drawing.label_anchor() else {
        return;
    };
    let (low, high) = bounding_box(&drawing.outer);
    let (largest, smallest) = NAME_PIXELS;
    let room = (0.8 * (high.x - low.x) * view.scale) as f32;
    let width_at_largest = typeface.width(&drawing.name, largest).max(f32::EPSILON);
    let size = (largest * room / width_at_largest).min(largest);
    if size < smallest {
        return;
    }
    let (x, y) = view.to_pixels(anchor);
    typeface.draw(
        pixmap,
        &Label {
            text: &drawing.name,
            x,
            baseline: y + 0.35 * size,
            size,
            colour: NAME_COLOUR,
            align: Align::Centre,
        },
    );
}

/// Dashed lines (sew or fold), closed or open.
fn draw_dashed(
    pixmap: &mut Pixmap,
    view: &View,
    lines: &[Vec<BulgeVertex>],
    closed: bool,
    rgba: [u8; 4],
) {
    let step = ARC_STEP_PIXELS / view.scale;
    let sampled: Vec<Vec<DVec2>> = lines
        .iter()
        .map(|line| {
            if closed {
                sample_closed(line, step)
            } else {
                sample_open(line, step)
            }
        })
        .collect();
    if let Some(path) = view.path(&sampled, closed) {
        stroke(
            pixmap,
            &path,
            rgba,
            StrokeDash::new(DASH_PIXELS.to_vec(), 0.0),
        );
    }
}

/// Sheet-to-pixel mapping: uniform scale, y flipped, a margin all round.
struct View {
    scale: f64,
    sheet_height: f64,
    width: u32,
    height: u32,
}

impl View {
    /// The mapping that fits the sheet's longer side into `pixels`, margins included.
    fn fit(sheet: &SheetDrawing, pixels: u32) -> Self {
        let drawable = (f64::from(pixels) - 2.0 * MARGIN_PIXELS).max(1.0);
        let scale = drawable / sheet.width.max(sheet.height);
        let size =
            |length: f64| ((length * scale + 2.0 * MARGIN_PIXELS).round() as u32).clamp(1, pixels);
        Self {
            scale,
            sheet_height: sheet.height,
            width: size(sheet.width),
            height: size(sheet.height),
        }
    }

    /// A sheet point in pixels.
    fn to_pixels(&self, point: DVec2) -> (f32, f32) {
        let x = MARGIN_PIXELS + point.x * self.scale;
        let y = MARGIN_PIXELS + (self.sheet_height - point.y) * self.scale;
        (x as f32, y as f32)
    }

    /// One path of several polylines in sheet coordinates, each closed or not; `None` when empty.
    fn path(&self, polylines: &[Vec<DVec2>], closed: bool) -> Option<Path> {
        let mut builder = PathBuilder::new();
        for polyline in polylines {
            let Some((first, rest)) = polyline.split_first() else {
                continue;
            };
            let (x, y) = self.to_pixels(*first);
            builder.move_to(x, y);
            for point in rest {
                let (x, y) = self.to_pixels(*point);
                builder.line_to(x, y);
            }
            if closed {
                builder.close();
            }
        }
        builder.finish()
    }
}

/// A tiny-skia colour from RGBA bytes.
fn colour([red, green, blue, alpha]: [u8; 4]) -> Color {
    Color::from_rgba8(red, green, blue, alpha)
}

/// A solid anti-aliased paint.
fn paint(rgba: [u8; 4]) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color(colour(rgba));
    paint.anti_alias = true;
    paint
}

/// Fills a path, holes (inner rings) left open.
fn fill(pixmap: &mut Pixmap, path: &Path, rgba: [u8; 4]) {
    pixmap.fill_path(
        path,
        &paint(rgba),
        FillRule::EvenOdd,
        Transform::identity(),
        None,
    );
}

/// Strokes a path one pixel wide, dashed when a dash is given.
fn stroke(pixmap: &mut Pixmap, path: &Path, rgba: [u8; 4], dash: Option<StrokeDash>) {
    let stroke = Stroke {
        width: 1.0,
        dash,
        ..Default::default()
    };
    pixmap.stroke_path(path, &paint(rgba), &stroke, Transform::identity(), None);
}

#[cfg(test)]
mod tests {
    use crate::export::drawing::PlacedPart;
    use crate::export::sheet_png::*;
    use crate::pattern::PartDrawing;

    /// A 1000 x 500 sheet with one 200 x 100 plate at (100, 100) that has a 20 x 20 hole.
    fn sheet() -> SheetDrawing {
        let rectangle = |low: DVec2, size: DVec2| {
            vec![
                low,
                low + DVec2::new(size.x, 0.0),
                low + size,
                low + DVec2::new(0.0, size.y),
            ]
        };
        let plate = PartDrawing {
            name: "plate".into(),
            quantity: 1,
            outer: rectangle(DVec2::new(100.0, 100.0), DVec2::new(200.0, 100.0)),
            holes: vec![rectangle(DVec2::new(240.0, 140.0), DVec2::splat(20.0))],
            ..Default::default()
        };
        SheetDrawing {
            index: 1,
            width: 1000.0,
            height: 500.0,
            parts: vec![PlacedPart { drawing: plate }],
            ..Default::default()
        }
    }

    /// The colour of the preview pixel over a sheet point.
    fn pixel_at(pixmap: &Pixmap, view: &View, point: DVec2) -> [u8; 4] {
        let (x, y) = view.to_pixels(point);
        let pixel = pixmap.pixel(x as u32, y as u32).expect("inside the image");
        [pixel.red(), pixel.green(), pixel.blue(), pixel.alpha()]
    }

    #[test]
    fn preview_fills_parts_and_leaves_holes_open() {
        let sheet = sheet();
        let bytes = render_sheet_png(&sheet, &DxfOptions::default(), 500).expect("renders");
        let pixmap = Pixmap::decode_png(&bytes).expect("a PNG");
        // 484 pixels for 1000 mm, plus an 8-pixel margin on each side.
        assert_eq!((pixmap.width(), pixmap.height()), (500, 258));
        let view = View::fit(&sheet, 500);
        assert_eq!(
            pixel_at(&pixmap, &view, DVec2::new(150.0, 150.0)),
            PART_FILL
        );
        assert_eq!(
            pixel_at(&pixmap, &view, DVec2::new(250.0, 150.0)),
            SHEET_FILL
        );
        assert_eq!(
            pixel_at(&pixmap, &view, DVec2::new(600.0, 300.0)),
            SHEET_FILL
        );
    }

    /// Pixels of the preview darker than any fill or line colour but the names', around a sheet
    /// point (a square of `radius` pixels).
    fn name_pixels(pixmap: &Pixmap, view: &View, point: DVec2, radius: i64) -> usize {
        let (x, y) = view.to_pixels(point);
        let (x, y) = (x as i64, y as i64);
        let mut count = 0;
        for dy in -radius..=radius {
            for dx in -radius..=radius {
                let Some(pixel) = pixmap.pixel((x + dx) as u32, (y + dy) as u32) else {
                    continue;
                };
                if u16::from(pixel.red()) + u16::from(pixel.green()) < 150 && pixel.blue() < 120 {
                    count += 1;
                }
            }
        }
        count
    }

    #[test]
    fn each_part_is_named_where_its_name_fits() {
        let mut sheet = sheet();
        let options = DxfOptions::default();
        let pixmap =
            Pixmap::decode_png(&render_sheet_png(&sheet, &options, 1000).expect("renders"))
                .expect("a PNG");
        let view = View::fit(&sheet, 1000);
        let anchor = sheet.parts[0].drawing.label_anchor().expect("an anchor");
        assert!(
            name_pixels(&pixmap, &view, anchor, 12) > 10,
            "the name is written"
        );
        // A part a few millimetres wide has no room for its name.
        for point in &mut sheet.parts[0].drawing.outer {
            *point = DVec2::new(100.0, 100.0) + (*point - DVec2::new(100.0, 100.0)) * 0.04;
        }
        sheet.parts[0].drawing.holes.clear();
        let pixmap =
            Pixmap::decode_png(&render_sheet_png(&sheet, &options, 1000).expect("renders"))
                .expect("a PNG");
        let anchor = sheet.parts[0].drawing.label_anchor().expect("an anchor");
        assert_eq!(
            name_pixels(&pixmap, &view, anchor, 12),
            0,
            "no unreadable name"
        );
    }

    #[test]
    fn preview_is_deterministic_and_checks_its_size() {
        let sheet = sheet();
        let options = DxfOptions::default();
        let first = render_sheet_png(&sheet, &options, 300).expect("renders");
        assert!(first == render_sheet_png(&sheet, &options, 300).expect("renders"));
        assert!(matches!(
            render_sheet_png(&sheet, &options, 4),
            Err(ExportError::InvalidPreviewSize { pixels: 4 })
        ));
    }
}
