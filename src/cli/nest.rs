//! `flatcut nest`: benchmark instances (ESICUP JSON) onto sheets or a roll, checked independently,
//! written to `OUT/nest.json`.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;

use flatcut::nest::{Rotations, Stock};
use flatcut::pipeline::{BenchmarkConfig, nest_benchmark, write_benchmark};
use flatcut::progress::Progress;

use super::console::{say, stdout_text};
use super::outcome::Outcome;
use super::parse::{parse_rotations, parse_sheet};

/// Arguments of `flatcut nest`.
#[derive(Debug, Args)]
pub struct NestArgs {
    /// ESICUP instance files (JSON, as in jagua-rs/sparrow); their items are nested together.
    #[arg(required = true, value_name = "INPUT")]
    inputs: Vec<PathBuf>,
    /// Output directory; `nest.json` is written there.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// Nest on identical sheets WIDTHxHEIGHT in mm (filled along the width).
    #[arg(long, value_name = "WxH", value_parser = parse_sheet, conflicts_with = "roll")]
    sheet: Option<(f64, f64)>,
    /// Nest on a roll this wide (mm); the used length is minimised. Defaults to the instance's
    /// strip_height.
    #[arg(long, value_name = "W")]
    roll: Option<f64>,
    /// Gap between parts and to the stock edge, mm.
    #[arg(long, value_name = "MM", default_value_t = BenchmarkConfig::default().gap)]
    gap: f64,
    /// Search budget in seconds (a deterministic work budget, capped by the wall clock).
    #[arg(long, value_name = "S", default_value_t = BenchmarkConfig::default().time_seconds)]
    time: f64,
    /// Work budget in collision queries instead of --time × the nominal rate: the same result on
    /// any machine (--time still caps the wall clock).
    #[arg(long, value_name = "QUERIES")]
    work: Option<u64>,
    /// Seed of the search.
    #[arg(long, value_name = "N", default_value_t = BenchmarkConfig::default().seed)]
    seed: u64,
    /// Allowed rotations for every part, overriding the instance: a list of degrees ("0,90,180"),
    /// a step ("step:15") or "free" (24 angles, every 15°; not a continuous search).
    #[arg(long, value_name = "LIST|step:DEG|free", value_parser = parse_rotations)]
    rotations: Option<Rotations>,
    /// Place small parts inside the holes of larger ones (the parts keep the gap to the hole edge).
    #[arg(long)]
    in_holes: bool,
    /// Allow parts to be mirrored.
    #[arg(long)]
    mirror: bool,
    /// Print the result JSON to stdout.
    #[arg(long)]
    json: bool,
}

impl NestArgs {
    /// The job, converted in one place.
    fn config(&self) -> BenchmarkConfig {
        let stock = match (self.sheet, self.roll) {
            (Some((width, height)), _) => Some(Stock::Sheets { width, height }),
            (None, Some(width)) => Some(Stock::Roll { width }),
            (None, None) => None,
        };
        BenchmarkConfig {
            inputs: self.inputs.clone(),
            stock,
            gap: self.gap,
            time_seconds: self.time,
            work_limit: self.work,
            seed: self.seed,
            rotations: self.rotations.clone(),
            in_holes: self.in_holes,
            mirror: self.mirror,
        }
    }
}

/// Runs `flatcut nest`.
pub fn run(args: NestArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    let started = Instant::now();
    let config = args.config();
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
        "flatcut nest: {}: {stock_word}, length used {:.3} mm, utilisation {:.2} %, {:.1} s, seed {}, {} evaluations, stopped by {:?}, verified",
        output.names.join("+"),
        layout.used_length,
        layout.utilisation * 100.0,
        started.elapsed().as_secs_f64(),
        output.options.seed,
        layout.evaluations,
        layout.stop_reason,
    );
    Ok(Outcome::Success)
}
