//! Compaction: a feasible position slid left, then down, until the copy touches something (steps,
//! then bisection). Used by the bottom-left placement and by the placement in holes.

use glam::DVec2;

use crate::nest::collision::{CollisionEngine, JaguaEngine, ShapeId};

/// Slide step of the compaction, as a fraction of the copy's extent along each axis.
pub(super) const COMPACTION_STEP_FRACTION: f64 = 0.25;
/// Bisection steps when a found position is pushed left or down.
const REFINE_STEPS: u32 = 6;
/// Rounds of slide-left then slide-down after a position is found.
const COMPACTION_ROUNDS: u32 = 4;
/// Most steps of one slide.
const MAX_SLIDE_STEPS: u32 = 16;

/// Slides a feasible position left, then down, until it touches something, up to
/// [`COMPACTION_ROUNDS`] times or until it no longer moves. `steps` are the slide steps along x
/// (the scan step) and y (the level spacing).
pub(super) fn compact(
    engine: &mut JaguaEngine,
    shape: ShapeId,
    (mut u, mut v): (f64, f64),
    (u_low, v_low): (f64, f64),
    steps: DVec2,
    to_translation: impl Fn(f64, f64) -> DVec2,
) -> (f64, f64) {
    for _ in 0..COMPACTION_ROUNDS {
        let (previous_u, previous_v) = (u, v);
        u = slide(u, u_low, steps.x, |candidate| {
            engine.fits(shape, to_translation(candidate, v))
        });
        v = slide(v, v_low, steps.y, |candidate| {
            engine.fits(shape, to_translation(u, candidate))
        });
        if (previous_u - u).abs() + (previous_v - v).abs() <= steps.min_element() / 64.0 {
            break;
        }
    }
    (u, v)
}

/// From a feasible `from`, moves towards `limit` (below `from`) in steps of `step` while the
/// position fits (at most [`MAX_SLIDE_STEPS`] steps), then bisects [`REFINE_STEPS`] times between
/// the last position that fits and the first that does not.
fn slide(from: f64, limit: f64, step: f64, mut fits: impl FnMut(f64) -> bool) -> f64 {
    let mut feasible = from;
    for _ in 0..MAX_SLIDE_STEPS {
        if feasible <= limit {
            return limit;
        }
        let next = (feasible - step).max(limit);
        if !fits(next) {
            let mut infeasible = next;
            for _ in 0..REFINE_STEPS {
                let middle = (infeasible + feasible) / 2.0;
                if fits(middle) {
                    feasible = middle;
                } else {
                    infeasible = middle;
                }
            }
            return feasible;
        }
        feasible = next;
    }
    feasible
}
