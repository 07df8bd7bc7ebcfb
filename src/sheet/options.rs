//! Options of the sheet-metal unfold.

use serde::{Deserialize, Serialize};

use super::bend_rule::BendRule;

/// The K-factor used when none is given: the neutral fibre at 0.44 of the thickness from the
/// inside of the bend (air bending of mild steel, R ≈ t).
pub const DEFAULT_K_FACTOR: f64 = 0.44;

/// How thin solids are unfolded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SheetOptions {
    /// Where the neutral fibre lies, as a fraction of the thickness from the inside of each
    /// bend, in `[0, 1]`; default [`DEFAULT_K_FACTOR`]. Used by [`BendRule::KFactor`].
    pub k_factor: f64,
    /// Where the bends' allowances come from: the K-factor (default), DIN 6935 or a bend table.
    #[serde(default, skip_serializing_if = "is_k_factor")]
    pub rule: BendRule,
    /// The STEP entity id of the `ADVANCED_FACE` to unfold from (a planar face of a skin),
    /// instead of the largest planar face.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_face: Option<u64>,
}

/// Whether a rule is the default K-factor rule (left out of the report).
fn is_k_factor(rule: &BendRule) -> bool {
    rule == &BendRule::KFactor
}

impl Default for SheetOptions {
    fn default() -> Self {
        Self {
            k_factor: DEFAULT_K_FACTOR,
            rule: BendRule::KFactor,
            base_face: None,
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
