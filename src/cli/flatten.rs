//! `flatcut flatten INPUT -o OUT/` and `flatcut run INPUT... -o OUT/`: flatten parts and write
//! their patterns, facet models and the report.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;

use flatcut::export::obj::{mesh_obj, pattern_obj};
use flatcut::export::report::{PartReport, Report};
use flatcut::export::write_atomically;
use flatcut::flatten::{FlattenOptions, Solver};
use flatcut::pipeline::{PartResult, RunOptions, flatten_part, load_parts};
use flatcut::progress::Progress;
use flatcut::units::Units;

use super::Outcome;

/// Arguments shared by `flatten` and `run`.
#[derive(Debug, Args)]
pub struct FlattenArgs {
    /// Input parts: part files (.toml), STEP files (.step, .stp), triangle meshes (.obj, .stl).
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Output directory (created if missing).
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// Permissible area and shape error E_S, E_C (fractions: 0.01 is 1 %).
    #[arg(long, default_value_t = FlattenOptions::default().tolerance)]
    tolerance: f64,
    /// Solver: `fast` minimises the paper's energy quickly; `paper` follows the paper step by step.
    #[arg(long, value_enum, default_value_t = Solver::default())]
    solver: Solver,
    /// Step budget of the energy release (phase two).
    #[arg(long, default_value_t = FlattenOptions::default().max_steps)]
    max_steps: usize,
    /// Units of mesh coordinates.
    #[arg(long, value_enum, default_value_t = Units::default())]
    units: Units,
    #[command(flatten)]
    sizes: super::tessellate::MeshSizeArgs,
    /// Print the report to stdout as JSON.
    #[arg(long)]
    json: bool,
    /// Write 0 for every `seconds` in the report, so reports of the same input are byte-identical.
    #[arg(long)]
    no_timings: bool,
}

impl FlattenArgs {
    /// The library options, converted in one place.
    fn run_options(&self) -> anyhow::Result<RunOptions> {
        anyhow::ensure!(
            self.tolerance.is_finite() && self.tolerance > 0.0,
            "--tolerance must be a positive fraction (0.01 is 1 %), got {}",
            self.tolerance
        );
        let flatten = FlattenOptions {
            solver: self.solver,
            tolerance: self.tolerance,
            max_steps: self.max_steps,
            ..FlattenOptions::default()
        };
        Ok(RunOptions {
            units: self.units,
            flatten,
            tessellate: self.sizes.options()?,
        })
    }
}

/// Runs `flatten` or `run`: every input is read and checked before anything is written.
pub fn run(args: FlattenArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    let options = args.run_options()?;
    let mut jobs = Vec::new();
    for input in &args.inputs {
        jobs.extend(load_parts(input, &options)?);
    }
    for job in &jobs {
        for warning in &job.warnings {
            eprintln!("flatcut: warning: {}: {warning}", job.source.display());
        }
    }
    let results = jobs
        .into_iter()
        .map(|job| flatten_part(job, &options, progress))
        .collect::<Result<Vec<PartResult>, _>>()?;
    std::fs::create_dir_all(&args.output).with_context(|| {
        format!(
            "{}: cannot create the output directory",
            args.output.display()
        )
    })?;
    for result in &results {
        write_part_files(&args.output, result)?;
    }
    let parts: Vec<PartReport> = results
        .iter()
        .map(|r| PartReport::new(r, &options, !args.no_timings))
        .collect();
    let all_met = parts.iter().all(|p| p.tolerance_met);
    for part in &parts {
        eprintln!(
            "flatcut: {}: E_S {:.4} %, E_C {:.4} %, {} flipped, {}",
            part.name,
            part.area_error * 100.0,
            part.shape_error * 100.0,
            part.flipped,
            if part.tolerance_met {
                "within tolerance"
            } else {
                "OVER TOLERANCE"
            }
        );
    }
    let report = Report::new(options, parts).to_json();
    let report_path = args.output.join("report.json");
    write_atomically(&report_path, report.as_bytes())
        .with_context(|| format!("{}: cannot write", report_path.display()))?;
    if args.json {
        print!("{report}");
    }
    Ok(if all_met {
        Outcome::Success
    } else {
        Outcome::OverTolerance
    })
}

fn write_part_files(directory: &Path, result: &PartResult) -> anyhow::Result<()> {
    let job = &result.job;
    let header = format!(
        "flatcut {} part '{}' from {}",
        env!("CARGO_PKG_VERSION"),
        job.name,
        job.source.display()
    );
    let files = [
        (
            "mesh.obj",
            mesh_obj(
                &format!("{header}\n3D facet model"),
                job.model.positions(),
                job.model.triangles(),
            ),
        ),
        (
            "pattern.obj",
            pattern_obj(
                &format!("{header}\nflat pattern (z = 0)"),
                &result.flattened.positions,
                job.model.triangles(),
            ),
        ),
    ];
    for (suffix, text) in files {
        let path = directory.join(format!("{}.{suffix}", job.name));
        write_atomically(&path, text.as_bytes())
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    Ok(())
}
