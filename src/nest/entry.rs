//! The one call that nests: validates the items and options, places every copy, searches for a
//! shorter layout and returns it (see `search/` for how).

use super::errors::NestError;
use super::item::NestItem;
use super::layout::NestLayout;
use super::options::NestOptions;
use super::search::Problem;
use crate::progress::Progress;

/// Nests `items` on the stock of `options`. See the module documentation for the objective.
///
/// Errors on empty input, invalid stock or gap, invalid outlines or rotations, and parts that do
/// not fit on the stock in any allowed rotation.
pub fn nest(
    items: &[NestItem],
    options: &NestOptions,
    progress: &dyn Progress,
) -> Result<NestLayout, NestError> {
    Problem::new(items, options)?.solve(progress)
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use glam::DVec2;

    use crate::geometry::signed_area;
    use crate::nest::entry::nest;
    use crate::nest::errors::NestError;
    use crate::nest::item::NestItem;
    use crate::nest::layout::{NestLayout, Placement, StopReason};
    use crate::nest::options::NestOptions;
    use crate::nest::rotations::{ANGLE_TOLERANCE_DEGREES, Rotations};
    use crate::nest::stock::Stock;
    use crate::nest::verify;
    use crate::progress::NoProgress;

    /// A rectangle item with its lower-left corner at the origin.
    fn rectangle(width: f64, height: f64, quantity: u32, rotations: Rotations) -> NestItem {
        NestItem {
            name: format!("{width}x{height}"),
            outer: vec![
                DVec2::ZERO,
                DVec2::new(width, 0.0),
                DVec2::new(width, height),
                DVec2::new(0.0, height),
            ],
            holes: Vec::new(),
            quantity,
            rotations,
            mirror: None,
            grain_degrees: None,
        }
    }

    /// Options with a small deterministic work budget and no practical wall-clock limit.
    fn options(stock: Stock, gap: f64, work: u64) -> NestOptions {
        NestOptions {
            stock,
            gap,
            time_limit: Duration::from_secs(3600),
            work_limit: Some(work),
            ..NestOptions::default()
        }
    }

    fn checked(items: &[NestItem], options: &NestOptions) -> NestLayout {
        let layout = nest(items, options, &NoProgress).expect("nesting succeeds");
        let violations = verify::verify(items, &layout);
        assert!(violations.is_empty(), "{violations:?}");
        layout
    }

    #[test]
    fn squares_that_tile_exactly_fill_the_roll() {
        // The collision engine keeps a clearance of 1e-5 of the stock scale (see `collision`).
        let items = [rectangle(10.0, 10.0, 4, Rotations::Fixed(vec![0.0]))];
        let layout = checked(&items, &options(Stock::Roll { width: 20.01 }, 0.0, 50_000));
        assert_eq!(layout.sheets.len(), 1);
        assert!(
            layout.used_length < 20.0 * 1.001,
            "length {}",
            layout.used_length
        );
        assert!(layout.utilisation > 0.99);
    }

    #[test]
    fn every_copy_is_placed_with_an_allowed_rotation() {
        let items = [
            rectangle(30.0, 5.0, 3, Rotations::Fixed(vec![90.0])),
            rectangle(7.0, 4.0, 5, Rotations::Step(90.0)),
        ];
        let layout = checked(&items, &options(Stock::Roll { width: 40.0 }, 1.0, 50_000));
        let placements: Vec<&Placement> = layout
            .sheets
            .iter()
            .flat_map(|sheet| &sheet.placements)
            .collect();
        assert_eq!(placements.len(), 8);
        for placement in placements.iter().filter(|placement| placement.item == 0) {
            assert!((placement.rotation_degrees - 90.0).abs() < ANGLE_TOLERANCE_DEGREES);
        }
    }

    #[test]
    fn holed_part_is_placed_by_its_outer_ring() {
        let mut frame = rectangle(30.0, 30.0, 1, Rotations::Fixed(vec![0.0]));
        frame.holes = vec![vec![
            DVec2::new(5.0, 5.0),
            DVec2::new(5.0, 25.0),
            DVec2::new(25.0, 25.0),
            DVec2::new(25.0, 5.0),
        ]];
        let items = [frame, rectangle(5.0, 5.0, 2, Rotations::Fixed(vec![0.0]))];
        let layout = checked(&items, &options(Stock::Roll { width: 30.01 }, 0.0, 20_000));
        assert!(
            layout.used_length >= 35.0 - 1e-6,
            "nothing goes into the hole"
        );
        let net_area = 30.0 * 30.0 - 20.0 * 20.0 + 2.0 * 25.0;
        assert!((layout.utilisation - net_area / (30.01 * layout.used_length)).abs() < 1e-9);
    }

    #[test]
    fn a_part_with_grain_is_only_placed_with_its_grain_along_x() {
        let mut strip = rectangle(4.0, 20.0, 6, Rotations::Step(15.0));
        strip.grain_degrees = Some(90.0);
        let items = [strip];
        // Standing (across the grain) six strips would take 27 of this roll; lying, 41.
        let layout = checked(&items, &options(Stock::Roll { width: 21.0 }, 0.5, 100_000));
        for placement in &layout.sheets[0].placements {
            let turned = (placement.rotation_degrees - 270.0).abs() < ANGLE_TOLERANCE_DEGREES
                || (placement.rotation_degrees - 90.0).abs() < ANGLE_TOLERANCE_DEGREES;
            assert!(turned, "rotation {}", placement.rotation_degrees);
        }
        assert!(layout.used_length > 40.0, "length {}", layout.used_length);
        let mut across = layout.clone();
        across.sheets[0].placements[0].rotation_degrees = 0.0;
        assert!(
            verify::verify(&items, &across)
                .iter()
                .any(|violation| matches!(
                    violation,
                    verify::Violation::OrientationNotAllowed { .. }
                )),
            "the check refuses a copy across the grain"
        );
    }

    #[test]
    fn grain_poses_include_the_mirrored_ones_when_mirroring_is_allowed() {
        let mut item = rectangle(5.0, 3.0, 1, Rotations::Fixed(vec![0.0]));
        item.grain_degrees = Some(30.0);
        assert_eq!(item.poses(), Some(vec![(150.0, false), (330.0, false)]));
        item.mirror = Some(item.rotations.clone());
        let poses = item.poses().expect("valid grain");
        assert_eq!(poses.len(), 4);
        for (rotation, mirrored) in poses {
            assert!(item.allows(rotation, mirrored));
            let grain = DVec2::from_angle(30f64.to_radians());
            let pose = Placement {
                item: 0,
                copy: 0,
                rotation_degrees: rotation,
                mirrored,
                translation: DVec2::ZERO,
            };
            let placed = pose.transform_point(grain) - pose.transform_point(DVec2::ZERO);
            assert!(placed.y.abs() < 1e-9, "grain along x: {placed}");
        }
        assert!(!item.allows(0.0, false));
        item.grain_degrees = Some(f64::NAN);
        assert!(matches!(
            nest(
                &[item],
                &options(Stock::Roll { width: 20.0 }, 0.0, 1_000),
                &NoProgress
            ),
            Err(NestError::InvalidGrain { .. })
        ));
    }

    #[test]
    fn small_parts_go_into_holes_when_asked() {
        let mut frame = rectangle(30.0, 30.0, 2, Rotations::Fixed(vec![0.0, 180.0]));
        frame.holes = vec![vec![
            DVec2::new(5.0, 5.0),
            DVec2::new(5.0, 25.0),
            DVec2::new(25.0, 25.0),
            DVec2::new(25.0, 5.0),
        ]];
        let items = [
            frame,
            rectangle(8.0, 5.0, 7, Rotations::Fixed(vec![0.0, 180.0])),
        ];
        let mut chosen = options(Stock::Roll { width: 31.5 }, 0.5, 50_000);
        chosen.in_holes = true;
        let layout = checked(&items, &chosen);
        assert!(
            layout.used_length < 62.0,
            "every small part in a hole: {}",
            layout.used_length
        );
        let net_area = 2.0 * (30.0 * 30.0 - 20.0 * 20.0) + 7.0 * 40.0;
        assert!((layout.utilisation - net_area / (31.5 * layout.used_length)).abs() < 1e-9);
        chosen.in_holes = false;
        let solid = checked(&items, &chosen);
        assert!(solid.used_length > layout.used_length + 5.0);
    }

    #[test]
    fn sheets_are_added_as_needed() {
        let items = [rectangle(10.0, 10.0, 3, Rotations::Fixed(vec![0.0]))];
        let stock = Stock::Sheets {
            width: 15.0,
            height: 15.0,
        };
        let layout = checked(&items, &options(stock, 1.0, 20_000));
        assert_eq!(layout.sheets.len(), 3);
        assert!(
            layout
                .sheets
                .iter()
                .all(|sheet| sheet.placements.len() == 1)
        );
    }

    /// Trapezoids free to rotate, nested on sheets: the search through overlap turns some of
    /// them between the sampled orientations (every 15°), and the layout passes the independent
    /// check and repeats for the same seed and work.
    #[test]
    fn parts_free_to_rotate_are_turned_between_the_sampled_angles_on_sheets() {
        let outer = vec![
            DVec2::ZERO,
            DVec2::new(11.0, 0.0),
            DVec2::new(8.0, 6.0),
            DVec2::new(2.0, 6.0),
        ];
        let trapezoid = verify::tests::polygon("trapezoid", outer, 14, Rotations::Free);
        let items = [trapezoid];
        let stock = Stock::Sheets {
            width: 40.0,
            height: 30.0,
        };
        let chosen = options(stock, 0.0, 1_500_000);
        let layout = checked(&items, &chosen);
        assert_eq!(layout, checked(&items, &chosen));
        let off_the_grid = |placement: &Placement| {
            let from_grid = placement.rotation_degrees.rem_euclid(15.0);
            from_grid.min(15.0 - from_grid) > 1e-3
        };
        let placements = layout.sheets.iter().flat_map(|sheet| &sheet.placements);
        assert!(
            placements.clone().any(off_the_grid),
            "{:?}",
            placements.map(|p| p.rotation_degrees).collect::<Vec<_>>()
        );
    }

    #[test]
    fn same_seed_gives_the_same_layout() {
        let items = [
            rectangle(13.0, 7.0, 4, Rotations::Step(90.0)),
            rectangle(5.0, 9.0, 5, Rotations::Fixed(vec![0.0, 180.0])),
            rectangle(3.0, 2.0, 6, Rotations::Free),
        ];
        let chosen = options(Stock::Roll { width: 25.0 }, 0.5, 200_000);
        let first = checked(&items, &chosen);
        let second = checked(&items, &chosen);
        assert_eq!(first, second);
        assert_eq!(first.stop_reason, StopReason::WorkBudget);
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let square = rectangle(10.0, 10.0, 1, Rotations::Fixed(vec![0.0]));
        let roll = |width| options(Stock::Roll { width }, 0.0, 1_000);
        let run = |items: &[NestItem], options: &NestOptions| nest(items, options, &NoProgress);
        assert!(matches!(run(&[], &roll(10.0)), Err(NestError::EmptyInput)));
        assert!(matches!(
            run(std::slice::from_ref(&square), &roll(0.0)),
            Err(NestError::InvalidStock { .. })
        ));
        assert!(matches!(
            run(std::slice::from_ref(&square), &roll(5.0)),
            Err(NestError::PartTooLarge { .. })
        ));
        assert!(
            matches!(
                run(std::slice::from_ref(&square), &roll(10.0)),
                Err(NestError::PartTooLarge { .. })
            ),
            "the engine's clearance is part of the fit"
        );
        assert!(matches!(
            run(
                std::slice::from_ref(&square),
                &options(Stock::Roll { width: 20.0 }, -1.0, 1_000)
            ),
            Err(NestError::InvalidGap(_))
        ));
        let stepped = NestItem {
            rotations: Rotations::Step(0.0),
            ..square.clone()
        };
        assert!(matches!(
            run(&[stepped], &roll(20.0)),
            Err(NestError::InvalidRotationStep { .. })
        ));
        let flat = NestItem {
            outer: vec![DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)],
            ..square
        };
        assert!(matches!(
            run(&[flat], &roll(20.0)),
            Err(NestError::InvalidOutline { .. })
        ));
    }

    #[test]
    fn placement_maps_points_by_mirror_then_rotation_then_translation() {
        let placement = Placement {
            item: 0,
            copy: 0,
            rotation_degrees: 90.0,
            mirrored: true,
            translation: DVec2::new(10.0, 0.0),
        };
        let mapped = placement.transform_point(DVec2::new(1.0, 0.0));
        assert!((mapped - DVec2::new(10.0, -1.0)).length() < 1e-12);
        let ring = placement.transform_ring(&[DVec2::ZERO, DVec2::X, DVec2::Y]);
        assert!(
            signed_area(&ring) > 0.0,
            "a mirrored ring keeps its orientation"
        );
    }
}
