//! Options of a run: [`RunOptions`] for loading and flattening each part, and [`RunConfig`], the
//! whole run's (inputs, every stage's options, stock and nesting). `Default` is the only source
//! of defaults: the command line reads its defaults from here.

use std::path::PathBuf;
use std::time::Duration;

use serde::{Deserialize, Serialize};

use crate::cut::CutOptions;
use crate::error::Error;
use crate::export::DxfVersion;
use crate::export::energy_png::EnergyPngOptions;
use crate::flatten::FlattenOptions;
use crate::mesh::SeamSource;
use crate::nest::{DEFAULT_SEED, MAXIMUM_STOCK_MM, NestOptions, Rotations, Stock};
use crate::pattern::PatternOptions;
use crate::progress::Deadline;
use crate::sheet::SheetOptions;
use crate::tessellate::TessellateOptions;
use crate::units::Units;

/// Options of loading and flattening one part, echoed in the report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunOptions {
    /// Units of mesh files (part files and STEP files carry their own).
    pub units: Units,
    /// Where a mesh file's pieces come from (echoed only when not the default).
    #[serde(default, skip_serializing_if = "SeamSource::is_default")]
    pub seams: SeamSource,
    /// Whether a mesh file's duplicate vertices are welded and its non-manifold edges and
    /// vertices split, with a warning each (echoed only when set).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub repair: bool,
    /// Flattening options.
    pub flatten: FlattenOptions,
    /// Cutting options (seams, crest-line cuts).
    pub cut: CutOptions,
    /// Tessellation of part and STEP files.
    pub tessellate: TessellateOptions,
    /// Quantity, material and thickness given for the parts, over what their files say (echoed
    /// only when one is given).
    #[serde(default, skip_serializing_if = "PartOverrides::is_empty")]
    pub overrides: PartOverrides,
    /// How STEP solids recognised as sheet metal are unfolded (echoed only when not the
    /// default).
    #[serde(default, skip_serializing_if = "SheetOptions::is_default")]
    pub sheet: SheetOptions,
    /// Longest a part's flattening and cutting may run, seconds; default
    /// [`DEFAULT_PART_TIME_LIMIT`] (echoed only when not the default). A part still over
    /// tolerance then is rejected with the reason.
    #[serde(
        default = "default_part_time_limit",
        skip_serializing_if = "is_default_part_time_limit"
    )]
    pub time_limit_seconds: f64,
}

/// Default of [`RunOptions::time_limit_seconds`]: ten minutes, well beyond any sample part.
pub const DEFAULT_PART_TIME_LIMIT: f64 = 600.0;

/// Largest [`RunOptions::time_limit_seconds`] accepted: a week.
pub const MAXIMUM_PART_TIME_LIMIT: f64 = 604_800.0;

fn default_part_time_limit() -> f64 {
    DEFAULT_PART_TIME_LIMIT
}

fn is_default_part_time_limit(seconds: &f64) -> bool {
    *seconds == DEFAULT_PART_TIME_LIMIT
}

impl Default for RunOptions {
    fn default() -> Self {
        Self {
            units: Units::default(),
            seams: SeamSource::default(),
            repair: false,
            flatten: FlattenOptions::default(),
            cut: CutOptions::default(),
            tessellate: TessellateOptions::default(),
            overrides: PartOverrides::default(),
            sheet: SheetOptions::default(),
            time_limit_seconds: DEFAULT_PART_TIME_LIMIT,
        }
    }
}

impl RunOptions {
    /// The flatten options of one part: the run's, with a deadline
    /// [`Self::time_limit_seconds`] from now.
    pub fn part_flatten_options(&self) -> FlattenOptions {
        FlattenOptions {
            deadline: Deadline::after(Duration::from_secs_f64(self.time_limit_seconds)),
            ..self.flatten.clone()
        }
    }
}

/// What the command line or a batch manifest says of a part, over what its file says.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct PartOverrides {
    /// The part's name, over the file's stem (`NAME-1`, `NAME-2`, … for a file of several
    /// parts): a batch's manifest names its parts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// How many copies to cut (a mesh says 1, a part file its `quantity`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quantity: Option<u32>,
    /// Material, printed on the label and used to group parts onto stock.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Sheet thickness in mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness_mm: Option<f64>,
}

impl PartOverrides {
    /// Whether nothing is overridden.
    pub fn is_empty(&self) -> bool {
        self == &Self::default()
    }

    /// Checks the quantity (at least 1) and the thickness (positive, finite); the error names
    /// the command-line option.
    pub fn validate(&self) -> Result<(), Error> {
        if self.quantity == Some(0) {
            return Err(Error::InvalidOption {
                option: "--quantity",
                value: "0".to_string(),
                reason: "give at least 1 copy".to_string(),
            });
        }
        if let Some(thickness) = self.thickness_mm
            && !(thickness.is_finite() && thickness > 0.0)
        {
            return Err(Error::InvalidOption {
                option: "--thickness",
                value: figure(thickness),
                reason: "give a positive thickness in mm".to_string(),
            });
        }
        Ok(())
    }
}

/// Largest permissible area and shape error a run accepts (a fraction: 0.5 is 50 %); a larger
/// one is almost surely a percentage given as a fraction (`1` meant as 1 %).
pub const MAXIMUM_TOLERANCE: f64 = 0.5;

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
    /// Work budget in collision queries, replacing the time budget × the nominal rate (the
    /// wall clock still caps it): the same layout on any machine. Default `None`.
    pub work_limit: Option<u64>,
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
            work_limit: None,
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
            work_limit: self.work_limit,
            in_holes: self.in_holes,
        }
    }

    /// Checks the nesting options on `stock` before any input is read: the stock's sizes
    /// (positive, finite, at most [`MAXIMUM_STOCK_MM`]), the gap and, with stock, the rotations.
    /// The error names the command-line option.
    pub fn validate(&self, stock: Option<Stock>) -> Result<(), Error> {
        let size = |value: f64| value.is_finite() && value > 0.0 && value <= MAXIMUM_STOCK_MM;
        let size_reason = |dimension: &str, value: f64| {
            format!(
                "the {dimension} is {} mm: give a positive size in mm, at most {MAXIMUM_STOCK_MM} mm",
                figure(value)
            )
        };
        match stock {
            Some(Stock::Sheets { width, height }) => {
                for (dimension, value) in [("sheet width", width), ("sheet height", height)] {
                    if !size(value) {
                        return invalid(
                            "--sheet",
                            format!("{}x{}", figure(width), figure(height)),
                            size_reason(dimension, value),
                        );
                    }
                }
            }
            Some(Stock::Roll { width }) if !size(width) => {
                return invalid("--roll", figure(width), size_reason("roll width", width));
            }
            _ => {}
        }
        let gap = self.gap;
        if !(gap.is_finite() && gap >= 0.0) {
            return invalid(
                "--gap",
                gap.to_string(),
                "give a gap of 0 mm or more".to_string(),
            );
        }
        if stock.is_some() && self.rotations.angles().is_none() {
            let (value, reason) = match &self.rotations {
                Rotations::Step(step) => (
                    format!("step:{step}"),
                    format!(
                        "rotation step {step} degrees is invalid: give a step in [{}, 360]",
                        crate::nest::MINIMUM_ROTATION_STEP_DEGREES
                    ),
                ),
                other => (
                    format!("{other:?}"),
                    "give at least one angle, every one finite".to_string(),
                ),
            };
            return invalid("--rotations", value, reason);
        }
        Ok(())
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

impl RunConfig {
    /// Checks every option that can be checked before any input is read: the tolerance in
    /// (0, [`MAXIMUM_TOLERANCE`]], the pattern's lengths and the nesting options on the stock
    /// ([`NestingConfig::validate`]). The error names the command-line option.
    pub fn validate(&self) -> Result<(), Error> {
        let tolerance = self.options.flatten.tolerance;
        if !(tolerance.is_finite() && tolerance > 0.0 && tolerance <= MAXIMUM_TOLERANCE) {
            return invalid(
                "--tolerance",
                tolerance.to_string(),
                format!("give a fraction above 0 and at most {MAXIMUM_TOLERANCE} (0.01 is 1 %)"),
            );
        }
        let k_factor = self.options.sheet.k_factor;
        if !self.options.sheet.is_valid() {
            return invalid(
                "--k-factor",
                figure(k_factor),
                "give the neutral fibre's place as a fraction of the thickness, 0 to 1".to_owned(),
            );
        }
        let time_limit = self.options.time_limit_seconds;
        if !(time_limit > 0.0 && time_limit <= MAXIMUM_PART_TIME_LIMIT) {
            return invalid(
                "--time-limit",
                figure(time_limit),
                format!(
                    "give a part's limit in seconds, above 0 and at most {MAXIMUM_PART_TIME_LIMIT}"
                ),
            );
        }
        self.pattern.validate()?;
        self.options.overrides.validate()?;
        self.nesting.validate(self.stock)
    }
}

/// The error of an option out of its range.
fn invalid(option: &'static str, value: String, reason: String) -> Result<(), Error> {
    Err(Error::InvalidOption {
        option,
        value,
        reason,
    })
}

/// A figure as given, or in exponent form when it is huge (`1e300`, not 301 digits).
fn figure(value: f64) -> String {
    if value.is_finite() && value.abs() >= 1e15 {
        format!("{value:e}")
    } else {
        value.to_string()
    }
}

#[cfg(test)]
mod tests {
    use crate::pipeline::config::*;

    fn refused(config: &RunConfig) -> String {
        match config.validate() {
            Err(error @ Error::InvalidOption { .. }) => error.to_string(),
            other => panic!("expected an invalid option, got {other:?}"),
        }
    }

    #[test]
    fn absurd_options_are_refused_naming_the_option() {
        assert!(RunConfig::default().validate().is_ok());
        let mut config = RunConfig::default();
        config.options.flatten.tolerance = 1.0;
        assert!(refused(&config).starts_with("--tolerance 1:"));
        config.options.flatten.tolerance = 0.01;
        for limit in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e300] {
            config.options.time_limit_seconds = limit;
            assert!(refused(&config).starts_with("--time-limit"), "{limit}");
        }
        let mut config = RunConfig {
            stock: Some(Stock::Sheets {
                width: f64::INFINITY,
                height: 100.0,
            }),
            ..RunConfig::default()
        };
        assert!(refused(&config).starts_with("--sheet infx100:"));
        config.stock = Some(Stock::Roll { width: 0.0 });
        assert!(refused(&config).contains("roll width is 0 mm"));
        config.stock = Some(Stock::Roll { width: 100.0 });
        config.nesting.gap = -5.0;
        assert!(refused(&config).starts_with("--gap -5:"));
    }
}
