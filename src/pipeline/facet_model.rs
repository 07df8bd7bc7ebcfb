//! The facet model of one input, as `flatcut tessellate` writes it: a part file or a STEP file
//! tessellated (a mesh file taken as it is), validated, and written as one OBJ holding every
//! component.

use std::path::Path;

use crate::cad::TriangleSoup;
use crate::error::Error;
use crate::export::ExportError;
use crate::export::obj::mesh_obj;
use crate::export::write_atomically;
use crate::ingest::{Input, read_input};
use crate::mesh::validate;
use crate::tessellate::{TessellateOptions, TessellationFigures};
use crate::units::Units;

use super::load::{tessellate_part, tessellate_step};

/// Where a facet model came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FacetSource {
    /// A part file's surfaces, tessellated, in the part's units.
    Part {
        /// The part's units.
        units: Units,
        /// The tessellation's figures.
        figures: TessellationFigures,
    },
    /// A STEP file's faces, tessellated, in millimetres.
    Step {
        /// The tessellation's figures.
        figures: TessellationFigures,
    },
    /// A mesh file, as read.
    Mesh,
}

/// A validated facet model of one input.
#[derive(Debug, Clone)]
pub struct FacetModelOutput {
    /// Every component's triangles, with the fold-edge tags.
    pub soup: TriangleSoup,
    /// What it was made from.
    pub source: FacetSource,
    /// Repairs validation made, as messages.
    pub warnings: Vec<String>,
}

/// Reads `path` (meshes in `units`), tessellates it when it is a part or STEP file, and validates
/// the result.
pub fn facet_model(
    path: &Path,
    units: Units,
    options: &TessellateOptions,
) -> Result<FacetModelOutput, Error> {
    let (soup, source) = match read_input(path, units)? {
        Input::Part(part) => {
            let tessellation = tessellate_part(path, &part, options)?;
            let source = FacetSource::Part {
                units: part.units,
                figures: tessellation.figures,
            };
            (tessellation.soup().clone(), source)
        }
        Input::Step(brep) => {
            let tessellation = tessellate_step(path, &brep, options)?;
            let source = FacetSource::Step {
                figures: tessellation.figures,
            };
            (tessellation.soup().clone(), source)
        }
        Input::Mesh(mesh) => (mesh.soup, FacetSource::Mesh),
    };
    let validated = validate(&soup).map_err(|defects| Error::FacetModel {
        path: path.to_path_buf(),
        defects,
    })?;
    let warnings = validated
        .warnings
        .iter()
        .map(|warning| warning.located(&soup.source_lines))
        .collect();
    Ok(FacetModelOutput {
        soup,
        source,
        warnings,
    })
}

/// Writes the facet model as OBJ to `path`, under the comment `header`.
pub fn write_facet_model(model: &FacetModelOutput, header: &str, path: &Path) -> Result<(), Error> {
    let text = mesh_obj(header, &model.soup.positions, &model.soup.triangles);
    write_atomically(path, text.as_bytes()).map_err(|source| {
        Error::Export(ExportError::Write {
            path: path.to_path_buf(),
            source,
        })
    })
}
