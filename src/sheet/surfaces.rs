//! The surface kinds a sheet-metal solid is made of, planes, cylinders and cones (and formed
//! faces of any other kind), and the relations
//! between two faces that recognition and unfolding ask about: is one the continuation of the
//! other across a shared edge (tangent), and are they the two sides of the sheet (opposite, at
//! what thickness).

use glam::DVec3;

use crate::cad::{BrepShell, SurfaceGeometry};

/// Largest distance, in mm, between two positions that are the same (a plane through an axis,
/// two radii, two parallel planes at a given thickness).
pub const LENGTH_TOLERANCE_MM: f64 = 1e-4;

/// Largest `1 − |cos|` between two directions that are parallel, and largest `|cos|` between two
/// that are perpendicular.
pub const DIRECTION_TOLERANCE: f64 = 1e-7;

/// A face's surface: a plane, a cylinder or a cone (world coordinates, mm), or a formed face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SheetSurface {
    /// A plane through `origin` with unit `normal` (either side).
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
    /// A cone with its apex at `apex`, opening along unit `axis`: a point at distance `s` from
    /// the apex along a generator is `s · sin(half_angle)` from the axis.
    Cone {
        /// The apex.
        apex: DVec3,
        /// Unit axis, from the apex into the cone.
        axis: DVec3,
        /// Half the apex angle, radians, in `(0, π/2)`.
        half_angle: f64,
    },
    /// Any other surface (a sphere, a torus, a surface of revolution, a B-spline): a formed
    /// region (a dimple, a louvre), not developable. It continues no face smoothly and is
    /// opposite none.
    Formed,
}

/// Whether two unit directions are parallel (same or opposite sense).
pub fn parallel(a: DVec3, b: DVec3) -> bool {
    1.0 - a.dot(b).abs() <= DIRECTION_TOLERANCE
}

/// Distance from `point` to the line through `origin` along unit `axis`.
pub fn distance_to_axis(point: DVec3, origin: DVec3, axis: DVec3) -> f64 {
    let offset = point - origin;
    (offset - axis * offset.dot(axis)).length()
}

/// Whether two lengths are the same within [`LENGTH_TOLERANCE_MM`].
pub fn same_length(a: f64, b: f64) -> bool {
    (a - b).abs() <= LENGTH_TOLERANCE_MM
}

impl SheetSurface {
    /// The surface of a face: a plane, a cylinder, a cone, or else [`SheetSurface::Formed`].
    pub fn of_face(geometry: SurfaceGeometry) -> Self {
        Self::of(geometry).unwrap_or(Self::Formed)
    }

    /// The surface of a face, or `None` when it is neither a plane, a cylinder nor a cone.
    pub fn of(geometry: SurfaceGeometry) -> Option<Self> {
        match geometry {
            SurfaceGeometry::Plane { origin, normal } => Some(Self::Plane { origin, normal }),
            SurfaceGeometry::Cylinder {
                origin,
                axis,
                radius,
            } => Some(Self::Cylinder {
                origin,
                axis,
                radius,
            }),
            SurfaceGeometry::Cone {
                origin,
                axis,
                radius,
                half_angle,
            } if half_angle != 0.0 => {
                let opening = axis * half_angle.signum();
                Some(Self::Cone {
                    apex: origin - opening * (radius / half_angle.abs().tan()),
                    axis: opening,
                    half_angle: half_angle.abs(),
                })
            }
            _ => None,
        }
    }

    /// Whether `other` continues this surface smoothly across a shared edge: the same plane, the
    /// same cylinder, the same cone, or a plane tangent to a cylinder (parallel to its axis at
    /// its radius) or to a cone (through its apex, along a generator).
    pub fn tangent_to(&self, other: &Self) -> bool {
        match (*self, *other) {
            (Self::Cone { .. }, _) | (_, Self::Cone { .. }) => cone_tangent_to(self, other),
            (
                Self::Plane { origin, normal },
                Self::Plane {
                    origin: other_origin,
                    normal: other_normal,
                },
            ) => {
                parallel(normal, other_normal)
                    && (other_origin - origin).dot(normal).abs() <= LENGTH_TOLERANCE_MM
            }
            (plane @ Self::Plane { .. }, cylinder @ Self::Cylinder { .. })
            | (cylinder @ Self::Cylinder { .. }, plane @ Self::Plane { .. }) => {
                plane_tangent_to_cylinder(&plane, &cylinder)
            }
            (
                Self::Cylinder {
                    origin,
                    axis,
                    radius,
                },
                Self::Cylinder {
                    origin: other_origin,
                    axis: other_axis,
                    radius: other_radius,
                },
            ) => {
                coaxial(origin, axis, other_origin, other_axis) && same_length(radius, other_radius)
            }
            (Self::Formed, _) | (_, Self::Formed) => false,
        }
    }

    /// The thickness between this surface and `other` when they can be the two sides of a sheet:
    /// parallel planes (their distance), coaxial cylinders (the difference of their radii) or
    /// coaxial cones of one half-angle opening the same way (their distance along the normal,
    /// `cone_offset`).
    pub fn opposite_distance(&self, other: &Self) -> Option<f64> {
        match (*self, *other) {
            (
                Self::Cone {
                    apex,
                    axis,
                    half_angle,
                },
                Self::Cone {
                    apex: other_apex,
                    axis: other_axis,
                    half_angle: other_half_angle,
                },
            ) if axis.dot(other_axis) > 0.0
                && coaxial(apex, axis, other_apex, other_axis)
                && same_angle(half_angle, other_half_angle) =>
            {
                Some(cone_offset(apex, axis, half_angle, other_apex).abs())
            }
            (
                Self::Plane { origin, normal },
                Self::Plane {
                    origin: other_origin,
                    normal: other_normal,
                },
            ) if parallel(normal, other_normal) => Some((other_origin - origin).dot(normal).abs()),
            (
                Self::Cylinder {
                    origin,
                    axis,
                    radius,
                },
                Self::Cylinder {
                    origin: other_origin,
                    axis: other_axis,
                    radius: other_radius,
                },
            ) if coaxial(origin, axis, other_origin, other_axis) => {
                Some((radius - other_radius).abs())
            }
            _ => None,
        }
    }
}

/// The bounding diagonal of a shell's vertices, mm.
pub fn vertices_extent(shell: &BrepShell) -> f64 {
    let points = shell
        .shell
        .vertices
        .iter()
        .map(|p| DVec3::new(p.x, p.y, p.z));
    let (low, high) = points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(low, high), p| (low.min(p), high.max(p)),
    );
    if low.x <= high.x {
        (high - low).length()
    } else {
        0.0
    }
}

/// Whether two half-angles are the same (within [`DIRECTION_TOLERANCE`] radians).
fn same_angle(a: f64, b: f64) -> bool {
    (a - b).abs() <= DIRECTION_TOLERANCE
}

/// The signed distance along the normal from a cone (`apex`, unit `axis`, `half_angle`) to the
/// coaxial cone of the same half-angle whose apex is `other_apex`: positive when the other lies
/// outside it (away from the axis). Offsetting a cone by `d` along its outward normal moves its
/// apex by `−d / sin(half_angle)` along the axis.
pub fn cone_offset(apex: DVec3, axis: DVec3, half_angle: f64, other_apex: DVec3) -> f64 {
    (apex - other_apex).dot(axis) * half_angle.sin()
}

/// Whether two surfaces, one of them a cone, continue each other smoothly: the same cone, or a
/// plane through the cone's apex whose normal makes the angle `π/2 − half_angle` with its axis
/// (tangent along a generator). A cone never continues a cylinder.
fn cone_tangent_to(one: &SheetSurface, other: &SheetSurface) -> bool {
    match (*one, *other) {
        (
            SheetSurface::Cone {
                apex,
                axis,
                half_angle,
            },
            SheetSurface::Cone {
                apex: other_apex,
                axis: other_axis,
                half_angle: other_half_angle,
            },
        ) => {
            apex.distance(other_apex) <= LENGTH_TOLERANCE_MM
                && 1.0 - axis.dot(other_axis) <= DIRECTION_TOLERANCE
                && same_angle(half_angle, other_half_angle)
        }
        (
            SheetSurface::Cone {
                apex,
                axis,
                half_angle,
            },
            SheetSurface::Plane { origin, normal },
        )
        | (
            SheetSurface::Plane { origin, normal },
            SheetSurface::Cone {
                apex,
                axis,
                half_angle,
            },
        ) => {
            (normal.dot(axis).abs() - half_angle.sin()).abs() <= DIRECTION_TOLERANCE
                && (apex - origin).dot(normal).abs() <= LENGTH_TOLERANCE_MM
        }
        _ => false,
    }
}

/// Whether two axes are the same line.
fn coaxial(origin: DVec3, axis: DVec3, other_origin: DVec3, other_axis: DVec3) -> bool {
    parallel(axis, other_axis)
        && distance_to_axis(other_origin, origin, axis) <= LENGTH_TOLERANCE_MM
}

/// Whether a plane is tangent to a cylinder: parallel to its axis, at its radius from it.
fn plane_tangent_to_cylinder(plane: &SheetSurface, cylinder: &SheetSurface) -> bool {
    let (
        SheetSurface::Plane {
            origin: plane_origin,
            normal,
        },
        SheetSurface::Cylinder {
            origin,
            axis,
            radius,
        },
    ) = (*plane, *cylinder)
    else {
        return false;
    };
    normal.dot(axis).abs() <= DIRECTION_TOLERANCE
        && same_length((origin - plane_origin).dot(normal).abs(), radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plane_at_the_radius_parallel_to_the_axis_is_tangent() {
        let cylinder = SheetSurface::Cylinder {
            origin: DVec3::ZERO,
            axis: DVec3::Z,
            radius: 2.0,
        };
        let tangent = SheetSurface::Plane {
            origin: DVec3::new(5.0, -2.0, 1.0),
            normal: DVec3::Y,
        };
        let through_axis = SheetSurface::Plane {
            origin: DVec3::ZERO,
            normal: DVec3::Y,
        };
        assert!(tangent.tangent_to(&cylinder) && cylinder.tangent_to(&tangent));
        assert!(!through_axis.tangent_to(&cylinder));
    }

    #[test]
    fn opposite_faces_give_the_thickness() {
        let inner = SheetSurface::Cylinder {
            origin: DVec3::ZERO,
            axis: DVec3::Z,
            radius: 2.0,
        };
        let outer = SheetSurface::Cylinder {
            origin: DVec3::new(0.0, 0.0, 7.0),
            axis: -DVec3::Z,
            radius: 3.5,
        };
        assert_eq!(inner.opposite_distance(&outer), Some(1.5));
        let top = SheetSurface::Plane {
            origin: DVec3::new(1.0, 1.0, 2.0),
            normal: DVec3::Z,
        };
        let bottom = SheetSurface::Plane {
            origin: DVec3::ZERO,
            normal: -DVec3::Z,
        };
        assert_eq!(top.opposite_distance(&bottom), Some(2.0));
        assert_eq!(top.opposite_distance(&inner), None);
    }
}
