//! Options of the pattern stage: how closely the fitted contour follows the flat outline, and
//! the seam allowance. `Default` is the only source of defaults.

use serde::{Deserialize, Serialize};

use super::contour::DEFAULT_CHORD_TOLERANCE;
use super::errors::PatternError;

/// How a part's cut contours are made from its flat outline.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PatternOptions {
    /// Largest distance between the part's polyline and the fitted contour (lines and arcs), in
    /// mm; default [`DEFAULT_CHORD_TOLERANCE`] (0.01 mm).
    pub chord_tolerance: f64,
    /// Seam allowance in mm: the cut contours are offset outward by it and the nominal outline
    /// becomes the sew line. Default `None` (cut on the nominal outline).
    pub seam_allowance: Option<f64>,
    /// Whether sheet-metal parts' DXFs also draw each bend zone's two tangent lines (where the
    /// bend starts and ends, the allowance apart) on the `BEND_ZONE` layer. Default `false`.
    #[serde(default, skip_serializing_if = "is_false")]
    pub bend_zones: bool,
}

/// Whether a flag is off (left out of the JSON).
fn is_false(flag: &bool) -> bool {
    !*flag
}

impl Default for PatternOptions {
    fn default() -> Self {
        Self {
            chord_tolerance: DEFAULT_CHORD_TOLERANCE,
            seam_allowance: None,
            bend_zones: false,
        }
    }
}

impl PatternOptions {
    /// An error when a length is not positive and finite.
    pub fn validate(&self) -> Result<(), PatternError> {
        let positive = |value: f64| value.is_finite() && value > 0.0;
        if !positive(self.chord_tolerance) {
            return Err(PatternError::InvalidChordTolerance {
                value: self.chord_tolerance,
            });
        }
        match self.seam_allowance {
            Some(value) if !positive(value) => Err(PatternError::InvalidSeamAllowance { value }),
            _ => Ok(()),
        }
    }
}
