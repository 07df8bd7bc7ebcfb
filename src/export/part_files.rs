//! The files of one flattened part, written into the output directory:
//! `<part>.mesh.obj` and `<part>.pattern.obj` (same vertices and faces), `<part>.dxf` (the cut
//! file) and `<part>.energy.png` (the energy map). Every file is written atomically.

use std::path::Path;

use glam::DVec2;

use super::drawing::PartDrawing;
use super::dxf::{DxfOptions, write_part_dxf};
use super::energy_png::{
    EnergyMap, EnergyPngError, EnergyPngOptions, NEGLIGIBLE_STRAIN, PatternFigures,
    negligible_vertex_energy, render_energy_png,
};
use super::fold_polylines::fold_polylines;
use super::obj::{mesh_obj, pattern_obj};
use super::write_atomically;
use crate::error::Error;
use crate::flatten::grain::flat_grain;
use crate::flatten::outline::Outline;
use crate::flatten::stiffness::Stiffness;
use crate::flatten::{Flattened, SpringSystem};
use crate::geometry::deep_interior_point;
use crate::mesh::FacetModel;
use crate::pipeline::PartResult;

/// How a part's files are drawn.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PartFileOptions {
    /// DXF version, chord tolerance and seam allowance.
    pub dxf: DxfOptions,
    /// Size of the energy picture.
    pub energy: EnergyPngOptions,
}

/// Writes every file of a flattened part into `directory`; `spring_constant` is the `C` the part
/// was flattened with (the energy map shows its energy).
pub fn write_part_files(
    directory: &Path,
    result: &PartResult,
    spring_constant: f64,
    options: &PartFileOptions,
) -> Result<(), Error> {
    let job = &result.job;
    let header = format!(
        "flatcut {} part '{}' from {}",
        env!("CARGO_PKG_VERSION"),
        job.name,
        job.source.display()
    );
    let (positions, triangles) = (&result.flattened.positions, job.model.triangles());
    let mesh = mesh_obj(
        &format!("{header}\n3D facet model"),
        job.model.positions(),
        triangles,
    );
    let pattern = pattern_obj(
        &format!("{header}\nflat pattern (z = 0)"),
        positions,
        triangles,
    );
    let dxf =
        write_part_dxf(&part_drawing(result), &options.dxf).map_err(|source| Error::Export {
            path: job.source.clone(),
            part: job.name.clone(),
            source,
        })?;
    let png = energy_png(result, spring_constant, &options.energy).map_err(|source| {
        Error::EnergyMap {
            path: job.source.clone(),
            part: job.name.clone(),
            source,
        }
    })?;
    let files: [(&str, &[u8]); 4] = [
        ("mesh.obj", mesh.as_bytes()),
        ("pattern.obj", pattern.as_bytes()),
        ("dxf", &dxf),
        ("energy.png", &png),
    ];
    for (suffix, bytes) in files {
        let path = directory.join(format!("{}.{suffix}", job.name));
        write_atomically(&path, bytes).map_err(|source| Error::Write { path, source })?;
    }
    Ok(())
}

/// What the part's DXF shows: its flat outline, holes and fold lines, with its name, quantity and
/// material, and its grain line when the part has a grain direction.
pub fn part_drawing(result: &PartResult) -> PartDrawing {
    let (job, positions) = (&result.job, &result.flattened.positions);
    let outline = Outline::of_pattern(&job.model, positions);
    let grain = job
        .attributes
        .grain
        .and_then(|direction| flat_grain(&job.model, positions, direction))
        .map(|direction| grain_line(&outline.outer, &outline.holes, direction));
    PartDrawing {
        name: job.name.clone(),
        units: job.units,
        quantity: job.quantity,
        material: job.attributes.material.clone(),
        outer: outline.outer,
        holes: outline.holes,
        fold_lines: fold_polylines(&job.model, positions),
        grain,
    }
}

/// The grain line drawn on a pattern: along the unit `direction`, through a point deep inside
/// the material ([`deep_interior_point`]), half as long as the outer contour's extent along
/// `direction`.
fn grain_line(outer: &[DVec2], holes: &[Vec<DVec2>], direction: DVec2) -> [DVec2; 2] {
    let (first, last) = outer
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            let along = p.dot(direction);
            (a.min(along), b.max(along))
        });
    let centre = deep_interior_point(outer, holes);
    let half = 0.25 * (last - first);
    [centre - half * direction, centre + half * direction]
}

/// The energy picture of a flattened part: per-vertex energy (Eq. 1) of the final pattern, and
/// beside it the pattern before crest-line cutting when the part was cut.
fn energy_png(
    result: &PartResult,
    spring_constant: f64,
    options: &EnergyPngOptions,
) -> Result<Vec<u8>, EnergyPngError> {
    let job = &result.job;
    let after = PatternEnergy::new(
        &job.model,
        &job.stiffness,
        &result.flattened,
        spring_constant,
    );
    let after_map = after.map(result, cut_polylines(result), result.cuts.len());
    let before = result.uncut.as_ref().map(|uncut| {
        PatternEnergy::new(
            &uncut.model,
            &uncut.stiffness,
            &uncut.flattened,
            spring_constant,
        )
    });
    let before_map = before
        .as_ref()
        .map(|before| before.map(result, Vec::new(), 0));
    render_energy_png(&after_map, before_map.as_ref(), options)
}

/// A pattern with its springs' per-vertex energies (Eq. 1).
struct PatternEnergy<'a> {
    model: &'a FacetModel,
    flattened: &'a Flattened,
    energies: Vec<f64>,
    negligible_energy: f64,
    spring_constant: f64,
}

impl<'a> PatternEnergy<'a> {
    fn new(
        model: &'a FacetModel,
        stiffness: &Stiffness,
        flattened: &'a Flattened,
        spring_constant: f64,
    ) -> Self {
        let springs = SpringSystem::new(model, stiffness.factors(), spring_constant);
        Self {
            model,
            flattened,
            energies: springs.vertex_energies(&flattened.positions),
            negligible_energy: negligible_vertex_energy(&springs, NEGLIGIBLE_STRAIN),
            spring_constant,
        }
    }

    /// The energy map of this pattern of `result`'s part, with `cuts` cuts drawn as
    /// `cut_polylines`.
    fn map(
        &self,
        result: &PartResult,
        cut_polylines: Vec<Vec<DVec2>>,
        cuts: usize,
    ) -> EnergyMap<'_> {
        let units = result.job.units.symbol();
        let accuracy = self.flattened.stats.accuracy;
        let positions = &self.flattened.positions;
        EnergyMap {
            name: result.job.name.clone(),
            energy_units: format!("{units}², C = {}", self.spring_constant),
            length_units: units.to_string(),
            positions,
            triangles: self.model.triangles(),
            vertex_energies: &self.energies,
            boundary_loops: self.model.boundary_loops(),
            cut_polylines,
            fold_polylines: fold_polylines(self.model, positions),
            figures: PatternFigures {
                area_error: accuracy.area_error,
                shape_error: accuracy.shape_error,
                max_strain: accuracy.max_strain,
                cuts,
            },
            negligible_energy: self.negligible_energy,
        }
    }
}

/// The cuts in the flat pattern: after splitting, both sides of a cut are boundary edges whose
/// ends sit at the cut's 3D points, so those edges are drawn (each as a two-point polyline).
fn cut_polylines(result: &PartResult) -> Vec<Vec<DVec2>> {
    let key = |p: glam::DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    let on_cut: std::collections::BTreeSet<[u64; 3]> = result
        .cuts
        .iter()
        .flat_map(|cut| cut.points.iter().map(|&p| key(p)))
        .collect();
    let (model, flat) = (&result.job.model, &result.flattened.positions);
    let at_cut = |v: u32| on_cut.contains(&key(model.positions()[v as usize]));
    model
        .edges()
        .iter()
        .enumerate()
        .filter(|&(e, &[a, b])| model.is_boundary_edge(e) && at_cut(a) && at_cut(b))
        .map(|(_, &[a, b])| vec![flat[a as usize], flat[b as usize]])
        .collect()
}
