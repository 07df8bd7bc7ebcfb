//! Surfaces closed on themselves from pole to pole (a full sphere, a closed surface of
//! revolution), which STEP bounds with a vertex loop only: split into two caps meshed in polar
//! maps.

use std::ops::Bound;

use glam::DVec3;
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::Surface as StepSurface;

use super::domain_map::Axis;
use super::native::{native_derivatives, native_point};
use crate::geometry::golden_section_minimum;
use crate::geometry::tolerance::STEP_POLE_RATIO;

/// Samples along the meridian when a surface is checked for poles at both ends.
const MERIDIAN_SAMPLES: usize = 16;

/// Steps of the golden-section search for a pole along a periodic meridian.
const GOLDEN_SECTION_STEPS: usize = 80;

/// A surface closed on itself from pole to pole: periodic in its angle about an axis, its other
/// parameter running between two poles (a full sphere, a closed surface of revolution). STEP
/// writes a face covering such a surface with a vertex loop only (no edge), so flatcut splits it
/// along its middle parallel into two caps, each bounded by that parallel and a seam meridian out
/// to its pole and back (the layout of a hemisphere's face), and meshes each cap in the polar map.
#[derive(Debug, Clone)]
pub struct PoleToPole {
    surface: StepSurface,
    angular: Axis,
    period: f64,
    /// The meridian parameter at the two poles.
    poles: [f64; 2],
    /// Angle of the seam meridian (the parallel's start).
    angle0: f64,
}

impl PoleToPole {
    /// The surface's pole-to-pole structure, if it has one: a periodic angle whose parallel's
    /// radius `|∂S/∂θ|` vanishes (relative to its largest) at two values of the other parameter,
    /// the ends of its range, or, when that parameter is periodic too (a full ellipse revolved
    /// covers its ellipsoid twice), two consecutive zeros over one period.
    pub fn of(surface: &StepSurface) -> Option<Self> {
        let periods = [surface.u_period(), surface.v_period()];
        let (u, v) = surface.parameter_range();
        [
            (Axis::U, periods[0], v, periods[1]),
            (Axis::V, periods[1], u, periods[0]),
        ]
        .into_iter()
        .find_map(|(angular, period, range, meridian_period)| {
            Self::about(surface, angular, period?, range, meridian_period)
        })
    }

    fn about(
        surface: &StepSurface,
        angular: Axis,
        period: f64,
        range: (Bound<f64>, Bound<f64>),
        meridian_period: Option<f64>,
    ) -> Option<Self> {
        let finite = |bound: Bound<f64>| match bound {
            Bound::Included(t) | Bound::Excluded(t) => Some(t).filter(|t| t.is_finite()),
            Bound::Unbounded => None,
        };
        let (t0, t1) = match meridian_period {
            Some(meridian_period) => {
                let start = finite(range.0).unwrap_or(0.0);
                (start, start + meridian_period)
            }
            None => (finite(range.0)?, finite(range.1)?),
        };
        if t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        let closed = PoleToPole {
            surface: surface.clone(),
            angular,
            period,
            poles: [t0, t1],
            angle0: 0.0,
        };
        let step = (t1 - t0) / MERIDIAN_SAMPLES as f64;
        let radii: Vec<f64> = (0..=MERIDIAN_SAMPLES)
            .map(|i| closed.parallel_radius(t0 + step * i as f64))
            .collect();
        let largest = radii.iter().copied().fold(0.0_f64, f64::max);
        if !(largest > 0.0 && largest.is_finite()) {
            return None;
        }
        let is_pole = |t: f64| closed.parallel_radius(t) <= STEP_POLE_RATIO * largest;
        let poles = match meridian_period {
            None => [t0, t1],
            Some(_) => {
                let count = MERIDIAN_SAMPLES;
                let mut zeros = (0..count)
                    .filter(|&i| {
                        radii[i] <= radii[(i + count - 1) % count] && radii[i] <= radii[i + 1]
                    })
                    .map(|i| {
                        let t = t0 + step * i as f64;
                        closed.smallest_radius(t - step, t + step)
                    })
                    .filter(|&t| is_pole(t));
                let first = zeros.next()?;
                let second = zeros.find(|&t| t - first > 0.5 * step)?;
                [first, second]
            }
        };
        (is_pole(poles[0]) && is_pole(poles[1])).then_some(PoleToPole { poles, ..closed })
    }

    /// The parameter in `[low, high]` where the parallel's radius is smallest (golden section).
    fn smallest_radius(&self, low: f64, high: f64) -> f64 {
        golden_section_minimum(|t| self.parallel_radius(t), low, high, GOLDEN_SECTION_STEPS)
    }

    fn parallel_radius(&self, t: f64) -> f64 {
        let (su, sv) = native_derivatives(&self.surface, self.angular.join(t, self.angle0));
        match self.angular {
            Axis::U => su.length(),
            Axis::V => sv.length(),
        }
    }

    fn middle(&self) -> f64 {
        0.5 * (self.poles[0] + self.poles[1])
    }

    /// The point of the middle parallel at `s` of the way round (0 and 1 on the seam).
    pub fn parallel(&self, s: f64) -> DVec3 {
        let angle = self.angle0 + self.period * s;
        native_point(&self.surface, self.angular.join(self.middle(), angle))
    }

    /// The point of the seam meridian at `s` of the way from the middle parallel to pole
    /// `pole` (0 or 1).
    pub fn meridian(&self, pole: usize, s: f64) -> DVec3 {
        let t = self.middle() + (self.poles[pole] - self.middle()) * s;
        native_point(&self.surface, self.angular.join(t, self.angle0))
    }

    /// Points on a grid of parallels and meridians (for the part's size).
    pub fn grid_points(&self) -> Vec<DVec3> {
        let count = MERIDIAN_SAMPLES;
        let mut points = Vec::with_capacity((count + 1) * (count + 1));
        for i in 0..=count {
            let t = self.poles[0] + (self.poles[1] - self.poles[0]) * i as f64 / count as f64;
            for j in 0..=count {
                let angle = self.angle0 + self.period * j as f64 / count as f64;
                points.push(native_point(&self.surface, self.angular.join(t, angle)));
            }
        }
        points
    }
}
