//! The crest-line cut loop proper: from a part opened and flattened, cut step by step (a new cut
//! or an extension of one) along the crest line that pays best, until the part is within
//! tolerance, the budget is spent, no cut pays or time runs out; see the module documentation of
//! [`crate::cut`].

use super::errors::CutError;
use super::options::{CutOptions, EXTENSIONS_PER_CUT, MIN_RELEASE, NoCutRegion, STALLED_STEPS};
use super::result::{Cut, CutFigures, CutStop, UncutPattern};
use super::state::{CutState, polyline};
use super::trials::{Starts, best_cut_widening};
use crate::flatten::{FlattenOptions, Flattened};
use crate::progress::Progress;

/// What a run of the cut loop may do: its cut budget, the regions no cut may pass, the flatten
/// options (the loop's, converged to [`CUT_LOOP_ENERGY_TOLERANCE`](super::CUT_LOOP_ENERGY_TOLERANCE)) and
/// the cut options.
pub(super) struct Plan<'a> {
    pub(super) max_cuts: usize,
    pub(super) regions: &'a [NoCutRegion],
    pub(super) flatten_options: &'a FlattenOptions,
    pub(super) options: &'a CutOptions,
}

/// A part being cut: the cut model, its pattern, the cuts made so far with the vertex each ends
/// at inside the part (where an extension may start), and the part before its first cut.
#[derive(Clone)]
pub(super) struct Cutting {
    pub(super) state: CutState,
    pub(super) flattened: Flattened,
    pub(super) cuts: Vec<Cut>,
    pub(super) tips: Vec<u32>,
    pub(super) uncut: Option<UncutPattern>,
}

impl Cutting {
    /// A part with no cut yet.
    pub(super) fn uncut(state: CutState, flattened: Flattened) -> Self {
        Self {
            state,
            flattened,
            cuts: Vec::new(),
            tips: Vec::new(),
            uncut: None,
        }
    }

    /// The part as it is now, as the pattern before its first cut.
    pub(super) fn as_uncut(&self) -> UncutPattern {
        UncutPattern {
            model: self.state.model.clone(),
            stiffness: self.state.stiffness.clone(),
            flattened: self.flattened.clone(),
        }
    }
}

/// Cuts the part along crest lines until it is within tolerance, the cut budget is spent, no cut
/// pays or time runs out (see the module documentation); the cut steps since the last that paid
/// are taken back unless they brought the part within tolerance or ended an overlap. Progress is
/// reported as `stage`.
pub(super) fn cut_along_crest_lines(
    cutting: Cutting,
    plan: &Plan<'_>,
    stage: &str,
    progress: &dyn Progress,
) -> Result<(Cutting, CutStop), CutError> {
    let Cutting {
        mut state,
        mut flattened,
        mut cuts,
        mut tips,
        mut uncut,
    } = cutting;
    let flatten_options = plan.flatten_options;
    let max_cuts = plan.max_cuts;
    let mut payoff = Payoff::new(
        (state.clone(), flattened.clone(), cuts.clone(), tips.clone()),
        flattened.stats.energy,
    );
    let step_budget = max_cuts * (1 + EXTENSIONS_PER_CUT);
    let mut reporting = false;
    let mut steps = 0;
    let stop = loop {
        if flattened.stats.accuracy.within(flatten_options.tolerance) {
            break CutStop::ToleranceMet;
        }
        if flatten_options.deadline.passed() {
            break CutStop::TimeLimit;
        }
        let new_cut_allowed = cuts.len() < max_cuts;
        if steps >= step_budget || (!new_cut_allowed && tips.is_empty()) {
            break CutStop::CutBudget;
        }
        let blocked = state.blocked(plan.regions);
        let starts = Starts {
            tips: &tips,
            new_cut_allowed,
            blocked: &blocked,
        };
        if !reporting {
            progress.start(stage, step_budget as u64);
            reporting = true;
        }
        let Some(improvement) =
            best_cut_widening(&state, &flattened, flatten_options, plan.options, &starts)?
        else {
            // Trials cut short by the deadline find nothing: that is the time limit's doing.
            break if flatten_options.deadline.passed() {
                CutStop::TimeLimit
            } else if new_cut_allowed {
                CutStop::NoBetterCut
            } else {
                CutStop::CutBudget
            };
        };
        steps += 1;
        progress.advance(steps as u64);
        let line = &improvement.line;
        // The line's vertices are those of the cut state (a straightened cut inserts vertices).
        let points = polyline(&improvement.state.model, &line.vertices);
        let vertices: Vec<u32> = line
            .vertices
            .iter()
            .map(|&v| improvement.state.original_vertex[v as usize])
            .collect();
        let tip = line.vertices[line.vertices.len() - 1];
        let after = CutFigures::of(&improvement.flattened);
        match tips.iter().position(|&known| known == line.vertices[0]) {
            Some(extended) => {
                let cut = &mut cuts[extended];
                cut.points.extend_from_slice(&points[1..]);
                cut.vertices.extend_from_slice(&vertices[1..]);
                cut.length += line.length;
                cut.after = after;
                tips[extended] = tip;
            }
            None => {
                if uncut.is_none() {
                    uncut = Some(UncutPattern {
                        model: state.model.clone(),
                        stiffness: state.stiffness.clone(),
                        flattened: flattened.clone(),
                    });
                }
                cuts.push(Cut {
                    points,
                    vertices,
                    length: line.length,
                    before: CutFigures::of(&flattened),
                    after,
                });
                tips.push(tip);
            }
        }
        state = improvement.state;
        flattened = improvement.flattened;
        let snapshot = || (state.clone(), flattened.clone(), cuts.clone(), tips.clone());
        let stalled = payoff.record(flattened.stats.energy, snapshot);
        // A step that brings the part within tolerance ends the loop as such, paid or not.
        if stalled && !flattened.stats.accuracy.within(flatten_options.tolerance) {
            break CutStop::NoBetterCut;
        }
    };
    let overlap_ended =
        payoff.snapshot().1.stats.accuracy.overlap && !flattened.stats.accuracy.overlap;
    let within = flattened.stats.accuracy.within(flatten_options.tolerance);
    if payoff.unpaid() && !within && !overlap_ended {
        // The steps since the last that paid released less than MIN_RELEASE together and
        // neither brought the part within tolerance nor ended an overlap: length for nothing,
        // taken back.
        (state, flattened, cuts, tips) = payoff.into_snapshot();
        if cuts.is_empty() {
            uncut = None;
        }
    }
    if reporting {
        progress.finish();
    }
    let cutting = Cutting {
        state,
        flattened,
        cuts,
        tips,
        uncut,
    };
    Ok((cutting, stop))
}

/// Which cut steps paid: the state after the last step that lowered the spring energy by at
/// least [`MIN_RELEASE`] below the last such state's (the start counts as one), and the steps
/// taken since.
struct Payoff<T> {
    snapshot: T,
    energy: f64,
    steps_since: usize,
}

impl<T> Payoff<T> {
    /// The start: `snapshot` at `energy`.
    fn new(snapshot: T, energy: f64) -> Self {
        Self {
            snapshot,
            energy,
            steps_since: 0,
        }
    }

    /// Records a step that ended at `energy`; when it pays (with the steps since the last that
    /// paid), `snapshot` is kept. True when the last [`STALLED_STEPS`] steps have not paid.
    fn record(&mut self, energy: f64, snapshot: impl FnOnce() -> T) -> bool {
        if energy <= (1.0 - MIN_RELEASE) * self.energy {
            *self = Self::new(snapshot(), energy);
            return false;
        }
        self.steps_since += 1;
        self.steps_since >= STALLED_STEPS
    }

    /// True when steps were taken since the last that paid.
    fn unpaid(&self) -> bool {
        self.steps_since > 0
    }

    /// The state after the last step that paid.
    fn snapshot(&self) -> &T {
        &self.snapshot
    }

    /// The state after the last step that paid.
    fn into_snapshot(self) -> T {
        self.snapshot
    }
}

#[cfg(test)]
mod tests {
    use crate::cut::crest_cuts::*;

    /// The step numbers a payoff keeps and whether it stalls, for a run of step energies from 100.
    fn run(energies: &[f64]) -> (usize, bool) {
        let mut payoff = Payoff::new(0, 100.0);
        let mut stalled = false;
        for (step, &energy) in energies.iter().enumerate() {
            stalled = payoff.record(energy, || step + 1);
            if stalled {
                break;
            }
        }
        (payoff.into_snapshot(), stalled)
    }

    #[test]
    fn steps_that_release_little_one_by_one_pay_together() {
        // 0.6 % and then 0.5 % more: together over 1 %, so the second step pays.
        assert_eq!(run(&[99.4, 98.9]), (2, false));
    }

    #[test]
    fn a_step_that_opens_the_way_pays_with_the_one_it_opens() {
        // A short dart that releases nothing, then its extension that releases 40 %.
        assert_eq!(run(&[100.2, 60.0]), (2, false));
    }

    #[test]
    fn steps_that_do_not_pay_stall_the_loop_and_are_taken_back() {
        let energies = [90.0, 89.9, 90.1, 89.5, 89.2, 50.0];
        assert_eq!(STALLED_STEPS, 4);
        // Step 1 paid; steps 2 to 5 release 0.9 % together: stalled, back to step 1.
        assert_eq!(run(&energies), (1, true));
    }
}
