//! The files of one flattened part, written into the output directory:
//! `<part>.mesh.obj` and `<part>.pattern.obj` (same vertices and faces), `<part>.pattern.json`
//! (what nesting needs, [`PatternFile`]), `<part>.dxf` (the cut file; `<part>.REJECTED.dxf` for a
//! rejected part) and `<part>.energy.png` (the energy map). Every file is written atomically.

use std::path::Path;

use glam::DVec2;

use super::atomic::write_atomically;
use super::dxf::write_part_dxf;
use super::dxf_options::DxfOptions;
use super::energy_png::{
    EnergyMap, EnergyPngError, EnergyPngOptions, PatternFigures, render_energy_png,
};
use super::errors::ExportError;
use super::obj::{mesh_obj, pattern_obj};
use crate::cut::UncutPattern;
use crate::flatten::Flattened;
use crate::mesh::FacetModel;
use crate::pattern::{Pattern, PatternFile, VertexEnergy, fold_polylines};

/// How a part's files are drawn.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PartFileOptions {
    /// DXF version, chord tolerance and seam allowance.
    pub dxf: DxfOptions,
    /// Size of the energy picture.
    pub energy: EnergyPngOptions,
}

/// What the files of one flattened part are written from.
#[derive(Debug, Clone, Copy)]
pub struct PartFiles<'a> {
    /// The input file the part came from (named in the file headers and errors).
    pub source: &'a Path,
    /// The cut facet model.
    pub model: &'a FacetModel,
    /// Its pattern and figures.
    pub flattened: &'a Flattened,
    /// The part before its first crest-line cut, when one was made.
    pub uncut: Option<&'a UncutPattern>,
    /// The part's pattern: drawing, cut lines and energies.
    pub pattern: &'a Pattern,
    /// The part's pattern file, written as `<part>.pattern.json`; a rejected part's cut file is
    /// `<part>.REJECTED.dxf`.
    pub pattern_file: &'a PatternFile,
    /// Number of crest-line cuts made.
    pub cuts: usize,
    /// The spring constant `C` the part was flattened with.
    pub spring_constant: f64,
}

/// Writes every file of a flattened part into `directory`.
pub fn write_part_files(
    directory: &Path,
    part: &PartFiles<'_>,
    options: &PartFileOptions,
) -> Result<(), ExportError> {
    let name = &part.pattern.drawing.name;
    let header = format!(
        "flatcut {} part '{}' from {}",
        env!("CARGO_PKG_VERSION"),
        name,
        part.source.display()
    );
    let (positions, triangles) = (&part.flattened.positions, part.model.triangles());
    let mesh = mesh_obj(
        &format!("{header}\n3D facet model"),
        part.model.positions(),
        triangles,
    );
    let pattern = pattern_obj(
        &format!("{header}\nflat pattern (z = 0)"),
        positions,
        triangles,
    );
    // A rejected part's outline can be too broken to draw (a hole collapsed to nothing): it then
    // gets no cut file, and its report says why it is rejected.
    let dxf = match write_part_dxf(&part.pattern.drawing, &options.dxf) {
        Ok(bytes) => Some(bytes),
        Err(_) if part.pattern_file.rejected => None,
        Err(source) => {
            return Err(ExportError::Drawing {
                path: part.source.to_path_buf(),
                part: name.clone(),
                source: Box::new(source),
            });
        }
    };
    let png = energy_png(part, &options.energy).map_err(|source| ExportError::EnergyMap {
        path: part.source.to_path_buf(),
        part: name.clone(),
        source,
    })?;
    let pattern_json = part.pattern_file.to_json().map_err(ExportError::Json)?;
    let cut_file = if part.pattern_file.rejected {
        "REJECTED.dxf"
    } else {
        "dxf"
    };
    let files: [(&str, Option<&[u8]>); 5] = [
        ("mesh.obj", Some(mesh.as_bytes())),
        ("pattern.obj", Some(pattern.as_bytes())),
        ("pattern.json", Some(pattern_json.as_bytes())),
        (cut_file, dxf.as_deref()),
        ("energy.png", Some(&png)),
    ];
    for (suffix, bytes) in files.iter().filter_map(|&(s, b)| Some((s, b?))) {
        let path = directory.join(format!("{name}.{suffix}"));
        write_atomically(&path, bytes).map_err(|source| ExportError::Write { path, source })?;
    }
    Ok(())
}

/// The energy picture of a flattened part: per-vertex energy (Eq. 1) of the final pattern, and
/// beside it the pattern before crest-line cutting when the part was cut.
fn energy_png(part: &PartFiles<'_>, options: &EnergyPngOptions) -> Result<Vec<u8>, EnergyPngError> {
    let pattern = part.pattern;
    let after = energy_map(
        part,
        MapSource {
            model: part.model,
            flattened: part.flattened,
            energy: &pattern.energy,
            fold_polylines: pattern.drawing.fold_lines.clone(),
        },
        pattern.cut_lines.clone(),
        part.cuts,
    );
    let before = part
        .uncut
        .zip(pattern.uncut_energy.as_ref())
        .map(|(uncut, energy)| {
            let source = MapSource {
                model: &uncut.model,
                flattened: &uncut.flattened,
                energy,
                fold_polylines: fold_polylines(&uncut.model, &uncut.flattened.positions),
            };
            energy_map(part, source, Vec::new(), 0)
        });
    render_energy_png(&after, before.as_ref(), options)
}

/// One pattern shown in the energy picture.
struct MapSource<'a> {
    model: &'a FacetModel,
    flattened: &'a Flattened,
    energy: &'a VertexEnergy,
    fold_polylines: Vec<Vec<DVec2>>,
}

/// The energy map of one pattern of `part`, with `cuts` cuts drawn as `cut_polylines`.
fn energy_map<'a>(
    part: &PartFiles<'_>,
    source: MapSource<'a>,
    cut_polylines: Vec<Vec<DVec2>>,
    cuts: usize,
) -> EnergyMap<'a> {
    let units = part.pattern.drawing.units.symbol();
    let accuracy = source.flattened.stats.accuracy;
    EnergyMap {
        name: part.pattern.drawing.name.clone(),
        energy_units: format!("{units}², C = {}", part.spring_constant),
        length_units: units.to_string(),
        positions: &source.flattened.positions,
        triangles: source.model.triangles(),
        vertex_energies: &source.energy.vertex,
        boundary_loops: source.model.boundary_loops(),
        cut_polylines,
        fold_polylines: source.fold_polylines,
        figures: PatternFigures {
            area_error: accuracy.area_error,
            shape_error: accuracy.shape_error,
            max_strain: accuracy.max_strain,
            cuts,
        },
        negligible_energy: source.energy.negligible,
    }
}
