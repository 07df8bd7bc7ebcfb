//! Moving a vertex onto a curve that passes near it (a smooth cut, a plane section), so that the
//! curve does not turn at the vertex: allowed only where the vertex's faces stay well shaped.

use glam::DVec3;

use super::facet::{FacetModel, NONE};

/// The largest angle (radians) a face around a moved vertex may turn by (10°).
pub const MAX_MOVED_FACE_TURN: f64 = 10.0 * std::f64::consts::PI / 180.0;

/// Whether `vertex` of `model` may move to `to`: none of its faces has an edge on a fold line,
/// and each keeps at least half its smallest angle and turns by less than
/// [`MAX_MOVED_FACE_TURN`].
pub fn can_move_vertex(model: &FacetModel, vertex: u32, to: DVec3) -> bool {
    let positions = model.positions();
    let on_fold = model.vertex_faces(vertex).iter().any(|&face| {
        model.face_edges()[face as usize]
            .iter()
            .any(|&e| model.edge_fold_lines()[e as usize] != NONE)
    });
    if on_fold {
        return false;
    }
    model.vertex_faces(vertex).iter().all(|&face| {
        let corners = model.triangles()[face as usize];
        let before = corners.map(|v| positions[v as usize]);
        let after = corners.map(|v| {
            if v == vertex {
                to
            } else {
                positions[v as usize]
            }
        });
        let normal = |[a, b, c]: [DVec3; 3]| (b - a).cross(c - a).normalize_or_zero();
        smallest_angle(after) >= 0.5 * smallest_angle(before)
            && normal(before).angle_between(normal(after)) < MAX_MOVED_FACE_TURN
    })
}

/// The smallest angle of the triangle with these corners, radians.
pub fn smallest_angle(corners: [DVec3; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let at = corners[k];
            (corners[(k + 1) % 3] - at).angle_between(corners[(k + 2) % 3] - at)
        })
        .fold(f64::INFINITY, f64::min)
}
