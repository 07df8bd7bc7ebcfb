//! Choosing the next cut: the candidate crest lines of the current pattern, each cut and
//! flattened briefly (screening), the most promising flattened on (trials), and the one of
//! largest gain kept; with the rules that say which pattern is better.

use std::sync::Arc;

use glam::DVec2;
use rayon::prelude::*;

use super::crest::{CrestLine, CrestSettings, crest_lines};
use super::density::{self, planning_map};
use super::errors::CutError;
use super::options::{
    CutOptions, FULL_TRIALS, LENGTH_EXPONENT, SCREEN_ITERATIONS, TRIAL_BUDGET,
    TRIAL_STEP_TOLERANCE, WIDER_SEARCH,
};
use super::paths::{Adjacency, path_length};
use super::smooth_cut::{Straightened, extension, smooth_cut};
use super::state::CutState;
use crate::flatten::{
    Accuracy, FastOptions, FillOrder, FlattenOptions, Flattened, SpringSystem, StopReason,
    flatten_from, flatten_unrepaired,
};
use crate::progress::NoProgress;

/// A cut that lowered the error.
#[derive(Clone)]
pub(super) struct Improvement {
    pub(super) state: CutState,
    pub(super) flattened: Flattened,
    pub(super) line: CrestLine,
}

/// Where the next cut step may go: it may start at the inner end of an existing cut (an
/// extension), elsewhere only while new cuts are allowed, and never pass a blocked vertex.
pub(super) struct Starts<'a> {
    pub(super) tips: &'a [u32],
    pub(super) new_cut_allowed: bool,
    pub(super) blocked: &'a [bool],
}

/// Which cuts a search may make.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shapes {
    /// Only smooth ones: straightened lines, straight extensions, edge paths already straight.
    Smooth,
    /// Also a line along its edges where its straightening cannot be cut (a zig-zag or a hooked
    /// extension): the last resort when no smooth cut lowers the error.
    AlongEdges,
}

/// A candidate cut, made and flattened.
#[derive(Clone)]
struct Trial {
    improvement: Improvement,
    /// Its gain: [`f64::MAX`]` / L` when it meets the tolerance, else `ΔE / L^LENGTH_EXPONENT`.
    gain: f64,
}

/// [`best_cut`] among smooth cuts, and when it finds none, again with lines from
/// [`WIDER_SEARCH`] times as many maxima, and when it still finds none, once more allowing cuts
/// along edges whose straightening cannot be cut ([`Shapes::AlongEdges`]).
pub(super) fn best_cut_widening(
    state: &CutState,
    flattened: &Flattened,
    flatten_options: &FlattenOptions,
    options: &CutOptions,
    starts: &Starts<'_>,
) -> Result<Option<Improvement>, CutError> {
    let search = |options: &CutOptions, shapes: Shapes| {
        best_cut(state, flattened, flatten_options, options, starts, shapes)
    };
    if let Some(improvement) = search(options, Shapes::Smooth)? {
        return Ok(Some(improvement));
    }
    let wider = CutOptions {
        candidates: options.candidates * WIDER_SEARCH,
        ..options.clone()
    };
    if let Some(improvement) = search(&wider, Shapes::Smooth)? {
        return Ok(Some(improvement));
    }
    search(&wider, Shapes::AlongEdges)
}

/// Picks the next cut in two rounds. Screening: every crest line of the current pattern is cut and
/// flattened for [`SCREEN_ITERATIONS`] solver iterations, warm-started from the current pattern
/// (the lines in parallel; the results keep the lines' order). Trial: the screened cuts that
/// lower the error, those without overlap first and then by gain, are flattened on to the trial
/// threshold [`TRIAL_STEP_TOLERANCE`] until [`FULL_TRIALS`] still lower the error, or
/// [`TRIAL_BUDGET`] were tried and at least one does; among those the one of largest gain
/// (the shortest within tolerance, else the largest `ΔE / L^LENGTH_EXPONENT`) is flattened to
/// the full threshold and returned.
fn best_cut(
    state: &CutState,
    flattened: &Flattened,
    flatten_options: &FlattenOptions,
    options: &CutOptions,
    starts: &Starts<'_>,
    shapes: Shapes,
) -> Result<Option<Improvement>, CutError> {
    let springs = SpringSystem::new(
        &state.model,
        state.stiffness.factors(),
        flatten_options.spring_constant,
    );
    let lines = candidate_lines(state, flattened, &springs, options, starts);
    // Every candidate is the state with vertices appended: its Laplacian is factored in the
    // state's elimination order, extended, instead of being ordered afresh.
    let flatten_options = &FlattenOptions {
        fill_order: FillOrder::of(state.model.vertex_count(), &springs)
            .ok()
            .map(Arc::new),
        ..flatten_options.clone()
    };
    let screen_options = with_fast(flatten_options, |fast| FastOptions {
        max_iterations: fast.max_iterations.min(SCREEN_ITERATIONS),
        step_tolerance: fast.step_tolerance.max(TRIAL_STEP_TOLERANCE),
        ..fast
    });
    let candidates: Vec<Option<Candidate>> = lines
        .into_par_iter()
        .map(|line| cut_candidate(state, &flattened.positions, line, starts, shapes))
        .collect::<Result<_, _>>()?;
    let mut screened = screen_all(candidates, flattened, &screen_options)?;
    let overlaps = |trial: &Trial| trial.improvement.flattened.stats.accuracy.overlap;
    screened.sort_by(|a, b| {
        overlaps(a)
            .cmp(&overlaps(b))
            .then(b.gain.total_cmp(&a.gain))
    });
    let trial_options = with_fast(flatten_options, |fast| FastOptions {
        step_tolerance: fast.step_tolerance.max(TRIAL_STEP_TOLERANCE),
        ..fast
    });
    let Some(Trial {
        mut improvement, ..
    }) = best_trial(screened, flattened, &trial_options)?
    else {
        return Ok(None);
    };
    let refined = flatten_from(
        &improvement.state.model,
        &improvement.state.stiffness,
        &improvement.flattened.positions,
        flatten_options,
    )?;
    if is_better(
        &refined.stats.accuracy,
        &improvement.flattened.stats.accuracy,
    ) || refined.stats.accuracy.within(flatten_options.tolerance)
    {
        improvement.flattened = refined;
    }
    Ok(Some(improvement))
}

/// The trial round of [`best_cut`]: the screened cuts, in their order, flattened on with
/// `trial_options` until [`FULL_TRIALS`] still lower the error, or [`TRIAL_BUDGET`] were tried
/// and at least one does; the one of largest gain among those that do. The trials run in
/// parallel batches no larger than the number the rule is sure to try next, so the choice is
/// the one trying them one by one would make.
fn best_trial(
    screened: Vec<Trial>,
    flattened: &Flattened,
    trial_options: &FlattenOptions,
) -> Result<Option<Trial>, CutError> {
    let mut best: Option<Trial> = None;
    let mut accepted = 0;
    let mut tried = 0;
    let mut waiting = screened.into_iter();
    while accepted < FULL_TRIALS && !(tried >= TRIAL_BUDGET && accepted > 0) {
        if trial_options.deadline.passed() {
            break;
        }
        let batch_size = if tried < TRIAL_BUDGET {
            (FULL_TRIALS - accepted).min(TRIAL_BUDGET - tried)
        } else {
            1
        };
        let batch: Vec<Trial> = waiting.by_ref().take(batch_size).collect();
        if batch.is_empty() {
            break;
        }
        tried += batch.len();
        let flattened_on: Vec<Option<Trial>> = batch
            .into_par_iter()
            .map(|trial| flatten_on(trial, flattened, trial_options))
            .collect::<Result<_, _>>()?;
        for trial in flattened_on.into_iter().flatten() {
            accepted += 1;
            if best.as_ref().is_none_or(|known| trial.gain > known.gain) {
                best = Some(trial);
            }
        }
    }
    Ok(best)
}

/// The crest lines of the current pattern a cut step may take: those of the energy map (Eq. 1)
/// and those of the tension map (stretched springs only, where a cut opens; on a saddle the
/// energy peaks where the pattern is compressed and a cut there would overlap), both as planning
/// maps ([`density`]: energy per unit area smoothed over a length tied to the part's size, so
/// the lines do not depend on the mesh); without repeats, an extension of an earlier cut or a
/// new cut only while new cuts are allowed. `springs` are the state's.
fn candidate_lines(
    state: &CutState,
    flattened: &Flattened,
    springs: &SpringSystem,
    options: &CutOptions,
    starts: &Starts<'_>,
) -> Vec<CrestLine> {
    let adjacency = Adjacency::new(&state.model);
    let areas = density::vertex_areas(&state.model);
    let map_of = |energies: Vec<f64>| planning_map(&state.model, &adjacency, &areas, &energies);
    let energy = map_of(springs.vertex_energies(&flattened.positions));
    let tension = map_of(springs.tension_energies(&flattened.positions));
    let settings = CrestSettings {
        blocked: starts.blocked,
        candidates: options.candidates,
        dart_floor: options.dart_floor,
        tension: &tension,
        tips: starts.tips,
        extensions_only: !starts.new_cut_allowed,
    };
    let mut lines: Vec<CrestLine> = Vec::new();
    for map in [&energy, &tension] {
        for line in crest_lines(&state.model, &adjacency, map, &settings) {
            let allowed = starts.new_cut_allowed || starts.tips.contains(&line.vertices[0]);
            if allowed && !lines.iter().any(|known| known.vertices == line.vertices) {
                lines.push(line);
            }
        }
    }
    lines
}

/// The flatten options with the fast solver's options changed by `change`.
fn with_fast(
    options: &FlattenOptions,
    change: impl FnOnce(FastOptions) -> FastOptions,
) -> FlattenOptions {
    FlattenOptions {
        fast: change(options.fast),
        ..options.clone()
    }
}

/// A crest line as cut ([`cut_candidate`]).
#[derive(PartialEq)]
struct Candidate {
    /// The state cut along the line.
    state: CutState,
    /// The start of its pattern: each vertex where the pattern before the cut had it.
    start: Vec<DVec2>,
    /// The line as cut, its vertices those of `state`.
    line: CrestLine,
}

/// The screening of [`best_cut`]: each candidate flattened with `screen_options` and judged
/// ([`screen`]), in parallel, the trials that lower the error in the candidates' order. Crest
/// lines that straighten to the same cut (same line, same cut model and start) are flattened
/// once: their trials are copies of the first one's, so the trial round sees what it would if
/// each had been flattened.
fn screen_all(
    candidates: Vec<Option<Candidate>>,
    flattened: &Flattened,
    screen_options: &FlattenOptions,
) -> Result<Vec<Trial>, CutError> {
    let candidates: Vec<Candidate> = candidates.into_iter().flatten().collect();
    let same_as: Vec<Option<usize>> = (0..candidates.len())
        .map(|i| (0..i).find(|&j| same_cut(&candidates[j], &candidates[i])))
        .collect();
    let mut screened: Vec<Option<Option<Trial>>> = candidates
        .into_par_iter()
        .zip(same_as.par_iter())
        .map(|(candidate, repeat)| match repeat {
            Some(_) => Ok(None),
            None => screen(candidate, flattened, screen_options).map(Some),
        })
        .collect::<Result<_, _>>()?;
    for (i, repeat) in same_as.iter().enumerate() {
        if let Some(first) = *repeat {
            screened[i] = screened[first].clone();
        }
    }
    Ok(screened.into_iter().flatten().flatten().collect())
}

/// Whether two candidates are the same cut: the same path and length in the same cut model
/// with the same start (the path first, which tells most apart at once; the lines' estimated
/// releases only ranked them).
fn same_cut(a: &Candidate, b: &Candidate) -> bool {
    a.line.vertices == b.line.vertices
        && a.line.length == b.line.length
        && a.start == b.start
        && a.state == b.state
}

/// Flattens a cut candidate with `screen_options`; `None` if the cut does not lower the error.
fn screen(
    Candidate { state, start, line }: Candidate,
    flattened: &Flattened,
    screen_options: &FlattenOptions,
) -> Result<Option<Trial>, CutError> {
    let candidate = reflatten(&state, &start, screen_options)?;
    let improvement = Improvement {
        state,
        flattened: candidate,
        line,
    };
    Ok(judge(
        improvement,
        flattened,
        screen_options.tolerance,
        Overlap::Ignored,
    ))
}

/// The candidate of a crest line: `state` cut along it, the start of its pattern (from the
/// pattern `positions` of `state`: each copy where its original was) and the line as cut. The line is cut along its geodesic straightening ([`smooth_cut`]:
/// crossing faces, the mesh refined along it), or when it extends a cut, straight on from that
/// cut for its length ([`straight_extension`]), or along its edges when they are already
/// straight. A line whose straightening is refused is cut along its edges only when `shapes`
/// allows it (those zig-zag or leave a hooked dart). `None` if it cannot be cut (it would cut a
/// piece off, open nothing, or run along the boundary or a fold line).
fn cut_candidate(
    state: &CutState,
    positions: &[DVec2],
    line: CrestLine,
    starts: &Starts<'_>,
    shapes: Shapes,
) -> Result<Option<Candidate>, CutError> {
    let start = line.vertices[0];
    let straightened = if starts.tips.contains(&start) {
        extension(state, &line.vertices, line.length, starts.blocked)
    } else {
        smooth_cut(state, &line.vertices, starts.blocked)
    };
    let (cut, line, start_of) = match straightened {
        Straightened::Refused if shapes == Shapes::Smooth => return Ok(None),
        Straightened::AlongEdges | Straightened::Refused => {
            (state.cut_along(&line.vertices), line, positions.to_vec())
        }
        Straightened::Smooth(smooth) => {
            let line = CrestLine {
                length: path_length(&smooth.state.model, &smooth.path),
                vertices: smooth.path.clone(),
                estimated_release: line.estimated_release,
            };
            let start_of = smooth.start_from(positions);
            (smooth.state.cut_along(&smooth.path), line, start_of)
        }
    };
    match cut {
        Ok((next, copied_vertex)) => {
            let start = copied_vertex
                .iter()
                .map(|&v| start_of[v as usize])
                .collect();
            Ok(Some(Candidate {
                state: next,
                start,
                line,
            }))
        }
        Err(error) if uncuttable(&error) => Ok(None),
        Err(error) => Err(error),
    }
}

/// Whether a cut error only says that this line cannot be cut.
pub(super) fn uncuttable(error: &CutError) -> bool {
    matches!(
        error,
        CutError::Disconnects
            | CutError::OpensNothing
            | CutError::BoundaryEdge { .. }
            | CutError::FoldLine { .. }
    )
}

/// Flattens a screened cut on from its screened pattern with `trial_options`; `None` if it no
/// longer lowers the error.
fn flatten_on(
    trial: Trial,
    before: &Flattened,
    trial_options: &FlattenOptions,
) -> Result<Option<Trial>, CutError> {
    let Improvement {
        state,
        flattened,
        line,
    } = trial.improvement;
    let further = flatten_from(
        &state.model,
        &state.stiffness,
        &flattened.positions,
        trial_options,
    )?;
    let flattened = if is_better(&flattened.stats.accuracy, &further.stats.accuracy) {
        flattened
    } else {
        further
    };
    let improvement = Improvement {
        state,
        flattened,
        line,
    };
    Ok(judge(
        improvement,
        before,
        trial_options.tolerance,
        Overlap::Refused,
    ))
}

/// Whether [`judge`] refuses an overlapping pattern. Screening ignores overlap: after a few
/// iterations the freshly cut sides have barely separated and touch (which counts as overlap) on
/// fine meshes; the trial round refuses it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Overlap {
    Ignored,
    Refused,
}

/// The trial of a cut model and its pattern, or `None` if it does not lower the error of the
/// pattern `before` or has a flipped triangle: the loop never takes a cut whose pattern is not
/// injective (the first flattening of a disk has no flipped triangle, and the warm-started
/// re-flattenings keep every triangle positive, so this refuses only what the solvers could
/// not make valid).
fn judge(
    improvement: Improvement,
    before: &Flattened,
    tolerance: f64,
    overlap: Overlap,
) -> Option<Trial> {
    let after = &improvement.flattened.stats;
    if after.accuracy.flipped > 0 {
        return None;
    }
    let lower = match overlap {
        Overlap::Refused => pays(&after.accuracy, &before.stats.accuracy, tolerance),
        Overlap::Ignored => after.accuracy.larger_error() < before.stats.accuracy.larger_error(),
    };
    if !lower {
        return None;
    }
    let length = improvement.line.length;
    let gain = if after.accuracy.within(tolerance) {
        // Within tolerance: nothing beats it but a shorter cut that is too.
        f64::MAX / length
    } else {
        (before.stats.energy - after.energy) / length.powf(LENGTH_EXPONENT)
    };
    Some(Trial { improvement, gain })
}

/// The pattern of a cut model, warm-started from `start` (the pattern before the cut, each copy
/// where its original was). When the warm start cannot move (the solver's orientation guard
/// blocks it), a cold flattening is tried too, without the flip-free repair, and kept when it is
/// better and has no flipped triangle the warm one does not have.
fn reflatten(
    next: &CutState,
    start: &[DVec2],
    flatten_options: &FlattenOptions,
) -> Result<Flattened, CutError> {
    let warm = flatten_from(&next.model, &next.stiffness, start, flatten_options)?;
    if warm.stats.stop_reason != StopReason::OrientationBlocked {
        return Ok(warm);
    }
    let cold = flatten_unrepaired(&next.model, &next.stiffness, flatten_options, &NoProgress)?;
    let valid = cold.stats.accuracy.flipped == 0 || warm.stats.accuracy.flipped > 0;
    Ok(
        if valid && is_better(&cold.stats.accuracy, &warm.stats.accuracy) {
            cold
        } else {
            warm
        },
    )
}

/// True if a cut that takes the pattern from `before` to `after` is worth making: `after` is the
/// better pattern ([`is_better`]), except that a cut leaving an overlapping pattern overlapping
/// with as many flipped triangles does not pay once `E_S` and `E_C` are within `tolerance`: the
/// overlap alone keeps the part out, and such a cut only adds length (the FreeCAD box's pocket
/// wall lies over its top face however it is cut: 8 cuts, 665 mm and 100 s spent in vain).
fn pays(after: &Accuracy, before: &Accuracy, tolerance: f64) -> bool {
    let overlap_kept = after.overlap && before.overlap && after.flipped == before.flipped;
    if overlap_kept && before.larger_error() <= tolerance {
        return false;
    }
    is_better(after, before)
}

/// True if `candidate` is a better pattern than `current`: it does not overlap while `current`
/// does; or both overlap and it has fewer flipped triangles (among the opened variants of a
/// closed part; the cut loop itself takes no pattern with a flipped triangle, see [`judge`]); or
/// its larger error is lower.
pub(super) fn is_better(candidate: &Accuracy, current: &Accuracy) -> bool {
    match (candidate.overlap, current.overlap) {
        (false, true) => true,
        (true, false) => false,
        (true, true) if candidate.flipped != current.flipped => candidate.flipped < current.flipped,
        _ => candidate.larger_error() < current.larger_error(),
    }
}

#[cfg(test)]
mod tests {
    use crate::cut::trials::*;

    fn accuracy(error: f64, flipped: usize, overlap: bool) -> Accuracy {
        Accuracy {
            area_error: error,
            shape_error: error / 2.0,
            max_strain: 0.0,
            flipped,
            overlap,
        }
    }

    #[test]
    fn a_cut_that_leaves_an_overlap_within_tolerance_does_not_pay() {
        let before = accuracy(0.001, 0, true);
        assert!(!pays(&accuracy(0.0005, 0, true), &before, 0.01));
        assert!(pays(&accuracy(0.0005, 0, false), &before, 0.01));
        assert!(pays(&accuracy(0.02, 0, false), &before, 0.01));
    }

    #[test]
    fn over_tolerance_a_lower_error_pays_even_while_overlapping() {
        let before = accuracy(0.05, 3, true);
        assert!(pays(&accuracy(0.04, 3, true), &before, 0.01));
        assert!(pays(&accuracy(0.06, 1, true), &before, 0.01));
        assert!(!pays(&accuracy(0.06, 3, true), &before, 0.01));
    }
}
