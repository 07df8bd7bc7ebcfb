//! Parts in holes ([`NestOptions::in_holes`](crate::nest::NestOptions::in_holes)): before the
//! search, small copies are placed inside the holes of large ones, in the large copy's own frame.
//!
//! Copies are taken by decreasing outer area. For each copy of an item with holes (that is not
//! itself in a hole), each hole becomes a container of its own (the hole ring shrunk by the gap,
//! [`JaguaEngine::in_polygon`]); every smaller copy whose outer area is below the hole's area is
//! tried in it, at the first fitting point of a grid of [`HOLE_GRID`] + 1 points per axis over the hole's
//! bounding box (bottom row first, left to right), slid left and down until it touches. A copy in
//! a hole then travels with its host: the search places the host by its outer ring (its holes
//! and their contents lie inside it), and the layout composes the two placements.
//!
//! A copy only goes into a hole in a relative pose that gives it an allowed pose (rotation,
//! mirroring, grain) for *every* pose its host may take; with hosts turned by 90° steps and guests
//! limited to 0° and 180°, nothing fits that rule and the holes stay empty.

use std::sync::Arc;

use glam::DVec2;

use super::compaction::{COMPACTION_STEP_FRACTION, compact};
use super::problem::Problem;
use crate::geometry::{bounding_box, signed_area};
use crate::nest::collision::{CollisionEngine, JaguaEngine, Pose, ShapeId};
use crate::nest::layout::Placement;

/// Grid intervals per axis (so `HOLE_GRID + 1` points) tried for a copy in a hole.
pub const HOLE_GRID: u32 = 24;

/// A copy placed inside a hole of another copy, in the host's own frame.
#[derive(Debug, Clone, Copy)]
pub(super) struct Guest {
    /// Index of the copy.
    pub(super) copy: usize,
    /// Its oriented shape (rotation and mirroring relative to the host).
    pub(super) shape: ShapeId,
    /// Its translation in the host's frame.
    pub(super) translation: DVec2,
}

impl Problem<'_> {
    /// For every copy, the copies placed in its holes: all empty unless `in_holes` is set.
    pub(super) fn fill_holes(&self) -> Vec<Vec<Guest>> {
        let mut guests: Vec<Vec<Guest>> = vec![Vec::new(); self.copies.len()];
        if !self.options.in_holes {
            return guests;
        }
        let mut is_guest = vec![false; self.copies.len()];
        let outer_area = |copy: usize| signed_area(&self.items[self.copies[copy].item].outer).abs();
        for host in 0..self.copies.len() {
            let host_item = self.copies[host].item;
            if is_guest[host] {
                continue;
            }
            for hole in &self.items[host_item].holes {
                let Ok(mut engine) = JaguaEngine::in_polygon(Arc::clone(&self.library), hole)
                else {
                    continue;
                };
                let hole_area = signed_area(hole).abs();
                let mut failed_items = Vec::new();
                for (guest, guest_copy) in self.copies.iter().enumerate().skip(host + 1) {
                    let guest_item = guest_copy.item;
                    if is_guest[guest]
                        || failed_items.contains(&guest_item)
                        || outer_area(guest) >= hole_area
                    {
                        continue;
                    }
                    match self.position_in_hole(&mut engine, host_item, guest_item, hole) {
                        Some((shape, translation)) => {
                            engine.insert(guest as u32, Pose::upright(shape), translation);
                            is_guest[guest] = true;
                            guests[host].push(Guest {
                                copy: guest,
                                shape,
                                translation,
                            });
                        }
                        None => failed_items.push(guest_item),
                    }
                }
            }
        }
        guests
    }

    /// The first grid position (bottom row first), slid left and down, where a copy of
    /// `guest_item` fits in the hole of `engine`, in a relative pose allowed under every pose of
    /// `host_item`.
    fn position_in_hole(
        &self,
        engine: &mut JaguaEngine,
        host_item: usize,
        guest_item: usize,
        hole: &[DVec2],
    ) -> Option<(ShapeId, DVec2)> {
        let (hole_min, hole_max) = bounding_box(hole);
        for &shape in &self.item_shapes[guest_item] {
            if !self.allowed_under_every_host_pose(host_item, shape) {
                continue;
            }
            let orientation = &self.orientations[shape];
            let size = orientation.max - orientation.min;
            let (low, high) = (hole_min, hole_max - size);
            if high.x < low.x || high.y < low.y {
                continue;
            }
            let to_translation = |u: f64, v: f64| DVec2::new(u, v) - orientation.min;
            let grid = f64::from(HOLE_GRID);
            for row in 0..=HOLE_GRID {
                for column in 0..=HOLE_GRID {
                    let u = low.x + (high.x - low.x) * f64::from(column) / grid;
                    let v = low.y + (high.y - low.y) * f64::from(row) / grid;
                    if engine.fits(shape, to_translation(u, v)) {
                        let steps = size * COMPACTION_STEP_FRACTION;
                        let (u, v) =
                            compact(engine, shape, (u, v), (low.x, low.y), steps, to_translation);
                        return Some((shape, to_translation(u, v)));
                    }
                }
            }
        }
        None
    }

    /// Whether a guest in oriented shape `shape`, relative to its host, has an allowed pose
    /// whatever allowed pose the host (a copy of `host_item`) takes: a host free to rotate, which
    /// the search through overlap turns to any angle, only takes guests free to rotate too.
    fn allowed_under_every_host_pose(&self, host_item: usize, shape: ShapeId) -> bool {
        let guest = &self.orientations[shape];
        if self.turns[host_item] && !self.turns[guest.item] {
            return false;
        }
        let relative = Placement {
            item: guest.item,
            copy: 0,
            rotation_degrees: guest.rotation_degrees,
            mirrored: guest.mirrored,
            translation: DVec2::ZERO,
        };
        self.item_shapes[host_item].iter().all(|&host_shape| {
            let host = &self.orientations[host_shape];
            let host_pose = Placement {
                rotation_degrees: host.rotation_degrees,
                mirrored: host.mirrored,
                ..relative
            };
            let pose = host_pose.compose(&relative);
            self.items[guest.item].allows(pose.rotation_degrees, pose.mirrored)
        })
    }

    /// The placements of the guests (`guests`, from [`Problem::fill_holes`]) of a copy placed at
    /// `host`.
    pub(super) fn guest_placements(
        &self,
        guests: &[Vec<Guest>],
        copy: usize,
        host: &Placement,
    ) -> Vec<Placement> {
        guests[copy]
            .iter()
            .map(|guest| {
                let copy = self.copies[guest.copy];
                host.compose(&self.placement(copy, Pose::upright(guest.shape), guest.translation))
            })
            .collect()
    }

    /// The copies the search places itself: all but the guests (`guests`, from
    /// [`Problem::fill_holes`]), in order of decreasing area.
    pub(super) fn hosts_and_others(&self, guests: &[Vec<Guest>]) -> Vec<usize> {
        let guests: Vec<usize> = guests.iter().flatten().map(|guest| guest.copy).collect();
        (0..self.copies.len())
            .filter(|copy| !guests.contains(copy))
            .collect()
    }
}
