//! B-spline and NURBS patches built from their spec: knots and control grids checked, the patch
//! not degenerate, its trim loops simple and inside its domain.

use glam::DVec2;
use truck_modeling::{BSplineSurface, KnotVec, Vector4};

use super::checks::check;
use super::errors::SpecDefect;
use super::loops::check_loops;
use super::spec::{BsplineSpec, TrimSpec};
use crate::cad::{PatchGeometry, PatchSurface, Surface};
use crate::geometry::tolerance::GEOMETRY_TOLERANCE;

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

pub fn build_bspline(spec: &BsplineSpec) -> Result<Surface, SpecDefect> {
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
    use crate::ingest::part::bspline::*;

    #[test]
    fn clamped_knots_have_the_right_length() {
        assert_eq!(
            clamped_uniform_knots(4, 3),
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
        );
        assert_eq!(clamped_uniform_knots(5, 2).len(), 8);
    }
}
