//! The pipeline for one input: ingest, validate (one part per connected component), flatten.
//! Values in, values out; the binary writes the files through [`crate::export`].

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::cut::{Cut, CutConstraints, CutOptions, CutStop, Seam, cut_and_flatten};
use crate::error::Error;
use crate::flatten::{FlattenOptions, Flattened, Stiffness};
use crate::ingest::{read_cut_sidecar, read_mesh};
use crate::mesh::{FacetModel, validate};
use crate::progress::Progress;
use crate::units::Units;

/// Options of a run, echoed in the report.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct RunOptions {
    /// Units of mesh files (part files and STEP files carry their own).
    pub units: Units,
    /// Flattening options.
    pub flatten: FlattenOptions,
    /// Cutting options (seams, crest-line cuts).
    pub cut: CutOptions,
}

/// One part ready to flatten: a connected facet model with its stiffness map.
#[derive(Debug, Clone)]
pub struct PartJob {
    /// Part name (the file stem, with `-N` when the file holds several components).
    pub name: String,
    /// The input file.
    pub source: PathBuf,
    /// Units of the coordinates.
    pub units: Units,
    /// How many copies to cut.
    pub quantity: u32,
    /// The facet model.
    pub model: FacetModel,
    /// Per-edge stiffness factors.
    pub stiffness: Stiffness,
    /// User seams and no-cut regions (from the part's sidecar file).
    pub constraints: CutConstraints,
    /// Repairs made to the input, as messages.
    pub warnings: Vec<String>,
}

/// A flattened part.
#[derive(Debug, Clone)]
pub struct PartResult {
    /// What was flattened: its model and stiffness are those after seams and cuts.
    pub job: PartJob,
    /// The pattern of the cut model and its figures.
    pub flattened: Flattened,
    /// Seams made to open the part.
    pub seams: Vec<Seam>,
    /// Crest-line cuts made.
    pub cuts: Vec<Cut>,
    /// Why cutting stopped.
    pub cut_stop: CutStop,
}

/// Reads an input file and splits it into parts, one per connected component.
pub fn load_parts(path: &Path, options: &RunOptions) -> Result<Vec<PartJob>, Error> {
    let input = read_mesh(path, options.units)?;
    let validated = validate(&input.soup).map_err(|defects| Error::Mesh {
        path: path.to_path_buf(),
        defects,
    })?;
    let warnings: Vec<String> = validated.warnings.iter().map(ToString::to_string).collect();
    let several = validated.components.len() > 1;
    let constraints = read_cut_sidecar(path, validated.components.len())?.unwrap_or_default();
    Ok(validated
        .components
        .into_iter()
        .enumerate()
        .map(|(i, model)| PartJob {
            name: if several {
                format!("{}-{}", input.name, i + 1)
            } else {
                input.name.clone()
            },
            source: path.to_path_buf(),
            units: input.units,
            quantity: 1,
            stiffness: Stiffness::uniform(&model),
            constraints: constraints.clone(),
            model,
            warnings: warnings.clone(),
        })
        .collect())
}

/// Flattens one part, with seams and crest-line cuts until it is within tolerance or the cut
/// budget is spent.
pub fn flatten_part(
    mut job: PartJob,
    options: &RunOptions,
    progress: &dyn Progress,
) -> Result<PartResult, Error> {
    let result = cut_and_flatten(
        &job.model,
        &job.stiffness,
        &job.constraints,
        &options.flatten,
        &options.cut,
        progress,
    )
    .map_err(|reason| Error::Cut {
        path: job.source.clone(),
        part: job.name.clone(),
        reason,
    })?;
    job.model = result.model;
    job.stiffness = result.stiffness;
    Ok(PartResult {
        job,
        flattened: result.flattened,
        seams: result.seams,
        cuts: result.cuts,
        cut_stop: result.stop,
    })
}
