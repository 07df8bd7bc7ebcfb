//! The library's top-level error: what went wrong, naming the file or part and the defect.

use std::path::PathBuf;

use crate::cut::CutError;
use crate::export::ExportError;
use crate::flatten::FlattenError;
use crate::ingest::IngestError;
use crate::mesh::{Defect, MeshDefects};
use crate::nest::NestError;
use crate::nest::verify::Violation;
use crate::pattern::{PatternError, PatternFileError};

/// What to do about `defects` that `--repair` mends, if there are any.
fn repair_hint(defects: &MeshDefects) -> &'static str {
    let mendable = defects.defects.iter().any(|defect| {
        matches!(
            defect,
            Defect::NonManifoldEdge { .. }
                | Defect::NonManifoldVertex { .. }
                | Defect::RepeatedTriangle { .. }
                | Defect::NonOrientable { .. }
        )
    });
    if mendable {
        "\n  (--repair welds vertices at the same point, drops duplicate faces, splits the \
         non-manifold edges and vertices and cuts a non-orientable surface open where its \
         orientations conflict, with a warning for each; a garment with its sewing \
         pattern as texture coordinates can also be cut into its pieces \
         with --seams from-uv)"
    } else {
        ""
    }
}

/// An error of a flatcut run.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An input file could not be read or parsed.
    #[error(transparent)]
    Ingest(#[from] IngestError),
    /// An input mesh has defects that stop it from being flattened.
    #[error("{path}: the mesh cannot be used: {defects}{}", repair_hint(defects))]
    Mesh {
        /// The input file.
        path: PathBuf,
        /// Every defect found.
        defects: MeshDefects,
    },
    /// The facet model `flatcut tessellate` made of an input has defects.
    #[error("{path}: the facet model cannot be used: {defects}")]
    FacetModel {
        /// The input file.
        path: PathBuf,
        /// Every defect found.
        defects: MeshDefects,
    },
    /// A part's surfaces could not be tessellated.
    #[error("{path}: cannot tessellate: {defect}")]
    Tessellate {
        /// The input file.
        path: PathBuf,
        /// Why.
        defect: crate::tessellate::TessellateError,
    },
    /// A STEP file's B-rep could not be tessellated.
    #[error("{path}: {defect}")]
    Brep {
        /// The input file.
        path: PathBuf,
        /// Why, naming the shell and face or the surface.
        defect: crate::tessellate::BrepError,
    },
    /// `--seams from-uv` was asked of an input without a texture layout.
    #[error("{path}: --seams from-uv: {reason}; use the default seams (--seams auto)")]
    SeamsFromUv {
        /// The input file.
        path: PathBuf,
        /// Why the input has no texture layout.
        reason: String,
    },
    /// A sheet-metal solid could not be unfolded as asked (a base face that is not a flange, a
    /// bend the bend rule does not cover).
    #[error("{path}: sheet metal: {reason}")]
    SheetMetal {
        /// The input file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// A part could not be flattened.
    #[error("{path}: part '{part}': {source}")]
    Flatten {
        /// The input file.
        path: PathBuf,
        /// The part's name.
        part: String,
        /// Why.
        source: FlattenError,
    },
    /// A part could not be opened by seams, cut or flattened after cutting.
    #[error("{path}: part '{part}': {reason}")]
    Cut {
        /// The input file.
        path: PathBuf,
        /// The part's name.
        part: String,
        /// Why (in the message, not repeated as a source).
        reason: CutError,
    },
    /// Two parts have one name: the second's files would overwrite the first's.
    #[error(
        "{}: part '{name}' has the name of a part from {}: its output files would overwrite \
         the other's; give one of them another name (`name = ...` in a part file, or rename the \
         file)",
        path.display(),
        earlier.display()
    )]
    DuplicateName {
        /// The input file of the second part.
        path: PathBuf,
        /// The name both parts have.
        name: String,
        /// The input file of the first part.
        earlier: PathBuf,
    },
    /// A part's pattern could not be made, or the pattern options are invalid.
    #[error(transparent)]
    Pattern(#[from] PatternError),
    /// The patterns could not be nested.
    #[error(transparent)]
    Nest(#[from] NestError),
    /// The independent check found defects in the nested layout.
    #[error(
        "the independent check rejected the nested layout:\n  {}",
        violations.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n  ")
    )]
    LayoutRejected {
        /// Every defect found.
        violations: Vec<Violation>,
    },
    /// Benchmark instances of different strip heights, with no stock given.
    #[error(
        "{}: strip_height differs from the first instance's: give --roll W or --sheet WxH",
        path.display()
    )]
    StripHeightDiffers {
        /// The instance whose strip height differs.
        path: PathBuf,
    },
    /// The nesting time budget is not a number of seconds.
    #[error("--time {seconds}: give a number of seconds, 0 or more")]
    InvalidTime {
        /// The rejected value.
        seconds: f64,
    },
    /// Nothing says what to nest on.
    #[error("give --sheet WxH or --roll W")]
    NoStock,
    /// The independent check found defects in a benchmark's layout.
    #[error(
        "the independent check rejected the layout ({} defects):\n  {}",
        violations.len(),
        violations.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n  ")
    )]
    BenchmarkLayoutRejected {
        /// Every defect found.
        violations: Vec<Violation>,
    },
    /// `flatcut nest` was given pattern inputs and benchmark instances together.
    #[error(
        "{} is a pattern input (a `.pattern.json` file or a folder of them) and {} a benchmark \
         instance: nest one kind at a time",
        pattern.display(),
        instance.display()
    )]
    MixedNestInputs {
        /// A pattern input.
        pattern: PathBuf,
        /// A benchmark instance.
        instance: PathBuf,
    },
    /// A folder given to `flatcut nest` holds no pattern file.
    #[error(
        "{}: no `*.pattern.json` file in this folder: give a run's output folder or pattern files",
        folder.display()
    )]
    NoPatternFiles {
        /// The folder.
        folder: PathBuf,
    },
    /// A pattern file or folder could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    ReadPatterns {
        /// The file or folder.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A pattern file is not one this flatcut reads.
    #[error("{}: {source}", path.display())]
    PatternFile {
        /// The file.
        path: PathBuf,
        /// Why.
        source: PatternFileError,
    },
    /// Two pattern files are of parts of one name: their sheets and reports would mix them up.
    #[error(
        "{}: part '{name}' has the name of the part of {}: give each part its own name",
        path.display(),
        earlier.display()
    )]
    DuplicatePattern {
        /// The second pattern file.
        path: PathBuf,
        /// The name both parts have.
        name: String,
        /// The first pattern file.
        earlier: PathBuf,
    },
    /// Pattern files of rejected parts were given without `--include-rejected`.
    #[error(
        "these parts were rejected (over tolerance, flipped triangles or overlap; their run's \
         report.json says why) and are not nested unless --include-rejected is given: {}",
        parts.iter().map(|(name, path)| format!("'{name}' ({})", path.display())).collect::<Vec<_>>().join(", ")
    )]
    RejectedPatterns {
        /// Each rejected part's name and pattern file.
        parts: Vec<(String, PathBuf)>,
    },
    /// Pattern files made with different pattern options, which the sheet drawings cannot mix.
    #[error(
        "{}: its cut contours are made with other pattern options (chord tolerance, seam \
         allowance) than those of {}: nest them separately, or flatten them again with the same \
         --dxf-chord and --seam-allowance",
        path.display(),
        earlier.display()
    )]
    PatternOptionsDiffer {
        /// The pattern file whose options differ.
        path: PathBuf,
        /// The first pattern file.
        earlier: PathBuf,
    },
    /// An option is out of its range (found before any input is read).
    #[error("{option} {value}: {reason}")]
    InvalidOption {
        /// The command-line option.
        option: &'static str,
        /// The value given.
        value: String,
        /// What is wrong and what to give instead.
        reason: String,
    },
    /// An input lies in the output folder under a name of the kind a run writes there.
    #[error(
        "{}: this input is in the output folder {} under a name of the kind a run writes \
         (`<part>.mesh.obj`, `.pattern.obj`, `.pattern.json`, `.dxf`, `.png`, `report.json`): the run would \
         overwrite or remove it; move it out of the folder or give another -o",
        input.display(),
        directory.display()
    )]
    InputInOutput {
        /// The input file.
        input: PathBuf,
        /// The output folder.
        directory: PathBuf,
    },
    /// Several inputs cannot be used: every one of them, in input order.
    #[error("{} inputs cannot be used:\n{}", errors.len(), bulleted(errors))]
    Inputs {
        /// Each input's error.
        errors: Vec<Error>,
    },
    /// The run was interrupted (SIGINT or SIGTERM) before it replaced the output folder's files.
    #[error("interrupted: the output folder keeps the previous run")]
    Interrupted,
    /// The output directory could not be created.
    #[error("{}: cannot create or write the output directory", path.display())]
    CreateDirectory {
        /// The directory.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// An output file could not be written or drawn.
    #[error(transparent)]
    Export(#[from] ExportError),
}

/// Each error on a line of its own, indented: `  - message`.
fn bulleted(errors: &[Error]) -> String {
    errors
        .iter()
        .map(|error| format!("  - {}", error.to_string().replace('\n', "\n    ")))
        .collect::<Vec<_>>()
        .join("\n")
}
