//! The rulings of a ruled surface: the straight lines it is made of, as pairs of points on its
//! two curves, the curves sampled at a mesh size and chord tolerance.
//!
//! The loft correspondence follows the classical construction of a developable transition: each
//! ruling joins the points of the two sections whose tangents are parallel, found by merging the
//! sections' edge directions in angular order (a polygon corner becomes the apex of a cone fan,
//! a polygon side the base of a plane triangle or trapezoid).

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::frame::Frame;
use super::profile::{fractions_through, pieces_for_arc, pieces_for_length};
use super::surface::{RuledSurface, Section};
use crate::geometry::tolerance::PARALLEL_ANGLE_TOLERANCE;

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

/// The rulings of `surface`, sections sampled at `mesh_size` and `chord`.
pub fn rulings(surface: &RuledSurface, mesh_size: f64, chord: f64) -> Rulings {
    rulings_through(surface, mesh_size, chord, &[])
}

/// [`rulings`] with a ruling at each domain `u` of `through` (the angle in degrees of a cylinder
/// or a cone, the arc length along an extrusion's profile; see
/// [`SurfaceDomain`](super::SurfaceDomain)): the stretches of the sections between them are
/// sampled each on its own, so that the rulings next to them keep about their usual spacing. A
/// loft's rulings are fixed by its sections' tangents and ignore `through`.
pub fn rulings_through(
    surface: &RuledSurface,
    mesh_size: f64,
    chord: f64,
    through: &[f64],
) -> Rulings {
    match surface {
        RuledSurface::Circular {
            frame,
            bottom,
            top,
            angles,
        } => {
            let range = angles[1] - angles[0];
            let radius = bottom.radius.max(top.radius);
            let stations: Vec<f64> = through
                .iter()
                .map(|u| (u.to_radians() - angles[0]) / range)
                .collect();
            let fractions = fractions_through(&stations, |span| {
                pieces_for_arc(radius, range * span, mesh_size, chord)
            });
            let angle =
                std::iter::once(angles[0]).chain(fractions.iter().map(|t| angles[0] + t.of(range)));
            let (bottom, top) = angle
                .map(|a| (frame.point(bottom.point(a)), frame.point(top.point(a))))
                .unzip();
            same_index_rulings(bottom, top)
        }
        RuledSurface::Extrusion {
            frame,
            profile,
            direction,
        } => {
            let points = profile.sample_through(mesh_size, chord, through);
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
        // A long side is split into pieces of at most the mesh size. Two parallel sides are split
        // each to its own length, their points paired along a monotone path: every ruling
        // between them stays in their common plane, which is meshed as one planar piece.
        let count = |advance: bool, edge: [DVec3; 2]| {
            if advance {
                pieces_for_length(edge[0].distance(edge[1]), mesh_size)
            } else {
                0
            }
        };
        let (lower_pieces, upper_pieces) = (
            count(advance_lower, lower_edge),
            count(advance_upper, upper_edge),
        );
        let steps = lower_pieces.max(upper_pieces);
        let (mut lower_done, mut upper_done) = (0, 0);
        for k in 1..=steps {
            if lower_done < k * lower_pieces / steps {
                lower_done += 1;
                let t = lower_done as f64 / lower_pieces as f64;
                rulings.bottom.push(lower_edge[0].lerp(lower_edge[1], t));
            }
            if upper_done < k * upper_pieces / steps {
                upper_done += 1;
                let t = upper_done as f64 / upper_pieces as f64;
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
