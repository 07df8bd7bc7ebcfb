//! Small checks shared by the builders of surfaces and features: a condition or a positive
//! length, failing with a defect naming the field.

use glam::DVec3;

use super::errors::SpecDefect;

/// `Ok` when `condition` holds, else a defect of `field`.
pub fn check(condition: bool, field: &str, message: impl Into<String>) -> Result<(), SpecDefect> {
    if condition {
        Ok(())
    } else {
        Err(SpecDefect::new(field, message))
    }
}

/// `Ok` when `value` is a positive finite length, else a defect of `field`.
pub fn positive(value: f64, field: &str) -> Result<(), SpecDefect> {
    check(
        value.is_finite() && value > 0.0,
        field,
        format!("must be a positive length, got {value}"),
    )
}

/// A 3D vector from a part file's array.
pub fn vector(v: [f64; 3]) -> DVec3 {
    DVec3::from_array(v)
}
