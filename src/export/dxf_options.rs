//! How DXF files are written: the version, and the chord tolerance and seam allowance of the
//! contours drawn.

use serde::{Deserialize, Serialize};

use crate::pattern::PatternOptions;

/// DXF version written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DxfVersion {
    /// AutoCAD 2000 (AC1015): LWPOLYLINE, `$INSUNITS`. The default.
    #[default]
    R2000,
    /// AutoCAD R12 (AC1009), for old controllers: POLYLINE with bulged VERTEX entities and no unit
    /// header.
    R12,
}

/// How DXF files are written.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DxfOptions {
    /// DXF version; default [`DxfVersion::R2000`].
    pub version: DxfVersion,
    /// Chord tolerance and seam allowance of the contours drawn (sheets are fitted after their
    /// parts are placed).
    pub pattern: PatternOptions,
}
