//! The start of a union's flattening when two neighbouring pieces are glued back together: the
//! patterns the two pieces already have, the second moved rigidly onto the first along the curve
//! they share, instead of a pattern grown from nothing. Both pieces lie flat within tolerance,
//! so their union's pattern is close to them; started there, the quick flattening that screens
//! the union skips its growing phase. On the Hencky scan midpoint-subdivided to 320k triangles
//! the gluing took 47 s from grown starts and about 40 s from the pieces' patterns, and ended
//! with 262 pieces instead of 343 (`super::pieces` uses this start for unions of at least
//! `WARM_START_MIN_TRIANGLES`, and grows one where this start ends in a fold).

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec2;

use super::piece::Piece;
use super::result::CutResult;
use super::state::{PointKey, point_key};

/// The flat positions of two pieces' points, the second piece's moved rigidly onto the first's
/// along the points they share.
pub(super) struct UnionStart {
    /// The first piece's flat position at each of its points.
    first: BTreeMap<PointKey, DVec2>,
    /// The second piece's, moved.
    second: BTreeMap<PointKey, DVec2>,
}

impl UnionStart {
    /// The two pieces' patterns (`result`s, numbered by their piece's vertices through
    /// `original_vertex`), the second moved by the rotation and translation that best fit its
    /// shared points to the first's (least squares). `None` when they share fewer than two
    /// points.
    pub fn new(first: (&Piece, &CutResult), second: (&Piece, &CutResult)) -> Option<Self> {
        let first = flat_points(first.0, first.1);
        let mut second = flat_points(second.0, second.1);
        let pairs: Vec<(DVec2, DVec2)> = (first.iter())
            .filter_map(|(key, &p)| Some((p, *second.get(key)?)))
            .collect();
        let (rotation, from, to) = best_rigid_fit(&pairs)?;
        for q in second.values_mut() {
            *q = to + rotation.rotate(*q - from);
        }
        Some(Self { first, second })
    }

    /// The start positions of `union`'s vertices, its first `first_count` vertices from the
    /// first piece and the others from the second (as [`Piece::glued`] numbers them), a
    /// vertex where the two were glued (inside the union, on both pieces) at the mean of the two
    /// positions; a point only one piece holds (one a T-junction split added) takes that
    /// piece's. `None` when a vertex is on neither piece.
    pub fn positions(&self, union: &Piece, first_count: usize) -> Option<Vec<DVec2>> {
        let boundary: BTreeSet<u32> = union
            .model
            .boundary_loops()
            .iter()
            .flatten()
            .copied()
            .collect();
        (union.model.positions().iter().enumerate())
            .map(|(v, &point)| {
                let key = point_key(point);
                let (mine, theirs) = if v < first_count {
                    (self.first.get(&key), self.second.get(&key))
                } else {
                    (self.second.get(&key), self.first.get(&key))
                };
                match (mine, theirs) {
                    (Some(&p), Some(&q)) if !boundary.contains(&(v as u32)) => Some((p + q) / 2.0),
                    (Some(&p), _) | (None, Some(&p)) => Some(p),
                    (None, None) => None,
                }
            })
            .collect()
    }
}

/// The flat position of each point of `piece` in its pattern `result` (the first copy of a
/// point its opening seams split).
fn flat_points(piece: &Piece, result: &CutResult) -> BTreeMap<PointKey, DVec2> {
    let mut points = BTreeMap::new();
    for (&v, &flat) in result
        .original_vertex
        .iter()
        .zip(&result.flattened.positions)
    {
        points
            .entry(point_key(piece.model.positions()[v as usize]))
            .or_insert(flat);
    }
    points
}

/// The rotation (as a unit complex number) and the two centroids, `from` and `to`, of the
/// rigid motion `q ↦ to + rotation · (q − from)` that brings the second points of `pairs` closest
/// to the first in least squares; `None` for fewer than two pairs.
fn best_rigid_fit(pairs: &[(DVec2, DVec2)]) -> Option<(DVec2, DVec2, DVec2)> {
    if pairs.len() < 2 {
        return None;
    }
    let count = pairs.len() as f64;
    let to = pairs.iter().map(|pair| pair.0).sum::<DVec2>() / count;
    let from = pairs.iter().map(|pair| pair.1).sum::<DVec2>() / count;
    let (mut cosine, mut sine) = (0.0, 0.0);
    for &(p, q) in pairs {
        let (p, q) = (p - to, q - from);
        cosine += q.dot(p);
        sine += q.perp_dot(p);
    }
    let rotation = DVec2::new(cosine, sine).try_normalize()?;
    Some((rotation, from, to))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_best_rigid_fit_undoes_a_rotation_and_a_shift() {
        let points = [
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 1.0),
        ];
        let rotation = DVec2::from_angle(0.7);
        let shift = DVec2::new(-3.0, 5.0);
        let pairs: Vec<(DVec2, DVec2)> = (points.iter())
            .map(|&p| (p, shift + rotation.rotate(p)))
            .collect();
        let (found, from, to) = best_rigid_fit(&pairs).expect("a fit");
        for (p, q) in pairs {
            assert!((to + found.rotate(q - from) - p).length() < 1e-12);
        }
        assert!(best_rigid_fit(&[(DVec2::ZERO, DVec2::ONE)]).is_none());
    }
}
