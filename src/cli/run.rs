//! `flatcut run INPUT... -o OUT/ [--sheet WxH | --roll W]`: the whole pipeline. Flattens and cuts
//! every part like `flatten`, then, when stock is given, nests the patterns in their quantities
//! and writes `sheets/sheet-NNN.dxf` and `.png`, with the sheets in `report.json`.

use clap::Args;

use flatcut::nest::{Rotations, Stock};
use flatcut::pipeline::{NestingConfig, RunConfig};
use flatcut::progress::Progress;

use super::flatten::FlattenArgs;
use super::job::execute;
use super::outcome::Outcome;
use super::parse::{parse_rotations, parse_sheet, time_limit};

/// Arguments of `run`: those of `flatten`, and the stock to nest on.
#[derive(Debug, Args)]
pub struct RunArgs {
    #[command(flatten)]
    flatten: FlattenArgs,
    /// Nest the patterns on identical sheets WIDTHxHEIGHT in mm (as many as needed).
    #[arg(long, value_name = "WxH", value_parser = parse_sheet, conflicts_with = "roll")]
    sheet: Option<(f64, f64)>,
    /// Nest the patterns on a roll this wide (mm), using as little length as possible.
    #[arg(long, value_name = "W")]
    roll: Option<f64>,
    /// Gap between parts and to the stock edge, mm.
    #[arg(long, value_name = "MM", default_value_t = NestingConfig::default().gap)]
    gap: f64,
    /// Nesting search budget in seconds (a deterministic work budget, capped by the wall clock).
    #[arg(long, value_name = "S", default_value_t = NestingConfig::default().time_limit.as_secs_f64())]
    time: f64,
    /// Nesting work budget in collision queries instead of --time × the nominal rate: the same
    /// layout on any machine (--time still caps the wall clock).
    #[arg(long, value_name = "QUERIES")]
    work: Option<u64>,
    /// Seed of the nesting search.
    #[arg(long, value_name = "N", default_value_t = NestingConfig::default().seed)]
    seed: u64,
    /// Allowed rotations, measured from the pattern's minimum-area bounding rectangle: a list of
    /// degrees ("0,180"), a step ("step:15") or "free" (any angle: sampled every 15°, turned
    /// continuously between by the search through overlap); default
    /// 0,90,180,270. A part with a grain is only turned to keep it along x.
    #[arg(long, value_name = "LIST|step:DEG|free", value_parser = parse_rotations)]
    rotations: Option<Rotations>,
    /// Nest small parts inside the holes of larger ones (keeping the gap to the hole edge).
    #[arg(long)]
    in_holes: bool,
    /// Allow parts to be mirrored (only for material with no face side).
    #[arg(long)]
    mirror: bool,
}

impl RunArgs {
    /// The stock, if any was given.
    fn stock(&self) -> Option<Stock> {
        match (self.sheet, self.roll) {
            (Some((width, height)), _) => Some(Stock::Sheets { width, height }),
            (None, Some(width)) => Some(Stock::Roll { width }),
            (None, None) => None,
        }
    }

    /// The run's configuration, converted in one place: `flatten`'s, with the stock and how to
    /// nest on it.
    fn config(&self) -> anyhow::Result<RunConfig> {
        let stock = self.stock();
        let defaults = NestingConfig::default();
        let nesting = NestingConfig {
            gap: self.gap,
            time_limit: if stock.is_some() {
                time_limit(self.time)?
            } else {
                defaults.time_limit
            },
            work_limit: self.work,
            seed: self.seed,
            rotations: self.rotations.clone().unwrap_or(defaults.rotations),
            in_holes: self.in_holes,
            mirror: self.mirror,
        };
        Ok(RunConfig {
            stock,
            nesting,
            ..self.flatten.config()?
        })
    }
}

/// Runs the whole pipeline.
pub fn run(args: RunArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    let config = args.config()?;
    execute(
        &config,
        args.flatten.output(),
        args.flatten.json(),
        progress,
    )
}
