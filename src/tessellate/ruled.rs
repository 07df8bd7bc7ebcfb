//! Structured meshes of ruled surfaces along their rulings.
//!
//! Input: a [`RuledSurface`], a target edge length `mesh_size` and a chord tolerance (part units).
//! Output: a [`FaceMesh`] whose every vertex lies on a ruling and whose every triangle lies between
//! two consecutive rulings. For a developable surface (cylinder, cone, the convex hull of two
//! sections in parallel planes, an extrusion) the quadrilateral between two consecutive rulings of
//! the sampled sections is planar, so the mesh is exactly developable: it flattens with no strain,
//! which is how E_S and E_C reach round-off on these kinds. A closed section (a full turn) is
//! opened along its first ruling: the seam's vertices are duplicated, not shared.
//!
//! The loft correspondence follows the classical construction of a developable transition: each
//! ruling joins the points of the two sections whose tangents are parallel, found by merging the
//! sections' edge directions in angular order (a polygon corner becomes the apex of a cone fan,
//! a polygon side the base of a plane triangle or trapezoid).

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::face_mesh::FaceMesh;
use super::strip::stitch_rows;
use super::surface::{Frame, RuledSurface, Section, pieces_for_arc, pieces_for_length};

/// Two edge directions closer than this (radians) are parallel: both sections advance together.
pub const PARALLEL_ANGLE_TOLERANCE: f64 = 1e-9;

/// A circle section of a loft has at least this many corners.
pub const MINIMUM_CIRCLE_PIECES: usize = 8;

/// The rulings of a surface: section points (in part coordinates) and which pairs they join.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Rulings {
    /// Points of the first curve.
    pub bottom: Vec<DVec3>,
    /// Points of the second curve.
    pub top: Vec<DVec3>,
    /// Each ruling as `[bottom index, top index]`; consecutive rulings advance one or both.
    pub pairs: Vec<[usize; 2]>,
}

/// Meshes a ruled surface along its rulings.
pub fn mesh_ruled(surface: &RuledSurface, mesh_size: f64, chord: f64) -> FaceMesh {
    mesh_rulings(&rulings(surface, mesh_size, chord), mesh_size)
}

/// The rulings of `surface`, sections sampled at `mesh_size` and `chord`.
pub fn rulings(surface: &RuledSurface, mesh_size: f64, chord: f64) -> Rulings {
    match surface {
        RuledSurface::Circular {
            frame,
            bottom,
            top,
            angles,
        } => {
            let range = angles[1] - angles[0];
            let radius = bottom.radius.max(top.radius);
            let pieces = pieces_for_arc(radius, range, mesh_size, chord);
            let angle = |k: usize| angles[0] + range * k as f64 / pieces as f64;
            let bottom = (0..=pieces).map(|k| frame.point(bottom.point(angle(k))));
            let top = (0..=pieces).map(|k| frame.point(top.point(angle(k))));
            same_index_rulings(bottom.collect(), top.collect())
        }
        RuledSurface::Extrusion {
            frame,
            profile,
            direction,
        } => {
            let points = profile.sample(mesh_size, chord);
            let bottom: Vec<DVec3> = points.iter().map(|p| frame.point(p.extend(0.0))).collect();
            let offset = frame.vector(*direction);
            let top = bottom.iter().map(|&p| p + offset).collect();
            same_index_rulings(bottom, top)
        }
        RuledSurface::Loft {
            frame,
            bottom,
            top,
            seam,
        } => loft_rulings(frame, bottom, top, *seam, mesh_size, chord),
    }
}

fn same_index_rulings(bottom: Vec<DVec3>, top: Vec<DVec3>) -> Rulings {
    let pairs = (0..bottom.len()).map(|k| [k, k]).collect();
    Rulings { bottom, top, pairs }
}

/// A closed convex polygon sampled from a section, starting at its support point for the seam
/// direction, with the direction of each outgoing edge measured from the seam in `[0, 2π)`.
struct SampledSection {
    corners: Vec<DVec2>,
    directions: Vec<f64>,
}

/// Samples a section; circles get `circle_pieces` corners (the same for both sections of a loft,
/// so that two circles pair corner for corner).
fn sample_section(section: &Section, seam: f64, circle_pieces: usize) -> SampledSection {
    match section {
        Section::Circle { center, radius, .. } => {
            let pieces = circle_pieces;
            // Corner k has tangent direction seam + 2πk/n: corner 0 is the support point of the
            // seam direction; edge k turns halfway between its corners.
            let corners = (0..pieces)
                .map(|k| {
                    let tangent = seam + TAU * k as f64 / pieces as f64;
                    *center + DVec2::from_angle(tangent - TAU / 4.0) * *radius
                })
                .collect();
            let directions = (0..pieces)
                .map(|k| TAU * (k as f64 + 0.5) / pieces as f64)
                .collect();
            SampledSection {
                corners,
                directions,
            }
        }
        Section::Polygon { corners, .. } => {
            let count = corners.len();
            let direction = |k: usize| {
                let edge = corners[(k + 1) % count] - corners[k];
                (edge.y.atan2(edge.x) - seam).rem_euclid(TAU)
            };
            let start = (0..count)
                .min_by(|&a, &b| direction(a).total_cmp(&direction(b)))
                .unwrap_or(0);
            let order: Vec<usize> = (0..count).map(|k| (start + k) % count).collect();
            SampledSection {
                corners: order.iter().map(|&k| corners[k]).collect(),
                directions: order.iter().map(|&k| direction(k)).collect(),
            }
        }
    }
}

fn loft_rulings(
    frame: &Frame,
    bottom: &Section,
    top: &Section,
    seam: f64,
    mesh_size: f64,
    chord: f64,
) -> Rulings {
    let radius = [bottom, top]
        .iter()
        .filter_map(|section| match section {
            Section::Circle { radius, .. } => Some(*radius),
            Section::Polygon { .. } => None,
        })
        .fold(0.0, f64::max);
    let circle_pieces = pieces_for_arc(radius, TAU, mesh_size, chord).max(MINIMUM_CIRCLE_PIECES);
    let lower = sample_section(bottom, seam, circle_pieces);
    let upper = sample_section(top, seam, circle_pieces);
    let lower_point =
        |k: usize| frame.point(lower.corners[k % lower.corners.len()].extend(bottom.z()));
    let upper_point =
        |k: usize| frame.point(upper.corners[k % upper.corners.len()].extend(top.z()));
    let mut rulings = Rulings {
        bottom: vec![lower_point(0)],
        top: vec![upper_point(0)],
        pairs: vec![[0, 0]],
    };
    let (mut i, mut j) = (0, 0);
    let (lower_count, upper_count) = (lower.directions.len(), upper.directions.len());
    while i < lower_count || j < upper_count {
        let lower_next = lower.directions.get(i).copied().unwrap_or(f64::INFINITY);
        let upper_next = upper.directions.get(j).copied().unwrap_or(f64::INFINITY);
        let both = (lower_next - upper_next).abs() <= PARALLEL_ANGLE_TOLERANCE;
        let advance_lower = both || lower_next < upper_next;
        let advance_upper = both || !advance_lower;
        let lower_edge = [lower_point(i), lower_point(i + 1)];
        let upper_edge = [upper_point(j), upper_point(j + 1)];
        // A long side is split into pieces of at most the mesh size; two parallel sides are
        // split alike so that every ruling stays in their common plane.
        let mut pieces = 1;
        if advance_lower {
            pieces = pieces.max(pieces_for_length(
                lower_edge[0].distance(lower_edge[1]),
                mesh_size,
            ));
        }
        if advance_upper {
            pieces = pieces.max(pieces_for_length(
                upper_edge[0].distance(upper_edge[1]),
                mesh_size,
            ));
        }
        for k in 1..=pieces {
            let t = k as f64 / pieces as f64;
            if advance_lower {
                rulings.bottom.push(lower_edge[0].lerp(lower_edge[1], t));
            }
            if advance_upper {
                rulings.top.push(upper_edge[0].lerp(upper_edge[1], t));
            }
            rulings
                .pairs
                .push([rulings.bottom.len() - 1, rulings.top.len() - 1]);
        }
        i += usize::from(advance_lower);
        j += usize::from(advance_upper);
    }
    rulings
}

/// Meshes rulings: each ruling split into pieces of at most `mesh_size`, consecutive rulings
/// stitched. Section points shared by consecutive rulings become shared vertices.
pub fn mesh_rulings(rulings: &Rulings, mesh_size: f64) -> FaceMesh {
    let mut mesh = FaceMesh::default();
    let bottom: Vec<u32> = rulings.bottom.iter().map(|&p| mesh.add_vertex(p)).collect();
    let top: Vec<u32> = rulings.top.iter().map(|&p| mesh.add_vertex(p)).collect();
    let mut previous: Option<Vec<u32>> = None;
    for &[b, t] in &rulings.pairs {
        let (start, end) = (rulings.bottom[b], rulings.top[t]);
        let pieces = pieces_for_length(start.distance(end), mesh_size);
        let mut row = vec![bottom[b]];
        for k in 1..pieces {
            row.push(mesh.add_vertex(start.lerp(end, k as f64 / pieces as f64)));
        }
        row.push(top[t]);
        if let Some(left) = &previous {
            stitch_rows(left, &row, &mesh.positions, &mut mesh.triangles);
        }
        previous = Some(row);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tessellate::surface::RuledCircle;

    fn area(mesh: &FaceMesh) -> f64 {
        mesh.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    #[test]
    fn a_cylinder_strip_has_the_area_of_its_polygon() {
        let surface = RuledSurface::Circular {
            frame: Frame::WORLD,
            bottom: RuledCircle {
                center: DVec3::ZERO,
                radius: 50.0,
                tilt: 0.0,
            },
            top: RuledCircle {
                center: DVec3::new(0.0, 0.0, 100.0),
                radius: 50.0,
                tilt: 0.0,
            },
            angles: [0.0, TAU],
        };
        let mesh = mesh_ruled(&surface, 5.0, 0.05);
        let analytic = TAU * 50.0 * 100.0;
        assert!((area(&mesh) - analytic).abs() / analytic < 1e-3);
    }

    #[test]
    fn square_to_round_rulings_fan_from_the_corners() {
        let surface = RuledSurface::Loft {
            frame: Frame::WORLD,
            bottom: Section::Polygon {
                corners: vec![
                    DVec2::new(-100.0, -100.0),
                    DVec2::new(100.0, -100.0),
                    DVec2::new(100.0, 100.0),
                    DVec2::new(-100.0, 100.0),
                ],
                z: 0.0,
            },
            top: Section::Circle {
                center: DVec2::ZERO,
                radius: 60.0,
                z: 150.0,
            },
            seam: 0.0,
        };
        let rulings = rulings(&surface, 10.0, 0.1);
        // Each side of 200 is split into 20 pieces of 10; the last point closes the loop.
        assert_eq!(rulings.bottom.len(), 81);
        assert!(rulings.bottom[80].distance(rulings.bottom[0]) < 1e-12);
        // Rulings advance one or both ends by one point at a time, and some stay on a square
        // corner while the circle turns: the cone fans.
        assert!(rulings.pairs.windows(2).all(|w| {
            let step = [w[1][0] - w[0][0], w[1][1] - w[0][1]];
            step[0] <= 1 && step[1] <= 1 && step[0] + step[1] >= 1
        }));
        let fan_steps = rulings
            .pairs
            .windows(2)
            .filter(|w| w[0][0] == w[1][0])
            .count();
        assert!(fan_steps >= 4);
        // Top points lie on the circle or on a chord of it split to match a parallel side.
        assert!(rulings.top.iter().all(|p| {
            let radius = p.truncate().length();
            (59.0..=60.0 + 1e-9).contains(&radius)
        }));
        assert_eq!(rulings.pairs.last(), Some(&[80, rulings.top.len() - 1]));
    }
}
