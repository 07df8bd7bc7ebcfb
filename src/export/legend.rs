//! The colour legend of the energy report: a vertical colour bar from 0 (bottom, blue) to the
//! scale's upper value (top, red), with tick labels in the energy's units, a mark at each isoline
//! level, and a title that names the quantity, its units and the scale's mapping.
//!
//! Also the number formats of the report's labels ([`format_value`], [`format_percent`]).

use tiny_skia::{Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

use super::colormap::{ColorScale, palette_colour};
use super::text::{Align, Label, Typeface};

/// Number of labelled ticks along the bar, ends included.
const TICKS: usize = 5;

/// Where the legend goes and how big its parts are, in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegendFrame {
    /// Left edge of the colour bar.
    pub left: f32,
    /// Top of the legend's title.
    pub top: f32,
    /// Bottom of the colour bar.
    pub bottom: f32,
    /// Width of the colour bar.
    pub bar_width: f32,
    /// Font size of the labels.
    pub text_size: f32,
}

/// What the legend says about the quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct LegendText {
    /// The quantity, e.g. "Energy per vertex (Eq. 1)".
    pub quantity: String,
    /// Its units, e.g. "mm², C = 0.5".
    pub units: String,
    /// A remark printed under the scale's mapping, if any.
    pub note: Option<String>,
}

/// Draws the legend; `levels` are the isoline levels, marked across the bar.
pub fn draw_legend(
    pixmap: &mut Pixmap,
    typeface: &Typeface,
    frame: &LegendFrame,
    scale: &ColorScale,
    text: &LegendText,
    levels: &[f64],
) {
    let line_height = 1.35 * frame.text_size;
    let title = [
        Some(text.quantity.as_str()),
        Some(text.units.as_str()),
        Some(scale.mapping().description()),
        text.note.as_deref(),
    ];
    let mut baseline = frame.top + typeface.ascent(frame.text_size);
    for line in title.into_iter().flatten() {
        typeface.draw(
            pixmap,
            &Label {
                text: line,
                x: frame.left,
                baseline,
                size: frame.text_size,
                colour: [0, 0, 0],
                align: Align::Left,
            },
        );
        baseline += line_height;
    }
    let bar_top = baseline + 0.6 * line_height;
    if frame.bottom - bar_top < 4.0 * line_height {
        return;
    }
    let bar = BarGeometry {
        left: frame.left,
        top: bar_top,
        bottom: frame.bottom,
        width: frame.bar_width,
    };
    draw_bar(pixmap, &bar);
    for &level in levels {
        let y = bar.y_at(scale.position(level));
        stroke_line(pixmap, [bar.left, y], [bar.left + bar.width, y], 1.0, 150);
    }
    draw_ticks(pixmap, typeface, &bar, scale, frame.text_size);
}

/// The colour bar's rectangle.
struct BarGeometry {
    left: f32,
    top: f32,
    bottom: f32,
    width: f32,
}

impl BarGeometry {
    /// The y of scale position `position` (0 at the bottom, 1 at the top).
    fn y_at(&self, position: f64) -> f32 {
        self.bottom - (self.bottom - self.top) * position as f32
    }
}

/// Fills the bar row by row with the palette and frames it.
fn draw_bar(pixmap: &mut Pixmap, bar: &BarGeometry) {
    let (top, bottom) = (bar.top.round() as i32, bar.bottom.round() as i32);
    let rows = (bottom - top).max(1);
    for row in top..bottom {
        let position = f64::from(bottom - 1 - row) / f64::from((rows - 1).max(1));
        let [r, g, b] = palette_colour(position);
        fill_rect(
            pixmap,
            [bar.left, row as f32, bar.width, 1.0],
            [r, g, b, 255],
        );
    }
    let corners = [
        [bar.left, bar.top],
        [bar.left + bar.width, bar.top],
        [bar.left + bar.width, bar.bottom],
        [bar.left, bar.bottom],
    ];
    for k in 0..4 {
        stroke_line(pixmap, corners[k], corners[(k + 1) % 4], 1.0, 255);
    }
}

/// Tick marks and value labels at evenly spaced scale positions.
fn draw_ticks(
    pixmap: &mut Pixmap,
    typeface: &Typeface,
    bar: &BarGeometry,
    scale: &ColorScale,
    text_size: f32,
) {
    let right = bar.left + bar.width;
    for k in 0..TICKS {
        let position = k as f64 / (TICKS - 1) as f64;
        let y = bar.y_at(position);
        stroke_line(pixmap, [right, y], [right + 0.4 * text_size, y], 1.5, 255);
        typeface.draw(
            pixmap,
            &Label {
                text: &format_value(scale.value_at(position)),
                x: right + 0.7 * text_size,
                baseline: y + 0.36 * text_size,
                size: text_size,
                colour: [0, 0, 0],
                align: Align::Left,
            },
        );
    }
}

/// Fills `[x, y, width, height]` with an sRGB colour and alpha.
pub fn fill_rect(pixmap: &mut Pixmap, [x, y, width, height]: [f32; 4], colour: [u8; 4]) {
    if let Some(rect) = Rect::from_xywh(x, y, width, height) {
        let mut paint = Paint::default();
        paint.set_color_rgba8(colour[0], colour[1], colour[2], colour[3]);
        pixmap.fill_rect(rect, &paint, Transform::identity(), None);
    }
}

/// A black line of `width` pixels and `alpha` from `start` to `end`.
fn stroke_line(pixmap: &mut Pixmap, start: [f32; 2], end: [f32; 2], width: f32, alpha: u8) {
    let mut builder = PathBuilder::new();
    builder.move_to(start[0], start[1]);
    builder.line_to(end[0], end[1]);
    if let Some(path) = builder.finish() {
        let mut paint = Paint::default();
        paint.set_color_rgba8(0, 0, 0, alpha);
        paint.anti_alias = true;
        let stroke = Stroke {
            width,
            ..Stroke::default()
        };
        pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
    }
}

/// Three significant digits: plain between 0.01 and 10 000, otherwise `m.mm×10ⁿ`.
pub fn format_value(value: f64) -> String {
    if !value.is_finite() {
        return value.to_string();
    }
    let magnitude = value.abs();
    if magnitude < f64::MIN_POSITIVE {
        return "0".to_string();
    }
    let exponent = magnitude.log10().floor() as i32;
    if (-2..4).contains(&exponent) {
        let decimals = (2 - exponent).max(0) as usize;
        return format!("{value:.decimals$}");
    }
    let mantissa = value / 10f64.powi(exponent);
    // Rounding may carry the mantissa to 10.0: renormalise.
    let (mantissa, exponent) = if mantissa.abs() >= 9.995 {
        (mantissa / 10.0, exponent + 1)
    } else {
        (mantissa, exponent)
    };
    format!("{mantissa:.2}×10{}", superscript(exponent))
}

/// A fraction as a percentage with three decimals, or three significant digits below 0.001 %.
pub fn format_percent(fraction: f64) -> String {
    let percent = fraction * 100.0;
    if percent.abs() >= 0.001 || percent.abs() < f64::MIN_POSITIVE {
        format!("{percent:.3} %")
    } else {
        format!("{} %", format_value(percent))
    }
}

/// An integer in superscript digits.
fn superscript(number: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut text = String::new();
    if number < 0 {
        text.push('⁻');
    }
    for digit in number.unsigned_abs().to_string().bytes() {
        text.push(DIGITS[usize::from(digit - b'0')]);
    }
    text
}

#[cfg(test)]
mod tests {
    use crate::export::legend::*;

    #[test]
    fn values_have_three_significant_digits() {
        assert_eq!(format_value(0.0), "0");
        assert_eq!(format_value(1.23456), "1.23");
        assert_eq!(format_value(0.0123456), "0.0123");
        assert_eq!(format_value(123.456), "123");
        assert_eq!(format_value(1234.56), "1235");
        assert_eq!(format_value(0.000123456), "1.23×10⁻⁴");
        assert_eq!(format_value(123456.0), "1.23×10⁵");
        assert_eq!(format_value(9.9999e-5), "1.00×10⁻⁴");
    }

    #[test]
    fn percentages_stay_readable() {
        assert_eq!(format_percent(0.01234), "1.234 %");
        assert_eq!(format_percent(0.0), "0.000 %");
        assert_eq!(format_percent(1.0e-14), "1.00×10⁻¹² %");
    }
}
