//! Search through overlap on a roll, in two phases from the sequence search's best layout, both
//! built on the separator (`separator.rs`):
//!
//! 1. **Exploration** ([`EXPLORATION_SHARE`] of the budget): cut the strip
//!    [`EXPLORATION_STEP`] shorter at a random split (the parts right of it move left, into
//!    overlap) and separate. A separated layout is the new best and is cut again. When separation
//!    fails, the least-overlapping layout joins a pool of failed layouts at that length; one of
//!    them (the better ones more likely) is disrupted (two large parts swap places, carrying the
//!    parts they land on into the places they left) and separated again, at the same length:
//!    the search keeps working on the short strip instead of going back.
//! 2. **Compression** (the rest): from the best, cut by a step that falls linearly with the work
//!    spent from [`COMPRESSION_STEPS`]`.0` to `.1`, at a random split, and separate; keep the
//!    result if it separates, else go back to the best.

use std::sync::Arc;

use glam::DVec2;

use super::problem::{CLEARANCE_RELATIVE, Problem};
use super::random::SplitMix64;
use super::separator::{Limits, Part, Separator};
use super::solution::{Placed, Solution};
use crate::nest::collision::{CollisionEngine, JaguaEngine};

/// Share of the budget of the search through overlap spent on exploration.
pub const EXPLORATION_SHARE: f64 = 0.8;
/// Exploration: each cut shortens the strip by this fraction of its length.
pub const EXPLORATION_STEP: f64 = 0.001;
/// Compression: the cut, as a fraction of the strip's length, at the start and at the end.
pub const COMPRESSION_STEPS: (f64, f64) = (0.0005, 0.00001);
/// When a separation gives up during exploration.
const EXPLORATION_LIMITS: Limits = Limits {
    rounds: 200,
    strikes: 3,
};
/// When a separation gives up during compression.
const COMPRESSION_LIMITS: Limits = Limits {
    rounds: 100,
    strikes: 5,
};
/// Spread of the choice in the pool of failed layouts: the rank drawn is `|N(0, σ)| × pool size`
/// (the least overlapping first).
const POOL_SPREAD: f64 = 0.25;

impl Problem<'_> {
    /// Searches through overlap from the complete roll layout `best` within `budget` work
    /// (collision queries), calling `stop` with the work spent (true ends the search) and
    /// `on_best` with the length of each shorter separated layout; returns the shortest separated
    /// layout found (or `None` if none is shorter) and the work.
    pub(super) fn compress(
        &self,
        best: &Solution<JaguaEngine>,
        budget: u64,
        random: &mut SplitMix64,
        stop: impl FnMut(u64) -> bool,
        on_best: impl FnMut(f64),
    ) -> (Option<Solution<JaguaEngine>>, u64) {
        let parts = parts_of(best);
        if parts.len() != best.order.len() || parts.len() < 2 {
            return (None, 0);
        }
        let length = self.cost(best).length;
        let (compressed, work) = self.compress_parts(parts, length, budget, random, stop, on_best);
        let solution = compressed.map(|(parts, length)| self.solution_of(&parts, length));
        (solution, work)
    }

    /// Searches through overlap for a shorter strip holding `parts` (separated, on a strip
    /// `length` long: the roll, or the last sheet): exploration, then compression, within
    /// `budget` work. Returns the shortest separated layout found and its length (or `None` if
    /// none is shorter), and the work.
    pub(super) fn compress_parts(
        &self,
        parts: Vec<Part>,
        length: f64,
        budget: u64,
        random: &mut SplitMix64,
        mut stop: impl FnMut(u64) -> bool,
        mut on_best: impl FnMut(f64),
    ) -> (Option<(Vec<Part>, f64)>, u64) {
        let mut separator = Separator::new(self, parts, length);
        let mut best_parts = separator.parts.clone();
        let mut best_length = separator.used_length();
        let mut improved = false;
        let exploration_budget = (budget as f64 * EXPLORATION_SHARE) as u64;
        let mut pool: Vec<(f64, Vec<Part>)> = Vec::new();
        separator.reset(&best_parts, best_length, true);
        cut_at_random(
            &mut separator,
            best_length * (1.0 - EXPLORATION_STEP),
            random,
        );
        while separator.work() < exploration_budget && !stop(separator.work()) {
            let loss =
                separator.separate(EXPLORATION_LIMITS, random, exploration_budget, &mut stop);
            if loss <= 0.0 {
                best_parts.clone_from(&separator.parts);
                best_length = separator.used_length();
                improved = true;
                on_best(best_length);
                pool.clear();
                separator.reset(&best_parts, best_length, true);
                cut_at_random(
                    &mut separator,
                    best_length * (1.0 - EXPLORATION_STEP),
                    random,
                );
                continue;
            }
            let rank = pool.partition_point(|(pooled, _)| *pooled <= loss);
            pool.insert(rank, (loss, separator.parts.clone()));
            let chosen =
                ((half_normal(random) * POOL_SPREAD).min(0.999) * pool.len() as f64) as usize;
            let length = separator.length;
            separator.reset(&pool[chosen].1, length, true);
            separator.disrupt(random);
        }
        let start = separator.work();
        while separator.work() < budget && !stop(separator.work()) {
            let progress =
                (separator.work() - start) as f64 / budget.saturating_sub(start).max(1) as f64;
            let step = COMPRESSION_STEPS.0 + (COMPRESSION_STEPS.1 - COMPRESSION_STEPS.0) * progress;
            separator.reset(&best_parts, best_length, true);
            cut_at_random(&mut separator, best_length * (1.0 - step), random);
            let loss = separator.separate(COMPRESSION_LIMITS, random, budget, &mut stop);
            if loss <= 0.0 {
                best_parts.clone_from(&separator.parts);
                best_length = separator.used_length();
                improved = true;
                on_best(best_length);
            }
        }
        let work = separator.work();
        (improved.then_some((best_parts, best_length)), work)
    }

    /// A roll solution holding `parts` on a strip `length` long (plus the inset).
    fn solution_of(&self, parts: &[Part], length: f64) -> Solution<JaguaEngine> {
        let mut engine = JaguaEngine::new(
            Arc::clone(&self.library),
            DVec2::ZERO,
            DVec2::new(
                length + self.library.inflation() + CLEARANCE_RELATIVE * self.scale,
                self.height,
            ),
        )
        .expect("the strip holds every part");
        let mut placed = Vec::with_capacity(parts.len());
        for part in parts {
            engine.insert(part.copy as u32, part.pose, part.translation);
            placed.push(Some(Placed {
                bin: 0,
                pose: part.pose,
                translation: part.translation,
                right: part.translation.x + self.bounds(part.pose).1.x,
            }));
        }
        Solution {
            order: parts.iter().map(|part| part.copy).collect(),
            placed,
            bins: vec![engine],
        }
    }
}

/// The placed copies of a solution as the separator's parts, in the solution's order.
pub(super) fn parts_of(solution: &Solution<JaguaEngine>) -> Vec<Part> {
    (solution.placed.iter().zip(&solution.order))
        .filter_map(|(placed, &copy)| {
            placed.map(|placed| Part {
                copy,
                pose: placed.pose,
                translation: placed.translation,
            })
        })
        .collect()
}

/// Cuts the separator's strip to `length` at a uniformly drawn split.
fn cut_at_random(separator: &mut Separator, length: f64, random: &mut SplitMix64) {
    let split = random.unit() * separator.length;
    separator.cut(length, split);
}

/// `|N(0, 1)|` (Box-Muller).
fn half_normal(random: &mut SplitMix64) -> f64 {
    let radius = (-2.0 * (1.0 - random.unit()).ln()).sqrt();
    (radius * (std::f64::consts::TAU * random.unit()).cos()).abs()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nest::NestItem;
    use crate::nest::collision::Pose;
    use crate::nest::layout::StopReason;
    use crate::nest::options::NestOptions;
    use crate::nest::rotations::Rotations;
    use crate::nest::stock::Stock;
    use crate::nest::verify::tests::{polygon, square};
    use crate::nest::verify::verify;

    /// Nesting on a roll `width` wide, every other option the default.
    fn roll(width: f64) -> NestOptions {
        NestOptions {
            stock: Stock::Roll { width },
            ..NestOptions::default()
        }
    }

    /// The four copies of the problem's first shape (a 10 mm square), copy `i` at `at(i)`.
    fn four_squares(problem: &Problem, at: impl Fn(f64) -> DVec2) -> Vec<Part> {
        (0..4)
            .map(|copy| Part {
                copy,
                pose: Pose::upright(problem.item_shapes[0][0]),
                translation: at(copy as f64),
            })
            .collect()
    }

    /// Four 10 mm squares piled onto each other on a 21 mm roll 40 mm long: the separator must
    /// spread them into a layout the independent check accepts.
    #[test]
    fn the_separator_resolves_piled_squares_into_a_verified_layout() {
        let items = vec![square("square 10", 10.0, 4)];
        let options = roll(21.0);
        let problem = Problem::new(&items, &options).expect("valid problem");
        let parts = four_squares(&problem, |copy| DVec2::new(1.0 + copy, 1.0 + copy));
        let mut separator = Separator::new(&problem, parts, 40.0);
        let limits = Limits {
            rounds: 50,
            strikes: 3,
        };
        let loss = separator.separate(limits, &mut SplitMix64(0), u64::MAX, &mut |_| false);
        assert_eq!(loss, 0.0);
        let length = separator.used_length();
        let solution = problem.solution_of(&separator.parts, length);
        let layout = problem.layout(
            &solution,
            &problem.fill_holes(),
            0,
            0,
            StopReason::WorkBudget,
        );
        let violations = verify(&items, &layout);
        assert!(violations.is_empty(), "{violations:?}");
        assert!(layout.used_length <= 40.0 + 1e-9);
    }

    /// A bar 13.6 × 0.2 mm free to rotate, on a strip 8.45 mm wide cut to 11.2 mm: it fits only
    /// turned by 35.9° to 37.5° (or those plus 180°, or mirrored about either axis), between the
    /// sampled orientations every 15°, so the separator must turn it continuously. On the same
    /// strip a bar limited to the 24 sampled orientations cannot be separated.
    #[test]
    fn the_separator_turns_a_part_free_to_rotate_between_its_sampled_orientations() {
        let bar = |rotations: Rotations| {
            let outer = vec![
                DVec2::ZERO,
                DVec2::new(13.6, 0.0),
                DVec2::new(13.6, 0.2),
                DVec2::new(0.0, 0.2),
            ];
            polygon("bar", outer, 1, rotations)
        };
        let limits = Limits {
            rounds: 200,
            strikes: 5,
        };
        let separated = |item: NestItem| {
            let items = vec![item];
            let options = roll(8.45);
            let problem = Problem::new(&items, &options).expect("valid problem");
            let start = vec![Part {
                copy: 0,
                pose: Pose::upright(problem.item_shapes[0][0]),
                translation: DVec2::new(0.1, 0.1),
            }];
            let mut separator = Separator::new(&problem, start, 11.2);
            let loss = separator.separate(limits, &mut SplitMix64(3), 20_000_000, &mut |_| false);
            let solution = problem.solution_of(&separator.parts, separator.used_length());
            let fill = problem.fill_holes();
            let layout = problem.layout(&solution, &fill, 0, 0, StopReason::WorkBudget);
            let violations = verify(&items, &layout);
            (loss, layout, violations)
        };
        let (loss, layout, violations) = separated(bar(Rotations::Free));
        assert_eq!(loss, 0.0);
        assert!(violations.is_empty(), "{violations:?}");
        assert!(layout.used_length <= 11.2, "{}", layout.used_length);
        let angle = layout.sheets[0].placements[0]
            .rotation_degrees
            .rem_euclid(180.0);
        let tilt = angle.min(180.0 - angle);
        assert!((35.8..=37.6).contains(&tilt), "turned by {angle}°");
        let (loss, ..) = separated(bar(Rotations::Step(15.0)));
        assert!(loss > 0.0);
    }

    /// Compression of a loose layout (four 10 mm squares in one row on a roll wide enough for two
    /// rows) finds a shorter verified layout.
    #[test]
    fn compression_shortens_a_loose_layout() {
        let items = vec![square("square 10", 10.0, 4)];
        let options = roll(20.5);
        let problem = Problem::new(&items, &options).expect("valid problem");
        let parts = four_squares(&problem, |copy| DVec2::new(0.1 + 12.0 * copy, 0.1));
        let start = problem.solution_of(&parts, 46.2);
        let (compressed, work) =
            problem.compress(&start, 2_000_000, &mut SplitMix64(1), |_| false, |_| ());
        assert!(work > 0);
        let compressed = compressed.expect("a shorter layout");
        assert!(problem.cost(&compressed).length < 40.0);
        let layout = problem.layout(
            &compressed,
            &problem.fill_holes(),
            0,
            0,
            StopReason::WorkBudget,
        );
        let violations = verify(&items, &layout);
        assert!(violations.is_empty(), "{violations:?}");
    }

    /// The same seed and budget give the same layout (the parallel workers do not leak the
    /// thread count or timing into the result).
    #[test]
    fn compression_is_deterministic() {
        let items = vec![square("square 10", 10.0, 6)];
        let options = roll(20.5);
        let problem = Problem::new(&items, &options).expect("valid problem");
        let parts: Vec<Part> = (0..6)
            .map(|copy| Part {
                copy,
                pose: Pose::upright(problem.item_shapes[0][0]),
                translation: DVec2::new(0.1 + 12.0 * copy as f64, 0.1),
            })
            .collect();
        let start = problem.solution_of(&parts, 70.2);
        let run = || {
            let (compressed, work) =
                problem.compress(&start, 1_000_000, &mut SplitMix64(5), |_| false, |_| ());
            let compressed = compressed.expect("a shorter layout");
            let places: Vec<(usize, [u64; 2])> = (compressed.placed.iter().flatten())
                .map(|placed| {
                    let t = placed.translation;
                    (placed.pose.shape, [t.x.to_bits(), t.y.to_bits()])
                })
                .collect();
            (places, work)
        };
        assert_eq!(run(), run());
    }
}
