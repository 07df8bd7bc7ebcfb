//! The CAD surfaces a part is made of: built once from a part file (or the loose surfaces of a
//! STEP file) with their exact parameters, then sampled by the tessellator at the requested mesh
//! size and chord tolerance.
//!
//! Three families, each meshed by the algorithm that suits it:
//! - [`RuledSurface`]: surfaces made of straight rulings (cylinder and cone segments, developable
//!   lofts, extrusions), meshed along the rulings so that a developable surface stays exactly
//!   developable;
//! - [`RevolutionSurface`]: a profile of lines and arcs turned about an axis, meshed on parallels;
//! - [`PatchSurface`]: a planar region or a B-spline/NURBS patch (truck-geometry) with trim loops,
//!   meshed by constrained Delaunay refinement in its parameter domain.
//!
//! Lengths are in the part's units, angles in radians.

use glam::{DVec2, DVec3};
use truck_modeling::{BSplineSurface, NurbsSurface, Vector4};

use super::frame::Frame;
use super::profile::Profile;

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
    /// mapped from its surface's parameters by the tessellator).
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
