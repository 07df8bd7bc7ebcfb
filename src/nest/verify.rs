//! Independent check of a [`NestLayout`], in exact f64 geometry of its own: it shares no code with
//! the collision engine or the search, so a bug there cannot hide here.
//!
//! For every sheet: every copy of every item is placed exactly once, with an allowed rotation and
//! mirroring; every placed outer ring lies inside the sheet at least `gap` from its edges; no two
//! rings overlap (a proper crossing of two edges, or a vertex, an edge midpoint or a point just
//! inside a convex corner of one ring lying strictly inside the other); and, when the gap is
//! positive, every two rings are at least `gap` apart (the smallest segment-to-segment distance).
//!
//! Tolerance: distances are compared with [`TOLERANCE_RELATIVE`] × the sheet's largest side, so
//! that round-off (and the f32 geometry of the engine, which keeps a wider margin) does not raise
//! false alarms. Overlaps shallower than that tolerance are not reported.
//!
//! Parts are solids bounded by their outer rings, except that a part may lie inside a hole of
//! another (no edge of the two rings properly crossing, every test point of the inner part inside
//! the hole or on its edge); it must then be at least `gap` from the hole's ring.
//! Pairs are found with a sweep over bounding boxes sorted by their left edge, so a few hundred
//! parts take milliseconds.

use std::fmt;

use glam::DVec2;
use serde::Serialize;

use super::item::NestItem;
use super::layout::{NestLayout, Placement};
use crate::geometry::distance_to_segment;

/// Distances within this fraction of the sheet's largest side are considered equal: the slack of
/// every check (inside the sheet, inside a hole, the gap, the depth of an overlap), so round-off
/// and the engine's f32 margin raise no false alarm.
pub const TOLERANCE_RELATIVE: f64 = 1e-7;
/// How far inside a convex corner the corner test point lies, as a fraction of the shorter of
/// the corner's two edges.
const CORNER_PROBE_FRACTION: f64 = 1e-3;

/// One defect of a layout.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Violation {
    /// A placement names an item that does not exist or a copy beyond its quantity.
    UnknownCopy {
        /// The sheet (0-based).
        sheet: usize,
        /// The item index given.
        item: usize,
        /// The copy given.
        copy: u32,
    },
    /// A copy is placed more than once.
    DuplicateCopy {
        /// The item.
        item: usize,
        /// The copy.
        copy: u32,
    },
    /// A copy is not placed at all.
    MissingCopy {
        /// The item.
        item: usize,
        /// The copy.
        copy: u32,
    },
    /// A copy has a rotation the item does not allow, or is mirrored when it may not be.
    OrientationNotAllowed {
        /// The item.
        item: usize,
        /// The copy.
        copy: u32,
        /// The rotation used, degrees.
        rotation_degrees: f64,
        /// Whether it was mirrored.
        mirrored: bool,
    },
    /// A copy reaches closer than the gap to the sheet edge, or beyond it.
    OutsideSheet {
        /// The sheet.
        sheet: usize,
        /// The item.
        item: usize,
        /// The copy.
        copy: u32,
        /// How far past the allowed area (sheet minus gap) it reaches, mm.
        overshoot: f64,
    },
    /// Two copies overlap.
    Overlap {
        /// The sheet.
        sheet: usize,
        /// First copy (item, copy).
        first: (usize, u32),
        /// Second copy (item, copy).
        second: (usize, u32),
    },
    /// Two copies are closer than the gap.
    GapTooSmall {
        /// The sheet.
        sheet: usize,
        /// First copy (item, copy).
        first: (usize, u32),
        /// Second copy (item, copy).
        second: (usize, u32),
        /// The measured distance, mm.
        distance: f64,
        /// The required gap, mm.
        gap: f64,
    },
}

impl fmt::Display for Violation {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Violation::UnknownCopy { sheet, item, copy } => {
                write!(
                    formatter,
                    "sheet {sheet}: placement of unknown item {item} copy {copy}"
                )
            }
            Violation::DuplicateCopy { item, copy } => write!(
                formatter,
                "item {item} copy {copy} is placed more than once"
            ),
            Violation::MissingCopy { item, copy } => {
                write!(formatter, "item {item} copy {copy} is not placed")
            }
            Violation::OrientationNotAllowed {
                item,
                copy,
                rotation_degrees,
                mirrored,
            } => write!(
                formatter,
                "item {item} copy {copy}: rotation {rotation_degrees} degrees{} is not allowed",
                if *mirrored { " mirrored" } else { "" }
            ),
            Violation::OutsideSheet {
                sheet,
                item,
                copy,
                overshoot,
            } => write!(
                formatter,
                "sheet {sheet}: item {item} copy {copy} reaches {overshoot:.6} mm past the sheet edge minus the gap"
            ),
            Violation::Overlap {
                sheet,
                first,
                second,
            } => write!(
                formatter,
                "sheet {sheet}: item {} copy {} overlaps item {} copy {}",
                first.0, first.1, second.0, second.1
            ),
            Violation::GapTooSmall {
                sheet,
                first,
                second,
                distance,
                gap,
            } => write!(
                formatter,
                "sheet {sheet}: item {} copy {} and item {} copy {} are {distance:.6} mm apart, less than the gap {gap} mm",
                first.0, first.1, second.0, second.1
            ),
        }
    }
}

/// A placed ring with its bounding box and its holes.
struct Placed {
    key: (usize, u32),
    ring: Vec<DVec2>,
    holes: Vec<Vec<DVec2>>,
    min: DVec2,
    max: DVec2,
}

/// Every defect of `layout` for `items` (empty when the layout is valid).
pub fn verify(items: &[NestItem], layout: &NestLayout) -> Vec<Violation> {
    let mut violations = check_copies(items, layout);
    for (sheet_index, sheet) in layout.sheets.iter().enumerate() {
        let tolerance = TOLERANCE_RELATIVE * sheet.width.max(sheet.height);
        let mut placed: Vec<Placed> = sheet
            .placements
            .iter()
            .filter_map(|placement| place(items, placement))
            .collect();
        for part in &placed {
            let low = DVec2::splat(layout.gap);
            let high = DVec2::new(sheet.width, sheet.height) - low;
            let overshoot = (low - part.min).max(part.max - high).max_element();
            if overshoot > tolerance {
                violations.push(Violation::OutsideSheet {
                    sheet: sheet_index,
                    item: part.key.0,
                    copy: part.key.1,
                    overshoot,
                });
            }
        }
        placed.sort_by(|a, b| a.min.x.total_cmp(&b.min.x));
        let reach = layout.gap + tolerance;
        for (index, first) in placed.iter().enumerate() {
            for second in placed[index + 1..]
                .iter()
                .take_while(|second| second.min.x <= first.max.x + reach)
            {
                if second.min.y > first.max.y + reach || first.min.y > second.max.y + reach {
                    continue;
                }
                let hole = enclosing_hole(first, second, tolerance)
                    .or_else(|| enclosing_hole(second, first, tolerance));
                if let Some((hole, guest)) = hole {
                    let distance = ring_distance(hole, guest);
                    if layout.gap > 0.0 && distance < layout.gap - tolerance {
                        violations.push(Violation::GapTooSmall {
                            sheet: sheet_index,
                            first: first.key,
                            second: second.key,
                            distance,
                            gap: layout.gap,
                        });
                    }
                } else if overlaps(&first.ring, &second.ring, tolerance) {
                    violations.push(Violation::Overlap {
                        sheet: sheet_index,
                        first: first.key,
                        second: second.key,
                    });
                } else if layout.gap > 0.0 {
                    let distance = ring_distance(&first.ring, &second.ring);
                    if distance < layout.gap - tolerance {
                        violations.push(Violation::GapTooSmall {
                            sheet: sheet_index,
                            first: first.key,
                            second: second.key,
                            distance,
                            gap: layout.gap,
                        });
                    }
                }
            }
        }
    }
    violations
}

/// Unknown, duplicate, missing copies and disallowed orientations.
fn check_copies(items: &[NestItem], layout: &NestLayout) -> Vec<Violation> {
    let mut violations = Vec::new();
    let mut seen: Vec<Vec<bool>> = items
        .iter()
        .map(|item| vec![false; item.quantity as usize])
        .collect();
    for (sheet, placements) in layout
        .sheets
        .iter()
        .map(|sheet| &sheet.placements)
        .enumerate()
    {
        for placement in placements {
            let (item, copy) = (placement.item, placement.copy);
            let Some(slot) = seen
                .get_mut(item)
                .and_then(|copies| copies.get_mut(copy as usize))
            else {
                violations.push(Violation::UnknownCopy { sheet, item, copy });
                continue;
            };
            if *slot {
                violations.push(Violation::DuplicateCopy { item, copy });
            }
            *slot = true;
            let entry = &items[item];
            if !entry.allows(placement.rotation_degrees, placement.mirrored) {
                violations.push(Violation::OrientationNotAllowed {
                    item,
                    copy,
                    rotation_degrees: placement.rotation_degrees,
                    mirrored: placement.mirrored,
                });
            }
        }
    }
    for (item, copies) in seen.iter().enumerate() {
        for (copy, placed) in copies.iter().enumerate() {
            if !placed {
                violations.push(Violation::MissingCopy {
                    item,
                    copy: copy as u32,
                });
            }
        }
    }
    violations
}

fn place(items: &[NestItem], placement: &Placement) -> Option<Placed> {
    let item = items.get(placement.item)?;
    let ring = placement.transform_ring(&item.outer);
    let (min, max) = ring.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(min, max), point| (min.min(*point), max.max(*point)),
    );
    Some(Placed {
        key: (placement.item, placement.copy),
        ring,
        holes: item
            .holes
            .iter()
            .map(|hole| placement.transform_ring(hole))
            .collect(),
        min,
        max,
    })
}

/// The hole of `host` that holds all of `guest` (no proper edge crossing, every test point of
/// the guest inside the hole or within `tolerance` of its ring), with the guest's ring.
fn enclosing_hole<'a>(
    host: &'a Placed,
    guest: &'a Placed,
    tolerance: f64,
) -> Option<(&'a [DVec2], &'a [DVec2])> {
    host.holes
        .iter()
        .find(|hole| {
            let crossing = edges(hole)
                .any(|edge| edges(&guest.ring).any(|other| properly_cross(edge, other, tolerance)));
            !crossing
                && probes(&guest.ring).all(|point| {
                    strictly_inside(point, hole, tolerance)
                        || edges(hole)
                            .any(|(start, end)| distance_to_segment(point, start, end) <= tolerance)
                })
        })
        .map(|hole| (hole.as_slice(), guest.ring.as_slice()))
}

/// The edges of a ring as (start, end) pairs.
fn edges(ring: &[DVec2]) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
    (0..ring.len()).map(move |index| (ring[index], ring[(index + 1) % ring.len()]))
}

/// Whether the interiors of two rings overlap by more than `tolerance`.
fn overlaps(first: &[DVec2], second: &[DVec2], tolerance: f64) -> bool {
    let crossing =
        edges(first).any(|edge| edges(second).any(|other| properly_cross(edge, other, tolerance)));
    crossing
        || probes(first).any(|point| strictly_inside(point, second, tolerance))
        || probes(second).any(|point| strictly_inside(point, first, tolerance))
}

/// Test points of a ring: its vertices, its edge midpoints, and a point just inside each convex
/// corner.
fn probes(ring: &[DVec2]) -> impl Iterator<Item = DVec2> + '_ {
    let orientation = ring_orientation(ring);
    (0..ring.len()).flat_map(move |index| {
        let previous = ring[(index + ring.len() - 1) % ring.len()];
        let (corner, next) = (ring[index], ring[(index + 1) % ring.len()]);
        let convex = (corner - previous).perp_dot(next - corner) * orientation > 0.0;
        let reach =
            CORNER_PROBE_FRACTION * (corner - previous).length().min((next - corner).length());
        let inward = ((previous - corner).normalize_or_zero()
            + (next - corner).normalize_or_zero())
        .normalize_or_zero();
        let corner_probe = convex.then_some(corner + inward * reach);
        [Some(corner), Some((corner + next) / 2.0), corner_probe]
            .into_iter()
            .flatten()
    })
}

/// +1 for a counter-clockwise ring, −1 for a clockwise one.
fn ring_orientation(ring: &[DVec2]) -> f64 {
    let twice_area: f64 = edges(ring).map(|(start, end)| start.perp_dot(end)).sum();
    twice_area.signum()
}

/// Whether two segments cross at a single point interior to both, each endpoint being more than
/// `tolerance` from the other segment's line.
fn properly_cross((a, b): (DVec2, DVec2), (c, d): (DVec2, DVec2), tolerance: f64) -> bool {
    let side = |start: DVec2, end: DVec2, point: DVec2| {
        let length = (end - start).length();
        if length > 0.0 {
            (end - start).perp_dot(point - start) / length
        } else {
            0.0
        }
    };
    let (side_c, side_d) = (side(a, b, c), side(a, b, d));
    let (side_a, side_b) = (side(c, d, a), side(c, d, b));
    let apart = |first: f64, second: f64| {
        (first > tolerance && second < -tolerance) || (first < -tolerance && second > tolerance)
    };
    apart(side_c, side_d) && apart(side_a, side_b)
}

/// Whether `point` is inside `ring` (even-odd rule) and more than `tolerance` from its boundary.
fn strictly_inside(point: DVec2, ring: &[DVec2], tolerance: f64) -> bool {
    let mut inside = false;
    for (start, end) in edges(ring) {
        if distance_to_segment(point, start, end) <= tolerance {
            return false;
        }
        if (start.y > point.y) != (end.y > point.y) {
            let crossing_x = start.x + (point.y - start.y) / (end.y - start.y) * (end.x - start.x);
            if point.x < crossing_x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Smallest distance between the boundaries of two non-overlapping rings.
fn ring_distance(first: &[DVec2], second: &[DVec2]) -> f64 {
    let mut smallest = f64::INFINITY;
    for (a, b) in edges(first) {
        for (c, d) in edges(second) {
            let distance = distance_to_segment(a, c, d)
                .min(distance_to_segment(b, c, d))
                .min(distance_to_segment(c, a, b))
                .min(distance_to_segment(d, a, b));
            smallest = smallest.min(distance);
        }
    }
    smallest
}

#[cfg(test)]
pub(crate) mod tests {
    use crate::nest::layout::{SheetLayout, StopReason};
    use crate::nest::rotations::Rotations;
    use crate::nest::stock::Stock;
    use crate::nest::verify::*;

    /// A square item of side `side` mm, in `quantity`, upright only (a fixture other nest tests
    /// share).
    pub(crate) fn square(name: &str, side: f64, quantity: u32) -> NestItem {
        let outer = vec![
            DVec2::ZERO,
            DVec2::new(side, 0.0),
            DVec2::new(side, side),
            DVec2::new(0.0, side),
        ];
        polygon(name, outer, quantity, Rotations::Fixed(vec![0.0]))
    }

    /// An item with the ring `outer`, no hole, no mirroring and no grain.
    pub(crate) fn polygon(
        name: &str,
        outer: Vec<DVec2>,
        quantity: u32,
        rotations: Rotations,
    ) -> NestItem {
        NestItem {
            name: name.to_string(),
            outer,
            holes: Vec::new(),
            quantity,
            rotations,
            mirror: None,
            grain_degrees: None,
        }
    }

    fn at(item: usize, copy: u32, x: f64, y: f64) -> Placement {
        Placement {
            item,
            copy,
            rotation_degrees: 0.0,
            mirrored: false,
            translation: DVec2::new(x, y),
        }
    }

    fn layout(gap: f64, placements: Vec<Placement>) -> NestLayout {
        NestLayout {
            stock: Stock::Sheets {
                width: 100.0,
                height: 50.0,
            },
            gap,
            sheets: vec![SheetLayout {
                width: 100.0,
                height: 50.0,
                used_length: 100.0,
                placements,
                utilisation: 0.0,
            }],
            utilisation: 0.0,
            used_length: 100.0,
            work: 0,
            evaluations: 0,
            stop_reason: StopReason::WorkBudget,
        }
    }

    #[test]
    fn valid_layout_with_touching_parts_passes() {
        let items = [square("a", 10.0, 2)];
        let placed = layout(0.0, vec![at(0, 0, 0.0, 0.0), at(0, 1, 10.0, 0.0)]);
        assert_eq!(verify(&items, &placed), Vec::new());
    }

    /// A 30 mm square frame with a 20 mm square hole, and a 5 mm square.
    fn frame_and_square() -> [NestItem; 2] {
        let mut frame = square("frame", 30.0, 1);
        frame.holes = vec![vec![
            DVec2::new(5.0, 5.0),
            DVec2::new(5.0, 25.0),
            DVec2::new(25.0, 25.0),
            DVec2::new(25.0, 5.0),
        ]];
        [frame, square("small", 5.0, 1)]
    }

    #[test]
    fn a_part_inside_a_hole_with_the_gap_passes() {
        let items = frame_and_square();
        let placed = layout(1.0, vec![at(0, 0, 1.0, 1.0), at(1, 0, 7.0, 7.0)]);
        assert_eq!(verify(&items, &placed), Vec::new());
    }

    #[test]
    fn a_part_too_close_to_the_hole_edge_or_across_it_is_caught() {
        let items = frame_and_square();
        let close = verify(
            &items,
            &layout(1.0, vec![at(0, 0, 1.0, 1.0), at(1, 0, 6.5, 12.0)]),
        );
        assert!(
            matches!(close.as_slice(), [Violation::GapTooSmall { distance, .. }] if (distance - 0.5).abs() < 1e-9),
            "{close:?}"
        );
        let across = verify(
            &items,
            &layout(0.0, vec![at(0, 0, 0.0, 0.0), at(1, 0, 3.0, 12.0)]),
        );
        assert!(
            matches!(across.as_slice(), [Violation::Overlap { .. }]),
            "{across:?}"
        );
        let in_the_material = verify(
            &items,
            &layout(0.0, vec![at(0, 0, 0.0, 0.0), at(1, 0, 10.0, 0.0)]),
        );
        assert!(
            matches!(in_the_material.as_slice(), [Violation::Overlap { .. }]),
            "a part inside the frame's material, not its hole: {in_the_material:?}"
        );
    }

    #[test]
    fn planted_overlap_is_caught() {
        let items = [square("a", 10.0, 2)];
        let placed = layout(0.0, vec![at(0, 0, 0.0, 0.0), at(0, 1, 9.0, 3.0)]);
        let violations = verify(&items, &placed);
        assert!(
            matches!(violations.as_slice(), [Violation::Overlap { .. }]),
            "{violations:?}"
        );
    }

    #[test]
    fn coincident_and_collinear_overlaps_are_caught() {
        let items = [square("a", 10.0, 2)];
        for offset in [0.0, 5.0] {
            let placed = layout(0.0, vec![at(0, 0, 0.0, 0.0), at(0, 1, offset, 0.0)]);
            let violations = verify(&items, &placed);
            assert!(
                matches!(violations.as_slice(), [Violation::Overlap { .. }]),
                "{violations:?}"
            );
        }
    }

    #[test]
    fn part_outside_the_sheet_is_caught() {
        let items = [square("a", 10.0, 1)];
        let placed = layout(0.0, vec![at(0, 0, 95.0, 0.0)]);
        let violations = verify(&items, &placed);
        assert!(
            matches!(violations.as_slice(), [Violation::OutsideSheet { overshoot, .. }] if (overshoot - 5.0).abs() < 1e-9),
            "{violations:?}"
        );
    }

    #[test]
    fn too_small_gap_is_caught_with_the_distance() {
        let items = [square("a", 10.0, 2)];
        let placed = layout(2.0, vec![at(0, 0, 2.0, 2.0), at(0, 1, 13.0, 2.0)]);
        let violations = verify(&items, &placed);
        assert!(
            matches!(violations.as_slice(), [Violation::GapTooSmall { distance, .. }] if (distance - 1.0).abs() < 1e-9),
            "{violations:?}"
        );
        let edge = layout(2.0, vec![at(0, 0, 1.0, 2.0), at(0, 1, 20.0, 2.0)]);
        assert!(matches!(
            verify(&items, &edge).as_slice(),
            [Violation::OutsideSheet { .. }]
        ));
    }

    #[test]
    fn missing_duplicate_and_disallowed_copies_are_caught() {
        let items = [square("a", 10.0, 2)];
        let mut rotated = at(0, 0, 20.0, 0.0);
        rotated.rotation_degrees = 90.0;
        rotated.translation.x += 10.0;
        let placed = layout(0.0, vec![rotated, at(0, 0, 40.0, 0.0)]);
        let violations = verify(&items, &placed);
        assert!(
            violations
                .iter()
                .any(|violation| matches!(violation, Violation::OrientationNotAllowed { .. }))
        );
        assert!(
            violations
                .iter()
                .any(|violation| matches!(violation, Violation::DuplicateCopy { .. }))
        );
        assert!(violations.contains(&Violation::MissingCopy { item: 0, copy: 1 }));
    }
}
