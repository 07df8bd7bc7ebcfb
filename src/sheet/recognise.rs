//! Thin-solid recognition on a B-rep shell: is it a sheet of one thickness, and which faces are
//! its chosen skin.
//!
//! A sheet-metal solid has two skins at thickness `t` (parallel planes at distance `t`, coaxial
//! cylinders of radii `R` and `R + t`, coaxial cones of one half-angle `t` apart along the
//! normal) joined by narrow edge faces (walls) that touch both skins.
//! The chosen skin is the side of the largest planar face: that face and every face reached from
//! it across edges where the surface continues smoothly (a flange into its bend, a bend into the
//! next flange). The thickness is the distance from the largest planar face to the nearest
//! parallel plane that shares a wall with it (or, when it has none, as a box's base with corner
//! reliefs, across the first bend or flange of its skin that has one), and it must hold for every
//! face of the skin. Formed faces (a dimple's spheres and tori, B-splines) belong to the skin
//! they run into.

use super::surfaces::{SheetSurface, same_length};
use crate::cad::BrepShell;

/// A sheet's thickness may be at most this fraction of the square root of its largest planar
/// face's area: a thicker solid is a block, not a sheet.
pub const MAXIMUM_THICKNESS_RATIO: f64 = 0.2;

/// A shell recognised as a sheet of one thickness.
#[derive(Debug, Clone, PartialEq)]
pub struct ThinSolid {
    /// The sheet's thickness, mm.
    pub thickness: f64,
    /// The largest planar face: where the unfold starts, fixed in place.
    pub base_face: usize,
    /// The faces of the chosen skin (the base face's side), base face first.
    pub skin: Vec<usize>,
    /// Every face's surface, in the shell's face order.
    pub surfaces: Vec<SheetSurface>,
    /// For each face of `skin` (same order), one face of the other skin opposite it.
    pub partners: Vec<usize>,
    /// The formed faces (neither plane, cylinder nor cone: a dimple, a louvre) on the chosen
    /// skin: each joins the skin's faces (and walls) only, not the other skin's; ascending.
    pub formed: Vec<usize>,
    /// Faces that share an edge, per face.
    pub neighbours: Vec<Vec<usize>>,
}

/// Why a shell is not a sheet of one thickness.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum NotASheet {
    /// The shell is not a solid of planes, cylinders and cones only (a sphere, a spline), so it
    /// is not unfolded as sheet metal.
    OtherSurfaces(String),
    /// Planes, cylinders and cones, but not two skins at one thickness joined by walls.
    NoConstantThickness(String),
}

impl NotASheet {
    /// The reason, in words.
    pub fn reason(&self) -> &str {
        match self {
            Self::OtherSurfaces(reason) | Self::NoConstantThickness(reason) => reason,
        }
    }
}

/// Recognises a shell as a thin solid; `face_areas` are the faces' areas (mm²), in the shell's
/// face order; the unfold starts from `base_face` (a planar face) when given, else from the
/// largest planar face. A sheet with a cone that is not a bend between flanges is refused with
/// that reason, a solid with cones that is no sheet without a warning (`cone_refusal`).
pub fn recognise(
    shell: &BrepShell,
    face_areas: &[f64],
    base_face: Option<usize>,
) -> Result<ThinSolid, NotASheet> {
    let surfaces = sheet_surfaces(shell);
    recognise_surfaces(shell, surfaces.clone(), face_areas, base_face)
        .map_err(|reason| formed_refusal(shell, &surfaces, reason))
        .map_err(|reason| cone_refusal(shell, &surfaces, reason))
}

/// Whether a shell may be a sheet worth recognising: all its faces planes, cylinders and
/// cones, or, with formed faces among them (a dimple, a louvre), two parallel planes sharing a
/// wall within [`MAXIMUM_THICKNESS_RATIO`] of its size (a solid of revolution or a free-form
/// body is not tessellated again for an unfold).
pub fn may_be_sheet(shell: &BrepShell) -> bool {
    let surfaces = sheet_surfaces(shell);
    !surfaces.contains(&SheetSurface::Formed)
        || has_thin_planes(shell, &surfaces, &face_neighbours(shell))
}

/// [`recognise`] on the shell's surfaces.
fn recognise_surfaces(
    shell: &BrepShell,
    surfaces: Vec<SheetSurface>,
    face_areas: &[f64],
    base_face: Option<usize>,
) -> Result<ThinSolid, NotASheet> {
    let neighbours = face_neighbours(shell);
    let base_face = base_face
        .or_else(|| largest_plane(&surfaces, face_areas))
        .ok_or_else(|| NotASheet::NoConstantThickness("the solid has no planar face".to_owned()))?;
    let skin = smooth_region(&surfaces, &neighbours, base_face);
    let thickness = sheet_thickness(&surfaces, &neighbours, &skin).ok_or_else(|| {
        NotASheet::NoConstantThickness(format!(
            "neither the largest planar face ({}) nor any face of its skin has an opposite face across a wall",
            shell.describe_face(base_face)
        ))
    })?;
    if thickness > MAXIMUM_THICKNESS_RATIO * face_areas[base_face].sqrt() {
        return Err(NotASheet::NoConstantThickness(format!(
            "thickness {thickness:.3} mm is too large for a sheet of this size"
        )));
    }
    let partners = opposite_skin(&surfaces, &neighbours, &skin, thickness).map_err(|face| {
        NotASheet::NoConstantThickness(format!(
            "{} has no opposite face at thickness {thickness:.4} mm",
            shell.describe_face(face)
        ))
    })?;
    let mut solid = ThinSolid {
        thickness,
        base_face,
        skin,
        surfaces,
        partners,
        formed: Vec::new(),
        neighbours,
    };
    let other_skin = other_skin(&solid);
    let (formed, other_formed) = formed_sides(&solid, &other_skin);
    solid.formed = formed;
    check_walls(shell, &solid, &other_skin, &other_formed)?;
    Ok(solid)
}

/// Every face's surface ([`SheetSurface::Formed`] for any but a plane, a cylinder or a cone).
fn sheet_surfaces(shell: &BrepShell) -> Vec<SheetSurface> {
    (0..shell.shell.faces.len())
        .map(|face| SheetSurface::of_face(shell.surface_geometry(face)))
        .collect()
}

/// Why a shell with formed faces is not a sheet: with planes close enough to be a sheet's two
/// skins ([`has_thin_planes`]) the recognition's own `reason`, worth a warning; otherwise (a
/// solid of revolution, a free-form body) [`NotASheet::OtherSurfaces`] naming the first formed
/// face, as for any solid that is not made of planes, cylinders and cones.
fn formed_refusal(shell: &BrepShell, surfaces: &[SheetSurface], reason: NotASheet) -> NotASheet {
    match surfaces.iter().position(|s| *s == SheetSurface::Formed) {
        Some(face) if !has_thin_planes(shell, surfaces, &face_neighbours(shell)) => {
            NotASheet::OtherSurfaces(format!(
                "{} is neither a plane, a cylinder nor a cone",
                shell.describe_face(face)
            ))
        }
        _ => reason,
    }
}

/// Why a shell with cones that is not recognised as a sheet is not: when it has planes close
/// enough to be a sheet's two skins ([`has_thin_planes`]), a cone that no neighbouring plane or
/// cone continues smoothly is named (a conical transition, such as a hopper's wall meeting its
/// flange at an angle, is not unfolded exactly yet), and with every cone a bend between flanges
/// the recognition's own `reason` stands. Otherwise the solid (a solid cone, a turned part) is
/// no sheet and its reason is [`NotASheet::OtherSurfaces`], which is not worth a warning.
fn cone_refusal(shell: &BrepShell, surfaces: &[SheetSurface], reason: NotASheet) -> NotASheet {
    let neighbours = face_neighbours(shell);
    let cones: Vec<usize> = (0..surfaces.len())
        .filter(|&face| matches!(surfaces[face], SheetSurface::Cone { .. }))
        .collect();
    if cones.is_empty() {
        return reason;
    }
    if !has_thin_planes(shell, surfaces, &neighbours) {
        return NotASheet::OtherSurfaces(reason.reason().to_owned());
    }
    let continued = |face: usize| {
        neighbours[face].iter().any(|&other| {
            !matches!(surfaces[other], SheetSurface::Cylinder { .. })
                && surfaces[face].tangent_to(&surfaces[other])
        })
    };
    match cones.into_iter().find(|&face| !continued(face)) {
        Some(cone) => NotASheet::NoConstantThickness(format!(
            "{} is a cone that is not a bend between two flanges: conical transitions are not unfolded exactly yet",
            shell.describe_face(cone)
        )),
        None => reason,
    }
}

/// Whether two parallel planes sharing a wall lie close enough to be a sheet's two skins
/// (within [`MAXIMUM_THICKNESS_RATIO`] of the part's size).
fn has_thin_planes(
    shell: &BrepShell,
    surfaces: &[SheetSurface],
    neighbours: &[Vec<usize>],
) -> bool {
    let planes: Vec<(usize, SheetSurface)> = surfaces
        .iter()
        .enumerate()
        .filter_map(|(face, surface)| match surface {
            plane @ SheetSurface::Plane { .. } => Some((face, *plane)),
            _ => None,
        })
        .collect();
    let size = super::surfaces::vertices_extent(shell);
    planes.iter().any(|&(a, plane)| {
        planes.iter().any(|&(b, other)| {
            a < b
                && share_a_wall(neighbours, a, b)
                && plane.opposite_distance(&other).is_some_and(|distance| {
                    distance > super::surfaces::LENGTH_TOLERANCE_MM
                        && distance <= MAXIMUM_THICKNESS_RATIO * size
                })
        })
    })
}

/// Faces sharing an edge with each face, ascending.
fn face_neighbours(shell: &BrepShell) -> Vec<Vec<usize>> {
    let mut neighbours = vec![Vec::new(); shell.shell.faces.len()];
    for ([a, b], _) in shell.adjacent_faces() {
        neighbours[a].push(b);
        neighbours[b].push(a);
    }
    for list in &mut neighbours {
        list.sort_unstable();
        list.dedup();
    }
    neighbours
}

/// The planar face of largest area (the first of equal ones).
fn largest_plane(surfaces: &[SheetSurface], face_areas: &[f64]) -> Option<usize> {
    let planes = (0..surfaces.len()).filter(|&f| matches!(surfaces[f], SheetSurface::Plane { .. }));
    planes.fold(None, |best: Option<usize>, face| match best {
        Some(best) if face_areas[best] >= face_areas[face] => Some(best),
        _ => Some(face),
    })
}

/// Whether two faces touch a common third face.
fn share_a_wall(neighbours: &[Vec<usize>], a: usize, b: usize) -> bool {
    neighbours[a]
        .iter()
        .any(|wall| neighbours[b].contains(wall))
}

/// The sheet's thickness: the distance from the first face of `skin` (the base face, then its
/// bends and flanges in breadth-first order) that has an opposite face off the skin sharing a
/// wall with it, to the nearest such face. A box whose base meets its other side only through
/// its bends (corner reliefs, no hole) has no wall on its base; its thickness is found across a
/// bend (coaxial cylinders sharing their end walls) or a flange. [`opposite_skin`] then checks
/// it over the whole skin.
fn sheet_thickness(
    surfaces: &[SheetSurface],
    neighbours: &[Vec<usize>],
    skin: &[usize],
) -> Option<f64> {
    skin.iter().find_map(|&face| {
        (0..surfaces.len())
            .filter(|&other| !skin.contains(&other) && share_a_wall(neighbours, face, other))
            .filter_map(|other| surfaces[face].opposite_distance(&surfaces[other]))
            .filter(|&distance| distance > super::surfaces::LENGTH_TOLERANCE_MM)
            .min_by(f64::total_cmp)
    })
}

/// For each face of `skin` (same order), the face of the other skin opposite it at
/// `thickness`: one sharing a wall with it, or else one that continues, smoothly, the opposite
/// face of a skin face it continues (the outer side of a box's base, reached from the outer
/// sides of its bends). Faces are matched until no more can be; the first face left without an
/// opposite one is the error.
fn opposite_skin(
    surfaces: &[SheetSurface],
    neighbours: &[Vec<usize>],
    skin: &[usize],
    thickness: f64,
) -> Result<Vec<usize>, usize> {
    let off_skin = |other: &usize| !skin.contains(other);
    let mut partners: Vec<Option<usize>> = skin
        .iter()
        .map(|&face| opposite_faces(surfaces, neighbours, face, thickness).find(off_skin))
        .collect();
    loop {
        let mut found = false;
        for index in 0..skin.len() {
            if partners[index].is_some() {
                continue;
            }
            let face = skin[index];
            let across_neighbour = skin
                .iter()
                .zip(&partners)
                .filter(|&(&next, _)| neighbours[face].contains(&next))
                .filter_map(|(_, &partner)| partner)
                .flat_map(|partner| {
                    neighbours[partner]
                        .iter()
                        .copied()
                        .filter(move |&other| surfaces[partner].tangent_to(&surfaces[other]))
                })
                .filter(|&other| {
                    off_skin(&other)
                        && surfaces[face]
                            .opposite_distance(&surfaces[other])
                            .is_some_and(|distance| same_length(distance, thickness))
                })
                .min();
            if let Some(other) = across_neighbour {
                partners[index] = Some(other);
                found = true;
            }
        }
        if !found {
            break;
        }
    }
    skin.iter()
        .zip(partners)
        .map(|(&face, partner)| partner.ok_or(face))
        .collect()
}

/// Faces opposite `face` at `thickness` that share a wall with it, ascending.
fn opposite_faces<'a>(
    surfaces: &'a [SheetSurface],
    neighbours: &'a [Vec<usize>],
    face: usize,
    thickness: f64,
) -> impl Iterator<Item = usize> + 'a {
    (0..surfaces.len()).filter(move |&other| {
        other != face
            && surfaces[face]
                .opposite_distance(&surfaces[other])
                .is_some_and(|distance| same_length(distance, thickness))
            && share_a_wall(neighbours, face, other)
    })
}

/// The faces reached from `start` across edges where the surface continues smoothly, in
/// breadth-first order.
pub fn smooth_region(
    surfaces: &[SheetSurface],
    neighbours: &[Vec<usize>],
    start: usize,
) -> Vec<usize> {
    let mut region = vec![start];
    let mut next = 0;
    while next < region.len() {
        let face = region[next];
        next += 1;
        for &other in &neighbours[face] {
            if !region.contains(&other) && surfaces[face].tangent_to(&surfaces[other]) {
                region.push(other);
            }
        }
    }
    region
}

/// Which faces are on the other skin: the chosen skin's opposite faces ([`ThinSolid::partners`])
/// and every face opposite one of its faces at the thickness across a wall.
fn other_skin(solid: &ThinSolid) -> Vec<bool> {
    let on_skin = |face: usize| solid.skin.contains(&face);
    (0..solid.surfaces.len())
        .map(|face| {
            !on_skin(face)
                && (solid.partners.contains(&face)
                    || solid.skin.iter().any(|&skin_face| {
                        opposite_faces(
                            &solid.surfaces,
                            &solid.neighbours,
                            skin_face,
                            solid.thickness,
                        )
                        .any(|other| other == face)
                    }))
        })
        .collect()
}

/// The formed faces on the chosen skin and those on the other skin, each ascending: a
/// connected group of formed faces belongs to the skin whose faces it touches when it touches
/// one skin only (a dimple's two sides, each running into its flange's side). A group touching
/// both skins is left to be a wall, one touching neither is neither ([`check_walls`]).
fn formed_sides(solid: &ThinSolid, other_skin: &[bool]) -> (Vec<usize>, Vec<usize>) {
    let (mut chosen, mut other) = (Vec::new(), Vec::new());
    for group in formed_groups(&solid.surfaces, &solid.neighbours) {
        let touches = |side: &dyn Fn(usize) -> bool| {
            group
                .iter()
                .any(|&face| solid.neighbours[face].iter().any(|&n| side(n)))
        };
        let on_chosen = touches(&|face| solid.skin.contains(&face));
        let on_other = touches(&|face| other_skin[face]);
        match (on_chosen, on_other) {
            (true, false) => chosen.extend(group),
            (false, true) => other.extend(group),
            _ => {}
        }
    }
    chosen.sort_unstable();
    other.sort_unstable();
    (chosen, other)
}

/// The formed faces grouped by adjacency (each group connected through formed faces), in
/// order of their first face.
pub(super) fn formed_groups(
    surfaces: &[SheetSurface],
    neighbours: &[Vec<usize>],
) -> Vec<Vec<usize>> {
    let mut grouped = vec![false; surfaces.len()];
    let mut groups = Vec::new();
    for start in 0..surfaces.len() {
        if grouped[start] || surfaces[start] != SheetSurface::Formed {
            continue;
        }
        grouped[start] = true;
        let mut group = vec![start];
        let mut next = 0;
        while next < group.len() {
            for &other in &neighbours[group[next]] {
                if !grouped[other] && surfaces[other] == SheetSurface::Formed {
                    grouped[other] = true;
                    group.push(other);
                }
            }
            next += 1;
        }
        groups.push(group);
    }
    groups
}

/// Checks that every face is on a skin (the chosen one, `other_skin`, or formed on either) or
/// is a wall touching both skins.
fn check_walls(
    shell: &BrepShell,
    solid: &ThinSolid,
    other_skin: &[bool],
    other_formed: &[usize],
) -> Result<(), NotASheet> {
    let on_skin = |face: usize| solid.skin.contains(&face) || solid.formed.contains(&face);
    let on_other = |face: usize| other_skin[face] || other_formed.contains(&face);
    for face in (0..solid.surfaces.len()).filter(|&face| !on_skin(face) && !on_other(face)) {
        let touches_skin = solid.neighbours[face].iter().any(|&n| on_skin(n));
        let touches_other = solid.neighbours[face].iter().any(|&n| on_other(n));
        if !(touches_skin && touches_other) {
            return Err(NotASheet::NoConstantThickness(format!(
                "{} is neither on a skin nor a wall between the two skins",
                shell.describe_face(face)
            )));
        }
    }
    Ok(())
}
