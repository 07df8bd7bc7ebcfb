//! What one energy map shows: a flat pattern with its per-vertex energies and the lines drawn on
//! it, and the figures printed with it. Plain values for [`super::energy_png`] and its layout and
//! panel drawing.

use glam::DVec2;

/// Default image width in pixels.
pub const DEFAULT_WIDTH_PIXELS: u32 = 1600;

/// The accuracy figures printed with a map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatternFigures {
    /// `E_S` (Eq. 4), a fraction.
    pub area_error: f64,
    /// `E_C` (Eq. 6), a fraction.
    pub shape_error: f64,
    /// Largest relative edge length change, a fraction.
    pub max_strain: f64,
    /// Number of cuts made.
    pub cuts: usize,
}

/// One energy map: a flat pattern with its per-vertex energy and the lines to draw on it.
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyMap<'a> {
    /// The part's name, printed in the title.
    pub name: String,
    /// Units of the energy values for the legend, e.g. "mm², C = 0.5".
    pub energy_units: String,
    /// Symbol of the length units of `positions`, e.g. "mm", for the scale bar.
    pub length_units: String,
    /// Flat vertex positions, model units, y up.
    pub positions: &'a [DVec2],
    /// Triangles as vertex index triples.
    pub triangles: &'a [[u32; 3]],
    /// Per-vertex energy (Eq. 1), one per position, at least 0.
    pub vertex_energies: &'a [f64],
    /// Closed boundary loops as vertex indices: the outline.
    pub boundary_loops: &'a [Vec<u32>],
    /// Cuts, as flat polylines in model units.
    pub cut_polylines: Vec<Vec<DVec2>>,
    /// Fold lines, as flat polylines in model units.
    pub fold_polylines: Vec<Vec<DVec2>>,
    /// The figures printed with the map.
    pub figures: PatternFigures,
    /// The energy below which differences are round-off, not deformation (see
    /// [`crate::pattern::negligible_vertex_energy`]); the colour scale's top is never below it, so a pattern
    /// without deformation (a developable surface) comes out all blue. 0 for none.
    pub negligible_energy: f64,
}
