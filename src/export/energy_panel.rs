//! One panel of the energy report: a flat pattern filled with its interpolated per-vertex energy
//! (Eq. 16), its isolines, outline, fold lines and cuts, drawn into a rectangle of the image.
//!
//! Input: the pattern (flat positions in model units, y up), a [`PanelFrame`] that maps it into
//! pixels (y down) at a given scale, the colour scale and the isolines. The drawing order puts
//! the fill first and the cuts last, so lines are never hidden by the colours.

use glam::DVec2;
use tiny_skia::{
    LineCap, LineJoin, Paint, PathBuilder, Pixmap, PremultipliedColorU8, Stroke, StrokeDash,
    Transform,
};

use super::colormap::{ColorScale, palette_colour};
use super::energy_map::EnergyMap;
use super::raster::fill_interpolated;
use crate::flatten::isolines::Isoline;

/// How a line is stroked: colour (sRGB and alpha), width and optional dash and gap, in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineStyle {
    /// sRGB colour and alpha.
    pub colour: [u8; 4],
    /// Width, pixels.
    pub width: f32,
    /// Dash and gap lengths, pixels; `None` for a solid line.
    pub dash: Option<[f32; 2]>,
}

/// The styles of the report's lines at a given size factor (1 for a 1600-pixel-wide image).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineStyles {
    /// The pattern's outline: solid black.
    pub outline: LineStyle,
    /// Under the cut: a wide black line.
    pub cut_under: LineStyle,
    /// Over the cut: magenta dashes, so the cut reads magenta and black.
    pub cut_over: LineStyle,
    /// Under a fold line: a white halo.
    pub fold_under: LineStyle,
    /// Over a fold line: dark blue dashes.
    pub fold_over: LineStyle,
    /// Isolines: thin, translucent dark grey.
    pub isoline: LineStyle,
    /// The maximum-energy marker's outer ring: black.
    pub marker_under: LineStyle,
    /// The maximum-energy marker's inner ring: white.
    pub marker_over: LineStyle,
    /// Radius of the maximum-energy marker, pixels.
    pub marker_radius: f32,
}

impl LineStyles {
    /// The styles scaled by `size` (1 for a 1600-pixel-wide image).
    pub fn scaled(size: f32) -> Self {
        let style = |colour, width: f32, dash: Option<[f32; 2]>| LineStyle {
            colour,
            width: width * size,
            dash: dash.map(|[on, off]| [on * size, off * size]),
        };
        Self {
            outline: style([0, 0, 0, 255], 2.0, None),
            cut_under: style([0, 0, 0, 255], 6.0, None),
            cut_over: style([235, 0, 170, 255], 3.5, Some([14.0, 8.0])),
            fold_under: style([255, 255, 255, 230], 5.0, None),
            fold_over: style([15, 25, 120, 255], 2.5, Some([10.0, 6.0])),
            isoline: style([20, 20, 20, 110], 1.1, None),
            marker_under: style([0, 0, 0, 255], 5.0, None),
            marker_over: style([255, 255, 255, 255], 2.0, None),
            marker_radius: 9.0 * size,
        }
    }
}

/// Where a pattern goes in the image: `pixel = origin + scale × (x − min.x, max.y − y)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PanelFrame {
    /// Pixel position of the pattern's top-left bounding-box corner `(min.x, max.y)`.
    pub origin: DVec2,
    /// Pixels per model unit.
    pub scale: f64,
    /// The pattern's bounding box minimum, model units.
    pub min: DVec2,
    /// The pattern's bounding box maximum, model units.
    pub max: DVec2,
}

impl PanelFrame {
    /// The pixel position of pattern point `point`.
    pub fn pixel(&self, point: DVec2) -> DVec2 {
        self.origin + self.scale * DVec2::new(point.x - self.min.x, self.max.y - point.y)
    }
}

/// Draws `map` into its frame: the energy fill, isolines, fold lines, outline and cuts, and a
/// ring on the vertex of highest energy unless that energy is negligible (round-off).
pub fn draw_panel(
    pixmap: &mut Pixmap,
    map: &EnergyMap,
    frame: &PanelFrame,
    colours: &ColorScale,
    isolines: &[Isoline],
    styles: &LineStyles,
) {
    let corners: Vec<DVec2> = map.positions.iter().map(|&p| frame.pixel(p)).collect();
    let palette = palette_table();
    fill_interpolated(
        pixmap,
        &corners,
        map.triangles,
        map.vertex_energies,
        |value| {
            let index = (colours.position(value) * (palette.len() - 1) as f64).round() as usize;
            palette[index.min(palette.len() - 1)]
        },
    );
    let isoline_curves: Vec<Vec<DVec2>> = isolines
        .iter()
        .flat_map(|line| to_pixels(&line.polylines, frame))
        .collect();
    stroke_polylines(pixmap, &isoline_curves, false, &styles.isoline);
    let folds = to_pixels(&map.fold_polylines, frame);
    stroke_polylines(pixmap, &folds, false, &styles.fold_under);
    stroke_polylines(pixmap, &folds, false, &styles.fold_over);
    let outline: Vec<Vec<DVec2>> = map
        .boundary_loops
        .iter()
        .map(|ring| {
            ring.iter()
                .filter_map(|&v| corners.get(v as usize).copied())
                .collect()
        })
        .collect();
    stroke_polylines(pixmap, &outline, true, &styles.outline);
    let cuts = to_pixels(&map.cut_polylines, frame);
    stroke_polylines(pixmap, &cuts, false, &styles.cut_under);
    stroke_polylines(pixmap, &cuts, false, &styles.cut_over);
    let deformed = |vertex: &usize| map.vertex_energies[*vertex] > map.negligible_energy;
    if let Some(vertex) = maximum_vertex(map.vertex_energies).filter(deformed) {
        draw_marker(pixmap, corners[vertex], styles);
    }
}

/// The vertex of highest energy (the first of equals), if any.
fn maximum_vertex(energies: &[f64]) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (vertex, &energy) in energies.iter().enumerate() {
        if best.is_none_or(|(_, highest)| energy > highest) {
            best = Some((vertex, energy));
        }
    }
    best.map(|(vertex, _)| vertex)
}

/// A ring, black outside and white inside, centred on `centre` (pixels).
pub fn draw_marker(pixmap: &mut Pixmap, centre: DVec2, styles: &LineStyles) {
    let ring = ring_points(centre, f64::from(styles.marker_radius));
    stroke_polylines(pixmap, &ring, true, &styles.marker_under);
    stroke_polylines(pixmap, &ring, true, &styles.marker_over);
}

/// Points around a circle, as one closed polyline.
fn ring_points(centre: DVec2, radius: f64) -> Vec<Vec<DVec2>> {
    const SIDES: usize = 48;
    vec![
        (0..SIDES)
            .map(|k| {
                let angle = std::f64::consts::TAU * k as f64 / SIDES as f64;
                centre + radius * DVec2::new(angle.cos(), angle.sin())
            })
            .collect(),
    ]
}

/// Number of entries of the precomputed palette: finer than the 8-bit colour channels resolve.
const PALETTE_ENTRIES: usize = 1024;

/// The palette sampled at evenly spaced positions, as opaque pixels.
fn palette_table() -> Vec<PremultipliedColorU8> {
    (0..PALETTE_ENTRIES)
        .map(|k| {
            let [r, g, b] = palette_colour(k as f64 / (PALETTE_ENTRIES - 1) as f64);
            PremultipliedColorU8::from_rgba(r, g, b, 255)
                .unwrap_or(PremultipliedColorU8::TRANSPARENT)
        })
        .collect()
}

/// Polylines in model units to pixels.
fn to_pixels(polylines: &[Vec<DVec2>], frame: &PanelFrame) -> Vec<Vec<DVec2>> {
    polylines
        .iter()
        .map(|line| line.iter().map(|&p| frame.pixel(p)).collect())
        .collect()
}

/// Strokes every polyline with at least two points (closed ones back to their start) in one
/// path, so overlapping pieces blend once.
pub fn stroke_polylines(
    pixmap: &mut Pixmap,
    polylines: &[Vec<DVec2>],
    closed: bool,
    style: &LineStyle,
) {
    let mut builder = PathBuilder::new();
    for line in polylines.iter().filter(|line| line.len() >= 2) {
        builder.move_to(line[0].x as f32, line[0].y as f32);
        for point in &line[1..] {
            builder.line_to(point.x as f32, point.y as f32);
        }
        if closed {
            builder.close();
        }
    }
    let Some(path) = builder.finish() else {
        return;
    };
    let mut paint = Paint::default();
    let [r, g, b, a] = style.colour;
    paint.set_color_rgba8(r, g, b, a);
    paint.anti_alias = true;
    let stroke = Stroke {
        width: style.width,
        line_cap: if style.dash.is_some() {
            LineCap::Butt
        } else {
            LineCap::Round
        },
        line_join: LineJoin::Round,
        dash: style
            .dash
            .and_then(|[on, off]| StrokeDash::new(vec![on, off], 0.0)),
        ..Stroke::default()
    };
    pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
}
