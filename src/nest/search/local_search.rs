//! The search loop and its budget: the first complete layout (the roll grown until everything
//! fits), then rounds of neighbours evaluated in parallel, strip shrinking on a roll or threshold
//! accepting on sheets, until the work budget, the time limit, or nothing left to try.

use std::time::Instant;

use rayon::prelude::*;

use super::placement::Pass;
use super::problem::{LENGTH_TOLERANCE_RELATIVE, Problem};
use super::random::SplitMix64;
use super::solution::{Placed, Solution};
use crate::nest::collision::{CollisionEngine, JaguaEngine, Pose};
use crate::nest::errors::NestError;
use crate::nest::layout::{NestLayout, StopReason};
use crate::progress::Progress;

/// Collision queries per second of budget: below the rate of the release build on a shared
/// 2-core machine (1.3 to 2.6 million per second measured), so that the deterministic work budget,
/// not the wall clock, normally ends a `--time 60` run (in about 25-45 s there).
pub const NOMINAL_QUERIES_PER_SECOND: f64 = 1_000_000.0;
/// Threshold accepting: at the start a neighbour up to this fraction longer than the current
/// solution is accepted; the threshold falls linearly to zero as the work budget is spent.
pub const ACCEPTANCE_THRESHOLD: f64 = 0.01;
/// Strip shrinking: each time every copy fits, the roll is first cut this fraction shorter.
pub const SHRINK_FRACTION: f64 = 0.02;
/// Smallest cut of the strip shrinking: the fraction is halved, down to this, whenever the search
/// stalls.
pub const MIN_SHRINK_FRACTION: f64 = 0.0025;
/// Rounds without a strict decrease of the area left out after which the shrinking search goes
/// back to the best complete layout and cuts it by half the previous fraction.
pub const STALL_ROUNDS: u32 = 40;
/// The share of the work budget given to the sequence search; the rest goes to the search
/// through overlap (`compression.rs` on a roll, `sheets.rs` on sheets), which starts from its
/// best layout.
pub const SEQUENCE_SEARCH_SHARE: f64 = 0.05;
/// On sheets, the share of the work budget given to the sequence search (it decides the number
/// of sheets first); the rest goes to the search through overlap (`sheets.rs`).
pub const SHEETS_SEQUENCE_SEARCH_SHARE: f64 = 0.5;
/// How many times the roll length of the construction may double before the search gives up.
const MAX_ROLL_DOUBLINGS: u32 = 8;
/// Roll length of the first attempt, as a multiple of (net area / roll width) plus the largest part.
const INITIAL_ROLL_FACTOR: f64 = 2.0;

impl Problem<'_> {
    /// Places small copies in the holes of large ones (when asked), runs the construction and the
    /// local search, and returns the best layout.
    pub(crate) fn solve(&self, progress: &dyn Progress) -> Result<NestLayout, NestError> {
        let guests = self.fill_holes();
        let started = Instant::now();
        let budget = self
            .options
            .work_limit
            .unwrap_or((self.options.time_limit.as_secs_f64() * NOMINAL_QUERIES_PER_SECOND) as u64);
        progress.start("nest", budget);
        let shrinking = self.sheet_width.is_none();
        let total_budget = budget;
        let share = if shrinking {
            SEQUENCE_SEARCH_SHARE
        } else {
            SHEETS_SEQUENCE_SEARCH_SHARE
        };
        let budget = (budget as f64 * share) as u64;
        let mut random = SplitMix64(self.options.seed);
        let mut pass = Pass {
            roll_length: self.initial_roll_length(),
            allow_unplaced: false,
        };
        let mut attempts = 0;
        let (mut best, mut work) = loop {
            let (solution, work) = self.extend(
                Solution::empty(self.hosts_and_others(&guests)),
                pass,
                &mut random,
            );
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
                self.report_best(progress, self.cost(&best).length);
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
        let mut stop_reason = stop_reason;
        if shrinking {
            self.pull_in_rightmost(&mut best, &mut work, &mut random);
        }
        if stop_reason == StopReason::WorkBudget || stop_reason == StopReason::Complete {
            let start_work = work;
            let stop = |spent: u64| {
                progress.advance((start_work + spent).min(total_budget));
                started.elapsed() >= self.options.time_limit
            };
            let remaining = total_budget.saturating_sub(work);
            let (improved, spent) = if shrinking {
                self.compress(&best, remaining, &mut random, stop, |length| {
                    self.report_best(progress, length);
                })
            } else {
                self.improve_sheets(&best, remaining, &mut random, stop, |sheets, length| {
                    report_sheets(progress, sheets, length);
                })
            };
            work += spent;
            stop_reason = if started.elapsed() >= self.options.time_limit {
                StopReason::TimeLimit
            } else {
                StopReason::WorkBudget
            };
            if let Some(mut improved) = improved {
                if shrinking {
                    self.pull_in_rightmost(&mut improved, &mut work, &mut random);
                }
                let layout = self.layout(&improved, &guests, work, evaluations, stop_reason);
                if crate::nest::verify::verify(self.items, &layout).is_empty() {
                    progress.finish();
                    return Ok(layout);
                }
            }
        }
        progress.finish();
        Ok(self.layout(&best, &guests, work, evaluations, stop_reason))
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
            let pose = Pose::upright(shape);
            engine.insert(copy as u32, pose, translation);
            best.bins[0] = engine;
            best.placed[position] = Some(Placed {
                bin: 0,
                pose,
                translation,
                right: moved_right,
            });
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
            let (solution, spent) = self.extend(Solution::empty(order.clone()), pass, random);
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

    /// Shows the density of a complete roll layout `length` long as the stage's status (the
    /// lengths of the search are those of the inflated outlines, so it is a hair below the final
    /// figure measured on the exact ones).
    fn report_best(&self, progress: &dyn Progress, length: f64) {
        let area: f64 = (self.copies.iter())
            .map(|copy| self.items[copy.item].area().max(0.0))
            .sum();
        progress.status(&format!(
            "best density {:.2} %",
            100.0 * area / (self.height * length)
        ));
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
}

/// Shows the sheets and the last sheet's used length of a better sheet layout as the stage's
/// status (the length of the inflated outlines, a hair above the final figure).
fn report_sheets(progress: &dyn Progress, sheets: usize, length: f64) {
    progress.status(&format!("best {sheets} sheet(s), last {length:.1} mm used"));
}
