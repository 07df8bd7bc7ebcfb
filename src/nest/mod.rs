//! Nesting: place flat patterns, each in its quantity, on rectangular sheets or on a roll.
//!
//! Inputs are [`NestItem`]s (closed outlines in mm, optional holes, quantity, allowed rotations,
//! mirroring) and [`NestOptions`] (stock, gap, time limit, seed). The output is a [`NestLayout`]:
//! per sheet the [`Placement`] of every copy, and the utilisation.
//!
//! * **Sheets** (`Stock::Sheets`): as few sheets as possible, then the least used length of the
//!   last sheet. Sheets are filled from their left edge along x; the used length is measured along x.
//! * **Roll** (`Stock::Roll`): a strip whose *width* is its extent along y; the used length along x
//!   is minimised (the ESICUP strip-packing problem, where `strip_height` is the roll width).
//!
//! Collisions are detected by jagua-rs 1.1.0 behind our own trait ([`collision::CollisionEngine`]);
//! the search ([`search`]) is ours: a bottom-left constructive placement followed by a seeded local
//! search over the placement order. Every result can be checked by [`verify::verify`], an
//! independent exact f64 check that shares no code with the collision engine.
//!
//! Parts with holes are placed by their outer ring: nothing is placed inside a hole.

pub mod collision;
mod errors;
pub mod instance;
pub mod parts;
pub mod search;
pub mod verify;

use std::time::Duration;

use glam::DVec2;
use serde::Serialize;

pub use errors::NestError;

use crate::progress::Progress;

/// Default gap between parts and to the stock edge, in mm. Zero: the CAM adds the kerf.
pub const DEFAULT_GAP: f64 = 0.0;
/// Default search budget (see [`NestOptions::time_limit`]).
pub const DEFAULT_TIME_LIMIT: Duration = Duration::from_secs(60);
/// Default seed of the search.
pub const DEFAULT_SEED: u64 = 0;
/// Number of evenly spaced rotations tried for a part whose rotation is [`Rotations::Free`].
pub const FREE_ROTATION_SAMPLES: u32 = 24;

/// The smallest rotation step accepted, degrees: 360 orientations per part (a step of 1e-9
/// asked for 3.6e11 and aborted on memory).
pub const MINIMUM_ROTATION_STEP_DEGREES: f64 = 1.0;

/// Which rotations a part may take, in degrees counter-clockwise about its own origin.
///
/// A part with a grain direction ([`NestItem::grain_degrees`]) ignores its `Rotations`: it is only
/// placed with its grain along the stock's x axis (see [`NestItem::poses`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Rotations {
    /// Only these angles.
    Fixed(Vec<f64>),
    /// Every multiple of this step in [0, 360).
    Step(f64),
    /// Any angle; the search tries [`FREE_ROTATION_SAMPLES`] evenly spaced ones.
    Free,
}

impl Rotations {
    /// The distinct angles the search tries, each in [0, 360), in increasing order.
    ///
    /// Returns `None` for an empty list, a non-finite angle, or a step outside
    /// [[`MINIMUM_ROTATION_STEP_DEGREES`], 360].
    pub fn angles(&self) -> Option<Vec<f64>> {
        let mut angles: Vec<f64> = match self {
            Rotations::Fixed(list) => {
                if list.is_empty() || list.iter().any(|angle| !angle.is_finite()) {
                    return None;
                }
                list.iter().map(|angle| angle.rem_euclid(360.0)).collect()
            }
            Rotations::Step(step) => {
                if !step.is_finite() || *step < MINIMUM_ROTATION_STEP_DEGREES || *step > 360.0 {
                    return None;
                }
                let count = (360.0 / step - ANGLE_TOLERANCE_DEGREES).ceil().max(1.0) as u32;
                (0..count).map(|index| f64::from(index) * step).collect()
            }
            Rotations::Free => {
                let step = 360.0 / f64::from(FREE_ROTATION_SAMPLES);
                (0..FREE_ROTATION_SAMPLES)
                    .map(|index| f64::from(index) * step)
                    .collect()
            }
        };
        angles.sort_by(f64::total_cmp);
        angles.dedup_by(|a, b| angle_distance(*a, *b) < ANGLE_TOLERANCE_DEGREES);
        if angles.len() > 1
            && angle_distance(angles[0], angles[angles.len() - 1]) < ANGLE_TOLERANCE_DEGREES
        {
            angles.pop();
        }
        Some(angles)
    }

    /// Whether `angle` (degrees) is one of the allowed rotations, within [`ANGLE_TOLERANCE_DEGREES`].
    pub fn allows(&self, angle: f64) -> bool {
        match self {
            Rotations::Free => angle.is_finite(),
            _ => self.angles().is_some_and(|angles| {
                angles
                    .iter()
                    .any(|allowed| angle_distance(*allowed, angle) < ANGLE_TOLERANCE_DEGREES)
            }),
        }
    }
}

/// The direction (degrees) of a grain at `grain` degrees after the part is mirrored (x → −x), or
/// `grain` itself when it is not.
fn grain_after_mirror(grain: f64, mirrored: bool) -> f64 {
    if mirrored { 180.0 - grain } else { grain }
}

/// Two angles closer than this (degrees) are the same rotation.
pub const ANGLE_TOLERANCE_DEGREES: f64 = 1e-6;

/// Distance between two angles on the circle, in degrees, in [0, 180].
fn angle_distance(a: f64, b: f64) -> f64 {
    let difference = (a - b).rem_euclid(360.0);
    difference.min(360.0 - difference)
}

/// One pattern to place, `quantity` times.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NestItem {
    /// Name shown in errors and reports.
    pub name: String,
    /// Outer boundary in mm: a closed ring without a repeated last point, either orientation.
    pub outer: Vec<DVec2>,
    /// Inner boundaries (cut-outs). Kept for the report and the area; the part is placed whole by
    /// its outer ring.
    pub holes: Vec<Vec<DVec2>>,
    /// How many copies to place.
    pub quantity: u32,
    /// Allowed rotations.
    pub rotations: Rotations,
    /// Whether a copy may be mirrored (turned over) before rotation.
    pub mirror_allowed: bool,
    /// Grain direction of the material in the item's own coordinates, degrees counter-clockwise
    /// from its x axis. When set, `rotations` is ignored: a copy is only placed with its grain
    /// along the stock's x axis (the roll length, the sheet width), pointing either way, so at
    /// the two rotations that do so (and, if `mirror_allowed`, the two that do so for the mirrored
    /// part).
    pub grain_degrees: Option<f64>,
}

impl NestItem {
    /// The distinct (rotation in degrees in [0, 360), mirrored) poses a copy may take: with a
    /// grain, the rotations that lay the grain along x; without, every allowed rotation, each also
    /// mirrored when mirroring is allowed. `None` for invalid rotations or a non-finite grain.
    pub fn poses(&self) -> Option<Vec<(f64, bool)>> {
        let mirrors: &[bool] = if self.mirror_allowed {
            &[false, true]
        } else {
            &[false]
        };
        let mut poses = Vec::new();
        for &mirrored in mirrors {
            let angles = match self.grain_degrees {
                Some(grain) => {
                    let along_x = -grain_after_mirror(grain, mirrored);
                    Rotations::Fixed(vec![along_x, along_x + 180.0]).angles()?
                }
                None => self.rotations.angles()?,
            };
            poses.extend(angles.into_iter().map(|angle| (angle, mirrored)));
        }
        Some(poses)
    }

    /// Whether a copy may be placed at `rotation_degrees`, mirrored or not (see
    /// [`NestItem::poses`]), within [`ANGLE_TOLERANCE_DEGREES`].
    pub fn allows(&self, rotation_degrees: f64, mirrored: bool) -> bool {
        if mirrored && !self.mirror_allowed {
            return false;
        }
        match self.grain_degrees {
            Some(grain) => {
                let along_x = grain_after_mirror(grain, mirrored) + rotation_degrees;
                angle_distance(along_x, 0.0) < ANGLE_TOLERANCE_DEGREES
                    || angle_distance(along_x, 180.0) < ANGLE_TOLERANCE_DEGREES
            }
            None => self.rotations.allows(rotation_degrees),
        }
    }

    /// Net area in mm²: outer ring minus holes.
    pub fn area(&self) -> f64 {
        let holes: f64 = self.holes.iter().map(|hole| polygon_area(hole).abs()).sum();
        polygon_area(&self.outer).abs() - holes
    }
}

/// The stock parts are cut from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stock {
    /// Identical rectangular sheets, as many as needed: `width` along x, `height` along y.
    Sheets {
        /// Extent along x, mm.
        width: f64,
        /// Extent along y, mm.
        height: f64,
    },
    /// A roll of fixed `width` (its extent along y) and unbounded length along x.
    Roll {
        /// Extent along y, mm.
        width: f64,
    },
}

impl std::fmt::Display for Stock {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stock::Sheets { width, height } => write!(formatter, "sheets {width} x {height} mm"),
            Stock::Roll { width } => write!(formatter, "roll {width} mm wide"),
        }
    }
}

/// Options of [`nest`]. [`Default`] is the only source of defaults.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NestOptions {
    /// Sheets or roll. Default: a roll 1000 mm wide ([`DEFAULT_ROLL_WIDTH`]).
    pub stock: Stock,
    /// Minimum distance between two parts and between a part and the stock edge, mm.
    /// Default [`DEFAULT_GAP`].
    pub gap: f64,
    /// Search budget. The search counts its work in collision queries and stops after
    /// `time_limit × NOMINAL_QUERIES_PER_SECOND` of them (a deterministic budget), or when this much
    /// wall-clock time has passed, whichever comes first. Default [`DEFAULT_TIME_LIMIT`].
    pub time_limit: Duration,
    /// Seed of the search's random choices. Default [`DEFAULT_SEED`].
    pub seed: u64,
    /// Work budget in collision queries, replacing `time_limit × NOMINAL_QUERIES_PER_SECOND`
    /// (the wall-clock `time_limit` still applies). Default `None`.
    pub work_limit: Option<u64>,
    /// Place small parts inside the holes of larger ones (before the search, see
    /// `search::holes`). Default `false`: a part with holes is placed as a solid.
    pub in_holes: bool,
}

/// Default roll width when none is given, mm.
pub const DEFAULT_ROLL_WIDTH: f64 = 1000.0;

impl Default for NestOptions {
    fn default() -> Self {
        Self {
            stock: Stock::Roll {
                width: DEFAULT_ROLL_WIDTH,
            },
            gap: DEFAULT_GAP,
            time_limit: DEFAULT_TIME_LIMIT,
            seed: DEFAULT_SEED,
            work_limit: None,
            in_holes: false,
        }
    }
}

/// Where one copy of an item went.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Placement {
    /// Index of the item in the input slice.
    pub item: usize,
    /// Which copy of the item (0-based, below its quantity).
    pub copy: u32,
    /// Rotation in degrees, counter-clockwise, in [0, 360).
    pub rotation_degrees: f64,
    /// Whether the item was mirrored (x → −x) before the rotation.
    pub mirrored: bool,
    /// Translation applied after the rotation, mm.
    pub translation: DVec2,
}

impl Placement {
    /// Maps a point of the item's own coordinates to the sheet: first mirror about the item's y
    /// axis if `mirrored` (x → −x), then rotate by `rotation_degrees` counter-clockwise about the
    /// item's origin, then add `translation`.
    pub fn transform_point(&self, point: DVec2) -> DVec2 {
        let mirrored = if self.mirrored {
            DVec2::new(-point.x, point.y)
        } else {
            point
        };
        DVec2::from_angle(self.rotation_degrees.to_radians()).rotate(mirrored) + self.translation
    }

    /// The placement of a copy that sits at `inner` in the frame of the copy placed by `self`
    /// (a part in a hole): `result.transform_point(p) == self.transform_point(inner.transform_point(p))`.
    /// The item and copy are those of `inner`.
    pub fn compose(&self, inner: &Placement) -> Placement {
        let turned = if self.mirrored {
            -inner.rotation_degrees
        } else {
            inner.rotation_degrees
        };
        Placement {
            rotation_degrees: (self.rotation_degrees + turned).rem_euclid(360.0),
            mirrored: self.mirrored != inner.mirrored,
            translation: self.transform_point(inner.translation),
            ..*inner
        }
    }

    /// The ring `points` (outer ring or hole of the item) at its placed position. A mirrored ring
    /// is also reversed, so it keeps its orientation (CCW stays CCW).
    pub fn transform_ring(&self, points: &[DVec2]) -> Vec<DVec2> {
        let mut placed: Vec<DVec2> = points
            .iter()
            .map(|point| self.transform_point(*point))
            .collect();
        if self.mirrored {
            placed.reverse();
        }
        placed
    }
}

/// One sheet, or the used part of the roll.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SheetLayout {
    /// Extent along x, mm: the sheet width, or on a roll the used length.
    pub width: f64,
    /// Extent along y, mm: the sheet height, or the roll width.
    pub height: f64,
    /// Length used along x: from 0 to the far edge of the last part plus the gap, mm.
    pub used_length: f64,
    /// The parts on this sheet.
    pub placements: Vec<Placement>,
    /// Net part area divided by `width × height`.
    pub utilisation: f64,
}

/// Why the search stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// The deterministic work budget was spent: the result depends only on input, options, seed.
    WorkBudget,
    /// The wall-clock limit came first: the result depends on the machine's speed.
    TimeLimit,
    /// Every part fits on the first sheet and nothing better is possible to search for.
    Complete,
}

/// The result of [`nest`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NestLayout {
    /// The stock that was used.
    pub stock: Stock,
    /// The gap kept, mm.
    pub gap: f64,
    /// The sheets in order (exactly one for a roll).
    pub sheets: Vec<SheetLayout>,
    /// Net part area over the total area of all sheets (on a roll: width × used length).
    pub utilisation: f64,
    /// Length used on the last sheet or on the roll, mm.
    pub used_length: f64,
    /// Collision queries spent (the search's unit of work).
    pub work: u64,
    /// Layouts evaluated by the search.
    pub evaluations: u64,
    /// Why the search stopped.
    pub stop_reason: StopReason,
}

/// Nests `items` on the stock of `options`. See the module documentation for the objective.
///
/// Errors on empty input, invalid stock or gap, invalid outlines or rotations, and parts that do
/// not fit on the stock in any allowed rotation.
pub fn nest(
    items: &[NestItem],
    options: &NestOptions,
    progress: &dyn Progress,
) -> Result<NestLayout, NestError> {
    search::Problem::new(items, options)?.solve(progress)
}

pub use crate::geometry::signed_area as polygon_area;

#[cfg(test)]
mod tests {
    use super::*;
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
            mirror_allowed: false,
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
        item.mirror_allowed = true;
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
            polygon_area(&ring) > 0.0,
            "a mirrored ring keeps its orientation"
        );
    }
}
