//! The exact unfold of a thin solid's chosen skin, on the B-rep: the base flange fixed, every
//! other flange placed rigidly, every bend unrolled at its neutral fibre (`R_inner + K · t`), so
//! that the flat length across a bend is its bend allowance (a bend on a cone developed at its
//! neutral cone, `cone_bend.rs`). The skin's triangles (from the
//! tessellation) carry the unfold to the flat pattern: each vertex goes where its face's map puts
//! it, so holes and cut-outs come out as the inner boundaries of the flat skin.

use glam::{DVec2, DVec3};

use super::bend::{BendDirection, BendLine};
use super::bend_rule::{BendAllowance, BendGeometry, BendRule, allowance_by_rule};
use super::cone_bend::{ConeFigures, enter_cone_bend};
use super::face_map::{BendMap, BendSurfaceMap, FaceMap, PlaneMap};
use super::options::SheetOptions;
use super::recognise::{ThinSolid, formed_groups};
use super::surfaces::SheetSurface;
use crate::cad::TriangleSoup;
use crate::geometry::long_side_of_smallest_rectangle;

/// A thin solid's skin and its flat pattern.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetUnfold {
    /// The sheet's thickness, mm.
    pub thickness: f64,
    /// The K-factor every bend was unrolled with, when the rule is the K-factor.
    pub k_factor: Option<f64>,
    /// The bend rule in words (`K 0.44`, `DIN 6935`, `bend table FILE`).
    pub rule: String,
    /// The face the unfold started from (the largest planar face), in the shell's face order.
    pub base_face: usize,
    /// The chosen skin's triangles, counter-clockwise seen from outside the solid, tagged with
    /// their faces.
    pub skin: TriangleSoup,
    /// The flat position of every vertex of `skin`, seen from outside the skin, its smallest
    /// bounding rectangle axis-aligned (longer side along x) and starting at the origin.
    pub flat: Vec<DVec2>,
    /// The bends, in the order the unfold met them, in the flat pattern's frame.
    pub bends: Vec<BendLine>,
    /// The skin's formed regions, each drawn as its projection onto its flange.
    pub formed: Vec<FormedRegion>,
}

/// A formed region of the skin (a dimple, a louvre: faces that are not developable) drawn as
/// its projection onto the plane of the one flange it lies in: the flat blank a stretch-formed
/// feature is pressed from.
#[derive(Debug, Clone, PartialEq)]
pub struct FormedRegion {
    /// Its faces, ascending, in the shell's face order.
    pub faces: Vec<usize>,
    /// A face of the flange it lies in.
    pub flange: usize,
}

/// Why a thin solid's skin is not unfolded exactly.
#[derive(Debug, Clone, PartialEq)]
pub enum UnfoldRefusal {
    /// The bend rule does not cover a bend (the reason): the part is refused.
    Rule(String),
    /// A formed region cannot be drawn as its projection onto one flange (`reason`): the skin
    /// is flattened by the energy model instead.
    FormedRegion {
        /// The region's faces, in the shell's face order.
        faces: Vec<usize>,
        /// Why its projection does not do.
        reason: String,
    },
    /// Two faces of the skin put a vertex they share `gap` mm apart on the flat: the skin does
    /// not develop as one piece (a conical bend meeting a cylindrical one, bends closing a
    /// loop); it is flattened by the energy model instead.
    Disagreement {
        /// The two faces, in the shell's face order.
        faces: [usize; 2],
        /// How far apart they put their common vertex, mm.
        gap: f64,
    },
}

/// Largest distance, in mm, between the flat positions two faces of the skin give a vertex
/// they share (an exact unfold puts it at one point, to round-off).
const FLAT_AGREEMENT_MM: f64 = 1e-3;

/// A bend met by the unfold: its map and whether the skin is on its inside.
#[derive(Debug, Clone, Copy)]
struct BendZone {
    map: BendSurfaceMap,
    inner_radius: f64,
    skin_inside: bool,
}

/// Unfolds the chosen skin of `solid`, whose triangles are those of `soup` tagged with the
/// skin's faces (a soup's face source is the shell's face index), each bend's allowance by the
/// options' rule (a table's rows picked by `material`), each formed region projected onto its
/// flange ([`FormedRegion`]); refused when the rule does not cover a bend or a formed region
/// cannot be projected.
pub fn unfold_skin(
    solid: &ThinSolid,
    soup: &TriangleSoup,
    options: &SheetOptions,
    material: Option<&str>,
) -> Result<SheetUnfold, UnfoldRefusal> {
    let mut skin = skin_triangles(solid, soup);
    let face_vertices = vertices_by_face(&skin, solid.surfaces.len());
    let k_neutral = |_: usize, inner: f64| inner + options.k_factor * solid.thickness;
    let (maps, zones) = face_maps(solid, &skin, &face_vertices, &k_neutral);
    let allowances = zones
        .iter()
        .enumerate()
        .map(|(index, zone)| {
            let bend = bend_geometry(solid.thickness, zone, &bend_points(&skin, &maps, index));
            if matches!(zone.map, BendSurfaceMap::Cone(_)) && options.rule != BendRule::KFactor {
                return Err(conical_rule_refusal(options, &bend));
            }
            allowance_by_rule(&options.rule, options.k_factor, bend, material)
                .map(|allowance| (bend.angle, allowance))
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(UnfoldRefusal::Rule)?;
    let rule_neutral = |index: usize, inner: f64| match (zones.get(index), allowances.get(index)) {
        (Some(zone), _) if matches!(zone.map, BendSurfaceMap::Cone(_)) => k_neutral(index, inner),
        (_, Some(&(angle, ref allowance))) if angle > 0.0 => allowance.allowance / angle,
        _ => k_neutral(index, inner),
    };
    let (mut maps, zones) = face_maps(solid, &skin, &face_vertices, &rule_neutral);
    let formed = project_formed(solid, &mut maps)?;
    let flat = flat_positions(&skin, &maps)?;
    if wound_clockwise(&skin, &flat) {
        for triangle in &mut skin.triangles {
            triangle.swap(1, 2);
        }
    }
    check_formed_projections(&skin, &flat, &formed)?;
    let mut bends: Vec<BendLine> = zones
        .iter()
        .zip(allowances)
        .enumerate()
        .map(|(index, (zone, (_, allowance)))| {
            bend_line(
                zone,
                solid.thickness,
                bend_points(&skin, &maps, index),
                allowance,
            )
        })
        .collect();
    let mut flat = flat;
    rest_position(&mut flat, &mut bends);
    Ok(SheetUnfold {
        thickness: solid.thickness,
        k_factor: (options.rule == BendRule::KFactor).then_some(options.k_factor),
        rule: options.rule.describe(options.k_factor),
        base_face: solid.base_face,
        skin,
        flat,
        bends,
        formed,
    })
}

/// Maps each formed region of the skin onto the plane of the flange it lies in (orthogonal
/// projection, [`FaceMap::Flange`]): every face it touches must be a face of that one flange,
/// which surrounds it (a region running into a bend, joining two flanges or reaching a wall, as
/// a curl at the edge or a louvre's lance does, is refused).
fn project_formed(
    solid: &ThinSolid,
    maps: &mut [Option<FaceMap>],
) -> Result<Vec<FormedRegion>, UnfoldRefusal> {
    let groups = formed_groups(&solid.surfaces, &solid.neighbours);
    let mut regions = Vec::new();
    for mut faces in groups
        .into_iter()
        .filter(|group| solid.formed.contains(&group[0]))
    {
        faces.sort_unstable();
        let mut touched: Vec<usize> = faces
            .iter()
            .flat_map(|&face| solid.neighbours[face].iter().copied())
            .filter(|face| solid.skin.contains(face))
            .collect();
        touched.sort_unstable();
        touched.dedup();
        let refuse = |reason: &str| UnfoldRefusal::FormedRegion {
            faces: faces.clone(),
            reason: reason.to_owned(),
        };
        let flange_maps: Vec<Option<PlaneMap>> = touched
            .iter()
            .map(|&face| match maps[face] {
                Some(FaceMap::Flange(map)) => Some(map),
                _ => None,
            })
            .collect();
        let Some(&Some(map)) = flange_maps.first() else {
            return Err(refuse(if touched.is_empty() {
                "it touches no flange"
            } else {
                "it runs into a bend"
            }));
        };
        if flange_maps.iter().any(|other| *other != Some(map)) {
            return Err(refuse(
                "it runs into a bend or joins flanges that do not lie in one plane",
            ));
        }
        let meets_a_wall = faces.iter().any(|&face| {
            solid.neighbours[face]
                .iter()
                .any(|n| !solid.skin.contains(n) && !solid.formed.contains(n))
        });
        if meets_a_wall {
            return Err(refuse(
                "it reaches an edge of the sheet (a wall: the outline, a hole, a lance), so its flat extent is not its projection's",
            ));
        }
        for &face in &faces {
            maps[face] = Some(FaceMap::Flange(map));
        }
        regions.push(FormedRegion {
            faces,
            flange: touched[0],
        });
    }
    Ok(regions)
}

/// Refuses a formed region whose projection folds over: one of its triangles turned over (or
/// flat) on the pattern, whose triangles all turn counter-clockwise; the form is then not a
/// height field over its flange.
fn check_formed_projections(
    skin: &TriangleSoup,
    flat: &[DVec2],
    formed: &[FormedRegion],
) -> Result<(), UnfoldRefusal> {
    for region in formed {
        let folds_over = skin
            .triangles
            .iter()
            .zip(&skin.face_sources)
            .filter(|&(_, face)| region.faces.contains(&(*face as usize)))
            .any(|(&[a, b, c], _)| {
                let [a, b, c] = [a, b, c].map(|v| flat[v as usize]);
                (b - a).perp_dot(c - a) <= 0.0
            });
        if folds_over {
            return Err(UnfoldRefusal::FormedRegion {
                faces: region.faces.clone(),
                reason: "its projection onto its flange folds over".to_owned(),
            });
        }
    }
    Ok(())
}

/// The triangles of `soup` (a tessellation of the solid, each triangle tagged with its face's
/// index in the shell) on the chosen skin's faces and its formed faces, with only the vertices
/// they use.
pub fn skin_triangles(solid: &ThinSolid, soup: &TriangleSoup) -> TriangleSoup {
    let mut on_skin = vec![false; solid.surfaces.len()];
    for &face in solid.skin.iter().chain(&solid.formed) {
        on_skin[face] = true;
    }
    let mut index = vec![u32::MAX; soup.positions.len()];
    let mut skin = TriangleSoup::default();
    for (triangle, &face) in soup.triangles.iter().zip(&soup.face_sources) {
        if !on_skin.get(face as usize).copied().unwrap_or(false) {
            continue;
        }
        let corners = triangle.map(|vertex| {
            let slot = &mut index[vertex as usize];
            if *slot == u32::MAX {
                *slot = skin.positions.len() as u32;
                skin.positions.push(soup.positions[vertex as usize]);
            }
            *slot
        });
        skin.triangles.push(corners);
        skin.face_sources.push(face);
    }
    skin
}

/// The vertices of each face's triangles, per face of the shell.
fn vertices_by_face(skin: &TriangleSoup, faces: usize) -> Vec<Vec<u32>> {
    let mut vertices = vec![Vec::new(); faces];
    for (triangle, &face) in skin.triangles.iter().zip(&skin.face_sources) {
        vertices[face as usize].extend_from_slice(triangle);
    }
    for list in &mut vertices {
        list.sort_unstable();
        list.dedup();
    }
    vertices
}

/// Every skin face's map to the flat pattern, reached from the base face across smooth edges,
/// and the bends met on the way; `neutral` gives the neutral radius of the bend met `index`-th
/// from its inner radius.
fn face_maps(
    solid: &ThinSolid,
    skin: &TriangleSoup,
    face_vertices: &[Vec<u32>],
    neutral: &dyn Fn(usize, f64) -> f64,
) -> (Vec<Option<FaceMap>>, Vec<BendZone>) {
    let mut maps: Vec<Option<FaceMap>> = vec![None; solid.surfaces.len()];
    let mut zones = Vec::new();
    maps[solid.base_face] = Some(FaceMap::Flange(base_map(solid)));
    let mut queue = vec![solid.base_face];
    let mut next = 0;
    while next < queue.len() {
        let face = queue[next];
        next += 1;
        let Some(map) = maps[face] else { continue };
        for &other in &solid.neighbours[face] {
            let on_skin = solid.skin.contains(&other);
            if !on_skin
                || maps[other].is_some()
                || !solid.surfaces[face].tangent_to(&solid.surfaces[other])
            {
                continue;
            }
            let surface = solid.surfaces[other];
            maps[other] = Some(match (map, surface) {
                // A formed face continues no face, so it is never reached here.
                (FaceMap::Flange(plane), SheetSurface::Plane { .. } | SheetSurface::Formed) => {
                    FaceMap::Flange(plane)
                }
                (FaceMap::Flange(plane), SheetSurface::Cone { .. }) => {
                    let positions = face_vertices[other]
                        .iter()
                        .map(|&v| skin.positions[v as usize]);
                    let partner = solid.skin.iter().position(|&f| f == other).unwrap_or(0);
                    let entry = enter_cone_bend(
                        &plane,
                        &solid.surfaces[face],
                        &surface,
                        &solid.surfaces[solid.partners[partner]],
                        positions,
                        solid.thickness,
                        &|inner| neutral(zones.len(), inner),
                    );
                    let map = BendSurfaceMap::Cone(entry.map);
                    zones.push(BendZone {
                        map,
                        inner_radius: entry.inner_radius,
                        skin_inside: entry.skin_inside,
                    });
                    FaceMap::Bend(zones.len() - 1, map)
                }
                (FaceMap::Flange(plane), SheetSurface::Cylinder { .. }) => {
                    let positions = face_vertices[other]
                        .iter()
                        .map(|&v| skin.positions[v as usize]);
                    let zone = enter_bend(
                        solid,
                        &plane,
                        &solid.surfaces[face],
                        other,
                        positions,
                        &|inner| neutral(zones.len(), inner),
                    );
                    zones.push(zone);
                    FaceMap::Bend(zones.len() - 1, zone.map)
                }
                (FaceMap::Bend(_, BendSurfaceMap::Cylinder(bend)), SheetSurface::Plane { .. }) => {
                    FaceMap::Flange(bend.flange_at(bend.angle(tangent_point(&bend, &surface))))
                }
                (
                    FaceMap::Bend(_, BendSurfaceMap::Cone(cone)),
                    SheetSurface::Plane { normal, .. },
                ) => FaceMap::Flange(cone.flange_at(cone.tangent_angle(normal))),
                (bend @ FaceMap::Bend(..), _) => bend,
            });
            queue.push(other);
        }
    }
    (maps, zones)
}

/// The base face's map: its plane seen from outside the skin (away from the other skin), any
/// in-plane axes.
fn base_map(solid: &ThinSolid) -> PlaneMap {
    let SheetSurface::Plane { origin, normal } = solid.surfaces[solid.base_face] else {
        unreachable!("the base face is the largest planar face");
    };
    let partner = solid.surfaces[solid.partners[0]];
    let SheetSurface::Plane {
        origin: partner_origin,
        ..
    } = partner
    else {
        unreachable!("a plane's opposite face is a plane");
    };
    let outward = if (origin - partner_origin).dot(normal) >= 0.0 {
        normal
    } else {
        -normal
    };
    let first = outward.any_orthonormal_vector();
    PlaneMap {
        origin,
        axes: [first, outward.cross(first)],
        flat_origin: DVec2::ZERO,
        flat_axes: [DVec2::X, DVec2::Y],
    }
}

/// The bend a flange (`plane`, its surface `flange`) runs into at face `face` (a cylinder whose
/// triangle vertices are `positions`): unrolled from the tangent line, turning the way the face
/// lies, at the neutral radius `neutral` gives for its inner radius.
fn enter_bend(
    solid: &ThinSolid,
    plane: &PlaneMap,
    flange: &SheetSurface,
    face: usize,
    positions: impl Iterator<Item = DVec3> + Clone,
    neutral: &dyn Fn(f64) -> f64,
) -> BendZone {
    let SheetSurface::Cylinder {
        origin,
        axis,
        radius,
    } = solid.surfaces[face]
    else {
        unreachable!("a bend is a cylinder");
    };
    let SheetSurface::Plane {
        origin: flange_origin,
        normal,
    } = *flange
    else {
        unreachable!("a bend is entered from a flange");
    };
    let start = -normal * (origin - flange_origin).dot(normal).signum();
    let across = axis.cross(start);
    let farthest = positions
        .map(|p| (p - origin).dot(across))
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(1.0);
    let towards = if farthest >= 0.0 { across } else { -across };
    let skin_position = solid.skin.iter().position(|&f| f == face).unwrap_or(0);
    let partner_radius = match solid.surfaces[solid.partners[skin_position]] {
        SheetSurface::Cylinder { radius, .. } => radius,
        _ => radius,
    };
    let skin_inside = radius < partner_radius;
    let inner_radius = radius.min(partner_radius);
    BendZone {
        map: BendSurfaceMap::Cylinder(BendMap {
            axis_origin: origin,
            axis,
            start,
            towards,
            skin_radius: radius,
            neutral_radius: neutral(inner_radius),
            flat_origin: plane.point(origin + start * radius),
            flat_axis: plane.direction(axis),
            flat_across: plane.direction(towards),
        }),
        inner_radius,
        skin_inside,
    }
}

/// The point where a plane tangent to a bend touches it (on the radial line at `a = 0`).
fn tangent_point(bend: &BendMap, plane: &SheetSurface) -> DVec3 {
    let SheetSurface::Plane { origin, normal } = *plane else {
        unreachable!("only a plane touches a bend along a line");
    };
    let distance = (bend.axis_origin - origin).dot(normal);
    bend.axis_origin - normal * distance
}

/// Every skin vertex's flat position, from the first face that uses it; refused when two faces
/// put a vertex they share more than [`FLAT_AGREEMENT_MM`] apart: the skin does not develop as
/// one piece (a conical bend meeting a cylindrical one, bends closing a loop).
fn flat_positions(
    skin: &TriangleSoup,
    maps: &[Option<FaceMap>],
) -> Result<Vec<DVec2>, UnfoldRefusal> {
    let mut flat: Vec<Option<(DVec2, u32)>> = vec![None; skin.positions.len()];
    for (triangle, &face) in skin.triangles.iter().zip(&skin.face_sources) {
        let Some(map) = maps[face as usize] else {
            continue;
        };
        for &vertex in triangle {
            let point = map.point(skin.positions[vertex as usize]);
            match flat[vertex as usize] {
                None => flat[vertex as usize] = Some((point, face)),
                Some((first, first_face)) if first.distance(point) > FLAT_AGREEMENT_MM => {
                    return Err(UnfoldRefusal::Disagreement {
                        faces: [first_face as usize, face as usize],
                        gap: first.distance(point),
                    });
                }
                Some(_) => {}
            }
        }
    }
    Ok(flat
        .into_iter()
        .map(|p| p.map_or(DVec2::ZERO, |(point, _)| point))
        .collect())
}

/// Whether the soup's triangles turn clockwise on the flat pattern (a shell lists its faces seen
/// from inside; a part file's polygons may face either way): the pattern is then mirrored.
pub(super) fn wound_clockwise(soup: &TriangleSoup, flat: &[DVec2]) -> bool {
    let signed: f64 = soup
        .triangles
        .iter()
        .map(|&[a, b, c]| {
            let [a, b, c] = [a, b, c].map(|v| flat[v as usize]);
            (b - a).perp_dot(c - a)
        })
        .sum();
    signed < 0.0
}

/// The 3D positions of the vertices of bend `bend`'s faces.
fn bend_points(skin: &TriangleSoup, maps: &[Option<FaceMap>], bend: usize) -> Vec<DVec3> {
    skin.triangles
        .iter()
        .zip(&skin.face_sources)
        .filter(|&(_, &face)| matches!(maps[face as usize], Some(FaceMap::Bend(index, _)) if index == bend))
        .flat_map(|(triangle, _)| triangle.map(|v| skin.positions[v as usize]))
        .collect()
}

/// A bend's angle: the largest angle of its points from its start line.
fn bend_angle(map: &BendSurfaceMap, points: &[DVec3]) -> f64 {
    points.iter().map(|&p| map.angle(p)).fold(0.0, f64::max)
}

/// What a bend's allowance is computed from: a cylinder's inner radius and angle, a cone's
/// inner radius at the middle of its bend line and its developed angle.
fn bend_geometry(thickness: f64, zone: &BendZone, points: &[DVec3]) -> BendGeometry {
    match &zone.map {
        BendSurfaceMap::Cylinder(_) => BendGeometry {
            thickness,
            inner_radius: zone.inner_radius,
            angle: bend_angle(&zone.map, points),
        },
        BendSurfaceMap::Cone(map) => {
            let figures = ConeFigures::of(map, zone.skin_inside, thickness, points);
            BendGeometry {
                thickness,
                inner_radius: figures.middle_inner_radius(),
                angle: figures.developed_angle,
            }
        }
    }
}

/// Why a conical bend is not unfolded by a rule other than the K-factor: its inner radius
/// varies along the bend line, and only a neutral fibre at one depth `K · t` is a cone that
/// develops exactly.
fn conical_rule_refusal(options: &SheetOptions, bend: &BendGeometry) -> String {
    format!(
        "a conical bend (inner radius {:.4} mm at the middle of its bend line, varying along it) is unfolded exactly with the K-factor only, not by {}: give --k-factor",
        bend.inner_radius,
        options.rule.describe(options.k_factor)
    )
}

/// A bend's line on the flat pattern (its centre, from end to end along the axis), angle, inner
/// radius and allowance.
fn bend_line(
    zone: &BendZone,
    thickness: f64,
    points: Vec<DVec3>,
    allowance: BendAllowance,
) -> BendLine {
    let map = &zone.map;
    if let BendSurfaceMap::Cone(cone) = map {
        return conical_bend_line(zone, cone, thickness, &points, allowance);
    }
    let angle = bend_angle(map, &points);
    let (low, high) = points
        .iter()
        .map(|&p| map.along(p))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), a| {
            (low.min(a), high.max(a))
        });
    let inner_radius = zone.inner_radius;
    BendLine {
        line: [map.flat(low, angle / 2.0), map.flat(high, angle / 2.0)],
        direction: if zone.skin_inside {
            BendDirection::Up
        } else {
            BendDirection::Down
        },
        angle_degrees: angle.to_degrees(),
        inner_radius,
        allowance: allowance.allowance,
        rule: Some(allowance.rule),
        conical: None,
    }
}

/// A conical bend's line on the flat pattern (the developed generator halfway through it), the
/// angle its flange turns, its inner radius and allowance at the middle and at the ends.
fn conical_bend_line(
    zone: &BendZone,
    map: &super::face_map::ConeMap,
    thickness: f64,
    points: &[DVec3],
    allowance: BendAllowance,
) -> BendLine {
    let figures = ConeFigures::of(map, zone.skin_inside, thickness, points);
    let (line, conical) = figures.line(map);
    BendLine {
        line,
        direction: if zone.skin_inside {
            BendDirection::Up
        } else {
            BendDirection::Down
        },
        angle_degrees: figures.turn.to_degrees(),
        inner_radius: figures.middle_inner_radius(),
        allowance: allowance.allowance,
        rule: Some(allowance.rule),
        conical: Some(conical),
    }
}

/// Turns the pattern (and its bend lines) so that its smallest bounding rectangle is
/// axis-aligned with the longer side along x, and moves it to start at the origin.
pub fn rest_position(flat: &mut [DVec2], bends: &mut [BendLine]) {
    let turn = long_side_of_smallest_rectangle(flat)
        .map_or(DVec2::X, |direction| DVec2::new(direction.x, -direction.y));
    let low = flat
        .iter()
        .map(|&p| turn.rotate(p))
        .fold(DVec2::INFINITY, DVec2::min);
    let place = |p: DVec2| turn.rotate(p) - low;
    for p in flat.iter_mut() {
        *p = place(*p);
    }
    for bend in bends.iter_mut() {
        bend.move_points(place);
    }
}

#[cfg(test)]
mod tests {
    use crate::sheet::unfold::*;

    /// The map of the plane z = 0 moved by `shift` on the flat.
    fn shifted(shift: DVec2) -> Option<FaceMap> {
        Some(FaceMap::Flange(PlaneMap {
            origin: DVec3::ZERO,
            axes: [DVec3::X, DVec3::Y],
            flat_origin: shift,
            flat_axes: [DVec2::X, DVec2::Y],
        }))
    }

    /// A unit square of two triangles, one on face 0 and one on face 1, sharing a diagonal.
    fn square() -> TriangleSoup {
        TriangleSoup {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0)],
            triangles: vec![[0, 1, 2], [1, 3, 2]],
            face_sources: vec![0, 1],
            ..TriangleSoup::default()
        }
    }

    #[test]
    fn faces_agreeing_on_their_common_vertices_give_each_vertex_one_flat_position() {
        let flat = flat_positions(&square(), &[shifted(DVec2::ZERO), shifted(DVec2::ZERO)])
            .expect("one piece");
        assert_eq!(flat[3], DVec2::ONE);
    }

    #[test]
    fn faces_putting_a_common_vertex_apart_are_refused_naming_them_and_the_gap() {
        let maps = [shifted(DVec2::ZERO), shifted(DVec2::new(0.0, 0.01))];
        match flat_positions(&square(), &maps) {
            Err(UnfoldRefusal::Disagreement { faces, gap }) => {
                assert_eq!(faces, [0, 1]);
                assert!((gap - 0.01).abs() < 1e-12, "{gap}");
            }
            other => panic!("not refused: {other:?}"),
        }
        let within = [shifted(DVec2::ZERO), shifted(DVec2::new(0.0, 1e-4))];
        assert!(flat_positions(&square(), &within).is_ok());
    }
}
