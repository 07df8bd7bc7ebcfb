//! Search through overlap on sheets, from the sequence search's best layout, in two phases built
//! on the separator (`separator.rs`):
//!
//! 1. **Fewer sheets** (at most [`SHEET_REDUCTION_SHARE`] of the budget): the parts of the last
//!    sheet, largest first, are taken one at a time into an earlier sheet (those with the least
//!    area used first) at a random position and that sheet is separated; a part that separates
//!    stays there. When the last sheet is emptied it is dropped and the next last sheet is tried.
//!    A part moved off the last sheet never makes its used length longer. Then, while the last
//!    sheet is about as long as its widest part alone, that part is traded (half the budget left at
//!    most) for a part of an earlier sheet that is narrower alone, if both sheets separate.
//! 2. **Shorter last sheet** (the rest): the last sheet's parts are compressed like a strip
//!    (`compression.rs`: exploration, then compression), never beyond the sheet's width.

use std::sync::Arc;

use glam::DVec2;

use super::compression::parts_of;
use super::problem::{LENGTH_TOLERANCE_RELATIVE, Problem};
use super::random::SplitMix64;
use super::separator::{Limits, Part, Separator, strip_range};
use super::solution::{Placed, Solution};
use crate::nest::collision::{CollisionEngine, JaguaEngine, Pose, ShapeId};

/// Largest share of the budget of the search through overlap spent on emptying the last sheet.
pub const SHEET_REDUCTION_SHARE: f64 = 0.5;
/// When the separation of a sheet that was given one more part gives up, in the first pass over
/// the last sheet's parts; each further pass doubles the rounds, up to [`INSERTION_PASSES`].
const INSERTION_LIMITS: Limits = Limits {
    rounds: 50,
    strikes: 2,
};
/// Passes over the parts left on the last sheet (each with new random starts and twice the
/// rounds of the one before) before the search turns to its length.
pub const INSERTION_PASSES: u32 = 4;

/// How hard one part is tried into the earlier sheets: the separator's limits, the budget of the
/// phase and the work spent so far in it.
struct Attempt<'w> {
    limits: Limits,
    budget: u64,
    work: &'w mut u64,
}

/// A last sheet within this fraction of its widest part's length alone is traded from (no
/// compression could shorten it much).
pub const TRADE_SLACK: f64 = 0.05;

/// The parts of each sheet, in order.
type Sheets = Vec<Vec<Part>>;

impl Problem<'_> {
    /// Searches through overlap from the complete sheet layout `best` within `budget` work
    /// (collision queries), calling `stop` with the work spent (true ends the search) and
    /// `on_best` with the sheets and the last sheet's length of each better layout; returns the
    /// best layout found (or `None` if none is better) and the work.
    pub(super) fn improve_sheets(
        &self,
        best: &Solution<JaguaEngine>,
        budget: u64,
        random: &mut SplitMix64,
        mut stop: impl FnMut(u64) -> bool,
        mut on_best: impl FnMut(usize, f64),
    ) -> (Option<Solution<JaguaEngine>>, u64) {
        let parts = parts_of(best);
        if parts.len() != best.order.len() || parts.is_empty() {
            return (None, 0);
        }
        let mut sheets: Sheets = vec![Vec::new(); best.bins_in_use()];
        for (part, placed) in parts.iter().zip(best.placed.iter().flatten()) {
            sheets[placed.bin].push(*part);
        }
        let reduction_budget = (budget as f64 * SHEET_REDUCTION_SHARE) as u64;
        let (mut improved, mut work) =
            self.empty_last_sheets(&mut sheets, reduction_budget, random, &mut stop);
        let attempt = Attempt {
            limits: INSERTION_LIMITS,
            budget: work + budget.saturating_sub(work) / 2,
            work: &mut work,
        };
        improved |= self.trade_widest_part(&mut sheets, attempt, random, &mut stop);
        if improved {
            on_best(sheets.len(), self.sheet_length(&sheets));
        }
        let last = sheets.pop().expect("at least one sheet");
        if last.len() < 2 {
            // A part alone is already as far left as the construction could put it.
            sheets.push(last);
            return (improved.then(|| self.solution_of_sheets(&sheets)), work);
        }
        let length = self.sheet_length(std::slice::from_ref(&last));
        let (compressed, spent) = self.compress_parts(
            last.clone(),
            length,
            budget.saturating_sub(work),
            random,
            |spent| stop(work + spent),
            |length| on_best(sheets.len() + 1, length),
        );
        work += spent;
        match compressed {
            Some((parts, _)) => {
                sheets.push(parts);
                improved = true;
            }
            None => sheets.push(last),
        }
        (improved.then(|| self.solution_of_sheets(&sheets)), work)
    }

    /// Phase 1: moves the parts of the last sheet into the others while the budget lasts,
    /// dropping the last sheet whenever it is emptied. Returns whether anything moved, and the
    /// work.
    fn empty_last_sheets(
        &self,
        sheets: &mut Sheets,
        budget: u64,
        random: &mut SplitMix64,
        stop: &mut impl FnMut(u64) -> bool,
    ) -> (bool, u64) {
        let mut work = 0;
        let mut moved_any = false;
        let mut pass = 0;
        while sheets.len() > 1 && pass < INSERTION_PASSES {
            let limits = Limits {
                rounds: INSERTION_LIMITS.rounds << pass,
                ..INSERTION_LIMITS
            };
            let area = |part: &Part| self.items[self.copies[part.copy].item].area();
            let mut candidates = sheets[sheets.len() - 1].clone();
            candidates.sort_by(|a, b| area(b).total_cmp(&area(a)).then(a.copy.cmp(&b.copy)));
            for part in candidates {
                if work >= budget || stop(work) {
                    return (moved_any, work);
                }
                let attempt = Attempt {
                    limits,
                    budget,
                    work: &mut work,
                };
                if self.move_to_earlier_sheet(sheets, part, attempt, random, stop) {
                    moved_any = true;
                    let last = sheets.len() - 1;
                    sheets[last].retain(|kept| kept.copy != part.copy);
                }
            }
            if sheets[sheets.len() - 1].is_empty() {
                sheets.pop();
                pass = 0;
            } else {
                pass += 1;
            }
        }
        (moved_any, work)
    }

    /// While the last sheet's length is within [`TRADE_SLACK`] of its widest part's alone (no
    /// compression can go below that), trades that part for a part of an earlier sheet that is narrower alone (the
    /// largest such part first): the earlier sheet takes the wide part at a random position and
    /// the last sheet the narrow one at the wide one's place, in its narrowest orientation; the
    /// trade stands if both sheets separate. Returns whether a trade was made.
    fn trade_widest_part(
        &self,
        sheets: &mut Sheets,
        attempt: Attempt,
        random: &mut SplitMix64,
        stop: &mut impl FnMut(u64) -> bool,
    ) -> bool {
        let width = self.sheet_width.expect("sheets have a width");
        let tolerance = LENGTH_TOLERANCE_RELATIVE * self.scale;
        let Attempt {
            limits,
            budget,
            work,
        } = attempt;
        let area = |part: &Part| self.items[self.copies[part.copy].item].area();
        let alone_right = |part: &Part| {
            let alone = self.alone_at_left(part);
            alone.translation.x + self.bounds(alone.pose).1.x
        };
        let mut traded = false;
        'trades: while sheets.len() > 1 {
            let last = sheets.len() - 1;
            let right = self.sheet_length(&sheets[last..]);
            let Some(widest) = (0..sheets[last].len()).max_by(|&a, &b| {
                alone_right(&sheets[last][a]).total_cmp(&alone_right(&sheets[last][b]))
            }) else {
                break;
            };
            let wide = sheets[last][widest];
            if alone_right(&wide) < right * (1.0 - TRADE_SLACK) {
                break;
            }
            let mut offers: Vec<(usize, usize)> = Vec::new();
            for (sheet, parts) in sheets[..last].iter().enumerate() {
                for (index, other) in parts.iter().enumerate() {
                    if alone_right(other) < right - tolerance {
                        offers.push((sheet, index));
                    }
                }
            }
            offers.sort_by(|&(a_sheet, a), &(b_sheet, b)| {
                let (a, b) = (&sheets[a_sheet][a], &sheets[b_sheet][b]);
                area(b).total_cmp(&area(a)).then(a.copy.cmp(&b.copy))
            });
            for (sheet, index) in offers {
                let narrow = sheets[sheet][index];
                let (low, high) = strip_range(self, width, wide.pose);
                let mut earlier = sheets[sheet].clone();
                earlier[index] = Part {
                    translation: low + DVec2::new(random.unit(), random.unit()) * (high - low),
                    ..wide
                };
                let turned = self.alone_at_left(&narrow);
                let (low, high) = strip_range(self, right, turned.pose);
                let mut later = sheets[last].clone();
                later[widest] = Part {
                    translation: wide.translation.clamp(low, high),
                    ..turned
                };
                let mut separated = Vec::with_capacity(2);
                for (parts, length) in [(earlier, width), (later, right)] {
                    if *work >= budget || stop(*work) {
                        break 'trades;
                    }
                    let mut separator = Separator::new(self, parts, length);
                    let before = *work;
                    let loss = separator.separate(limits, random, budget - before, &mut |spent| {
                        stop(before + spent)
                    });
                    *work += separator.work();
                    if loss > 0.0 {
                        break;
                    }
                    separated.push(separator.parts);
                }
                if let [earlier, later] = &separated[..] {
                    sheets[sheet].clone_from(earlier);
                    sheets[last].clone_from(later);
                    traded = true;
                    continue 'trades;
                }
            }
            break;
        }
        traded
    }

    /// `part` alone on a sheet: at the bottom-left corner, in its narrowest allowed orientation.
    fn alone_at_left(&self, part: &Part) -> Part {
        let width = self.sheet_width.expect("sheets have a width");
        let extent = |shape: ShapeId| {
            let orientation = &self.orientations[shape];
            orientation.max.x - orientation.min.x
        };
        let shapes = &self.item_shapes[self.copies[part.copy].item];
        let shape = (shapes.iter().copied())
            .min_by(|&a, &b| extent(a).total_cmp(&extent(b)).then(a.cmp(&b)))
            .unwrap_or(part.pose.shape);
        let pose = Pose::upright(shape);
        Part {
            pose,
            translation: strip_range(self, width, pose).0,
            ..*part
        }
    }

    /// Tries to separate `part` into each sheet but the last, those with the least area used
    /// first; true (and that sheet updated) on the first that separates.
    fn move_to_earlier_sheet(
        &self,
        sheets: &mut Sheets,
        part: Part,
        attempt: Attempt,
        random: &mut SplitMix64,
        stop: &mut impl FnMut(u64) -> bool,
    ) -> bool {
        let width = self.sheet_width.expect("sheets have a width");
        let used = |sheet: &Vec<Part>| -> f64 {
            (sheet.iter())
                .map(|part| self.items[self.copies[part.copy].item].area())
                .sum()
        };
        let mut targets: Vec<usize> = (0..sheets.len() - 1).collect();
        targets.sort_by(|&a, &b| {
            used(&sheets[a])
                .total_cmp(&used(&sheets[b]))
                .then(a.cmp(&b))
        });
        let Attempt {
            limits,
            budget,
            work,
        } = attempt;
        for target in targets {
            if *work >= budget || stop(*work) {
                return false;
            }
            let (low, high) = strip_range(self, width, part.pose);
            let mut trial = sheets[target].clone();
            trial.push(Part {
                translation: low + DVec2::new(random.unit(), random.unit()) * (high - low),
                ..part
            });
            let mut separator = Separator::new(self, trial, width);
            let before = *work;
            let loss = separator.separate(limits, random, budget - before, &mut |spent| {
                stop(before + spent)
            });
            *work += separator.work();
            if loss <= 0.0 {
                sheets[target].clone_from(&separator.parts);
                return true;
            }
        }
        false
    }

    /// Right end of the parts of the last of `sheets` (inflated outlines).
    fn sheet_length(&self, sheets: &[Vec<Part>]) -> f64 {
        (sheets.last().into_iter().flatten())
            .map(|part| part.translation.x + self.bounds(part.pose).1.x)
            .fold(0.0, f64::max)
    }

    /// A sheet solution holding the parts of each of `sheets` on its own sheet.
    fn solution_of_sheets(&self, sheets: &[Vec<Part>]) -> Solution<JaguaEngine> {
        let width = self.sheet_width.expect("sheets have a width");
        let mut solution = Solution::empty(Vec::new());
        for (bin, parts) in sheets.iter().enumerate() {
            let mut engine = JaguaEngine::new(
                Arc::clone(&self.library),
                DVec2::ZERO,
                DVec2::new(width, self.height),
            )
            .expect("the sheet holds its parts");
            for part in parts {
                engine.insert(part.copy as u32, part.pose, part.translation);
                solution.order.push(part.copy);
                solution.placed.push(Some(Placed {
                    bin,
                    pose: part.pose,
                    translation: part.translation,
                    right: part.translation.x + self.bounds(part.pose).1.x,
                }));
            }
            solution.bins.push(engine);
        }
        solution
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

    /// Nesting on 25 × 25 mm sheets, every other option the default.
    fn sheets_25() -> NestOptions {
        NestOptions {
            stock: Stock::Sheets {
                width: 25.0,
                height: 25.0,
            },
            ..NestOptions::default()
        }
    }

    /// Copy `copy` of the problem's first shape (a 10 mm square) at `(x, y)`.
    fn square_at(problem: &Problem, copy: usize, x: f64, y: f64) -> Part {
        Part {
            copy,
            pose: Pose::upright(problem.item_shapes[0][0]),
            translation: DVec2::new(x, y),
        }
    }

    /// Checks `solution` independently and returns its layout.
    fn verified(
        problem: &Problem,
        items: &[crate::nest::NestItem],
        solution: &Solution<JaguaEngine>,
    ) -> crate::nest::NestLayout {
        let layout = problem.layout(
            solution,
            &problem.fill_holes(),
            0,
            0,
            StopReason::WorkBudget,
        );
        let violations = verify(items, &layout);
        assert!(violations.is_empty(), "{violations:?}");
        layout
    }

    /// Three 10 mm squares on the first 25 mm sheet and a fourth alone on a second: the fourth
    /// fits in the first sheet's free corner, so the search ends on one sheet.
    #[test]
    fn the_last_sheet_is_emptied_into_the_others() {
        let items = vec![square("square 10", 10.0, 4)];
        let options = sheets_25();
        let problem = Problem::new(&items, &options).expect("valid problem");
        let first = vec![
            square_at(&problem, 0, 0.5, 0.5),
            square_at(&problem, 1, 12.0, 0.5),
            square_at(&problem, 2, 0.5, 12.0),
        ];
        let start = problem.solution_of_sheets(&[first, vec![square_at(&problem, 3, 0.5, 0.5)]]);
        assert_eq!(verified(&problem, &items, &start).sheets.len(), 2);
        let (improved, work) =
            problem.improve_sheets(&start, 2_000_000, &mut SplitMix64(3), |_| false, |_, _| ());
        assert!(work > 0);
        let improved = improved.expect("a better layout");
        let layout = verified(&problem, &items, &improved);
        assert_eq!(layout.sheets.len(), 1);
        assert_eq!(layout.sheets[0].placements.len(), 4);
    }

    /// A 20 × 10 mm bar alone on the last 25 mm sheet, which the first sheet (another bar and a
    /// 10 mm square) has no room for: the bar trades places with the square, and the last sheet
    /// is used over about 10 mm instead of 20.
    #[test]
    fn a_wide_part_alone_on_the_last_sheet_trades_places_with_a_narrower_one() {
        let mut bar = square("bar", 10.0, 2);
        bar.outer = vec![
            DVec2::ZERO,
            DVec2::new(20.0, 0.0),
            DVec2::new(20.0, 10.0),
            DVec2::new(0.0, 10.0),
        ];
        let items = vec![bar, square("square 10", 10.0, 1)];
        let options = sheets_25();
        let problem = Problem::new(&items, &options).expect("valid problem");
        let copy_of = |item: usize| {
            (problem.copies.iter())
                .position(|copy| copy.item == item)
                .expect("a copy")
        };
        let at = |copy: usize, x: f64, y: f64| Part {
            copy,
            pose: Pose::upright(problem.item_shapes[problem.copies[copy].item][0]),
            translation: DVec2::new(x, y),
        };
        let (bar, square) = (copy_of(0), copy_of(1));
        let first = vec![at(bar, 0.5, 0.5), at(square, 0.5, 12.0)];
        let start = problem.solution_of_sheets(&[first, vec![at(bar + 1, 0.5, 0.5)]]);
        assert!(verified(&problem, &items, &start).used_length > 20.0);
        let (improved, _) =
            problem.improve_sheets(&start, 2_000_000, &mut SplitMix64(4), |_| false, |_, _| ());
        let layout = verified(&problem, &items, &improved.expect("a shorter last sheet"));
        assert_eq!(layout.sheets.len(), 2);
        assert!(layout.used_length < 11.0, "{}", layout.used_length);
        assert_eq!(layout.sheets[1].placements[0].item, 1, "the square is last");
    }

    /// Two 10 mm squares side by side on a 25 × 25 mm sheet with room for them one above the
    /// other: the last sheet's used length shrinks from 22 mm to about 10, deterministically.
    #[test]
    fn the_last_sheet_is_compressed_like_a_strip_deterministically() {
        let items = vec![square("square 10", 10.0, 2)];
        let options = sheets_25();
        let problem = Problem::new(&items, &options).expect("valid problem");
        let parts = vec![
            square_at(&problem, 0, 0.5, 0.5),
            square_at(&problem, 1, 12.0, 0.5),
        ];
        let start = problem.solution_of_sheets(&[parts]);
        assert!(verified(&problem, &items, &start).used_length > 21.9);
        let run = || {
            let (improved, _) =
                problem.improve_sheets(&start, 1_000_000, &mut SplitMix64(9), |_| false, |_, _| ());
            improved.expect("a shorter last sheet")
        };
        let layout = verified(&problem, &items, &run());
        assert_eq!(layout.sheets.len(), 1);
        assert!(layout.used_length < 11.0, "{}", layout.used_length);
        let places = |solution: &Solution<JaguaEngine>| -> Vec<[u64; 2]> {
            (solution.placed.iter().flatten())
                .map(|placed| {
                    [
                        placed.translation.x.to_bits(),
                        placed.translation.y.to_bits(),
                    ]
                })
                .collect()
        };
        assert_eq!(places(&run()), places(&run()));
    }
}
