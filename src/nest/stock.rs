//! The stock parts are cut from: identical rectangular sheets, or a roll.

use serde::Serialize;

/// The largest stock dimension accepted, mm (100 m): the collision engine's geometry is single
/// precision, and sheet previews are drawn to scale.
pub const MAXIMUM_STOCK_MM: f64 = 1e5;

/// The stock parts are cut from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stock {
    /// Identical rectangular sheets, as many as needed: `width` along x, `height` along y.
    Sheets {
        /// Extent along x, mm.
        width: f64,
        /// Extent along y, mm.
        height: f64,
    },
    /// A roll of fixed `width` (its extent along y) and unbounded length along x.
    Roll {
        /// Extent along y, mm.
        width: f64,
    },
}

impl std::fmt::Display for Stock {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stock::Sheets { width, height } => write!(formatter, "sheets {width} x {height} mm"),
            Stock::Roll { width } => write!(formatter, "roll {width} mm wide"),
        }
    }
}
