//! The rest position of a flat pattern. Its shape does not depend on it, but the files and the
//! nesting start from it: a part with a grain direction is turned so that its grain runs along
//! +x (the stock's grain: a roll's length, a sheet's x axis); any other part so that its
//! smallest-area bounding rectangle is axis-aligned with the longer side along x. Then the
//! pattern is moved so that its bounding box starts at the origin.

use glam::{DVec2, DVec3};

use super::accuracy::Accuracy;
use super::flattened::Flattened;
use super::grain::flat_grain;
use crate::geometry::long_side_of_smallest_rectangle;
use crate::mesh::FacetModel;

/// Turns and moves `flattened` (the pattern of `model`) into its rest position, given the
/// part's 3D grain direction if it has one, and measures its accuracy again from the moved
/// positions so that the figures are those of the pattern written out.
pub fn orient(model: &FacetModel, flattened: &mut Flattened, grain: Option<DVec3>) {
    let positions = &mut flattened.positions;
    let direction = grain
        .and_then(|grain| flat_grain(model, positions, grain))
        .or_else(|| long_side_of_smallest_rectangle(positions));
    if let Some(direction) = direction {
        let turn = DVec2::new(direction.x, -direction.y);
        for p in positions.iter_mut() {
            *p = turn.rotate(*p);
        }
    }
    move_to_origin(positions);
    flattened.stats.accuracy = Accuracy::measure(model, positions);
}

/// Translates the pattern so its bounding box starts at the origin.
pub(super) fn move_to_origin(positions: &mut [DVec2]) {
    let min = positions
        .iter()
        .fold(DVec2::splat(f64::INFINITY), |m, &p| m.min(p));
    for p in positions.iter_mut() {
        *p -= min;
    }
}
