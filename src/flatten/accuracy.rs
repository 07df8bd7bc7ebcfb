//! The paper's accuracy measures (§4) and the validity checks a cutting shop needs, computed
//! from the facet model and a flat pattern alone, so any solver's output can be judged the same
//! way.
//!
//! - Area error `E_S = Σ|A − A'| / Σ A` over triangles (Eq. 4).
//! - Shape error `E_C = Σ|L − L'| / Σ L` over edges (Eq. 6), `L` the edge's rest length (its 3D
//!   length unless bend allowance set another).
//! - Maximum edge strain `max |L' − L| / L`.
//! - Flipped triangles: signed flat area not positive (the model's orientation is counter-
//!   clockwise).
//! - Self-overlap: a flipped triangle, or two boundary segments that cross.
//!
//! All in absolute units: the pattern is never rescaled before measuring.

use glam::DVec2;
use serde::Serialize;

use crate::geometry::segments_within;
use crate::mesh::FacetModel;

/// Default permissible `E_S` and `E_C` (1 %, the paper's): the bound on the area and shape errors
/// at which the paper's solver stops.
pub const DEFAULT_TOLERANCE: f64 = 0.01;

/// The accuracy figures of a flat pattern.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Accuracy {
    /// `E_S` (Eq. 4), a fraction.
    pub area_error: f64,
    /// `E_C` (Eq. 6), a fraction.
    pub shape_error: f64,
    /// Largest relative edge length change.
    pub max_strain: f64,
    /// Number of triangles whose flat orientation is reversed or degenerate.
    pub flipped: usize,
    /// True if the pattern overlaps itself.
    pub overlap: bool,
}

impl Accuracy {
    /// Measures a pattern; `pattern[v]` is the flat position of the model's vertex `v`.
    pub fn measure(model: &FacetModel, pattern: &[DVec2]) -> Self {
        let flipped = flipped_triangles(model, pattern);
        Self {
            area_error: area_error(model, pattern),
            shape_error: shape_error(model, pattern),
            max_strain: max_strain(model, pattern),
            flipped,
            overlap: flipped > 0 || boundary_self_intersects(model, pattern),
        }
    }

    /// The larger of `E_S` and `E_C`.
    pub fn larger_error(&self) -> f64 {
        self.area_error.max(self.shape_error)
    }

    /// True if both errors are within `tolerance` and the pattern is a valid cut shape.
    pub fn within(&self, tolerance: f64) -> bool {
        self.area_error <= tolerance && self.shape_error <= tolerance && !self.overlap
    }
}

/// Signed area of a flat triangle (positive when counter-clockwise).
pub fn signed_area(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    0.5 * (b - a).perp_dot(c - a)
}

/// `E_S` of Eq. 4.
pub fn area_error(model: &FacetModel, pattern: &[DVec2]) -> f64 {
    let (mut difference, mut total) = (0.0, 0.0);
    for (f, t) in model.triangles().iter().enumerate() {
        let area = model.triangle_area(f);
        let [a, b, c] = t.map(|v| pattern[v as usize]);
        difference += (area - signed_area(a, b, c).abs()).abs();
        total += area;
    }
    difference / total
}

/// `E_C` of Eq. 6.
pub fn shape_error(model: &FacetModel, pattern: &[DVec2]) -> f64 {
    let (mut difference, mut total) = (0.0, 0.0);
    for (&[a, b], &rest) in model.edges().iter().zip(model.rest_lengths()) {
        difference += (pattern[a as usize].distance(pattern[b as usize]) - rest).abs();
        total += rest;
    }
    difference / total
}

/// Largest relative edge length change.
pub fn max_strain(model: &FacetModel, pattern: &[DVec2]) -> f64 {
    model
        .edges()
        .iter()
        .zip(model.rest_lengths())
        .map(|(&[a, b], &rest)| {
            (pattern[a as usize].distance(pattern[b as usize]) - rest).abs() / rest
        })
        .fold(0.0, f64::max)
}

/// A flat triangle whose signed area is at most this fraction of its 3D area is degenerate: a
/// sliver that no longer has a shape (the independent metrics' definition, `|A'| < 1e-9 A`).
pub const DEGENERATE_AREA_RATIO: f64 = 1e-9;

/// The triangles whose signed flat area is at most `ratio` times their 3D area (with `ratio` =
/// [`DEGENERATE_AREA_RATIO`]: the flipped and the degenerate ones).
pub fn squeezed_triangles(model: &FacetModel, pattern: &[DVec2], ratio: f64) -> Vec<usize> {
    (model.triangles().iter().enumerate())
        .filter(|&(f, t)| {
            let [a, b, c] = t.map(|v| pattern[v as usize]);
            signed_area(a, b, c) <= ratio * model.triangle_area(f)
        })
        .map(|(f, _)| f)
        .collect()
}

/// Number of triangles with non-positive signed flat area.
pub fn flipped_triangles(model: &FacetModel, pattern: &[DVec2]) -> usize {
    flipped(model, pattern).count()
}

/// The triangles with non-positive signed flat area, in order.
pub fn flipped_faces(model: &FacetModel, pattern: &[DVec2]) -> Vec<usize> {
    flipped(model, pattern).collect()
}

/// The triangles with non-positive signed flat area.
fn flipped<'a>(model: &'a FacetModel, pattern: &'a [DVec2]) -> impl Iterator<Item = usize> + 'a {
    (model.triangles().iter().enumerate())
        .filter(|(_, t)| {
            let [a, b, c] = t.map(|v| pattern[v as usize]);
            signed_area(a, b, c) <= 0.0
        })
        .map(|(f, _)| f)
}

/// True if two boundary segments that share no vertex intersect (touching counts).
pub fn boundary_self_intersects(model: &FacetModel, pattern: &[DVec2]) -> bool {
    boundary_comes_within(model, pattern, 0.0)
}

/// True if two boundary segments that share no vertex come within `gap` of each other: with a
/// small `gap`, a test that turning or moving the pattern does not change (where two sides lie
/// on each other, as along a crack of no width in the surface itself, whether they touch is
/// decided by rounding, and the test with no gap may say no before a turn and yes after).
pub fn boundary_comes_within(model: &FacetModel, pattern: &[DVec2], gap: f64) -> bool {
    let segments: Vec<[u32; 2]> = model.boundary_sides().collect();
    any_segments_within(&segments, pattern, gap)
}

/// Smallest grid cell of the boundary crossing test, relative to the boundary's extent: keeps
/// the grid finite when the segments are all but zero-length; it does not change which crossings
/// are found, only how they are bucketed.
const SMALLEST_CELL_RELATIVE: f64 = 1e-12;

/// Tests segment pairs that share no vertex for coming within `gap`, bucketed on a uniform grid
/// (each segment's box grown by `gap`) so the cost stays near linear for well-spread boundaries.
fn any_segments_within(segments: &[[u32; 2]], pattern: &[DVec2], gap: f64) -> bool {
    if segments.len() < 2 {
        return false;
    }
    let (mut min, mut max) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    let mut total_length = 0.0;
    for &[a, b] in segments {
        let (p, q) = (pattern[a as usize], pattern[b as usize]);
        min = min.min(p.min(q));
        max = max.max(p.max(q));
        total_length += p.distance(q);
    }
    let cell = (total_length / segments.len() as f64)
        .max(SMALLEST_CELL_RELATIVE * (max - min).length())
        .max(f64::MIN_POSITIVE);
    let columns = (((max.x - min.x) / cell) as usize + 1).min(1 << 12);
    let rows = (((max.y - min.y) / cell) as usize + 1).min(1 << 12);
    let cell_size = DVec2::new(
        (max.x - min.x).max(cell) / columns as f64,
        (max.y - min.y).max(cell) / rows as f64,
    );
    let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); columns * rows];
    let cell_range = |p: DVec2, q: DVec2| {
        let low = ((p.min(q) - gap - min) / cell_size).floor();
        let high = ((p.max(q) + gap - min) / cell_size).floor();
        let clamp = |x: f64, n: usize| (x.max(0.0) as usize).min(n - 1);
        (
            clamp(low.x, columns),
            clamp(high.x, columns),
            clamp(low.y, rows),
            clamp(high.y, rows),
        )
    };
    for (s, &[a, b]) in segments.iter().enumerate() {
        let (x0, x1, y0, y1) = cell_range(pattern[a as usize], pattern[b as usize]);
        for y in y0..=y1 {
            for x in x0..=x1 {
                buckets[y * columns + x].push(s as u32);
            }
        }
    }
    buckets.iter().any(|bucket| {
        bucket.iter().enumerate().any(|(i, &s)| {
            bucket[i + 1..].iter().any(|&t| {
                let ([a, b], [c, d]) = (segments[s as usize], segments[t as usize]);
                let shares_vertex = a == c || a == d || b == c || b == d;
                !shares_vertex
                    && segments_within(
                        pattern[a as usize],
                        pattern[b as usize],
                        pattern[c as usize],
                        pattern[d as usize],
                        gap,
                    )
            })
        })
    })
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};

    use crate::cad::TriangleSoup;
    use crate::flatten::accuracy::{boundary_comes_within, boundary_self_intersects};
    use crate::mesh::validate;

    /// A flat fan of four right-angled triangles around the origin whose last spoke ends
    /// `opening` short of a full turn, as a distinct vertex: a square with a slit of that width
    /// (at the rim) from its edge to its centre, as positions in the plane and the model.
    fn slit_square(opening: f64) -> (Vec<DVec2>, crate::mesh::FacetModel) {
        let mut flat = vec![DVec2::ZERO];
        for quarter in 0..4 {
            flat.push(DVec2::from_angle(
                quarter as f64 * std::f64::consts::FRAC_PI_2,
            ));
        }
        flat.push(DVec2::from_angle(-opening));
        let positions = flat.iter().map(|p| p.extend(0.0)).collect::<Vec<DVec3>>();
        let triangles = (1..=4).map(|i| [0, i, i + 1]).collect();
        let model = validate(&TriangleSoup::new(positions, triangles))
            .expect("valid")
            .components
            .remove(0);
        (flat, model)
    }

    #[test]
    fn a_slit_a_rounding_wide_does_not_cross_but_touches_within_a_small_gap() {
        let (pattern, model) = slit_square(1e-13);
        assert!(!boundary_self_intersects(&model, &pattern));
        assert!(boundary_comes_within(&model, &pattern, 1e-9));
        let (pattern, model) = slit_square(0.1);
        assert!(!boundary_comes_within(&model, &pattern, 1e-9));
        let (pattern, model) = slit_square(-0.1);
        assert!(boundary_self_intersects(&model, &pattern));
    }
}
