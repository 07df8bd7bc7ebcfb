//! Building a part's surfaces from their spec: every field checked (positive radii, convex
//! sections, planar polygons, ...) and converted once into the CAD model's [`Surface`]s (profiles
//! in `profile.rs`, B-spline and NURBS patches in `bspline.rs`).
//!
//! Input: a [`SurfaceSpec`] as parsed. Output: the [`Surface`], or the first [`SpecDefect`]
//! naming the field relative to the surface's table. Lengths stay in the part's units; angles are
//! converted from degrees to radians.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::bspline::build_bspline;
use super::checks::{check, positive, vector};
use super::errors::SpecDefect;
use super::loops::{check_loops, polygon_area};
use super::profile::{build_profile, check_profile_off_axis};
use super::spec::{
    ConeSpec, CylinderSpec, ExtrusionSpec, LoftSpec, PlacementSpec, PolygonSpec, RevolutionSpec,
    SectionShape, SectionSpec, SurfaceSpec,
};
use crate::cad::{
    Frame, PatchGeometry, PatchSurface, RevolutionSurface, RuledCircle, RuledSurface, Section,
    Surface,
};
use crate::geometry::tolerance::{GEOMETRY_TOLERANCE, TURNING_TOLERANCE};

/// The largest mitre tilt accepted, degrees.
pub const MAXIMUM_CUT_DEGREES: f64 = 80.0;

/// Builds one surface.
pub fn build_surface(spec: &SurfaceSpec) -> Result<Surface, SpecDefect> {
    match spec {
        SurfaceSpec::Polygon(polygon) => build_polygon(polygon),
        SurfaceSpec::Cylinder(cylinder) => build_cylinder(cylinder),
        SurfaceSpec::Cone(cone) => build_cone(cone),
        SurfaceSpec::Revolution(revolution) => build_revolution(revolution),
        SurfaceSpec::Bspline(patch) => build_bspline(patch),
        SurfaceSpec::Loft(loft) => build_loft(loft),
        SurfaceSpec::Extrusion(extrusion) => build_extrusion(extrusion),
    }
}

fn frame(placement: &PlacementSpec) -> Result<Frame, SpecDefect> {
    let finite = placement
        .origin
        .iter()
        .chain(&placement.axis)
        .chain(placement.reference.iter().flatten())
        .all(|c| c.is_finite());
    check(
        finite,
        "placement",
        "origin, axis and reference must be finite numbers",
    )?;
    let axis = vector(placement.axis);
    let reference = placement.reference.map(vector).unwrap_or_else(|| {
        if axis.normalize_or_zero().x.abs() > 0.9 {
            DVec3::Y
        } else {
            DVec3::X
        }
    });
    Frame::new(vector(placement.origin), axis, reference).ok_or_else(|| {
        SpecDefect::new(
            "placement",
            "the axis must be a non-zero vector and the reference must not be parallel to it",
        )
    })
}

fn angle_range(angles: [f64; 2]) -> Result<[f64; 2], SpecDefect> {
    let span = angles[1] - angles[0];
    check(
        angles.iter().all(|a| a.is_finite()) && span > 0.0 && span <= 360.0,
        "angles",
        format!(
            "must be [start, end] in degrees with 0 < end - start <= 360, got [{}, {}]",
            angles[0], angles[1]
        ),
    )?;
    Ok(angles.map(f64::to_radians))
}

fn build_cylinder(spec: &CylinderSpec) -> Result<Surface, SpecDefect> {
    positive(spec.radius, "radius")?;
    positive(spec.height, "height")?;
    for (value, field) in [(spec.bottom_cut, "bottom_cut"), (spec.top_cut, "top_cut")] {
        check(
            value.is_finite() && value.abs() <= MAXIMUM_CUT_DEGREES,
            field,
            format!(
                "must be a tilt between -{MAXIMUM_CUT_DEGREES} and {MAXIMUM_CUT_DEGREES} degrees, got {value}"
            ),
        )?;
    }
    let reach = spec.radius
        * (spec.bottom_cut.to_radians().tan().abs() + spec.top_cut.to_radians().tan().abs());
    check(
        reach < spec.height,
        "height",
        format!("the tilted ends meet: the height must exceed {reach} for these cuts"),
    )?;
    Ok(Surface::Ruled(RuledSurface::Circular {
        frame: frame(&spec.placement)?,
        bottom: RuledCircle {
            center: DVec3::ZERO,
            radius: spec.radius,
            tilt: spec.bottom_cut.to_radians(),
        },
        top: RuledCircle {
            center: DVec3::new(0.0, 0.0, spec.height),
            radius: spec.radius,
            tilt: spec.top_cut.to_radians(),
        },
        angles: angle_range(spec.angles)?,
    }))
}

fn build_cone(spec: &ConeSpec) -> Result<Surface, SpecDefect> {
    positive(spec.bottom_radius, "bottom_radius")?;
    positive(spec.top_radius, "top_radius")?;
    positive(spec.height, "height")?;
    check(
        spec.top_offset.iter().all(|v| v.is_finite()),
        "top_offset",
        "must be finite",
    )?;
    Ok(Surface::Ruled(RuledSurface::Circular {
        frame: frame(&spec.placement)?,
        bottom: RuledCircle {
            center: DVec3::ZERO,
            radius: spec.bottom_radius,
            tilt: 0.0,
        },
        top: RuledCircle {
            center: DVec3::new(spec.top_offset[0], spec.top_offset[1], spec.height),
            radius: spec.top_radius,
            tilt: 0.0,
        },
        angles: angle_range(spec.angles)?,
    }))
}

fn build_revolution(spec: &RevolutionSpec) -> Result<Surface, SpecDefect> {
    let profile = build_profile(spec.start, &spec.profile)?;
    check_profile_off_axis(&profile)?;
    Ok(Surface::Revolution(RevolutionSurface {
        frame: frame(&spec.placement)?,
        profile,
        angles: angle_range(spec.angles)?,
    }))
}

fn build_extrusion(spec: &ExtrusionSpec) -> Result<Surface, SpecDefect> {
    let direction = vector(spec.direction);
    check(
        direction.is_finite() && direction.z.abs() > 0.0,
        "direction",
        "must have a non-zero component along the local z axis (out of the profile's plane)",
    )?;
    Ok(Surface::Ruled(RuledSurface::Extrusion {
        frame: frame(&spec.placement)?,
        profile: build_profile(spec.start, &spec.profile)?,
        direction,
    }))
}

fn build_section(spec: &SectionSpec, field: &str) -> Result<Section, SpecDefect> {
    let center = DVec2::from_array(spec.center);
    check(
        center.is_finite(),
        &format!("{field}.center"),
        "must be finite numbers",
    )?;
    check(
        spec.z.is_finite(),
        &format!("{field}.z"),
        "must be a finite height",
    )?;
    let required = |value: Option<f64>, name: &str| -> Result<f64, SpecDefect> {
        let value = value.ok_or_else(|| {
            SpecDefect::new(
                format!("{field}.{name}"),
                format!("a {:?} section needs '{name}'", spec.shape).to_lowercase(),
            )
        })?;
        positive(value, &format!("{field}.{name}"))?;
        Ok(value)
    };
    Ok(match spec.shape {
        SectionShape::Circle => Section::Circle {
            center,
            radius: required(spec.diameter, "diameter")? / 2.0,
            z: spec.z,
        },
        SectionShape::Rectangle => {
            let half = DVec2::new(
                required(spec.width, "width")?,
                required(spec.depth, "depth")?,
            ) / 2.0;
            Section::Polygon {
                corners: vec![
                    center - half,
                    center + DVec2::new(half.x, -half.y),
                    center + half,
                    center + DVec2::new(-half.x, half.y),
                ],
                z: spec.z,
            }
        }
        SectionShape::Polygon => {
            let points = spec.points.as_ref().ok_or_else(|| {
                SpecDefect::new(
                    format!("{field}.points"),
                    "a polygon section needs 'points'",
                )
            })?;
            let corners: Vec<DVec2> = points
                .iter()
                .map(|&p| center + DVec2::from_array(p))
                .collect();
            check(
                is_strictly_convex(&corners),
                &format!("{field}.points"),
                "must be at least three corners of a convex polygon, counter-clockwise",
            )?;
            Section::Polygon { corners, z: spec.z }
        }
    })
}

fn is_strictly_convex(corners: &[DVec2]) -> bool {
    let count = corners.len();
    count >= 3
        && (0..count).all(|k| {
            let (a, b, c) = (
                corners[k],
                corners[(k + 1) % count],
                corners[(k + 2) % count],
            );
            (b - a).perp_dot(c - b) > 0.0
        })
        && polygon_area(corners) > 0.0
        && turning_once(corners)
}

/// True when the edge directions turn through one full turn (no winding twice).
fn turning_once(corners: &[DVec2]) -> bool {
    let count = corners.len();
    let total: f64 = (0..count)
        .map(|k| {
            let a = corners[(k + 1) % count] - corners[k];
            let b = corners[(k + 2) % count] - corners[(k + 1) % count];
            a.angle_to(b)
        })
        .sum();
    (total - TAU).abs() < TURNING_TOLERANCE
}

fn build_loft(spec: &LoftSpec) -> Result<Surface, SpecDefect> {
    let bottom = build_section(&spec.bottom, "bottom")?;
    let top = build_section(&spec.top, "top")?;
    check(
        (top.z() - bottom.z()).abs() > 0.0,
        "top.z",
        "the two sections must lie in different parallel planes (different z)",
    )?;
    check(spec.seam.is_finite(), "seam", "must be an angle in degrees")?;
    Ok(Surface::Ruled(RuledSurface::Loft {
        frame: frame(&spec.placement)?,
        bottom,
        top,
        seam: spec.seam.to_radians(),
    }))
}

fn build_polygon(spec: &PolygonSpec) -> Result<Surface, SpecDefect> {
    check(
        spec.points.len() >= 3,
        "points",
        "a polygon needs at least three points",
    )?;
    let points: Vec<DVec3> = spec.points.iter().map(|&p| vector(p)).collect();
    let normal = newell_normal(&points);
    check(
        normal.length() > 0.0,
        "points",
        "the points are collinear: the polygon has no area",
    )?;
    let frame = Frame::new(points[0], normal, points[1] - points[0])
        .or_else(|| Frame::new(points[0], normal, DVec3::X))
        .or_else(|| Frame::new(points[0], normal, DVec3::Y))
        .ok_or_else(|| SpecDefect::new("points", "the polygon has no plane"))?;
    let size = points
        .iter()
        .map(|p| p.distance(points[0]))
        .fold(0.0, f64::max);
    let to_plane = |points: &[DVec3], field: &str| -> Result<Vec<DVec2>, SpecDefect> {
        points
            .iter()
            .map(|&p| {
                let local = p - frame.origin;
                check(
                    local.dot(frame.z).abs() <= GEOMETRY_TOLERANCE * size,
                    field,
                    "the points must all lie on one plane",
                )?;
                Ok(DVec2::new(local.dot(frame.x), local.dot(frame.y)))
            })
            .collect()
    };
    let outer = to_plane(&points, "points")?;
    let holes = spec
        .holes
        .iter()
        .enumerate()
        .map(|(i, hole)| {
            let hole: Vec<DVec3> = hole.iter().map(|&p| vector(p)).collect();
            to_plane(&hole, &format!("holes[{i}]"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let (outer, holes) = check_loops(outer, holes, "points", "holes")?;
    Ok(Surface::Patch(PatchSurface {
        geometry: PatchGeometry::Plane(frame),
        outer,
        holes,
    }))
}

fn newell_normal(points: &[DVec3]) -> DVec3 {
    let count = points.len();
    (0..count)
        .map(|k| points[k].cross(points[(k + 1) % count]))
        .sum::<DVec3>()
}
