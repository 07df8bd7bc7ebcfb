//! Options of a run: [`RunOptions`] for loading and flattening each part, and [`RunConfig`], the
//! whole run's (inputs, every stage's options, stock and nesting). `Default` is the only source
//! of defaults: the command line reads its defaults from here.

use std::path::PathBuf;
use std::time::Duration;

use serde::Serialize;

use crate::cut::CutOptions;
use crate::export::DxfVersion;
use crate::export::energy_png::EnergyPngOptions;
use crate::flatten::FlattenOptions;
use crate::nest::{DEFAULT_SEED, NestOptions, Rotations, Stock};
use crate::pattern::PatternOptions;
use crate::tessellate::TessellateOptions;
use crate::units::Units;

/// Options of loading and flattening one part, echoed in the report.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct RunOptions {
    /// Units of mesh files (part files and STEP files carry their own).
    pub units: Units,
    /// Flattening options.
    pub flatten: FlattenOptions,
    /// Cutting options (seams, crest-line cuts).
    pub cut: CutOptions,
    /// Tessellation of part and STEP files.
    pub tessellate: TessellateOptions,
}

/// Gap between nested parts and to the stock edge in a run, mm.
pub const DEFAULT_RUN_GAP: f64 = 2.0;

/// Nesting search budget of a run.
pub const DEFAULT_RUN_TIME_LIMIT: Duration = Duration::from_secs(10);

/// Rotations tried for flattened parts, degrees from the pattern's minimum-area bounding
/// rectangle.
pub const DEFAULT_RUN_ROTATIONS: [f64; 4] = [0.0, 90.0, 180.0, 270.0];

/// How a run nests its patterns (the stock is [`RunConfig::stock`]).
#[derive(Debug, Clone, PartialEq)]
pub struct NestingConfig {
    /// Gap between parts and to the stock edge, mm; default [`DEFAULT_RUN_GAP`].
    pub gap: f64,
    /// Search budget (a deterministic work budget, capped by the wall clock); default
    /// [`DEFAULT_RUN_TIME_LIMIT`].
    pub time_limit: Duration,
    /// Seed of the search; default [`DEFAULT_SEED`].
    pub seed: u64,
    /// Rotations allowed for every part, measured from its minimum-area bounding rectangle; a
    /// part with a grain is only turned to keep it along x. Default [`DEFAULT_RUN_ROTATIONS`].
    pub rotations: Rotations,
    /// Whether small parts may go inside the holes of larger ones.
    pub in_holes: bool,
    /// Whether parts may be mirrored (only for material with no face side).
    pub mirror: bool,
}

impl Default for NestingConfig {
    fn default() -> Self {
        Self {
            gap: DEFAULT_RUN_GAP,
            time_limit: DEFAULT_RUN_TIME_LIMIT,
            seed: DEFAULT_SEED,
            rotations: Rotations::Fixed(DEFAULT_RUN_ROTATIONS.to_vec()),
            in_holes: false,
            mirror: false,
        }
    }
}

impl NestingConfig {
    /// The nester's options on `stock`.
    pub fn nest_options(&self, stock: Stock) -> NestOptions {
        NestOptions {
            stock,
            gap: self.gap,
            time_limit: self.time_limit,
            seed: self.seed,
            work_limit: None,
            in_holes: self.in_holes,
        }
    }
}

/// Everything a run needs: its inputs and every stage's options.
#[derive(Debug, Clone, PartialEq)]
pub struct RunConfig {
    /// Input parts: part files (.toml), STEP files (.step, .stp), triangle meshes (.obj, .stl).
    pub inputs: Vec<PathBuf>,
    /// Loading, tessellating, flattening and cutting each part.
    pub options: RunOptions,
    /// Chord tolerance of the cut contours and seam allowance.
    pub pattern: PatternOptions,
    /// DXF version of the cut files.
    pub dxf_version: DxfVersion,
    /// Size of the energy pictures.
    pub energy_png: EnergyPngOptions,
    /// The stock to nest the patterns on; `None` (the default) for no nesting.
    pub stock: Option<Stock>,
    /// How the patterns are nested when there is stock.
    pub nesting: NestingConfig,
    /// Whether the report records wall-clock seconds (`false` writes 0, for byte-identical
    /// reports); default `true`.
    pub timings: bool,
}

impl Default for RunConfig {
    fn default() -> Self {
        Self {
            inputs: Vec::new(),
            options: RunOptions::default(),
            pattern: PatternOptions::default(),
            dxf_version: DxfVersion::default(),
            energy_png: EnergyPngOptions::default(),
            stock: None,
            nesting: NestingConfig::default(),
            timings: true,
        }
    }
}
