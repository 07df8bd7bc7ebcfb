//! Bend rules: how a bend's allowance (the flat length of its bend zone) is found from its
//! thickness, inner radius and angle. A K-factor (`BA = θ · (R + K · t)`), a shop's bend table
//! (K, BA or BD by thickness, radius and angle, interpolated), or DIN 6935's correction factor.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use super::bend_table::{BendTable, TableQuantity};

/// The bend allowance `BA = θ · (R_inner + K · t)`: the flat length of a bend of `angle`
/// radians, inner radius `inner_radius` and thickness `thickness`, at K-factor `k_factor`.
pub fn bend_allowance(angle: f64, inner_radius: f64, k_factor: f64, thickness: f64) -> f64 {
    angle * (inner_radius + k_factor * thickness)
}

/// Where the bends' allowances come from.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum BendRule {
    /// One K-factor for every bend (the options' `k_factor`).
    #[default]
    KFactor,
    /// DIN 6935 (cold bending of flat steel products): the correction factor
    /// `k = 0.65 + 0.5 · log10(R / t)` for `R / t < 5`, 1 above, and `BA = θ · (R + k · t / 2)`.
    Din6935,
    /// A bend table, by material, thickness, inner radius and angle.
    Table(BendTable),
}

impl BendRule {
    /// The rule in words, for the report and the summary: `K 0.44`, `DIN 6935`,
    /// `bend table FILE`.
    pub fn describe(&self, k_factor: f64) -> String {
        match self {
            Self::KFactor => format!("K {k_factor}"),
            Self::Din6935 => "DIN 6935".to_owned(),
            Self::Table(table) => format!("bend table {}", table.file),
        }
    }
}

/// One bend as the rules see it: lengths in mm, the angle in radians (how far the flange
/// turns).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BendGeometry {
    /// Sheet thickness.
    pub thickness: f64,
    /// Inner bend radius.
    pub inner_radius: f64,
    /// Bend angle, radians.
    pub angle: f64,
}

impl BendGeometry {
    /// The outside setback `OSSB = (R + t) · tan(θ/2)`: from the outer skin's tangent line to
    /// the virtual sharp (where the two flanges' outer skins meet).
    pub fn outside_setback(&self) -> f64 {
        (self.inner_radius + self.thickness) * (self.angle / 2.0).tan()
    }
}

/// Which rule gave a bend's allowance, with its figures (recorded per bend in the report).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum AllowanceRule {
    /// `BA = θ · (R + K · t)`.
    KFactor {
        /// The K-factor.
        k: f64,
    },
    /// A bend table's value interpolated at the bend.
    Table {
        /// The table's file.
        file: String,
        /// What the table gives: `k`, `ba` or `bd`.
        quantity: TableQuantity,
        /// The interpolated K-factor, allowance or deduction.
        value: f64,
        /// The lines of the table rows interpolated.
        lines: Vec<u64>,
    },
    /// DIN 6935.
    Din6935 {
        /// The standard's correction factor `k` (the neutral fibre at `k · t / 2` from the
        /// inside: a K-factor of `k / 2`).
        k: f64,
        /// The standard's compensation value `v`: the flat length is the two outside leg
        /// dimensions plus `v`.
        compensation: f64,
    },
}

/// A bend's allowance and the rule that gave it.
#[derive(Debug, Clone, PartialEq)]
pub struct BendAllowance {
    /// The bend allowance, mm.
    pub allowance: f64,
    /// The rule and its figures.
    pub rule: AllowanceRule,
}

/// The allowance of `bend` by `rule` (`k_factor` for [`BendRule::KFactor`]), the table's rows
/// picked by `material`; an error when the rule does not cover the bend.
pub fn allowance_by_rule(
    rule: &BendRule,
    k_factor: f64,
    bend: BendGeometry,
    material: Option<&str>,
) -> Result<BendAllowance, String> {
    match rule {
        BendRule::KFactor => Ok(BendAllowance {
            allowance: bend_allowance(bend.angle, bend.inner_radius, k_factor, bend.thickness),
            rule: AllowanceRule::KFactor { k: k_factor },
        }),
        BendRule::Din6935 => din6935(bend),
        BendRule::Table(table) => {
            let found = table.value_at(
                material,
                bend.thickness,
                bend.inner_radius,
                bend.angle.to_degrees(),
            )?;
            let allowance = match table.quantity {
                TableQuantity::K => {
                    bend_allowance(bend.angle, bend.inner_radius, found.value, bend.thickness)
                }
                TableQuantity::Ba => found.value,
                TableQuantity::Bd => 2.0 * bend.outside_setback() - found.value,
            };
            if !(allowance.is_finite() && allowance >= 0.0) {
                return Err(format!(
                    "bend table {}: the bend's allowance comes out at {allowance:.4} mm (rows {:?})",
                    table.file, found.lines
                ));
            }
            Ok(BendAllowance {
                allowance,
                rule: AllowanceRule::Table {
                    file: table.file.clone(),
                    quantity: table.quantity,
                    value: found.value,
                    lines: found.lines,
                },
            })
        }
    }
}

/// DIN 6935's correction factor `k = 0.65 + 0.5 · log10(R / t)` for `R / t < 5`, 1 from there.
pub fn din6935_factor(inner_radius: f64, thickness: f64) -> f64 {
    let ratio = inner_radius / thickness;
    if ratio >= 5.0 {
        1.0
    } else {
        0.65 + 0.5 * ratio.log10()
    }
}

/// A bend's allowance by DIN 6935: `BA = θ · (R + k · t / 2)`, and the standard's compensation
/// `v` by opening angle `β = 180° − θ`: `BA − 2 (R + t)` for β up to 90°, `BA − 2 (R + t) ·
/// tan(θ/2)` up to 165°, 0 beyond.
fn din6935(bend: BendGeometry) -> Result<BendAllowance, String> {
    let k = din6935_factor(bend.inner_radius, bend.thickness);
    if k <= 0.0 || k.is_nan() {
        return Err(format!(
            "DIN 6935 does not cover an inner radius of {:.4} mm at thickness {:.4} mm (its correction factor 0.65 + 0.5·log10(R/t) is not positive below R/t = 0.05)",
            bend.inner_radius, bend.thickness
        ));
    }
    let opening = PI - bend.angle;
    if opening < -1e-9 {
        return Err(format!(
            "DIN 6935 covers opening angles of 0 to 180°; this bend turns by {:.3}°",
            bend.angle.to_degrees()
        ));
    }
    let allowance = bend.angle * (bend.inner_radius + k * bend.thickness / 2.0);
    let compensation = if opening <= PI / 2.0 {
        allowance - 2.0 * (bend.inner_radius + bend.thickness)
    } else if opening <= 165f64.to_radians() {
        allowance - 2.0 * bend.outside_setback()
    } else {
        0.0
    };
    Ok(BendAllowance {
        allowance,
        rule: AllowanceRule::Din6935 { k, compensation },
    })
}

#[cfg(test)]
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;

    fn bend(thickness: f64, inner_radius: f64, degrees: f64) -> BendGeometry {
        BendGeometry {
            thickness,
            inner_radius,
            angle: degrees.to_radians(),
        }
    }

    #[test]
    fn din6935_worked_example() {
        // t 2, R 4, 90°: R/t = 2, k = 0.65 + 0.5 · 0.30103 = 0.800515; BA = π/2 · (4 + 0.800515)
        // = 7.540631; v = BA − 2 · (4 + 2) = −4.459369 (a 50 x 50 outside L is 95.540631 flat).
        let result = din6935(bend(2.0, 4.0, 90.0)).unwrap();
        let AllowanceRule::Din6935 { k, compensation } = result.rule else {
            panic!("{result:?}")
        };
        assert!((k - 0.800_514_997_8).abs() < 1e-9, "{k}");
        assert!(
            (result.allowance - 7.540_631_3).abs() < 1e-6,
            "{}",
            result.allowance
        );
        assert!((compensation + 4.459_368_7).abs() < 1e-6, "{compensation}");
        // R/t ≥ 5: k = 1, the neutral fibre in the middle.
        assert_eq!(din6935_factor(10.0, 2.0), 1.0);
        // 45°: β = 135°, v = BA − 2 (R + t) tan 22.5°.
        let result = din6935(bend(2.0, 4.0, 45.0)).unwrap();
        let AllowanceRule::Din6935 { compensation, .. } = result.rule else {
            panic!()
        };
        let expected = result.allowance - 12.0 * 22.5f64.to_radians().tan();
        assert!((compensation - expected).abs() < 1e-12);
        // 10°: β = 170°, v taken as 0.
        let result = din6935(bend(2.0, 4.0, 10.0)).unwrap();
        assert!(
            matches!(result.rule, AllowanceRule::Din6935 { compensation, .. } if compensation == 0.0)
        );
        assert!(din6935(bend(2.0, 0.0, 90.0)).is_err());
    }

    #[test]
    fn a_bend_deduction_table_converts_through_the_outside_setback() {
        // t 2, R 3, 90°: OSSB = 5, BD 4.5 → BA = 10 − 4.5 = 5.5.
        let table =
            BendTable::parse("bd.csv", "thickness,inner_radius,angle,bd\n2,3,90,4.5\n").unwrap();
        let result =
            allowance_by_rule(&BendRule::Table(table), 0.44, bend(2.0, 3.0, 90.0), None).unwrap();
        assert!((result.allowance - 5.5).abs() < 1e-12);
        let table =
            BendTable::parse("ba.csv", "thickness,inner_radius,angle,ba\n2,3,90,4.5\n").unwrap();
        let result =
            allowance_by_rule(&BendRule::Table(table), 0.44, bend(2.0, 3.0, 90.0), None).unwrap();
        assert_eq!(result.allowance, 4.5);
        let k = allowance_by_rule(&BendRule::KFactor, 0.5, bend(2.0, 3.0, 90.0), None).unwrap();
        assert!((k.allowance - FRAC_PI_2 * 4.0).abs() < 1e-12);
        let allowance = bend_allowance(FRAC_PI_2, 1.64, 0.38, 2.0);
        assert!((allowance - FRAC_PI_2 * 2.4).abs() < 1e-12);
    }
}
