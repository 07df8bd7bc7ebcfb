//! The rotations a part may take: a fixed list, a step, or free (sampled), and the angle
//! comparison every rotation check uses.

use serde::Serialize;

/// Number of evenly spaced rotations tried for a part whose rotation is [`Rotations::Free`].
pub const FREE_ROTATION_SAMPLES: u32 = 24;

/// The smallest rotation step accepted, degrees: 360 orientations per part (a step of 1e-9
/// asked for 3.6e11 and aborted on memory).
pub const MINIMUM_ROTATION_STEP_DEGREES: f64 = 1.0;

/// Two angles closer than this (degrees) are the same rotation: bounds the difference between an
/// allowed rotation and a placed one, and merges listed angles that round to the same rotation.
pub const ANGLE_TOLERANCE_DEGREES: f64 = 1e-6;

/// Which rotations a part may take, in degrees counter-clockwise about its own origin.
///
/// A part with a grain direction ([`NestItem::grain_degrees`](crate::nest::NestItem::grain_degrees))
/// ignores its `Rotations`: it is only placed with its grain along the stock's x axis (see
/// [`NestItem::poses`](crate::nest::NestItem::poses)).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Rotations {
    /// Only these angles.
    Fixed(Vec<f64>),
    /// Every multiple of this step in [0, 360).
    Step(f64),
    /// Any angle: the construction tries [`FREE_ROTATION_SAMPLES`] evenly spaced ones, and the
    /// search through overlap turns parts continuously between them.
    Free,
}

impl Rotations {
    /// The distinct angles the search tries, each in [0, 360), in increasing order.
    ///
    /// Returns `None` for an empty list, a non-finite angle, or a step outside
    /// [[`MINIMUM_ROTATION_STEP_DEGREES`], 360].
    pub fn angles(&self) -> Option<Vec<f64>> {
        let mut angles: Vec<f64> = match self {
            Rotations::Fixed(list) => {
                if list.is_empty() || list.iter().any(|angle| !angle.is_finite()) {
                    return None;
                }
                list.iter().map(|angle| angle.rem_euclid(360.0)).collect()
            }
            Rotations::Step(step) => {
                if !step.is_finite() || *step < MINIMUM_ROTATION_STEP_DEGREES || *step > 360.0 {
                    return None;
                }
                let count = (360.0 / step - ANGLE_TOLERANCE_DEGREES).ceil().max(1.0) as u32;
                (0..count).map(|index| f64::from(index) * step).collect()
            }
            Rotations::Free => {
                let step = 360.0 / f64::from(FREE_ROTATION_SAMPLES);
                (0..FREE_ROTATION_SAMPLES)
                    .map(|index| f64::from(index) * step)
                    .collect()
            }
        };
        angles.sort_by(f64::total_cmp);
        angles.dedup_by(|a, b| angle_distance(*a, *b) < ANGLE_TOLERANCE_DEGREES);
        if angles.len() > 1
            && angle_distance(angles[0], angles[angles.len() - 1]) < ANGLE_TOLERANCE_DEGREES
        {
            angles.pop();
        }
        Some(angles)
    }

    /// These rotations each followed by a turn of `offset` degrees: a step stays a step when the
    /// offset is one of its multiples, free stays free. Invalid rotations stay as they are, for
    /// the search to report.
    pub fn turned_by(&self, offset: f64) -> Rotations {
        match self {
            Rotations::Free => Rotations::Free,
            Rotations::Step(step)
                if angle_distance((offset / step).round() * step, offset)
                    < ANGLE_TOLERANCE_DEGREES =>
            {
                self.clone()
            }
            _ => self.angles().map_or_else(
                || self.clone(),
                |angles| Rotations::Fixed(angles.iter().map(|angle| angle + offset).collect()),
            ),
        }
    }

    /// Every rotation of any of `sets`: `None` when there is none, free when one is free, the
    /// set itself when all are the same, else the list of all their angles. Invalid rotations
    /// are kept (the first of them) for the search to report.
    pub fn union(sets: &[Rotations]) -> Option<Rotations> {
        let first = sets.first()?;
        if sets.iter().all(|set| set == first) {
            return Some(first.clone());
        }
        if sets.contains(&Rotations::Free) {
            return Some(Rotations::Free);
        }
        let mut all = Vec::new();
        for set in sets {
            match set.angles() {
                Some(angles) => all.extend(angles),
                None => return Some(set.clone()),
            }
        }
        Some(Rotations::Fixed(all))
    }

    /// Whether `angle` (degrees) is one of the allowed rotations, within [`ANGLE_TOLERANCE_DEGREES`].
    pub fn allows(&self, angle: f64) -> bool {
        match self {
            Rotations::Free => angle.is_finite(),
            _ => self.angles().is_some_and(|angles| {
                angles
                    .iter()
                    .any(|allowed| angle_distance(*allowed, angle) < ANGLE_TOLERANCE_DEGREES)
            }),
        }
    }
}

/// Distance between two angles on the circle, in degrees, in [0, 180].
pub(super) fn angle_distance(a: f64, b: f64) -> f64 {
    let difference = (a - b).rem_euclid(360.0);
    difference.min(360.0 - difference)
}
