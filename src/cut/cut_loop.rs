//! The cut loop: open the part, flatten it, and cut it along crest lines until it is within
//! tolerance or the cut budget is spent; see the module documentation of [`crate::cut`].

use std::collections::BTreeSet;

use super::errors::CutError;
use super::opening::{lay_user_seams, open_and_flatten};
use super::options::{
    CAP_CURVATURE, CUT_LOOP_ENERGY_TOLERANCE, CUTS_PER_CAP, CutConstraints, CutOptions,
    DEFAULT_MAX_CUTS, EXTENSIONS_PER_CUT, MIN_RELEASE, STALLED_STEPS,
};
use super::result::{Cut, CutFigures, CutResult, CutStop, UncutPattern};
use super::seam;
use super::state::{CutState, PointKey, point_key, polyline};
use super::trials::{Starts, best_cut_widening};
use crate::flatten::{
    FastOptions, FlattenOptions, Flattened, Stiffness, flatten_from, overlap_free_flatten,
};
use crate::mesh::FacetModel;
use crate::progress::Progress;

/// The flatten options of the cut loop: the caller's, converged to at least
/// [`CUT_LOOP_ENERGY_TOLERANCE`].
pub(super) fn converged_options(options: &FlattenOptions) -> FlattenOptions {
    let energy_tolerance = options.fast.energy_tolerance.min(CUT_LOOP_ENERGY_TOLERANCE);
    FlattenOptions {
        fast: FastOptions {
            energy_tolerance,
            ..options.fast
        },
        ..options.clone()
    }
}

/// Opens the part with seams, flattens it and cuts it along crest lines until it is within
/// tolerance; see the module documentation.
pub fn cut_and_flatten(
    model: &FacetModel,
    stiffness: &Stiffness,
    constraints: &CutConstraints,
    flatten_options: &FlattenOptions,
    options: &CutOptions,
    progress: &dyn Progress,
) -> Result<CutResult, CutError> {
    let mut state = CutState {
        model: model.clone(),
        stiffness: stiffness.clone(),
        original_vertex: (0..model.vertex_count() as u32).collect(),
    };
    let mut user_seams = Vec::new();
    lay_user_seams(&mut state, constraints, &mut user_seams)?;
    let (mut state, seams, mut flattened) =
        open_and_flatten(&state, constraints, user_seams, flatten_options, progress)?;
    let max_cuts = options
        .max_cuts
        .unwrap_or_else(|| default_cut_budget(&state.model));
    let loop_options = converged_options(flatten_options);
    if !flattened.stats.accuracy.within(flatten_options.tolerance) && max_cuts > 0 {
        let start = flattened.positions.clone();
        flattened = flatten_from(&state.model, &state.stiffness, &start, &loop_options)?;
    }
    if flattened.stats.accuracy.overlap {
        flattened = without_overlap(&state, flattened, &loop_options, None)?;
    }
    let flatten_options = &loop_options;
    let mut cuts: Vec<Cut> = Vec::new();
    let mut tips: Vec<u32> = Vec::new();
    let mut uncut = None;
    let mut payoff = Payoff::new(
        (state.clone(), flattened.clone(), Vec::new()),
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
        let blocked = state.blocked(&constraints.no_cut_regions);
        let starts = Starts {
            tips: &tips,
            new_cut_allowed,
            blocked: &blocked,
        };
        if !reporting {
            progress.start("cut", step_budget as u64);
            reporting = true;
        }
        let Some(improvement) =
            best_cut_widening(&state, &flattened, flatten_options, options, &starts)?
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
                if cuts.is_empty() {
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
        let snapshot = || (state.clone(), flattened.clone(), cuts.clone());
        if payoff.record(flattened.stats.energy, snapshot) {
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
        (state, flattened, cuts) = payoff.into_snapshot();
        if cuts.is_empty() {
            uncut = None;
        }
    }
    if reporting {
        progress.finish();
    }
    if flattened.stats.accuracy.overlap {
        let tolerance = Some(flatten_options.tolerance);
        flattened = without_overlap(&state, flattened, flatten_options, tolerance)?;
    }
    let cut_edges = cut_sides(&state, &cuts);
    Ok(CutResult {
        cut_edges,
        model: state.model,
        stiffness: state.stiffness,
        original_vertex: state.original_vertex,
        flattened,
        seams,
        cuts,
        stop,
        uncut,
    })
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

/// The part's pattern made again with its outline kept from crossing itself
/// ([`overlap_free_flatten`]) when the first flattening or the cut loop ends on a pattern that
/// overlaps itself (the loop then cuts from a valid pattern, and never takes a cut whose
/// pattern overlaps: [`is_better`](super::trials::is_better)). The new pattern is kept when it
/// neither overlaps nor has a flipped triangle (and, given a `tolerance`, is within it: a valid
/// pattern far over the tolerance tells less than the overlapping one it would replace); else
/// the pattern stays as it was, and the part is rejected for its overlap.
fn without_overlap(
    state: &CutState,
    flattened: Flattened,
    options: &FlattenOptions,
    tolerance: Option<f64>,
) -> Result<Flattened, CutError> {
    let remade = overlap_free_flatten(&state.model, &state.stiffness, options)?;
    Ok(match remade {
        Some(remade)
            if !remade.stats.accuracy.overlap
                && remade.stats.accuracy.flipped == 0
                && tolerance.is_none_or(|t| remade.stats.accuracy.within(t)) =>
        {
            remade
        }
        _ => flattened,
    })
}

/// The number of crest-line cuts a part may get when the user sets none: [`CUTS_PER_CAP`] per
/// [`CAP_CURVATURE`] of the total absolute Gaussian curvature `∫|K| dA = Σ |2π − Σθ|` over the
/// interior vertices of the opened part (the curvature its seams did not release), and at least
/// [`DEFAULT_MAX_CUTS`]. A closed UV sphere halved along its bisector holds about `3.5π` (28
/// cuts); a box opened to its net holds none (8).
pub fn default_cut_budget(model: &FacetModel) -> usize {
    let scaled = (CUTS_PER_CAP * total_absolute_curvature(model) / CAP_CURVATURE).ceil();
    DEFAULT_MAX_CUTS.max(scaled as usize)
}

/// The total absolute Gaussian curvature `∫|K| dA = Σ |2π − Σθ|` over the interior vertices of
/// the model, radians.
pub fn total_absolute_curvature(model: &FacetModel) -> f64 {
    seam::angle_deficits(model).iter().map(|d| d.abs()).sum()
}

/// The edges of the cut model that are sides of a cut: boundary edges both of whose ends lie at
/// a point of some cut (copies keep their original's position exactly; a smoothed cut's points
/// are inserted vertices that have no input vertex of their own).
fn cut_sides(state: &CutState, cuts: &[Cut]) -> Vec<usize> {
    let on_cut: BTreeSet<PointKey> = cuts
        .iter()
        .flat_map(|cut| cut.points.iter().map(|&p| point_key(p)))
        .collect();
    let at_cut = |v: u32| on_cut.contains(&point_key(state.model.positions()[v as usize]));
    let model = &state.model;
    model
        .edges()
        .iter()
        .enumerate()
        .filter(|&(e, &[a, b])| model.is_boundary_edge(e) && at_cut(a) && at_cut(b))
        .map(|(e, _)| e)
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::cut::cut_loop::*;

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
