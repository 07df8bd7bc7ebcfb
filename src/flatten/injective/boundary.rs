//! The boundary barrier: keeps the pattern's outline (holes included) from crossing itself, so a
//! pattern that starts without overlap never gets one (a global injectivity the orientation
//! barrier alone does not give; Smith and Schaefer 2015, Li et al. 2020).
//!
//! For a boundary vertex `p` and a boundary edge `ab` not ending at it, at distance `d`, the
//! term is `w b(d / r)` with `b` the barrier of [`Barrier`] at threshold 1 (zero beyond the reach
//! `r`, infinite at contact), `r` a tenth of the mean boundary edge, `w` the mean spring constant
//! times `r²`. Its Hessian enters as the Gauss-Newton blocks of the three vertices on the
//! diagonal (positive semi-definite; the blocks between them are left out, so the sparsity of
//! the spring Hessian is kept). A step is bounded so that no boundary vertex reaches a boundary
//! edge along it ([`BoundaryBarrier::max_contact_free_step`]): with the flip-free bound, every
//! iterate has neither a flipped triangle nor a crossing outline.

use std::collections::HashMap;

use glam::DVec2;

use super::barrier::Barrier;
use crate::flatten::springs::SpringSystem;
use crate::geometry::segment_fraction;
use crate::mesh::FacetModel;

/// The reach of the boundary barrier, relative to the mean boundary edge length.
pub const BOUNDARY_REACH: f64 = 0.1;

/// The barrier's shape: IPC's, at threshold 1 of `d / r`.
const SHAPE: Barrier = Barrier {
    threshold: 1.0,
    weight: 1.0,
};

/// A boundary vertex close to a boundary edge: the pair, their distance and its gradient with
/// respect to the vertex and the edge's two ends.
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    /// The boundary vertex.
    pub vertex: u32,
    /// The edge's two ends.
    pub edge: [u32; 2],
    /// The distance from the vertex to the edge.
    pub distance: f64,
    /// The gradient of the distance with respect to the vertex, the edge's first and second end.
    pub gradient: [DVec2; 3],
}

/// The boundary barrier of one model.
#[derive(Debug, Clone)]
pub struct BoundaryBarrier {
    vertices: Vec<u32>,
    edges: Vec<[u32; 2]>,
    reach: f64,
    weight: f64,
}

impl BoundaryBarrier {
    /// The barrier of `model`'s boundary loops, `None` for a closed model.
    pub fn new(model: &FacetModel, springs: &SpringSystem) -> Option<Self> {
        let edges: Vec<[u32; 2]> = model.boundary_sides().collect();
        if edges.is_empty() {
            return None;
        }
        let rest = model.positions();
        let mean_length = edges
            .iter()
            .map(|&[a, b]| rest[a as usize].distance(rest[b as usize]))
            .sum::<f64>()
            / edges.len() as f64;
        let mean_constant =
            springs.constants.iter().sum::<f64>() / springs.constants.len().max(1) as f64;
        let reach = BOUNDARY_REACH * mean_length;
        let mut vertices: Vec<u32> = edges.iter().map(|e| e[0]).collect();
        vertices.sort_unstable();
        vertices.dedup();
        Some(Self {
            vertices,
            edges,
            reach,
            weight: mean_constant * reach * reach,
        })
    }

    /// Every boundary vertex within the reach of a boundary edge not ending at it, in a fixed
    /// order (by vertex, then by edge).
    pub fn contacts(&self, positions: &[DVec2]) -> Vec<Contact> {
        // Cells about an edge long (at least the reach), so an edge covers a few cells.
        let mean_length = self
            .edges
            .iter()
            .map(|&[a, b]| positions[a as usize].distance(positions[b as usize]))
            .sum::<f64>()
            / self.edges.len() as f64;
        let cell = mean_length.max(self.reach);
        let key = |p: DVec2| ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64);
        let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (index, &[a, b]) in self.edges.iter().enumerate() {
            let (p, q) = (positions[a as usize], positions[b as usize]);
            let (low, high) = (key(p.min(q) - self.reach), key(p.max(q) + self.reach));
            for i in low.0..=high.0 {
                for j in low.1..=high.1 {
                    grid.entry((i, j)).or_default().push(index);
                }
            }
        }
        let mut contacts = Vec::new();
        for &v in &self.vertices {
            let p = positions[v as usize];
            let Some(candidates) = grid.get(&key(p)) else {
                continue;
            };
            for &index in candidates {
                let edge = self.edges[index];
                if edge.contains(&v) {
                    continue;
                }
                let [a, b] = edge.map(|e| positions[e as usize]);
                let (distance, gradient) = point_segment_distance(p, a, b);
                if distance < self.reach {
                    contacts.push(Contact {
                        vertex: v,
                        edge,
                        distance,
                        gradient,
                    });
                }
            }
        }
        contacts
    }

    /// The barrier's value, slope and curvature with respect to the distance of a contact at
    /// `distance`, weight included.
    pub fn at(&self, distance: f64) -> [f64; 3] {
        let [value, slope, curvature] = SHAPE.at(distance / self.reach);
        [
            self.weight * value,
            self.weight * slope / self.reach,
            self.weight * curvature / (self.reach * self.reach),
        ]
    }

    /// The barrier's value at `positions` (infinite if a boundary vertex touches an edge).
    pub fn value(&self, positions: &[DVec2]) -> f64 {
        self.contacts(positions)
            .iter()
            .map(|contact| self.at(contact.distance)[0])
            .sum()
    }

    /// The largest step along `direction` at which no boundary vertex has reached a boundary
    /// edge not ending at it (infinity if none ever does): for every pair whose boxes swept over
    /// a unit step overlap (found by sweeping along x), the first time the vertex lies on the
    /// segment.
    pub fn max_contact_free_step(&self, positions: &[DVec2], direction: &[DVec2]) -> f64 {
        let swept = |points: &[u32]| {
            let mut low = DVec2::splat(f64::INFINITY);
            let mut high = DVec2::splat(f64::NEG_INFINITY);
            for &v in points {
                let (p, d) = (positions[v as usize], direction[v as usize]);
                low = low.min(p).min(p + d);
                high = high.max(p).max(p + d);
            }
            (low, high)
        };
        let vertex_boxes: Vec<(DVec2, DVec2)> =
            self.vertices.iter().map(|&v| swept(&[v])).collect();
        let edge_boxes: Vec<(DVec2, DVec2)> = self.edges.iter().map(|e| swept(e)).collect();
        let mut bound = f64::INFINITY;
        for (vi, ei) in overlapping_boxes(&vertex_boxes, &edge_boxes) {
            let v = self.vertices[vi];
            let edge = self.edges[ei];
            if edge.contains(&v) {
                continue;
            }
            let [a, b] = edge.map(|e| positions[e as usize]);
            let [da, db] = edge.map(|e| direction[e as usize]);
            let (p, dp) = (positions[v as usize], direction[v as usize]);
            bound = bound.min(first_contact(p, a, b, dp, da, db));
        }
        bound
    }
}

/// The pairs (first list, second list) of boxes `(low, high)` that overlap, by a sweep along x.
fn overlapping_boxes(first: &[(DVec2, DVec2)], second: &[(DVec2, DVec2)]) -> Vec<(usize, usize)> {
    let mut events: Vec<(f64, bool, usize)> = first
        .iter()
        .enumerate()
        .map(|(i, b)| (b.0.x, false, i))
        .chain(second.iter().enumerate().map(|(i, b)| (b.0.x, true, i)))
        .collect();
    events.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let (mut active_first, mut active_second): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    let mut pairs = Vec::new();
    let overlap_y = |a: &(DVec2, DVec2), b: &(DVec2, DVec2)| a.0.y <= b.1.y && b.0.y <= a.1.y;
    for (x, in_second, i) in events {
        active_first.retain(|&j| first[j].1.x >= x);
        active_second.retain(|&j| second[j].1.x >= x);
        if in_second {
            pairs.extend(
                active_first
                    .iter()
                    .filter(|&&j| overlap_y(&first[j], &second[i]))
                    .map(|&j| (j, i)),
            );
            active_second.push(i);
        } else {
            pairs.extend(
                active_second
                    .iter()
                    .filter(|&&j| overlap_y(&first[i], &second[j]))
                    .map(|&j| (i, j)),
            );
            active_first.push(i);
        }
    }
    pairs
}

/// The distance from `p` to the segment `ab` and its gradient with respect to `p`, `a` and `b`.
pub fn point_segment_distance(p: DVec2, a: DVec2, b: DVec2) -> (f64, [DVec2; 3]) {
    let side = b - a;
    let t = segment_fraction(p, a, b);
    let offset = p - (a + side * t);
    let distance = offset.length();
    let normal = if distance > 0.0 {
        offset / distance
    } else {
        DVec2::ZERO
    };
    (distance, [normal, -normal * (1.0 - t), -normal * t])
}

/// The first time in `(0, ∞)` at which `p + t dp` lies on the segment from `a + t da` to
/// `b + t db`, infinity if never: the roots of the doubled signed area of `(p, a, b)`, a
/// quadratic in `t`, at which the vertex is between the segment's ends.
fn first_contact(p: DVec2, a: DVec2, b: DVec2, dp: DVec2, da: DVec2, db: DVec2) -> f64 {
    let (e1, e2) = (a - p, b - p);
    let (f1, f2) = (da - dp, db - dp);
    let (c2, c1, c0) = (
        f1.perp_dot(f2),
        e1.perp_dot(f2) + f1.perp_dot(e2),
        e1.perp_dot(e2),
    );
    let mut roots = Vec::with_capacity(2);
    if c2.abs() > f64::EPSILON * (c1.abs() + c0.abs()) {
        let discriminant = c1 * c1 - 4.0 * c2 * c0;
        if discriminant >= 0.0 {
            let q = -0.5 * (c1 + c1.signum() * discriminant.sqrt());
            roots.extend([q / c2, c0 / q]);
        }
    } else if c1 != 0.0 {
        roots.push(-c0 / c1);
    }
    roots
        .into_iter()
        .filter(|&t| t > 0.0 && t.is_finite())
        .filter(|&t| {
            let (q, s, r) = (p + dp * t, a + da * t, b + db * t);
            let side = r - s;
            let along = (q - s).dot(side);
            along >= 0.0 && along <= side.length_squared()
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic generator of numbers in [-1, 1).
    fn numbers(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    #[test]
    fn the_sweep_finds_exactly_the_overlapping_boxes() {
        let mut next = numbers(3);
        let mut boxes = |count: usize| -> Vec<(DVec2, DVec2)> {
            (0..count)
                .map(|_| {
                    let low = DVec2::new(next(), next());
                    (
                        low,
                        low + DVec2::new(0.3 * next().abs(), 0.3 * next().abs()),
                    )
                })
                .collect()
        };
        let (first, second) = (boxes(200), boxes(150));
        let mut swept = overlapping_boxes(&first, &second);
        swept.sort_unstable();
        let mut brute = Vec::new();
        for (i, a) in first.iter().enumerate() {
            for (j, b) in second.iter().enumerate() {
                if a.0.x <= b.1.x && b.0.x <= a.1.x && a.0.y <= b.1.y && b.0.y <= a.1.y {
                    brute.push((i, j));
                }
            }
        }
        assert!(!brute.is_empty());
        assert_eq!(swept, brute);
    }

    #[test]
    fn the_distance_gradient_matches_finite_differences() {
        let mut next = numbers(7);
        for _ in 0..200 {
            let mut points = [0; 3].map(|_| DVec2::new(next(), next()));
            let (_, gradient) = point_segment_distance(points[0], points[1], points[2]);
            for corner in 0..3 {
                for axis in 0..2 {
                    let h = 1e-7;
                    let mut at = |delta: f64| {
                        points[corner][axis] += delta;
                        let d = point_segment_distance(points[0], points[1], points[2]).0;
                        points[corner][axis] -= delta;
                        d
                    };
                    let numeric = (at(h) - at(-h)) / (2.0 * h);
                    assert!(
                        (numeric - gradient[corner][axis]).abs() < 1e-5,
                        "{points:?} corner {corner} axis {axis}: {numeric} against {}",
                        gradient[corner][axis]
                    );
                }
            }
        }
    }

    #[test]
    fn the_first_contact_is_where_a_fine_scan_first_sees_the_vertex_cross_the_segment() {
        let mut next = numbers(11);
        let (mut found, mut grazing) = (0, 0);
        for _ in 0..2000 {
            let [p, a, b, dp, da, db] = [0; 6].map(|_| DVec2::new(next(), next()));
            let contact = first_contact(p, a, b, dp, da, db);
            // The scan: the first step at which the side of p changes while p projects inside.
            let side = |t: f64| {
                let (q, s, r) = (p + dp * t, a + da * t, b + db * t);
                (
                    (r - s).perp_dot(q - s),
                    (q - s).dot(r - s) / (r - s).length_squared(),
                )
            };
            let steps = 20000;
            let mut scanned = f64::INFINITY;
            let mut previous = side(0.0).0;
            for i in 1..=steps {
                let t = 2.0 * i as f64 / steps as f64;
                let area = side(t).0;
                if area.signum() != previous.signum() {
                    // The sign change's time, by bisection; a crossing if p is on the segment.
                    let (mut low, mut high) = (t - 2.0 / steps as f64, t);
                    for _ in 0..60 {
                        let middle = 0.5 * (low + high);
                        if side(middle).0.signum() == previous.signum() {
                            low = middle;
                        } else {
                            high = middle;
                        }
                    }
                    if (0.0..=1.0).contains(&side(high).1) {
                        scanned = high;
                        break;
                    }
                }
                previous = area;
            }
            if scanned.is_finite() {
                found += 1;
                assert!(
                    (contact - scanned).abs() < 1e-6,
                    "{contact} against {scanned}"
                );
            } else if contact < 2.0 {
                // Both roots within one scan step: the vertex touches the segment and goes back.
                grazing += 1;
            }
        }
        assert!(found > 100, "the test meets contacts: {found}");
        assert!(grazing < 20, "{grazing} contacts the scan does not see");
    }
}
