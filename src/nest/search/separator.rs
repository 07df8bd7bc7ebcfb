//! Compression through overlap (roll only): from the best complete layout, cut the strip shorter,
//! push the parts beyond the cut back inside (they now overlap), and *separate* them by moving and
//! turning one colliding part at a time to the position of least weighted overlap (sampled, then
//! refined by coordinate descent), raising the weight of every pair that keeps colliding (guided
//! local search). A separated layout is kept and cut again; when separation fails, the best is
//! restored and the cut halved.
//!
//! The overlap measure is [`JaguaEngine::overlap`] (pole-based, see `collision.rs`); a layout is
//! separated when no part collides with anything (the same test as the bottom-left placement).

use std::sync::Arc;

use glam::DVec2;

use super::problem::{CLEARANCE_RELATIVE, Problem};
use super::random::SplitMix64;
use super::solution::{Placed, Solution};
use crate::nest::collision::{CollisionEngine, JaguaEngine, Obstacle, ShapeId};

/// First cut of the compression, as a fraction of the strip's length.
pub const COMPRESSION_STEP: f64 = 0.005;
/// Smallest cut: below this the step stays here.
pub const MIN_COMPRESSION_STEP: f64 = 0.0005;
/// Separation rounds (every colliding part moved once) without a lower total overlap after which
/// the separation gives up.
pub const SEPARATION_PATIENCE: u32 = 25;
/// Random positions tried anywhere in the strip per move, in a random allowed orientation.
pub const GLOBAL_SAMPLES: usize = 24;
/// Random positions tried near the part's position per move (its orientation or another).
pub const LOCAL_SAMPLES: usize = 24;
/// Multiplier of a pair's weight per round in which it still collides.
pub const WEIGHT_GROWTH: f64 = 1.3;
/// Work counted per overlap query, in collision queries: an overlap query collects every
/// collision and measures each (and a move re-registers the part in the quadtree), about this many
/// times the cost of a yes/no query on this machine (measured on shirts).
pub const OVERLAP_QUERY_WORK: u64 = 4;

/// A part of the separator's layout.
#[derive(Debug, Clone, Copy)]
struct Part {
    copy: usize,
    shape: ShapeId,
    translation: DVec2,
}

/// The separator's state on one strip length.
struct Separator<'p, 'a> {
    problem: &'p Problem<'a>,
    parts: Vec<Part>,
    engine: JaguaEngine,
    /// Pair weights, `n × n`, symmetric; the edge weight of part `i` is at `n × n + i`.
    weights: Vec<f64>,
    length: f64,
}

impl Problem<'_> {
    /// Compresses the complete roll layout `best` within `budget` work (collision queries);
    /// returns the shortest separated layout found (or `None` if none is shorter) and the work.
    pub(super) fn compress(
        &self,
        best: &Solution<JaguaEngine>,
        budget: u64,
        random: &mut SplitMix64,
        mut stop: impl FnMut(u64) -> bool,
    ) -> (Option<Solution<JaguaEngine>>, u64) {
        let mut parts: Vec<Part> = (best.placed.iter().zip(&best.order))
            .filter_map(|(placed, &copy)| {
                placed.map(|placed| Part {
                    copy,
                    shape: placed.shape,
                    translation: placed.translation,
                })
            })
            .collect();
        if parts.len() != best.order.len() || parts.is_empty() {
            return (None, 0);
        }
        let clearance = CLEARANCE_RELATIVE * self.scale;
        let mut best_length = self.cost(best).length;
        let mut best_parts = parts.clone();
        let mut improved = false;
        let mut step = COMPRESSION_STEP;
        let mut work = 0;
        let mut weights = vec![1.0; parts.len() * (parts.len() + 1)];
        while work < budget && !stop(work) {
            let length = best_length * (1.0 - step);
            parts.clone_from(&best_parts);
            let limit = length - clearance;
            for part in &mut parts {
                let right = part.translation.x + self.orientations[part.shape].max.x;
                if right > limit {
                    part.translation.x -= right - limit;
                }
            }
            let mut separator = Separator::new(self, parts.clone(), weights.clone(), length);
            let separated = separator.separate(random, budget - work.min(budget));
            work += separator.engine.queries() * OVERLAP_QUERY_WORK;
            weights = separator.weights;
            if separated {
                parts = separator.parts;
                best_length = parts
                    .iter()
                    .map(|part| part.translation.x + self.orientations[part.shape].max.x)
                    .fold(0.0, f64::max);
                best_parts.clone_from(&parts);
                improved = true;
            } else {
                step = (step / 2.0).max(MIN_COMPRESSION_STEP);
            }
        }
        if !improved {
            return (None, work);
        }
        (Some(self.solution_of(&best_parts, best_length)), work)
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
            engine.insert(part.copy as u32, part.shape, part.translation);
            placed.push(Some(Placed {
                bin: 0,
                shape: part.shape,
                translation: part.translation,
                right: part.translation.x + self.orientations[part.shape].max.x,
            }));
        }
        Solution {
            order: parts.iter().map(|part| part.copy).collect(),
            placed,
            bins: vec![engine],
        }
    }
}

impl<'p, 'a> Separator<'p, 'a> {
    fn new(problem: &'p Problem<'a>, parts: Vec<Part>, weights: Vec<f64>, length: f64) -> Self {
        let container = length + problem.library.inflation();
        let mut engine = JaguaEngine::new(
            Arc::clone(&problem.library),
            DVec2::ZERO,
            DVec2::new(container, problem.height),
        )
        .expect("the strip is longer than the gap");
        for (index, part) in parts.iter().enumerate() {
            engine.insert(index as u32, part.shape, part.translation);
        }
        Self {
            problem,
            parts,
            engine,
            weights,
            length,
        }
    }

    /// Every collision of the layout: (part, obstacle, overlap), each pair once.
    fn collisions(&mut self) -> Vec<(usize, Obstacle, f64)> {
        let mut found = Vec::new();
        for index in 0..self.parts.len() {
            let part = self.parts[index];
            let overlaps = (self.engine).overlaps(part.shape, part.translation, Some(index as u32));
            for (obstacle, overlap) in overlaps {
                if matches!(obstacle, Obstacle::Part(other) if (other as usize) < index) {
                    continue;
                }
                found.push((index, obstacle, overlap));
            }
        }
        found
    }

    /// Separation rounds until no part collides (true) or [`SEPARATION_PATIENCE`] rounds pass
    /// without a lower total overlap, or `budget` work is spent (false).
    fn separate(&mut self, random: &mut SplitMix64, budget: u64) -> bool {
        let mut best_total = f64::INFINITY;
        let mut patience = 0;
        let n = self.parts.len();
        loop {
            let collisions = self.collisions();
            if collisions.is_empty() {
                return true;
            }
            let total: f64 = collisions.iter().map(|(_, _, overlap)| overlap).sum();
            if total < best_total * (1.0 - 1e-3) {
                best_total = total;
                patience = 0;
            } else {
                patience += 1;
                if patience >= SEPARATION_PATIENCE {
                    return false;
                }
            }
            if self.engine.queries() * OVERLAP_QUERY_WORK >= budget {
                return false;
            }
            // Guided local search: pairs that still collide weigh more.
            let largest = collisions
                .iter()
                .map(|(_, _, overlap)| *overlap)
                .fold(0.0, f64::max);
            for &(index, obstacle, overlap) in &collisions {
                let growth = 1.0 + (WEIGHT_GROWTH - 1.0) * (overlap / largest).sqrt();
                match obstacle {
                    Obstacle::Edge => self.weights[n * n + index] *= growth,
                    Obstacle::Part(other) => {
                        let other = other as usize;
                        self.weights[index * n + other] *= growth;
                        self.weights[other * n + index] *= growth;
                    }
                }
            }
            let mut colliding: Vec<usize> = collisions
                .iter()
                .flat_map(|&(index, obstacle, _)| match obstacle {
                    Obstacle::Edge => [Some(index), None],
                    Obstacle::Part(other) => [Some(index), Some(other as usize)],
                })
                .flatten()
                .collect();
            colliding.sort_unstable();
            colliding.dedup();
            for position in (1..colliding.len()).rev() {
                colliding.swap(position, random.below(position + 1));
            }
            for index in colliding {
                self.move_part(index, random);
            }
        }
    }

    /// Moves part `index` to the position of least weighted overlap found: its own, random
    /// positions anywhere and nearby, the best refined by coordinate descent.
    fn move_part(&mut self, index: usize, random: &mut SplitMix64) {
        let problem = self.problem;
        let part = self.parts[index];
        let item = problem.copies[part.copy].item;
        let shapes = &problem.item_shapes[item];
        self.engine.remove(index as u32);
        let inset = problem.library.inflation() + CLEARANCE_RELATIVE * problem.scale;
        let weights = &self.weights;
        let n = self.parts.len();
        let weight = move |obstacle: Obstacle| match obstacle {
            Obstacle::Edge => weights[n * n + index],
            Obstacle::Part(other) => weights[index * n + other as usize],
        };
        let engine = &mut self.engine;
        let mut evaluate = |shape: ShapeId, translation: DVec2, bound: f64| {
            engine.overlap(shape, translation, bound, weight)
        };
        let mut best = (
            part.shape,
            part.translation,
            evaluate(part.shape, part.translation, f64::INFINITY),
        );
        let range = |shape: ShapeId| {
            let orientation = &problem.orientations[shape];
            let low = DVec2::splat(inset) - orientation.min;
            let high =
                DVec2::new(self.length, problem.height) - DVec2::splat(inset) - orientation.max;
            (low, high.max(low))
        };
        let current_size =
            problem.orientations[part.shape].max - problem.orientations[part.shape].min;
        for sample in 0..GLOBAL_SAMPLES + LOCAL_SAMPLES {
            if best.2 <= 0.0 {
                break;
            }
            let shape = if sample < GLOBAL_SAMPLES || random.below(4) == 0 {
                shapes[random.below(shapes.len())]
            } else {
                part.shape
            };
            let (low, high) = range(shape);
            let translation = if sample < GLOBAL_SAMPLES {
                low + DVec2::new(random.unit(), random.unit()) * (high - low)
            } else {
                let jitter = DVec2::new(random.unit() - 0.5, random.unit() - 0.5) * current_size;
                (part.translation + jitter).clamp(low, high)
            };
            let overlap = evaluate(shape, translation, best.2);
            if overlap < best.2 {
                best = (shape, translation, overlap);
            }
        }
        // Coordinate descent from the best: steps along x and y, halved when nothing improves.
        let (low, high) = range(best.0);
        let size = problem.orientations[best.0].max - problem.orientations[best.0].min;
        let mut step = size * 0.1;
        while best.2 > 0.0 && step.max_element() > size.max_element() * 1e-3 {
            let mut moved = false;
            for direction in [DVec2::X, DVec2::NEG_X, DVec2::Y, DVec2::NEG_Y] {
                let translation = (best.1 + direction * step).clamp(low, high);
                let overlap = evaluate(best.0, translation, best.2);
                if overlap < best.2 {
                    best = (best.0, translation, overlap);
                    moved = true;
                    break;
                }
            }
            if !moved {
                step *= 0.5;
            }
        }
        self.parts[index].shape = best.0;
        self.parts[index].translation = best.1;
        self.engine.insert(index as u32, best.0, best.1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nest::layout::StopReason;
    use crate::nest::options::NestOptions;
    use crate::nest::stock::Stock;
    use crate::nest::verify::tests::square;
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
                shape: problem.item_shapes[0][0],
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
        let weights = vec![1.0; parts.len() * (parts.len() + 1)];
        let mut separator = Separator::new(&problem, parts, weights, 40.0);
        assert!(!separator.collisions().is_empty());
        assert!(separator.separate(&mut SplitMix64(0), u64::MAX));
        assert!(separator.collisions().is_empty());
        let length = (separator.parts.iter())
            .map(|part| part.translation.x + problem.orientations[part.shape].max.x)
            .fold(0.0, f64::max);
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

    /// Compression of a loose layout (four 10 mm squares in one row on a roll wide enough for two
    /// rows) finds a shorter verified layout.
    #[test]
    fn compression_shortens_a_loose_layout() {
        let items = vec![square("square 10", 10.0, 4)];
        let options = roll(20.5);
        let problem = Problem::new(&items, &options).expect("valid problem");
        let parts = four_squares(&problem, |copy| DVec2::new(0.1 + 12.0 * copy, 0.1));
        let start = problem.solution_of(&parts, 46.2);
        let (compressed, work) = problem.compress(&start, 2_000_000, &mut SplitMix64(1), |_| false);
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
}
