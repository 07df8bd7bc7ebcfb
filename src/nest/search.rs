//! The placement search: what goes where, using a [`CollisionEngine`] for every feasibility test.
//!
//! 1. **Constructive bottom-left placement.** Copies are taken in a sequence (initially by
//!    decreasing area). Each copy goes to the first sheet where it fits (always the one roll), at
//!    the position that minimises its right edge, then its bottom edge. Per allowed orientation:
//!    [`SAMPLES_PER_ORIENTATION`] seeded uniform samples left of the current front (right of the
//!    front everything fits, so the front itself, at the bottom and at the top, is the fallback);
//!    the [`COMPACTED_CANDIDATES`] fitting samples with the lowest right edge are slid left and down
//!    (steps, then bisection) until they touch.
//! 2. **Local search over the sequence.** Each round draws [`NEIGHBOURS_PER_ROUND`] moves (swap two
//!    copies of different items, or move one copy earlier) from a seeded splitmix64 generator,
//!    re-places every copy from the first changed position (the prefix is kept), and evaluates the
//!    neighbours in parallel (rayon), each with its own seed.
//!    * On a **roll**, the search works by *strip shrinking*: whenever a layout holds every copy,
//!      it becomes the best and the roll is cut [`SHRINK_FRACTION`] shorter than it; copies that
//!      no longer fit are left out, and the search minimises the area left out (ties accepted)
//!      until a sequence fits everything again.
//!    * On **sheets**, the search minimises (sheets used, length used on the last sheet) with
//!      threshold accepting: a neighbour up to [`ACCEPTANCE_THRESHOLD`] longer is accepted at the
//!      start, falling linearly to zero.
//!
//! Determinism: the work is counted in collision queries and the search stops after
//! `work_limit` of them (default `time_limit × NOMINAL_QUERIES_PER_SECOND`), so the result depends
//! only on the items, the options and the seed, not on the machine or the thread count. The
//! wall-clock `time_limit` is also enforced between rounds; when it stops the search first (a slow
//! or busy machine) the layout says so with [`StopReason::TimeLimit`] and may differ between runs.

mod holes;

use std::sync::Arc;
use std::time::Instant;

use glam::DVec2;
use rayon::prelude::*;

use super::collision::{CollisionEngine, JaguaEngine, ShapeId, ShapeLibrary};
use super::{
    NestError, NestItem, NestLayout, NestOptions, Placement, SheetLayout, Stock, StopReason,
    polygon_area,
};
use crate::progress::Progress;

/// Collision queries per second of budget: below the rate of the release build on a shared
/// 2-core machine (1.3 to 2.6 million per second measured), so that the deterministic work budget,
/// not the wall clock, normally ends a `--time 60` run (in about 25-45 s there).
pub const NOMINAL_QUERIES_PER_SECOND: f64 = 1_000_000.0;
/// Neighbours evaluated (in parallel) per round of the local search. Fixed, so the result does not
/// depend on the number of threads.
pub const NEIGHBOURS_PER_ROUND: usize = 4;
/// Threshold accepting: at the start a neighbour up to this fraction longer than the current
/// solution is accepted; the threshold falls linearly to zero as the work budget is spent.
pub const ACCEPTANCE_THRESHOLD: f64 = 0.01;

/// What one placement pass works with.
#[derive(Debug, Clone, Copy)]
struct Pass {
    /// Length of the roll (ignored for sheets).
    roll_length: f64,
    /// Whether a copy that finds no room is left out (strip shrinking) rather than failing.
    allow_unplaced: bool,
}

/// Strip shrinking: each time every copy fits, the roll is first cut this fraction shorter.
pub const SHRINK_FRACTION: f64 = 0.02;
/// Smallest cut of the strip shrinking: the fraction is halved, down to this, whenever the search
/// stalls.
pub const MIN_SHRINK_FRACTION: f64 = 0.0025;
/// Rounds without a strict decrease of the area left out after which the shrinking search goes
/// back to the best complete layout and cuts it by half the previous fraction.
pub const STALL_ROUNDS: u32 = 40;
/// Random positions tried per orientation of a copy.
pub const SAMPLES_PER_ORIENTATION: usize = 200;
/// How many of the fitting samples (those with the lowest right edge) are compacted.
pub const COMPACTED_CANDIDATES: usize = 4;
/// Samples are drawn over the height range widened by this fraction on each side and clamped, so
/// that about that fraction of them lie exactly on the bottom or the top edge.
const EDGE_SAMPLE_FRACTION: f64 = 0.1;
/// Clearance (relative to the stock scale) kept from the stock edge and from the front, above the
/// shapes' inflation, so that a candidate is not rejected for touching after f32 rounding.
const CLEARANCE_RELATIVE: f64 = 1e-6;
/// How many times the roll length of the construction may double before the search gives up.
const MAX_ROLL_DOUBLINGS: u32 = 8;
/// Slide step of the compaction, as a fraction of the copy's extent along each axis.
const COMPACTION_STEP_FRACTION: f64 = 0.25;
/// Bisection steps when a found position is pushed left or down.
const REFINE_STEPS: u32 = 6;
/// Rounds of slide-left then slide-down after a position is found.
const COMPACTION_ROUNDS: u32 = 4;
/// Most steps of one slide.
const MAX_SLIDE_STEPS: u32 = 16;
/// Two lengths closer than this (relative to the stock scale) are equal.
const LENGTH_TOLERANCE_RELATIVE: f64 = 1e-9;
/// Roll length of the first attempt, as a multiple of (net area / roll width) plus the largest part.
const INITIAL_ROLL_FACTOR: f64 = 2.0;

/// One copy of an item in one orientation, in the item's rotated frame.
#[derive(Debug, Clone)]
struct Orientation {
    item: usize,
    rotation_degrees: f64,
    mirrored: bool,
    /// Inflated bounding box in the rotated frame.
    min: DVec2,
    max: DVec2,
}

/// One copy to place.
#[derive(Debug, Clone, Copy)]
struct PartCopy {
    item: usize,
    copy: u32,
}

/// A copy as placed in a solution.
#[derive(Debug, Clone, Copy)]
struct Placed {
    bin: usize,
    shape: ShapeId,
    translation: DVec2,
    /// Right edge of the inflated shape.
    right: f64,
}

/// A full or partial solution: the sequence, where each copy went, and the engines per bin.
#[derive(Clone)]
struct Solution<E> {
    order: Vec<usize>,
    /// Parallel to the first positions of `order`; `None` for a copy left out (strip shrinking).
    placed: Vec<Option<Placed>>,
    bins: Vec<E>,
}

impl<E> Solution<E> {
    /// Sheets (bins) that hold at least one placed copy: one past the highest bin used.
    fn bins_in_use(&self) -> usize {
        self.placed
            .iter()
            .flatten()
            .map(|placed| placed.bin + 1)
            .max()
            .unwrap_or(0)
    }
}

/// The objective, compared lexicographically: net area of the copies left out (strip shrinking
/// only), sheets used, then the length used on the last.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Cost {
    unplaced: f64,
    bins: usize,
    length: f64,
}

/// Validated input, oriented shapes and the collision library: everything the search needs.
pub(crate) struct Problem<'a> {
    items: &'a [NestItem],
    options: &'a NestOptions,
    orientations: Vec<Orientation>,
    item_shapes: Vec<Vec<ShapeId>>,
    copies: Vec<PartCopy>,
    library: Arc<ShapeLibrary>,
    /// Stock extent along y (sheet height or roll width) and, for sheets, along x.
    height: f64,
    sheet_width: Option<f64>,
    scale: f64,
    /// Per copy, the copies placed in its holes (see [`holes`]).
    guests: Vec<Vec<holes::Guest>>,
}

/// splitmix64 (Steele, Lea and Flood 2014): a tiny, seedable, well-mixed generator.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut mixed = self.0;
        mixed = (mixed ^ (mixed >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        mixed = (mixed ^ (mixed >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        mixed ^ (mixed >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `0..bound` (`bound` > 0), by rejection-free multiply-shift.
    fn below(&mut self, bound: usize) -> usize {
        ((u128::from(self.next()) * bound as u128) >> 64) as usize
    }
}

impl<'a> Problem<'a> {
    /// Validates the input and prepares the oriented shapes.
    pub(crate) fn new(items: &'a [NestItem], options: &'a NestOptions) -> Result<Self, NestError> {
        let (height, sheet_width) = validate_stock(options)?;
        if !options.gap.is_finite() || options.gap < 0.0 {
            return Err(NestError::InvalidGap(options.gap));
        }
        if items.iter().all(|item| item.quantity == 0) {
            return Err(NestError::EmptyInput);
        }
        let mut orientations = Vec::new();
        let mut rings = Vec::new();
        let mut item_shapes = Vec::with_capacity(items.len());
        for (index, item) in items.iter().enumerate() {
            validate_outline(item)?;
            let poses = item.poses().ok_or_else(|| rotation_error(item))?;
            let mut shapes = Vec::new();
            for &(rotation_degrees, mirrored) in &poses {
                let pose = Placement {
                    item: index,
                    copy: 0,
                    rotation_degrees,
                    mirrored,
                    translation: DVec2::ZERO,
                };
                let ring = pose.transform_ring(&item.outer);
                let (min, max) = bounds(&ring);
                let size = max - min + DVec2::splat(2.0 * options.gap);
                if size.y <= height && sheet_width.is_none_or(|width| size.x <= width) {
                    shapes.push(orientations.len());
                    orientations.push(Orientation {
                        item: index,
                        rotation_degrees,
                        mirrored,
                        min,
                        max,
                    });
                    rings.push(ring);
                }
            }
            if shapes.is_empty() && item.quantity > 0 {
                return Err(too_large(item, &poses, options));
            }
            item_shapes.push(shapes);
        }
        let net_area: f64 = items
            .iter()
            .map(|item| item.area().max(0.0) * f64::from(item.quantity))
            .sum();
        let scale = sheet_width.unwrap_or(net_area / height).max(height);
        let library = ShapeLibrary::new(&rings, options.gap, scale).map_err(|rejected| {
            NestError::CollisionShape {
                item: items[orientations[rejected.index].item].name.clone(),
                reason: rejected.reason,
            }
        })?;
        for (shape, orientation) in orientations.iter_mut().enumerate() {
            (orientation.min, orientation.max) = library.inflated_bounds(shape);
        }
        let margin = 2.0 * (library.inflation() + CLEARANCE_RELATIVE * scale);
        for (item, shapes) in items.iter().zip(&mut item_shapes) {
            shapes.retain(|&shape| {
                let size = orientations[shape].max - orientations[shape].min + DVec2::splat(margin);
                size.y <= height && sheet_width.is_none_or(|width| size.x <= width)
            });
            if shapes.is_empty() && item.quantity > 0 {
                let poses = item.poses().unwrap_or_default();
                return Err(too_large(item, &poses, options));
            }
        }
        let mut copies: Vec<PartCopy> = items
            .iter()
            .enumerate()
            .flat_map(|(item, entry)| (0..entry.quantity).map(move |copy| PartCopy { item, copy }))
            .collect();
        let areas: Vec<f64> = items
            .iter()
            .map(|item| polygon_area(&item.outer).abs())
            .collect();
        copies.sort_by(|a, b| {
            areas[b.item]
                .total_cmp(&areas[a.item])
                .then(a.item.cmp(&b.item))
                .then(a.copy.cmp(&b.copy))
        });
        let mut problem = Self {
            items,
            options,
            orientations,
            item_shapes,
            copies,
            library: Arc::new(library),
            height,
            sheet_width,
            scale,
            guests: Vec::new(),
        };
        problem.guests = problem.fill_holes();
        Ok(problem)
    }

    /// Runs the construction and the local search, and returns the best layout.
    pub(crate) fn solve(&self, progress: &dyn Progress) -> Result<NestLayout, NestError> {
        let started = Instant::now();
        let budget = self
            .options
            .work_limit
            .unwrap_or((self.options.time_limit.as_secs_f64() * NOMINAL_QUERIES_PER_SECOND) as u64);
        progress.start("nest", budget);
        let shrinking = self.sheet_width.is_none();
        let mut random = SplitMix64(self.options.seed);
        let mut pass = Pass {
            roll_length: self.initial_roll_length(),
            allow_unplaced: false,
        };
        let mut attempts = 0;
        let (mut best, mut work) = loop {
            let (solution, work) =
                self.extend(self.empty(self.hosts_and_others()), pass, &mut random);
            match solution {
                Some(solution) => break (solution, work),
                None if shrinking && attempts < MAX_ROLL_DOUBLINGS => pass.roll_length *= 2.0,
                None => return Err(NestError::NoPosition),
            }
            attempts += 1;
        };
        let mut current = best.clone();
        let mut shrink_fraction = SHRINK_FRACTION;
        let mut stalled_rounds = 0;
        if shrinking {
            (current, pass) = self.shrink(&mut best, shrink_fraction, &mut work, &mut random);
        }
        let mut evaluations = 1;
        let stop_reason = loop {
            progress.advance(work.min(budget));
            if work >= budget {
                break StopReason::WorkBudget;
            }
            if started.elapsed() >= self.options.time_limit {
                break StopReason::TimeLimit;
            }
            let Some(moves) = self.draw_moves(&current, &mut random) else {
                break StopReason::Complete;
            };
            let results: Vec<(Option<Solution<JaguaEngine>>, u64)> = moves
                .into_par_iter()
                .map(|(order, first_changed, seed)| {
                    self.evaluate(&current, order, first_changed, pass, &mut SplitMix64(seed))
                })
                .collect();
            evaluations += results.len() as u64;
            let mut chosen: Option<Solution<JaguaEngine>> = None;
            for (solution, spent) in results {
                work += spent;
                if let Some(solution) = solution
                    && chosen
                        .as_ref()
                        .is_none_or(|chosen| self.better(self.cost(&solution), self.cost(chosen)))
                {
                    chosen = Some(solution);
                }
            }
            let Some(chosen) = chosen else { continue };
            let (chosen_cost, current_cost) = (self.cost(&chosen), self.cost(&current));
            if shrinking && chosen_cost.unplaced <= 0.0 {
                best = chosen;
                stalled_rounds = 0;
                (current, pass) = self.shrink(&mut best, shrink_fraction, &mut work, &mut random);
            } else if shrinking {
                stalled_rounds = if self.less_left_out(chosen_cost, current_cost) {
                    0
                } else {
                    stalled_rounds + 1
                };
                if chosen_cost.unplaced <= current_cost.unplaced {
                    current = chosen;
                }
                if stalled_rounds >= STALL_ROUNDS && shrink_fraction > MIN_SHRINK_FRACTION {
                    shrink_fraction = (shrink_fraction / 2.0).max(MIN_SHRINK_FRACTION);
                    stalled_rounds = 0;
                    (current, pass) =
                        self.shrink(&mut best, shrink_fraction, &mut work, &mut random);
                }
            } else {
                let remaining = (1.0 - work as f64 / budget.max(1) as f64).max(0.0);
                let threshold = ACCEPTANCE_THRESHOLD * remaining * current_cost.length;
                if self.acceptable(chosen_cost, current_cost, threshold) {
                    current = chosen;
                    if self.better(self.cost(&current), self.cost(&best)) {
                        best = current.clone();
                    }
                }
            }
        };
        if shrinking {
            self.pull_in_rightmost(&mut best, &mut work, &mut random);
        }
        progress.finish();
        Ok(self.layout(&best, work, evaluations, stop_reason))
    }

    /// Final polish on a roll: the copy with the rightmost edge moves to the best position found
    /// for it among the others (as in the construction) while that shortens the roll.
    fn pull_in_rightmost(
        &self,
        best: &mut Solution<JaguaEngine>,
        work: &mut u64,
        random: &mut SplitMix64,
    ) {
        let tolerance = LENGTH_TOLERANCE_RELATIVE * self.scale;
        loop {
            let mut rights: Vec<(f64, usize)> = (best.placed.iter().enumerate())
                .filter_map(|(position, placed)| placed.map(|placed| (placed.right, position)))
                .collect();
            rights.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
            let [(right, position), (front, _), ..] = rights[..] else {
                return;
            };
            let copy = best.order[position];
            let mut engine = best.bins[0].clone();
            engine.remove(copy as u32);
            let pass = Pass {
                roll_length: right + self.library.inflation(),
                allow_unplaced: true,
            };
            let queries_before = engine.queries();
            let found =
                self.best_position(&mut engine, self.copies[copy].item, front, pass, random);
            *work += engine.queries() - queries_before;
            let Some((shape, translation, moved_right)) = found else {
                return;
            };
            if moved_right >= right - tolerance {
                return;
            }
            engine.insert(copy as u32, shape, translation);
            best.bins[0] = engine;
            best.placed[position] = Some(Placed {
                bin: 0,
                shape,
                translation,
                right: moved_right,
            });
        }
    }

    /// A solution with nothing placed yet.
    fn empty(&self, order: Vec<usize>) -> Solution<JaguaEngine> {
        Solution {
            order,
            placed: Vec::new(),
            bins: Vec::new(),
        }
    }

    /// Strip shrinking (roll only): cuts the roll [`SHRINK_FRACTION`] shorter than `best` and places
    /// its sequence on it, leaving out what does not fit. While everything fits, that layout becomes the
    /// new `best` and the roll is cut again. Returns the first incomplete layout and its pass.
    fn shrink(
        &self,
        best: &mut Solution<JaguaEngine>,
        fraction: f64,
        work: &mut u64,
        random: &mut SplitMix64,
    ) -> (Solution<JaguaEngine>, Pass) {
        let order = best.order.clone();
        loop {
            let pass = Pass {
                roll_length: self.cost(best).length * (1.0 - fraction),
                allow_unplaced: true,
            };
            let (solution, spent) = self.extend(self.empty(order.clone()), pass, random);
            *work += spent;
            let Some(solution) = solution else {
                return (best.clone(), pass);
            };
            if self.cost(&solution).unplaced > 0.0 {
                return (solution, pass);
            }
            *best = solution;
        }
    }

    /// Roll length of the first attempt (grown if a copy finds no room).
    fn initial_roll_length(&self) -> f64 {
        if let Some(width) = self.sheet_width {
            return width;
        }
        let area: f64 = self
            .copies
            .iter()
            .map(|copy| self.items[copy.item].area().max(0.0))
            .sum();
        let largest = self
            .orientations
            .iter()
            .map(|shape| (shape.max - shape.min).max_element())
            .fold(0.0, f64::max);
        INITIAL_ROLL_FACTOR * (area / self.height + largest) + 2.0 * self.options.gap
    }

    /// Draws the moves of one round: each a new sequence, its first changed position and a seed.
    /// `None` when no move changes anything (fewer than two distinct items).
    ///
    /// Positions are drawn with a bias towards the end of the sequence (re-placing a short tail
    /// is cheap, and the tail decides the length). While copies are left out (strip shrinking),
    /// half the moves take one of them and insert it at a uniformly drawn earlier position.
    fn draw_moves(
        &self,
        current: &Solution<JaguaEngine>,
        random: &mut SplitMix64,
    ) -> Option<Vec<(Vec<usize>, usize, u64)>> {
        let order = &current.order;
        let left_out: Vec<usize> = (current.placed.iter().enumerate())
            .filter(|(_, placed)| placed.is_none())
            .map(|(position, _)| position)
            .collect();
        let first_item = self.copies[order[0]].item;
        if order
            .iter()
            .all(|&copy| self.copies[copy].item == first_item)
        {
            return None;
        }
        let mut moves = Vec::with_capacity(NEIGHBOURS_PER_ROUND);
        let tail_biased = |random: &mut SplitMix64| {
            let reach = random.below(order.len()) + 1;
            order.len() - 1 - random.below(reach)
        };
        while moves.len() < NEIGHBOURS_PER_ROUND {
            let targeted = !left_out.is_empty() && random.below(2) == 0;
            let (mut first, mut second) = if targeted {
                let second = left_out[random.below(left_out.len())];
                (random.below(second.max(1)), second)
            } else {
                (tail_biased(random), tail_biased(random))
            };
            if self.copies[order[first]].item == self.copies[order[second]].item {
                continue;
            }
            if first > second {
                std::mem::swap(&mut first, &mut second);
            }
            let mut changed = order.to_vec();
            if !targeted && random.below(2) == 0 {
                changed.swap(first, second);
            } else {
                let moved = changed.remove(second);
                changed.insert(first, moved);
            }
            moves.push((changed, first, random.next()));
        }
        Some(moves)
    }

    /// Re-places `order` from `first_changed` on, keeping the prefix of `base`. Returns the
    /// solution (`None` if a copy found no room on the roll) and the queries spent.
    fn evaluate(
        &self,
        base: &Solution<JaguaEngine>,
        order: Vec<usize>,
        first_changed: usize,
        pass: Pass,
        random: &mut SplitMix64,
    ) -> (Option<Solution<JaguaEngine>>, u64) {
        let mut prefix = base.clone();
        for (position, placed) in base.placed.iter().enumerate().skip(first_changed) {
            if let Some(placed) = placed {
                prefix.bins[placed.bin].remove(base.order[position] as u32);
            }
        }
        prefix.placed.truncate(first_changed);
        let used_bins = prefix.bins_in_use();
        prefix.bins.truncate(used_bins.max(1));
        prefix.order = order;
        self.extend(prefix, pass, random)
    }

    /// Places the copies of `solution.order` that are not placed yet, in order.
    fn extend(
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
                        shape,
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
            solution.bins[placed.bin].insert(copy as u32, placed.shape, placed.translation);
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
    /// right edge). Per orientation: [`SAMPLES_PER_ORIENTATION`] uniform samples left of the front
    /// (beyond it everything fits, so the front itself is the fallback), the
    /// [`COMPACTED_CANDIDATES`] lowest right edges among those that fit are slid left and down
    /// until they touch, and the best is kept (lowest right edge, then lowest bottom).
    fn best_position(
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
        for &shape in &self.item_shapes[item] {
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
            for _ in 0..SAMPLES_PER_ORIENTATION {
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

    fn cost(&self, solution: &Solution<JaguaEngine>) -> Cost {
        let bins = solution.bins_in_use();
        let length = solution
            .placed
            .iter()
            .flatten()
            .filter(|placed| placed.bin + 1 == bins)
            .map(|placed| placed.right)
            .fold(0.0, f64::max);
        let unplaced = (solution.placed.iter().zip(&solution.order))
            .filter(|(placed, _)| placed.is_none())
            .map(|(_, &copy)| self.items[self.copies[copy].item].area())
            .sum();
        Cost {
            unplaced,
            bins,
            length,
        }
    }

    /// Threshold accepting: whether a neighbour costing `candidate` replaces the current solution
    /// costing `current`: it must use no more sheets and be at most `threshold` longer.
    fn acceptable(&self, candidate: Cost, current: Cost, threshold: f64) -> bool {
        candidate.bins < current.bins
            || (candidate.bins == current.bins && candidate.length <= current.length + threshold)
    }

    /// Two areas closer than this are equal.
    fn area_tolerance(&self) -> f64 {
        LENGTH_TOLERANCE_RELATIVE * self.scale * self.scale
    }

    /// Whether `a` leaves strictly less area out than `b` (strip shrinking).
    fn less_left_out(&self, a: Cost, b: Cost) -> bool {
        a.unplaced < b.unplaced - self.area_tolerance()
    }

    /// Whether `a` is strictly better than `b`.
    fn better(&self, a: Cost, b: Cost) -> bool {
        if (a.unplaced - b.unplaced).abs() > self.area_tolerance() {
            return a.unplaced < b.unplaced;
        }
        a.bins < b.bins
            || (a.bins == b.bins && a.length < b.length - LENGTH_TOLERANCE_RELATIVE * self.scale)
    }

    /// Converts a solution into the public layout, measured in exact geometry.
    fn layout(
        &self,
        solution: &Solution<JaguaEngine>,
        work: u64,
        evaluations: u64,
        stop_reason: StopReason,
    ) -> NestLayout {
        let bin_count = solution.bins_in_use();
        let mut sheets: Vec<SheetLayout> = Vec::with_capacity(bin_count);
        for bin in 0..bin_count {
            let mut placements = Vec::new();
            let mut far_edge: f64 = 0.0;
            let mut area = 0.0;
            for (position, placed) in solution
                .placed
                .iter()
                .enumerate()
                .filter_map(|(position, placed)| placed.map(|placed| (position, placed)))
                .filter(|(_, placed)| placed.bin == bin)
            {
                let copy_index = solution.order[position];
                let copy = self.copies[copy_index];
                let orientation = &self.orientations[placed.shape];
                let placement = Placement {
                    item: copy.item,
                    copy: copy.copy,
                    rotation_degrees: orientation.rotation_degrees,
                    mirrored: orientation.mirrored,
                    translation: placed.translation,
                };
                let item = &self.items[copy.item];
                far_edge = placement
                    .transform_ring(&item.outer)
                    .iter()
                    .map(|point| point.x)
                    .fold(far_edge, f64::max);
                area += item.area();
                for guest in self.guest_placements(copy_index, &placement) {
                    area += self.items[guest.item].area();
                    placements.push(guest);
                }
                placements.push(placement);
            }
            placements.sort_by(|a, b| a.item.cmp(&b.item).then(a.copy.cmp(&b.copy)));
            let used_length = far_edge + self.options.gap;
            let width = self.sheet_width.unwrap_or(used_length);
            let utilisation = area / (width * self.height);
            sheets.push(SheetLayout {
                width,
                height: self.height,
                used_length,
                placements,
                utilisation,
            });
        }
        let area: f64 = self
            .copies
            .iter()
            .map(|copy| self.items[copy.item].area())
            .sum();
        let stock_area: f64 = sheets.iter().map(|sheet| sheet.width * sheet.height).sum();
        NestLayout {
            stock: self.options.stock,
            gap: self.options.gap,
            utilisation: area / stock_area,
            used_length: sheets.last().map_or(0.0, |sheet| sheet.used_length),
            sheets,
            work,
            evaluations,
            stop_reason,
        }
    }
}

/// Slides a feasible position left, then down, until it touches something, up to
/// [`COMPACTION_ROUNDS`] times or until it no longer moves. `steps` are the slide steps along x
/// (the scan step) and y (the level spacing).
fn compact(
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

fn bounds(ring: &[DVec2]) -> (DVec2, DVec2) {
    ring.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(min, max), point| (min.min(*point), max.max(*point)),
    )
}

/// The largest stock dimension accepted, mm (100 m): the collision engine's geometry is single
/// precision, and sheet previews are drawn to scale.
pub const MAXIMUM_STOCK_MM: f64 = 1e5;

fn validate_stock(options: &NestOptions) -> Result<(f64, Option<f64>), NestError> {
    let check = |dimension: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 && value <= MAXIMUM_STOCK_MM {
            Ok(value)
        } else {
            Err(NestError::InvalidStock { dimension, value })
        }
    };
    match options.stock {
        Stock::Sheets { width, height } => Ok((
            check("sheet height", height)?,
            Some(check("sheet width", width)?),
        )),
        Stock::Roll { width } => Ok((check("roll width", width)?, None)),
    }
}

fn validate_outline(item: &NestItem) -> Result<(), NestError> {
    let invalid = |defect: &str| NestError::InvalidOutline {
        item: item.name.clone(),
        defect: defect.to_string(),
    };
    if item.outer.len() < 3 {
        return Err(invalid("the outline has fewer than 3 points"));
    }
    if item.outer.iter().any(|point| !point.is_finite()) {
        return Err(invalid("the outline has a non-finite coordinate"));
    }
    let (min, max) = bounds(&item.outer);
    let extent = (max - min).max_element();
    if polygon_area(&item.outer).abs() <= f64::EPSILON * extent * extent {
        return Err(invalid("the outline has no area"));
    }
    Ok(())
}

fn rotation_error(item: &NestItem) -> NestError {
    if let Some(degrees) = item.grain_degrees {
        return NestError::InvalidGrain {
            item: item.name.clone(),
            degrees,
        };
    }
    match item.rotations {
        super::Rotations::Step(step) => NestError::InvalidRotationStep {
            item: item.name.clone(),
            step,
        },
        _ => NestError::InvalidRotationList {
            item: item.name.clone(),
        },
    }
}

/// The error for an item that fits in none of its orientations, reporting the smallest one.
fn too_large(item: &NestItem, poses: &[(f64, bool)], options: &NestOptions) -> NestError {
    let (width, height) = poses
        .iter()
        .map(|&(rotation_degrees, mirrored)| {
            let pose = Placement {
                item: 0,
                copy: 0,
                rotation_degrees,
                mirrored,
                translation: DVec2::ZERO,
            };
            let (min, max) = bounds(&pose.transform_ring(&item.outer));
            max - min + DVec2::splat(2.0 * options.gap)
        })
        .map(|size| (size.x, size.y))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0.0, 0.0));
    NestError::PartTooLarge {
        item: item.name.clone(),
        width,
        height,
        stock: options.stock.to_string(),
    }
}
