//! Loading one input: ingest, tessellate (part files), validate (one part per connected
//! component), stiffness (fold lines, regions).

use std::path::{Path, PathBuf};

use glam::DVec3;
use serde::Serialize;

use crate::cut::CutConstraints;
use crate::error::Error;
use crate::flatten::Stiffness;
use crate::ingest::part::{PartAttributes, PartInput, RegionShape};
use crate::ingest::{Input, read_cut_sidecar, read_input};
use crate::mesh::{FacetModel, TriangleSoup, validate};
use crate::tessellate::parameter_region::ParameterRegion;
use crate::tessellate::surface_domain::SurfaceDomain;
use crate::tessellate::{TessellateOptions, Tessellation, tessellate};
use crate::units::Units;

use super::config::RunOptions;

/// Figures of the tessellation a part came from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TessellationFigures {
    /// Target edge length used (part units).
    pub mesh_size: f64,
    /// Chord tolerance used (part units).
    pub chord: f64,
    /// Smallest triangle angle of the whole part's mesh, degrees.
    pub minimum_angle: f64,
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
    /// Material, thickness and grain direction from a part file.
    pub attributes: PartAttributes,
    /// Number of fold lines of the part (edge tags on the model index them).
    pub fold_line_count: u32,
    /// Tessellation figures, for parts made from surfaces.
    pub tessellation: Option<TessellationFigures>,
    /// The facet model.
    pub model: FacetModel,
    /// Per-edge stiffness factors.
    pub stiffness: Stiffness,
    /// User seams and no-cut regions (from the part's sidecar file).
    pub constraints: CutConstraints,
    /// Repairs made to the input, as messages.
    pub warnings: Vec<String>,
}

/// Reads an input file (mesh, part file or STEP file) and splits it into parts, one per
/// connected component.
pub fn load_parts(path: &Path, options: &RunOptions) -> Result<Vec<PartJob>, Error> {
    match read_input(path, options.units, &options.tessellate)? {
        Input::Mesh(mesh) => {
            let template = template(mesh.name, mesh.units);
            split_parts(path, &mesh.soup, template, |_, _| {})
        }
        Input::Step(step) => {
            let mut template = template(step.name, Units::Millimetres);
            template.tessellation = Some(TessellationFigures {
                mesh_size: step.mesh_size,
                chord: step.chord,
                minimum_angle: step.minimum_angle,
            });
            split_parts(path, &step.soup, template, |_, _| {})
        }
        Input::Part(part) => load_part_file(path, &part, &options.tessellate),
    }
}

/// Tessellates a part file's surfaces (for `flatcut tessellate` and the pipeline).
pub fn tessellate_part(
    path: &Path,
    part: &PartInput,
    options: &TessellateOptions,
) -> Result<Tessellation, Error> {
    tessellate(&part.cad, options).map_err(|defect| Error::Tessellate {
        path: path.to_path_buf(),
        defect,
    })
}

/// What every part of one input file shares.
#[derive(Debug, Clone)]
struct PartHeader {
    name: String,
    units: Units,
    quantity: u32,
    attributes: PartAttributes,
    fold_line_count: u32,
    tessellation: Option<TessellationFigures>,
}

fn template(name: String, units: Units) -> PartHeader {
    PartHeader {
        name,
        units,
        quantity: 1,
        attributes: PartAttributes::default(),
        fold_line_count: 0,
        tessellation: None,
    }
}

fn load_part_file(
    path: &Path,
    part: &PartInput,
    options: &TessellateOptions,
) -> Result<Vec<PartJob>, Error> {
    let tessellation = tessellate_part(path, part, options)?;
    let mut template = template(part.name.clone(), part.units);
    template.quantity = part.quantity;
    template.attributes = part.attributes.clone();
    template.fold_line_count = part.fold_stiffness.len() as u32;
    template.tessellation = Some(TessellationFigures {
        mesh_size: tessellation.mesh_size,
        chord: tessellation.chord,
        minimum_angle: tessellation.minimum_angle,
    });
    let lookup = VertexLookup::new(tessellation.soup());
    split_parts(path, tessellation.soup(), template, |model, stiffness| {
        for (line, fold) in part.fold_stiffness.iter().enumerate() {
            let width = fold.width.unwrap_or(2.0 * tessellation.mesh_size);
            stiffness.raise_near_fold_line(model, line as u32, width / 2.0, fold.factor);
        }
        for region in &part.regions {
            let members = match &region.shape {
                RegionShape::Parameter { surface, polygon } => {
                    let domain = SurfaceDomain::new(&part.cad.surfaces[*surface]);
                    ParameterRegion::new(domain, polygon.clone())
                        .vertices_inside(&tessellation.welded, *surface as u32)
                }
                RegionShape::Box { .. } => Vec::new(),
            };
            stiffness.raise_where(region.factor, |edge| {
                let [a, b] = model.edges()[edge].map(|v| model.positions()[v as usize]);
                match &region.shape {
                    RegionShape::Box { min, max } => {
                        let midpoint = (a + b) * 0.5;
                        midpoint.cmpge(*min).all() && midpoint.cmple(*max).all()
                    }
                    RegionShape::Parameter { .. } => [a, b]
                        .iter()
                        .all(|&p| lookup.find(p).is_some_and(|v| members[v])),
                }
            });
        }
    })
}

/// Soup vertices sorted by position, to find the soup vertex of a model vertex (validation keeps
/// positions bit for bit).
struct VertexLookup {
    sorted: Vec<([u64; 3], usize)>,
}

impl VertexLookup {
    fn new(soup: &TriangleSoup) -> Self {
        let mut sorted: Vec<([u64; 3], usize)> = soup
            .positions
            .iter()
            .enumerate()
            .map(|(v, p)| (key(*p), v))
            .collect();
        sorted.sort_unstable();
        Self { sorted }
    }

    fn find(&self, position: DVec3) -> Option<usize> {
        let wanted = key(position);
        let index = self.sorted.partition_point(|(k, _)| *k < wanted);
        self.sorted
            .get(index)
            .filter(|(k, _)| *k == wanted)
            .map(|&(_, v)| v)
    }
}

fn key(p: DVec3) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// Validates a soup into one job per component, each with its stiffness set by `stiffen`.
fn split_parts(
    path: &Path,
    soup: &TriangleSoup,
    header: PartHeader,
    mut stiffen: impl FnMut(&FacetModel, &mut Stiffness),
) -> Result<Vec<PartJob>, Error> {
    let validated = validate(soup).map_err(|defects| Error::Mesh {
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
        .map(|(i, model)| {
            let mut stiffness = Stiffness::uniform(&model);
            stiffen(&model, &mut stiffness);
            PartJob {
                name: if several {
                    format!("{}-{}", header.name, i + 1)
                } else {
                    header.name.clone()
                },
                source: path.to_path_buf(),
                units: header.units,
                quantity: header.quantity,
                attributes: header.attributes.clone(),
                fold_line_count: header.fold_line_count,
                tessellation: header.tessellation,
                stiffness,
                constraints: constraints.clone(),
                model,
                warnings: warnings.clone(),
            }
        })
        .collect())
}
