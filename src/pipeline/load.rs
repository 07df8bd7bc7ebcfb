//! Loading one input: ingest, tessellate (part files), validate (one part per connected
//! component), stiffness (fold lines, regions). A STEP solid recognised as sheet metal is
//! unfolded here, exactly (see [`crate::sheet`]): its part is its chosen skin with the flat
//! pattern already made.

use std::mem::{Discriminant, discriminant};
use std::path::{Path, PathBuf};

use glam::DVec2;

use crate::cad::{
    Brep, BrepShell, FoldBend, FoldLineGeometry, ParameterRegion, PartAttributes, PartModel,
    RegionShape, SourceLines, SurfaceDomain, TriangleSoup,
};
use crate::cut::{CutConstraints, NoCutRegion};
use crate::error::Error;
use crate::flatten::Stiffness;
use crate::geometry::weld::finite_bounds;
use crate::ingest::{CutSidecar, Input, read_cut_sidecar, read_input};
use crate::mesh::{
    Defect, FacetModel, NAMED_WELDS, SeamSource, check_welded, cut_open_non_orientable,
    repair_degenerate_triangles, split_at_texture_seams, split_non_manifold, validate,
    weld_duplicates,
};
use crate::sheet::{
    BendLine, BendRule, FoldedPart, NotASheet, SHEET_CHORD_MM, SheetOptions, SheetUnfold,
    ThinSolid, UnfoldRefusal, base_face_index, may_be_sheet, recognise_shell, skin_triangles,
    unfold_folds, unfold_skin,
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
    /// The K-factor every bend was unrolled with, when the rule is the K-factor.
    pub k_factor: Option<f64>,
    /// The bend rule in words (`K 0.44`, `DIN 6935`, `bend table FILE`).
    pub rule: String,
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
            let (soup, mut repairs) = prepared_soup(path, mesh.soup, options)?;
            repairs.extend(small_mesh_warning(&soup, mesh.units));
            let mut jobs = split_parts(path, &soup, template, |_, _, _| {})?;
            for job in &mut jobs {
                job.warnings.splice(0..0, repairs.iter().cloned());
                if let Some(thickness) = thin_solid_thickness(&job.model) {
                    job.warnings.push(format!(
                        "the mesh is a closed thin solid, about {thickness:.3} {} thick: it is \
                         flattened as a closed surface, both skins and the edges between them; \
                         for a sheet-metal unfold give its STEP file, or a mesh of one skin",
                        job.units.symbol()
                    ));
                }
            }
            Ok(jobs)
        }
        _ if options.seams == SeamSource::FromUv => Err(Error::SeamsFromUv {
            path: path.to_path_buf(),
            reason: "only mesh files carry a texture layout; part and STEP files get their seams \
                     from the cut stage"
                .into(),
        }),
        Input::Step(brep) if brep.shells.len() > 1 && brep.shells.iter().any(may_be_sheet) => {
            shell_by_shell_parts(path, &brep, options)
        }
        Input::Step(brep) => step_parts(path, &brep, options),
        Input::Part(part) if part.fold_bends.iter().any(Option::is_some) => {
            folded_part(path, &part, options)
        }
        Input::Part(part) => load_part_file(path, &part, &options.tessellate),
    }
}

/// A closed solid's thickness `t` is at most this fraction of its size `√(A / 2)` (A its area,
/// both skins) for it to be a thin solid, a sheet or a plate: 0.02 for a bent 1.5 mm sheet of
/// 150 by 30 mm, 0.19 for a cube, 0.27 for a sphere.
pub const THIN_SOLID_RATIO: f64 = 0.05;

/// The thickness of a closed mesh that is a thin solid (a sheet-metal part exported as a mesh):
/// twice its enclosed volume over its area ([`THIN_SOLID_RATIO`]); `None` for an open surface or
/// a thick solid.
fn thin_solid_thickness(model: &FacetModel) -> Option<f64> {
    if !model.is_closed() {
        return None;
    }
    let positions = model.positions();
    let volume: f64 = (model.triangles().iter())
        .map(|t| {
            let [a, b, c] = t.map(|v| positions[v as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum();
    let area = model.area();
    let thickness = 2.0 * volume.abs() / area;
    (area > 0.0 && thickness <= THIN_SOLID_RATIO * (area / 2.0).sqrt()).then_some(thickness)
}

/// The parts of a STEP file: its solid unfolded when it is sheet metal ([`sheet_metal_part`]),
/// else its shells tessellated and flattened as surfaces, one part per connected piece, with a
/// warning when a thin solid is not unfolded.
fn step_parts(path: &Path, brep: &Brep, options: &RunOptions) -> Result<Vec<PartJob>, Error> {
    let not_a_sheet = match sheet_metal_part(path, brep, options)? {
        Ok(jobs) => return Ok(jobs),
        Err(reason) => reason,
    };
    let tessellation = tessellate_step(path, brep, &options.tessellate)?;
    let mut template = template(brep.name.clone(), Units::Millimetres);
    template.tessellation = Some(tessellation.figures);
    let mut jobs = split_parts(path, tessellation.soup(), template, |_, _, _| {})
        .map_err(|error| with_step_faces(error, brep, tessellation.soup()))?;
    if let Some(reason) = not_a_sheet {
        for job in &mut jobs {
            job.warnings.push(format!(
                "not unfolded as sheet metal ({reason}): flattened as a surface"
            ));
        }
    }
    Ok(jobs)
}

/// The parts of a STEP file of several solids (a multi-body part), one of which may be sheet
/// metal: each shell handled as a file of that solid alone ([`step_parts`]: a sheet-metal solid
/// unfolded, any other flattened as a surface), its parts named `<file>-<k>` for the `k`-th
/// shell. A `--base-face` applies to the shell holding that face (an error when none does); the
/// others unfold from their own largest planar face. Seams and no-cut regions (the file's cut
/// sidecar) need a file per part, as for a mesh of several parts.
fn shell_by_shell_parts(
    path: &Path,
    brep: &Brep,
    options: &RunOptions,
) -> Result<Vec<PartJob>, Error> {
    read_cut_sidecar(path, brep.shells.len())?;
    let holds = |shell: &BrepShell, id: u64| shell.faces.iter().any(|face| face.id == id);
    if let Some(id) = options.sheet.base_face
        && !brep.shells.iter().any(|shell| holds(shell, id))
    {
        return Err(Error::SheetMetal {
            path: path.to_path_buf(),
            reason: format!("--base-face #{id}: no solid of the file has an ADVANCED_FACE #{id}"),
        });
    }
    let mut others = options.clone();
    others.sheet.base_face = None;
    let mut jobs = Vec::new();
    for (k, shell) in brep.shells.iter().enumerate() {
        let single = Brep {
            name: format!("{}-{}", brep.name, k + 1),
            shells: vec![shell.clone()],
            loose: Vec::new(),
            unsupported: brep.unsupported.clone(),
        };
        let holds_base = options.sheet.base_face.is_some_and(|id| holds(shell, id));
        let shell_options = if holds_base { options } else { &others };
        jobs.extend(step_parts(path, &single, shell_options)?);
    }
    Ok(jobs)
}

/// A mesh read in millimetres whose bounding box's diagonal is under this (mm) gets a warning
/// that its units may be metres or centimetres: garment tools export
/// metres, and a dress read as millimetres is under 2 mm tall.
pub const SMALL_MESH_MM: f64 = 20.0;

/// The warning for a mesh read in millimetres that is under [`SMALL_MESH_MM`] across, naming
/// `--units m` and `--units cm`; `None` for any other.
fn small_mesh_warning(soup: &TriangleSoup, units: Units) -> Option<String> {
    let (min, max) = finite_bounds(&soup.positions)?;
    let across = (max - min).length() * units.millimetres();
    (units == Units::Millimetres && across < SMALL_MESH_MM).then(|| {
        format!(
            "the mesh is only {across:.3} mm across (its bounding box's diagonal, read in \
             millimetres): if the file is in metres (as garment tools export) or centimetres, \
             give --units m or --units cm"
        )
    })
}

/// A mesh file's soup as the options want it: refused if it is a triangle soup (without
/// `--repair`, which welds it), duplicates welded (`--repair`), cut into its
/// texture charts (`--seams from-uv`), duplicate and zero-area triangles mended and non-manifold
/// edges and vertices split (`--repair`); with the repairs made, as warnings.
fn prepared_soup(
    path: &Path,
    mut soup: TriangleSoup,
    options: &RunOptions,
) -> Result<(TriangleSoup, Vec<String>), Error> {
    if !options.repair {
        check_welded(&soup).map_err(|defects| Error::Mesh {
            path: path.to_path_buf(),
            defects,
        })?;
    }
    let mut warnings = Vec::new();
    let mut note = |soup: &TriangleSoup, repairs: Vec<Defect>| {
        warnings.extend(repair_warnings(&repairs, &soup.source_lines));
    };
    if options.repair {
        let (welded, repairs) = weld_duplicates(&soup);
        note(&soup, repairs);
        soup = welded;
    }
    if options.seams == SeamSource::FromUv {
        soup = split_at_texture_seams(&soup).ok_or_else(|| Error::SeamsFromUv {
            path: path.to_path_buf(),
            reason: "the file gives no texture point (OBJ `vt`) for every face corner".into(),
        })?;
    }
    if options.repair {
        let (mended, repairs) = repair_degenerate_triangles(&soup);
        note(&soup, repairs);
        soup = mended;
        let (split, repairs) = split_non_manifold(&soup);
        note(&soup, repairs);
        soup = split;
        let (cut, repairs) = cut_open_non_orientable(&soup);
        note(&soup, repairs);
        soup = cut;
    }
    Ok((soup, warnings))
}

/// The repairs as warnings located in the file: the first [`NAMED_WELDS`] of each kind named one
/// by one, the others of that kind counted in one warning (a scan with holes can have thousands
/// of split vertices, and every part of the file carries its warnings).
fn repair_warnings(repairs: &[Defect], lines: &SourceLines) -> Vec<String> {
    // Per kind of repair: its first repair and how many there are.
    let mut kinds: Vec<(Discriminant<Defect>, &Defect, usize)> = Vec::new();
    let mut warnings = Vec::new();
    for repair in repairs {
        let kind = discriminant(repair);
        let position = match kinds.iter().position(|(seen, ..)| *seen == kind) {
            Some(position) => position,
            None => {
                kinds.push((kind, repair, 0));
                kinds.len() - 1
            }
        };
        kinds[position].2 += 1;
        if kinds[position].2 <= NAMED_WELDS {
            warnings.push(repair.located(lines));
        }
    }
    for (_, first, count) in kinds {
        if count > NAMED_WELDS {
            warnings.push(format!(
                "{} more repairs of the same kind as \"{}\" (--repair)",
                count - NAMED_WELDS,
                first.located(lines)
            ));
        }
    }
    warnings
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

/// The part of a STEP file of one solid recognised as sheet metal, its skin unfolded exactly
/// from the options' base face or its largest planar face (its formed regions projected onto
/// their flanges, with a warning each); otherwise why not (`None` for anything else: several
/// shells, a solid that is no sheet). The solid is tessellated once, for the unfold: its chord
/// at most [`SHEET_CHORD_MM`], its faces triangulated from their boundaries
/// ([`tessellate_brep_for_unfold`]); it is recognised on that tessellation's face areas. A
/// skin whose formed region cannot be projected is flattened as a surface, that skin only
/// ([`skin_surface_parts`]). A base face that cannot be used (no such face, not a flange, the
/// part not a sheet) is an error.
fn sheet_metal_part(
    path: &Path,
    brep: &Brep,
    options: &RunOptions,
) -> Result<Result<Vec<PartJob>, Option<String>>, Error> {
    let refuse = |reason: String| Error::SheetMetal {
        path: path.to_path_buf(),
        reason,
    };
    let base_face_refused = |reason: String| match options.sheet.base_face {
        Some(id) => Err(refuse(format!("--base-face #{id}: {reason}"))),
        None => Ok(Err(None)),
    };
    let [shell] = brep.shells.as_slice() else {
        return base_face_refused(format!(
            "the file holds {} shells, not one sheet-metal solid",
            brep.shells.len()
        ));
    };
    if !may_be_sheet(shell) {
        return base_face_refused(
            "the part is not a solid of planes and cylinders, nor a sheet with formed regions"
                .to_owned(),
        );
    }
    // A solid this tessellation fails on is left to the surface path, which reports its own
    // error if it fails too.
    let Ok(fine) = tessellate_brep_for_unfold(brep, &options.tessellate, SHEET_CHORD_MM) else {
        return base_face_refused("the solid cannot be tessellated for an unfold".to_owned());
    };
    let solid = match thin_solid(shell, fine.soup(), &options.sheet).map_err(refuse)? {
        Ok(solid) => solid,
        Err(reason) => return Ok(Err(reason)),
    };
    let material = options.overrides.material.as_deref();
    let unfold = match unfold_skin(&solid, fine.soup(), &options.sheet, material) {
        Ok(unfold) => unfold,
        Err(UnfoldRefusal::Rule(reason)) => return Err(refuse(reason)),
        Err(UnfoldRefusal::FormedRegion { faces, reason }) => {
            let warning = format!(
                "formed region {} is not developable and {reason}: the skin of {} flattened as a surface, its bends without bend allowance",
                describe_faces(shell, &faces),
                shell.describe_face(solid.base_face)
            );
            return skin_surface_parts(path, brep, &solid, options, warning).map(Ok);
        }
        Err(UnfoldRefusal::Disagreement { faces, gap }) => {
            let warning = format!(
                "the skin does not unfold as one piece ({} and {} put a common point {gap:.4} mm apart: a conical bend meeting a cylindrical one, or bends closing a loop, is not unfolded exactly): the skin of {} flattened as a surface, its bends without bend allowance",
                shell.describe_face(faces[0]),
                shell.describe_face(faces[1]),
                shell.describe_face(solid.base_face)
            );
            return skin_surface_parts(path, brep, &solid, options, warning).map(Ok);
        }
    };
    let warnings: Vec<String> = unfold
        .formed
        .iter()
        .map(|region| {
            format!(
                "formed region {} is not developable: drawn as its projection onto its flange ({}), the flat blank it is pressed from",
                describe_faces(shell, &region.faces),
                shell.describe_face(region.flange)
            )
        })
        .collect();
    let base_face = shell.describe_face(solid.base_face);
    let mut header = template(brep.name.clone(), Units::Millimetres);
    header.tessellation = Some(fine.figures);
    let Some(mut job) = sheet_job(path, unfold, base_face, header)? else {
        return Ok(Err(Some("its skin is not one piece".to_owned())));
    };
    job.warnings.extend(warnings);
    Ok(Ok(vec![job]))
}

/// Faces described one after the other (`ADVANCED_FACE #12 on SPHERICAL_SURFACE (#40), ...`).
fn describe_faces(shell: &BrepShell, faces: &[usize]) -> String {
    let described: Vec<String> = faces.iter().map(|&f| shell.describe_face(f)).collect();
    described.join(", ")
}

/// The parts of a thin solid's chosen skin (with its formed faces) flattened as a surface (it
/// does not unfold exactly, `warning` says why): the
/// solid tessellated the usual way and only the skin's triangles kept, so that one skin is
/// flattened, never the closed solid's two; each part carries `warning`.
fn skin_surface_parts(
    path: &Path,
    brep: &Brep,
    solid: &ThinSolid,
    options: &RunOptions,
    warning: String,
) -> Result<Vec<PartJob>, Error> {
    let tessellation = tessellate_step(path, brep, &options.tessellate)?;
    let skin = skin_triangles(solid, tessellation.soup());
    let mut template = template(brep.name.clone(), Units::Millimetres);
    template.tessellation = Some(tessellation.figures);
    let mut jobs = split_parts(path, &skin, template, |_, _, _| {})
        .map_err(|error| with_step_faces(error, brep, &skin))?;
    for job in &mut jobs {
        job.warnings.push(warning.clone());
    }
    Ok(jobs)
}

/// The thin solid of `shell`, recognised from the options' base face or its largest planar
/// face; otherwise why not, when that is worth a warning (`None` when it is no sheet at all). A
/// base face that cannot be used is an error (the reason).
fn thin_solid(
    shell: &BrepShell,
    soup: &TriangleSoup,
    options: &SheetOptions,
) -> Result<Result<ThinSolid, Option<String>>, String> {
    let recognised = recognise_shell(shell, soup, None).map_err(|not_a_sheet| match not_a_sheet {
        NotASheet::OtherSurfaces(reason) => (false, reason),
        NotASheet::NoConstantThickness(reason) => (true, reason),
    });
    match (recognised, options.base_face) {
        (Ok(solid), None) => Ok(Ok(solid)),
        (Ok(solid), Some(id)) => {
            let base = base_face_index(shell, &solid, id)?;
            recognise_shell(shell, soup, Some(base))
                .map(Ok)
                .map_err(|not_a_sheet| format!("--base-face #{id}: {}", not_a_sheet.reason()))
        }
        (Err((_, reason)), Some(id)) => Err(format!(
            "--base-face #{id}: the part is not a sheet-metal solid ({reason})"
        )),
        (Err((constant_thickness, reason)), None) => Ok(Err(constant_thickness.then_some(reason))),
    }
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
    header.attributes.thickness = Some(unfold.thickness);
    unfolded_job(path, &unfold.skin, header, |soup_vertices| SheetPart {
        flat: soup_vertices
            .iter()
            .map(|&vertex| unfold.flat[vertex as usize])
            .collect(),
        bends: unfold.bends,
        thickness: unfold.thickness,
        k_factor: unfold.k_factor,
        rule: unfold.rule,
        base_face,
    })
}

/// The part of an exact unfold of `soup`: the soup validated into one facet model, its sheet
/// made by `sheet` from the soup vertex of each model vertex; `None` when the soup is not one
/// connected piece.
fn unfolded_job(
    path: &Path,
    soup: &TriangleSoup,
    header: PartHeader,
    sheet: impl FnOnce(&[u32]) -> SheetPart,
) -> Result<Option<PartJob>, Error> {
    let validated = validate(soup).map_err(|defects| Error::Mesh {
        path: path.to_path_buf(),
        defects,
    })?;
    let ([model], [soup_vertices]) = (
        validated.components.as_slice(),
        validated.soup_vertices.as_slice(),
    ) else {
        return Ok(None);
    };
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
        warnings: validated
            .warnings
            .iter()
            .map(|warning| warning.located(&soup.source_lines))
            .collect(),
        sheet: Some(sheet(soup_vertices)),
    }))
}

/// A part file whose folds have bend radii: its polygons unfolded exactly about their folds,
/// each bend with the allowance of the bend rule ([`unfold_folds`]).
fn folded_part(path: &Path, part: &PartModel, options: &RunOptions) -> Result<Vec<PartJob>, Error> {
    let refuse = |reason: String| Error::SheetMetal {
        path: path.to_path_buf(),
        reason,
    };
    if !part.cad.weld {
        return Err(refuse(
            "a fold with a bend_radius joins two polygons: give join = \"weld\"".to_owned(),
        ));
    }
    let tessellation = tessellate_part(path, part, &options.tessellate)?;
    let folds: Vec<([usize; 2], Option<FoldBend>)> = part
        .cad
        .fold_lines
        .iter()
        .zip(&part.fold_bends)
        .filter_map(|(geometry, bend)| match geometry {
            FoldLineGeometry::Between { surfaces } => Some((*surfaces, *bend)),
            FoldLineGeometry::OnSurface { .. } => None,
        })
        .collect();
    let millimetres = part.units.millimetres();
    let thickness = options
        .overrides
        .thickness_mm
        .map(|mm| mm / millimetres)
        .or(part.attributes.thickness)
        .ok_or_else(|| refuse("a bend needs the part's thickness".to_owned()))?;
    let material = options
        .overrides
        .material
        .as_deref()
        .or(part.attributes.material.as_deref());
    let folded = FoldedPart {
        soup: tessellation.soup(),
        surfaces: part.cad.surfaces.len(),
        folds: &folds,
        thickness,
        millimetres,
    };
    let unfold = unfold_folds(&folded, &options.sheet, material).map_err(refuse)?;
    let mut header = template(part.name.clone(), part.units);
    header.quantity = part.quantity;
    header.attributes = part.attributes.clone();
    header.tessellation = Some(tessellation.figures);
    let job = unfolded_job(path, tessellation.soup(), header, |soup_vertices| {
        SheetPart {
            flat: soup_vertices
                .iter()
                .map(|&vertex| unfold.flat[vertex as usize])
                .collect(),
            bends: unfold.bends,
            thickness: thickness * millimetres,
            k_factor: (options.sheet.rule == BendRule::KFactor).then_some(options.sheet.k_factor),
            rule: options.sheet.rule.describe(options.sheet.k_factor),
            base_face: format!("surface {}", unfold.base_surface),
        }
    })?;
    job.map(|job| vec![job])
        .ok_or_else(|| refuse("the polygons of a part with bends must be one piece".to_owned()))
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
    let warnings: Vec<String> = validated
        .warnings
        .iter()
        .map(|warning| warning.located(&soup.source_lines))
        .collect();
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Of 25 split vertices and 3 welds, the warnings name the first 10 splits and the 3 welds,
    /// and count the other 15 splits in one.
    #[test]
    fn repairs_beyond_the_first_of_their_kind_are_counted() {
        let splits = (0..25).map(|vertex| Defect::SplitVertex { vertex, copies: 2 });
        let welds = (0..3).map(|vertex| Defect::WeldedVertex {
            vertex: 30 + vertex,
            into: vertex,
        });
        let repairs: Vec<Defect> = splits.chain(welds).collect();
        let warnings = repair_warnings(&repairs, &SourceLines::default());
        assert_eq!(warnings.len(), NAMED_WELDS + 3 + 1);
        assert_eq!(warnings[0], repairs[0].located(&SourceLines::default()));
        let last = warnings.last().expect("a count");
        assert!(
            last.starts_with("15 more repairs of the same kind as"),
            "{last}"
        );
    }
}
