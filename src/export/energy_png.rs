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
use serde::{Deserialize, Serialize};
use tiny_skia::{Color, Pixmap};

use super::colormap::{ColorScale, ScaleMapping};
use super::energy_layout::Layout;
pub use super::energy_map::{DEFAULT_WIDTH_PIXELS, EnergyMap, PatternFigures};
use super::energy_panel::{LineStyles, draw_panel};
use super::indexed_png::encode_indexed_png;
use super::legend::{LegendText, draw_legend, format_percent, format_value};
use super::text::Typeface;
use crate::flatten::isolines::{evenly_spaced_levels, isolines};
use crate::pattern::NEGLIGIBLE_STRAIN;

/// Default number of isoline levels, evenly spaced over the colour scale.
pub const DEFAULT_ISOLINE_COUNT: usize = 9;

/// Smallest and largest accepted image width, in pixels.
pub const WIDTH_PIXEL_RANGE: (u32, u32) = (480, 8000);

/// Options of [`render_energy_png`]. `Default` is the only source of defaults.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
    let panels = captioned_panels(map, before);
    let largest = panels
        .iter()
        .flat_map(|(panel, _)| panel.vertex_energies.iter().copied())
        .fold(0.0, f64::max);
    let floored = largest < map.negligible_energy;
    let colours = ColorScale::new(largest.max(map.negligible_energy), options.mapping);
    let patterns: Vec<&[DVec2]> = panels.iter().map(|(panel, _)| panel.positions).collect();
    let layout = Layout::new(options.width_pixels, &patterns);
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
        note: floored.then(floor_note),
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
    encode_indexed_png(&pixmap).map_err(|error| EnergyPngError::Image(error.to_string()))
}

/// The panels in drawing order (before cutting first), each with its caption.
fn captioned_panels<'m, 'a>(
    map: &'m EnergyMap<'a>,
    before: Option<&'m EnergyMap<'a>>,
) -> Vec<(&'m EnergyMap<'a>, String)> {
    match before {
        Some(before) => {
            let after = cuts_phrase("after", map.figures.cuts);
            vec![
                (before, panel_caption("before cutting", &before.figures)),
                (map, panel_caption(&after, &map.figures)),
            ]
        }
        None => vec![(map, single_caption(map))],
    }
}

/// The legend's remark when the scale's top is the negligible-energy floor.
fn floor_note() -> String {
    let strain = format_value(NEGLIGIBLE_STRAIN);
    format!(
        "top: energy at strain {}",
        strain.trim_start_matches("1.00×")
    )
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
    let indices = [
        (
            "triangle",
            first_out_of_range(map.triangles.iter().flatten(), vertices),
        ),
        (
            "boundary loop",
            first_out_of_range(map.boundary_loops.iter().flatten(), vertices),
        ),
    ];
    for (what, bad) in indices {
        if let Some(vertex) = bad {
            return Err(EnergyPngError::VertexIndex {
                panel,
                what,
                vertex,
                vertices,
            });
        }
    }
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

/// The first index not below `vertices`, if any.
fn first_out_of_range<'a>(indices: impl Iterator<Item = &'a u32>, vertices: usize) -> Option<u32> {
    indices.copied().find(|&v| v as usize >= vertices)
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

#[cfg(test)]
mod tests {
    use crate::export::colormap::palette_colour;
    use crate::export::energy_panel::PanelFrame;
    use crate::export::energy_png::*;

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
        let patterns: Vec<&[DVec2]> = maps.iter().map(|map| map.positions).collect();
        Layout::new(width, &patterns).frames
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
