//! `flatcut nest`: pattern files (`<part>.pattern.json`, or run output folders holding them)
//! nested together by material and thickness, their sheets written as `flatcut run` writes them;
//! or benchmark instances (ESICUP JSON). Either way the layout is checked independently and
//! described in `OUT/nest.json`.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;

use flatcut::export::sheets::SHEETS_FOLDER;
use flatcut::nest::{Rotations, Stock};
use flatcut::pipeline::{
    BenchmarkConfig, NestInputKind, NestingConfig, PatternNestConfig, nest_benchmark,
    nest_input_kind, nest_patterns_into, write_benchmark,
};
use flatcut::progress::Progress;

use super::console::{say, stdout_text};
use super::outcome::Outcome;
use super::parse::{DxfVersionArg, parse_rotations, parse_sheet, time_limit};

/// Arguments of `flatcut nest`.
#[derive(Debug, Args)]
pub struct NestArgs {
    /// Pattern files (`<part>.pattern.json`) and folders holding them (a run's output folder:
    /// every `*.pattern.json` directly inside, in file-name order), or ESICUP instance files
    /// (JSON, as in jagua-rs/sparrow); one kind at a time. Their parts are nested together.
    #[arg(required = true, value_name = "INPUT")]
    inputs: Vec<PathBuf>,
    /// Output directory; `nest.json` and the sheet files (`sheet-NNN.dxf` and `.png`) are written
    /// there.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// Nest on identical sheets WIDTHxHEIGHT in mm (filled along the width).
    #[arg(long, value_name = "WxH", value_parser = parse_sheet, conflicts_with = "roll")]
    sheet: Option<(f64, f64)>,
    /// Nest on a roll this wide (mm); the used length is minimised. Required for patterns (or
    /// --sheet); for instances it defaults to their strip_height.
    #[arg(long, value_name = "W")]
    roll: Option<f64>,
    /// Gap between parts and to the stock edge, mm (defaults: [`gap_help`]).
    #[arg(long, value_name = "MM", help = gap_help())]
    gap: Option<f64>,
    /// Search budget in seconds (defaults: [`time_help`]).
    #[arg(long, value_name = "S", help = time_help())]
    time: Option<f64>,
    /// Work budget in collision queries instead of --time × the nominal rate: the same result on
    /// any machine (--time still caps the wall clock).
    #[arg(long, value_name = "QUERIES")]
    work: Option<u64>,
    /// Seed of the search.
    #[arg(long, value_name = "N", default_value_t = BenchmarkConfig::default().seed)]
    seed: u64,
    /// Allowed rotations for every part: a list of degrees ("0,90,180"), a step ("step:15") or
    /// "free" (any angle: the first layouts try 24, every 15°, and the search through overlap
    /// turns parts continuously between them). For patterns, measured from the
    /// pattern's minimum-area bounding rectangle, default 0,90,180,270 (as `flatcut run`); for
    /// instances, overriding theirs.
    #[arg(long, value_name = "LIST|step:DEG|free", value_parser = parse_rotations)]
    rotations: Option<Rotations>,
    /// Place small parts inside the holes of larger ones (the parts keep the gap to the hole edge).
    #[arg(long)]
    in_holes: bool,
    /// Allow parts to be mirrored.
    #[arg(long)]
    mirror: bool,
    /// Patterns only: nest the patterns of rejected parts (over tolerance) too; without it they
    /// are refused.
    #[arg(long)]
    include_rejected: bool,
    /// Patterns only: DXF version of the sheet files.
    #[arg(long, value_enum, default_value_t = DxfVersionArg::R2000)]
    dxf_version: DxfVersionArg,
    /// Print nest.json to stdout.
    #[arg(long)]
    json: bool,
}

/// The help of `--gap`, with the defaults of both kinds of input.
fn gap_help() -> String {
    format!(
        "Gap between parts and to the stock edge, mm [default: {} for patterns, as `flatcut run`; \
         {} for instances]",
        NestingConfig::default().gap,
        BenchmarkConfig::default().gap
    )
}

/// The help of `--time`, with the defaults of both kinds of input.
fn time_help() -> String {
    format!(
        "Search budget in seconds (a deterministic work budget, capped by the wall clock) \
         [default: {} for patterns, as `flatcut run`; {} for instances]",
        NestingConfig::default().time_limit.as_secs_f64(),
        BenchmarkConfig::default().time_seconds
    )
}

impl NestArgs {
    /// The stock, if any was given.
    fn stock(&self) -> Option<Stock> {
        match (self.sheet, self.roll) {
            (Some((width, height)), _) => Some(Stock::Sheets { width, height }),
            (None, Some(width)) => Some(Stock::Roll { width }),
            (None, None) => None,
        }
    }

    /// The benchmark job, converted in one place.
    fn benchmark_config(&self) -> BenchmarkConfig {
        let defaults = BenchmarkConfig::default();
        BenchmarkConfig {
            inputs: self.inputs.clone(),
            stock: self.stock(),
            gap: self.gap.unwrap_or(defaults.gap),
            time_seconds: self.time.unwrap_or(defaults.time_seconds),
            work_limit: self.work,
            seed: self.seed,
            rotations: self.rotations.clone(),
            in_holes: self.in_holes,
            mirror: self.mirror,
        }
    }

    /// The fan-in job, converted in one place; defaults are a run's ([`NestingConfig`]).
    fn pattern_config(&self) -> anyhow::Result<PatternNestConfig> {
        let defaults = NestingConfig::default();
        let nesting = NestingConfig {
            gap: self.gap.unwrap_or(defaults.gap),
            time_limit: match self.time {
                Some(seconds) => time_limit(seconds)?,
                None => defaults.time_limit,
            },
            work_limit: self.work,
            seed: self.seed,
            rotations: self.rotations.clone().unwrap_or(defaults.rotations),
            in_holes: self.in_holes,
            mirror: self.mirror,
        };
        Ok(PatternNestConfig {
            inputs: self.inputs.clone(),
            stock: self.stock(),
            nesting,
            dxf_version: self.dxf_version.into(),
            include_rejected: self.include_rejected,
        })
    }
}

/// Runs `flatcut nest` on pattern inputs or on benchmark instances.
pub fn run(args: NestArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    match nest_input_kind(&args.inputs)? {
        NestInputKind::Patterns => run_patterns(&args, progress),
        NestInputKind::Instances => run_benchmark(&args, progress),
    }
}

/// Nests pattern files into the output folder and prints one line per group.
fn run_patterns(args: &NestArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    let config = args.pattern_config()?;
    let (output, json) =
        nest_patterns_into(&config, &args.output, progress, &super::interrupt::watch)?;
    for group in &output.groups {
        let layout = &group.nested.layout;
        let material = group.material.as_deref().unwrap_or("no material");
        let thickness = group
            .thickness_mm
            .map_or(String::new(), |thickness| format!(" {thickness} mm"));
        say!(
            "flatcut nest: {material}{thickness}: {} part(s) on {} sheet(s) in {}, utilisation {:.2} %, length used {:.1} mm, stopped by {:?}, verified",
            group.patterns.len(),
            layout.sheets.len(),
            args.output.join(&group.folder).display(),
            layout.utilisation * 100.0,
            layout.used_length,
            layout.stop_reason,
        );
    }
    if args.json {
        stdout_text(&json);
    }
    let rejected = output
        .groups
        .iter()
        .flat_map(|group| &group.patterns)
        .any(|sourced| sourced.pattern.rejected);
    Ok(if rejected {
        Outcome::OverTolerance
    } else {
        Outcome::Success
    })
}

/// Nests benchmark instances and writes their sheets and `nest.json`.
fn run_benchmark(args: &NestArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    let started = Instant::now();
    let config = args.benchmark_config();
    let output = nest_benchmark(&config, progress)?;
    let json = write_benchmark(&output, &config, &args.output)?;
    if args.json {
        stdout_text(&json);
    }
    let layout = &output.layout;
    let stock_word = match output.options.stock {
        Stock::Sheets { .. } => format!("{} sheet(s)", layout.sheets.len()),
        Stock::Roll { .. } => "roll".to_string(),
    };
    say!(
        "flatcut nest: {}: {stock_word} in {}, length used {:.3} mm, density {:.2} %, {:.1} s, seed {}, {} evaluations, stopped by {:?}, verified",
        output.names.join("+"),
        args.output.join(SHEETS_FOLDER).display(),
        layout.used_length,
        layout.utilisation * 100.0,
        started.elapsed().as_secs_f64(),
        output.options.seed,
        layout.evaluations,
        layout.stop_reason,
    );
    Ok(Outcome::Success)
}
