//! `flatcut run INPUT... -o OUT/ [--sheet WxH | --roll W]`: the whole pipeline. Flattens and cuts
//! every part like `flatten`, then, when stock is given, nests the patterns in their quantities
//! and writes `sheets/sheet-NNN.dxf` and `.png`, with the sheets in `report.json`.

use std::time::Duration;

use anyhow::bail;
use clap::Args;

use flatcut::export::PartDrawing;
use flatcut::export::part_files::part_drawing;
use flatcut::export::report::sheet_reports;
use flatcut::export::sheets::{sheet_drawings, write_sheet_files};
use flatcut::flatten::grain::flat_grain;
use flatcut::nest::parts::items_from_drawings;
use flatcut::nest::verify::verify;
use flatcut::nest::{self, NestOptions, Rotations, Stock};
use flatcut::pipeline::PartResult;
use flatcut::progress::Progress;

use super::Outcome;
use super::flatten::{FlattenArgs, Nesting};
use super::nest::{parse_rotations, parse_sheet};

/// Rotations tried for flattened parts unless `--rotations` says otherwise.
const DEFAULT_PART_ROTATIONS: [f64; 4] = [0.0, 90.0, 180.0, 270.0];

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
    #[arg(long, value_name = "MM", default_value_t = 2.0)]
    gap: f64,
    /// Nesting search budget in seconds (a deterministic work budget, capped by the wall clock).
    #[arg(long, value_name = "S", default_value_t = 10.0)]
    time: f64,
    /// Seed of the nesting search.
    #[arg(long, value_name = "N", default_value_t = nest::DEFAULT_SEED)]
    seed: u64,
    /// Allowed rotations, measured from the pattern's minimum-area bounding rectangle: a list of
    /// degrees ("0,180"), a step ("step:15") or "free" (24 angles, every 15°); default
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
}

/// Runs the whole pipeline.
pub fn run(args: RunArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    let Some(stock) = args.stock() else {
        return super::flatten::run(args.flatten, None, progress);
    };
    if !args.time.is_finite() || args.time < 0.0 {
        bail!("--time {}: give a number of seconds, 0 or more", args.time);
    }
    let options = NestOptions {
        stock,
        gap: args.gap,
        time_limit: Duration::from_secs_f64(args.time),
        seed: args.seed,
        work_limit: None,
        in_holes: args.in_holes,
    };
    let rotations = args
        .rotations
        .clone()
        .unwrap_or(Rotations::Fixed(DEFAULT_PART_ROTATIONS.to_vec()));
    let nesting = Nesting {
        options,
        rotations,
        mirror: args.mirror,
    };
    super::flatten::run(args.flatten, Some(&nesting), progress)
}

/// Nests the flattened parts (their drawings, with the grain of each part file), checks the
/// layout independently, writes the sheet files and returns the report's sheet entries.
pub fn nest_and_write(
    directory: &std::path::Path,
    results: &[PartResult],
    nesting: &Nesting,
    dxf: &flatcut::export::DxfOptions,
    progress: &dyn Progress,
) -> anyhow::Result<Vec<flatcut::export::report::SheetReport>> {
    let drawings: Vec<PartDrawing> = results.iter().map(part_drawing).collect();
    let grains: Vec<Option<f64>> = results
        .iter()
        .map(|result| {
            let grain = result.job.attributes.grain?;
            let flat = flat_grain(&result.job.model, &result.flattened.positions, grain)?;
            Some(flat.y.atan2(flat.x).to_degrees())
        })
        .collect();
    let items = items_from_drawings(&drawings, &grains, dxf, &nesting.rotations, nesting.mirror)?;
    let layout = nest::nest(&items, &nesting.options, progress)?;
    let violations = verify(&items, &layout);
    if !violations.is_empty() {
        let list: Vec<String> = violations.iter().map(ToString::to_string).collect();
        bail!(
            "the independent check rejected the nested layout:\n  {}",
            list.join("\n  ")
        );
    }
    let files = write_sheet_files(directory, &sheet_drawings(&drawings, &layout), dxf)?;
    let names: Vec<String> = items.iter().map(|item| item.name.clone()).collect();
    eprintln!(
        "flatcut: nested on {} sheet(s), utilisation {:.2} %, length used {:.1} mm",
        layout.sheets.len(),
        layout.utilisation * 100.0,
        layout.used_length
    );
    Ok(sheet_reports(&layout, &names, &files))
}
