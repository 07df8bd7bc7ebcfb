//! Building a part's surfaces from their spec: every field checked (positive radii, rectangular
//! control grids, simple trim loops, ...) and converted once into the tessellator's
//! [`Surface`]s; B-spline and NURBS patches become truck-geometry surfaces.
//!
//! Input: a [`SurfaceSpec`] as parsed. Output: the [`Surface`], or the first [`SpecDefect`]
//! naming the field relative to the surface's table. Lengths stay in the part's units; angles are
//! converted from degrees to radians.

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};
use truck_modeling::{BSplineSurface, KnotVec, Vector4};

use super::errors::SpecDefect;
use super::loops::{check_loops, polygon_area};
use super::spec::{
    BsplineSpec, ConeSpec, CylinderSpec, ExtrusionSpec, LoftSpec, PlacementSpec, PolygonSpec,
    ProfileSegmentSpec, RevolutionSpec, SectionShape, SectionSpec, SurfaceSpec, TrimSpec,
};
use crate::tessellate::surface::{
    Frame, PatchGeometry, PatchSurface, Profile, ProfileSegment, RevolutionSurface, RuledCircle,
    RuledSurface, Section, Surface,
};

/// Relative tolerance of geometric checks (planarity, arc end points), as a fraction of the
/// feature's size.
pub const GEOMETRY_TOLERANCE: f64 = 1e-6;
/// The largest mitre tilt accepted, degrees.
pub const MAXIMUM_CUT_DEGREES: f64 = 80.0;

pub(super) fn check(
    condition: bool,
    field: &str,
    message: impl Into<String>,
) -> Result<(), SpecDefect> {
    if condition {
        Ok(())
    } else {
        Err(SpecDefect::new(field, message))
    }
}

pub(super) fn positive(value: f64, field: &str) -> Result<(), SpecDefect> {
    check(
        value.is_finite() && value > 0.0,
        field,
        format!("must be a positive length, got {value}"),
    )
}

fn vector(v: [f64; 3]) -> DVec3 {
    DVec3::from_array(v)
}

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

/// A profile of lines and arcs, checked: no zero-length segment, arcs' ends on their circle.
fn build_profile(start: [f64; 2], segments: &[ProfileSegmentSpec]) -> Result<Profile, SpecDefect> {
    check(
        !segments.is_empty(),
        "profile",
        "needs at least one segment",
    )?;
    let mut from = DVec2::from_array(start);
    check(from.is_finite(), "start", "must be finite numbers")?;
    let size = segments
        .iter()
        .map(|s| DVec2::from_array(s.to).distance(from))
        .fold(0.0, f64::max);
    let mut built = Vec::with_capacity(segments.len());
    for (index, segment) in segments.iter().enumerate() {
        let field = format!("profile[{index}]");
        let to = DVec2::from_array(segment.to);
        let length = from.distance(to);
        check(
            to.is_finite() && length > GEOMETRY_TOLERANCE * size,
            &field,
            format!("the segment has (almost) zero length ({length}) or a non-finite end point"),
        )?;
        built.push(match segment.center {
            None => {
                check(segment.clockwise.is_none(), &field, "'clockwise' needs a 'center'")?;
                ProfileSegment::Line { to }
            }
            Some(center) => {
                let center = DVec2::from_array(center);
                let radius = from.distance(center);
                check(
                    radius > 0.0 && (to.distance(center) - radius).abs() <= GEOMETRY_TOLERANCE * radius.max(1.0),
                    &format!("{field}.center"),
                    format!(
                        "the arc's ends are {radius} and {} from its centre; they must be equally far",
                        to.distance(center)
                    ),
                )?;
                // The ends differ, so the shorter way turns by a non-zero angle in (-π, π].
                let mut sweep = (from - center).angle_to(to - center);
                check(
                    segment.clockwise.is_some()
                        || (sweep.abs() - PI).abs() > GEOMETRY_TOLERANCE,
                    &format!("{field}.clockwise"),
                    "the arc is a half circle, so it has no shorter way round: add clockwise = true or false",
                )?;
                match segment.clockwise {
                    Some(true) if sweep > 0.0 => sweep -= TAU,
                    Some(false) if sweep < 0.0 => sweep += TAU,
                    _ => {}
                }
                ProfileSegment::Arc { to, center, sweep }
            }
        });
        from = to;
    }
    let profile = Profile {
        start: DVec2::from_array(start),
        segments: built,
    };
    check_simple_profile(&profile)?;
    Ok(profile)
}

/// Pieces per arc when a profile is checked for crossing itself or the axis.
const PROFILE_CHECK_PIECES: usize = 64;

/// The profile as a polyline: its points, for each piece (between points `k` and `k + 1`) the
/// index of the segment it belongs to, and the geometry tolerance at the profile's size.
fn profile_polyline(profile: &Profile) -> (Vec<DVec2>, Vec<usize>, f64) {
    let mut points = vec![profile.start];
    let mut segment_of_piece = Vec::new();
    for (index, segment) in profile.segments.iter().enumerate() {
        let from = *points
            .last()
            .expect("the polyline starts with the profile's start");
        let single = Profile {
            start: from,
            segments: vec![*segment],
        };
        let sampled = match *segment {
            ProfileSegment::Line { to } => vec![from, to],
            ProfileSegment::Arc { .. } => {
                single.sample(single.length() / PROFILE_CHECK_PIECES as f64, f64::INFINITY)
            }
        };
        segment_of_piece.extend(std::iter::repeat_n(index, sampled.len() - 1));
        points.extend(&sampled[1..]);
    }
    let size = points
        .iter()
        .map(|p| p.distance(profile.start))
        .fold(0.0, f64::max);
    (points, segment_of_piece, GEOMETRY_TOLERANCE * size)
}

/// Checks that a profile neither crosses nor touches itself (a closed profile only at its start)
/// and never turns straight back over itself.
fn check_simple_profile(profile: &Profile) -> Result<(), SpecDefect> {
    let (points, segment_of_piece, tolerance) = profile_polyline(profile);
    let closed = profile.is_closed(tolerance);
    let pieces = points.len() - 1;
    let crossing = |i: usize, j: usize| {
        let adjacent = j == i + 1 || (closed && i == 0 && j == pieces - 1);
        let touching =
            segment_distance((points[i], points[i + 1]), (points[j], points[j + 1])) <= tolerance;
        let turns_back = j == i + 1 && {
            let (a, b) = (points[i + 1] - points[i], points[j + 1] - points[j]);
            a.dot(b) < 0.0 && a.perp_dot(b).abs() <= GEOMETRY_TOLERANCE * a.length() * b.length()
        };
        (!adjacent && touching) || turns_back
    };
    for i in 0..pieces {
        if let Some(j) = (i + 1..pieces).find(|&j| crossing(i, j)) {
            let (first, second) = (segment_of_piece[i], segment_of_piece[j]);
            let what = if first == second {
                format!("segment {first} runs back over itself")
            } else {
                format!("segments {first} and {second} cross or touch")
            };
            return Err(SpecDefect::new(
                "profile",
                format!("the profile crosses itself: {what}"),
            ));
        }
    }
    Ok(())
}

/// The distance between two line segments in the plane (0 when they cross).
fn segment_distance(a: (DVec2, DVec2), b: (DVec2, DVec2)) -> f64 {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let crosses = side(b.0, b.1, a.0) * side(b.0, b.1, a.1) < 0.0
        && side(a.0, a.1, b.0) * side(a.0, a.1, b.1) < 0.0;
    if crosses {
        return 0.0;
    }
    [
        point_segment_distance(a.0, b),
        point_segment_distance(a.1, b),
        point_segment_distance(b.0, a),
        point_segment_distance(b.1, a),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min)
}

fn point_segment_distance(point: DVec2, (from, to): (DVec2, DVec2)) -> f64 {
    let along = to - from;
    let t =
        ((point - from).dot(along) / along.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
    point.distance(from + along * t)
}

/// Checks that a revolution profile stays off the far side of the axis and meets the axis only
/// at its ends (a pole); a stretch on the axis, or a touch between the ends, would pinch the
/// surface to a point.
fn check_profile_off_axis(profile: &Profile) -> Result<(), SpecDefect> {
    let (points, segment_of_piece, tolerance) = profile_polyline(profile);
    let last = points.len() - 1;
    let on_axis = (1..last).find(|&k| points[k].x <= tolerance);
    let beyond = (0..=last).find(|&k| points[k].x < -tolerance);
    match (beyond, on_axis) {
        (Some(k), _) => Err(SpecDefect::new(
            format!("profile[{}]", segment_of_piece[k.min(last - 1)]),
            "the profile crosses the axis (a negative radius); keep every point at radius >= 0",
        )),
        (None, Some(k)) => Err(SpecDefect::new(
            format!("profile[{}]", segment_of_piece[k - 1]),
            "the profile meets the axis between its ends, where the surface would pinch to a point; \
             only its first and last points may lie on the axis (radius 0)",
        )),
        (None, None) => Ok(()),
    }
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
    (total - TAU).abs() < 1e-6
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

/// A clamped uniform knot vector on [0, 1] for `count` control points of `degree`.
fn clamped_uniform_knots(count: usize, degree: usize) -> Vec<f64> {
    let inner = count - degree;
    let mut knots = vec![0.0; degree + 1];
    knots.extend((1..inner).map(|k| k as f64 / inner as f64));
    knots.extend(std::iter::repeat_n(1.0, degree + 1));
    knots
}

fn check_knots(knots: &[f64], count: usize, degree: usize, field: &str) -> Result<(), SpecDefect> {
    check(
        knots.len() == count + degree + 1,
        field,
        format!(
            "needs {} knots ({count} control points + degree {degree} + 1), got {}",
            count + degree + 1,
            knots.len()
        ),
    )?;
    check(
        knots.windows(2).all(|w| w[0] <= w[1]) && knots.iter().all(|k| k.is_finite()),
        field,
        "knots must be finite and non-decreasing",
    )?;
    check(
        knots[degree] < knots[count],
        field,
        "the knots span no parameter range",
    )
}

fn build_bspline(spec: &BsplineSpec) -> Result<Surface, SpecDefect> {
    let rows = spec.control_points.len();
    let columns = spec.control_points.first().map_or(0, Vec::len);
    let [degree_u, degree_v] = spec.degree;
    check(
        degree_u >= 1 && degree_v >= 1,
        "degree",
        "degrees must be at least 1",
    )?;
    check(
        spec.control_points.iter().all(|row| row.len() == columns),
        "control_points",
        "the control grid is not rectangular: every row needs the same number of points",
    )?;
    check(
        rows > degree_u && columns > degree_v,
        "control_points",
        format!(
            "a degree [{degree_u}, {degree_v}] patch needs at least {} x {} control points, got {rows} x {columns}",
            degree_u + 1,
            degree_v + 1
        ),
    )?;
    let knots_u = spec
        .knots_u
        .clone()
        .unwrap_or_else(|| clamped_uniform_knots(rows, degree_u));
    let knots_v = spec
        .knots_v
        .clone()
        .unwrap_or_else(|| clamped_uniform_knots(columns, degree_v));
    check_knots(&knots_u, rows, degree_u, "knots_u")?;
    check_knots(&knots_v, columns, degree_v, "knots_v")?;
    let weights = match &spec.weights {
        Some(weights) => {
            check(
                weights.len() == rows && weights.iter().all(|row| row.len() == columns),
                "weights",
                format!("needs one weight per control point: {rows} rows of {columns}"),
            )?;
            check(
                weights.iter().flatten().all(|w| w.is_finite() && *w > 0.0),
                "weights",
                "weights must be positive",
            )?;
            weights.clone()
        }
        None => vec![vec![1.0; columns]; rows],
    };
    let homogeneous: Vec<Vec<Vector4>> = spec
        .control_points
        .iter()
        .zip(&weights)
        .map(|(row, row_weights)| {
            row.iter()
                .zip(row_weights)
                .map(|(p, &w)| Vector4::new(p[0] * w, p[1] * w, p[2] * w, w))
                .collect()
        })
        .collect();
    check(
        spec.control_points
            .iter()
            .flatten()
            .all(|p| p.iter().all(|c| c.is_finite())),
        "control_points",
        "coordinates must be finite",
    )?;
    let surface = BSplineSurface::try_new(
        (
            KnotVec::from(knots_u.clone()),
            KnotVec::from(knots_v.clone()),
        ),
        homogeneous,
    )
    .map_err(|e| SpecDefect::new("control_points", format!("not a valid B-spline patch: {e}")))?;
    let geometry = PatchGeometry::nurbs(surface);
    let domain_low = DVec2::new(knots_u[degree_u], knots_v[degree_v]);
    let domain_high = DVec2::new(knots_u[rows], knots_v[columns]);
    check_not_degenerate(&geometry, domain_low, domain_high)?;
    let (outer, holes) = build_trim(spec.trim.as_ref(), domain_low, domain_high)?;
    Ok(Surface::Patch(PatchSurface {
        geometry,
        outer,
        holes,
    }))
}

/// Samples of the parameter domain per side in the degeneracy check.
const DEGENERACY_SAMPLES: usize = 8;

fn check_not_degenerate(
    geometry: &PatchGeometry,
    low: DVec2,
    high: DVec2,
) -> Result<(), SpecDefect> {
    let samples: Vec<DVec2> = (0..=DEGENERACY_SAMPLES)
        .flat_map(|i| (0..=DEGENERACY_SAMPLES).map(move |j| DVec2::new(i as f64, j as f64)))
        .map(|t| low + (high - low) * (t / DEGENERACY_SAMPLES as f64))
        .collect();
    let size = samples
        .iter()
        .map(|&p| geometry.point(p).distance(geometry.point(low)))
        .fold(0.0, f64::max);
    let degenerate_samples = samples
        .iter()
        .filter(|&&p| {
            let (du, dv) = geometry.derivatives(p);
            let scale = (high - low).x * (high - low).y;
            let area_density = du.cross(dv).length() * scale;
            !area_density.is_finite() || area_density <= GEOMETRY_TOLERANCE * size * size
        })
        .count();
    check(
        size > 0.0 && degenerate_samples * 2 < samples.len(),
        "control_points",
        "the control grid is degenerate: the patch has (almost) no area",
    )
}

fn build_trim(
    trim: Option<&TrimSpec>,
    low: DVec2,
    high: DVec2,
) -> Result<(Vec<DVec2>, Vec<Vec<DVec2>>), SpecDefect> {
    let rectangle = vec![
        low,
        DVec2::new(high.x, low.y),
        high,
        DVec2::new(low.x, high.y),
    ];
    let Some(trim) = trim else {
        return Ok((rectangle, Vec::new()));
    };
    let to_points = |points: &[[f64; 2]]| -> Vec<DVec2> {
        points.iter().map(|&p| DVec2::from_array(p)).collect()
    };
    let outer = trim.outer.as_deref().map(to_points).unwrap_or(rectangle);
    let margin = GEOMETRY_TOLERANCE * (high - low).length();
    let in_domain = |p: &DVec2| p.cmpge(low - margin).all() && p.cmple(high + margin).all();
    check(
        outer.iter().all(in_domain),
        "trim.outer",
        format!(
            "must lie in the parameter domain [{}, {}] x [{}, {}]",
            low.x, high.x, low.y, high.y
        ),
    )?;
    let holes: Vec<Vec<DVec2>> = trim.holes.iter().map(|h| to_points(h)).collect();
    let outer = outer.iter().map(|p| p.clamp(low, high)).collect();
    check_loops(outer, holes, "trim.outer", "trim.holes")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamped_knots_have_the_right_length() {
        assert_eq!(
            clamped_uniform_knots(4, 3),
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
        );
        assert_eq!(clamped_uniform_knots(5, 2).len(), 8);
    }
}
