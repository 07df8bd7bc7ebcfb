//! Text onto a tiny-skia pixmap (tiny-skia draws no text): glyph outlines from ab_glyph,
//! rasterised to coverage and blended in one solid colour.
//!
//! The font is DejaVu Sans, embedded in the binary from `assets/fonts/DejaVuSans.ttf` (Bitstream
//! Vera licence, `assets/fonts/LICENSE-DejaVu.txt`), so the output does not depend on the fonts
//! of the machine. Positions and sizes are in pixels; `baseline` is the y of the text's baseline.

use ab_glyph::{Font, FontRef, GlyphId, InvalidFont, PxScale, ScaleFont, point};
use tiny_skia::{Pixmap, PremultipliedColorU8};

/// The embedded font file.
const DEJAVU_SANS: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Where a text's anchor point lies along the text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Align {
    /// The anchor is the text's left end.
    Left,
    /// The anchor is the text's middle.
    Centre,
}

/// One line of text to draw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Label<'a> {
    /// The text.
    pub text: &'a str,
    /// Anchor x, pixels.
    pub x: f32,
    /// Baseline y, pixels (y down).
    pub baseline: f32,
    /// Font size (em height), pixels.
    pub size: f32,
    /// Colour, sRGB.
    pub colour: [u8; 3],
    /// Where the anchor lies along the text.
    pub align: Align,
}

/// The embedded typeface.
#[derive(Debug, Clone)]
pub struct Typeface {
    font: FontRef<'static>,
}

impl Typeface {
    /// DejaVu Sans, embedded at build time.
    pub fn embedded() -> Result<Self, InvalidFont> {
        Ok(Self {
            font: FontRef::try_from_slice(DEJAVU_SANS)?,
        })
    }

    /// The advance width of `text` at `size` pixels, kerning included.
    pub fn width(&self, text: &str, size: f32) -> f32 {
        let scaled = self.font.as_scaled(PxScale::from(size));
        let mut width = 0.0;
        let mut previous: Option<GlyphId> = None;
        for character in text.chars() {
            let id = scaled.glyph_id(character);
            if let Some(before) = previous {
                width += scaled.kern(before, id);
            }
            width += scaled.h_advance(id);
            previous = Some(id);
        }
        width
    }

    /// Height above the baseline of the tallest glyphs at `size` pixels.
    pub fn ascent(&self, size: f32) -> f32 {
        self.font.as_scaled(PxScale::from(size)).ascent()
    }

    /// Draws `label` onto `pixmap`, clipped to the image.
    pub fn draw(&self, pixmap: &mut Pixmap, label: &Label) {
        let scaled = self.font.as_scaled(PxScale::from(label.size));
        let width = self.width(label.text, label.size);
        let mut x = match label.align {
            Align::Left => label.x,
            Align::Centre => label.x - 0.5 * width,
        };
        let mut previous: Option<GlyphId> = None;
        for character in label.text.chars() {
            let id = scaled.glyph_id(character);
            if let Some(before) = previous {
                x += scaled.kern(before, id);
            }
            let glyph = id.with_scale_and_position(label.size, point(x, label.baseline));
            if let Some(outlined) = self.font.outline_glyph(glyph) {
                let bounds = outlined.px_bounds();
                outlined.draw(|gx, gy, coverage| {
                    let px = bounds.min.x as i64 + i64::from(gx);
                    let py = bounds.min.y as i64 + i64::from(gy);
                    blend(pixmap, px, py, label.colour, coverage);
                });
            }
            x += scaled.h_advance(id);
            previous = Some(id);
        }
    }
}

/// Blends `colour` at `coverage` (0 to 1) over the pixel `(x, y)`, if it is in the image.
fn blend(pixmap: &mut Pixmap, x: i64, y: i64, colour: [u8; 3], coverage: f32) {
    let (width, height) = (i64::from(pixmap.width()), i64::from(pixmap.height()));
    if x < 0 || y < 0 || x >= width || y >= height {
        return;
    }
    let coverage = coverage.clamp(0.0, 1.0);
    let index = (y * width + x) as usize;
    let pixel = &mut pixmap.pixels_mut()[index];
    let mix = |source: u8, destination: u8| {
        (f32::from(source) * coverage + f32::from(destination) * (1.0 - coverage)).round() as u8
    };
    let alpha = mix(255, pixel.alpha());
    // Premultiplied colour channels never exceed alpha; the mix keeps that, and the clamp makes
    // sure rounding does too.
    let channel = |source: u8, destination: u8| mix(source, destination).min(alpha);
    if let Some(blended) = PremultipliedColorU8::from_rgba(
        channel(colour[0], pixel.red()),
        channel(colour[1], pixel.green()),
        channel(colour[2], pixel.blue()),
        alpha,
    ) {
        *pixel = blended;
    }
}

#[cfg(test)]
mod tests {
    use crate::export::text::*;

    fn white(width: u32, height: u32) -> Pixmap {
        let mut pixmap = Pixmap::new(width, height).expect("pixmap size");
        pixmap.fill(tiny_skia::Color::WHITE);
        pixmap
    }

    fn dark_pixels(pixmap: &Pixmap) -> Vec<(u32, u32)> {
        let width = pixmap.width();
        pixmap
            .pixels()
            .iter()
            .enumerate()
            .filter(|(_, p)| p.red() < 128)
            .map(|(i, _)| (i as u32 % width, i as u32 / width))
            .collect()
    }

    #[test]
    fn the_embedded_font_loads_and_measures() {
        let typeface = Typeface::embedded().expect("embedded font");
        let short = typeface.width("E", 20.0);
        let long = typeface.width("Energy", 20.0);
        assert!(short > 5.0 && long > 4.0 * short, "{short} {long}");
        assert!((typeface.width("Energy", 40.0) - 2.0 * long).abs() < 0.5);
    }

    #[test]
    fn text_is_drawn_where_it_is_anchored() {
        let typeface = Typeface::embedded().expect("embedded font");
        let mut pixmap = white(200, 50);
        let label = Label {
            text: "E_S 1.2 %",
            x: 100.0,
            baseline: 35.0,
            size: 20.0,
            colour: [0, 0, 0],
            align: Align::Centre,
        };
        typeface.draw(&mut pixmap, &label);
        let dark = dark_pixels(&pixmap);
        assert!(dark.len() > 50);
        let (min_x, max_x) = dark.iter().fold((u32::MAX, 0), |(low, high), &(x, _)| {
            (low.min(x), high.max(x))
        });
        let width = typeface.width(label.text, label.size);
        assert!((f64::from(min_x) - (100.0 - 0.5 * f64::from(width))).abs() < 4.0);
        assert!((f64::from(max_x) - (100.0 + 0.5 * f64::from(width))).abs() < 4.0);
        assert!(dark.iter().all(|&(_, y)| (14..=40).contains(&y)));
    }

    #[test]
    fn text_outside_the_image_is_clipped() {
        let typeface = Typeface::embedded().expect("embedded font");
        let mut pixmap = white(20, 20);
        let label = Label {
            text: "WWWWWWWW",
            x: -30.0,
            baseline: 25.0,
            size: 30.0,
            colour: [0, 0, 0],
            align: Align::Left,
        };
        typeface.draw(&mut pixmap, &label);
        assert!(!dark_pixels(&pixmap).is_empty());
    }
}
