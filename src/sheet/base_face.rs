//! The face a thin solid is unfolded from when the user chooses it (`--base-face ID`): the STEP
//! entity id of an `ADVANCED_FACE` that is a plane on one of the two skins (a flange's side).
//! Its side is the one drawn; it stays fixed and the rest of the skin unfolds from it.

use super::recognise::ThinSolid;
use super::surfaces::SheetSurface;
use crate::cad::BrepShell;

/// The index in `shell` of the face with entity id `id`, checked against the thin solid
/// recognised from the largest planar face: a plane on either skin. The error says why not
/// (no such face, not a plane, a wall between the skins).
pub fn base_face_index(shell: &BrepShell, solid: &ThinSolid, id: u64) -> Result<usize, String> {
    let face = shell
        .faces
        .iter()
        .position(|source| source.id == id)
        .ok_or_else(|| {
            format!("--base-face #{id}: the solid has no ADVANCED_FACE #{id} (its faces are listed in `flatcut tessellate`'s report)")
        })?;
    let description = shell.describe_face(face);
    if !matches!(solid.surfaces[face], SheetSurface::Plane { .. }) {
        return Err(format!(
            "--base-face #{id}: {description} is not planar: give a flange's face"
        ));
    }
    if !(solid.skin.contains(&face) || solid.partners.contains(&face) || on_other_skin(solid, face))
    {
        return Err(format!(
            "--base-face #{id}: {description} is a wall between the two skins (an edge of the sheet), not a flange's face"
        ));
    }
    Ok(face)
}

/// Whether a planar face is on the skin opposite the chosen one: parallel to a face of the
/// chosen skin at the thickness and sharing a wall with it.
fn on_other_skin(solid: &ThinSolid, face: usize) -> bool {
    solid.skin.iter().any(|&skin_face| {
        solid.surfaces[skin_face]
            .opposite_distance(&solid.surfaces[face])
            .is_some_and(|distance| {
                (distance - solid.thickness).abs() <= super::surfaces::LENGTH_TOLERANCE_MM
            })
            && solid.neighbours[skin_face]
                .iter()
                .any(|wall| solid.neighbours[face].contains(wall))
    })
}
