//! The flip-free step bound of Smith and Schaefer (2015, "Bijective parameterization with free
//! boundaries", §4.1): the largest step along a search direction that keeps every triangle
//! positively oriented.
//!
//! Moving the pattern `P` along the direction `D` by `t`, the doubled signed area of a triangle
//! `(a, b, c)` is a quadratic in `t`:
//! `2A(t) = (e₁ + t f₁) × (e₂ + t f₂) = e₁×e₂ + t (e₁×f₂ + f₁×e₂) + t² f₁×f₂`, with
//! `e₁ = b − a`, `e₂ = c − a` and `f₁`, `f₂` the same differences of the direction. Its smallest
//! positive root is where the triangle first degenerates; the minimum over the triangles bounds
//! the step.

use glam::DVec2;
use rayon::prelude::*;

use crate::mesh::FacetModel;

/// Smallest positive root of `c₂ t² + c₁ t + c₀` for `c₀ > 0`, or infinity if it has none: the
/// step at which a triangle of doubled area `c₀` degenerates. Roots by the cancellation-free
/// pair `q / c₂` and `c₀ / q` with `q = −½ (c₁ + sign(c₁) √(c₁² − 4 c₂ c₀))`, which also covers
/// the linear case `c₂ = 0`.
pub fn smallest_positive_root(c2: f64, c1: f64, c0: f64) -> f64 {
    let discriminant = c1 * c1 - 4.0 * c2 * c0;
    if discriminant < 0.0 {
        return f64::INFINITY;
    }
    let q = -0.5 * (c1 + c1.signum() * discriminant.sqrt());
    [q / c2, c0 / q]
        .into_iter()
        .filter(|&t| t > 0.0 && t.is_finite())
        .fold(f64::INFINITY, f64::min)
}

/// The step `t` at which the positively oriented triangle `corners` moved along `direction` (one
/// vector per corner) first has zero area; infinity if it never does.
pub fn triangle_flip_step(corners: [DVec2; 3], direction: [DVec2; 3]) -> f64 {
    let [a, b, c] = corners;
    let [da, db, dc] = direction;
    let (e1, e2) = (b - a, c - a);
    let (f1, f2) = (db - da, dc - da);
    smallest_positive_root(
        f1.perp_dot(f2),
        e1.perp_dot(f2) + f1.perp_dot(e2),
        e1.perp_dot(e2),
    )
}

/// The largest step along `direction` (one vector per vertex) that keeps every triangle of
/// `model`, positively oriented at `positions`, from degenerating: the minimum of
/// [`triangle_flip_step`] over the triangles (infinity if none ever degenerates).
pub fn max_flip_free_step(model: &FacetModel, positions: &[DVec2], direction: &[DVec2]) -> f64 {
    model
        .triangles()
        .par_iter()
        .map(|t| {
            let corners = t.map(|v| positions[v as usize]);
            let moved = t.map(|v| direction[v as usize]);
            triangle_flip_step(corners, moved)
        })
        .reduce(|| f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use crate::flatten::accuracy::signed_area;
    use crate::flatten::injective::step::*;

    /// A small deterministic generator (xorshift), so the test needs no dependency.
    struct Numbers(u64);

    impl Numbers {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }

        fn point(&mut self) -> DVec2 {
            DVec2::new(self.next(), self.next())
        }
    }

    fn area_at(corners: [DVec2; 3], direction: [DVec2; 3], t: f64) -> f64 {
        let [a, b, c] = [0, 1, 2].map(|i| corners[i] + direction[i] * t);
        signed_area(a, b, c)
    }

    #[test]
    fn the_flip_free_step_is_where_a_brute_force_scan_first_sees_zero_area() {
        let mut numbers = Numbers(0x9e37_79b9_7f4a_7c15);
        let mut finite = 0;
        for _ in 0..2000 {
            let mut corners = [numbers.point(), numbers.point(), numbers.point()];
            if signed_area(corners[0], corners[1], corners[2]) < 0.0 {
                corners.swap(1, 2);
            }
            if signed_area(corners[0], corners[1], corners[2]) < 1e-3 {
                continue;
            }
            let direction = [numbers.point(), numbers.point(), numbers.point()];
            let step = triangle_flip_step(corners, direction);
            // Brute force: the first sign change of the area on a fine grid of [0, 10].
            let samples = 20_000;
            let first_zero = (1..=samples)
                .map(|i| 10.0 * i as f64 / samples as f64)
                .find(|&t| area_at(corners, direction, t) <= 0.0);
            match first_zero {
                Some(t) => {
                    finite += 1;
                    let grid = 10.0 / samples as f64;
                    assert!(
                        step <= t + 1e-12 && step > t - grid - 1e-12,
                        "step {step}, brute force {t}"
                    );
                    assert!(area_at(corners, direction, step).abs() < 1e-9);
                    assert!(area_at(corners, direction, 0.999 * step) > 0.0);
                }
                None => assert!(step > 10.0 - 1e-9, "step {step} but no zero before 10"),
            }
        }
        assert!(
            finite > 500,
            "only {finite} triangles degenerate: a weak test"
        );
    }

    #[test]
    fn a_translation_never_flips_and_a_squash_flips_where_it_degenerates() {
        let corners = [DVec2::ZERO, DVec2::X, DVec2::Y];
        assert_eq!(triangle_flip_step(corners, [DVec2::ONE; 3]), f64::INFINITY);
        let squash = [DVec2::ZERO, DVec2::ZERO, DVec2::new(0.0, -1.0)];
        assert!((triangle_flip_step(corners, squash) - 1.0).abs() < 1e-15);
    }
}
