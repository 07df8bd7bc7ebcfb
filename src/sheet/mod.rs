//! The sheet-metal stage (after mesh, before flatten): a STEP solid that is a thin sheet of one
//! thickness, unfolded exactly on its B-rep instead of by the energy model.
//!
//! [`recognise_shell`] recognises the solid ([`recognise`]: two skins at one thickness, parallel
//! planes and coaxial cylinders and cones, joined by walls, with formed regions on either skin)
//! and picks the skin of the largest planar face;
//! [`unfold_skin`] unfolds it: flanges placed rigidly, each bend unrolled at its neutral fibre, so that its flat
//! width is the bend allowance `BA = θ · (R_inner + K · t)` ([`bend_allowance`]). The result, a
//! [`SheetUnfold`], is the skin's triangles with one exact flat position per vertex and the
//! [`BendLine`]s; the pipeline turns it into a part's pattern like any flattened part, with its
//! bend lines drawn on the `BEND_UP` / `BEND_DOWN` layers. See `docs/sheet-metal.md`.

mod base_face;
mod bend;
mod bend_rule;
mod bend_table;
mod cone_bend;
mod face_map;
mod fold_unfold;
mod options;
mod recognise;
mod surfaces;
mod unfold;

pub use base_face::base_face_index;
pub use bend::{BendDirection, BendLine, ConicalBend};
pub use bend_rule::{
    AllowanceRule, BendAllowance, BendGeometry, BendRule, allowance_by_rule, bend_allowance,
    din6935_factor,
};
pub use bend_table::{
    BendTable, BendTableRow, TABLE_ANGLE_TOLERANCE_DEGREES, TABLE_LENGTH_TOLERANCE_MM,
    TableQuantity, TableValue,
};
pub use fold_unfold::{FoldUnfold, FoldedPart, unfold_folds};
pub use options::{DEFAULT_K_FACTOR, SheetOptions};
pub use recognise::{MAXIMUM_THICKNESS_RATIO, NotASheet, ThinSolid, may_be_sheet, recognise};
pub use surfaces::{LENGTH_TOLERANCE_MM, SheetSurface};
pub use unfold::{
    FormedRegion, SheetUnfold, UnfoldRefusal, rest_position, skin_triangles, unfold_skin,
};

use crate::cad::{BrepShell, TriangleSoup};

/// The chord, in mm, a thin solid is tessellated with before it is unfolded (when the default
/// is coarser): a fifth of the DXF's default chord tolerance, so that the skin's boundary
/// vertices, which lie exactly on its circles, are dense enough for the DXF to draw them as true
/// arcs.
pub const SHEET_CHORD_MM: f64 = 0.002;

/// Recognises `shell` as a thin solid ([`recognise`]) unfolded from `base_face` (a face index,
/// [`base_face_index`]) or the largest planar face; `soup` is the shell's tessellation, each
/// triangle tagged with its face's index in the shell (the faces' areas come from it).
pub fn recognise_shell(
    shell: &BrepShell,
    soup: &TriangleSoup,
    base_face: Option<usize>,
) -> Result<ThinSolid, NotASheet> {
    recognise(shell, &face_areas(soup, shell.shell.faces.len()), base_face)
}

/// The area of each face's triangles, per face of the shell.
fn face_areas(soup: &TriangleSoup, faces: usize) -> Vec<f64> {
    let mut areas = vec![0.0; faces];
    for (&[a, b, c], &face) in soup.triangles.iter().zip(&soup.face_sources) {
        if let Some(area) = areas.get_mut(face as usize) {
            let [a, b, c] = [a, b, c].map(|v| soup.positions[v as usize]);
            *area += 0.5 * (b - a).cross(c - a).length();
        }
    }
    areas
}
