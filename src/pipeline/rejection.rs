//! Why a flattened part is rejected: an error over the tolerance, flipped triangles or a pattern
//! that overlaps itself. A rejected part's cut file is written as `<part>.REJECTED.dxf`, the
//! summary line and `report.json` (`rejected`) say why, and the run exits with 3.

use crate::flatten::Accuracy;

/// Every reason to reject a part of these figures at `tolerance` (a fraction), in words; empty
/// for a part that may be cut.
pub fn rejection_reasons(accuracy: &Accuracy, tolerance: f64) -> Vec<String> {
    let mut reasons = Vec::new();
    for (symbol, error) in [("E_S", accuracy.area_error), ("E_C", accuracy.shape_error)] {
        if error > tolerance {
            reasons.push(format!(
                "{symbol} {:.4} % over the tolerance {} %",
                error * 100.0,
                tolerance * 100.0
            ));
        }
    }
    if accuracy.flipped > 0 {
        reasons.push(format!("{} flipped triangle(s)", accuracy.flipped));
    }
    if accuracy.overlap {
        reasons.push("the pattern overlaps itself".to_string());
    }
    reasons
}

#[cfg(test)]
mod tests {
    use crate::pipeline::rejection::*;

    #[test]
    fn every_reason_is_named() {
        let good = Accuracy {
            area_error: 0.001,
            shape_error: 0.002,
            max_strain: 0.0,
            flipped: 0,
            overlap: false,
        };
        assert!(rejection_reasons(&good, 0.01).is_empty());
        let bad = Accuracy {
            shape_error: 0.169,
            flipped: 2,
            overlap: true,
            ..good
        };
        assert_eq!(
            rejection_reasons(&bad, 0.01),
            [
                "E_C 16.9000 % over the tolerance 1 %",
                "2 flipped triangle(s)",
                "the pattern overlaps itself"
            ]
        );
    }
}
