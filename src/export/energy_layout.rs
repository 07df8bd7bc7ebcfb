//! The page layout of the energy report: the header with the part's name and figures, the
//! pattern panels side by side at one common length scale with their captions, the legend column
//! on the right, and the key with line samples and a scale bar at the bottom.
//!
//! Sizes are in pixels and scale with the image width (factor 1 at [`DEFAULT_WIDTH_PIXELS`]);
//! text never shrinks below [`MIN_TEXT_FACTOR`] of its full size, so small images stay readable.

use glam::DVec2;
use tiny_skia::Pixmap;

use super::energy_map::{DEFAULT_WIDTH_PIXELS, EnergyMap};
use super::energy_panel::{LineStyle, LineStyles, PanelFrame, draw_marker, stroke_polylines};
use super::legend::{LegendFrame, format_percent};
use super::text::{Align, Label, Typeface};

/// The bounding box of a pattern's positions.
fn bounds(positions: &[DVec2]) -> (DVec2, DVec2) {
    positions.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(low, high), &p| (low.min(p), high.max(p)),
    )
}

/// Where everything goes, in pixels; sizes scale with the width (`size` 1 at 1600 pixels).
pub(super) struct Layout {
    /// Image width.
    pub(super) width: u32,
    /// Image height.
    pub(super) height: u32,
    /// Scale of lines, margins and spacing: 1 at 1600 pixels.
    pub(super) size: f32,
    /// Scale of text and of the bands that hold text: `size`, but never below
    /// [`MIN_TEXT_FACTOR`], so labels stay readable in small images.
    text: f32,
    margin: f32,
    /// Where each pattern goes, in the order given.
    pub(super) frames: Vec<PanelFrame>,
    /// Where the legend goes.
    pub(super) legend: LegendFrame,
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
    /// Lays out the patterns (flat positions of each panel) side by side at one common length
    /// scale, the legend to their right.
    pub(super) fn new(width: u32, patterns: &[&[DVec2]]) -> Self {
        let size = width as f32 / DEFAULT_WIDTH_PIXELS as f32;
        let text = size.max(MIN_TEXT_FACTOR);
        let margin = MARGIN * size;
        let count = patterns.len().max(1) as f32;
        let panels_width = width as f32 - 2.0 * margin - LEGEND_WIDTH * text;
        let panel_width = f64::from((panels_width - (count - 1.0) * margin) / count);
        let boxes: Vec<(DVec2, DVec2)> = patterns.iter().map(|p| bounds(p)).collect();
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
    pub(super) fn draw_header(&self, pixmap: &mut Pixmap, typeface: &Typeface, map: &EnergyMap) {
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
    pub(super) fn draw_caption(
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
    pub(super) fn draw_key(
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

/// A scale-bar length (one significant digit, from [`round_length`]) in plain decimals:
/// "50", "0.2", "0.005".
fn format_length(length: f64) -> String {
    let decimals = (-length.log10().floor()).max(0.0) as usize;
    format!("{length:.decimals$}")
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
    use crate::export::energy_layout::*;

    #[test]
    fn scale_bar_lengths_are_round() {
        assert!((round_length(37.0) - 20.0).abs() < 1e-12);
        assert!((round_length(73.0) - 50.0).abs() < 1e-12);
        assert!((round_length(0.19) - 0.1).abs() < 1e-12);
        assert_eq!(format_length(50.0), "50");
        assert_eq!(format_length(0.002), "0.002");
        assert_eq!(format_length(0.5), "0.5");
    }

    #[test]
    fn panels_share_one_scale_and_keep_their_proportions() {
        let wide = [DVec2::ZERO, DVec2::new(200.0, 50.0)];
        let square = [DVec2::ZERO, DVec2::new(100.0, 100.0)];
        let layout = Layout::new(DEFAULT_WIDTH_PIXELS, &[&wide, &square]);
        let [first, second] = [layout.frames[0], layout.frames[1]];
        assert!((first.scale - second.scale).abs() < 1e-12);
        let right_edge = first.pixel(DVec2::new(200.0, 0.0)).x;
        assert!(
            right_edge < second.pixel(DVec2::ZERO).x,
            "panels do not overlap"
        );
        assert!(f64::from(layout.legend.left) > second.pixel(DVec2::new(100.0, 0.0)).x);
        assert!(layout.height > 0 && layout.width == DEFAULT_WIDTH_PIXELS);
    }
}
