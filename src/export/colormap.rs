//! The colour scale of the energy report: values to positions on the scale, positions to colours.
//!
//! The palette follows the paper's Fig. 9 ("red represents regions with the highest energy level,
//! and blue represents regions with the lowest"): a jet-like ramp blue → cyan → green → yellow →
//! red, interpolated linearly in sRGB between five stops at 0, ¼, ½, ¾ and 1. The stops are
//! softened from the pure jet primaries (no black-blue or dark-red ends, a duller green) so that
//! black outlines, magenta cuts and grey isolines stay readable on every part of the scale, and
//! the lightness rises from blue to yellow before it falls to red.
//!
//! The scale runs from 0 (no deformation) to an upper value, the largest value shown. Energy maps
//! are sharply peaked (the energy grows with the square of the length change), so the default
//! [`ScaleMapping::SquareRoot`] spreads the colours by `√E`, which is proportional to the length
//! change of the springs: equal colour steps mean equal steps of stretch, not of energy.
//! [`ScaleMapping::Linear`] maps the energy itself.

use serde::Serialize;

/// How a value is placed on the colour scale between 0 and the upper value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ScaleMapping {
    /// Position `v / upper`.
    Linear,
    /// Position `√(v / upper)`: equal colour steps are equal steps of stretch (the default).
    #[default]
    SquareRoot,
}

impl ScaleMapping {
    /// A short phrase for legends: "linear scale", "square-root scale".
    pub fn description(self) -> &'static str {
        match self {
            ScaleMapping::Linear => "linear scale",
            ScaleMapping::SquareRoot => "square-root scale",
        }
    }
}

/// A colour scale from 0 to `upper`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColorScale {
    upper: f64,
    mapping: ScaleMapping,
}

impl ColorScale {
    /// A scale from 0 to `upper` (a value at or below 0, or not finite, gives a scale on which
    /// every value is at the low end).
    pub fn new(upper: f64, mapping: ScaleMapping) -> Self {
        let upper = if upper.is_finite() && upper > 0.0 {
            upper
        } else {
            0.0
        };
        Self { upper, mapping }
    }

    /// The largest value shown; larger values take the top colour.
    pub fn upper(&self) -> f64 {
        self.upper
    }

    /// The mapping from values to positions.
    pub fn mapping(&self) -> ScaleMapping {
        self.mapping
    }

    /// Position of `value` on the scale, clamped to `[0, 1]`.
    pub fn position(&self, value: f64) -> f64 {
        if self.upper <= 0.0 || value.is_nan() {
            return 0.0;
        }
        let fraction = (value / self.upper).clamp(0.0, 1.0);
        match self.mapping {
            ScaleMapping::Linear => fraction,
            ScaleMapping::SquareRoot => fraction.sqrt(),
        }
    }

    /// The value at `position` (in `[0, 1]`): the inverse of [`ColorScale::position`].
    pub fn value_at(&self, position: f64) -> f64 {
        let position = position.clamp(0.0, 1.0);
        match self.mapping {
            ScaleMapping::Linear => position * self.upper,
            ScaleMapping::SquareRoot => position * position * self.upper,
        }
    }

    /// The colour of `value`.
    pub fn colour(&self, value: f64) -> [u8; 3] {
        palette_colour(self.position(value))
    }
}

/// The palette's stops: position and sRGB colour.
const STOPS: [(f64, [f64; 3]); 5] = [
    (0.0, [30.0, 60.0, 200.0]),
    (0.25, [20.0, 170.0, 230.0]),
    (0.5, [70.0, 190.0, 90.0]),
    (0.75, [250.0, 210.0, 40.0]),
    (1.0, [210.0, 30.0, 35.0]),
];

/// The palette colour at `position` in `[0, 1]` (clamped): blue at 0, red at 1.
pub fn palette_colour(position: f64) -> [u8; 3] {
    let position = if position.is_nan() {
        0.0
    } else {
        position.clamp(0.0, 1.0)
    };
    let upper = STOPS
        .iter()
        .position(|&(stop, _)| stop >= position)
        .unwrap_or(STOPS.len() - 1)
        .max(1);
    let (start, low) = STOPS[upper - 1];
    let (end, high) = STOPS[upper];
    let fraction = (position - start) / (end - start);
    [0, 1, 2].map(|channel| {
        let value = low[channel] + (high[channel] - low[channel]) * fraction;
        value.round().clamp(0.0, 255.0) as u8
    })
}

#[cfg(test)]
mod tests {
    use crate::export::colormap::*;

    #[test]
    fn ends_are_blue_and_red() {
        let [r, g, b] = palette_colour(0.0);
        assert!(b > 150 && r < 60 && g < 100);
        let [r, g, b] = palette_colour(1.0);
        assert!(r > 180 && g < 60 && b < 60);
    }

    #[test]
    fn palette_is_continuous_and_clamped() {
        let steps = 1000;
        for i in 0..steps {
            let [a, b] = [i, i + 1].map(|k| palette_colour(k as f64 / steps as f64));
            for channel in 0..3 {
                assert!((i32::from(a[channel]) - i32::from(b[channel])).abs() <= 2);
            }
        }
        assert_eq!(palette_colour(-1.0), palette_colour(0.0));
        assert_eq!(palette_colour(2.0), palette_colour(1.0));
        assert_eq!(palette_colour(f64::NAN), palette_colour(0.0));
    }

    #[test]
    fn positions_invert() {
        for mapping in [ScaleMapping::Linear, ScaleMapping::SquareRoot] {
            let scale = ColorScale::new(8.0, mapping);
            for k in 0..=10 {
                let position = k as f64 / 10.0;
                let back = scale.position(scale.value_at(position));
                assert!((back - position).abs() < 1e-12, "{mapping:?} {position}");
            }
            assert!((scale.position(100.0) - 1.0).abs() < 1e-12);
            assert!(scale.position(-1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn square_root_spreads_small_values() {
        let scale = ColorScale::new(1.0, ScaleMapping::SquareRoot);
        assert!((scale.position(0.25) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn empty_scale_puts_everything_low() {
        let scale = ColorScale::new(0.0, ScaleMapping::Linear);
        assert!(scale.position(5.0).abs() < 1e-12);
        assert_eq!(scale.colour(5.0), palette_colour(0.0));
    }
}
