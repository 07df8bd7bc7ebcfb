//! `flatcut flatten INPUT -o OUT/` and `flatcut run INPUT... -o OUT/`: flatten parts and write
//! their patterns, facet models and the report.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;

use flatcut::export::energy_png::{
    EnergyMap, EnergyPngOptions, NEGLIGIBLE_STRAIN, PatternFigures, negligible_vertex_energy,
    render_energy_png,
};
use flatcut::export::fold_polylines::fold_polylines;
use flatcut::export::obj::{mesh_obj, pattern_obj};
use flatcut::export::report::{PartReport, Report};
use flatcut::export::write_atomically;
use flatcut::flatten::{FlattenOptions, Solver, SpringSystem};
use flatcut::pipeline::{PartResult, RunOptions, flatten_part, load_parts};
use flatcut::progress::Progress;
use flatcut::units::Units;

use super::Outcome;

/// Above this many triangles `--solver paper` warns that it will be slow (its phase one is
/// quadratic: about 10 s at 5,000 triangles on a 2-core machine).
const PAPER_SOLVER_ADVISED_TRIANGLES: usize = 5_000;

/// Arguments shared by `flatten` and `run`.
#[derive(Debug, Args)]
pub struct FlattenArgs {
    /// Input parts: triangle meshes (.obj, .stl).
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
        if options.flatten.solver == Solver::Paper
            && job.model.triangle_count() > PAPER_SOLVER_ADVISED_TRIANGLES
        {
            eprintln!(
                "flatcut: warning: {}: {} triangles: the paper's solver is quadratic and will be slow; \
                 the default solver minimises the same energy",
                job.name,
                job.model.triangle_count()
            );
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
        write_part_files(&args.output, result, &options)?;
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

fn write_part_files(
    directory: &Path,
    result: &PartResult,
    options: &RunOptions,
) -> anyhow::Result<()> {
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
    let png = energy_png(result, options)
        .with_context(|| format!("part '{}': cannot draw the energy map", job.name))?;
    let path = directory.join(format!("{}.energy.png", job.name));
    write_atomically(&path, &png).with_context(|| format!("{}: cannot write", path.display()))?;
    Ok(())
}

/// The energy picture of a flattened part: per-vertex energy (Eq. 1) of the final pattern.
fn energy_png(result: &PartResult, options: &RunOptions) -> anyhow::Result<Vec<u8>> {
    let (job, flattened) = (&result.job, &result.flattened);
    let constant = options.flatten.spring_constant;
    let springs = SpringSystem::new(&job.model, job.stiffness.factors(), constant);
    let energies = springs.vertex_energies(&flattened.positions);
    let accuracy = flattened.stats.accuracy;
    let map = EnergyMap {
        name: job.name.clone(),
        energy_units: format!("{}², C = {constant}", job.units.symbol()),
        length_units: job.units.symbol().to_string(),
        positions: &flattened.positions,
        triangles: job.model.triangles(),
        vertex_energies: &energies,
        boundary_loops: job.model.boundary_loops(),
        cut_polylines: Vec::new(),
        fold_polylines: fold_polylines(&job.model, &flattened.positions),
        figures: PatternFigures {
            area_error: accuracy.area_error,
            shape_error: accuracy.shape_error,
            max_strain: accuracy.max_strain,
            cuts: 0,
        },
        negligible_energy: negligible_vertex_energy(&springs, NEGLIGIBLE_STRAIN),
    };
    Ok(render_energy_png(&map, None, &EnergyPngOptions::default())?)
}
