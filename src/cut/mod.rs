//! Cutting (paper §6.3): seams that open closed and ring surfaces, then crest-line cuts of the
//! energy map, each followed by a new flattening, until `E_S` and `E_C` are within tolerance or
//! the cut budget is spent.
//!
//! [`cut_and_flatten`] is the one-shot entry point:
//! 1. user seams ([`CutConstraints::seams`]) are laid on the mesh and cut;
//! 2. automatic seams ([`seam`], [`cut_graph`]) open the surface to a disk: one per ring loop; on a
//!    closed surface a tree–cotree cut graph first if it has handles, then a Steiner tree through
//!    the regions where its curvature concentrates, or, on a smooth one, around the bisector of
//!    its two farthest points but a hinge; the crest-line cut budget defaults to 8 per π of the
//!    curvature left ([`default_cut_budget`]);
//! 3. the part is flattened; while it is over tolerance and cuts are left, every candidate line of
//!    its energy map and of its tension map (stretched springs only: where a cut opens) ([`crest`])
//!    is cut and briefly flattened, warm-started from the current pattern, and the most promising
//!    are flattened on (`best_cut`, docs/cutting.md); among those that lower the error (`max(E_S, E_C)`, an
//!    overlapping pattern counting as worse than any other) the shortest that meets the tolerance
//!    is kept, or else the one of largest measured gain `ΔE / L^LENGTH_EXPONENT`; a line from the
//!    inner end of an earlier cut extends that cut;
//! 4. the cut model, its pattern and every cut with its figures before and after come back.
//!
//! Cuts never run along or across a fold line (no vertex of a fold-line edge is crossed) nor
//! through a no-cut region; a developable part within tolerance gets no cut.

pub mod crest;
pub mod cut_graph;
pub mod density;
mod errors;
pub mod paths;
pub mod seam;
pub mod split;

use std::f64::consts::PI;

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

pub use errors::CutError;
pub use seam::SeamKind;

use crate::flatten::{
    Accuracy, FastOptions, FlattenOptions, Flattened, SpringSystem, Stiffness, StopReason, flatten,
    flatten_from,
};
use crate::mesh::{FacetModel, NONE};
use crate::progress::{NoProgress, Progress};
use crest::{CrestLine, CrestSettings, DEFAULT_CANDIDATES, DEFAULT_DART_FLOOR, crest_lines};
use cut_graph::RegionSigns;
use density::planning_map;
use paths::{Adjacency, path_edges, path_length};
use split::split_along_edges;

/// Smallest default number of crest-line cuts per part (seams not counted); see
/// [`default_cut_budget`].
pub const DEFAULT_MAX_CUTS: usize = 8;
/// Total absolute Gaussian curvature `∫|K| dA` of the spherical cap of half-angle 60°,
/// `2π (1 − cos 60°) = π`, the unit of [`default_cut_budget`].
pub const CAP_CURVATURE: f64 = PI;
/// Crest-line cuts allowed per [`CAP_CURVATURE`] of total absolute curvature: the 60° cap reaches
/// 1 % with 5 of its 8, a closed UV sphere halved along its bisector (`3.5π` left) with 27.
pub const CUTS_PER_CAP: f64 = DEFAULT_MAX_CUTS as f64;
/// The cut loop keeps the candidate of largest `ΔE / L^LENGTH_EXPONENT` (measured energy drop
/// `ΔE`, cut length `L`). With 1 (drop per unit length) the loop prefers ever shorter steps, since
/// returns diminish along a cut, and spends its budget on millimetre extensions; with 1/2 a cut
/// three times as long wins if it releases more than `√3 ≈ 1.7` times the energy.
pub const LENGTH_EXPONENT: f64 = 0.5;
/// Candidate cuts are flattened with the fast solver's convergence threshold raised to this (a
/// fraction of the mean rest length; see [`FastOptions::step_tolerance`]): enough to rank them,
/// at a fraction of the cost. The chosen cut is then flattened to the full threshold.
pub const TRIAL_STEP_TOLERANCE: f64 = 1e-4;
/// Solver iterations of the screening round, in which every candidate cut is flattened briefly
/// to rank it (see `best_cut`).
pub const SCREEN_ITERATIONS: usize = 20;
/// Screened candidates that must still lower the error after being flattened on to
/// [`TRIAL_STEP_TOLERANCE`] before the choice is made among them.
pub const FULL_TRIALS: usize = 3;
/// Screened candidates flattened on per cut step (non-overlapping ones first, then by gain) before
/// the choice is made among those accepted; while none is, the trials go on down the list.
pub const TRIAL_BUDGET: usize = 6;
/// Extensions of a cut from its inner end allowed per cut, on average: the loop makes at most
/// `max_cuts × (1 + EXTENSIONS_PER_CUT)` cut steps. An extension lengthens a cut and does not
/// count as a new one.
pub const EXTENSIONS_PER_CUT: usize = 3;
/// When no line from the [`CutOptions::candidates`] highest maxima lowers the error without
/// overlap, the lines from this many times as many maxima are measured before the loop gives up.
pub const WIDER_SEARCH: usize = 4;

/// Options of [`cut_and_flatten`]. `Default` is the only source of defaults. The tolerance is the
/// flattening's ([`FlattenOptions::tolerance`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CutOptions {
    /// Largest number of crest-line cuts; `None` (the default) for [`default_cut_budget`] of the
    /// opened part. `Some(0)` disables cutting (seams are still made).
    pub max_cuts: Option<usize>,
    /// Crest lines traced before each cut, from the highest energy maxima; default
    /// [`DEFAULT_CANDIDATES`].
    pub candidates: usize,
    /// A dart stops where the energy falls below this multiple of the mean energy density (see [`density`]);
    /// default [`DEFAULT_DART_FLOOR`].
    pub dart_floor: f64,
}

/// What the user says about where a part is cut: read from the part's sidecar file (see
/// [`crate::ingest::read_cut_sidecar`]), empty by default.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CutConstraints {
    /// User seams: 3D polylines in model units, cut before anything else.
    #[serde(default)]
    pub seams: Vec<Vec<[f64; 3]>>,
    /// Regions no cut or automatic seam may pass through.
    #[serde(default)]
    pub no_cut_regions: Vec<NoCutRegion>,
}

impl Default for CutOptions {
    fn default() -> Self {
        Self {
            max_cuts: None,
            candidates: DEFAULT_CANDIDATES,
            dart_floor: DEFAULT_DART_FLOOR,
        }
    }
}

/// A ball of the part where nothing may be cut.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoCutRegion {
    /// Centre, model units.
    pub center: [f64; 3],
    /// Radius, model units.
    pub radius: f64,
}

/// Energy and errors of a pattern, before or after a cut.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CutFigures {
    /// Spring energy of the pattern.
    pub energy: f64,
    /// `E_S` (Eq. 4), a fraction.
    pub area_error: f64,
    /// `E_C` (Eq. 6), a fraction.
    pub shape_error: f64,
}

impl CutFigures {
    fn of(flattened: &Flattened) -> Self {
        Self {
            energy: flattened.stats.energy,
            area_error: flattened.stats.accuracy.area_error,
            shape_error: flattened.stats.accuracy.shape_error,
        }
    }
}

/// One crest-line cut.
#[derive(Debug, Clone, PartialEq)]
pub struct Cut {
    /// The cut as a 3D polyline, model units.
    pub points: Vec<DVec3>,
    /// Its 3D length.
    pub length: f64,
    /// The pattern before the cut.
    pub before: CutFigures,
    /// The pattern after the cut.
    pub after: CutFigures,
}

/// One seam.
#[derive(Debug, Clone, PartialEq)]
pub struct Seam {
    /// Why it was made.
    pub kind: SeamKind,
    /// The seam as a 3D polyline, model units.
    pub points: Vec<DVec3>,
    /// Its 3D length.
    pub length: f64,
}

/// Why the cutting stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CutStop {
    /// `E_S` and `E_C` are within tolerance (and the pattern does not overlap).
    ToleranceMet,
    /// [`CutOptions::max_cuts`] cuts were made.
    CutBudget,
    /// No candidate cut lowered the error.
    NoBetterCut,
}

/// The cut part and its pattern.
#[derive(Debug, Clone)]
pub struct CutResult {
    /// The facet model after every seam and cut.
    pub model: FacetModel,
    /// Its stiffness factors (carried over from the input's edges).
    pub stiffness: Stiffness,
    /// For each vertex of `model`, the input vertex it copies.
    pub original_vertex: Vec<u32>,
    /// The pattern of `model`.
    pub flattened: Flattened,
    /// Seams, in the order they were cut.
    pub seams: Vec<Seam>,
    /// Crest-line cuts, in the order they were made.
    pub cuts: Vec<Cut>,
    /// Why cutting stopped.
    pub stop: CutStop,
    /// The part as it was before the first crest-line cut, when one was made.
    pub uncut: Option<UncutPattern>,
}

/// A part opened by its seams and flattened, before any crest-line cut: what the energy report
/// shows as "before cutting".
#[derive(Debug, Clone)]
pub struct UncutPattern {
    /// The facet model after its seams.
    pub model: FacetModel,
    /// Its stiffness factors.
    pub stiffness: Stiffness,
    /// Its pattern.
    pub flattened: Flattened,
}

impl CutResult {
    /// Total 3D length of the crest-line cuts.
    pub fn total_cut_length(&self) -> f64 {
        self.cuts.iter().fold(0.0, |total, cut| total + cut.length)
    }
}

/// The fast solver's energy criterion inside the cut loop. The loop ranks candidate cuts by the
/// patterns they give, so each pattern is converged further than a single flattening needs: with
/// the solver's default (1e-4 over its window) the hemisphere sample ended its 8 cuts at
/// 1.46 % / 1.00 %, with 1e-6 at 0.99 % / 0.62 %.
pub const CUT_LOOP_ENERGY_TOLERANCE: f64 = 1e-6;

/// The flatten options of the cut loop: the caller's, converged to at least
/// [`CUT_LOOP_ENERGY_TOLERANCE`].
fn converged_options(options: &FlattenOptions) -> FlattenOptions {
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
    let flatten_options = &loop_options;
    let mut cuts: Vec<Cut> = Vec::new();
    let mut tips: Vec<u32> = Vec::new();
    let mut uncut = None;
    let step_budget = max_cuts * (1 + EXTENSIONS_PER_CUT);
    let mut reporting = false;
    let mut steps = 0;
    let stop = loop {
        if flattened.stats.accuracy.within(flatten_options.tolerance) {
            break CutStop::ToleranceMet;
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
            break if new_cut_allowed {
                CutStop::NoBetterCut
            } else {
                CutStop::CutBudget
            };
        };
        steps += 1;
        progress.advance(steps as u64);
        let line = &improvement.line;
        let points = polyline(&state.model, &line.vertices);
        let tip = line.vertices[line.vertices.len() - 1];
        let after = CutFigures::of(&improvement.flattened);
        match tips.iter().position(|&known| known == line.vertices[0]) {
            Some(extended) => {
                let cut = &mut cuts[extended];
                cut.points.extend_from_slice(&points[1..]);
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
                    length: line.length,
                    before: CutFigures::of(&flattened),
                    after,
                });
                tips.push(tip);
            }
        }
        state = improvement.state;
        flattened = improvement.flattened;
    };
    if reporting {
        progress.finish();
    }
    Ok(CutResult {
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

/// The number of crest-line cuts a part may get when the user sets none: [`CUTS_PER_CAP`] per
/// [`CAP_CURVATURE`] of the total absolute Gaussian curvature `∫|K| dA = Σ |2π − Σθ|` over the
/// interior vertices of the opened part (the curvature its seams did not release), and at least
/// [`DEFAULT_MAX_CUTS`]. A closed UV sphere halved along its bisector holds about `3.5π` (28
/// cuts); a box opened to its net holds none (8).
pub fn default_cut_budget(model: &FacetModel) -> usize {
    let curvature: f64 = seam::angle_deficits(model).iter().map(|d| d.abs()).sum();
    let scaled = (CUTS_PER_CAP * curvature / CAP_CURVATURE).ceil();
    DEFAULT_MAX_CUTS.max(scaled as usize)
}

/// The model being cut, with its stiffness and the way back to the input's vertices.
#[derive(Debug, Clone)]
struct CutState {
    model: FacetModel,
    stiffness: Stiffness,
    original_vertex: Vec<u32>,
}

impl CutState {
    /// The state after cutting along a vertex path, and for each of its vertices the vertex of
    /// `self` it copies.
    fn cut_along(&self, path: &[u32]) -> Result<(CutState, Vec<u32>), CutError> {
        let edges = path_edges(&self.model, path).ok_or_else(|| {
            CutError::InvalidResult("a cut path skips from a vertex to a non-neighbour".into())
        })?;
        self.cut_edges(&edges)
    }

    /// The state after cutting along a set of edges, and for each of its vertices the vertex of
    /// `self` it copies.
    fn cut_edges(&self, edges: &[usize]) -> Result<(CutState, Vec<u32>), CutError> {
        let split = split_along_edges(&self.model, edges)?;
        let factors = split
            .original_edge
            .iter()
            .map(|&e| self.stiffness.factors()[e])
            .collect();
        let original_vertex = split
            .original_vertex
            .iter()
            .map(|&v| self.original_vertex[v as usize])
            .collect();
        let state = CutState {
            model: split.model,
            stiffness: Stiffness::from_factors(factors),
            original_vertex,
        };
        Ok((state, split.original_vertex))
    }

    /// Vertices no cut may pass: the ends of fold-line edges and those in no-cut regions.
    fn blocked(&self, regions: &[NoCutRegion]) -> Vec<bool> {
        let positions = self.model.positions();
        let mut blocked: Vec<bool> = positions
            .iter()
            .map(|&p| {
                regions
                    .iter()
                    .any(|region| p.distance(DVec3::from(region.center)) <= region.radius)
            })
            .collect();
        for (&[a, b], &line) in self.model.edges().iter().zip(self.model.edge_fold_lines()) {
            if line != NONE {
                blocked[a as usize] = true;
                blocked[b as usize] = true;
            }
        }
        blocked
    }
}

/// Cuts the user's seams, in order.
fn lay_user_seams(
    state: &mut CutState,
    constraints: &CutConstraints,
    seams: &mut Vec<Seam>,
) -> Result<(), CutError> {
    for (index, points) in constraints.seams.iter().enumerate() {
        let points: Vec<DVec3> = points.iter().map(|&p| DVec3::from(p)).collect();
        let adjacency = Adjacency::new(&state.model);
        let blocked = state.blocked(&constraints.no_cut_regions);
        let path = seam::lay_polyline(&state.model, &adjacency, &blocked, &points, index)?;
        (*state, _) = state.cut_along(&path).map_err(|error| match error {
            CutError::Disconnects => CutError::SeamNotLaid {
                seam: index,
                from: 0,
                to: points.len() - 1,
            },
            other => other,
        })?;
        seams.push(make_seam(&state.model, SeamKind::User, &path));
    }
    Ok(())
}

/// Opens the part to a disk with automatic seams after `seams` (the user's) and flattens it. A
/// closed surface without handles whose curvature regions have both signs is opened both ways,
/// with seams through the regions of either sign and through the positive ones only
/// ([`cut_graph::RegionSigns`]), and the better pattern is kept ([`is_better`]: an overlapping
/// pattern is worse than any other): on a box with a pocket, the seam around the pocket's rim
/// lets the pocket develop exactly. On a surface with handles the negative curvature is the
/// inside of the handles, which their cut graph already follows: only positive regions are cut
/// (seams through a torus's inside cut thin strips off it).
fn open_and_flatten(
    state: &CutState,
    constraints: &CutConstraints,
    seams: Vec<Seam>,
    flatten_options: &FlattenOptions,
    progress: &dyn Progress,
) -> Result<(CutState, Vec<Seam>, Flattened), CutError> {
    let variants: &[RegionSigns] = if state.model.is_closed() && seam::genus(&state.model) == 0 {
        &[RegionSigns::Both, RegionSigns::Positive]
    } else {
        &[RegionSigns::Positive]
    };
    let mut best: Option<(CutState, Vec<Seam>, Flattened)> = None;
    for &signs in variants {
        let mut opened = state.clone();
        let mut opened_seams = seams.clone();
        open_to_disk(&mut opened, constraints, &mut opened_seams, signs)?;
        if best
            .as_ref()
            .is_some_and(|(_, known, _)| *known == opened_seams)
        {
            continue;
        }
        let flattened = flatten(&opened.model, &opened.stiffness, flatten_options, progress)?;
        if best
            .as_ref()
            .is_none_or(|(_, _, known)| is_better(&flattened.stats.accuracy, &known.stats.accuracy))
        {
            best = Some((opened, opened_seams, flattened));
        }
    }
    best.ok_or(CutError::NoSeam)
}

/// Cuts automatic seams until the model is a disk; `signs` says which curvature regions the
/// seams of a closed surface run through.
fn open_to_disk(
    state: &mut CutState,
    constraints: &CutConstraints,
    seams: &mut Vec<Seam>,
    signs: RegionSigns,
) -> Result<(), CutError> {
    let was_closed = state.model.is_closed();
    if was_closed && seam::genus(&state.model) > 0 {
        let graph = cut_graph::tree_cotree_cut_graph(&state.model, &Adjacency::new(&state.model));
        (*state, _) = state.cut_edges(&graph.edges)?;
        for chain in &graph.chains {
            seams.push(make_seam(&state.model, SeamKind::Handle, chain));
        }
    }
    if was_closed {
        let blocked = state.blocked(&constraints.no_cut_regions);
        let adjacency = Adjacency::new(&state.model);
        let graph = cut_graph::curvature_cut_graph(&state.model, &adjacency, &blocked, signs)
            .map(|graph| (SeamKind::Curvature, graph))
            .or_else(|| {
                cut_graph::bisector_cut_graph(&state.model, &adjacency, &blocked)
                    .map(|graph| (SeamKind::Bisector, graph))
            });
        if let Some((kind, graph)) = graph {
            (*state, _) = state.cut_edges(&graph.edges)?;
            for chain in &graph.chains {
                seams.push(make_seam(&state.model, kind, chain));
            }
        }
    }
    // Every seam removes a boundary loop, a handle or a corner, so this bounds the count.
    for _ in 0..=state.model.vertex_count() {
        let adjacency = Adjacency::new(&state.model);
        let blocked = state.blocked(&constraints.no_cut_regions);
        let Some((kind, path)) = seam::next_seam(&state.model, &adjacency, &blocked, was_closed)?
        else {
            return Ok(());
        };
        (*state, _) = state.cut_along(&path)?;
        seams.push(make_seam(&state.model, kind, &path));
    }
    Err(CutError::NoSeam)
}

fn make_seam(model: &FacetModel, kind: SeamKind, path: &[u32]) -> Seam {
    Seam {
        kind,
        points: polyline(model, path),
        length: path_length(model, path),
    }
}

/// 3D positions of a vertex path (copies keep their original's position, so the path's indices
/// are valid in the cut model too).
fn polyline(model: &FacetModel, path: &[u32]) -> Vec<DVec3> {
    path.iter()
        .map(|&v| model.positions()[v as usize])
        .collect()
}

/// A cut that lowered the error.
struct Improvement {
    state: CutState,
    flattened: Flattened,
    line: CrestLine,
}

/// Where the next cut step may go: it may start at the inner end of an existing cut (an
/// extension), elsewhere only while new cuts are allowed, and never pass a blocked vertex.
struct Starts<'a> {
    tips: &'a [u32],
    new_cut_allowed: bool,
    blocked: &'a [bool],
}

/// A candidate cut, made and flattened.
struct Trial {
    improvement: Improvement,
    /// Its gain: [`f64::MAX`]` / L` when it meets the tolerance, else `ΔE / L^LENGTH_EXPONENT`.
    gain: f64,
}

/// [`best_cut`], and when it finds no cut, [`best_cut`] again with lines from
/// [`WIDER_SEARCH`] times as many maxima.
fn best_cut_widening(
    state: &CutState,
    flattened: &Flattened,
    flatten_options: &FlattenOptions,
    options: &CutOptions,
    starts: &Starts<'_>,
) -> Result<Option<Improvement>, CutError> {
    if let Some(improvement) = best_cut(state, flattened, flatten_options, options, starts)? {
        return Ok(Some(improvement));
    }
    let wider = CutOptions {
        candidates: options.candidates * WIDER_SEARCH,
        ..options.clone()
    };
    best_cut(state, flattened, flatten_options, &wider, starts)
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
) -> Result<Option<Improvement>, CutError> {
    let lines = candidate_lines(state, flattened, flatten_options, options, starts);
    let screen_options = with_fast(flatten_options, |fast| FastOptions {
        max_iterations: fast.max_iterations.min(SCREEN_ITERATIONS),
        step_tolerance: fast.step_tolerance.max(TRIAL_STEP_TOLERANCE),
        ..fast
    });
    let screened: Vec<Option<Trial>> = lines
        .into_par_iter()
        .map(|line| screen(state, flattened, line, &screen_options))
        .collect::<Result<_, _>>()?;
    let mut screened: Vec<Trial> = screened.into_iter().flatten().collect();
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
    let mut best: Option<Trial> = None;
    let mut accepted = 0;
    for (tried, trial) in screened.into_iter().enumerate() {
        if accepted == FULL_TRIALS || (tried >= TRIAL_BUDGET && accepted > 0) {
            break;
        }
        let Some(trial) = flatten_on(trial, flattened, &trial_options)? else {
            continue;
        };
        accepted += 1;
        if best.as_ref().is_none_or(|known| trial.gain > known.gain) {
            best = Some(trial);
        }
    }
    let Some(Trial {
        mut improvement, ..
    }) = best
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

/// The crest lines of the current pattern a cut step may take: those of the energy map (Eq. 1)
/// and those of the tension map (stretched springs only, where a cut opens; on a saddle the
/// energy peaks where the pattern is compressed and a cut there would overlap), both as planning
/// maps ([`density`]: energy per unit area smoothed over a length tied to the part's size, so
/// the lines do not depend on the mesh); without repeats, an extension of an earlier cut or a
/// new cut only while new cuts are allowed.
fn candidate_lines(
    state: &CutState,
    flattened: &Flattened,
    flatten_options: &FlattenOptions,
    options: &CutOptions,
    starts: &Starts<'_>,
) -> Vec<CrestLine> {
    let springs = SpringSystem::new(
        &state.model,
        state.stiffness.factors(),
        flatten_options.spring_constant,
    );
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

/// Cuts along `line` and flattens with `screen_options`; `None` if the line cannot be cut (it
/// would cut a piece off, open nothing, or run along the boundary or a fold line) or the cut
/// does not lower the error.
fn screen(
    state: &CutState,
    flattened: &Flattened,
    line: CrestLine,
    screen_options: &FlattenOptions,
) -> Result<Option<Trial>, CutError> {
    let (next, copied_vertex) = match state.cut_along(&line.vertices) {
        Ok(cut) => cut,
        Err(
            CutError::Disconnects
            | CutError::OpensNothing
            | CutError::BoundaryEdge { .. }
            | CutError::FoldLine { .. },
        ) => return Ok(None),
        Err(other) => return Err(other),
    };
    let candidate = reflatten(&next, &copied_vertex, flattened, screen_options)?;
    let improvement = Improvement {
        state: next,
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
/// pattern `before`.
fn judge(
    improvement: Improvement,
    before: &Flattened,
    tolerance: f64,
    overlap: Overlap,
) -> Option<Trial> {
    let after = &improvement.flattened.stats;
    let lower = match overlap {
        Overlap::Refused => pays(&after.accuracy, &before.stats.accuracy, tolerance),
        Overlap::Ignored => error(&after.accuracy) < error(&before.stats.accuracy),
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

/// The pattern of a cut model, warm-started from the pattern before the cut (each copy starts
/// where its original was). When the warm start cannot move (the solver's orientation guard
/// blocks it), a cold flattening is tried too and the better pattern kept.
fn reflatten(
    next: &CutState,
    copied_vertex: &[u32],
    before: &Flattened,
    flatten_options: &FlattenOptions,
) -> Result<Flattened, CutError> {
    let start: Vec<DVec2> = copied_vertex
        .iter()
        .map(|&v| before.positions[v as usize])
        .collect();
    let warm = flatten_from(&next.model, &next.stiffness, &start, flatten_options)?;
    if warm.stats.stop_reason != StopReason::OrientationBlocked {
        return Ok(warm);
    }
    let cold = flatten(&next.model, &next.stiffness, flatten_options, &NoProgress)?;
    Ok(if is_better(&cold.stats.accuracy, &warm.stats.accuracy) {
        cold
    } else {
        warm
    })
}

/// The larger of `E_S` and `E_C`.
fn error(a: &Accuracy) -> f64 {
    a.area_error.max(a.shape_error)
}

/// True if a cut that takes the pattern from `before` to `after` is worth making: `after` is the
/// better pattern ([`is_better`]), except that a cut leaving an overlapping pattern overlapping
/// with as many flipped triangles does not pay once `E_S` and `E_C` are within `tolerance`: the
/// overlap alone keeps the part out, and such a cut only adds length (the FreeCAD box's pocket
/// wall lies over its top face however it is cut: 8 cuts, 665 mm and 100 s spent in vain).
fn pays(after: &Accuracy, before: &Accuracy, tolerance: f64) -> bool {
    let overlap_kept = after.overlap && before.overlap && after.flipped == before.flipped;
    if overlap_kept && error(before) <= tolerance {
        return false;
    }
    is_better(after, before)
}

/// True if `candidate` is a better pattern than `current`: it does not overlap while `current`
/// does; or both overlap and it has fewer flipped triangles (on an opened torus the cuts then
/// go where they unflip the pattern: 0 flipped instead of 3 after eight cuts); or its larger
/// error is lower.
fn is_better(candidate: &Accuracy, current: &Accuracy) -> bool {
    match (candidate.overlap, current.overlap) {
        (false, true) => true,
        (true, false) => false,
        (true, true) if candidate.flipped != current.flipped => candidate.flipped < current.flipped,
        _ => error(candidate) < error(current),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
