//! Loading one input: ingest, tessellate (part files), validate (one part per connected
//! component), stiffness (fold lines, regions). A STEP solid recognised as sheet metal is
//! unfolded here, exactly (see [`crate::sheet`]): its part is its chosen skin with the flat
//! pattern already made.

use std::path::{Path, PathBuf};

use glam::DVec2;

use crate::cad::{
    Brep, ParameterRegion, PartAttributes, PartModel, RegionShape, SurfaceDomain, SurfaceGeometry,
    TriangleSoup,
};
use crate::cut::{CutConstraints, NoCutRegion};
use crate::error::Error;
use crate::flatten::Stiffness;
use crate::ingest::{CutSidecar, Input, read_cut_sidecar, read_input};
use crate::mesh::{FacetModel, validate};
use crate::sheet::{
    BendLine, NotASheet, SHEET_CHORD_MM, SheetSurface, SheetUnfold, recognise_shell, unfold_skin,
};
pub use crate::tessellate::TessellationFigures;
use crate::tessellate::{
    TessellateOptions, Tessellation, tessellate_brep, tessellate_brep_for_unfold,
    tessellate_part as tessellate_cad, vertices_inside,
};
use crate::units::Units;

use super::config::{PartOverrides, RunOptions};
use super::step_defects::with_step_faces;

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
    /// The exact unfold, when the part is a sheet-metal solid (its model is then the chosen
    /// skin).
    pub sheet: Option<SheetPart>,
}

/// A sheet-metal part's exact unfold, made when it is loaded.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetPart {
    /// The flat position of each vertex of the part's model.
    pub flat: Vec<DVec2>,
    /// The bends, on the flat pattern.
    pub bends: Vec<BendLine>,
    /// The sheet's thickness, mm.
    pub thickness: f64,
    /// The K-factor the bends were unrolled with.
    pub k_factor: f64,
    /// The face the unfold started from, described (`ADVANCED_FACE #17 on PLANE (#31)`).
    pub base_face: String,
}

/// Reads an input file (mesh, part file or STEP file) and splits it into parts, one per
/// connected component.
pub fn load_parts(path: &Path, options: &RunOptions) -> Result<Vec<PartJob>, Error> {
    let mut jobs = read_parts(path, options)?;
    let several = jobs.len() > 1;
    for (index, job) in jobs.iter_mut().enumerate() {
        apply_overrides(job, &options.overrides);
        if let Some(name) = &options.overrides.name {
            job.name = if several {
                format!("{name}-{}", index + 1)
            } else {
                name.clone()
            };
        }
    }
    Ok(jobs)
}

/// Reads an input file into its parts, as the file describes them.
fn read_parts(path: &Path, options: &RunOptions) -> Result<Vec<PartJob>, Error> {
    match read_input(path, options.units)? {
        Input::Mesh(mesh) => {
            let template = template(mesh.name, mesh.units);
            split_parts(path, &mesh.soup, template, |_, _, _| {})
        }
        Input::Step(brep) => {
            let not_a_sheet = match sheet_metal_part(path, &brep, options)? {
                Ok(job) => return Ok(vec![job]),
                Err(reason) => reason,
            };
            let tessellation = tessellate_step(path, &brep, &options.tessellate)?;
            let mut template = template(brep.name.clone(), Units::Millimetres);
            template.tessellation = Some(tessellation.figures);
            let mut jobs = split_parts(path, tessellation.soup(), template, |_, _, _| {})
                .map_err(|error| with_step_faces(error, &brep, tessellation.soup()))?;
            if let Some(reason) = not_a_sheet {
                for job in &mut jobs {
                    job.warnings.push(format!(
                        "not unfolded as sheet metal ({reason}): flattened as a surface"
                    ));
                }
            }
            Ok(jobs)
        }
        Input::Part(part) => load_part_file(path, &part, &options.tessellate),
    }
}

/// Puts the quantity, material and thickness given for the part over the file's.
fn apply_overrides(job: &mut PartJob, overrides: &PartOverrides) {
    if let Some(quantity) = overrides.quantity {
        job.quantity = quantity;
    }
    if let Some(material) = &overrides.material {
        job.attributes.material = Some(material.clone());
    }
    if let Some(millimetres) = overrides.thickness_mm {
        job.attributes.thickness = Some(millimetres / job.units.millimetres());
    }
}

/// Tessellates a part file's surfaces (for `flatcut tessellate` and the pipeline).
pub fn tessellate_part(
    path: &Path,
    part: &PartModel,
    options: &TessellateOptions,
) -> Result<Tessellation, Error> {
    tessellate_cad(&part.cad, options).map_err(|defect| Error::Tessellate {
        path: path.to_path_buf(),
        defect,
    })
}

/// Tessellates a STEP file's B-rep (for `flatcut tessellate` and the pipeline).
pub fn tessellate_step(
    path: &Path,
    brep: &Brep,
    options: &TessellateOptions,
) -> Result<Tessellation, Error> {
    tessellate_brep(brep, options).map_err(|defect| Error::Brep {
        path: path.to_path_buf(),
        defect,
    })
}

/// The part of a STEP file of one solid of planes and cylinders recognised as sheet metal, its
/// skin unfolded exactly; otherwise why not (`None` for anything else: several shells, other
/// surfaces). The solid is tessellated once, for the unfold: its chord at most
/// [`SHEET_CHORD_MM`], its faces triangulated from their boundaries
/// ([`tessellate_brep_for_unfold`]); it is recognised on that tessellation's face areas.
fn sheet_metal_part(
    path: &Path,
    brep: &Brep,
    options: &RunOptions,
) -> Result<Result<PartJob, Option<String>>, Error> {
    let [shell] = brep.shells.as_slice() else {
        return Ok(Err(None));
    };
    let sheet_like = (0..shell.shell.faces.len()).all(|face| {
        let geometry = shell.surface_geometry(face);
        SheetSurface::of(geometry).is_some() || matches!(geometry, SurfaceGeometry::Cone { .. })
    });
    if !sheet_like {
        return Ok(Err(None));
    }
    // A solid this tessellation fails on is left to the surface path, which reports its own
    // error if it fails too.
    let Ok(fine) = tessellate_brep_for_unfold(brep, &options.tessellate, SHEET_CHORD_MM) else {
        return Ok(Err(None));
    };
    let solid = match recognise_shell(shell, fine.soup()) {
        Ok(solid) => solid,
        Err(NotASheet::OtherSurfaces(_)) => return Ok(Err(None)),
        Err(NotASheet::NoConstantThickness(reason)) => return Ok(Err(Some(reason))),
    };
    let unfold = unfold_skin(&solid, fine.soup(), &options.sheet);
    let base_face = shell.describe_face(solid.base_face);
    let mut header = template(brep.name.clone(), Units::Millimetres);
    header.tessellation = Some(fine.figures);
    Ok(sheet_job(path, unfold, base_face, header)?
        .ok_or_else(|| Some("its skin is not one piece".to_owned())))
}

/// The part of an unfolded sheet-metal solid: its skin validated into one facet model, the flat
/// positions carried to the model's vertices, the thickness from the solid; `None` when the
/// skin is not one connected piece.
fn sheet_job(
    path: &Path,
    unfold: SheetUnfold,
    base_face: String,
    mut header: PartHeader,
) -> Result<Option<PartJob>, Error> {
    let validated = validate(&unfold.skin).map_err(|defects| Error::Mesh {
        path: path.to_path_buf(),
        defects,
    })?;
    let ([model], [soup_vertices]) = (
        validated.components.as_slice(),
        validated.soup_vertices.as_slice(),
    ) else {
        return Ok(None);
    };
    header.attributes.thickness = Some(unfold.thickness);
    let flat = soup_vertices
        .iter()
        .map(|&vertex| unfold.flat[vertex as usize])
        .collect();
    Ok(Some(PartJob {
        name: header.name,
        source: path.to_path_buf(),
        units: header.units,
        quantity: header.quantity,
        attributes: header.attributes,
        fold_line_count: 0,
        tessellation: header.tessellation,
        stiffness: Stiffness::uniform(model),
        constraints: CutConstraints::default(),
        model: model.clone(),
        warnings: validated.warnings.iter().map(ToString::to_string).collect(),
        sheet: Some(SheetPart {
            flat,
            bends: unfold.bends,
            thickness: unfold.thickness,
            k_factor: unfold.k_factor,
            base_face,
        }),
    }))
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
    part: &PartModel,
    options: &TessellateOptions,
) -> Result<Vec<PartJob>, Error> {
    let tessellation = tessellate_part(path, part, options)?;
    let mut template = template(part.name.clone(), part.units);
    template.quantity = part.quantity;
    template.attributes = part.attributes.clone();
    template.fold_line_count = part.fold_stiffness.len() as u32;
    template.tessellation = Some(tessellation.figures);
    let mesh_size = tessellation.figures.mesh_size;
    split_parts(
        path,
        tessellation.soup(),
        template,
        |model, soup_vertices, stiffness| {
            for (line, fold) in part.fold_stiffness.iter().enumerate() {
                let width = fold.width.unwrap_or(2.0 * mesh_size);
                stiffness.raise_near_fold_line(model, line as u32, width / 2.0, fold.factor);
            }
            for region in &part.regions {
                let members = match &region.shape {
                    RegionShape::Parameter { surface, polygon } => {
                        let domain = SurfaceDomain::new(&part.cad.surfaces[*surface]);
                        let region = ParameterRegion::new(domain, polygon.clone());
                        vertices_inside(&region, &tessellation.welded, *surface as u32)
                    }
                    RegionShape::Box { .. } => Vec::new(),
                };
                stiffness.raise_where(region.factor, |edge| {
                    let ends = model.edges()[edge];
                    match &region.shape {
                        RegionShape::Box { min, max } => {
                            let [a, b] = ends.map(|v| model.positions()[v as usize]);
                            let midpoint = (a + b) * 0.5;
                            midpoint.cmpge(*min).all() && midpoint.cmple(*max).all()
                        }
                        RegionShape::Parameter { .. } => ends
                            .iter()
                            .all(|&v| members[soup_vertices[v as usize] as usize]),
                    }
                });
            }
        },
    )
}

/// The cut stage's constraints from a part's sidecar.
fn cut_constraints(sidecar: CutSidecar) -> CutConstraints {
    CutConstraints {
        seams: sidecar.seams,
        no_cut_regions: sidecar
            .no_cut_regions
            .iter()
            .map(|region| NoCutRegion {
                center: region.center,
                radius: region.radius,
            })
            .collect(),
    }
}

/// Validates a soup into one job per component, each with its stiffness set by `stiffen` (given
/// the component's model, the soup vertex of each model vertex, and the stiffness to raise).
fn split_parts(
    path: &Path,
    soup: &TriangleSoup,
    header: PartHeader,
    mut stiffen: impl FnMut(&FacetModel, &[u32], &mut Stiffness),
) -> Result<Vec<PartJob>, Error> {
    let validated = validate(soup).map_err(|defects| Error::Mesh {
        path: path.to_path_buf(),
        defects,
    })?;
    let warnings: Vec<String> = validated.warnings.iter().map(ToString::to_string).collect();
    let several = validated.components.len() > 1;
    let constraints = read_cut_sidecar(path, validated.components.len())?
        .map(cut_constraints)
        .unwrap_or_default();
    Ok(validated
        .components
        .into_iter()
        .zip(&validated.soup_vertices)
        .enumerate()
        .map(|(i, (model, soup_vertices))| {
            let mut stiffness = Stiffness::uniform(&model);
            stiffen(&model, soup_vertices, &mut stiffness);
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
                sheet: None,
            }
        })
        .collect())
}
