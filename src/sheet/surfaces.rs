//! The two surface kinds a sheet-metal solid is made of, planes and cylinders, and the relations
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

/// A face's surface, when it is a plane or a cylinder (world coordinates, mm).
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
    /// The surface of a face, or `None` when it is neither a plane nor a cylinder.
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
            _ => None,
        }
    }

    /// Whether `other` continues this surface smoothly across a shared edge: the same plane, the
    /// same cylinder, or a plane tangent to a cylinder (parallel to its axis at its radius).
    pub fn tangent_to(&self, other: &Self) -> bool {
        match (*self, *other) {
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
        }
    }

    /// The thickness between this surface and `other` when they can be the two sides of a sheet:
    /// parallel planes (their distance) or coaxial cylinders (the difference of their radii).
    pub fn opposite_distance(&self, other: &Self) -> Option<f64> {
        match (*self, *other) {
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
