//! The report's values made from a run: every option of the run, and one entry per part.

use glam::DVec2;

use crate::export::report::{
    BendReport, CutReport, FoldLineReport, NestingReport, PartReport, ReportOptions, SeamReport,
    SheetMetalReport, TessellationReport,
};
use crate::flatten::fold_lines::fold_line_lengths;
use crate::geometry::signed_area;

use crate::nest::Stock;

use super::config::{DEFAULT_PART_TIME_LIMIT, NestingConfig, RunConfig};
use super::part_result::PartResult;

/// The options the report records.
pub fn report_options(config: &RunConfig) -> ReportOptions {
    let options = &config.options;
    ReportOptions {
        units: options.units,
        seams: options.seams,
        repair: options.repair,
        flatten: options.flatten.clone(),
        cut: options.cut.clone(),
        tessellate: options.tessellate,
        pattern: config.pattern,
        dxf_version: config.dxf_version,
        energy_png: config.energy_png,
        nesting: config
            .stock
            .map(|stock| nesting_report(stock, &config.nesting)),
        part_time_limit_seconds: Some(options.time_limit_seconds)
            .filter(|&seconds| seconds != DEFAULT_PART_TIME_LIMIT),
    }
}

/// The nesting options a report records: `nesting` on `stock`.
pub fn nesting_report(stock: Stock, nesting: &NestingConfig) -> NestingReport {
    NestingReport {
        stock,
        gap: nesting.gap,
        time_limit_seconds: nesting.time_limit.as_secs_f64(),
        seed: nesting.seed,
        work_limit: nesting.work_limit,
        rotations: nesting.rotations.clone(),
        in_holes: nesting.in_holes,
        mirror: nesting.mirror,
    }
}

/// The report of a flattened part; `config.timings` false writes 0 seconds.
pub fn part_report(result: &PartResult, config: &RunConfig) -> PartReport {
    let (job, stats) = (&result.job, &result.flattened.stats);
    let flatten = &config.options.flatten;
    let accuracy = stats.accuracy;
    PartReport {
        name: job.name.clone(),
        source: job.source.display().to_string(),
        units: job.units.symbol(),
        quantity: job.quantity,
        triangles: job.model.triangle_count(),
        vertices: job.model.vertex_count(),
        area_error: accuracy.area_error,
        shape_error: accuracy.shape_error,
        max_strain: accuracy.max_strain,
        flipped: accuracy.flipped,
        overlap: accuracy.overlap,
        iterations: stats.iterations,
        stop_reason: stats.stop_reason,
        tolerance: flatten.tolerance,
        tolerance_met: result.tolerance_met(flatten.tolerance),
        seconds: if config.timings { stats.seconds } else { 0.0 },
        solver: flatten.solver,
        energy: stats.energy,
        initial_area_error: stats.initial_accuracy.area_error,
        initial_shape_error: stats.initial_accuracy.shape_error,
        cuts: result.cuts.iter().map(CutReport::new).collect(),
        total_cut_length: result
            .cuts
            .iter()
            .fold(0.0, |total, cut| total + cut.length),
        cut_stop: result.cut_stop,
        seams: result.seams.iter().map(SeamReport::new).collect(),
        fold_lines: fold_line_lengths(&job.model, &result.flattened.positions, job.fold_line_count)
            .into_iter()
            .map(|fold| FoldLineReport {
                length_3d: fold.length_3d,
                length_flat: fold.length_flat,
                error: fold.error,
            })
            .collect(),
        tessellation: job.tessellation.map(|figures| TessellationReport {
            mesh_size: figures.mesh_size,
            chord: figures.chord,
            minimum_angle: figures.minimum_angle,
        }),
        warnings: job.warnings.clone(),
        rejected: result.rejection_reasons(flatten.tolerance, &config.pattern),
        sheet_metal: sheet_metal_report(result),
    }
}

/// The sheet-metal figures of a part unfolded as sheet metal: its bends and its flat size from
/// the drawing's contours.
fn sheet_metal_report(result: &PartResult) -> Option<SheetMetalReport> {
    let sheet = result.job.sheet.as_ref()?;
    let drawing = &result.pattern.drawing;
    let (low, high) = drawing
        .outer
        .iter()
        .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(low, high), &p| {
            (low.min(p), high.max(p))
        });
    let holes: f64 = drawing
        .holes
        .iter()
        .map(|hole| signed_area(hole).abs())
        .sum();
    Some(SheetMetalReport {
        thickness: sheet.thickness,
        k_factor: sheet.k_factor,
        bend_rule: sheet.rule.clone(),
        base_face: sheet.base_face.clone(),
        bends: drawing.bends.iter().map(BendReport::new).collect(),
        flat_width: high.x - low.x,
        flat_height: high.y - low.y,
        flat_area: signed_area(&drawing.outer).abs() - holes,
    })
}
