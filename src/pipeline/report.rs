//! The report's values made from a run: every option of the run, and one entry per part.

use crate::export::report::{
    CutReport, FoldLineReport, NestingReport, PartReport, ReportOptions, SeamReport,
    TessellationReport,
};
use crate::flatten::fold_lines::fold_line_lengths;

use crate::nest::Stock;

use super::config::{NestingConfig, RunConfig};
use super::part_result::PartResult;

/// The options the report records.
pub fn report_options(config: &RunConfig) -> ReportOptions {
    let options = &config.options;
    ReportOptions {
        units: options.units,
        flatten: options.flatten.clone(),
        cut: options.cut.clone(),
        tessellate: options.tessellate,
        pattern: config.pattern,
        dxf_version: config.dxf_version,
        energy_png: config.energy_png,
        nesting: config
            .stock
            .map(|stock| nesting_report(stock, &config.nesting)),
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
        tolerance_met: accuracy.within(flatten.tolerance),
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
        rejected: super::rejection::rejection_reasons(&accuracy, flatten.tolerance),
    }
}
