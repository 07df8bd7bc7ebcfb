//! The CAD surfaces a part is made of, as the tessellator sees them: built once from a part file
//! (or another front end) and then sampled at the requested mesh size and chord tolerance.
//!
//! Three families, each meshed by the algorithm that suits it:
//! - [`RuledSurface`]: surfaces made of straight rulings (cylinder and cone segments, developable
//!   lofts, extrusions), meshed along the rulings so that a developable surface stays exactly
//!   developable ([`super::ruled`]);
//! - [`RevolutionSurface`]: a profile of lines and arcs turned about an axis, meshed on parallels
//!   ([`super::revolution`]);
//! - [`PatchSurface`]: a planar region or a B-spline/NURBS patch (truck-geometry) with trim loops,
//!   meshed by constrained Delaunay refinement in its parameter domain ([`super::patch`]).
//!
//! Lengths are in the part's units, angles in radians.

use glam::{DVec2, DVec3};
use truck_modeling::{BSplineSurface, NurbsSurface, Vector4};

/// A right-handed orthonormal frame: where local coordinates live in the part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Origin.
    pub origin: DVec3,
    /// Local x axis (unit).
    pub x: DVec3,
    /// Local y axis (unit).
    pub y: DVec3,
    /// Local z axis (unit).
    pub z: DVec3,
}

impl Frame {
    /// The world frame.
    pub const WORLD: Frame = Frame {
        origin: DVec3::ZERO,
        x: DVec3::X,
        y: DVec3::Y,
        z: DVec3::Z,
    };

    /// A frame from an origin, a z axis and a reference for x (made perpendicular to z). `None`
    /// when the axis is zero or the reference is parallel to it.
    pub fn new(origin: DVec3, axis: DVec3, reference: DVec3) -> Option<Frame> {
        let z = axis.try_normalize()?;
        let x = (reference - z * reference.dot(z)).try_normalize()?;
        Some(Frame {
            origin,
            x,
            y: z.cross(x),
            z,
        })
    }

    /// The world position of local coordinates.
    pub fn point(&self, local: DVec3) -> DVec3 {
        self.origin + self.x * local.x + self.y * local.y + self.z * local.z
    }

    /// The world direction of a local vector.
    pub fn vector(&self, local: DVec3) -> DVec3 {
        self.x * local.x + self.y * local.y + self.z * local.z
    }
}

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

/// Stations closer than this (fraction of the stretch) to each other or to an end are one.
const STATION_TOLERANCE: f64 = 1e-9;

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

/// A surface made of straight rulings between two curves.
#[derive(Debug, Clone, PartialEq)]
pub enum RuledSurface {
    /// Rulings between two circles (or ellipses cut by tilted planes) at the same angle: cylinder
    /// and cone segments, straight or oblique, with mitred ends.
    Circular {
        /// Local frame: circles parallel to its x-y plane.
        frame: Frame,
        /// Bottom circle.
        bottom: RuledCircle,
        /// Top circle.
        top: RuledCircle,
        /// Angular range `[start, end]`, radians.
        angles: [f64; 2],
    },
    /// A developable loft between two convex sections in parallel planes: each ruling joins the
    /// points of the two sections where their tangents are parallel (their convex hull).
    Loft {
        /// Local frame: sections parallel to its x-y plane.
        frame: Frame,
        /// Bottom section.
        bottom: Section,
        /// Top section.
        top: Section,
        /// Tangent direction (radians) at which the closed loft is opened.
        seam: f64,
    },
    /// A profile swept along a straight direction.
    Extrusion {
        /// Local frame of the profile (its x-y plane).
        frame: Frame,
        /// The profile.
        profile: Profile,
        /// Extrusion vector in local coordinates.
        direction: DVec3,
    },
}

/// One end circle of a [`RuledSurface::Circular`]: its rulings end on the plane through `center`
/// tilted by `tilt` about the local y axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RuledCircle {
    /// Centre in local coordinates.
    pub center: DVec3,
    /// Radius (> 0).
    pub radius: f64,
    /// Tilt of the end plane about the local y axis, radians (0: perpendicular to the axis).
    pub tilt: f64,
}

impl RuledCircle {
    /// The local point at angle `angle`: on the circle's cylinder of rulings, on the tilted plane.
    pub fn point(&self, angle: f64) -> DVec3 {
        let (sin, cos) = angle.sin_cos();
        let offset = self.radius * cos;
        DVec3::new(
            self.center.x + offset,
            self.center.y + self.radius * sin,
            self.center.z + offset * self.tilt.tan(),
        )
    }
}

/// A convex closed section of a loft, in a plane `z = const` of the loft's frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Section {
    /// A circle.
    Circle {
        /// Centre (local x, y).
        center: DVec2,
        /// Radius (> 0).
        radius: f64,
        /// Plane height.
        z: f64,
    },
    /// A convex polygon, counter-clockwise, absolute local x, y.
    Polygon {
        /// Corners.
        corners: Vec<DVec2>,
        /// Plane height.
        z: f64,
    },
}

impl Section {
    /// The plane height.
    pub fn z(&self) -> f64 {
        match self {
            Section::Circle { z, .. } | Section::Polygon { z, .. } => *z,
        }
    }
}

/// A profile `(radius, z)` turned about the local z axis.
#[derive(Debug, Clone, PartialEq)]
pub struct RevolutionSurface {
    /// Local frame (z is the axis, angle 0 along x).
    pub frame: Frame,
    /// Profile in `(radius, z)`.
    pub profile: Profile,
    /// Angular range `[start, end]`, radians.
    pub angles: [f64; 2],
}

/// The parametric surface under a patch.
#[derive(Debug, Clone)]
pub enum PatchGeometry {
    /// A plane: parameters are the frame's local x, y.
    Plane(Frame),
    /// A NURBS patch (a B-spline patch has all weights 1), truck-geometry.
    Nurbs(NurbsSurface<Vector4>),
    /// Any other parametric surface, evaluated in a domain of its own (a STEP face in a domain
    /// mapped from its surface's parameters, see [`super::face_domain`]).
    Mapped(std::sync::Arc<dyn MappedSurface>),
}

/// A parametric surface evaluated through a trait object: a point and its two partial derivatives
/// at domain coordinates.
pub trait MappedSurface: std::fmt::Debug + Send + Sync {
    /// The point at domain coordinates `parameters`.
    fn point(&self, parameters: DVec2) -> DVec3;
    /// The partial derivatives along the two domain coordinates.
    fn derivatives(&self, parameters: DVec2) -> (DVec3, DVec3);
}

impl PatchGeometry {
    /// A NURBS patch from a truck B-spline surface in homogeneous coordinates.
    pub fn nurbs(surface: BSplineSurface<Vector4>) -> Self {
        PatchGeometry::Nurbs(NurbsSurface::new(surface))
    }

    /// The point at parameters `(u, v)`.
    pub fn point(&self, parameters: DVec2) -> DVec3 {
        match self {
            PatchGeometry::Plane(frame) => frame.point(parameters.extend(0.0)),
            PatchGeometry::Nurbs(surface) => {
                let point = surface.subs(parameters.x, parameters.y);
                DVec3::new(point.x, point.y, point.z)
            }
            PatchGeometry::Mapped(surface) => surface.point(parameters),
        }
    }

    /// The partial derivatives `(∂S/∂u, ∂S/∂v)` at `(u, v)`.
    pub fn derivatives(&self, parameters: DVec2) -> (DVec3, DVec3) {
        match self {
            PatchGeometry::Plane(frame) => (frame.x, frame.y),
            PatchGeometry::Nurbs(surface) => {
                let u = surface.uder(parameters.x, parameters.y);
                let v = surface.vder(parameters.x, parameters.y);
                (DVec3::new(u.x, u.y, u.z), DVec3::new(v.x, v.y, v.z))
            }
            PatchGeometry::Mapped(surface) => surface.derivatives(parameters),
        }
    }
}

/// A trimmed parametric patch: the region inside `outer` and outside every hole.
#[derive(Debug, Clone)]
pub struct PatchSurface {
    /// The surface.
    pub geometry: PatchGeometry,
    /// Outer boundary in the parameter domain, counter-clockwise.
    pub outer: Vec<DVec2>,
    /// Holes in the parameter domain.
    pub holes: Vec<Vec<DVec2>>,
}

/// One surface of a part.
#[derive(Debug, Clone)]
pub enum Surface {
    /// Straight rulings.
    Ruled(RuledSurface),
    /// A surface of revolution.
    Revolution(RevolutionSurface),
    /// A trimmed patch.
    Patch(PatchSurface),
}

/// A fold line of a part.
#[derive(Debug, Clone, PartialEq)]
pub enum FoldLineGeometry {
    /// A polyline in a patch's parameter domain.
    OnSurface {
        /// Surface index.
        surface: usize,
        /// Parameter-domain points.
        points: Vec<DVec2>,
    },
    /// The edge shared by two surfaces.
    Between {
        /// The two surfaces.
        surfaces: [usize; 2],
    },
}
