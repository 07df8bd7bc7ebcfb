//! The separator: parts on a strip (the roll, a sheet, or the used part of the last sheet),
//! possibly overlapping, moved one colliding part at a time to the position of least weighted
//! overlap (sampled, then refined by coordinate descent), with the weights of pairs that keep
//! colliding raised and those of pairs that stopped colliding decayed (guided local search).
//! Each round runs [`WORKERS`] independent copies in parallel from the same state, each with its
//! own seed, and keeps the one of least weighted overlap; rounds continue until nothing
//! collides or no substantial progress is made ([`Limits`]: rounds without progress per strike,
//! strikes, each strike restarting from the least-overlapping state found).
//!
//! The overlap measure is [`JaguaEngine::overlap`] (pole-based, see `collision.rs`); a layout is
//! separated when no part collides with anything (the same test as the bottom-left placement).

use std::sync::Arc;

use glam::DVec2;
use rayon::prelude::*;

use super::problem::{CLEARANCE_RELATIVE, Problem, TURN_RANGE};
use super::random::SplitMix64;
use crate::nest::collision::{CollisionEngine, JaguaEngine, Obstacle, Pose};

/// Random positions tried anywhere in the strip per move, in a random allowed orientation (for a
/// part free to rotate, see `new_orientation`).
pub const GLOBAL_SAMPLES: usize = 24;
/// Random positions tried near the part's position per move (its orientation or another).
pub const LOCAL_SAMPLES: usize = 24;
/// The least overlapping positions of a move (sampled, or the part's own) that are each refined
/// by coordinate descent; the move takes the best refined one. (1 before; 5 did worse on shirts.)
pub const REFINED: usize = 3;
/// First step of the coordinate descent, as a fraction of the part's bounding box (0.25 did worse).
pub const DESCENT_FIRST_STEP: f64 = 0.1;
/// First turn of the coordinate descent of a part free to rotate, radians per unit of
/// [`DESCENT_FIRST_STEP`]: a turn by `DESCENT_FIRST_STEP × DESCENT_TURN` (5.7°) moves the far
/// end of a part about half as far as the first translation step. It grows and halves with the
/// translation step.
pub const DESCENT_TURN: f64 = 1.0;
/// Growth of the coordinate descent's step after a step that lowered the overlap (it halves after
/// one that did not), so that a part slides far along a long slope in few queries. (1 before: the
/// step only halved; 1.25 and 2 did worse on shirts than 1.5.)
pub const DESCENT_GROWTH: f64 = 1.5;
/// Weight multiplier of a pair that still collides, for the smallest overlap of the round; the
/// largest overlap gets [`WEIGHT_GROWTH_MAX`], others in proportion.
pub const WEIGHT_GROWTH_MIN: f64 = 1.2;
/// Weight multiplier of the pair with the largest overlap of the round.
pub const WEIGHT_GROWTH_MAX: f64 = 2.0;
/// Weight multiplier of a pair that does not collide (never below 1).
pub const WEIGHT_DECAY: f64 = 0.95;
/// A total overlap below this fraction of the previous least counts as substantial progress.
pub const SUBSTANTIAL_PROGRESS: f64 = 0.98;
/// Copies of the separator that run each round in parallel (rayon) from the same state, each
/// with its own seed; the round keeps the one of least weighted overlap. Fixed, so that the
/// result does not depend on the number of threads.
pub const WORKERS: usize = 2;
/// Work counted per overlap query, in collision queries: an overlap query collects every
/// collision and measures each (and a move re-registers the part in the quadtree), about this many
/// times the cost of a yes/no query on this machine (measured on shirts). A round of parallel
/// workers counts the work of the busiest one (its length in time on enough cores).
pub const OVERLAP_QUERY_WORK: u64 = 2;

/// A part of the separator's layout.
#[derive(Debug, Clone, Copy)]
pub(super) struct Part {
    pub(super) copy: usize,
    pub(super) pose: Pose,
    pub(super) translation: DVec2,
}

/// When a separation gives up: after `strikes` strikes in a row, a strike being `rounds` rounds
/// without substantial progress that did not lower the least total overlap substantially.
#[derive(Debug, Clone, Copy)]
pub(super) struct Limits {
    pub(super) rounds: u32,
    pub(super) strikes: u32,
}

/// A collision: the part (index), what it overlaps and the unweighted overlap.
type Collision = (usize, Obstacle, f64);

/// The separator's state on one strip length.
pub(super) struct Separator<'p, 'a> {
    problem: &'p Problem<'a>,
    pub(super) parts: Vec<Part>,
    /// One collision engine per worker ([`WORKERS`]), each holding `parts` between rounds: a
    /// round moves parts in every engine, then the engines of the workers not kept take the kept
    /// worker's moves (instead of cloning the kept engine, quadtree and all, every round). The
    /// first engine answers the queries outside rounds.
    engines: Vec<JaguaEngine>,
    /// Pair weights, `n × n`, symmetric; the edge weight of part `i` is at `n × n + i`.
    weights: Vec<f64>,
    pub(super) length: f64,
    /// Overlap queries counted before the current first engine (rebuilt when the length
    /// changes), and the work of the parallel rounds beyond the first engine's own.
    retired: u64,
}

/// What every worker of a round reads: the problem, the weights, the strip's length.
#[derive(Clone, Copy)]
struct Shared<'s, 'p, 'a> {
    problem: &'p Problem<'a>,
    weights: &'s [f64],
    length: f64,
}

impl<'p, 'a> Separator<'p, 'a> {
    /// A separator holding `parts` on a strip `length` long, every weight 1.
    pub(super) fn new(problem: &'p Problem<'a>, parts: Vec<Part>, length: f64) -> Self {
        let engines = Self::engines_of(problem, &parts, length);
        let n = parts.len();
        Self {
            problem,
            parts,
            engines,
            weights: vec![1.0; n * (n + 1)],
            length,
            retired: 0,
        }
    }

    /// [`WORKERS`] engines holding `parts` on a strip `length` long: one built, the others its
    /// copies.
    fn engines_of(problem: &Problem, parts: &[Part], length: f64) -> Vec<JaguaEngine> {
        vec![Self::engine_of(problem, parts, length); WORKERS]
    }

    fn engine_of(problem: &Problem, parts: &[Part], length: f64) -> JaguaEngine {
        let container = length + problem.library.inflation();
        let mut engine = JaguaEngine::new(
            Arc::clone(&problem.library),
            DVec2::ZERO,
            DVec2::new(container, problem.height),
        )
        .expect("the strip is longer than the gap");
        for (index, part) in parts.iter().enumerate() {
            engine.insert(index as u32, part.pose, part.translation);
        }
        engine
    }

    /// Work spent so far, in collision queries.
    pub(super) fn work(&self) -> u64 {
        (self.retired + self.engines[0].queries()) * OVERLAP_QUERY_WORK
    }

    /// Puts `parts` on a strip `length` long; with `reset_weights`, every weight back to 1. On
    /// the same strip, only the parts that moved are moved in the engines; a new length builds
    /// them anew.
    pub(super) fn reset(&mut self, parts: &[Part], length: f64, reset_weights: bool) {
        if length.to_bits() == self.length.to_bits() && parts.len() == self.parts.len() {
            for (index, (part, current)) in parts.iter().zip(&self.parts).enumerate() {
                for engine in &mut self.engines {
                    move_to(engine, index, current, part);
                }
            }
        } else {
            self.retired += self.engines[0].queries();
            self.engines = Self::engines_of(self.problem, parts, length);
        }
        self.parts.clear();
        self.parts.extend_from_slice(parts);
        self.length = length;
        if reset_weights {
            self.weights.fill(1.0);
        }
    }

    /// Right end of the parts (inflated outlines).
    pub(super) fn used_length(&self) -> f64 {
        (self.parts.iter())
            .map(|part| part.translation.x + self.problem.bounds(part.pose).1.x)
            .fold(0.0, f64::max)
    }

    /// Range of translations that keep `pose` inside the strip.
    fn range(&self, pose: Pose) -> (DVec2, DVec2) {
        strip_range(self.problem, self.length, pose)
    }

    /// Cuts the strip to `length`: the parts whose centre lies right of `split` move left by the
    /// difference, and any part still beyond the new end is pushed inside (into overlap).
    pub(super) fn cut(&mut self, length: f64, split: f64) {
        let delta = self.length - length;
        let mut parts = self.parts.clone();
        self.length = length;
        for part in &mut parts {
            let (min, max) = self.problem.bounds(part.pose);
            if part.translation.x + (min.x + max.x) / 2.0 > split {
                part.translation.x -= delta;
            }
            let (low, high) = self.range(part.pose);
            part.translation = part.translation.clamp(low, high);
        }
        self.reset(&parts, length, true);
    }

    /// Swaps the places (bounding-box centres) of two large parts of different items (large: the
    /// largest items that hold three quarters of the parts' area): a jump out of a local minimum.
    pub(super) fn disrupt(&mut self, random: &mut SplitMix64) {
        let problem = self.problem;
        let area = |part: &Part| problem.items[problem.copies[part.copy].item].area();
        let mut areas: Vec<f64> = self.parts.iter().map(area).collect();
        areas.sort_by(|a, b| b.total_cmp(a));
        let total: f64 = areas.iter().sum();
        let mut cumulative = 0.0;
        let cutoff = (areas.iter())
            .find(|&&part_area| {
                cumulative += part_area;
                cumulative > 0.75 * total
            })
            .copied()
            .unwrap_or(0.0);
        let large: Vec<usize> = (0..self.parts.len())
            .filter(|&index| area(&self.parts[index]) >= cutoff)
            .collect();
        if self.parts.len() < 2 || large.is_empty() {
            return;
        }
        let first = large[random.below(large.len())];
        let first_item = problem.copies[self.parts[first].copy].item;
        let others: Vec<usize> = (large.iter().copied())
            .filter(|&index| problem.copies[self.parts[index].copy].item != first_item)
            .collect();
        let second = if others.is_empty() {
            (first + 1 + random.below(self.parts.len() - 1)) % self.parts.len()
        } else {
            others[random.below(others.len())]
        };
        let centre = |part: &Part| {
            let (min, max) = problem.bounds(part.pose);
            (min + max) / 2.0
        };
        let mut parts = self.parts.clone();
        let (a, b) = (parts[first], parts[second]);
        parts[first].translation = b.translation + centre(&b) - centre(&a);
        parts[second].translation = a.translation + centre(&a) - centre(&b);
        for index in [first, second] {
            let (low, high) = self.range(parts[index].pose);
            parts[index].translation = parts[index].translation.clamp(low, high);
        }
        for (swapped, old) in [(first, a), (second, b)] {
            self.carry_covered_parts(&mut parts, swapped, old.translation, [first, second]);
        }
        self.reset(&parts, self.length, false);
    }

    /// After the swap of a disruption: the parts (other than the two `swapped`) whose inner point
    /// the part `moved` now covers move back by its displacement from `old` (they keep their
    /// place relative to it, around the part that took its old place), so that a large part
    /// swapped with a small one does not land on the small one's neighbours: they move with it.
    fn carry_covered_parts(
        &self,
        parts: &mut [Part],
        moved: usize,
        old: DVec2,
        swapped: [usize; 2],
    ) {
        let library = &self.problem.library;
        let cover = parts[moved];
        let displacement = cover.translation - old;
        for (index, part) in parts.iter_mut().enumerate() {
            let covered = !swapped.contains(&index)
                && library.contains(
                    cover.pose,
                    cover.translation,
                    library.inner_point(part.pose, part.translation),
                );
            if covered {
                let (low, high) = self.range(part.pose);
                part.translation = (part.translation - displacement).clamp(low, high);
            }
        }
    }

    /// Every collision of the layout: (part, obstacle, overlap), each pair once.
    fn collisions(&mut self) -> Vec<Collision> {
        collisions_of(&mut self.engines[0], &self.parts)
    }

    /// Index of a collision's weight (the pair's, or the part's edge weight), and of its mirror.
    fn weight_slots(&self, index: usize, obstacle: Obstacle) -> [usize; 2] {
        let n = self.parts.len();
        match obstacle {
            Obstacle::Edge => [n * n + index; 2],
            Obstacle::Part(other) => [index * n + other as usize, other as usize * n + index],
        }
    }

    fn weighted_total(&self, collisions: &[Collision]) -> f64 {
        (collisions.iter())
            .map(|&(index, obstacle, overlap)| {
                self.weights[self.weight_slots(index, obstacle)[0]] * overlap
            })
            .sum()
    }

    /// Guided local search: the weight of each colliding pair grows (more for larger overlaps),
    /// the others decay towards 1.
    fn update_weights(&mut self, collisions: &[Collision]) {
        let largest = (collisions.iter())
            .map(|(_, _, overlap)| *overlap)
            .fold(0.0, f64::max);
        let mut grown = vec![false; self.weights.len()];
        for &(index, obstacle, overlap) in collisions {
            let growth =
                WEIGHT_GROWTH_MIN + (WEIGHT_GROWTH_MAX - WEIGHT_GROWTH_MIN) * (overlap / largest);
            let [slot, mirror] = self.weight_slots(index, obstacle);
            self.weights[slot] *= growth;
            grown[slot] = true;
            if mirror != slot {
                self.weights[mirror] *= growth;
                grown[mirror] = true;
            }
        }
        for (weight, grown) in self.weights.iter_mut().zip(grown) {
            if !grown {
                *weight = (*weight * WEIGHT_DECAY).max(1.0);
            }
        }
    }

    /// Rounds until no part collides (returns 0) or the [`Limits`] end the separation, or the
    /// work reaches `budget`, or `stop` says so; then the layout is the least overlapping one
    /// found and the return value its total overlap.
    pub(super) fn separate(
        &mut self,
        limits: Limits,
        random: &mut SplitMix64,
        budget: u64,
        stop: &mut impl FnMut(u64) -> bool,
    ) -> f64 {
        let mut collisions = self.collisions();
        let mut least = total(&collisions);
        if least <= 0.0 {
            return 0.0;
        }
        let mut least_parts = self.parts.clone();
        let mut strikes = 0;
        'strikes: while strikes < limits.strikes {
            let strike_start = least;
            let mut stale = 0;
            while stale < limits.rounds {
                if self.work() >= budget || stop(self.work()) {
                    break 'strikes;
                }
                collisions = self.round(&collisions, random);
                let loss = total(&collisions);
                if loss <= 0.0 {
                    return 0.0;
                }
                if loss < least {
                    if loss < least * SUBSTANTIAL_PROGRESS {
                        stale = 0;
                    }
                    least = loss;
                    least_parts.clone_from(&self.parts);
                } else {
                    stale += 1;
                }
                self.update_weights(&collisions);
            }
            strikes = if least > strike_start * SUBSTANTIAL_PROGRESS {
                strikes + 1
            } else {
                0
            };
            self.reset(&least_parts, self.length, false);
            collisions = self.collisions();
        }
        self.reset(&least_parts, self.length, false);
        least
    }

    /// One round: [`WORKERS`] workers, each on its own engine, move every part of `collisions`
    /// in their own random order; the worker of least weighted overlap is kept and the others'
    /// engines take its moves. Returns its collisions.
    fn round(&mut self, collisions: &[Collision], random: &mut SplitMix64) -> Vec<Collision> {
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
        let seeds: Vec<u64> = (0..WORKERS).map(|_| random.next()).collect();
        let bases: Vec<u64> = self.engines.iter().map(JaguaEngine::queries).collect();
        let shared = Shared {
            problem: self.problem,
            weights: &self.weights,
            length: self.length,
        };
        let start = &self.parts;
        let outcomes: Vec<(Vec<Part>, Vec<Collision>)> = (self.engines.par_iter_mut())
            .zip(seeds)
            .map(|(engine, seed)| {
                let mut parts = start.clone();
                let mut random = SplitMix64(seed);
                let mut order = colliding.clone();
                for position in (1..order.len()).rev() {
                    order.swap(position, random.below(position + 1));
                }
                for index in order {
                    move_part(shared, engine, &mut parts, index, &mut random);
                }
                let collisions = collisions_after(engine, &parts, collisions, &colliding);
                (parts, collisions)
            })
            .collect();
        let spent: Vec<u64> = (self.engines.iter().zip(&bases))
            .map(|(engine, base)| engine.queries() - base)
            .collect();
        let busiest = spent.iter().copied().max().unwrap_or(0);
        self.retired += busiest - spent[0];
        let mut kept = 0;
        for (position, (_, collisions)) in outcomes.iter().enumerate() {
            if self.weighted_total(collisions) < self.weighted_total(&outcomes[kept].1) {
                kept = position;
            }
        }
        let (kept_parts, kept_collisions) = &outcomes[kept];
        (self.engines.par_iter_mut().zip(&outcomes))
            .enumerate()
            .filter(|&(position, _)| position != kept)
            .for_each(|(_, (engine, (parts, _)))| {
                for &index in &colliding {
                    move_to(engine, index, &parts[index], &kept_parts[index]);
                }
            });
        self.parts.clone_from(kept_parts);
        kept_collisions.clone()
    }
}

/// Moves part `index` to the position of least weighted overlap found: its own, random
/// positions anywhere and nearby, the [`REFINED`] best refined by coordinate descent.
fn move_part(
    shared: Shared,
    engine: &mut JaguaEngine,
    parts: &mut [Part],
    index: usize,
    random: &mut SplitMix64,
) {
    let Shared {
        problem,
        weights,
        length,
    } = shared;
    let part = parts[index];
    let item = problem.copies[part.copy].item;
    let turns = problem.turns[item];
    engine.remove(index as u32);
    let n = parts.len();
    let weight = move |obstacle: Obstacle| match obstacle {
        Obstacle::Edge => weights[n * n + index],
        Obstacle::Part(other) => weights[index * n + other as usize],
    };
    let this_range = |pose: Pose| strip_range(problem, length, pose);
    let mut evaluate = |pose: Pose, translation: DVec2, bound: f64| {
        engine.overlap(pose, translation, bound, weight)
    };
    let current = (
        part.pose,
        part.translation,
        evaluate(part.pose, part.translation, f64::INFINITY),
    );
    // The REFINED least overlapping positions so far (the current one among them), least first.
    let mut candidates = vec![current];
    let bound = |candidates: &[Candidate]| {
        if candidates.len() < REFINED {
            f64::INFINITY
        } else {
            candidates[candidates.len() - 1].2
        }
    };
    let current_size = {
        let (min, max) = problem.bounds(part.pose);
        max - min
    };
    for sample in 0..GLOBAL_SAMPLES + LOCAL_SAMPLES {
        if candidates[0].2 <= 0.0 {
            break;
        }
        let pose = if sample < GLOBAL_SAMPLES || random.below(4) == 0 {
            new_orientation(problem, item, random)
        } else {
            part.pose
        };
        let (low, high) = this_range(pose);
        let translation = if sample < GLOBAL_SAMPLES {
            low + DVec2::new(random.unit(), random.unit()) * (high - low)
        } else {
            let jitter = DVec2::new(random.unit() - 0.5, random.unit() - 0.5) * current_size;
            (part.translation + jitter).clamp(low, high)
        };
        let limit = bound(&candidates);
        let overlap = evaluate(pose, translation, limit);
        if overlap < limit {
            let rank = candidates.partition_point(|candidate| candidate.2 <= overlap);
            candidates.insert(rank, (pose, translation, overlap));
            candidates.truncate(REFINED);
        }
    }
    let mut best = candidates[0];
    for &candidate in &candidates {
        if best.2 <= 0.0 {
            break;
        }
        let refined = descend(problem, length, candidate, turns, random, &mut evaluate);
        if refined.2 < best.2 {
            best = refined;
        }
    }
    parts[index].pose = best.0;
    parts[index].translation = best.1;
    engine.insert(index as u32, best.0, best.1);
}

/// A pose in a random allowed orientation of `item`: for a part free to rotate, half the time an
/// orientation square to the stock, upright (parts that fit best square to each other keep
/// finding those poses), else any sampled orientation turned by a random angle within
/// [`TURN_RANGE`] of it, so that every angle can be drawn.
fn new_orientation(problem: &Problem, item: usize, random: &mut SplitMix64) -> Pose {
    let (shapes, square) = (&problem.item_shapes[item], &problem.square_shapes[item]);
    if !problem.turns[item] {
        return Pose::upright(shapes[random.below(shapes.len())]);
    }
    if !square.is_empty() && random.below(2) == 0 {
        return Pose::upright(square[random.below(square.len())]);
    }
    Pose {
        shape: shapes[random.below(shapes.len())],
        turn: (2.0 * random.unit() - 1.0) * TURN_RANGE,
    }
}

/// A candidate position of a moving part: its pose, translation and weighted overlap.
type Candidate = (Pose, DVec2, f64);

/// A move of the coordinate descent: a translation, or (for a part free to rotate) a turn.
#[derive(Debug, Clone, Copy)]
enum Step {
    /// Along this unit direction, by the translation step.
    Along(DVec2),
    /// Counter-clockwise about the part's centre by the turn step, times this sign.
    Turn(f64),
}

/// Coordinate descent from `start`: a step along ±x or ±y, or for a part free to rotate
/// (`turns`) a turn either way about its centre (tried from a random one, so that no move is
/// favoured) is taken when it lowers the overlap, then the steps grow by [`DESCENT_GROWTH`];
/// when none does, they halve, down to 1/1000 of the part's size. Each evaluation is bounded by
/// the overlap of the current position.
fn descend(
    problem: &Problem,
    length: f64,
    start: Candidate,
    turns: bool,
    random: &mut SplitMix64,
    evaluate: &mut impl FnMut(Pose, DVec2, f64) -> f64,
) -> Candidate {
    let mut best = start;
    let mut range = strip_range(problem, length, best.0);
    let size = {
        let (min, max) = problem.bounds(best.0);
        max - min
    };
    let mut step = size * DESCENT_FIRST_STEP;
    let mut turn_step = DESCENT_FIRST_STEP * DESCENT_TURN;
    let translations = [DVec2::X, DVec2::NEG_X, DVec2::Y, DVec2::NEG_Y].map(Step::Along);
    let mut moves: Vec<Step> = translations.to_vec();
    if turns {
        moves.extend([Step::Turn(1.0), Step::Turn(-1.0)]);
    }
    while best.2 > 0.0 && step.max_element() > size.max_element() * 1e-3 {
        let mut moved = false;
        let first = random.below(moves.len());
        moves.rotate_left(first);
        for &candidate_step in &moves {
            let (pose, translation) = match candidate_step {
                Step::Along(direction) => {
                    (best.0, (best.1 + direction * step).clamp(range.0, range.1))
                }
                Step::Turn(sign) => turned(problem, length, (best.0, best.1), sign * turn_step),
            };
            let overlap = evaluate(pose, translation, best.2);
            if overlap < best.2 {
                if pose != best.0 {
                    range = strip_range(problem, length, pose);
                }
                best = (pose, translation, overlap);
                moved = true;
                break;
            }
        }
        let factor = if moved { DESCENT_GROWTH } else { 0.5 };
        step *= factor;
        turn_step *= factor;
    }
    best
}

/// The pose and translation of a part at `(pose, translation)` turned further by `angle`
/// radians about the centre of its bounding box, kept inside a strip `length` long.
fn turned(
    problem: &Problem,
    length: f64,
    (pose, translation): (Pose, DVec2),
    angle: f64,
) -> (Pose, DVec2) {
    let (min, max) = problem.bounds(pose);
    let centre = (min + max) / 2.0;
    let turned = Pose {
        turn: pose.turn + angle,
        ..pose
    };
    let moved = translation + centre - DVec2::from_angle(angle).rotate(centre);
    let (low, high) = strip_range(problem, length, turned);
    (turned, moved.clamp(low, high))
}

/// Moves part `index` in `engine` from `current` to `target`, when they differ.
fn move_to(engine: &mut JaguaEngine, index: usize, current: &Part, target: &Part) {
    if !same_place(current, target) {
        engine.remove(index as u32);
        engine.insert(index as u32, target.pose, target.translation);
    }
}

/// Whether two parts lie at the same place in the same pose (bit for bit).
fn same_place(a: &Part, b: &Part) -> bool {
    a.pose.shape == b.pose.shape
        && a.pose.turn.to_bits() == b.pose.turn.to_bits()
        && a.translation.x.to_bits() == b.translation.x.to_bits()
        && a.translation.y.to_bits() == b.translation.y.to_bits()
}

/// Every collision of `parts` as registered in `engine`: (part, obstacle, overlap), each pair
/// once.
fn collisions_of(engine: &mut JaguaEngine, parts: &[Part]) -> Vec<Collision> {
    let mut found = Vec::new();
    for (index, part) in parts.iter().enumerate() {
        let overlaps = engine.overlaps(part.pose, part.translation, Some(index as u32));
        for (obstacle, overlap) in overlaps {
            if matches!(obstacle, Obstacle::Part(other) if (other as usize) < index) {
                continue;
            }
            found.push((index, obstacle, overlap));
        }
    }
    found
}

/// The collisions of the layout after the parts `moved` (sorted) moved, from those before
/// (`previous`, as [`collisions_of`] lists them): the pairs without a moved part are
/// kept, the moved parts queried again. Same pairs in the same order as `collisions()` would
/// give, at the cost of one query per moved part instead of one per part.
fn collisions_after(
    engine: &mut JaguaEngine,
    parts: &[Part],
    previous: &[Collision],
    moved: &[usize],
) -> Vec<Collision> {
    let mut is_moved = vec![false; parts.len()];
    for &index in moved {
        is_moved[index] = true;
    }
    let mut found: Vec<Collision> = (previous.iter().copied())
        .filter(|&(index, obstacle, _)| {
            !is_moved[index]
                && !matches!(obstacle, Obstacle::Part(other) if is_moved[other as usize])
        })
        .collect();
    for &index in moved {
        let part = parts[index];
        let overlaps = engine.overlaps(part.pose, part.translation, Some(index as u32));
        for (obstacle, overlap) in overlaps {
            match obstacle {
                Obstacle::Edge => found.push((index, obstacle, overlap)),
                // Between two moved parts, the pair is listed from the smaller index.
                Obstacle::Part(other) if is_moved[other as usize] && (other as usize) < index => {}
                Obstacle::Part(other) if (other as usize) < index => {
                    found.push((other as usize, Obstacle::Part(index as u32), overlap));
                }
                Obstacle::Part(_) => found.push((index, obstacle, overlap)),
            }
        }
    }
    found.sort_by_key(|&(index, obstacle, _)| {
        (
            index,
            match obstacle {
                Obstacle::Edge => None,
                Obstacle::Part(other) => Some(other),
            },
        )
    });
    found
}

/// Range of translations that keep `pose` inside a strip `length` long.
pub(super) fn strip_range(problem: &Problem, length: f64, pose: Pose) -> (DVec2, DVec2) {
    let inset = problem.library.inflation() + CLEARANCE_RELATIVE * problem.scale;
    let (min, max) = problem.bounds(pose);
    let low = DVec2::splat(inset) - min;
    let high = DVec2::new(length, problem.height) - DVec2::splat(inset) - max;
    (low, high.max(low))
}

/// Total unweighted overlap of `collisions`.
fn total(collisions: &[Collision]) -> f64 {
    collisions.iter().map(|(_, _, overlap)| overlap).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nest::options::NestOptions;
    use crate::nest::stock::Stock;
    use crate::nest::verify::tests::square;

    /// After a round, the collisions updated from the moved parts only are those of a full
    /// recount: the same pairs, each once, with the same overlaps up to round-off.
    #[test]
    fn collisions_updated_after_moves_match_a_full_recount() {
        let items = vec![square("square 10", 10.0, 8)];
        let options = NestOptions {
            stock: Stock::Roll { width: 21.0 },
            ..NestOptions::default()
        };
        let problem = Problem::new(&items, &options).expect("valid problem");
        let parts: Vec<Part> = (0..8)
            .map(|copy| Part {
                copy,
                pose: Pose::upright(problem.item_shapes[0][0]),
                translation: DVec2::new(1.0 + 3.0 * copy as f64, 1.0 + (copy % 3) as f64),
            })
            .collect();
        let mut separator = Separator::new(&problem, parts, 30.0);
        let mut random = SplitMix64(11);
        let mut collisions = separator.collisions();
        for _ in 0..6 {
            assert!(!collisions.is_empty());
            collisions = separator.round(&collisions, &mut random);
            let recount = separator.collisions();
            assert_eq!(
                collisions.len(),
                recount.len(),
                "{collisions:?} vs {recount:?}"
            );
            for (updated, full) in collisions.iter().zip(&recount) {
                assert_eq!((updated.0, updated.1), (full.0, full.1));
                assert!((updated.2 - full.2).abs() <= 1e-9 * full.2.max(1.0));
            }
        }
    }

    /// A disruption swapping the 10 mm square with one of three 2 mm squares in a row beside it
    /// carries the small squares the large one lands on back into its old place: whichever small
    /// square is drawn, the disrupted layout has no collision (without the carry, the large
    /// square would land on one or two small ones).
    #[test]
    fn a_disruption_carries_the_parts_the_swapped_large_part_lands_on() {
        let items = vec![square("big", 10.0, 1), square("small", 2.0, 3)];
        let options = NestOptions {
            stock: Stock::Roll { width: 12.0 },
            ..NestOptions::default()
        };
        let problem = Problem::new(&items, &options).expect("valid problem");
        let at = |copy: usize, x: f64| Part {
            copy,
            pose: Pose::upright(problem.item_shapes[problem.copies[copy].item][0]),
            translation: DVec2::new(x, 0.5),
        };
        let big = (0..4).find(|&copy| problem.copies[copy].item == 0).unwrap();
        let mut smalls = (0..4).filter(|&copy| copy != big);
        let mut parts = vec![at(big, 0.5)];
        parts.extend([20.0, 24.0, 28.0].map(|x| at(smalls.next().unwrap(), x)));
        for seed in 0..12 {
            let mut separator = Separator::new(&problem, parts.clone(), 40.0);
            assert!(separator.collisions().is_empty());
            separator.disrupt(&mut SplitMix64(seed));
            assert_ne!(separator.parts[0].translation, parts[0].translation);
            let collisions = separator.collisions();
            assert!(collisions.is_empty(), "seed {seed}: {collisions:?}");
        }
    }
}
