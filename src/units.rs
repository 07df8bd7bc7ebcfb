//! Length units of a part. Geometry stays in the part's units end to end (the pattern is 1:1);
//! the unit is carried to every output that states one (DXF `$INSUNITS`, the report).

use serde::{Deserialize, Serialize};

/// The unit of a part's coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Millimetres (the default).
    #[default]
    #[value(name = "mm")]
    #[serde(rename = "mm")]
    Millimetres,
    /// Centimetres.
    #[value(name = "cm")]
    #[serde(rename = "cm")]
    Centimetres,
    /// Metres (garment tools and scanners export meshes in metres).
    #[value(name = "m")]
    #[serde(rename = "m")]
    Metres,
    /// Inches.
    #[value(name = "in")]
    #[serde(rename = "in")]
    Inches,
}

impl Units {
    /// The unit's short name, as printed in reports.
    pub fn symbol(self) -> &'static str {
        match self {
            Units::Millimetres => "mm",
            Units::Centimetres => "cm",
            Units::Metres => "m",
            Units::Inches => "in",
        }
    }

    /// Millimetres in one unit.
    pub fn millimetres(self) -> f64 {
        match self {
            Units::Millimetres => 1.0,
            Units::Centimetres => 10.0,
            Units::Metres => 1000.0,
            Units::Inches => 25.4,
        }
    }
}
