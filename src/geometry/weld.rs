//! Welding points into shared vertices: the primitive under every welder of the reading and
//! meshing stages (STL corners, STEP face meshes, tessellated faces).
//!
//! Two rules, each deterministic:
//! - [`PointWelder`]: points come one by one and each takes the index of the first point seen
//!   within the tolerance of it, or a new index (STL corners within a tolerance; coincident
//!   STEP edge samples with a tolerance of zero, which welds exactly equal positions);
//! - [`merge_close_points`]: all points at once, grouped (the faces they come from); points of
//!   different groups within the tolerance are one, transitively, each represented by the lowest
//!   index (the faces of a part, which are never welded to themselves).

use std::collections::{BTreeMap, HashMap};

use glam::DVec3;

/// The bounding box (min, max) of the finite points; `None` when there is none.
pub fn finite_bounds<'a>(points: impl IntoIterator<Item = &'a DVec3>) -> Option<(DVec3, DVec3)> {
    let (min, max) = (points.into_iter().filter(|p| p.is_finite())).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(min, max), &p| (min.min(p), max.max(p)),
    );
    min.is_finite().then_some((min, max))
}

/// Welds points as they come (see the module documentation).
#[derive(Debug, Clone)]
pub struct PointWelder {
    /// Welding distance; zero welds equal positions only.
    tolerance: f64,
    /// Origin of the grid of cells `tolerance` wide.
    origin: DVec3,
    /// Points welded so far, by grid cell.
    grid: HashMap<[i64; 3], Vec<u32>>,
    /// Points welded so far, by position bits (tolerance zero).
    exact: BTreeMap<[u64; 3], u32>,
    /// The distinct points, in the order first seen.
    points: Vec<DVec3>,
}

impl PointWelder {
    /// A welder for points within `tolerance` of each other (zero: equal positions, `-0.0` and
    /// `0.0` alike); `origin` anchors the search grid (a corner of the points' bounding box).
    pub fn new(origin: DVec3, tolerance: f64) -> Self {
        Self {
            tolerance,
            origin,
            grid: HashMap::new(),
            exact: BTreeMap::new(),
            points: Vec::new(),
        }
    }

    /// The index of `point`: that of the first point seen within the tolerance, or a new one.
    /// A non-finite point always gets a new index (with a positive tolerance).
    pub fn insert(&mut self, point: DVec3) -> u32 {
        if self.tolerance == 0.0 {
            let key = point.to_array().map(|c| (c + 0.0).to_bits());
            let next = self.points.len() as u32;
            let index = *self.exact.entry(key).or_insert(next);
            if index == next {
                self.points.push(point);
            }
            return index;
        }
        if !point.is_finite() {
            self.points.push(point);
            return (self.points.len() - 1) as u32;
        }
        let [x, y, z] = ((point - self.origin) / self.tolerance)
            .floor()
            .as_i64vec3()
            .to_array();
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let near = self.grid.get(&[x + dx, y + dy, z + dz]);
                    for &v in near.map_or(&[][..], Vec::as_slice) {
                        if self.points[v as usize].distance(point) <= self.tolerance {
                            return v;
                        }
                    }
                }
            }
        }
        self.points.push(point);
        let v = (self.points.len() - 1) as u32;
        self.grid.entry([x, y, z]).or_default().push(v);
        v
    }

    /// The distinct points, indexed as [`PointWelder::insert`] numbered them.
    pub fn into_points(self) -> Vec<DVec3> {
        self.points
    }
}

/// For each point, the lowest-numbered point it is welded to: points of different `groups`
/// within `tolerance` of each other are one, transitively (see the module documentation).
pub fn merge_close_points(positions: &[DVec3], groups: &[u32], tolerance: f64) -> Vec<u32> {
    let mut order: Vec<u32> = (0..positions.len() as u32).collect();
    order.sort_by(|&a, &b| {
        positions[a as usize]
            .x
            .total_cmp(&positions[b as usize].x)
            .then(a.cmp(&b))
    });
    let mut representative: Vec<u32> = (0..positions.len() as u32).collect();
    for (rank, &v) in order.iter().enumerate() {
        let p = positions[v as usize];
        for &w in order[rank + 1..].iter() {
            let q = positions[w as usize];
            if q.x - p.x > tolerance {
                break;
            }
            if groups[v as usize] != groups[w as usize] && p.distance(q) <= tolerance {
                let (low, high) = (v.min(w), v.max(w));
                let target = representative[low as usize];
                if target < representative[high as usize] {
                    representative[high as usize] = target;
                }
            }
        }
    }
    // Resolve chains so every point points at a point that points at itself.
    for v in 0..representative.len() {
        let mut r = representative[v];
        while representative[r as usize] != r {
            r = representative[r as usize];
        }
        representative[v] = r;
    }
    representative
}

#[cfg(test)]
mod tests {
    use crate::geometry::weld::*;

    #[test]
    fn the_first_point_within_the_tolerance_wins() {
        let mut welder = PointWelder::new(DVec3::ZERO, 0.1);
        assert_eq!(welder.insert(DVec3::ZERO), 0);
        assert_eq!(welder.insert(DVec3::X), 1);
        assert_eq!(welder.insert(DVec3::new(0.05, 0.0, 0.0)), 0);
        assert_eq!(welder.into_points(), vec![DVec3::ZERO, DVec3::X]);
    }

    #[test]
    fn a_zero_tolerance_welds_equal_positions_only() {
        let mut welder = PointWelder::new(DVec3::ZERO, 0.0);
        assert_eq!(welder.insert(DVec3::new(-0.0, 1.0, 2.0)), 0);
        assert_eq!(welder.insert(DVec3::new(0.0, 1.0, 2.0)), 0);
        assert_eq!(welder.insert(DVec3::new(1e-300, 1.0, 2.0)), 1);
    }

    #[test]
    fn points_of_one_group_are_never_merged() {
        let points = [DVec3::ZERO, DVec3::ZERO, DVec3::ZERO];
        assert_eq!(merge_close_points(&points, &[0, 0, 1], 1e-9), vec![0, 1, 0]);
    }
}
