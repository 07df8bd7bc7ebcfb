//! Zero-area triangles of a face mesh removed: by an edge flip inside the face, dropped where
//! they hang off it.
//!
//! A face's boundary vertices are snapped onto the exact samples of its edges after meshing. Where
//! the mesher joined three consecutive samples of a straight edge into one thin triangle (they
//! were a hair off the line in the face's parameter domain), the snap makes the three collinear:
//! the triangle has zero area, its middle vertex on its longest edge. Flipping that longest edge
//! with the triangle's neighbour across it splits the neighbour at the middle vertex into two
//! proper triangles and removes the degenerate one, with the boundary and every other triangle
//! unchanged (the face keeps its area and stays conforming to its neighbours). Where the mesher
//! kept slivers just outside the boundary (samples a hair off the line, judged inside by a
//! rounded centroid), the snapped triangles hang off the face by sides no other triangle shares:
//! they cover nothing and are peeled off, as long as every vertex keeps a triangle. Where the mesher
//! kept a sliver just outside the boundary (three samples a hair off the line, classified by a
//! rounded centroid), the snapped triangle has no neighbour across its longest edge and hangs off
//! the face by a side no other triangle shares: it covers nothing, and is dropped.
//!
//! Input: positions (part units) and consistently oriented triangles. Output: the triangles
//! without those zero-area triangles; one that is neither (its longest edge on the boundary, its
//! other sides shared) is left for the caller's check to report.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::geometry::tolerance::has_zero_area;

/// True when the triangle has three distinct corners and zero area ([`has_zero_area`]: three
/// collinear corners); a triangle with a repeated corner is not.
pub fn is_degenerate(corners: [DVec3; 3]) -> bool {
    let [a, b, c] = corners;
    let repeated = a == b || b == c || c == a;
    !repeated && has_zero_area(corners)
}

/// Removes every zero-area triangle it can (see the module documentation): flips its longest edge
/// with a proper neighbour across it; then drops each connected group of the zero-area triangles
/// left that reaches the face's boundary (has a side no other triangle has), unless that would
/// leave a vertex in no triangle (the group filled a crack rather than hanging off the face).
pub fn remove_degenerate_triangles(positions: &[DVec3], triangles: &mut Vec<[u32; 3]>) {
    let corners = |t: [u32; 3]| t.map(|v| positions[v as usize]);
    let degenerate = |triangles: &[[u32; 3]]| -> Vec<usize> {
        (0..triangles.len())
            .filter(|&t| is_degenerate(corners(triangles[t])))
            .collect()
    };
    for index in degenerate(triangles) {
        flip_into_neighbour(positions, triangles, index);
    }
    let slivers = degenerate(triangles);
    if slivers.is_empty() {
        return;
    }
    let uses = edge_uses(triangles);
    let on_boundary = |t: usize| sides(triangles[t]).iter().any(|side| uses[side] == 1);
    let mut dropped = vec![false; triangles.len()];
    for group in groups(triangles, &slivers) {
        if group.iter().any(|&t| on_boundary(t)) {
            for t in group {
                dropped[t] = true;
            }
        }
    }
    let vertices = |keep: &dyn Fn(usize) -> bool| {
        let mut used: Vec<u32> = (0..triangles.len())
            .filter(|&t| keep(t))
            .flat_map(|t| triangles[t])
            .collect();
        used.sort_unstable();
        used.dedup();
        used
    };
    if vertices(&|t| !dropped[t]) == vertices(&|_| true) {
        let mut flags = dropped.into_iter();
        triangles.retain(|_| !flags.next().unwrap_or(false));
    }
}

/// Flips the longest edge of the zero-area triangle `index` with the triangle across it, when that
/// one has area and the two triangles the flip makes do too.
fn flip_into_neighbour(positions: &[DVec3], triangles: &mut [[u32; 3]], index: usize) {
    let corners = |t: [u32; 3]| t.map(|v| positions[v as usize]);
    let [x, y, middle] = rotated_to_longest_edge(triangles[index], positions);
    let Some(neighbour) =
        (0..triangles.len()).find(|&t| t != index && rotated_to_edge(triangles[t], y, x).is_some())
    else {
        return;
    };
    let Some([_, _, far]) = rotated_to_edge(triangles[neighbour], y, x) else {
        return;
    };
    let flipped = [[x, far, middle], [far, y, middle]];
    if !is_degenerate(corners(triangles[neighbour]))
        && flipped.iter().all(|&t| !is_degenerate(corners(t)))
    {
        triangles[index] = flipped[0];
        triangles[neighbour] = flipped[1];
    }
}

/// A triangle's sides as sorted vertex pairs.
fn sides(triangle: [u32; 3]) -> [(u32, u32); 3] {
    [0, 1, 2].map(|i| {
        let (a, b) = (triangle[i], triangle[(i + 1) % 3]);
        (a.min(b), a.max(b))
    })
}

/// How many triangles have each side.
fn edge_uses(triangles: &[[u32; 3]]) -> BTreeMap<(u32, u32), usize> {
    let mut uses = BTreeMap::new();
    for &triangle in triangles {
        for side in sides(triangle) {
            *uses.entry(side).or_insert(0) += 1;
        }
    }
    uses
}

/// The triangles of `members` grouped by shared sides (each group in ascending order).
fn groups(triangles: &[[u32; 3]], members: &[usize]) -> Vec<Vec<usize>> {
    let mut group_of: Vec<Option<usize>> = vec![None; members.len()];
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for start in 0..members.len() {
        if group_of[start].is_some() {
            continue;
        }
        let label = groups.len();
        group_of[start] = Some(label);
        let mut stack = vec![start];
        let mut group = Vec::new();
        while let Some(member) = stack.pop() {
            group.push(members[member]);
            let own = sides(triangles[members[member]]);
            for other in 0..members.len() {
                if group_of[other].is_none()
                    && sides(triangles[members[other]])
                        .iter()
                        .any(|s| own.contains(s))
                {
                    group_of[other] = Some(label);
                    stack.push(other);
                }
            }
        }
        group.sort_unstable();
        groups.push(group);
    }
    groups
}

/// The triangle rotated to `[x, y, opposite]` with `x → y` its longest edge.
fn rotated_to_longest_edge(triangle: [u32; 3], positions: &[DVec3]) -> [u32; 3] {
    let length = |i: usize| {
        positions[triangle[i] as usize].distance_squared(positions[triangle[(i + 1) % 3] as usize])
    };
    let first = (0..3)
        .max_by(|&i, &j| length(i).total_cmp(&length(j)))
        .unwrap_or(0);
    [0, 1, 2].map(|k| triangle[(first + k) % 3])
}

/// The triangle rotated to `[from, to, opposite]` when it has the directed edge `from → to`.
fn rotated_to_edge(triangle: [u32; 3], from: u32, to: u32) -> Option<[u32; 3]> {
    (0..3)
        .find(|&i| triangle[i] == from && triangle[(i + 1) % 3] == to)
        .map(|i| [0, 1, 2].map(|k| triangle[(i + k) % 3]))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::tessellate::collinear::{is_degenerate, remove_degenerate_triangles};

    fn area(positions: &[DVec3], t: [u32; 3]) -> f64 {
        let [a, b, c] = t.map(|v| positions[v as usize]);
        0.5 * (b - a).cross(c - a).z
    }

    /// Boundary samples 0, 1, 2 on the x axis (1 between, nearer 0) and the vertex 3 above them.
    fn samples_under_apex() -> [DVec3; 4] {
        [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.4, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, 1.0, 0.0),
        ]
    }

    #[test]
    fn a_collinear_boundary_triangle_is_flipped_into_its_neighbour() {
        let positions = samples_under_apex();
        let mut triangles = vec![[2, 0, 1], [0, 2, 3]];
        let total: f64 = triangles.iter().map(|&t| area(&positions, t)).sum();
        remove_degenerate_triangles(&positions, &mut triangles);
        assert_eq!(triangles.len(), 2);
        for &t in &triangles {
            assert!(!is_degenerate(t.map(|v| positions[v as usize])), "{t:?}");
            assert!(area(&positions, t) > 0.0, "{t:?} keeps the orientation");
        }
        let after: f64 = triangles.iter().map(|&t| area(&positions, t)).sum();
        assert!((after - total).abs() < 1e-15, "{after} {total}");
    }

    #[test]
    fn a_sliver_folded_over_boundary_samples_is_dropped() {
        // The face (0, 1, 3), (1, 2, 3) has the boundary 0 → 1 → 2; the sliver (0, 2, 1) lies
        // over those two sides, with its longest side 0-2 free.
        let positions = samples_under_apex();
        let mut triangles = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3]];
        remove_degenerate_triangles(&positions, &mut triangles);
        assert_eq!(triangles, [[0, 1, 3], [1, 2, 3]]);
    }

    /// Boundary samples 0 → 1 → 2 → 3 along the x axis under a face of four triangles reaching
    /// up to 4 and 5.
    fn strip_face() -> ([DVec3; 6], Vec<[u32; 3]>) {
        let positions = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.3, 0.0, 0.0),
            DVec3::new(0.6, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.2, 1.0, 0.0),
            DVec3::new(0.8, 1.0, 0.0),
        ];
        (positions, vec![[0, 1, 4], [1, 2, 4], [4, 2, 5], [2, 3, 5]])
    }

    #[test]
    fn slivers_hanging_off_the_boundary_are_peeled() {
        // One sliver on the side 2-3 with its longest side 0-3 free; then two stacked ones.
        for slivers in [vec![[3, 2, 0]], vec![[3, 2, 0], [2, 1, 0]]] {
            let (positions, face) = strip_face();
            let mut triangles = face.clone();
            triangles.extend(&slivers);
            remove_degenerate_triangles(&positions, &mut triangles);
            assert_eq!(triangles, face, "{slivers:?}");
        }
    }

    #[test]
    fn a_zero_area_triangle_holding_a_vertex_alone_is_left() {
        // The sliver (0, 1, 2) is the only triangle at 1, a boundary sample: dropping it would
        // lose the sample and open a crack along the neighbouring face.
        let positions = samples_under_apex();
        let mut triangles = vec![[0, 1, 2], [0, 3, 2]];
        let before = triangles.clone();
        remove_degenerate_triangles(&positions, &mut triangles);
        assert_eq!(triangles, before);
    }
}
