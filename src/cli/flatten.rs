//! `flatcut flatten INPUT -o OUT/` and `flatcut run INPUT... -o OUT/`: flatten parts and write
//! their patterns, facet models and the report.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;

use flatcut::cut::CutOptions;
use flatcut::export::part_files::{PartFileOptions, write_part_files};
use flatcut::export::report::{PartReport, Report};
use flatcut::export::{DEFAULT_CHORD_TOLERANCE, DxfOptions, DxfVersion, write_atomically};
use flatcut::flatten::{FlattenOptions, Solver};
use flatcut::nest::{NestOptions, Rotations};
use flatcut::pipeline::{PartJob, PartResult, RunOptions, flatten_part, load_parts};
use flatcut::progress::Progress;
use flatcut::units::Units;

use super::Outcome;

/// Above this many triangles `--solver paper` warns that it will be slow (its phase one is
/// quadratic: about 10 s at 5,000 triangles on a 2-core machine).
const PAPER_SOLVER_ADVISED_TRIANGLES: usize = 5_000;

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
    /// Largest number of crest-line cuts per part (0: no cuts; seams are still made). Default: 8
    /// per π of the opened part's total absolute Gaussian curvature ∫|K| dA (π is the curvature of
    /// a 60° spherical cap), at least 8.
    #[arg(long)]
    max_cuts: Option<usize>,
    /// Units of mesh coordinates.
    #[arg(long, value_enum, default_value_t = Units::default())]
    units: Units,
    /// DXF version of the cut files: `r2000` (LWPOLYLINE, units in the header) or `r12` for old
    /// controllers.
    #[arg(long, value_enum, default_value_t = DxfVersionArg::R2000)]
    dxf_version: DxfVersionArg,
    /// Chord tolerance of the DXF cut contours in mm: the written contour (lines and arcs) stays
    /// this close to the pattern's outline. (`--chord` is the tessellation's.)
    #[arg(long, value_name = "MM", default_value_t = DEFAULT_CHORD_TOLERANCE)]
    dxf_chord: f64,
    /// Seam allowance in mm for garments: the cut contour is offset outward by it, and the
    /// pattern's outline goes to the sew layer.
    #[arg(long, value_name = "MM")]
    seam_allowance: Option<f64>,
    #[command(flatten)]
    sizes: super::tessellate::MeshSizeArgs,
    /// Print the report to stdout as JSON.
    #[arg(long)]
    json: bool,
    /// Write 0 for every `seconds` in the report, so reports of the same input are byte-identical.
    #[arg(long)]
    no_timings: bool,
}

/// DXF versions on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum DxfVersionArg {
    /// AutoCAD 2000.
    R2000,
    /// AutoCAD R12.
    R12,
}

impl FlattenArgs {
    /// How part files are drawn.
    fn part_file_options(&self) -> PartFileOptions {
        let version = match self.dxf_version {
            DxfVersionArg::R2000 => DxfVersion::R2000,
            DxfVersionArg::R12 => DxfVersion::R12,
        };
        let dxf = DxfOptions {
            version,
            chord_tolerance: self.dxf_chord,
            seam_allowance: self.seam_allowance,
        };
        PartFileOptions {
            dxf,
            ..PartFileOptions::default()
        }
    }

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
        let cut = CutOptions {
            max_cuts: self.max_cuts,
            ..CutOptions::default()
        };
        Ok(RunOptions {
            units: self.units,
            flatten,
            cut,
            tessellate: self.sizes.options()?,
        })
    }
}

/// Runs `flatten` or `run`: every input is read and checked before anything is written.
/// The nesting step of `run`: where to nest and how.
#[derive(Debug, Clone)]
pub struct Nesting {
    /// Stock, gap, budget and seed.
    pub options: NestOptions,
    /// Rotations allowed for every part.
    pub rotations: Rotations,
    /// Whether parts may be mirrored.
    pub mirror: bool,
}

/// Refuses two parts of the same name: the second's files would overwrite the first's.
fn check_distinct_names(jobs: &[PartJob]) -> anyhow::Result<()> {
    for (index, job) in jobs.iter().enumerate() {
        if let Some(earlier) = jobs[..index].iter().find(|other| other.name == job.name) {
            anyhow::bail!(
                "{}: part '{}' has the name of a part from {}: its output files would overwrite \
                 the other's; give one of them another name (`name = ...` in a part file, or \
                 rename the file)",
                job.source.display(),
                job.name,
                earlier.source.display()
            );
        }
    }
    Ok(())
}

/// Runs `flatten`, or `run` when `nesting` is given: every input is read and checked before
/// anything is written.
pub fn run(
    args: FlattenArgs,
    nesting: Option<&Nesting>,
    progress: &dyn Progress,
) -> anyhow::Result<Outcome> {
    let options = args.run_options()?;
    let file_options = args.part_file_options();
    file_options.dxf.validate()?;
    let mut jobs = Vec::new();
    for input in &args.inputs {
        jobs.extend(load_parts(input, &options)?);
    }
    check_distinct_names(&jobs)?;
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
        write_part_files(
            &args.output,
            result,
            options.flatten.spring_constant,
            &file_options,
        )?;
    }
    let sheets = match nesting {
        Some(nesting) => super::run::nest_and_write(
            &args.output,
            &results,
            nesting,
            &file_options.dxf,
            progress,
        )?,
        None => Vec::new(),
    };
    let parts: Vec<PartReport> = results
        .iter()
        .map(|r| PartReport::new(r, &options, !args.no_timings))
        .collect();
    let all_met = parts.iter().all(|p| p.tolerance_met);
    for part in &parts {
        eprintln!(
            "flatcut: {}: E_S {:.4} %, E_C {:.4} %, {} flipped, {} seam(s), {} cut(s) of total length {:.4}, {}",
            part.name,
            part.area_error * 100.0,
            part.shape_error * 100.0,
            part.flipped,
            part.seams.len(),
            part.cuts.len(),
            part.total_cut_length,
            if part.tolerance_met {
                "within tolerance"
            } else {
                "OVER TOLERANCE"
            }
        );
    }
    let mut report = Report::new(options, parts);
    report.sheets = sheets;
    let report = report.to_json();
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
