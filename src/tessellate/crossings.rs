//! Fold polylines with the points where they cross each other added to both, so that the
//! meshers can make every crossing a shared vertex.

use glam::DVec2;

/// The polylines with the points where they cross each other added to both (in the domain):
/// each crossing is computed once and is the same point of both, so that it becomes one vertex
/// and no short piece is left next to it.
pub(super) fn with_crossings(folds: &[(u32, Vec<DVec2>)]) -> Vec<(u32, Vec<DVec2>)> {
    let side = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    // Per polyline and segment: the crossings on it as (fraction along it, point).
    let mut found: Vec<Vec<Vec<(f64, DVec2)>>> = folds
        .iter()
        .map(|(_, points)| vec![Vec::new(); points.len().saturating_sub(1)])
        .collect();
    for first in 0..folds.len() {
        for second in first + 1..folds.len() {
            for (i, s) in folds[first].1.windows(2).enumerate() {
                for (j, o) in folds[second].1.windows(2).enumerate() {
                    let (d1, d2) = (side(o[0], o[1], s[0]), side(o[0], o[1], s[1]));
                    let (d3, d4) = (side(s[0], s[1], o[0]), side(s[0], s[1], o[1]));
                    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
                        let (t, t_other) = (d1 / (d1 - d2), d3 / (d3 - d4));
                        let point = s[0].lerp(s[1], t);
                        found[first][i].push((t, point));
                        found[second][j].push((t_other, point));
                    }
                }
            }
        }
    }
    folds
        .iter()
        .zip(found)
        .map(|((line, points), mut crossings)| {
            let mut result = vec![points[0]];
            for (k, q) in points.iter().skip(1).enumerate() {
                crossings[k].sort_by(|a, b| a.0.total_cmp(&b.0));
                result.extend(crossings[k].iter().map(|c| c.1));
                result.push(*q);
            }
            (*line, result)
        })
        .collect()
}
