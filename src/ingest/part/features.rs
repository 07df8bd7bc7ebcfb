//! Fold lines and stiffness regions of a part file, checked and converted: a fold line is a
//! polyline in a surface's parameter domain or the edge two surfaces share; a region is a 3D box
//! or a polygon in a surface's parameter domain.

use glam::{DVec2, DVec3};

use super::checks::{check, positive};
use super::errors::SpecDefect;
use super::loops::polygon_area;
use super::spec::{FoldLineSpec, RegionSpec, SheetSideSpec};
use crate::cad::{
    DEFAULT_FOLD_STIFFNESS, FoldBend, FoldLineGeometry, FoldStiffness, ParameterRegion,
    PatchGeometry, RegionShape, SheetSide, StiffnessRegion, Surface, SurfaceDomain,
};

/// Builds a fold line's geometry and stiffness.
pub fn build_fold_line(
    spec: &FoldLineSpec,
    surfaces: &[Surface],
) -> Result<(FoldLineGeometry, FoldStiffness), SpecDefect> {
    let factor = spec.factor.unwrap_or(DEFAULT_FOLD_STIFFNESS);
    check(
        factor.is_finite() && factor > 0.0,
        "factor",
        format!("must be positive, got {factor}"),
    )?;
    if let Some(width) = spec.width {
        positive(width, "width")?;
    }
    let in_range = |index: usize, field: &str| {
        check(
            index < surfaces.len(),
            field,
            format!(
                "surface {index} does not exist (there are {} surfaces, numbered from 0)",
                surfaces.len()
            ),
        )
    };
    let geometry = match (&spec.between, spec.surface, &spec.points) {
        (Some(pair), None, None) => {
            in_range(pair[0], "between")?;
            in_range(pair[1], "between")?;
            check(
                pair[0] != pair[1],
                "between",
                "needs two different surfaces",
            )?;
            FoldLineGeometry::Between { surfaces: *pair }
        }
        (None, Some(surface), Some(points)) => {
            in_range(surface, "surface")?;
            check(
                points.len() >= 2,
                "points",
                "a fold polyline needs at least two points",
            )?;
            let points: Vec<DVec2> = points.iter().map(|&p| DVec2::from_array(p)).collect();
            check_on_surface(&points, &SurfaceDomain::new(&surfaces[surface]))?;
            FoldLineGeometry::OnSurface { surface, points }
        }
        _ => {
            return Err(SpecDefect::new(
                "between",
                "give either 'between = [a, b]' or 'surface' with 'points'",
            ));
        }
    };
    Ok((
        geometry,
        FoldStiffness {
            factor,
            width: spec.width,
        },
    ))
}

/// A fold line's bend, when it has a bend radius: only on the edge two polygons share, and only
/// in a part with a `thickness`.
pub fn build_fold_bend(
    spec: &FoldLineSpec,
    surfaces: &[Surface],
    thickness: Option<f64>,
) -> Result<Option<FoldBend>, SpecDefect> {
    let Some(inner_radius) = spec.bend_radius else {
        check(
            spec.side.is_none(),
            "side",
            "is only read with a bend_radius",
        )?;
        return Ok(None);
    };
    check(
        inner_radius.is_finite() && inner_radius >= 0.0,
        "bend_radius",
        format!("must be a length of 0 or more, got {inner_radius}"),
    )?;
    check(
        thickness.is_some(),
        "bend_radius",
        "a bend needs the part's `thickness`",
    )?;
    let Some(pair) = spec.between else {
        return Err(SpecDefect::new(
            "bend_radius",
            "a bend is the edge two polygons share: give 'between = [a, b]'",
        ));
    };
    for index in pair {
        let planar = matches!(
            &surfaces[index],
            Surface::Patch(patch) if matches!(patch.geometry, PatchGeometry::Plane(_))
        );
        check(
            planar,
            "bend_radius",
            format!("surface {index} is not a polygon: only folds between polygons are bent"),
        )?;
    }
    let side = match spec.side.unwrap_or(SheetSideSpec::Mid) {
        SheetSideSpec::Inside => SheetSide::Inside,
        SheetSideSpec::Mid => SheetSide::Mid,
        SheetSideSpec::Outside => SheetSide::Outside,
    };
    Ok(Some(FoldBend { inner_radius, side }))
}

/// Checks that a fold polyline stays on its surface: every point in the surface's parameter
/// domain, no segment leaving it or crossing a trim loop.
fn check_on_surface(points: &[DVec2], domain: &SurfaceDomain) -> Result<(), SpecDefect> {
    check(
        points.iter().all(|p| p.is_finite()),
        "points",
        "every point must be finite",
    )?;
    for (k, pair) in points.windows(2).enumerate() {
        if let Some(reason) = domain
            .segment_outside(pair[0], pair[1])
            .or_else(|| along_edge(domain, pair[0], pair[1]))
        {
            return Err(SpecDefect::new(
                "points",
                format!(
                    "the fold polyline leaves its surface between points {k} and {}: {reason}",
                    k + 1
                ),
            ));
        }
    }
    for (k, turn) in points.windows(3).enumerate() {
        let (a, b) = (turn[1] - turn[0], turn[2] - turn[1]);
        check(
            !(a.dot(b) < 0.0 && a.perp_dot(b).abs() <= EDGE_PROBE * a.length() * b.length()),
            "points",
            format!(
                "the fold polyline turns straight back over itself at point {}",
                k + 1
            ),
        )?;
    }
    Ok(())
}

/// The corners of a `parameter_box` `[u_min, v_min, u_max, v_max]`; on a periodic `u` (an angle,
/// a closed extrusion profile) `u_max < u_min` runs through the seam, to `u_max` plus a period.
fn box_polygon(corners: [f64; 4], domain: &SurfaceDomain) -> Result<Vec<DVec2>, SpecDefect> {
    let [u0, v0, mut u1, v1] = corners;
    check(
        v1 > v0,
        "parameter_box",
        format!("v_max ({v1}) must exceed v_min ({v0})"),
    )?;
    match domain.period() {
        Some((_, period)) if u1 < u0 => u1 += period,
        _ => check(
            u1 > u0,
            "parameter_box",
            format!("u_max ({u1}) must exceed u_min ({u0})"),
        )?,
    }
    Ok(vec![
        DVec2::new(u0, v0),
        DVec2::new(u1, v0),
        DVec2::new(u1, v1),
        DVec2::new(u0, v1),
    ])
}

/// Relative step of the probes that find a fold segment lying on the edge of its domain.
const EDGE_PROBE: f64 = 1e-6;

/// Why the segment `from`-`to` runs along the edge (a rim, a side or the seam) of a cylinder's,
/// cone's, loft's, revolution's or extrusion's domain, if it does: its midpoint has a point off
/// the domain within a relative [`EDGE_PROBE`] step. Such a fold would give the edge's triangles
/// no width. (Polygon and B-spline domains take folds on their boundary.)
fn along_edge(domain: &SurfaceDomain, from: DVec2, to: DVec2) -> Option<String> {
    if matches!(domain, SurfaceDomain::Patch(_)) {
        return None;
    }
    let middle = (from + to) / 2.0;
    let step = (DVec2::ONE + middle.abs() + DVec2::splat(from.distance(to))) * EDGE_PROBE;
    let probes = [DVec2::X, DVec2::NEG_X, DVec2::Y, DVec2::NEG_Y].map(|d| middle + d * step);
    probes
        .iter()
        .any(|&p| domain.outside(p).is_some())
        .then(|| {
            format!(
                "the segment from ({}, {}) to ({}, {}) runs along the surface's edge or seam; \
                 move it inside (a fold between two surfaces is given with 'between')",
                from.x, from.y, to.x, to.y
            )
        })
}

/// Builds a stiffness region.
pub fn build_region(
    spec: &RegionSpec,
    surfaces: &[Surface],
) -> Result<StiffnessRegion, SpecDefect> {
    check(
        spec.factor.is_finite() && spec.factor > 0.0,
        "factor",
        format!("must be positive, got {}", spec.factor),
    )?;
    let shape = match (
        spec.box_min,
        spec.box_max,
        spec.surface,
        &spec.polygon,
        spec.parameter_box,
    ) {
        (Some(min), Some(max), None, None, None) => {
            let (min, max) = (DVec3::from_array(min), DVec3::from_array(max));
            check(
                min.cmplt(max).all(),
                "box_max",
                "every coordinate must exceed box_min's",
            )?;
            RegionShape::Box { min, max }
        }
        (None, None, Some(surface), polygon, parameter_box)
            if polygon.is_some() != parameter_box.is_some() =>
        {
            let Some(surface_geometry) = surfaces.get(surface) else {
                return Err(SpecDefect::new(
                    "surface",
                    format!(
                        "surface {surface} does not exist (there are {} surfaces, numbered from 0)",
                        surfaces.len()
                    ),
                ));
            };
            let domain = SurfaceDomain::new(surface_geometry);
            let (polygon, field) = match (polygon, parameter_box) {
                (Some(points), _) => (
                    points.iter().map(|&p| DVec2::from_array(p)).collect(),
                    "polygon",
                ),
                (None, Some(corners)) => (box_polygon(corners, &domain)?, "parameter_box"),
                (None, None) => (Vec::new(), "polygon"),
            };
            check(
                polygon.iter().all(|p| p.is_finite()),
                field,
                "every coordinate must be finite",
            )?;
            check(
                polygon.len() >= 3 && polygon_area(&polygon).abs() > 0.0,
                field,
                "needs at least three points enclosing an area",
            )?;
            if let Some(reason) = ParameterRegion::new(domain, polygon.clone()).off_domain() {
                return Err(SpecDefect::new(field, reason));
            }
            RegionShape::Parameter { surface, polygon }
        }
        _ => {
            return Err(SpecDefect::new(
                "box_min",
                "give either 'box_min' and 'box_max', or 'surface' with 'polygon' or 'parameter_box'",
            ));
        }
    };
    Ok(StiffnessRegion {
        factor: spec.factor,
        shape,
    })
}
