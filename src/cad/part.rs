//! A part as the part-file reader produces it: its geometry (surfaces and fold lines), the
//! attributes carried to the outputs (material, thickness, grain, quantity) and its features'
//! stiffness.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::features::{FoldBend, FoldLineGeometry, FoldStiffness, StiffnessRegion};
use super::rulings::rulings;
use super::surface::{RuledSurface, Surface};
use crate::units::Units;

/// Angular samples of a circle when the part's size is estimated.
const SIZE_SAMPLES: usize = 16;

/// A part's geometry as the tessellator needs it.
#[derive(Debug, Clone)]
pub struct CadPart {
    /// Surfaces in file order.
    pub surfaces: Vec<Surface>,
    /// Fold lines in file order.
    pub fold_lines: Vec<FoldLineGeometry>,
    /// Whether surfaces are welded along shared edges (false: each surface its own part).
    pub weld: bool,
}

/// Attributes of a part carried to the outputs (DXF labels, nesting).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PartAttributes {
    /// Material name.
    pub material: Option<String>,
    /// Sheet thickness (part units).
    pub thickness: Option<f64>,
    /// Grain direction on the part.
    pub grain: Option<DVec3>,
}

/// A part file, read and built: the geometry with everything the file says about the part.
#[derive(Debug, Clone)]
pub struct PartModel {
    /// Part name.
    pub name: String,
    /// Units of every length.
    pub units: Units,
    /// Copies to cut.
    pub quantity: u32,
    /// Material, thickness, grain.
    pub attributes: PartAttributes,
    /// The geometry.
    pub cad: CadPart,
    /// Stiffness of each fold line, in the order of `cad.fold_lines`.
    pub fold_stiffness: Vec<FoldStiffness>,
    /// The bend of each fold line made with a bend radius, in the order of `cad.fold_lines`.
    pub fold_bends: Vec<Option<FoldBend>>,
    /// Regions of raised stiffness.
    pub regions: Vec<StiffnessRegion>,
}

impl CadPart {
    /// The diagonal of a bounding box of sample points of every surface: the part's size.
    pub fn size(&self) -> f64 {
        let mut low = DVec3::splat(f64::INFINITY);
        let mut high = DVec3::splat(f64::NEG_INFINITY);
        for surface in &self.surfaces {
            for p in outline_points(surface) {
                low = low.min(p);
                high = high.max(p);
            }
        }
        (high - low).length()
    }
}

/// Sample points spanning a surface (for its size).
fn outline_points(surface: &Surface) -> Vec<DVec3> {
    match surface {
        Surface::Ruled(ruled) => {
            let rulings = rulings(ruled, f64::INFINITY, 0.0);
            let mut points = rulings.bottom;
            points.extend(rulings.top);
            if let RuledSurface::Circular {
                frame,
                bottom,
                top,
                angles,
            } = ruled
            {
                for k in 0..=SIZE_SAMPLES {
                    let angle =
                        angles[0] + (angles[1] - angles[0]) * k as f64 / SIZE_SAMPLES as f64;
                    points.push(frame.point(bottom.point(angle)));
                    points.push(frame.point(top.point(angle)));
                }
            }
            points
        }
        Surface::Revolution(revolution) => {
            let mut points = Vec::new();
            for p in revolution.profile.sample(f64::INFINITY, 0.0) {
                for k in 0..SIZE_SAMPLES {
                    let angle = TAU * k as f64 / SIZE_SAMPLES as f64;
                    let local = DVec3::new(p.x * angle.cos(), p.x * angle.sin(), p.y);
                    points.push(revolution.frame.point(local));
                }
            }
            points
        }
        Surface::Patch(patch) => {
            let (low, high) = patch
                .outer
                .iter()
                .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(l, h), &p| {
                    (l.min(p), h.max(p))
                });
            let grid = (0..=SIZE_SAMPLES)
                .flat_map(|i| (0..=SIZE_SAMPLES).map(move |j| DVec2::new(i as f64, j as f64)));
            grid.map(|t| {
                patch
                    .geometry
                    .point(low + (high - low) * t / SIZE_SAMPLES as f64)
            })
            .collect()
        }
    }
}
