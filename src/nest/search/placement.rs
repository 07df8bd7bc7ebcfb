//! Constructive bottom-left placement: copies are taken in the sequence's order; each goes to the
//! first bin where it fits, at the position found with the lowest right edge, then the lowest
//! bottom edge: seeded uniform samples left of the bin's front, the best few compacted.

use std::sync::Arc;

use glam::DVec2;

use super::compaction::{COMPACTION_STEP_FRACTION, compact};
use super::problem::{CLEARANCE_RELATIVE, LENGTH_TOLERANCE_RELATIVE, Problem};
use super::random::SplitMix64;
use super::solution::{Placed, Solution};
use crate::nest::collision::{CollisionEngine, JaguaEngine, Pose, ShapeId};

/// Random positions tried per orientation of a copy with at most [`SAMPLED_ORIENTATIONS`]
/// orientations.
pub const SAMPLES_PER_ORIENTATION: usize = 200;
/// A copy with more orientations than this (free rotation: 24) shares the samples of this many
/// among them, so that a layout costs about what one of four orientations costs.
pub const SAMPLED_ORIENTATIONS: usize = 4;
/// How many of the fitting samples (those with the lowest right edge) are compacted.
pub const COMPACTED_CANDIDATES: usize = 4;
/// Samples are drawn over the height range widened by this fraction on each side and clamped, so
/// that about that fraction of them lie exactly on the bottom or the top edge.
const EDGE_SAMPLE_FRACTION: f64 = 0.1;

/// What one placement pass works with.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pass {
    /// Length of the roll (ignored for sheets).
    pub(super) roll_length: f64,
    /// Whether a copy that finds no room is left out (strip shrinking) rather than failing.
    pub(super) allow_unplaced: bool,
}

impl Problem<'_> {
    /// Places the copies of `solution.order` that are not placed yet, in order.
    pub(super) fn extend(
        &self,
        mut solution: Solution<JaguaEngine>,
        pass: Pass,
        random: &mut SplitMix64,
    ) -> (Option<Solution<JaguaEngine>>, u64) {
        let queries_before: u64 = solution.bins.iter().map(CollisionEngine::queries).sum();
        let mut fronts = vec![f64::NEG_INFINITY; solution.bins.len()];
        for placed in solution.placed.iter().flatten() {
            fronts[placed.bin] = fronts[placed.bin].max(placed.right);
        }
        let spent = |bins: &[JaguaEngine]| {
            bins.iter().map(CollisionEngine::queries).sum::<u64>() - queries_before
        };
        for position in solution.placed.len()..solution.order.len() {
            let copy = solution.order[position];
            let item = self.copies[copy].item;
            let mut found = None;
            for bin in 0..=solution.bins.len() {
                if bin == solution.bins.len() {
                    if self.sheet_width.is_none() && bin > 0 {
                        break;
                    }
                    let Some(engine) = self.new_bin(pass.roll_length) else {
                        break;
                    };
                    solution.bins.push(engine);
                    fronts.push(f64::NEG_INFINITY);
                }
                if let Some((shape, translation, right)) =
                    self.best_position(&mut solution.bins[bin], item, fronts[bin], pass, random)
                {
                    found = Some(Placed {
                        bin,
                        pose: Pose::upright(shape),
                        translation,
                        right,
                    });
                    break;
                }
            }
            let Some(placed) = found else {
                if pass.allow_unplaced {
                    solution.placed.push(None);
                    continue;
                }
                let work = spent(&solution.bins);
                return (None, work);
            };
            solution.bins[placed.bin].insert(copy as u32, placed.pose, placed.translation);
            fronts[placed.bin] = fronts[placed.bin].max(placed.right);
            solution.placed.push(Some(placed));
        }
        let work = spent(&solution.bins);
        (Some(solution), work)
    }

    /// An empty sheet, or the roll cut at `roll_length`.
    fn new_bin(&self, roll_length: f64) -> Option<JaguaEngine> {
        let length = self.sheet_width.unwrap_or(roll_length);
        JaguaEngine::new(
            Arc::clone(&self.library),
            DVec2::ZERO,
            DVec2::new(length, self.height),
        )
        .ok()
    }

    /// Lowest-right-edge position found for a copy of `item` in one bin: (shape, translation,
    /// right edge). Per orientation: [`SAMPLES_PER_ORIENTATION`] uniform samples (shared among the
    /// orientations when there are more than [`SAMPLED_ORIENTATIONS`]) left of the front
    /// (beyond it everything fits, so the front itself is the fallback), the
    /// [`COMPACTED_CANDIDATES`] lowest right edges among those that fit are slid left and down
    /// until they touch, and the best is kept (lowest right edge, then lowest bottom).
    pub(super) fn best_position(
        &self,
        engine: &mut JaguaEngine,
        item: usize,
        front: f64,
        pass: Pass,
        random: &mut SplitMix64,
    ) -> Option<(ShapeId, DVec2, f64)> {
        let clearance = CLEARANCE_RELATIVE * self.scale;
        let inset = self.library.inflation() + clearance;
        let tolerance = LENGTH_TOLERANCE_RELATIVE * self.scale;
        let mut best: Option<(ShapeId, DVec2, f64, f64)> = None;
        let shapes = &self.item_shapes[item];
        let samples =
            SAMPLES_PER_ORIENTATION * SAMPLED_ORIENTATIONS.min(shapes.len()) / shapes.len();
        for &shape in shapes {
            let orientation = &self.orientations[shape];
            let size = orientation.max - orientation.min;
            let (u_low, v_low) = (inset, inset);
            let (u_high, v_high) = (
                pass.roll_length - inset - size.x,
                self.height - inset - size.y,
            );
            if u_high < u_low || v_high < v_low {
                continue;
            }
            let to_translation = |u: f64, v: f64| DVec2::new(u, v) - orientation.min;
            let reach = (front + clearance).max(u_low).min(u_high);
            let mut candidates: Vec<(f64, f64)> = Vec::with_capacity(COMPACTED_CANDIDATES + 2);
            for corner in [(reach, v_low), (reach, v_high)] {
                if engine.fits(shape, to_translation(corner.0, corner.1)) {
                    candidates.push(corner);
                }
            }
            let span = v_high - v_low;
            for _ in 0..samples {
                let u = u_low + random.unit() * (reach - u_low);
                let widened = v_low - EDGE_SAMPLE_FRACTION * span
                    + random.unit() * (1.0 + 2.0 * EDGE_SAMPLE_FRACTION) * span;
                let v = widened.clamp(v_low, v_high);
                let worst_kept = if candidates.len() < COMPACTED_CANDIDATES {
                    f64::INFINITY
                } else {
                    candidates
                        .iter()
                        .map(|candidate| candidate.0)
                        .fold(f64::NEG_INFINITY, f64::max)
                };
                let best_right = best.map_or(f64::INFINITY, |(_, _, right, _)| right);
                if u >= worst_kept || u + size.x >= best_right - tolerance {
                    continue;
                }
                if engine.fits(shape, to_translation(u, v)) {
                    if candidates.len() == COMPACTED_CANDIDATES
                        && let Some(worst) = candidates
                            .iter()
                            .position(|candidate| candidate.0 >= worst_kept)
                    {
                        candidates.swap_remove(worst);
                    }
                    candidates.push((u, v));
                }
            }
            let steps = size * COMPACTION_STEP_FRACTION;
            for candidate in candidates {
                let (u, v) = compact(
                    engine,
                    shape,
                    candidate,
                    (u_low, v_low),
                    steps,
                    to_translation,
                );
                let right = u + size.x;
                let better = best.is_none_or(|(_, _, best_right, best_v)| {
                    right < best_right - tolerance
                        || (right <= best_right + tolerance && v < best_v - tolerance)
                });
                if better {
                    best = Some((shape, to_translation(u, v), right, v));
                }
            }
        }
        best.map(|(shape, translation, right, _)| (shape, translation, right))
    }
}
