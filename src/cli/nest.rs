//! `flatcut nest`: benchmark instances (ESICUP JSON) onto sheets or a roll, checked independently,
//! written to `OUT/nest.json`.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use clap::Args;
use serde::Serialize;

use flatcut::export::write_atomically;
use flatcut::nest::instance::read_instance;
use flatcut::nest::verify::verify;
use flatcut::nest::{self, NestItem, NestLayout, NestOptions, Rotations, Stock};
use flatcut::progress::Progress;

use super::outcome::Outcome;
use super::parse::{parse_rotations, parse_sheet};

/// Version of the `nest.json` layout; raised when a key changes meaning.
const SCHEMA_VERSION: u32 = 1;

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
    #[arg(long, value_name = "MM", default_value_t = nest::DEFAULT_GAP)]
    gap: f64,
    /// Search budget in seconds (a deterministic work budget, capped by the wall clock).
    #[arg(long, value_name = "S", default_value_t = nest::DEFAULT_TIME_LIMIT.as_secs_f64())]
    time: f64,
    /// Work budget in collision queries instead of --time × the nominal rate: the same result on
    /// any machine (--time still caps the wall clock).
    #[arg(long, value_name = "QUERIES")]
    work: Option<u64>,
    /// Seed of the search.
    #[arg(long, value_name = "N", default_value_t = nest::DEFAULT_SEED)]
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

/// What `nest.json` holds.
#[derive(Serialize)]
struct Report<'a> {
    schema_version: u32,
    flatcut_version: &'static str,
    instances: Vec<String>,
    options: ReportOptions<'a>,
    parts: Vec<ReportPart<'a>>,
    verified: bool,
    #[serde(flatten)]
    layout: &'a NestLayout,
    density: f64,
}

#[derive(Serialize)]
struct ReportOptions<'a> {
    stock: Stock,
    gap: f64,
    time_limit_seconds: f64,
    seed: u64,
    work_limit: Option<u64>,
    rotations: Option<&'a Rotations>,
    mirror: bool,
    in_holes: bool,
}

#[derive(Serialize)]
struct ReportPart<'a> {
    name: &'a str,
    quantity: u32,
    area: f64,
}

/// Runs `flatcut nest`.
pub fn run(args: NestArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    let started = Instant::now();
    let mut items: Vec<NestItem> = Vec::new();
    let mut names = Vec::new();
    let mut strip_height: Option<f64> = None;
    for path in &args.inputs {
        let instance = read_instance(path)?;
        let differs = strip_height.is_some_and(|height| {
            (height - instance.strip_height).abs() > f64::EPSILON * height.abs()
        });
        if differs && args.roll.is_none() && args.sheet.is_none() {
            bail!(
                "{}: strip_height differs from the first instance's: give --roll W or --sheet WxH",
                path.display()
            );
        }
        strip_height.get_or_insert(instance.strip_height);
        names.push(instance.name);
        items.extend(instance.items);
    }
    if let Some(rotations) = &args.rotations {
        for item in &mut items {
            item.rotations = rotations.clone();
        }
    }
    for item in &mut items {
        item.mirror_allowed = args.mirror;
    }
    let stock = match (args.sheet, args.roll, strip_height) {
        (Some((width, height)), _, _) => Stock::Sheets { width, height },
        (None, Some(width), _) | (None, None, Some(width)) => Stock::Roll { width },
        (None, None, None) => bail!("give --sheet WxH or --roll W"),
    };
    if !args.time.is_finite() || args.time < 0.0 {
        bail!("--time {}: give a number of seconds, 0 or more", args.time);
    }
    let options = NestOptions {
        stock,
        gap: args.gap,
        time_limit: Duration::from_secs_f64(args.time),
        seed: args.seed,
        work_limit: args.work,
        in_holes: args.in_holes,
    };
    let layout = nest::nest(&items, &options, progress)?;
    let violations = verify(&items, &layout);
    if !violations.is_empty() {
        let list: Vec<String> = violations.iter().map(ToString::to_string).collect();
        bail!(
            "the independent check rejected the layout ({} defects):\n  {}",
            list.len(),
            list.join("\n  ")
        );
    }
    let report = Report {
        schema_version: SCHEMA_VERSION,
        flatcut_version: env!("CARGO_PKG_VERSION"),
        instances: names.clone(),
        options: ReportOptions {
            stock,
            gap: options.gap,
            time_limit_seconds: args.time,
            seed: options.seed,
            work_limit: options.work_limit,
            rotations: args.rotations.as_ref(),
            mirror: args.mirror,
            in_holes: args.in_holes,
        },
        parts: items
            .iter()
            .map(|item| ReportPart {
                name: &item.name,
                quantity: item.quantity,
                area: item.area(),
            })
            .collect(),
        verified: true,
        layout: &layout,
        density: layout.utilisation,
    };
    let json = serde_json::to_string_pretty(&report)? + "\n";
    std::fs::create_dir_all(&args.output)
        .with_context(|| format!("{}: cannot create the directory", args.output.display()))?;
    let path = args.output.join("nest.json");
    write_atomically(&path, json.as_bytes())
        .with_context(|| format!("{}: cannot write", path.display()))?;
    if args.json {
        print!("{json}");
    }
    let stock_word = match stock {
        Stock::Sheets { .. } => format!("{} sheet(s)", layout.sheets.len()),
        Stock::Roll { .. } => "roll".to_string(),
    };
    eprintln!(
        "flatcut nest: {}: {stock_word}, length used {:.3} mm, utilisation {:.2} %, {:.1} s, seed {}, {} evaluations, stopped by {:?}, verified",
        names.join("+"),
        layout.used_length,
        layout.utilisation * 100.0,
        started.elapsed().as_secs_f64(),
        options.seed,
        layout.evaluations,
        layout.stop_reason,
    );
    Ok(Outcome::Success)
}
