//! The exact geometry of a B-rep face's surface, read from truck-stepio's surface in world
//! coordinates (millimetres): a plane's normal, a cylinder's or cone's axis and radius, a
//! sphere's centre and radius, a torus's axis and radii, a surface of revolution's axis, an
//! extrusion's direction. The sheet-metal stages read thickness and bends from these.

use glam::DVec3;
use truck_meshalgo::prelude::*;
use truck_stepio::r#in::alias::{ElementarySurface, Surface as StepSurface, SweptCurve};

/// A face's surface with its exact parameters (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SurfaceGeometry {
    /// A plane through `origin` with unit `normal` (the surface's own, before the face's
    /// orientation).
    Plane {
        /// A point of the plane.
        origin: DVec3,
        /// Unit normal.
        normal: DVec3,
    },
    /// A cylinder about the line through `origin` along unit `axis`.
    Cylinder {
        /// A point of the axis.
        origin: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Radius.
        radius: f64,
    },
    /// A cone about the line through `origin` along unit `axis`: `radius` at `origin`, growing by
    /// `tan(half_angle)` per unit along `axis`.
    Cone {
        /// A point of the axis.
        origin: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Radius at `origin`.
        radius: f64,
        /// Half the apex angle, radians (signed: negative when the cone narrows along `axis`).
        half_angle: f64,
    },
    /// A sphere.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius.
        radius: f64,
    },
    /// A torus about the line through `center` along unit `axis`.
    Torus {
        /// Centre.
        center: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Distance from the axis to the tube's centre circle.
        major_radius: f64,
        /// The tube's radius.
        minor_radius: f64,
    },
    /// A curve turned about the line through `origin` along unit `axis`.
    Revolution {
        /// A point of the axis.
        origin: DVec3,
        /// Unit axis.
        axis: DVec3,
    },
    /// A curve swept along `direction` (its length is the sweep's).
    Extrusion {
        /// The sweep vector.
        direction: DVec3,
    },
    /// A B-spline surface (its control net is in the face's truck surface).
    BSpline,
    /// A NURBS surface (its control net and weights are in the face's truck surface).
    Nurbs,
}

fn point(p: Point3) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}

fn vector(v: Vector3) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

/// The axis (origin, unit direction) and the radius and height along the axis of a line's two
/// ends, in world coordinates through `transform`.
fn turned_line(
    line: &truck_modeling::Line<Point3>,
    origin: Point3,
    axis: Vector3,
    transform: &Matrix4,
) -> (DVec3, DVec3, [(f64, f64); 2]) {
    let origin = point(transform.transform_point(origin));
    let axis = vector(transform.transform_vector(axis)).normalize_or_zero();
    let ends = [line.0, line.1].map(|end| {
        let offset = point(transform.transform_point(end)) - origin;
        let height = offset.dot(axis);
        ((offset - axis * height).length(), height)
    });
    (origin, axis, ends)
}

impl SurfaceGeometry {
    /// The geometry of a truck-stepio surface.
    pub fn of(surface: &StepSurface) -> Self {
        match surface {
            StepSurface::ElementarySurface(elementary) => match elementary.as_ref() {
                ElementarySurface::Plane(plane) => Self::Plane {
                    origin: point(plane.origin()),
                    normal: vector(plane.normal()),
                },
                ElementarySurface::Sphere(sphere) => {
                    let transform = sphere.transform();
                    Self::Sphere {
                        center: point(transform.transform_point(sphere.entity().0.center())),
                        radius: sphere.entity().0.radius() * scale(transform),
                    }
                }
                ElementarySurface::ToroidalSurface(torus) => {
                    let transform = torus.transform();
                    let entity = torus.entity();
                    Self::Torus {
                        center: point(transform.transform_point(entity.center())),
                        axis: vector(transform.transform_vector(Vector3::unit_z()))
                            .normalize_or_zero(),
                        major_radius: entity.large_radius() * scale(transform),
                        minor_radius: entity.small_radius() * scale(transform),
                    }
                }
                ElementarySurface::CylindricalSurface(cylinder) => {
                    let revolved = cylinder.entity();
                    let (origin, axis, ends) = turned_line(
                        revolved.entity_curve(),
                        revolved.origin(),
                        revolved.axis(),
                        cylinder.transform(),
                    );
                    Self::Cylinder {
                        origin,
                        axis,
                        radius: ends[0].0,
                    }
                }
                ElementarySurface::ConicalSurface(cone) => {
                    let revolved = cone.entity();
                    let (origin, axis, [(r0, h0), (r1, h1)]) = turned_line(
                        revolved.entity_curve(),
                        revolved.origin(),
                        revolved.axis(),
                        cone.transform(),
                    );
                    Self::Cone {
                        origin: origin + axis * h0,
                        axis,
                        radius: r0,
                        half_angle: (r1 - r0).atan2(h1 - h0),
                    }
                }
            },
            StepSurface::SweptCurve(swept) => match swept.as_ref() {
                SweptCurve::ExtrudedCurve(extruded) => Self::Extrusion {
                    direction: vector(extruded.extruding_vector()),
                },
                SweptCurve::RevolutedCurve(revolved) => {
                    let transform = revolved.transform();
                    Self::Revolution {
                        origin: point(transform.transform_point(revolved.entity().origin())),
                        axis: vector(transform.transform_vector(revolved.entity().axis()))
                            .normalize_or_zero(),
                    }
                }
            },
            StepSurface::BSplineSurface(_) => Self::BSpline,
            StepSurface::NurbsSurface(_) => Self::Nurbs,
        }
    }
}

/// The length scale of a (similarity) transform.
fn scale(transform: &Matrix4) -> f64 {
    vector(transform.transform_vector(Vector3::unit_x())).length()
}
