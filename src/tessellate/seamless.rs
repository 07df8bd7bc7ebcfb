//! Faces of cylinders and cones written without a seam edge: the side of a cylinder bounded by
//! its two end circles only, each circle a loop that goes once round the axis (Onshape writes
//! cylinders, and the walls of round holes, this way). Such a face cannot be unrolled as it is,
//! so its two loops are joined into one along a ruling: the first loop from one of its points
//! once round, the ruling up to the other loop's point at the nearest angle, the other loop once
//! round the opposite way, and the ruling back down. The ruling's samples appear on both sides
//! of the joined loop, at the same positions, so the face's mesh welds across it into a ring.

use glam::DVec3;

use super::edge_sampling::EDGE_PIECE_RATIO;
use super::face_domain::BoundaryLoop;

/// A loop whose angle about the axis adds up to this many turns, within this much, goes once
/// round it.
const TURN_TOLERANCE: f64 = 0.25;

/// The angle of `point` about the line through `origin` along unit `axis`, in the plane of the
/// unit `reference` direction perpendicular to it.
fn angle_about(point: DVec3, origin: DVec3, axis: DVec3, reference: DVec3) -> f64 {
    let offset = point - origin;
    let radial = offset - axis * offset.dot(axis);
    axis.cross(reference)
        .dot(radial)
        .atan2(reference.dot(radial))
}

/// The signed number of turns a closed loop makes about the axis.
fn turns(points: &[DVec3], origin: DVec3, axis: DVec3, reference: DVec3) -> f64 {
    let angles: Vec<f64> = points
        .iter()
        .map(|&p| angle_about(p, origin, axis, reference))
        .collect();
    let total: f64 = (0..angles.len())
        .map(|k| {
            let step = angles[(k + 1) % angles.len()] - angles[k];
            (step + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
        })
        .sum();
    total / std::f64::consts::TAU
}

/// A unit direction perpendicular to unit `axis`.
fn perpendicular(axis: DVec3) -> DVec3 {
    let helper = if axis.x.abs() < 0.9 {
        DVec3::X
    } else {
        DVec3::Y
    };
    axis.cross(helper).normalize()
}

/// `loops` of a face on a surface of revolution about the line through `origin` along unit
/// `axis`, with two loops that each go once round the axis joined into one along a ruling (see
/// the module documentation); the ruling is split into pieces of at most [`EDGE_PIECE_RATIO`]
/// of `mesh_size`. Other loops are returned as they are.
pub fn join_seamless_loops(
    loops: Vec<BoundaryLoop>,
    origin: DVec3,
    axis: DVec3,
    mesh_size: f64,
) -> Vec<BoundaryLoop> {
    let reference = perpendicular(axis);
    let [first, second] = loops.as_slice() else {
        return loops;
    };
    let turns_of = |boundary: &BoundaryLoop| turns(&boundary.points, origin, axis, reference);
    let (first_turns, second_turns) = (turns_of(first), turns_of(second));
    let once_round = |t: f64| (t.abs() - 1.0).abs() <= TURN_TOLERANCE;
    if !once_round(first_turns) || !once_round(second_turns) || first.points.len() < 3 {
        return loops;
    }
    let start = first.points[0];
    let start_angle = angle_about(start, origin, axis, reference);
    let angle_gap = |p: DVec3| {
        let gap = angle_about(p, origin, axis, reference) - start_angle;
        (gap + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
    };
    let across = (0..second.points.len())
        .min_by(|&a, &b| {
            angle_gap(second.points[a])
                .abs()
                .total_cmp(&angle_gap(second.points[b]).abs())
        })
        .unwrap_or(0);
    let end = second.points[across];
    let pieces = (start.distance(end) / (EDGE_PIECE_RATIO * mesh_size))
        .ceil()
        .max(1.0) as usize;
    let ruling: Vec<DVec3> = (1..pieces)
        .map(|k| start.lerp(end, k as f64 / pieces as f64))
        .collect();
    // The second loop, from the point across, once round against the first loop's sense.
    let count = second.points.len();
    let same_sense = first_turns.signum() == second_turns.signum();
    let second_order: Vec<usize> = (0..count)
        .map(|k| {
            if same_sense {
                (across + count - k) % count
            } else {
                (across + k) % count
            }
        })
        .collect();
    let second_vertices: Vec<bool> = (0..count)
        .map(|index| second.edge_starts.contains(&index))
        .collect();
    let mut points = Vec::with_capacity(first.points.len() + count + 2 * ruling.len() + 2);
    let mut edge_starts = first.edge_starts.clone();
    points.extend_from_slice(&first.points);
    edge_starts.push(points.len());
    points.push(start);
    points.extend_from_slice(&ruling);
    for (k, &index) in second_order.iter().enumerate() {
        if k == 0 || second_vertices[index] {
            edge_starts.push(points.len());
        }
        points.push(second.points[index]);
    }
    edge_starts.push(points.len());
    points.push(end);
    points.extend(ruling.iter().rev());
    edge_starts.sort_unstable();
    edge_starts.dedup();
    vec![BoundaryLoop {
        points,
        edge_starts,
    }]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A circle of radius 2 about the z axis at height `z`, `count` points, turning `sense`.
    fn circle(z: f64, count: usize, sense: f64, phase: f64) -> BoundaryLoop {
        BoundaryLoop {
            points: (0..count)
                .map(|k| {
                    let angle = phase + sense * std::f64::consts::TAU * k as f64 / count as f64;
                    DVec3::new(2.0 * angle.cos(), 2.0 * angle.sin(), z)
                })
                .collect(),
            edge_starts: vec![0],
        }
    }

    #[test]
    fn two_end_circles_become_one_loop_cut_along_a_ruling() {
        let loops = vec![circle(0.0, 12, 1.0, 0.0), circle(3.0, 12, -1.0, 0.1)];
        let joined = join_seamless_loops(loops, DVec3::ZERO, DVec3::Z, 1.0);
        let [boundary] = joined.as_slice() else {
            panic!("one loop expected, got {}", joined.len());
        };
        // 12 + the start again + 3 ruling points + 12 + the end again + 3 ruling points back.
        assert_eq!(boundary.points.len(), 12 + 1 + 3 + 12 + 1 + 3);
        let points = &boundary.points;
        assert_eq!(points[12], points[0]);
        // The ruling runs from (2, 0, 0) to the top circle's point at the nearest angle (0.1).
        let top = DVec3::new(2.0 * 0.1f64.cos(), 2.0 * 0.1f64.sin(), 3.0);
        assert!(points[16].distance(top) < 1e-12, "{:?}", points[16]);
        assert_eq!(points[16], points[28]);
        assert_eq!(points[13], points[points.len() - 1]);
        // No turn left over: the joined loop goes round and back.
        let reference = perpendicular(DVec3::Z);
        assert!(turns(points, DVec3::ZERO, DVec3::Z, reference).abs() < 1e-9);
    }

    #[test]
    fn loops_of_a_face_with_a_seam_are_kept() {
        let loops = vec![circle(0.0, 12, 1.0, 0.0)];
        let kept = join_seamless_loops(loops.clone(), DVec3::ZERO, DVec3::Z, 1.0);
        assert_eq!(kept, loops);
    }
}
