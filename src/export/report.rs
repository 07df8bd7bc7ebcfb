//! `report.json`: the figures scripts read. Keys keep their names and meanings across versions;
//! new keys may be added (bump [`SCHEMA_VERSION`] only when a meaning changes).
//!
//! Everything in it is deterministic for the same input and options except `seconds`, which
//! `--no-timings` writes as 0 for byte-identical reports.

use std::path::Path;

use serde::Serialize;

use super::atomic::write_atomically;
use super::errors::ExportError;

use super::dxf_options::DxfVersion;
use super::energy_png::EnergyPngOptions;
use crate::cut::{Cut, CutFigures, CutOptions, CutStop, Seam, SeamKind};
use crate::flatten::{FlattenOptions, Solver, StopReason};
use crate::mesh::SeamSource;
use crate::nest::{NestLayout, Rotations, Stock};
use crate::pattern::PatternOptions;
use crate::sheet::{AllowanceRule, BendDirection, BendLine};
use crate::tessellate::TessellateOptions;
use crate::units::Units;

/// Version of the report's layout.
pub const SCHEMA_VERSION: u32 = 1;

/// The whole report.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The flatcut version that wrote it.
    pub flatcut_version: String,
    /// The options of the run.
    pub options: ReportOptions,
    /// One entry per part.
    pub parts: Vec<PartReport>,
    /// One entry per nested sheet or roll (empty without nesting).
    pub sheets: Vec<SheetReport>,
}

/// The options of a run, as the report records them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportOptions {
    /// Units of mesh files (part files and STEP files carry their own).
    pub units: Units,
    /// Where the pieces of mesh files came from, when not the default (left out otherwise).
    #[serde(skip_serializing_if = "SeamSource::is_default")]
    pub seams: SeamSource,
    /// Whether mesh files were repaired (`--repair`), when they were (left out otherwise).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub repair: bool,
    /// Flattening options.
    pub flatten: FlattenOptions,
    /// Cutting options (seams, crest-line cuts).
    pub cut: CutOptions,
    /// Tessellation of part and STEP files.
    pub tessellate: TessellateOptions,
    /// Chord tolerance of the cut contours (mm) and seam allowance (mm, `null` for none).
    pub pattern: PatternOptions,
    /// DXF version of the cut files: `r2000` or `r12`.
    pub dxf_version: DxfVersion,
    /// Size and colour scale of the energy pictures.
    pub energy_png: EnergyPngOptions,
    /// How the patterns were nested; `null` without stock.
    pub nesting: Option<NestingReport>,
    /// A part's time limit in seconds, when not the default (left out otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub part_time_limit_seconds: Option<f64>,
}

/// The nesting options of a run with stock.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NestingReport {
    /// The stock: sheets (width, height) or a roll (width), mm.
    pub stock: Stock,
    /// Gap between parts and to the stock edge, mm.
    pub gap: f64,
    /// Search budget, seconds.
    pub time_limit_seconds: f64,
    /// Seed of the search.
    pub seed: u64,
    /// Work budget in collision queries, when given (`--work`).
    pub work_limit: Option<u64>,
    /// Rotations allowed, degrees from each pattern's minimum-area bounding rectangle.
    pub rotations: Rotations,
    /// Whether small parts could go inside the holes of larger ones.
    pub in_holes: bool,
    /// Whether parts could be mirrored.
    pub mirror: bool,
}

/// Figures of the tessellation a part came from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TessellationReport {
    /// Target edge length used (part units).
    pub mesh_size: f64,
    /// Chord tolerance used (part units).
    pub chord: f64,
    /// Smallest triangle angle of the whole part's mesh, degrees.
    pub minimum_angle: f64,
}

/// Figures of one part.
#[derive(Debug, Clone, Serialize)]
pub struct PartReport {
    /// Part name; its files are `<name>.*`.
    pub name: String,
    /// The input file.
    pub source: String,
    /// Units of every length.
    pub units: &'static str,
    /// Copies to cut.
    pub quantity: u32,
    /// Triangles of the facet model.
    pub triangles: usize,
    /// Vertices of the facet model.
    pub vertices: usize,
    /// `E_S` (Eq. 4), a fraction.
    pub area_error: f64,
    /// `E_C` (Eq. 6), a fraction.
    pub shape_error: f64,
    /// Largest relative edge length change.
    pub max_strain: f64,
    /// Flipped triangles in the pattern.
    pub flipped: usize,
    /// Whether the pattern overlaps itself.
    pub overlap: bool,
    /// Phase-two iterations.
    pub iterations: usize,
    /// Why phase two stopped.
    pub stop_reason: StopReason,
    /// The permissible `E_S` and `E_C`.
    pub tolerance: f64,
    /// Both errors within the tolerance and no overlap.
    pub tolerance_met: bool,
    /// Wall-clock seconds for the part: seams, cuts and every flattening (0 with `--no-timings`).
    pub seconds: f64,
    /// The solver used.
    pub solver: Solver,
    /// Spring energy of the pattern.
    pub energy: f64,
    /// `E_S` after phase one.
    pub initial_area_error: f64,
    /// `E_C` after phase one.
    pub initial_shape_error: f64,
    /// Crest-line cuts made (3D polylines), in order.
    pub cuts: Vec<CutReport>,
    /// Total 3D length of the cuts (seams not included).
    pub total_cut_length: f64,
    /// Why cutting stopped: `tolerance_met`, `cut_budget` (`--max-cuts` reached) or
    /// `no_better_cut`.
    pub cut_stop: CutStop,
    /// Seams made to open a closed or ring surface, or given by the user.
    pub seams: Vec<SeamReport>,
    /// Fold lines and how well their length was kept.
    pub fold_lines: Vec<FoldLineReport>,
    /// Tessellation figures (mesh size, chord, smallest angle) for parts made from surfaces.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tessellation: Option<TessellationReport>,
    /// Repairs made to the input.
    pub warnings: Vec<String>,
    /// Why the part is rejected (over tolerance, flipped triangles, overlap; its cut file is then
    /// `<part>.REJECTED.dxf`); left out of the JSON when the part is accepted.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rejected: Vec<String>,
    /// For a STEP solid unfolded as sheet metal: thickness, K-factor, bends and flat size; left
    /// out for any other part.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sheet_metal: Option<SheetMetalReport>,
}

/// A sheet-metal part's unfold. Lengths in mm, angles in degrees.
#[derive(Debug, Clone, Serialize)]
pub struct SheetMetalReport {
    /// The sheet's thickness.
    pub thickness: f64,
    /// The K-factor every bend was unrolled with, when the rule is the K-factor (each bend's
    /// `rule` says what gave its allowance).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_factor: Option<f64>,
    /// The bend rule: `K 0.44`, `DIN 6935` or `bend table FILE`.
    pub bend_rule: String,
    /// The face the unfold started from: the largest planar face, whose side is drawn.
    pub base_face: String,
    /// Every bend.
    pub bends: Vec<BendReport>,
    /// The flat pattern's extent along x (its longer side).
    pub flat_width: f64,
    /// The flat pattern's extent along y.
    pub flat_height: f64,
    /// The flat pattern's area: the outer contour's less its holes'.
    pub flat_area: f64,
}

/// One bend of a sheet-metal part.
#[derive(Debug, Clone, Serialize)]
pub struct BendReport {
    /// How far the flange turns, degrees.
    pub angle: f64,
    /// Inner radius.
    pub inner_radius: f64,
    /// `up` or `down`, seen on the flat pattern as drawn.
    pub direction: BendDirection,
    /// Bend allowance: the flat width of the bend zone.
    pub allowance: f64,
    /// The rule that gave the allowance, with its figures: `k_factor` (`k`), `table` (`file`,
    /// `quantity`, the interpolated `value`, the rows' `lines`) or `din6935` (its correction
    /// factor `k` and compensation `v`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rule: Option<AllowanceRule>,
    /// Length of the bend line.
    pub length: f64,
    /// For a bend on a cone (whose `inner_radius` and `allowance` are the figures at the middle
    /// of its bend line): the figures at the line's two ends; left out for a bend on a cylinder.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub conical: Option<ConicalBendReport>,
}

/// What a bend on a cone adds to its report. Lengths in mm, angles in degrees.
#[derive(Debug, Clone, Serialize)]
pub struct ConicalBendReport {
    /// The inner radius at the bend line's two ends.
    pub inner_radius_ends: [f64; 2],
    /// The allowance (the bend zone's flat width) at the two ends.
    pub allowance_ends: [f64; 2],
    /// The developed angle `θ_c`: the allowance is `θ_c · (R + K · t)` at every point of the
    /// bend line.
    pub developed_angle: f64,
}

impl BendReport {
    /// The report of a bend line.
    pub fn new(bend: &BendLine) -> Self {
        Self {
            angle: bend.angle_degrees,
            inner_radius: bend.inner_radius,
            direction: bend.direction,
            allowance: bend.allowance,
            rule: bend.rule.clone(),
            length: bend.length(),
            conical: bend.conical.as_ref().map(|cone| ConicalBendReport {
                inner_radius_ends: cone.inner_radii,
                allowance_ends: cone.allowances,
                developed_angle: cone.developed_angle_degrees,
            }),
        }
    }
}

/// One nested sheet, or the used part of a roll. Lengths in mm.
#[derive(Debug, Clone, Serialize)]
pub struct SheetReport {
    /// The sheet's DXF, relative to the output directory.
    pub file: String,
    /// Sheet width (on a roll: the length used).
    pub width: f64,
    /// Sheet height (on a roll: the roll width).
    pub height: f64,
    /// On a roll, the length used; absent for sheets.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// The parts placed on it.
    pub parts: Vec<PlacementReport>,
    /// Net part area over sheet area.
    pub utilisation: f64,
}

/// One part placed on a sheet: its outline is mirrored in x (when `mirrored`), rotated by
/// `rotation` degrees counter-clockwise about the pattern's origin, then moved by `(x, y)`.
#[derive(Debug, Clone, Serialize)]
pub struct PlacementReport {
    /// Part name.
    pub name: String,
    /// Which copy of the part (from 0).
    pub copy: u32,
    /// Rotation, degrees counter-clockwise.
    pub rotation: f64,
    /// Mirrored before rotating.
    pub mirrored: bool,
    /// Translation along x, mm.
    pub x: f64,
    /// Translation along y, mm.
    pub y: f64,
}

/// One cut.
#[derive(Debug, Clone, Serialize)]
pub struct CutReport {
    /// Length in model units.
    pub length: f64,
    /// The 3D polyline.
    pub points: Vec<[f64; 3]>,
    /// Energy and errors of the pattern before the cut.
    pub before: CutFigures,
    /// Energy and errors of the pattern after the cut.
    pub after: CutFigures,
}

impl CutReport {
    /// The report of a cut.
    pub fn new(cut: &Cut) -> Self {
        Self {
            length: cut.length,
            points: cut.points.iter().map(|p| p.to_array()).collect(),
            before: cut.before,
            after: cut.after,
        }
    }
}

/// One seam.
#[derive(Debug, Clone, Serialize)]
pub struct SeamReport {
    /// Why it was made: `user`, `ring`, `closed` or `corner`.
    pub kind: SeamKind,
    /// Length in model units.
    pub length: f64,
    /// The 3D polyline.
    pub points: Vec<[f64; 3]>,
}

impl SeamReport {
    /// The report of a seam.
    pub fn new(seam: &Seam) -> Self {
        Self {
            kind: seam.kind,
            length: seam.length,
            points: seam.points.iter().map(|p| p.to_array()).collect(),
        }
    }
}

/// One fold line.
#[derive(Debug, Clone, Serialize)]
pub struct FoldLineReport {
    /// Length on the surface.
    pub length_3d: f64,
    /// Length in the pattern.
    pub length_flat: f64,
    /// Relative difference.
    pub error: f64,
}

impl Report {
    /// A report with no sheets.
    pub fn new(options: ReportOptions, parts: Vec<PartReport>) -> Self {
        Self {
            schema_version: SCHEMA_VERSION,
            flatcut_version: env!("CARGO_PKG_VERSION").to_string(),
            options,
            parts,
            sheets: Vec::new(),
        }
    }

    /// Writes [`Report::to_json`] to `directory/report.json`, atomically.
    pub fn write(&self, directory: &Path) -> Result<(), ExportError> {
        let path = directory.join("report.json");
        write_atomically(&path, self.to_json().as_bytes())
            .map_err(|source| ExportError::Write { path, source })
    }

    /// Pretty JSON with a final newline.
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self)
            .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
        text.push('\n');
        text
    }
}

/// The report entries of a nested layout; `names[i]` is the name of nesting item `i` and
/// `files[k]` the DXF of sheet `k`.
pub fn sheet_reports(
    layout: &NestLayout,
    names: &[String],
    files: &[std::path::PathBuf],
) -> Vec<SheetReport> {
    let on_roll = matches!(layout.stock, Stock::Roll { .. });
    layout
        .sheets
        .iter()
        .zip(files)
        .map(|(sheet, file)| SheetReport {
            file: file.display().to_string(),
            width: sheet.width,
            height: sheet.height,
            length: on_roll.then_some(sheet.used_length),
            parts: sheet
                .placements
                .iter()
                .map(|placement| PlacementReport {
                    name: names[placement.item].clone(),
                    copy: placement.copy,
                    rotation: placement.rotation_degrees,
                    mirrored: placement.mirrored,
                    x: placement.translation.x,
                    y: placement.translation.y,
                })
                .collect(),
            utilisation: sheet.utilisation,
        })
        .collect()
}
