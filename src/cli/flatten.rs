//! `flatcut flatten INPUT -o OUT/`: flatten parts and write their patterns, facet models and the
//! report. Its arguments are shared by `flatcut run`.

use std::path::{Path, PathBuf};

use clap::Args;

use flatcut::cut::CutOptions;
use flatcut::flatten::{FlattenOptions, Solver};
use flatcut::mesh::SeamSource;
use flatcut::pattern::PatternOptions;
use flatcut::pipeline::{PartOverrides, RunConfig, RunOptions};
use flatcut::progress::Progress;
use flatcut::sheet::{BendRule, BendTable, SheetOptions};
use flatcut::units::Units;

use super::job::execute;
use super::outcome::Outcome;
use super::parse::DxfVersionArg;

/// Arguments shared by `flatten` and `run`.
#[derive(Debug, Args)]
pub struct FlattenArgs {
    /// Input parts: part files (.toml), STEP files (.step, .stp), triangle meshes (.obj, .stl).
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Output directory (created if missing).
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    #[command(flatten)]
    part: PartArgs,
    /// Print the report to stdout as JSON.
    #[arg(long)]
    json: bool,
    /// Write 0 for every `seconds` in the report, so reports of the same input are byte-identical.
    #[arg(long)]
    no_timings: bool,
}

/// How each part is loaded, flattened, cut and drawn: the options `flatten`, `run` and `batch`
/// share.
#[derive(Debug, Args)]
pub struct PartArgs {
    /// Permissible area and shape error E_S, E_C (fractions: 0.01 is 1 %; at most 0.5).
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
    /// Where a part's pieces come from: `auto` (each connected mesh is one part, opened by the
    /// cut stage's seams and cut along crest lines; a part still over tolerance after them, or
    /// one with handles, is cut into pieces as by `pieces`), `whole` (as `auto`, but such a part
    /// is rejected whole), `from-uv` (each chart of the OBJ's texture layout, `vt`, is one part:
    /// a garment's sewing pattern pieces, their layout the start of the flattening) or `pieces`
    /// (no crest-line cut: a part over tolerance is cut by plane sections into pieces
    /// `<part>-p1`, `-p2`, ... until each is within tolerance).
    #[arg(long, value_enum, default_value_t = SeamSource::default())]
    seams: SeamSource,
    /// Repair a mesh file's connectivity, with a warning for each change: weld vertices at the
    /// same point, split edges shared by more than two triangles (keeping together, in pairs,
    /// those the texture layout continues across the edge) and vertices joining separate fans
    /// (after `--seams from-uv` has cut the texture charts apart).
    #[arg(long)]
    repair: bool,
    /// DXF version of the cut files: `r2000` (LWPOLYLINE, units in the header) or `r12` for old
    /// controllers.
    #[arg(long, value_enum, default_value_t = DxfVersionArg::R2000)]
    dxf_version: DxfVersionArg,
    /// Chord tolerance of the DXF cut contours in mm: the written contour (lines and arcs) stays
    /// this close to the pattern's outline. (`--chord` is the tessellation's.)
    #[arg(long, value_name = "MM", default_value_t = PatternOptions::default().chord_tolerance)]
    dxf_chord: f64,
    /// Seam allowance in mm for garments: the cut contour is offset outward by it, and the
    /// pattern's outline goes to the sew layer.
    #[arg(long, value_name = "MM")]
    seam_allowance: Option<f64>,
    #[command(flatten)]
    sizes: super::tessellate::MeshSizeArgs,
    /// How many copies of each part to cut, over what its file says (a mesh says 1).
    #[arg(long, value_name = "N")]
    quantity: Option<u32>,
    /// Material of the parts, over what their files say: printed on the label; parts of
    /// different materials are nested on separate stock.
    #[arg(long, value_name = "NAME")]
    material: Option<String>,
    /// Sheet thickness of the parts in mm, over what their files say.
    #[arg(long, value_name = "MM")]
    thickness: Option<f64>,
    /// K-factor of the bends of STEP solids recognised as sheet metal: where the neutral fibre
    /// lies, as a fraction of the thickness from the inside of the bend (bend allowance
    /// θ · (R + K · t)).
    #[arg(long, value_name = "K", default_value_t = SheetOptions::default().k_factor)]
    k_factor: f64,
    /// Longest a part's flattening and cutting may run, in seconds: a part still over tolerance
    /// then is rejected, with the reason, and the run exits with 3.
    #[arg(long, value_name = "S", default_value_t = RunOptions::default().time_limit_seconds)]
    time_limit: f64,
    /// Where the bend allowances of sheet-metal solids come from: `k-factor` (θ · (R + K · t),
    /// `--k-factor`) or `din6935` (DIN 6935's correction factor k = 0.65 + 0.5 · log10(R/t),
    /// BA = θ · (R + k · t / 2)). `--bend-table` gives a bend table instead.
    #[arg(long, value_enum, default_value_t = BendRuleArg::KFactor, conflicts_with = "bend_table")]
    bend_rule: BendRuleArg,
    /// A bend table (CSV: thickness, inner_radius, angle and one of k, ba, bd; optionally
    /// material, matched against the part's): each bend's allowance interpolated in it
    /// (docs/sheet-metal.md). A bend outside the table is an error.
    #[arg(long, value_name = "FILE")]
    bend_table: Option<PathBuf>,
    /// The STEP entity id of the ADVANCED_FACE a sheet-metal solid is unfolded from (a planar
    /// face of one of its skins; its side is drawn), instead of the largest planar face.
    #[arg(long, value_name = "ID", value_parser = parse_entity_id)]
    base_face: Option<u64>,
    /// Also draw each bend's two tangent lines (the bend zone's extent) on the BEND_ZONE layer.
    #[arg(long)]
    bend_zones: bool,
}

/// The bend rules `--bend-rule` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum BendRuleArg {
    /// One K-factor for every bend (`--k-factor`).
    KFactor,
    /// DIN 6935.
    Din6935,
}

/// An entity id, `17` or `#17`.
fn parse_entity_id(text: &str) -> Result<u64, String> {
    text.trim_start_matches('#')
        .parse()
        .map_err(|_| format!("{text:?} is not a STEP entity id (give 17 or #17)"))
}

impl FlattenArgs {
    /// The output directory.
    pub fn output(&self) -> &Path {
        &self.output
    }

    /// Whether the report goes to stdout too.
    pub fn json(&self) -> bool {
        self.json
    }

    /// The run's configuration, converted in one place (no stock: nesting is `run`'s).
    pub fn config(&self) -> anyhow::Result<RunConfig> {
        Ok(RunConfig {
            inputs: self.inputs.clone(),
            timings: !self.no_timings,
            ..self.part.config()?
        })
    }
}

impl PartArgs {
    /// The bend rule: the table read and checked when one is given.
    fn bend_rule(&self) -> anyhow::Result<BendRule> {
        Ok(match (&self.bend_table, self.bend_rule) {
            (Some(path), _) => BendRule::Table(BendTable::read(path).map_err(anyhow::Error::msg)?),
            (None, BendRuleArg::KFactor) => BendRule::KFactor,
            (None, BendRuleArg::Din6935) => BendRule::Din6935,
        })
    }

    /// The options of every part as a run's configuration with no inputs, converted in one
    /// place.
    pub fn config(&self) -> anyhow::Result<RunConfig> {
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
        let options = RunOptions {
            units: self.units,
            seams: self.seams,
            repair: self.repair,
            flatten,
            cut,
            tessellate: self.sizes.options()?,
            overrides: PartOverrides {
                name: None,
                quantity: self.quantity,
                material: self.material.clone(),
                thickness_mm: self.thickness,
            },
            sheet: SheetOptions {
                k_factor: self.k_factor,
                rule: self.bend_rule()?,
                base_face: self.base_face,
            },
            time_limit_seconds: self.time_limit,
        };
        Ok(RunConfig {
            options,
            pattern: PatternOptions {
                chord_tolerance: self.dxf_chord,
                seam_allowance: self.seam_allowance,
                bend_zones: self.bend_zones,
            },
            dxf_version: self.dxf_version.into(),
            ..RunConfig::default()
        })
    }
}

/// Runs `flatten`: every input is read and checked before anything is written.
pub fn run(args: FlattenArgs, progress: &dyn Progress) -> anyhow::Result<Outcome> {
    let config = args.config()?;
    execute(&config, args.output(), args.json(), progress)
}
