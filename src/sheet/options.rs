//! Options of the sheet-metal unfold.

use serde::{Deserialize, Serialize};

/// The K-factor used when none is given: the neutral fibre at 0.44 of the thickness from the
/// inside of the bend (air bending of mild steel, R ≈ t).
pub const DEFAULT_K_FACTOR: f64 = 0.44;

/// How thin solids are unfolded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SheetOptions {
    /// Where the neutral fibre lies, as a fraction of the thickness from the inside of each
    /// bend, in `[0, 1]`; default [`DEFAULT_K_FACTOR`].
    pub k_factor: f64,
}

impl Default for SheetOptions {
    fn default() -> Self {
        Self {
            k_factor: DEFAULT_K_FACTOR,
        }
    }
}

impl SheetOptions {
    /// Whether these are the default options (the report leaves them out then).
    pub fn is_default(&self) -> bool {
        self == &Self::default()
    }

    /// Whether the K-factor is a fraction of the thickness (finite, in `[0, 1]`).
    pub fn is_valid(&self) -> bool {
        (0.0..=1.0).contains(&self.k_factor)
    }
}
