//! The orientation barrier: a term per triangle that is zero while its flat area is at least a
//! threshold times its rest area and grows to infinity as the area goes to zero.
//!
//! With `x = A' / A` (signed flat area over rest area) and `s` the threshold, the barrier of
//! Li et al. (2020, "Incremental potential contact") is `b(x) = −(x − s)² ln(x / s)` for
//! `0 < x < s` and 0 above: twice continuously differentiable at `s` (value, slope and curvature
//! all vanish there), convex, and infinite at `x = 0`. A triangle carries
//! `w b(x)` with `w = weight × C̄ × A`, `C̄` the mean spring constant of its edges, so the term
//! scales like the spring energy (constant × length²) and follows the stiffness.

/// A barrier: its threshold `s` (the area ratio below which it acts) and its weight (relative to
/// the spring constant times the rest area).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Barrier {
    /// The area ratio `s` below which the barrier acts.
    pub threshold: f64,
    /// The weight relative to the spring constant times the rest area.
    pub weight: f64,
}

/// The orientation barrier: triangles kept at a tenth of their area or more feel nothing, so the
/// minimiser ends near the spring energy's own minimum.
pub const ORIENTATION_BARRIER: Barrier = Barrier {
    threshold: 0.1,
    weight: 1.0,
};

/// The opening barrier, for a pattern that has every triangle positively oriented but some
/// squeezed to slivers: it acts on every triangle below half its rest area, a thousand times as
/// strongly as the orientation barrier, so such triangles are pushed back to about half their
/// area (a spring pattern hardly resists a sliver: an obtuse triangle whose corner moves onto its
/// opposite side stretches one edge by a few per cent) and the rest feel nothing.
pub const OPENING_BARRIER: Barrier = Barrier {
    threshold: 0.5,
    weight: 1000.0,
};

/// The sliver barrier: the opening barrier's strength below a hundredth of the rest area only,
/// for a pattern that opening triangles up to half their area would take out of its tolerance.
pub const SLIVER_BARRIER: Barrier = Barrier {
    threshold: 0.01,
    weight: 1000.0,
};

/// The shaping barrier of the first stage from a Tutte start: it acts on every triangle
/// compressed below its rest area, strongly, so that the pattern unfolds instead of collapsing
/// into slivers (the spring energy alone does not mind a triangle of zero area whose sides keep
/// their lengths).
pub const SHAPING_BARRIER: Barrier = Barrier {
    threshold: 1.0,
    weight: 10.0,
};

impl Barrier {
    /// Value, first and second derivative of the barrier `b(x)` (without its weight) at the area
    /// ratio `x` (infinite value for `x ≤ 0`).
    pub fn at(&self, x: f64) -> [f64; 3] {
        let s = self.threshold;
        if x >= s {
            return [0.0; 3];
        }
        if x <= 0.0 {
            return [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY];
        }
        let (gap, log) = (x - s, (x / s).ln());
        let value = -gap * gap * log;
        let slope = -2.0 * gap * log - gap * gap / x;
        let curvature = -2.0 * log - 4.0 * gap / x + gap * gap / (x * x);
        [value, slope, curvature]
    }
}

#[cfg(test)]
mod tests {
    use crate::flatten::injective::barrier::*;

    #[test]
    fn the_barrier_is_smooth_at_the_threshold_convex_and_infinite_at_zero() {
        let b = ORIENTATION_BARRIER;
        let barrier = |x| b.at(x);
        let s = b.threshold;
        assert_eq!(barrier(s), [0.0; 3]);
        let [value, slope, curvature] = barrier(s * (1.0 - 1e-6));
        assert!(value.abs() < 1e-15 && slope.abs() < 1e-10 && curvature.abs() < 1e-4);
        assert!(barrier(1e-12)[0] > barrier(1e-6)[0] && barrier(1e-6)[0] > barrier(0.05)[0]);
        assert_eq!(barrier(0.0)[0], f64::INFINITY);
        for i in 1..100 {
            let x = s * i as f64 / 100.0;
            let [_, slope, curvature] = barrier(x);
            assert!(slope < 0.0 && curvature > 0.0, "x = {x}");
            let h = 1e-7 * x;
            let numeric = (barrier(x + h)[0] - barrier(x - h)[0]) / (2.0 * h);
            assert!(
                (numeric - slope).abs() <= 1e-5 * slope.abs().max(1e-6),
                "x = {x}"
            );
            let numeric = (barrier(x + h)[1] - barrier(x - h)[1]) / (2.0 * h);
            assert!(
                (numeric - curvature).abs() <= 1e-4 * curvature.max(1e-6),
                "x = {x}"
            );
        }
    }
}
