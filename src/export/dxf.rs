//! DXF cut files a cutting shop accepts: one part (`<part>.dxf`) or one nested sheet
//! (`sheets/sheet-NNN.dxf`), as bytes.
//!
//! Every cut contour is one closed polyline (LWPOLYLINE in R2000, POLYLINE with VERTEX entities in
//! R12) of straight segments and true arcs (bulges), fitted within the chord tolerance by the
//! pattern stage ([`crate::pattern::part_contours`]); no SPLINE or ELLIPSE anywhere. Layers are listed in [`layers`]. Nominal
//! geometry: the CAM adds kerf. `$INSUNITS` and `$MEASUREMENT` state the units in R2000; R12 has
//! neither, so the report must state them. The output is deterministic: the creation and update
//! dates and the drawing GUIDs are fixed, handles are assigned in drawing order.

use super::drawing::SheetDrawing;
use super::dxf_options::{DxfOptions, DxfVersion};
use super::dxf_repair::repair;
use super::errors::ExportError;
use crate::pattern::{
    BulgeVertex, LABEL_CHARACTER_WIDTH, PartContours, PartDrawing, part_contours, polyline_bounds,
};
use crate::sheet::BendDirection;
use crate::units::Units;
use dxf::entities::{Entity, EntityType, Line, LwPolyline, Polyline, Text, Vertex};
use dxf::enums::{AcadVersion, DrawingUnits, Units as DxfUnits};
use dxf::tables::{Layer, LineType};
use dxf::{Color, Drawing, LwPolylineVertex, Point};
use glam::DVec2;

/// Layer names, colours (AutoCAD colour index) and line types.
pub mod layers {
    /// Outer cut contours. Red, continuous.
    pub const CUT_OUTER: &str = "CUT_OUTER";
    /// Inner cut-outs (holes). Blue, continuous.
    pub const CUT_INNER: &str = "CUT_INNER";
    /// Fold and bend lines: drawn, never cut. Green, dashed.
    pub const FOLD: &str = "FOLD";
    /// Sew lines of a part cut with a seam allowance: drawn, never cut. Magenta, dashed.
    pub const SEW: &str = "SEW";
    /// Marks: grain line with its arrowhead and label (part name, quantity, material). Yellow,
    /// continuous; not cut.
    pub const MARKS: &str = "MARKS";
    /// The sheet outline, in sheet files. Grey, continuous; not cut.
    pub const SHEET: &str = "SHEET";
    /// Bend lines of sheet-metal parts folding up (towards the viewer): drawn, never cut.
    /// Green, dashed; the bend's note is on [`MARKS`].
    pub const BEND_UP: &str = "BEND_UP";
    /// Bend lines of sheet-metal parts folding down (away from the viewer): drawn, never cut.
    /// Cyan, dashed; the bend's note is on [`MARKS`].
    pub const BEND_DOWN: &str = "BEND_DOWN";
    /// Bend-zone extent lines of sheet-metal parts (`--bend-zones`): the two tangent lines of
    /// each bend, where the flat starts to bend; drawn, never cut. Grey (ACI 9), continuous.
    pub const BEND_ZONE: &str = "BEND_ZONE";
    /// Name of the dashed line type of the fold, sew and bend layers (defined in every file).
    pub const DASHED: &str = "DASHED";
    /// Every layer flatcut defines: name, colour index, line type.
    pub const ALL: [(&str, u8, &str); 9] = [
        (CUT_OUTER, 1, "CONTINUOUS"),
        (CUT_INNER, 5, "CONTINUOUS"),
        (FOLD, 3, DASHED),
        (SEW, 6, DASHED),
        (MARKS, 2, "CONTINUOUS"),
        (SHEET, 8, "CONTINUOUS"),
        (BEND_UP, 3, DASHED),
        (BEND_DOWN, 4, DASHED),
        (BEND_ZONE, 9, "CONTINUOUS"),
    ];
}

/// Label text height as a fraction of the part's smaller bounding-box side, clamped to
/// [`LABEL_HEIGHT_RANGE_MM`].
const LABEL_HEIGHT_FRACTION: f64 = 0.05;

/// Smallest and largest label text height, in mm.
const LABEL_HEIGHT_RANGE_MM: (f64, f64) = (2.0, 10.0);

/// Height of a bend's note as a fraction of the label's.
const BEND_NOTE_HEIGHT_FRACTION: f64 = 0.5;

/// Dash and gap of the dashed line type, in mm (ISO 128 long dash).
const DASH_PATTERN_MM: [f64; 2] = [12.7, -6.35];

/// Fixed creation and update date (2000-01-01 12:00 as a Julian date) and nil GUIDs, read through
/// the dxf crate, whose own defaults are the current time and random GUIDs.
const FIXED_HEADER: &str = "0\nSECTION\n2\nHEADER\n\
9\n$TDCREATE\n40\n2451545.0\n9\n$TDUCREATE\n40\n2451545.0\n\
9\n$TDUPDATE\n40\n2451545.0\n9\n$TDUUPDATE\n40\n2451545.0\n\
9\n$FINGERPRINTGUID\n2\n{00000000-0000-0000-0000-000000000000}\n\
9\n$VERSIONGUID\n2\n{00000000-0000-0000-0000-000000000000}\n\
0\nENDSEC\n0\nEOF\n";

/// The DXF of one part: its cut contours, fold and sew lines, grain line and label.
///
/// ```
/// use flatcut::export::{DxfOptions, write_part_dxf};
/// use flatcut::pattern::PartDrawing;
/// use glam::DVec2;
///
/// let part = PartDrawing {
///     name: "bracket".into(),
///     quantity: 4,
///     outer: vec![DVec2::ZERO, DVec2::new(80.0, 0.0), DVec2::new(80.0, 40.0), DVec2::new(0.0, 40.0)],
///     ..Default::default()
/// };
/// let bytes = write_part_dxf(&part, &DxfOptions::default())?;
/// assert!(String::from_utf8_lossy(&bytes).contains("LWPOLYLINE"));
/// # Ok::<(), flatcut::export::ExportError>(())
/// ```
pub fn write_part_dxf(drawing: &PartDrawing, options: &DxfOptions) -> Result<Vec<u8>, ExportError> {
    let contours = part_contours(drawing, &options.pattern)?;
    let mut document = new_document(options.version, drawing.units)?;
    add_part(&mut document, drawing, &contours, options);
    set_extents(&mut document, part_bounds(&contours));
    save(&document, options.version)
}

/// The DXF of one sheet: its outline and every placed part, as in [`write_part_dxf`]. The parts'
/// coordinates must be in the sheet's frame and units.
pub fn write_sheet_dxf(sheet: &SheetDrawing, options: &DxfOptions) -> Result<Vec<u8>, ExportError> {
    check_sheet(sheet)?;
    let mut document = new_document(options.version, sheet.units)?;
    add_polyline(
        &mut document,
        layers::SHEET,
        &sheet.corners().map(BulgeVertex::straight),
        true,
        options.version,
    );
    let mut bounds = (DVec2::ZERO, DVec2::new(sheet.width, sheet.height));
    for placed in &sheet.parts {
        let contours = part_contours(&placed.drawing, &options.pattern)?;
        add_part(&mut document, &placed.drawing, &contours, options);
        let (low, high) = part_bounds(&contours);
        bounds = (bounds.0.min(low), bounds.1.max(high));
    }
    set_extents(&mut document, bounds);
    save(&document, options.version)
}

/// An error when the sheet has no positive size or a part is in other units.
pub(crate) fn check_sheet(sheet: &SheetDrawing) -> Result<(), ExportError> {
    let positive = |value: f64| value.is_finite() && value > 0.0;
    if !positive(sheet.width) || !positive(sheet.height) {
        return Err(ExportError::InvalidSheetSize {
            index: sheet.index,
            width: sheet.width,
            height: sheet.height,
        });
    }
    match sheet
        .parts
        .iter()
        .find(|placed| placed.drawing.units != sheet.units)
    {
        Some(placed) => Err(ExportError::MixedUnits {
            part: placed.drawing.name.clone(),
            sheet: sheet.index,
            part_units: placed.drawing.units.symbol(),
            sheet_units: sheet.units.symbol(),
        }),
        None => Ok(()),
    }
}

/// Smallest box (lower and upper corner) holding every contour of a part.
fn part_bounds(contours: &PartContours) -> (DVec2, DVec2) {
    let closed = std::iter::once(&contours.outer)
        .chain(&contours.holes)
        .chain(&contours.sew_lines);
    let closed_bounds = closed.filter_map(|contour| polyline_bounds(contour, true));
    let open_bounds = contours
        .fold_lines
        .iter()
        .filter_map(|line| polyline_bounds(line, false));
    closed_bounds.chain(open_bounds).fold(
        (DVec2::INFINITY, DVec2::NEG_INFINITY),
        |(low, high), (contour_low, contour_high)| (low.min(contour_low), high.max(contour_high)),
    )
}

/// `$EXTMIN` and `$EXTMAX`, so that viewers and CAM open the drawing zoomed to its contents.
fn set_extents(document: &mut Drawing, (low, high): (DVec2, DVec2)) {
    if low.is_finite() && high.is_finite() {
        document.header.minimum_drawing_extents = point(low);
        document.header.maximum_drawing_extents = point(high);
    }
}

/// An empty drawing of the given version and units, with flatcut's layers and line types and a
/// fixed header.
fn new_document(version: DxfVersion, units: Units) -> Result<Drawing, ExportError> {
    let mut document = Drawing::load(&mut FIXED_HEADER.as_bytes())?;
    document.normalize();
    document.header.version = match version {
        DxfVersion::R2000 => AcadVersion::R2000,
        DxfVersion::R12 => AcadVersion::R12,
    };
    (
        document.header.default_drawing_units,
        document.header.drawing_units,
    ) = match units {
        Units::Millimetres => (DxfUnits::Millimeters, DrawingUnits::Metric),
        Units::Centimetres => (DxfUnits::Centimeters, DrawingUnits::Metric),
        Units::Metres => (DxfUnits::Meters, DrawingUnits::Metric),
        Units::Inches => (DxfUnits::Inches, DrawingUnits::English),
    };
    document.add_line_type(dashed_line_type(units));
    for (name, colour, line_type) in layers::ALL {
        document.add_layer(Layer {
            name: name.to_owned(),
            color: Color::from_index(colour),
            line_type_name: line_type.to_owned(),
            is_layer_plotted: true,
            ..Default::default()
        });
    }
    Ok(document)
}

/// The dashed line type, its pattern in the drawing's units.
fn dashed_line_type(units: Units) -> LineType {
    let lengths: Vec<f64> = DASH_PATTERN_MM
        .iter()
        .map(|length| length / units.millimetres())
        .collect();
    LineType {
        name: layers::DASHED.to_owned(),
        description: "Dashed __ __ __".to_owned(),
        element_count: lengths.len() as i32,
        total_pattern_length: lengths.iter().map(|length| length.abs()).sum(),
        dash_dot_space_lengths: lengths,
        ..Default::default()
    }
}

/// A part's contours, fold and sew lines and marks.
fn add_part(
    document: &mut Drawing,
    drawing: &PartDrawing,
    contours: &PartContours,
    options: &DxfOptions,
) {
    let version = options.version;
    add_polyline(document, layers::CUT_OUTER, &contours.outer, true, version);
    for hole in &contours.holes {
        add_polyline(document, layers::CUT_INNER, hole, true, version);
    }
    for sew_line in &contours.sew_lines {
        add_polyline(document, layers::SEW, sew_line, true, version);
    }
    for fold_line in &contours.fold_lines {
        add_polyline(document, layers::FOLD, fold_line, false, version);
    }
    add_bends(
        document,
        drawing,
        &contours.outer,
        options.pattern.bend_zones,
    );
    if let Some(([tail, head], arrowhead)) = drawing.grain_arrow() {
        let line = Line::new(point(tail), point(head));
        add_entity(document, layers::MARKS, EntityType::Line(line));
        let arrowhead = arrowhead.map(BulgeVertex::straight);
        add_polyline(document, layers::MARKS, &arrowhead, false, version);
    }
    add_label(document, drawing, &contours.outer);
}

/// Bend lines (a LINE on `BEND_UP` or `BEND_DOWN`) and their notes (`UP 90%%d R2`, TEXT on
/// `MARKS`, along the line, beside its middle), at half the label's height; with `zones`, each
/// bend's two tangent lines (a LINE each on `BEND_ZONE`, half the allowance either side).
fn add_bends(document: &mut Drawing, drawing: &PartDrawing, outer: &[BulgeVertex], zones: bool) {
    let height = label_height(drawing, outer) * BEND_NOTE_HEIGHT_FRACTION;
    for bend in &drawing.bends {
        let [start, end] = bend.line;
        if zones {
            for [from, to] in bend.zone_edges() {
                let line = Line::new(point(from), point(to));
                add_entity(document, layers::BEND_ZONE, EntityType::Line(line));
            }
        }
        let layer = match bend.direction {
            BendDirection::Up => layers::BEND_UP,
            BendDirection::Down => layers::BEND_DOWN,
        };
        let line = Line::new(point(start), point(end));
        add_entity(document, layer, EntityType::Line(line));
        let along = (end - start).normalize_or_zero();
        // `%%d` is the degree sign of DXF text (the file's code page may not have `°`).
        let value = escaped_text(&bend.note()).replace('°', "%%d");
        let width = value.chars().count() as f64 * height * LABEL_CHARACTER_WIDTH;
        let location = (start + end) * 0.5 - along * (width * 0.5) + along.perp() * (0.5 * height);
        let text = Text {
            location: point(location),
            text_height: height,
            rotation: along.y.atan2(along.x).to_degrees(),
            value,
            ..Default::default()
        };
        add_entity(document, layers::MARKS, EntityType::Text(text));
    }
}

/// A polyline of bulged vertices: LWPOLYLINE in R2000, POLYLINE and VERTEX entities in R12.
fn add_polyline(
    document: &mut Drawing,
    layer: &str,
    vertices: &[BulgeVertex],
    closed: bool,
    version: DxfVersion,
) {
    let entity = match version {
        DxfVersion::R2000 => {
            let mut polyline = LwPolyline {
                vertices: vertices
                    .iter()
                    .map(|vertex| LwPolylineVertex {
                        x: vertex.point.x,
                        y: vertex.point.y,
                        bulge: vertex.bulge,
                        ..Default::default()
                    })
                    .collect(),
                ..Default::default()
            };
            polyline.set_is_closed(closed);
            EntityType::LwPolyline(polyline)
        }
        DxfVersion::R12 => {
            let mut polyline = Polyline::default();
            polyline.set_is_closed(closed);
            for vertex in vertices {
                let mut dxf_vertex = Vertex::new(point(vertex.point));
                dxf_vertex.bulge = vertex.bulge;
                polyline.add_vertex(document, dxf_vertex);
            }
            EntityType::Polyline(polyline)
        }
    };
    add_entity(document, layer, entity);
}

/// The label (part name, quantity, material) where [`PartDrawing::label_placement`] puts it:
/// inside the part's material, clear of its cut, fold and bend lines and grain arrow, level or
/// turned along the part, as large as [`label_height`] allows down to the smallest height.
fn add_label(document: &mut Drawing, drawing: &PartDrawing, outer: &[BulgeVertex]) {
    let largest = label_height(drawing, outer);
    let smallest = LABEL_HEIGHT_RANGE_MM.0 / drawing.units.millimetres();
    let value = label_text(drawing);
    let characters = value.chars().count();
    let Some(placement) = drawing.label_placement(
        characters,
        LABEL_CHARACTER_WIDTH,
        (smallest.min(largest), largest),
    ) else {
        return;
    };
    let width = characters as f64 * placement.height * LABEL_CHARACTER_WIDTH;
    let text = Text {
        location: point(placement.insertion_point(width)),
        text_height: placement.height,
        rotation: placement.angle.to_degrees(),
        value,
        ..Default::default()
    };
    add_entity(document, layers::MARKS, EntityType::Text(text));
}

/// The label's text height: a fraction of the part's smaller side, clamped to
/// [`LABEL_HEIGHT_RANGE_MM`] (the smallest height for a part with no outline).
fn label_height(drawing: &PartDrawing, outer: &[BulgeVertex]) -> f64 {
    let unit = drawing.units.millimetres();
    let (smallest, largest) = LABEL_HEIGHT_RANGE_MM;
    let side = polyline_bounds(outer, true).map_or(0.0, |(low, high)| (high - low).min_element());
    (side * LABEL_HEIGHT_FRACTION).clamp(smallest / unit, largest / unit)
}

/// "name xQUANTITY material", written as TEXT shows it literally ([`escaped_text`]).
fn label_text(drawing: &PartDrawing) -> String {
    escaped_text(&drawing.label())
}

/// Text written so that TEXT shows it literally: control characters (which would break the
/// file) become spaces, `%` is written `%%%` (else `%%c`, `%%d`, ... are symbols) and `^` is
/// written `^ ` (else `^J`, ... are control codes).
fn escaped_text(label: &str) -> String {
    let mut escaped = String::with_capacity(label.len());
    for character in label.chars() {
        match character {
            '%' => escaped.push_str("%%%"),
            '^' => escaped.push_str("^ "),
            control if control.is_control() => escaped.push(' '),
            other => escaped.push(other),
        }
    }
    escaped
}

/// Adds an entity on a layer.
fn add_entity(document: &mut Drawing, layer: &str, specific: EntityType) {
    let mut entity = Entity::new(specific);
    entity.common.layer = layer.to_owned();
    document.add_entity(entity);
}

/// A point at z = 0.
fn point(position: DVec2) -> Point {
    Point::new(position.x, position.y, 0.0)
}

/// The drawing as ASCII DXF bytes, repaired for strict readers.
fn save(document: &Drawing, version: DxfVersion) -> Result<Vec<u8>, ExportError> {
    let mut bytes = Vec::new();
    document.save(&mut bytes)?;
    Ok(repair(bytes, version))
}

#[cfg(test)]
#[path = "dxf_tests.rs"]
mod tests;
