//! The search's solution turned into the public [`NestLayout`]: placements per sheet (copies in
//! holes composed with their hosts), lengths and utilisation measured on the exact outlines.

use super::holes::Guest;
use super::problem::Problem;
use super::solution::Solution;
use crate::nest::collision::JaguaEngine;
use crate::nest::layout::{NestLayout, SheetLayout, StopReason};

impl Problem<'_> {
    /// Converts a solution into the public layout, measured in exact geometry.
    pub(super) fn layout(
        &self,
        solution: &Solution<JaguaEngine>,
        guests: &[Vec<Guest>],
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
                let placement = self.placement(copy, placed.pose, placed.translation);
                let item = &self.items[copy.item];
                far_edge = placement
                    .transform_ring(&item.outer)
                    .iter()
                    .map(|point| point.x)
                    .fold(far_edge, f64::max);
                area += item.area();
                for guest in self.guest_placements(guests, copy_index, &placement) {
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
