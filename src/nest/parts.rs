//! Pattern files as nesting items: each part's cut outline (with the seam allowance when one is
//! given), in millimetres, in its quantity.

use glam::DVec2;

use super::{NestItem, Rotations};
use crate::geometry::long_side_of_smallest_rectangle;
use crate::pattern::{PatternError, PatternFile, closed_length, part_contours, sample_closed};

/// Largest step when a fitted contour (lines and arcs) is sampled back into a polygon for the
/// nester, in mm: arcs are followed within a fraction of the chord tolerance.
pub const OUTLINE_SAMPLE_STEP: f64 = 1.0;

/// Fewest steps along a contour's length when it is sampled for the nester: a part a few
/// millimetres round (a sub-millimetre piece of a scan in mm, drawn as two arcs) is sampled
/// finer than [`OUTLINE_SAMPLE_STEP`], so its polygon has an area.
pub const MIN_OUTLINE_SAMPLES: f64 = 16.0;

/// One nesting item per pattern file, in mm: the contour that will be cut (made with the file's
/// own chord tolerance and seam allowance), with `rotations` taken from the part's minimum-area
/// bounding rectangle ([`aligned_rotations`]), mirroring as given, and the file's grain direction
/// ([`PatternFile::grain_degrees`]), which overrides the rotations. `flatcut run` nests the
/// pattern files it writes, and `flatcut nest` the ones it reads, through this one function.
pub fn items_from_patterns<'a>(
    patterns: impl IntoIterator<Item = &'a PatternFile>,
    rotations: &Rotations,
    mirror_allowed: bool,
) -> Result<Vec<NestItem>, PatternError> {
    patterns
        .into_iter()
        .map(|pattern| nest_item(pattern, rotations, mirror_allowed))
        .collect()
}

/// The nesting item of one pattern file (see [`items_from_patterns`]).
fn nest_item(
    pattern: &PatternFile,
    rotations: &Rotations,
    mirror_allowed: bool,
) -> Result<NestItem, PatternError> {
    let drawing = &pattern.drawing;
    let scale = drawing.units.millimetres();
    let contours = part_contours(drawing, &pattern.options)?;
    let to_millimetres = |ring: Vec<DVec2>| ring.into_iter().map(|p| p * scale).collect();
    let step =
        (OUTLINE_SAMPLE_STEP / scale).min(closed_length(&contours.outer) / MIN_OUTLINE_SAMPLES);
    let outer: Vec<DVec2> = to_millimetres(sample_closed(&contours.outer, step));
    Ok(NestItem {
        name: drawing.name.clone(),
        holes: contours
            .holes
            .iter()
            .map(|hole| to_millimetres(sample_closed(hole, step)))
            .collect(),
        quantity: drawing.quantity,
        rotations: aligned_rotations(rotations, &outer),
        mirror: mirror_allowed.then(|| aligned_rotations(rotations, &outer)),
        outer,
        grain_degrees: pattern.grain_degrees,
    })
}

/// `rotations` measured from the orientation that lays the side of the minimum-area bounding
/// rectangle of `outer` along x: rotation 0 of the result puts that rectangle square to the
/// stock, so a flattened pattern, whatever angle the flattening left it at, is tried square to
/// the sheet first. `Free` and invalid rotations are returned unchanged.
pub fn aligned_rotations(rotations: &Rotations, outer: &[DVec2]) -> Rotations {
    match (rotations, rotations.angles()) {
        (Rotations::Free, _) | (_, None) => rotations.clone(),
        (_, Some(angles)) => {
            let offset = minimum_area_rectangle_degrees(outer);
            Rotations::Fixed(angles.into_iter().map(|angle| angle - offset).collect())
        }
    }
}

/// Direction (degrees, in [0, 180)) of the longer side of the smallest-area rectangle enclosing
/// `ring` ([`long_side_of_smallest_rectangle`]); 0 for a degenerate ring.
pub fn minimum_area_rectangle_degrees(ring: &[DVec2]) -> f64 {
    long_side_of_smallest_rectangle(ring).map_or(0.0, |side| {
        side.y.atan2(side.x).to_degrees().rem_euclid(180.0)
    })
}

#[cfg(test)]
mod tests {
    use crate::nest::parts::*;

    #[test]
    fn a_tilted_rectangle_is_tried_square_to_the_stock() {
        let tilt = DVec2::from_angle(30f64.to_radians());
        let ring: Vec<DVec2> = [
            (0.0, 0.0),
            (40.0, 0.0),
            (40.0, 10.0),
            (20.0, 12.0),
            (0.0, 10.0),
        ]
        .map(|(x, y)| tilt.rotate(DVec2::new(x, y)))
        .to_vec();
        let side = minimum_area_rectangle_degrees(&ring);
        assert!(
            (side.rem_euclid(90.0) - 30.0).abs() < 1e-9,
            "side at {side}"
        );
        let Rotations::Fixed(angles) = aligned_rotations(&Rotations::Fixed(vec![0.0, 90.0]), &ring)
        else {
            panic!("a list of angles")
        };
        assert_eq!(angles.len(), 2);
        for angle in angles {
            let turn = DVec2::from_angle(angle.to_radians());
            let turned: Vec<DVec2> = ring.iter().map(|point| turn.rotate(*point)).collect();
            let (low, high) = turned.iter().fold(
                (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                |(low, high), point| (low.min(*point), high.max(*point)),
            );
            let size = high - low;
            assert!(
                (size.x * size.y - 480.0).abs() < 1e-6,
                "square to the stock at {angle}: {size}"
            );
        }
        assert_eq!(aligned_rotations(&Rotations::Free, &ring), Rotations::Free);
    }
}
