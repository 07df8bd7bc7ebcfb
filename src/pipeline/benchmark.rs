//! Nesting benchmark instances (ESICUP JSON, as in jagua-rs and sparrow) from the library: their
//! items nested together on sheets or a roll and checked independently, for `flatcut nest`, which
//! writes the sheets as `flatcut run` draws them (`sheets/sheet-NNN.dxf` and `.png`) and
//! `nest.json`.

use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::error::Error;
use crate::export::DxfOptions;
use crate::export::nest_report::{NestReport, NestReportOptions};
use crate::export::sheets::{SHEETS_FOLDER, sheet_drawings, write_sheet_files};
use crate::nest::instance::read_instance;
use crate::nest::verify::verify;
use crate::nest::{
    DEFAULT_GAP, DEFAULT_SEED, DEFAULT_TIME_LIMIT, NestItem, NestLayout, NestOptions, Rotations,
    Stock, nest,
};
use crate::pattern::PartDrawing;
use crate::progress::Progress;
use crate::units::Units;

/// A benchmark nesting job. `Default` is the only source of defaults (the nester's).
#[derive(Debug, Clone, PartialEq)]
pub struct BenchmarkConfig {
    /// ESICUP instance files; their items are nested together.
    pub inputs: Vec<PathBuf>,
    /// The stock; `None` (the default) for a roll as wide as the instances' strip height.
    pub stock: Option<Stock>,
    /// Gap between parts and to the stock edge, mm; default [`DEFAULT_GAP`].
    pub gap: f64,
    /// Search budget in seconds, capped by the wall clock; default [`DEFAULT_TIME_LIMIT`].
    pub time_seconds: f64,
    /// Work budget in collision queries instead of the time budget × the nominal rate.
    pub work_limit: Option<u64>,
    /// Seed of the search; default [`DEFAULT_SEED`].
    pub seed: u64,
    /// Rotations for every item, mirrored or not, overriding the instances'; `None` keeps theirs.
    pub rotations: Option<Rotations>,
    /// Whether small items may go inside the holes of larger ones.
    pub in_holes: bool,
    /// Whether every item may be mirrored, at its rotations (besides any mirroring its instance
    /// allows).
    pub mirror: bool,
}

impl Default for BenchmarkConfig {
    fn default() -> Self {
        Self {
            inputs: Vec::new(),
            stock: None,
            gap: DEFAULT_GAP,
            time_seconds: DEFAULT_TIME_LIMIT.as_secs_f64(),
            work_limit: None,
            seed: DEFAULT_SEED,
            rotations: None,
            in_holes: false,
            mirror: false,
        }
    }
}

/// A nested benchmark.
#[derive(Debug, Clone)]
pub struct BenchmarkOutput {
    /// The instances' names, in input order.
    pub names: Vec<String>,
    /// Every instance's items, as nested.
    pub items: Vec<NestItem>,
    /// The nester's options used.
    pub options: NestOptions,
    /// The layout, checked independently.
    pub layout: NestLayout,
}

/// Reads the instances, nests their items together and checks the layout independently.
pub fn nest_benchmark(
    config: &BenchmarkConfig,
    progress: &dyn Progress,
) -> Result<BenchmarkOutput, Error> {
    let mut items: Vec<NestItem> = Vec::new();
    let mut names = Vec::new();
    let mut strip_height: Option<f64> = None;
    for path in &config.inputs {
        let instance = read_instance(path)?;
        let differs = strip_height.is_some_and(|height| {
            (height - instance.strip_height).abs() > f64::EPSILON * height.abs()
        });
        if differs && config.stock.is_none() {
            return Err(Error::StripHeightDiffers { path: path.clone() });
        }
        strip_height.get_or_insert(instance.strip_height);
        names.push(instance.name);
        items.extend(instance.items);
    }
    for item in &mut items {
        override_poses(item, config.rotations.as_ref(), config.mirror);
    }
    let stock = match (config.stock, strip_height) {
        (Some(stock), _) => stock,
        (None, Some(width)) => Stock::Roll { width },
        (None, None) => return Err(Error::NoStock),
    };
    let seconds = config.time_seconds;
    if !seconds.is_finite() || seconds < 0.0 {
        return Err(Error::InvalidTime { seconds });
    }
    let options = NestOptions {
        stock,
        gap: config.gap,
        time_limit: Duration::from_secs_f64(seconds),
        seed: config.seed,
        work_limit: config.work_limit,
        in_holes: config.in_holes,
    };
    let layout = nest(&items, &options, progress)?;
    let violations = verify(&items, &layout);
    if !violations.is_empty() {
        return Err(Error::BenchmarkLayoutRejected { violations });
    }
    Ok(BenchmarkOutput {
        names,
        items,
        options,
        layout,
    })
}

/// Writes the sheets of a nested benchmark (`sheets/sheet-NNN.dxf` and `.png`: each item's
/// outline and holes as drawn by `flatcut run`, named on the preview) and `nest.json` into
/// `directory` (created if missing), and returns the text of `nest.json`.
pub fn write_benchmark(
    output: &BenchmarkOutput,
    config: &BenchmarkConfig,
    directory: &Path,
) -> Result<String, Error> {
    let drawings: Vec<PartDrawing> = output.items.iter().map(item_drawing).collect();
    let sheets = sheet_drawings(&drawings, &output.layout);
    let files = write_sheet_files(
        directory,
        Path::new(SHEETS_FOLDER),
        &sheets,
        &DxfOptions::default(),
    )?;
    let options = NestReportOptions {
        stock: output.options.stock,
        gap: output.options.gap,
        time_limit_seconds: config.time_seconds,
        seed: output.options.seed,
        work_limit: output.options.work_limit,
        rotations: config.rotations.as_ref(),
        mirror: config.mirror,
        in_holes: config.in_holes,
    };
    let report = NestReport::new(
        &output.names,
        options,
        &output.items,
        &output.layout,
        &files,
    );
    Ok(report.write(directory)?)
}

/// Applies the command line's poses to an instance item: `rotations` (when given) replaces its
/// rotations, mirrored or not; `mirror` adds its rotations to those of its mirrored copies.
fn override_poses(item: &mut NestItem, rotations: Option<&Rotations>, mirror: bool) {
    if let Some(rotations) = rotations {
        item.rotations = rotations.clone();
        if item.mirror.is_some() {
            item.mirror = Some(rotations.clone());
        }
    }
    if mirror {
        let mut sets: Vec<Rotations> = item.mirror.take().into_iter().collect();
        sets.push(item.rotations.clone());
        item.mirror = Rotations::union(&sets);
    }
}

/// The drawing of a benchmark item: its outline and holes in millimetres, nothing else.
fn item_drawing(item: &NestItem) -> PartDrawing {
    PartDrawing {
        name: item.name.clone(),
        units: Units::Millimetres,
        quantity: item.quantity,
        material: None,
        outer: item.outer.clone(),
        holes: item.holes.clone(),
        fold_lines: Vec::new(),
        grain: None,
        bends: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec2;

    use super::*;
    use crate::nest::verify::tests::polygon;

    /// A triangle fixed at 0°, whose mirrored copies take `mirror`.
    fn triangle(mirror: Option<Rotations>) -> NestItem {
        let outer = vec![DVec2::ZERO, DVec2::X, DVec2::Y];
        NestItem {
            mirror,
            ..polygon("t", outer, 1, Rotations::Fixed(vec![0.0]))
        }
    }

    #[test]
    fn command_line_poses_override_or_extend_the_instances() {
        // Neither option: the instance's own poses stand.
        let mut item = triangle(Some(Rotations::Fixed(vec![180.0])));
        override_poses(&mut item, None, false);
        assert_eq!(item.poses(), Some(vec![(0.0, false), (180.0, true)]));
        // `--mirror` adds the rotations to the mirrored copy's own.
        override_poses(&mut item, None, true);
        assert_eq!(
            item.poses(),
            Some(vec![(0.0, false), (0.0, true), (180.0, true)])
        );
        // `--rotations` replaces both; an item never mirrored stays so.
        let step = Rotations::Step(90.0);
        override_poses(&mut item, Some(&step), false);
        assert_eq!(
            (&item.rotations, &item.mirror),
            (&step, &Some(step.clone()))
        );
        let mut plain = triangle(None);
        override_poses(&mut plain, Some(&step), false);
        assert_eq!(plain.mirror, None);
    }
}
