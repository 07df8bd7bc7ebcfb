//! The moves of the local search over the sequence: swap two copies of different items, or move
//! one copy earlier (a copy left out, while strip shrinking), and the re-placement of the changed
//! tail.

use super::placement::Pass;
use super::problem::Problem;
use super::random::SplitMix64;
use super::solution::Solution;
use crate::nest::collision::{CollisionEngine, JaguaEngine};

/// Neighbours evaluated (in parallel) per round of the local search. Fixed, so the result does not
/// depend on the number of threads.
pub const NEIGHBOURS_PER_ROUND: usize = 4;

impl Problem<'_> {
    /// Draws the moves of one round: each a new sequence, its first changed position and a seed.
    /// `None` when no move changes anything (fewer than two distinct items).
    ///
    /// Positions are drawn with a bias towards the end of the sequence (re-placing a short tail
    /// is cheap, and the tail decides the length). While copies are left out (strip shrinking),
    /// half the moves take one of them and insert it at a uniformly drawn earlier position.
    pub(super) fn draw_moves(
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
    pub(super) fn evaluate(
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
}
