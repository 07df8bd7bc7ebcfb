//! Input checks of the search: the stock, each outline, the rotations, and parts too large for
//! the stock, each refused with the error that says what to change.

use glam::DVec2;

use crate::geometry::{bounding_box, signed_area};
use crate::nest::errors::NestError;
use crate::nest::item::NestItem;
use crate::nest::layout::Placement;
use crate::nest::options::NestOptions;
use crate::nest::rotations::Rotations;
use crate::nest::stock::{MAXIMUM_STOCK_MM, Stock};

/// The stock extent along y (sheet height or roll width) and, for sheets, along x; an error for
/// a dimension that is not positive and finite or exceeds [`MAXIMUM_STOCK_MM`].
pub(super) fn validate_stock(options: &NestOptions) -> Result<(f64, Option<f64>), NestError> {
    let check = |dimension: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 && value <= MAXIMUM_STOCK_MM {
            Ok(value)
        } else {
            Err(NestError::InvalidStock { dimension, value })
        }
    };
    match options.stock {
        Stock::Sheets { width, height } => Ok((
            check("sheet height", height)?,
            Some(check("sheet width", width)?),
        )),
        Stock::Roll { width } => Ok((check("roll width", width)?, None)),
    }
}

/// An error for an outline with fewer than 3 points, a non-finite coordinate, or no area.
pub(super) fn validate_outline(item: &NestItem) -> Result<(), NestError> {
    let invalid = |defect: &str| NestError::InvalidOutline {
        item: item.name.clone(),
        defect: defect.to_string(),
    };
    if item.outer.len() < 3 {
        return Err(invalid("the outline has fewer than 3 points"));
    }
    if item.outer.iter().any(|point| !point.is_finite()) {
        return Err(invalid("the outline has a non-finite coordinate"));
    }
    let (min, max) = bounding_box(&item.outer);
    let extent = (max - min).max_element();
    if signed_area(&item.outer).abs() <= f64::EPSILON * extent * extent {
        return Err(invalid("the outline has no area"));
    }
    Ok(())
}

/// The error for an item whose poses are invalid: its grain, its rotation step or its list.
pub(super) fn rotation_error(item: &NestItem) -> NestError {
    if let Some(degrees) = item.grain_degrees {
        return NestError::InvalidGrain {
            item: item.name.clone(),
            degrees,
        };
    }
    match item.rotations {
        Rotations::Step(step) => NestError::InvalidRotationStep {
            item: item.name.clone(),
            step,
        },
        _ => NestError::InvalidRotationList {
            item: item.name.clone(),
        },
    }
}

/// The error for an item that fits in none of its orientations, reporting the smallest one.
pub(super) fn too_large(
    item: &NestItem,
    poses: &[(f64, bool)],
    options: &NestOptions,
) -> NestError {
    let (width, height) = poses
        .iter()
        .map(|&(rotation_degrees, mirrored)| {
            let pose = Placement {
                item: 0,
                copy: 0,
                rotation_degrees,
                mirrored,
                translation: DVec2::ZERO,
            };
            let (min, max) = bounding_box(&pose.transform_ring(&item.outer));
            max - min + DVec2::splat(2.0 * options.gap)
        })
        .map(|size| (size.x, size.y))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0.0, 0.0));
    NestError::PartTooLarge {
        item: item.name.clone(),
        width,
        height,
        stock: options.stock.to_string(),
    }
}
