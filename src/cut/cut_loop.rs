//! The cut loop: open the part, flatten it, and cut it along crest lines until it is within
//! tolerance or the cut budget is spent; see the module documentation of [`crate::cut`].

use std::collections::BTreeSet;

use super::coarse::{self, PLAN_ABOVE_TRIANGLES, Planned};
use super::crest_cuts::{Cutting, Plan, cut_along_crest_lines};
use super::errors::CutError;
use super::opening::{lay_user_seams, open_and_flatten};
use super::options::{
    CAP_CURVATURE, CUT_LOOP_ENERGY_TOLERANCE, CUTS_PER_CAP, CutConstraints, CutOptions,
    DEFAULT_MAX_CUTS,
};
use super::result::{Cut, CutResult, CutStop, Seam};
use super::state::{CutState, PointKey, point_key};
use crate::flatten::{
    FastOptions, FlattenOptions, Flattened, Stiffness, flatten_from, overlap_free_flatten,
    with_squeezed_triangles_opened,
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
/// tolerance; see the module documentation. A part of more than [`PLAN_ABOVE_TRIANGLES`]
/// triangles plans its cuts on a coarse remesh first (docs/cutting.md, "Planning on a coarse
/// remesh").
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
    let (state, seams, flattened) =
        open_and_flatten(&state, constraints, user_seams, flatten_options, progress)?;
    cut_opened(
        state,
        seams,
        flattened,
        constraints,
        flatten_options,
        options,
        progress,
    )
}

/// [`cut_and_flatten`] from the part opened to a disk by its `seams` (`state`) and flattened
/// (`flattened`, as [`crate::flatten::flatten`] makes it): the cuts along crest lines, the
/// overlap removed and the squeezed triangles opened.
pub(super) fn cut_opened(
    state: CutState,
    seams: Vec<Seam>,
    mut flattened: Flattened,
    constraints: &CutConstraints,
    flatten_options: &FlattenOptions,
    options: &CutOptions,
    progress: &dyn Progress,
) -> Result<CutResult, CutError> {
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
    let cutting = Cutting::uncut(state, flattened);
    let plan = Plan {
        max_cuts,
        regions: &constraints.no_cut_regions,
        flatten_options,
        options,
    };
    let planned = if planned_on_coarse_remesh(&cutting, &plan) {
        coarse::plan_cuts(&cutting, &plan, progress)?
    } else {
        Planned::Nothing
    };
    let (cutting, stop) = match planned {
        Planned::Cut(cut, stop) => (*cut, stop),
        Planned::Short(laid, stop) => {
            let left = laid.map_or(cutting, |laid| *laid);
            // The part itself measures a little lower than its remesh: it may be within.
            let accuracy = left.flattened.stats.accuracy;
            let within = accuracy.within(flatten_options.tolerance);
            (left, if within { CutStop::ToleranceMet } else { stop })
        }
        Planned::Nothing => cut_along_crest_lines(cutting, &plan, "cut", progress)?,
    };
    let Cutting {
        state,
        mut flattened,
        cuts,
        uncut,
        ..
    } = cutting;
    if flattened.stats.accuracy.overlap {
        let tolerance = Some(flatten_options.tolerance);
        flattened = without_overlap(&state, flattened, flatten_options, tolerance)?;
    }
    let flattened =
        with_squeezed_triangles_opened(&state.model, &state.stiffness, flattened, flatten_options);
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

/// Whether the part's cuts are planned on a coarse remesh first: it is over tolerance, has more
/// than [`PLAN_ABOVE_TRIANGLES`] triangles and may be cut.
fn planned_on_coarse_remesh(cutting: &Cutting, plan: &Plan<'_>) -> bool {
    let accuracy = &cutting.flattened.stats.accuracy;
    plan.max_cuts > 0
        && !accuracy.within(plan.flatten_options.tolerance)
        && cutting.state.model.triangle_count() > PLAN_ABOVE_TRIANGLES
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
    model.angle_deficits().iter().map(|d| d.abs()).sum()
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
