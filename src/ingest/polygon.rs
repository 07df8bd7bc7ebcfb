//! Polygon faces of mesh files (OBJ, OFF, PLY) made into triangles. A convex polygon is fanned
//! from its first corner; a concave one (an L-shaped panel exported as one n-gon) would fold
//! over itself fanned, so it is cut into ears in its own plane instead.

use glam::{DVec2, DVec3};

/// Gives `emit` the triangles of the polygon of `count` corners (at least 3) whose `k`-th corner
/// is at `corner(k)` (in order, either winding), as triples of corner numbers, each with the
/// polygon's winding: a triangle itself, without looking at its corners (files of triangles read
/// as fast as before); a larger polygon as [`polygon_triangles`] cuts it.
pub(crate) fn triangulate_polygon(
    count: usize,
    corner: impl Fn(usize) -> DVec3,
    mut emit: impl FnMut([usize; 3]),
) {
    if count == 3 {
        emit([0, 1, 2]);
        return;
    }
    let corners: Vec<DVec3> = (0..count).map(corner).collect();
    polygon_triangles(&corners).into_iter().for_each(emit);
}

/// The triangles of the polygon with corners `corners` (in order, either winding), as triples of
/// indices into `corners`, each with the polygon's winding. A convex polygon gives the fan from
/// corner 0; a concave one its ears (in the plane of its Newell normal); a polygon with no area
/// or crossing itself, where neither is right, the fan.
fn polygon_triangles(corners: &[DVec3]) -> Vec<[usize; 3]> {
    let fan = || (1..corners.len() - 1).map(|k| [0, k, k + 1]).collect();
    if corners.len() == 3 {
        return fan();
    }
    let normal = newell_normal(corners);
    if normal == DVec3::ZERO {
        return fan();
    }
    let u = normal.any_orthonormal_vector();
    let v = normal.cross(u);
    let flat: Vec<DVec2> = (corners.iter())
        .map(|&p| DVec2::new(p.dot(u), p.dot(v)))
        .collect();
    if is_convex(&flat) {
        return fan();
    }
    ears(&flat).unwrap_or_else(fan)
}

/// The polygon's Newell normal, normalised (zero for a polygon with no area): its winding is
/// counter-clockwise about it. Summed about the first corner, so that a part far from the
/// origin (a scan in survey coordinates) keeps its precision.
fn newell_normal(corners: &[DVec3]) -> DVec3 {
    let n = corners.len();
    let at = |i: usize| corners[i % n] - corners[0];
    let sum: DVec3 = (1..n).map(|i| at(i).cross(at(i + 1))).sum();
    sum.normalize_or_zero()
}

/// Twice the signed area of the triangle `a`, `b`, `c` (positive counter-clockwise).
fn turn(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - b)
}

/// Whether the counter-clockwise polygon turns left (or goes straight) at every corner.
fn is_convex(points: &[DVec2]) -> bool {
    let n = points.len();
    (0..n).all(|i| turn(points[i], points[(i + 1) % n], points[(i + 2) % n]) >= 0.0)
}

/// Ear clipping of a counter-clockwise simple polygon; `None` when no ear is left before the
/// last triangle (the polygon crosses itself).
fn ears(points: &[DVec2]) -> Option<Vec<[usize; 3]>> {
    let mut remaining: Vec<usize> = (0..points.len()).collect();
    let mut triangles = Vec::with_capacity(points.len() - 2);
    let mut start = 0;
    while remaining.len() > 3 {
        let m = remaining.len();
        let ear = (0..m)
            .map(|offset| (start + offset) % m)
            .find(|&k| is_ear(points, &remaining, k))?;
        let [a, b, c] = [(ear + m - 1) % m, ear, (ear + 1) % m].map(|k| remaining[k]);
        triangles.push([a, b, c]);
        remaining.remove(ear);
        start = ear.saturating_sub(1);
    }
    triangles.push([remaining[0], remaining[1], remaining[2]]);
    Some(triangles)
}

/// Whether corner `k` of the remaining polygon is an ear: a left turn whose triangle holds no
/// other remaining corner.
fn is_ear(points: &[DVec2], remaining: &[usize], k: usize) -> bool {
    let m = remaining.len();
    let [a, b, c] = [(k + m - 1) % m, k, (k + 1) % m].map(|i| remaining[i]);
    let [pa, pb, pc] = [a, b, c].map(|i| points[i]);
    if turn(pa, pb, pc) <= 0.0 {
        return false;
    }
    (remaining.iter().copied())
        .filter(|&i| i != a && i != b && i != c)
        .all(|i| {
            let p = points[i];
            p == pa
                || p == pb
                || p == pc
                || turn(pa, pb, p) < 0.0
                || turn(pb, pc, p) < 0.0
                || turn(pc, pa, p) < 0.0
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(corners: &[DVec3], triangles: &[[usize; 3]]) -> f64 {
        (triangles.iter())
            .map(|&[a, b, c]| {
                (corners[b] - corners[a])
                    .cross(corners[c] - corners[a])
                    .length()
                    / 2.0
            })
            .sum()
    }

    /// An L-shaped hexagon (area 6,400 of its 100 × 100 box) started at the corner whose fan
    /// folds over the notch: its triangles cover the L exactly, every one with the polygon's
    /// winding (normal +z).
    #[test]
    fn a_concave_polygon_is_cut_into_ears_not_fanned() {
        let corners = [
            (0.0, 100.0),
            (0.0, 0.0),
            (100.0, 0.0),
            (100.0, 40.0),
            (40.0, 40.0),
            (40.0, 100.0),
        ]
        .map(|(x, y)| DVec3::new(x, y, 5.0));
        let triangles = polygon_triangles(&corners);
        assert_eq!(triangles.len(), 4);
        assert!((area(&corners, &triangles) - 6400.0).abs() < 1e-9);
        for &[a, b, c] in &triangles {
            let normal = (corners[b] - corners[a]).cross(corners[c] - corners[a]);
            assert!(normal.z > 0.0, "{a} {b} {c}");
        }
    }

    /// A convex polygon is the fan from its first corner, as before (and a triangle is itself).
    #[test]
    fn a_convex_polygon_is_fanned_from_its_first_corner() {
        let square =
            [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| DVec3::new(x, 0.0, y));
        assert_eq!(polygon_triangles(&square), vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(polygon_triangles(&square[..3]), vec![[0, 1, 2]]);
    }
}
