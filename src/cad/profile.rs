//! Planar profiles of lines and arcs (the sections of extrusions, the meridians of surfaces of
//! revolution), their arc lengths and their sampling at a mesh size and chord tolerance.
//!
//! Lengths are in the part's units, angles in radians.

use glam::DVec2;

use crate::geometry::tolerance::STATION_TOLERANCE;

/// A planar profile: a start point and line or arc segments, in local 2D coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// First point.
    pub start: DVec2,
    /// Segments in order.
    pub segments: Vec<ProfileSegment>,
}

/// One profile segment, ending at `to`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProfileSegment {
    /// A straight line.
    Line {
        /// End point.
        to: DVec2,
    },
    /// A circular arc about `center`, turning by `sweep` radians (positive counter-clockwise).
    Arc {
        /// End point.
        to: DVec2,
        /// Centre.
        center: DVec2,
        /// Signed turning angle.
        sweep: f64,
    },
}

impl Profile {
    /// Points along the profile, each segment split so that pieces are at most `max_length` long
    /// and arcs deviate at most `chord` from their chords. The start and every segment end are
    /// included; consecutive duplicates are not produced.
    pub fn sample(&self, max_length: f64, chord: f64) -> Vec<DVec2> {
        self.sample_through(max_length, chord, &[])
    }

    /// [`Profile::sample`] with a point at each arc length of `through` (from the start): the
    /// stretches between them and the segment ends are split each on its own.
    pub fn sample_through(&self, max_length: f64, chord: f64, through: &[f64]) -> Vec<DVec2> {
        let mut points = vec![self.start];
        let mut before = 0.0;
        for (from, segment) in self.pieces() {
            let length = segment.length(from);
            let stations: Vec<f64> = through.iter().map(|s| (s - before) / length).collect();
            let fractions = match segment {
                ProfileSegment::Line { .. } => fractions_through(&stations, |span| {
                    pieces_for_length(span * length, max_length)
                }),
                ProfileSegment::Arc { center, sweep, .. } => {
                    let radius = from.distance(center);
                    fractions_through(&stations, |span| {
                        pieces_for_arc(radius, span * sweep.abs(), max_length, chord)
                    })
                }
            };
            // An arc ends exactly at its end point (a line's last fraction gives it anyway).
            let last = fractions.len() - 1;
            points.extend(fractions.iter().enumerate().map(|(k, t)| match segment {
                ProfileSegment::Arc { to, .. } if k == last => to,
                _ => segment.point_at(from, t),
            }));
            before += length;
        }
        points
    }
}

/// A point of `[0, 1]` split at stations: the end of piece `k` of the `count` equal pieces of the
/// stretch that starts at `from` and spans `span`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fraction {
    from: f64,
    span: f64,
    k: usize,
    count: usize,
}

impl Fraction {
    /// This fraction of `length`, rounded as `length · k / count` when the stretch is all of
    /// `[0, 1]` (so that sampling without stations is unchanged to the last bit).
    pub fn of(&self, length: f64) -> f64 {
        length * self.from + length * self.span * self.k as f64 / self.count as f64
    }
}

/// The fractions (in `(0, 1]`, increasing, ending at 1) that split `[0, 1]` at `stations` and
/// each stretch between them into `pieces(stretch)` equal pieces. Stations outside `(0, 1)` or
/// within `STATION_TOLERANCE` (1e-9) of an end or of each other are dropped.
pub fn fractions_through(stations: &[f64], pieces: impl Fn(f64) -> usize) -> Vec<Fraction> {
    let mut stops: Vec<f64> = stations
        .iter()
        .copied()
        .filter(|t| *t > STATION_TOLERANCE && *t < 1.0 - STATION_TOLERANCE)
        .collect();
    stops.sort_by(f64::total_cmp);
    stops.dedup_by(|a, b| *a - *b <= STATION_TOLERANCE);
    stops.push(1.0);
    let mut fractions = Vec::new();
    let mut from = 0.0;
    for stop in stops {
        let span = stop - from;
        let count = pieces(span);
        fractions.extend((1..=count).map(|k| Fraction {
            from,
            span,
            k,
            count,
        }));
        from = stop;
    }
    fractions
}

impl Profile {
    /// The segments with their start points, in order.
    fn pieces(&self) -> impl Iterator<Item = (DVec2, ProfileSegment)> + '_ {
        let starts = std::iter::once(self.start).chain(self.segments.iter().map(|s| s.end()));
        starts.zip(self.segments.iter().copied())
    }

    /// The profile's length.
    pub fn length(&self) -> f64 {
        self.pieces().map(|(from, s)| s.length(from)).sum()
    }

    /// Whether the profile ends at its start (a closed section).
    pub fn is_closed(&self, tolerance: f64) -> bool {
        self.segments
            .last()
            .is_some_and(|s| s.end().distance(self.start) <= tolerance)
    }

    /// The arc length from the start to the profile point nearest to `point`.
    pub fn nearest_arc_length(&self, point: DVec2) -> f64 {
        let mut best = (f64::INFINITY, 0.0);
        let mut before = 0.0;
        for (from, segment) in self.pieces() {
            let (distance, along) = segment.nearest(from, point);
            if distance < best.0 {
                best = (distance, before + along);
            }
            before += segment.length(from);
        }
        best.1
    }
}

impl ProfileSegment {
    /// The point at fraction `t` of the arc length of the segment starting at `from`.
    fn point_at(&self, from: DVec2, t: &Fraction) -> DVec2 {
        match *self {
            ProfileSegment::Line { to } => from.lerp(to, t.of(1.0)),
            ProfileSegment::Arc { center, sweep, .. } => {
                let start = (from - center).to_angle();
                center + DVec2::from_angle(start + t.of(sweep)) * from.distance(center)
            }
        }
    }

    /// The end point.
    pub fn end(&self) -> DVec2 {
        match *self {
            ProfileSegment::Line { to } | ProfileSegment::Arc { to, .. } => to,
        }
    }

    /// The length of the segment starting at `from`.
    fn length(&self, from: DVec2) -> f64 {
        match *self {
            ProfileSegment::Line { to } => from.distance(to),
            ProfileSegment::Arc { center, sweep, .. } => from.distance(center) * sweep.abs(),
        }
    }

    /// Distance from `point` to the segment starting at `from`, and the arc length from `from`
    /// to the nearest point.
    fn nearest(&self, from: DVec2, point: DVec2) -> (f64, f64) {
        match *self {
            ProfileSegment::Line { to } => {
                let length = from.distance(to);
                let along = if length > 0.0 {
                    ((point - from).dot(to - from) / length).clamp(0.0, length)
                } else {
                    0.0
                };
                let nearest = from + (to - from) * (along / length.max(f64::MIN_POSITIVE));
                (point.distance(nearest), along)
            }
            ProfileSegment::Arc { center, sweep, .. } => {
                let radius = from.distance(center);
                let start = (from - center).to_angle();
                let turn = (point - center).to_angle() - start;
                // The turn from the start towards `point` the way the arc runs, in [0, 2π).
                let ahead = (turn * sweep.signum()).rem_euclid(std::f64::consts::TAU);
                let overshoot = ahead - sweep.abs();
                let clamped = if overshoot <= 0.0 {
                    ahead
                } else if overshoot < std::f64::consts::TAU - ahead {
                    sweep.abs()
                } else {
                    0.0
                };
                let nearest = center + DVec2::from_angle(start + clamped * sweep.signum()) * radius;
                (point.distance(nearest), clamped * radius)
            }
        }
    }
}

/// Number of equal pieces so that each is at most `max_length` long (at least one).
pub fn pieces_for_length(length: f64, max_length: f64) -> usize {
    ((length / max_length).ceil() as usize).max(1)
}

/// Number of equal pieces of an arc of `radius` and `angle` (radians) so that each piece is at most
/// `max_length` long and deviates at most `chord` from its chord (at least one).
pub fn pieces_for_arc(radius: f64, angle: f64, max_length: f64, chord: f64) -> usize {
    let by_length = radius * angle / max_length;
    let ratio = (1.0 - chord / radius).clamp(-1.0, 1.0);
    let step_by_chord = 2.0 * ratio.acos();
    let by_chord = if step_by_chord > 0.0 {
        angle / step_by_chord
    } else {
        1.0
    };
    (by_length.max(by_chord).ceil() as usize).max(1)
}
