//! The pipeline owns the whole run: [`run`] takes a [`RunConfig`] from the inputs to the parts,
//! their patterns and the nested layout (checked independently), and [`write_outputs`] writes the
//! output folder through [`crate::export`]. The stages one part goes through are also callable
//! on their own: [`load_parts`] reads an input into parts (ingest, tessellate, validate,
//! stiffness) and [`flatten_job`] flattens, cuts and makes the pattern of one (or of each of its
//! pieces: [`flatten_in_pieces`] with `--seams pieces`, [`flatten_or_cut_into_pieces`] by
//! default when the part does not come within tolerance whole). The fan-in,
//! [`nest_patterns`] (and [`nest_patterns_into`] an output folder), nests the pattern files runs
//! wrote, grouped by material and thickness, without flattening again.

mod benchmark;
mod config;
mod facet_model;
mod flatten_part;
mod load;
mod output_folder;
mod outputs;
mod part_result;
mod pattern_nest;
mod rejection;
mod report;
mod run;
mod step_defects;

pub use benchmark::{BenchmarkConfig, BenchmarkOutput, nest_benchmark, write_benchmark};
pub use config::{
    DEFAULT_PART_TIME_LIMIT, DEFAULT_RUN_GAP, DEFAULT_RUN_ROTATIONS, DEFAULT_RUN_TIME_LIMIT,
    MAXIMUM_PART_TIME_LIMIT, MAXIMUM_TOLERANCE, NestingConfig, PartOverrides, RunConfig,
    RunOptions,
};
pub use facet_model::{FacetModelOutput, FacetSource, facet_model, write_facet_model};
pub use flatten_part::{flatten_in_pieces, flatten_job, flatten_or_cut_into_pieces, flatten_part};
pub use load::{
    PartJob, SMALL_MESH_MM, SheetPart, TessellationFigures, load_parts, tessellate_part,
    tessellate_step,
};
pub use output_folder::{
    InterruptHandle, MANIFEST_FILE, OutputFolder, check_inputs_outside, complete_run_present,
    remove_previous_run,
};
pub use outputs::{run_into, write_outputs};
pub use part_result::PartResult;
pub use pattern_nest::{
    NestInputKind, NestedGroup, PatternNestConfig, PatternNestOutput, SourcedPattern,
    group_folder_name, nest_input_kind, nest_loaded, nest_patterns, nest_patterns_into,
    pattern_files, read_pattern_file, read_patterns, write_pattern_nest,
};
pub use rejection::rejection_reasons;
pub use report::{nesting_report, part_report, report_options};
pub use run::{
    NestedLayout, PAPER_SOLVER_ADVISED_TRIANGLES, RunOutput, load_all, nest_checked, run,
    run_loaded,
};
