//! Flattening one loaded part: seams, crest-line cuts and re-flattening until it is within
//! tolerance (or, when it does not come within it whole, cut into pieces that each are), the
//! pattern turned to its grain, and the part's pattern made from it. A
//! sheet-metal part, unfolded exactly when it was loaded, only gets its pattern made.

use std::f64::consts::PI;

use crate::cut::{
    CAP_CURVATURE, CUTS_PER_CAP, CutConstraints, CutError, CutResult, CutStop, PIECES_CURVATURE,
    cut_and_flatten, cut_into_pieces, total_absolute_curvature,
};
use crate::error::Error;
use crate::flatten::orient::orient;
use crate::flatten::{Accuracy, FlattenOptions, FlattenStats, Flattened, SpringSystem, StopReason};
use crate::mesh::SeamSource;
use crate::pattern::{FlatShape, PatternSource, part_pattern};
use crate::progress::Progress;

use super::config::RunOptions;
use super::load::{PartJob, SheetPart};
use super::part_result::PartResult;
use super::rejection::rejection_reasons;

/// Flattens one loaded part into its results: one ([`flatten_part`]), or one per piece
/// ([`flatten_in_pieces`]) with `--seams pieces`, or with `--seams auto` when the part does not
/// come within tolerance whole ([`flatten_or_cut_into_pieces`]).
pub fn flatten_job(
    job: PartJob,
    options: &RunOptions,
    progress: &dyn Progress,
) -> Result<Vec<PartResult>, Error> {
    match options.seams {
        _ if job.sheet.is_some() => Ok(vec![flatten_part(job, options, progress)?]),
        SeamSource::Pieces => flatten_in_pieces(job, options, progress),
        SeamSource::Auto if job.constraints == CutConstraints::default() => {
            flatten_or_cut_into_pieces(job, options, progress)
        }
        SeamSource::Auto | SeamSource::Whole | SeamSource::FromUv => {
            Ok(vec![flatten_part(job, options, progress)?])
        }
    }
}

/// Flattens one part whole, with seams and crest-line cuts until it is within tolerance or the
/// cut budget is spent, and makes its pattern (whatever `options.seams` says: see
/// [`flatten_job`]).
pub fn flatten_part(
    job: PartJob,
    options: &RunOptions,
    progress: &dyn Progress,
) -> Result<PartResult, Error> {
    if let Some(sheet) = job.sheet.clone() {
        return Ok(unfolded_part(job, &sheet, options));
    }
    let started = std::time::Instant::now();
    let result = cut_and_flatten(
        &job.model,
        &job.stiffness,
        &job.constraints,
        &options.part_flatten_options(),
        &options.cut,
        progress,
    )
    .map_err(|reason| cut_error(&job, reason))?;
    Ok(part_result(job, result, started, options))
}

/// Cuts one part into pieces, each within tolerance ([`cut_into_pieces`]), and makes each
/// piece's pattern: one result per piece, named `<part>-p<k>`. A part with a cut sidecar is
/// refused (its seams and no-cut regions would not be kept).
pub fn flatten_in_pieces(
    job: PartJob,
    options: &RunOptions,
    progress: &dyn Progress,
) -> Result<Vec<PartResult>, Error> {
    if job.constraints != CutConstraints::default() {
        return Err(cut_error(&job, CutError::PiecesWithSidecar));
    }
    let started = std::time::Instant::now();
    let flatten_options = options.part_flatten_options();
    piece_results(job, &flatten_options, started, options, progress, |count| {
        format!("cut into {count} pieces (--seams pieces)")
    })
}

/// Flattens one part whole, as [`flatten_part`]; when it is still rejected after its cuts with
/// time left (or it has handles, which automatic seams do not cut), cuts it into pieces instead,
/// as [`flatten_in_pieces`], each piece saying why in a warning. With the default cut budget, a
/// part of more than [`PIECES_CURVATURE`] goes to pieces without trying cuts, and so does a
/// closed one: opened by its seams, its root piece is its net when that is within tolerance (a
/// box, a can), and otherwise it is cut into pieces, as a sphere is cut into gores (crest-line
/// cuts took 100-250 s on the shipped sphere, spheroid and vase for no cut kept). The pieces
/// share the part's time limit.
pub fn flatten_or_cut_into_pieces(
    job: PartJob,
    options: &RunOptions,
    progress: &dyn Progress,
) -> Result<Vec<PartResult>, Error> {
    let started = std::time::Instant::now();
    let flatten_options = options.part_flatten_options();
    let curvature = total_absolute_curvature(&job.model);
    let default_budget = options.cut.max_cuts.is_none();
    let why = if default_budget && job.model.is_closed() {
        "closed, it does not lie flat within tolerance opened by its seams".to_string()
    } else if default_budget && curvature > PIECES_CURVATURE {
        format!(
            "its total absolute curvature, {:.1} π, would take over {:.0} crest-line cuts",
            curvature / PI,
            CUTS_PER_CAP * PIECES_CURVATURE / CAP_CURVATURE
        )
    } else {
        let whole = cut_and_flatten(
            &job.model,
            &job.stiffness,
            &job.constraints,
            &flatten_options,
            &options.cut,
            progress,
        );
        match whole {
            Ok(result) => match whole_part_shortfall(&result, &flatten_options) {
                Some(why) => why,
                None => return Ok(vec![part_result(job, result, started, options)]),
            },
            Err(CutError::HigherGenus { genus }) => {
                format!("it has genus {genus}, which automatic seams do not open")
            }
            Err(reason) => return Err(cut_error(&job, reason)),
        }
    };
    piece_results(job, &flatten_options, started, options, progress, |count| {
        format!("cut into {count} pieces (--seams auto): whole, {why}")
    })
}

/// Why a part's whole pattern calls for pieces, or `None` when it does not: it is not rejected,
/// or it ran out of time (the pieces would have none left).
fn whole_part_shortfall(result: &CutResult, options: &FlattenOptions) -> Option<String> {
    let reasons = rejection_reasons(&result.flattened.stats.accuracy, options.tolerance);
    let out_of_time = result.stop == CutStop::TimeLimit || options.deadline.passed();
    (!reasons.is_empty() && !out_of_time).then(|| {
        format!(
            "after {} crest-line cut(s), it was rejected: {}",
            result.cuts.len(),
            reasons.join(", ")
        )
    })
}

/// The results of the part's pieces ([`cut_into_pieces`]), timed from `started`: one per piece,
/// each with the warning `why` makes of the count, or the part itself when it is one piece.
fn piece_results(
    job: PartJob,
    flatten_options: &FlattenOptions,
    started: std::time::Instant,
    options: &RunOptions,
    progress: &dyn Progress,
    why: impl Fn(usize) -> String,
) -> Result<Vec<PartResult>, Error> {
    let mut pieces = cut_into_pieces(&job.model, &job.stiffness, flatten_options, progress)
        .map_err(|reason| cut_error(&job, reason))?;
    if pieces.len() == 1 {
        let whole = pieces.remove(0);
        return Ok(vec![part_result(job, whole, started, options)]);
    }
    let count = pieces.len();
    let warning = why(count);
    Ok(pieces
        .into_iter()
        .enumerate()
        .map(|(k, piece)| {
            let piece_job = piece_job(&job, k, count, &warning, &piece);
            part_result(piece_job, piece, started, options)
        })
        .collect())
}

/// The error of a part the cut stage failed on.
fn cut_error(job: &PartJob, reason: CutError) -> Error {
    Error::Cut {
        path: job.source.clone(),
        part: job.name.clone(),
        reason,
    }
}

/// The job of piece `k` of `count` of the part: the part's, but for its name and model, with
/// the part's `warning` on why it is in pieces.
fn piece_job(job: &PartJob, k: usize, count: usize, warning: &str, piece: &CutResult) -> PartJob {
    let mut warnings = job.warnings.clone();
    warnings.push(warning.to_string());
    warnings.push(format!("piece {} of {count} of {}", k + 1, job.name));
    PartJob {
        name: format!("{}-p{}", job.name, k + 1),
        source: job.source.clone(),
        units: job.units,
        quantity: job.quantity,
        attributes: job.attributes.clone(),
        fold_line_count: job.fold_line_count,
        tessellation: job.tessellation,
        model: piece.model.clone(),
        stiffness: piece.stiffness.clone(),
        constraints: CutConstraints::default(),
        warnings,
        sheet: None,
    }
}

/// The part's result from its cut model and pattern: the pattern turned to the grain, its time
/// the whole part's so far, its drawing made.
fn part_result(
    mut job: PartJob,
    mut result: CutResult,
    started: std::time::Instant,
    options: &RunOptions,
) -> PartResult {
    let grain = job.attributes.grain;
    orient(&result.model, &mut result.flattened, grain);
    if let Some(uncut) = &mut result.uncut {
        orient(&uncut.model, &mut uncut.flattened, grain);
    }
    // The part's time is the whole of it: seams, every cut tried and every flattening.
    result.flattened.stats.seconds = started.elapsed().as_secs_f64();
    let pattern = part_pattern(&PatternSource {
        name: &job.name,
        units: job.units,
        quantity: job.quantity,
        material: job.attributes.material.as_deref(),
        grain,
        flat: FlatShape {
            model: &result.model,
            stiffness: &result.stiffness,
            positions: &result.flattened.positions,
        },
        uncut: result.uncut.as_ref().map(|uncut| FlatShape {
            model: &uncut.model,
            stiffness: &uncut.stiffness,
            positions: &uncut.flattened.positions,
        }),
        cut_edges: &result.cut_edges,
        spring_constant: options.flatten.spring_constant,
    });
    job.model = result.model;
    job.stiffness = result.stiffness;
    PartResult {
        job,
        flattened: result.flattened,
        seams: result.seams,
        cuts: result.cuts,
        cut_stop: result.stop,
        uncut: result.uncut,
        original_vertex: result.original_vertex,
        cut_edges: result.cut_edges,
        pattern,
    }
}

/// The result of a sheet-metal part: its exact unfold as the pattern (no seam, no cut), its
/// figures measured against the skin (the bends differ from it by their allowance, by design),
/// and its bend lines on the drawing.
fn unfolded_part(job: PartJob, sheet: &SheetPart, options: &RunOptions) -> PartResult {
    let started = std::time::Instant::now();
    let positions = sheet.flat.clone();
    let accuracy = Accuracy::measure(&job.model, &positions);
    let springs = SpringSystem::new(
        &job.model,
        job.stiffness.factors(),
        options.flatten.spring_constant,
    );
    let mut pattern = part_pattern(&PatternSource {
        name: &job.name,
        units: job.units,
        quantity: job.quantity,
        material: job.attributes.material.as_deref(),
        grain: None,
        flat: FlatShape {
            model: &job.model,
            stiffness: &job.stiffness,
            positions: &positions,
        },
        uncut: None,
        cut_edges: &[],
        spring_constant: options.flatten.spring_constant,
    });
    pattern.drawing.bends = sheet.bends.clone();
    // A part file's folds are its bends: drawn once, as bend lines.
    pattern.drawing.fold_lines.clear();
    let stats = FlattenStats {
        accuracy,
        initial_accuracy: accuracy,
        energy: springs.energy(&positions),
        iterations: 0,
        stop_reason: StopReason::ExactUnfold,
        seconds: started.elapsed().as_secs_f64(),
    };
    PartResult {
        original_vertex: (0..job.model.vertex_count() as u32).collect(),
        job,
        flattened: Flattened { positions, stats },
        seams: Vec::new(),
        cuts: Vec::new(),
        cut_stop: CutStop::ToleranceMet,
        uncut: None,
        cut_edges: Vec::new(),
        pattern,
    }
}
