//! The energy report picture `<part>.energy.png` (the paper's Fig. 9, §6.3): the flat pattern
//! filled with its elastic energy, interpolated linearly over each triangle from the per-vertex
//! energies of Eq. 1 (Eq. 16), blue where it is lowest and red where it is highest; isolines at
//! evenly spaced levels of the colour scale; the outline, fold lines and cuts; a colour legend
//! with units and scale; and the part's figures (E_S, E_C, maximum strain, cuts). When the map
//! before cutting is given it is drawn in a second panel, beside the first, at the same length
//! scale and on the same colour scale, so the two can be compared directly.
//!
//! Values in, PNG bytes out: no file is read or written here. The same input and options give
//! the same bytes.

use glam::DVec2;
use tiny_skia::{Color, Pixmap};

use super::colormap::{ColorScale, ScaleMapping};
use super::energy_panel::{
    LineStyle, LineStyles, PanelFrame, draw_marker, draw_panel, stroke_polylines,
};
use super::legend::{LegendFrame, LegendText, draw_legend, format_percent, format_value};
use super::text::{Align, Label, Typeface};
use crate::flatten::SpringSystem;
use crate::flatten::isolines::{evenly_spaced_levels, isolines};

/// Default image width in pixels.
pub const DEFAULT_WIDTH_PIXELS: u32 = 1600;

/// Default number of isoline levels, evenly spaced over the colour scale.
pub const DEFAULT_ISOLINE_COUNT: usize = 9;

/// Smallest and largest accepted image width, in pixels.
pub const WIDTH_PIXEL_RANGE: (u32, u32) = (480, 8000);

/// The accuracy figures printed with a map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatternFigures {
    /// `E_S` (Eq. 4), a fraction.
    pub area_error: f64,
    /// `E_C` (Eq. 6), a fraction.
    pub shape_error: f64,
    /// Largest relative edge length change, a fraction.
    pub max_strain: f64,
    /// Number of cuts made.
    pub cuts: usize,
}

/// One energy map: a flat pattern with its per-vertex energy and the lines to draw on it.
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyMap<'a> {
    /// The part's name, printed in the title.
    pub name: String,
    /// Units of the energy values for the legend, e.g. "mm², C = 0.5".
    pub energy_units: String,
    /// Symbol of the length units of `positions`, e.g. "mm", for the scale bar.
    pub length_units: String,
    /// Flat vertex positions, model units, y up.
    pub positions: &'a [DVec2],
    /// Triangles as vertex index triples.
    pub triangles: &'a [[u32; 3]],
    /// Per-vertex energy (Eq. 1), one per position, at least 0.
    pub vertex_energies: &'a [f64],
    /// Closed boundary loops as vertex indices: the outline.
    pub boundary_loops: &'a [Vec<u32>],
    /// Cuts, as flat polylines in model units.
    pub cut_polylines: Vec<Vec<DVec2>>,
    /// Fold lines, as flat polylines in model units.
    pub fold_polylines: Vec<Vec<DVec2>>,
    /// The figures printed with the map.
    pub figures: PatternFigures,
    /// The energy below which differences are round-off, not deformation (see
    /// [`negligible_vertex_energy`]); the colour scale's top is never below it, so a pattern
    /// without deformation (a developable surface) comes out all blue. 0 for none.
    pub negligible_energy: f64,
}

/// The strain taken as negligible for the colour scale's floor: one part per million, far below
/// any manufacturing tolerance and far above the round-off of an isometric flattening.
pub const NEGLIGIBLE_STRAIN: f64 = 1.0e-6;

/// The largest per-vertex energy (Eq. 1) the springs would hold if every one were strained by
/// `strain`: `max_i Σ_j ½ C_ij (strain · d_ij)²`.
pub fn negligible_vertex_energy(springs: &SpringSystem, strain: f64) -> f64 {
    let vertices = springs
        .edges
        .iter()
        .flatten()
        .map(|&v| v as usize + 1)
        .max()
        .unwrap_or(0);
    let mut energies = vec![0.0; vertices];
    for ((&[a, b], &rest), &constant) in springs
        .edges
        .iter()
        .zip(&springs.rest_lengths)
        .zip(&springs.constants)
    {
        let stretch = strain * rest;
        let energy = 0.5 * constant * stretch * stretch;
        energies[a as usize] += energy;
        energies[b as usize] += energy;
    }
    energies.into_iter().fold(0.0, f64::max)
}

/// Options of [`render_energy_png`]. `Default` is the only source of defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyPngOptions {
    /// Image width in pixels, within [`WIDTH_PIXEL_RANGE`]; default [`DEFAULT_WIDTH_PIXELS`]. The
    /// height follows from the pattern's aspect ratio.
    pub width_pixels: u32,
    /// How energies map to colours; default [`ScaleMapping::SquareRoot`].
    pub mapping: ScaleMapping,
    /// Isoline levels, evenly spaced over the colour scale; default [`DEFAULT_ISOLINE_COUNT`].
    pub isoline_count: usize,
}

impl Default for EnergyPngOptions {
    fn default() -> Self {
        Self {
            width_pixels: DEFAULT_WIDTH_PIXELS,
            mapping: ScaleMapping::default(),
            isoline_count: DEFAULT_ISOLINE_COUNT,
        }
    }
}

/// Why an energy picture could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EnergyPngError {
    /// The requested width is out of range.
    #[error("the image width {width} px is outside {min}..={max} px; choose a width in that range")]
    Width {
        /// The width asked for.
        width: u32,
        /// Smallest width.
        min: u32,
        /// Largest width.
        max: u32,
    },
    /// A map has no triangles.
    #[error("the {panel} has no triangles to draw")]
    Empty {
        /// Which map.
        panel: &'static str,
    },
    /// The energies do not match the vertices.
    #[error("the {panel} has {found} vertex energies for {expected} vertices")]
    EnergyCount {
        /// Which map.
        panel: &'static str,
        /// Vertices.
        expected: usize,
        /// Energies given.
        found: usize,
    },
    /// A triangle or boundary loop names a vertex that does not exist.
    #[error("a {what} of the {panel} refers to vertex {vertex}, but there are {vertices} vertices")]
    VertexIndex {
        /// Which map.
        panel: &'static str,
        /// "triangle" or "boundary loop".
        what: &'static str,
        /// The bad index.
        vertex: u32,
        /// Vertices.
        vertices: usize,
    },
    /// A position, polyline point or energy is NaN or infinite, or an energy is negative.
    #[error("the {panel} has an invalid {what} (not finite, or a negative energy)")]
    InvalidValue {
        /// Which map.
        panel: &'static str,
        /// "position", "energy", "cut point" or "fold-line point".
        what: &'static str,
    },
    /// The embedded font could not be read (a build defect).
    #[error("the embedded font cannot be read; the build is broken")]
    Font,
    /// The image could not be allocated or encoded.
    #[error("the PNG image cannot be made: {0}")]
    Image(String),
}

/// Renders the energy picture of `map`, with `before` (the map before cutting) in a second
/// panel when given, and returns the PNG bytes. The title, units and figures come from `map`.
pub fn render_energy_png(
    map: &EnergyMap,
    before: Option<&EnergyMap>,
    options: &EnergyPngOptions,
) -> Result<Vec<u8>, EnergyPngError> {
    let (min, max) = WIDTH_PIXEL_RANGE;
    if !(min..=max).contains(&options.width_pixels) {
        return Err(EnergyPngError::Width {
            width: options.width_pixels,
            min,
            max,
        });
    }
    check_map(map, "pattern")?;
    if let Some(before) = before {
        check_map(before, "map before cutting")?;
    }
    let typeface = Typeface::embedded().map_err(|_| EnergyPngError::Font)?;
    let panels: Vec<(&EnergyMap, String)> = match before {
        Some(before) => vec![
            (before, panel_caption("before cutting", &before.figures)),
            (
                map,
                panel_caption(&cuts_phrase("after", map.figures.cuts), &map.figures),
            ),
        ],
        None => vec![(map, single_caption(map))],
    };
    let largest = panels
        .iter()
        .flat_map(|(panel, _)| panel.vertex_energies.iter().copied())
        .fold(0.0, f64::max);
    let floored = largest < map.negligible_energy;
    let colours = ColorScale::new(largest.max(map.negligible_energy), options.mapping);
    let layout = Layout::new(options.width_pixels, &panels);
    let mut pixmap = Pixmap::new(layout.width, layout.height)
        .ok_or_else(|| EnergyPngError::Image("the image size is invalid".to_string()))?;
    pixmap.fill(Color::WHITE);
    let levels: Vec<f64> = evenly_spaced_levels(0.0, 1.0, options.isoline_count)
        .into_iter()
        .map(|position| colours.value_at(position))
        .collect();
    let styles = LineStyles::scaled(layout.size);
    for ((panel, caption), frame) in panels.iter().zip(&layout.frames) {
        let lines = isolines(
            panel.positions,
            panel.triangles,
            panel.vertex_energies,
            &levels,
        );
        draw_panel(&mut pixmap, panel, frame, &colours, &lines, &styles);
        layout.draw_caption(&mut pixmap, &typeface, frame, caption);
    }
    layout.draw_header(&mut pixmap, &typeface, map);
    let legend_text = LegendText {
        quantity: "Energy per vertex (Eq. 1)".to_string(),
        units: map.energy_units.clone(),
        note: floored.then(|| {
            let strain = format_value(NEGLIGIBLE_STRAIN);
            format!(
                "top: energy at strain {}",
                strain.trim_start_matches("1.00×")
            )
        }),
    };
    draw_legend(
        &mut pixmap,
        &typeface,
        &layout.legend,
        &colours,
        &legend_text,
        &levels,
    );
    layout.draw_key(&mut pixmap, &typeface, &styles, &map.length_units);
    encode_opaque_png(&pixmap).map_err(|error| EnergyPngError::Image(error.to_string()))
}

/// Encodes an opaque pixmap as an 8-bit RGB PNG with fast compression: several times faster than
/// tiny-skia's own encoder (RGBA, balanced compression) for a slightly larger file. Alpha is
/// dropped, which is exact for an opaque image (premultiplied and plain colours are then equal).
fn encode_opaque_png(pixmap: &Pixmap) -> Result<Vec<u8>, png::EncodingError> {
    let rgb: Vec<u8> = pixmap
        .pixels()
        .iter()
        .flat_map(|pixel| {
            let colour = pixel.demultiply();
            [colour.red(), colour.green(), colour.blue()]
        })
        .collect();
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, pixmap.width(), pixmap.height());
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&rgb)?;
    writer.finish()?;
    Ok(bytes)
}

/// Checks sizes, indices and values of one map.
fn check_map(map: &EnergyMap, panel: &'static str) -> Result<(), EnergyPngError> {
    let vertices = map.positions.len();
    if map.triangles.is_empty() {
        return Err(EnergyPngError::Empty { panel });
    }
    if map.vertex_energies.len() != vertices {
        return Err(EnergyPngError::EnergyCount {
            panel,
            expected: vertices,
            found: map.vertex_energies.len(),
        });
    }
    let bad_index =
        |what: &'static str, mut indices: Box<dyn Iterator<Item = u32> + '_>| match indices
            .find(|&v| v as usize >= vertices)
        {
            Some(vertex) => Err(EnergyPngError::VertexIndex {
                panel,
                what,
                vertex,
                vertices,
            }),
            None => Ok(()),
        };
    bad_index(
        "triangle",
        Box::new(map.triangles.iter().flatten().copied()),
    )?;
    bad_index(
        "boundary loop",
        Box::new(map.boundary_loops.iter().flatten().copied()),
    )?;
    let invalid = |what| EnergyPngError::InvalidValue { panel, what };
    if !map.positions.iter().all(|p| p.is_finite()) {
        return Err(invalid("position"));
    }
    if !map
        .vertex_energies
        .iter()
        .all(|e| e.is_finite() && *e >= 0.0)
    {
        return Err(invalid("energy"));
    }
    if !map.cut_polylines.iter().flatten().all(|p| p.is_finite()) {
        return Err(invalid("cut point"));
    }
    if !map.fold_polylines.iter().flatten().all(|p| p.is_finite()) {
        return Err(invalid("fold-line point"));
    }
    Ok(())
}

/// A panel's caption: what it shows and its errors.
fn panel_caption(what: &str, figures: &PatternFigures) -> String {
    format!(
        "{what}: E_S {}, E_C {}",
        format_percent(figures.area_error),
        format_percent(figures.shape_error)
    )
}

/// The caption of a single panel: what it shows (its figures are in the title).
fn single_caption(map: &EnergyMap) -> String {
    let triangles = map.triangles.len();
    match map.figures.cuts {
        0 => format!("flat pattern, {triangles} triangles"),
        cuts => format!(
            "flat pattern {}, {triangles} triangles",
            cuts_phrase("after", cuts)
        ),
    }
}

/// "after 1 cut", "after 3 cuts".
fn cuts_phrase(preposition: &str, cuts: usize) -> String {
    match cuts {
        1 => format!("{preposition} 1 cut"),
        cuts => format!("{preposition} {cuts} cuts"),
    }
}

/// The bounding box of a pattern's positions.
fn bounds(positions: &[DVec2]) -> (DVec2, DVec2) {
    positions.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(low, high), &p| (low.min(p), high.max(p)),
    )
}

/// Where everything goes, in pixels; sizes scale with the width (`size` 1 at 1600 pixels).
struct Layout {
    width: u32,
    height: u32,
    /// Scale of lines, margins and spacing: 1 at 1600 pixels.
    size: f32,
    /// Scale of text and of the bands that hold text: `size`, but never below
    /// [`MIN_TEXT_FACTOR`], so labels stay readable in small images.
    text: f32,
    margin: f32,
    frames: Vec<PanelFrame>,
    legend: LegendFrame,
    key_baseline: f32,
}

/// Header height (title and figures lines) at size 1, pixels.
const HEADER_HEIGHT: f32 = 104.0;
/// Caption band above each panel at size 1, pixels.
const CAPTION_HEIGHT: f32 = 40.0;
/// Key band (line styles, scale bar) below the panels at size 1, pixels.
const KEY_HEIGHT: f32 = 64.0;
/// Legend column width at size 1, pixels.
const LEGEND_WIDTH: f32 = 250.0;
/// Margin around everything and gap between panels at size 1, pixels.
const MARGIN: f32 = 28.0;
/// Blank space around a pattern inside its panel at size 1, pixels (room for the marker).
const PANEL_PADDING: f32 = 14.0;
/// Smallest panel height at size 1, pixels (room for the legend).
const MIN_PANEL_HEIGHT: f32 = 520.0;
/// Largest panel height as a multiple of the image width (for very tall patterns).
const MAX_PANEL_HEIGHT_RATIO: f64 = 1.2;
/// Smallest text scale: small images keep labels of at least 70 % of their 1600-pixel size.
const MIN_TEXT_FACTOR: f32 = 0.7;
/// Text sizes at size 1, pixels.
const TITLE_TEXT: f32 = 32.0;
const BODY_TEXT: f32 = 20.0;
const SMALL_TEXT: f32 = 17.0;

impl Layout {
    /// Lays out `panels` side by side at one common length scale, the legend to their right.
    fn new(width: u32, panels: &[(&EnergyMap, String)]) -> Self {
        let size = width as f32 / DEFAULT_WIDTH_PIXELS as f32;
        let text = size.max(MIN_TEXT_FACTOR);
        let margin = MARGIN * size;
        let count = panels.len().max(1) as f32;
        let panels_width = width as f32 - 2.0 * margin - LEGEND_WIDTH * text;
        let panel_width = f64::from((panels_width - (count - 1.0) * margin) / count);
        let boxes: Vec<(DVec2, DVec2)> = panels.iter().map(|(m, _)| bounds(m.positions)).collect();
        let extent = |(low, high): &(DVec2, DVec2)| (*high - *low).max(DVec2::splat(1e-12));
        let widest = boxes.iter().map(|b| extent(b).x).fold(0.0, f64::max);
        let tallest = boxes.iter().map(|b| extent(b).y).fold(0.0, f64::max);
        let max_height = MAX_PANEL_HEIGHT_RATIO * f64::from(width);
        let padding = f64::from(PANEL_PADDING * size);
        let scale = ((panel_width - 2.0 * padding) / widest).min(max_height / tallest);
        let panel_height =
            (tallest * scale + 2.0 * padding).max(f64::from(MIN_PANEL_HEIGHT * size));
        let panels_top = f64::from((HEADER_HEIGHT + CAPTION_HEIGHT) * text);
        let frames = boxes
            .iter()
            .enumerate()
            .map(|(k, (low, high))| {
                let left = f64::from(margin) + k as f64 * (panel_width + f64::from(margin));
                let drawn = (*high - *low) * scale;
                PanelFrame {
                    origin: DVec2::new(
                        left + 0.5 * (panel_width - drawn.x),
                        panels_top + 0.5 * (panel_height - drawn.y),
                    ),
                    scale,
                    min: *low,
                    max: *high,
                }
            })
            .collect();
        let panels_bottom = panels_top as f32 + panel_height as f32;
        let legend = LegendFrame {
            left: width as f32 - LEGEND_WIDTH * text,
            top: panels_top as f32 - CAPTION_HEIGHT * text,
            bottom: panels_bottom,
            bar_width: 30.0 * size,
            text_size: SMALL_TEXT * text,
        };
        let height = (panels_bottom + (KEY_HEIGHT * text) + margin).ceil() as u32;
        Self {
            width,
            height,
            size,
            text,
            margin,
            frames,
            legend,
            key_baseline: panels_bottom + 0.5 * KEY_HEIGHT * text + 0.35 * BODY_TEXT * text,
        }
    }

    /// The part name and its figures.
    fn draw_header(&self, pixmap: &mut Pixmap, typeface: &Typeface, map: &EnergyMap) {
        let title = format!("{}: elastic energy of the flat pattern", map.name);
        let figures = &map.figures;
        let line = format!(
            "E_S {}     E_C {}     max strain {}     cuts {}",
            format_percent(figures.area_error),
            format_percent(figures.shape_error),
            format_percent(figures.max_strain),
            figures.cuts
        );
        let title_baseline = self.margin + typeface.ascent(TITLE_TEXT * self.text);
        for (text, baseline, size) in [
            (title.as_str(), title_baseline, TITLE_TEXT),
            (
                line.as_str(),
                title_baseline + 1.9 * BODY_TEXT * self.text,
                BODY_TEXT,
            ),
        ] {
            typeface.draw(
                pixmap,
                &Label {
                    text,
                    x: self.margin,
                    baseline,
                    size: size * self.text,
                    colour: [0, 0, 0],
                    align: Align::Left,
                },
            );
        }
    }

    /// A panel's caption, centred above its pattern's box.
    fn draw_caption(
        &self,
        pixmap: &mut Pixmap,
        typeface: &Typeface,
        frame: &PanelFrame,
        text: &str,
    ) {
        let centre = frame.origin.x + 0.5 * frame.scale * (frame.max.x - frame.min.x);
        typeface.draw(
            pixmap,
            &Label {
                text,
                x: centre as f32,
                baseline: (HEADER_HEIGHT + 0.7 * CAPTION_HEIGHT) * self.text,
                size: BODY_TEXT * self.text,
                colour: [40, 40, 40],
                align: Align::Centre,
            },
        );
    }

    /// The key below the panels: a sample of each line style with its name, and a scale bar.
    fn draw_key(
        &self,
        pixmap: &mut Pixmap,
        typeface: &Typeface,
        styles: &LineStyles,
        length_units: &str,
    ) {
        let size = self.size;
        let text_size = SMALL_TEXT * self.text;
        let y = f64::from(self.key_baseline - 0.35 * text_size);
        let entries: [(&str, &[LineStyle]); 4] = [
            ("outline", &[styles.outline]),
            ("cut", &[styles.cut_under, styles.cut_over]),
            ("fold line", &[styles.fold_under, styles.fold_over]),
            ("isolines", &[styles.isoline]),
        ];
        let sample = f64::from(44.0 * size);
        let mut x = f64::from(self.margin);
        for (name, layers) in entries {
            let line = vec![vec![DVec2::new(x, y), DVec2::new(x + sample, y)]];
            for layer in layers {
                stroke_polylines(pixmap, &line, false, layer);
            }
            let label_x = x + sample + f64::from(0.5 * text_size);
            typeface.draw(
                pixmap,
                &Label {
                    text: name,
                    x: label_x as f32,
                    baseline: self.key_baseline,
                    size: text_size,
                    colour: [0, 0, 0],
                    align: Align::Left,
                },
            );
            x = label_x + f64::from(typeface.width(name, text_size) + 2.0 * text_size);
        }
        let radius = f64::from(styles.marker_radius);
        draw_marker(pixmap, DVec2::new(x + radius, y), styles);
        let name = "highest energy";
        let label_x = x + 2.0 * radius + f64::from(0.5 * text_size);
        typeface.draw(
            pixmap,
            &Label {
                text: name,
                x: label_x as f32,
                baseline: self.key_baseline,
                size: text_size,
                colour: [0, 0, 0],
                align: Align::Left,
            },
        );
        let x = label_x + f64::from(typeface.width(name, text_size) + 2.0 * text_size);
        self.draw_scale_bar(pixmap, typeface, x, y, length_units);
    }

    /// A scale bar of a round length near 150 pixels, starting at `x`.
    fn draw_scale_bar(
        &self,
        pixmap: &mut Pixmap,
        typeface: &Typeface,
        x: f64,
        y: f64,
        length_units: &str,
    ) {
        let Some(frame) = self.frames.first() else {
            return;
        };
        let length = round_length(f64::from(150.0 * self.size) / frame.scale);
        let pixels = length * frame.scale;
        let tick = f64::from(6.0 * self.size);
        let bar = vec![
            vec![DVec2::new(x, y - tick), DVec2::new(x, y + tick)],
            vec![DVec2::new(x, y), DVec2::new(x + pixels, y)],
            vec![
                DVec2::new(x + pixels, y - tick),
                DVec2::new(x + pixels, y + tick),
            ],
        ];
        let style = LineStyle {
            colour: [0, 0, 0, 255],
            width: 2.0 * self.size,
            dash: None,
        };
        stroke_polylines(pixmap, &bar, false, &style);
        typeface.draw(
            pixmap,
            &Label {
                text: &format!("{} {length_units}", format_length(length)),
                x: (x + pixels) as f32 + 0.6 * SMALL_TEXT * self.text,
                baseline: self.key_baseline,
                size: SMALL_TEXT * self.text,
                colour: [0, 0, 0],
                align: Align::Left,
            },
        );
    }
}

/// A scale-bar length: whole numbers without decimals.
fn format_length(length: f64) -> String {
    if length >= 1.0 {
        format!("{length:.0}")
    } else {
        format_value(length)
    }
}

/// The largest of 1, 2 or 5 times a power of ten not above `length` (positive).
fn round_length(length: f64) -> f64 {
    let power = 10f64.powf(length.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|step| step * power)
        .find(|&candidate| candidate <= length)
        .unwrap_or(power)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::colormap::palette_colour;

    /// A square grid pattern of `cells × cells` cells over `[0, 100]²` with per-vertex energy
    /// `energy(position)`, outlined by its border.
    struct Grid {
        positions: Vec<DVec2>,
        triangles: Vec<[u32; 3]>,
        energies: Vec<f64>,
        boundary: Vec<Vec<u32>>,
    }

    impl Grid {
        fn new(cells: u32, energy: impl Fn(DVec2) -> f64) -> Self {
            let side = cells + 1;
            let step = 100.0 / f64::from(cells);
            let positions: Vec<DVec2> = (0..side * side)
                .map(|k| DVec2::new(f64::from(k % side), f64::from(k / side)) * step)
                .collect();
            let mut triangles = Vec::new();
            for row in 0..cells {
                for column in 0..cells {
                    let corner = row * side + column;
                    triangles.push([corner, corner + 1, corner + side + 1]);
                    triangles.push([corner, corner + side + 1, corner + side]);
                }
            }
            let mut ring: Vec<u32> = (0..cells).collect();
            ring.extend((0..cells).map(|k| cells + k * side));
            ring.extend((0..cells).map(|k| side * side - 1 - k));
            ring.extend((0..cells).map(|k| (cells - k) * side));
            Self {
                energies: positions.iter().map(|&p| energy(p)).collect(),
                positions,
                triangles,
                boundary: vec![ring],
            }
        }

        fn map(&self) -> EnergyMap<'_> {
            EnergyMap {
                name: "grid".to_string(),
                energy_units: "mm², C = 0.5".to_string(),
                length_units: "mm".to_string(),
                positions: &self.positions,
                triangles: &self.triangles,
                vertex_energies: &self.energies,
                boundary_loops: &self.boundary,
                cut_polylines: Vec::new(),
                fold_polylines: Vec::new(),
                figures: PatternFigures {
                    area_error: 0.0123,
                    shape_error: 0.0234,
                    max_strain: 0.05,
                    cuts: 0,
                },
                negligible_energy: 0.0,
            }
        }
    }

    fn decode(png: &[u8]) -> Pixmap {
        Pixmap::decode_png(png).expect("the output is a PNG")
    }

    fn colour_at(pixmap: &Pixmap, pixel: DVec2) -> [u8; 3] {
        let colour = pixmap
            .pixel(pixel.x as u32, pixel.y as u32)
            .expect("inside the image")
            .demultiply();
        [colour.red(), colour.green(), colour.blue()]
    }

    fn distance(a: [u8; 3], b: [u8; 3]) -> i32 {
        (0..3)
            .map(|k| (i32::from(a[k]) - i32::from(b[k])).abs())
            .max()
            .unwrap_or(0)
    }

    /// The pixel frames the renderer uses for these panels.
    fn frames(width: u32, maps: &[&EnergyMap]) -> Vec<PanelFrame> {
        let panels: Vec<(&EnergyMap, String)> = maps.iter().map(|&m| (m, String::new())).collect();
        Layout::new(width, &panels).frames
    }

    #[test]
    fn image_has_the_width_asked_for_and_the_pattern_aspect() {
        let grid = Grid::new(10, |p| p.x);
        let png =
            render_energy_png(&grid.map(), None, &EnergyPngOptions::default()).expect("renders");
        let pixmap = decode(&png);
        assert_eq!(pixmap.width(), DEFAULT_WIDTH_PIXELS);
        // A square pattern in a panel about 1270 pixels wide, plus header and key.
        assert!(
            (1300..1600).contains(&pixmap.height()),
            "{}",
            pixmap.height()
        );
        let frame = frames(DEFAULT_WIDTH_PIXELS, &[&grid.map()])[0];
        let size = frame.pixel(DVec2::new(100.0, 0.0)) - frame.pixel(DVec2::new(0.0, 100.0));
        assert!((size.x - size.y).abs() < 1e-9, "aspect kept: {size}");
    }

    #[test]
    fn colours_span_the_scale_and_follow_the_energy() {
        // Energy grows along x: blue on the left edge, red on the right edge.
        let grid = Grid::new(20, |p| p.x * p.x);
        let map = grid.map();
        let pixmap =
            decode(&render_energy_png(&map, None, &EnergyPngOptions::default()).expect("renders"));
        let frame = frames(DEFAULT_WIDTH_PIXELS, &[&map])[0];
        let low = colour_at(&pixmap, frame.pixel(DVec2::new(1.0, 52.0)));
        let high = colour_at(&pixmap, frame.pixel(DVec2::new(99.0, 52.0)));
        assert!(distance(low, palette_colour(0.0)) <= 12, "low {low:?}");
        assert!(distance(high, palette_colour(1.0)) <= 12, "high {high:?}");
        let [red, _, blue] = high;
        assert!(red > 180 && blue < 80, "high is red: {high:?}");
        let [red, _, blue] = low;
        assert!(blue > 150 && red < 80, "low is blue: {low:?}");
        // Square-root scale: at x = 52 the energy, interpolated between the grid lines x = 50
        // and x = 55, is 2710 of 10 000, at √0.271 of the scale (off the isoline at ½).
        let middle = colour_at(&pixmap, frame.pixel(DVec2::new(52.0, 52.0)));
        assert!(
            distance(middle, palette_colour(0.271f64.sqrt())) <= 8,
            "middle {middle:?}"
        );
        let near = |target: [u8; 3]| {
            pixmap.pixels().iter().any(|p| {
                let c = p.demultiply();
                distance([c.red(), c.green(), c.blue()], target) <= 6
            })
        };
        for position in [0.0, 0.25, 0.5, 0.75, 1.0] {
            assert!(
                near(palette_colour(position)),
                "colour at {position} present"
            );
        }
    }

    #[test]
    fn the_same_input_gives_the_same_bytes() {
        let grid = Grid::new(12, |p| (p.x - 30.0).abs() + p.y);
        let options = EnergyPngOptions::default();
        let first = render_energy_png(&grid.map(), Some(&grid.map()), &options).expect("renders");
        let second = render_energy_png(&grid.map(), Some(&grid.map()), &options).expect("renders");
        assert_eq!(first, second);
    }

    #[test]
    fn both_panels_share_one_colour_scale() {
        let before = Grid::new(16, |p| 2.0 * p.x);
        let after = Grid::new(16, |p| p.x);
        let mut after_map = after.map();
        after_map.figures.cuts = 1;
        let before_map = before.map();
        let png = render_energy_png(&after_map, Some(&before_map), &EnergyPngOptions::default())
            .expect("renders");
        let pixmap = decode(&png);
        let frames = frames(DEFAULT_WIDTH_PIXELS, &[&before_map, &after_map]);
        let before_high = colour_at(&pixmap, frames[0].pixel(DVec2::new(99.0, 50.0)));
        let after_high = colour_at(&pixmap, frames[1].pixel(DVec2::new(99.0, 50.0)));
        assert!(distance(before_high, palette_colour(1.0)) <= 12);
        // Half the top energy sits at √½ of the square-root scale.
        let expected = palette_colour(0.5f64.sqrt());
        assert!(distance(after_high, expected) <= 16, "{after_high:?}");
    }

    #[test]
    fn cuts_and_outline_are_drawn_over_the_colours() {
        let grid = Grid::new(10, |p| p.x);
        let mut map = grid.map();
        map.cut_polylines = vec![vec![DVec2::new(50.0, 0.0), DVec2::new(50.0, 60.0)]];
        let pixmap =
            decode(&render_energy_png(&map, None, &EnergyPngOptions::default()).expect("renders"));
        let frame = frames(DEFAULT_WIDTH_PIXELS, &[&map])[0];
        let along_cut =
            (5..55).map(|y| colour_at(&pixmap, frame.pixel(DVec2::new(50.0, f64::from(y)))));
        let magenta = along_cut
            .filter(|&[r, g, b]| r > 200 && g < 40 && b > 130)
            .count();
        assert!(magenta > 10, "magenta dashes on the cut: {magenta}");
        let corner = colour_at(&pixmap, frame.pixel(DVec2::new(0.0, 50.0)));
        assert!(corner.iter().all(|&c| c < 60), "black outline: {corner:?}");
    }

    #[test]
    fn a_deformation_free_pattern_is_all_blue() {
        let grid = Grid::new(10, |p| 1e-25 * p.x);
        let mut map = grid.map();
        map.negligible_energy = 1e-9;
        let pixmap =
            decode(&render_energy_png(&map, None, &EnergyPngOptions::default()).expect("renders"));
        let frame = frames(DEFAULT_WIDTH_PIXELS, &[&map])[0];
        let high = colour_at(&pixmap, frame.pixel(DVec2::new(98.0, 50.0)));
        assert!(distance(high, palette_colour(0.0)) <= 6, "{high:?}");
    }

    #[test]
    fn bad_input_is_an_error() {
        let grid = Grid::new(4, |p| p.x);
        let options = EnergyPngOptions::default();
        let mut map = grid.map();
        map.vertex_energies = &grid.energies[1..];
        assert!(matches!(
            render_energy_png(&map, None, &options),
            Err(EnergyPngError::EnergyCount { .. })
        ));
        let negative = vec![-1.0; grid.positions.len()];
        let mut map = grid.map();
        map.vertex_energies = &negative;
        assert!(matches!(
            render_energy_png(&map, None, &options),
            Err(EnergyPngError::InvalidValue { what: "energy", .. })
        ));
        let bad_triangles = [[0, 1, 999]];
        let mut map = grid.map();
        map.triangles = &bad_triangles;
        assert!(matches!(
            render_energy_png(&map, None, &options),
            Err(EnergyPngError::VertexIndex { vertex: 999, .. })
        ));
        let narrow = EnergyPngOptions {
            width_pixels: 10,
            ..options
        };
        assert!(matches!(
            render_energy_png(&grid.map(), None, &narrow),
            Err(EnergyPngError::Width { .. })
        ));
    }

    #[test]
    fn negligible_energy_is_that_of_a_uniform_strain() {
        let springs = SpringSystem {
            edges: vec![[0, 1], [1, 2]],
            rest_lengths: vec![10.0, 20.0],
            constants: vec![0.5, 0.5],
        };
        // Vertex 1 ends both springs: ½·0.5·(0.1)² + ½·0.5·(0.2)² = 0.0125.
        let energy = negligible_vertex_energy(&springs, 0.01);
        assert!((energy - 0.0125).abs() < 1e-15, "{energy}");
    }

    /// About 100,000 triangles: run with `cargo test --release -- --ignored --nocapture`.
    #[test]
    #[ignore = "timing, prints the render time of about 100,000 triangles"]
    fn renders_a_hundred_thousand_triangles() {
        let grid = Grid::new(224, |p| (p.x * 0.1).sin().abs() * p.y);
        let started = std::time::Instant::now();
        let png =
            render_energy_png(&grid.map(), None, &EnergyPngOptions::default()).expect("renders");
        println!(
            "{} triangles: {:.3} s, {} bytes",
            grid.triangles.len(),
            started.elapsed().as_secs_f64(),
            png.len()
        );
    }
}
