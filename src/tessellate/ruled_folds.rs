//! Fold polylines on ruled surfaces, carried along the rulings so that the mesh stays exactly
//! developable.
//!
//! Input: a ruled surface's [`Rulings`], its [`SurfaceDomain`], fold polylines in that domain
//! and which of its two sections are welded to another surface. Output: the rulings with a ruling
//! added through every polyline vertex (and every crossing of two polylines) that is on none, and
//! the [`RulingFolds`] that [`super::ruled::mesh_rulings`] makes into vertices and edges: the
//! point where each polyline crosses each ruling, and the polyline's segments between
//! consecutive rulings. Every vertex stays on a ruling and every triangle between two consecutive
//! rulings, which is what makes the mesh of a developable surface exactly developable.
//!
//! The caller samples a cylinder's, a cone's or an extrusion's sections through the polylines'
//! vertices first ([`super::ruled::rulings_through`]: exact rulings of the surface, the rulings
//! next to them respaced), so on those a vertex is on a ruling already. Otherwise (a loft, or a
//! welded section kept as it is) a ruling is added inside the wedge (the planar piece between two consecutive rulings) that
//! holds the point: from the point of the wedge's bottom side at the point's fraction across the
//! wedge, through the point, to the top side (from the apex when the wedge is a fan's triangle).
//! It splits the planar wedge into two planar wedges. Where a polyline crosses a ruling is found
//! by bisection along the ruling in the domain (`v` is the local height, linear along a ruling;
//! `u` is constant along a cylinder's, a cone's or an extrusion's ruling and varies along a
//! loft's).
//!
//! `None` (the caller inserts the polylines by [`super::fold_insert`] instead) when a ruling
//! would be added with an end on a welded section (the neighbouring surface would not have that
//! point), when a polyline crosses a cone fan other than at the same fraction of each of its
//! rulings (a fan's mesh is laid out in rows across its rulings by [`super::fan`], which can put
//! a row along such a polyline: a section of a square-to-round at one height) or when a
//! polyline cannot be followed from ruling to ruling (it leaves a ruling's height range).

use glam::{DVec2, DVec3};

use super::crossings::with_crossings;
use super::ruled::{FoldSegment, RulingFolds, fan_wedges};
use crate::cad::{Rulings, SurfaceDomain};
use crate::geometry::tolerance::{SAME_POINT_RATIO, SAME_STATION_RATIO};

/// Bisection steps (the interval halves each time: far below round-off after 64).
const BISECTION_STEPS: usize = 64;

/// The rulings with rulings added through the polylines' vertices, and the folds along them (see
/// the module documentation). `welded` is `[bottom, top]`: whether that section shares its
/// points with another surface. A polyline vertex within `snap` (part units: the chord
/// tolerance) of a ruling is moved onto it rather than given a ruling of its own next to it.
pub fn fold_rulings(
    rulings: &Rulings,
    domain: &SurfaceDomain,
    folds: &[(u32, Vec<DVec2>)],
    welded: [bool; 2],
    mesh_size: f64,
    snap: f64,
) -> Option<(Rulings, RulingFolds)> {
    let tolerance = SAME_POINT_RATIO * mesh_size;
    let polylines = with_crossings(folds);
    let mut rulings = rulings.clone();
    for (_, points) in &polylines {
        for &point in points {
            if let Place::Inside(wedge, fraction) = place(&rulings, domain, point, tolerance, snap)?
            {
                add_ruling(&mut rulings, domain, wedge, fraction, point.y, welded)?;
            }
        }
    }
    let fan = fan_wedges(&rulings);
    let mut folds = RulingFolds {
        stations: vec![Vec::new(); rulings.pairs.len()],
        segments: Vec::new(),
    };
    for (line, points) in &polylines {
        let mut chain = Vec::new();
        for pair in points.windows(2) {
            let from = on_ruling(&rulings, domain, pair[0], tolerance, snap)?;
            let to = on_ruling(&rulings, domain, pair[1], tolerance, snap)?;
            chain.push(from);
            let step = if to.0 > from.0 { 1 } else { usize::MAX };
            let mut ruling = from.0;
            while ruling != to.0 {
                ruling = ruling.wrapping_add(step);
                if ruling == to.0 {
                    break;
                }
                chain.push((ruling, crossing(&rulings, domain, ruling, pair)?));
            }
            chain.push(to);
        }
        chain.dedup_by(|a, b| a.0 == b.0 && (a.1 - b.1).abs() * length(&rulings, a.0) <= tolerance);
        for pair in chain.windows(2) {
            let (from, to) = if pair[1].0 < pair[0].0 {
                (pair[1], pair[0])
            } else {
                (pair[0], pair[1])
            };
            // Across a fan, a fold must follow one of its rows.
            if to.0 > from.0
                && fan[from.0]
                && (to.1 - from.1).abs() * length(&rulings, from.0) > tolerance
            {
                return None;
            }
            folds.segments.push(FoldSegment {
                line: *line,
                from,
                to,
            });
        }
        for &(ruling, fraction) in &chain {
            folds.stations[ruling].push(fraction);
        }
    }
    for (ruling, stations) in folds.stations.iter_mut().enumerate() {
        let length = length(&rulings, ruling);
        stations.sort_by(f64::total_cmp);
        stations.dedup_by(|a, b| (*a - *b).abs() * length <= tolerance);
    }
    fans_cut_along_rows(&rulings, &folds, &fan, tolerance).then_some((rulings, folds))
}

/// Whether every cone fan has the same fold stations (fractions inside its rulings) on each of
/// its rulings: [`super::fan`] can then lay a row of its mesh along each of them.
fn fans_cut_along_rows(
    rulings: &Rulings,
    folds: &RulingFolds,
    fan: &[bool],
    tolerance: f64,
) -> bool {
    let inner = |ruling: usize| -> Vec<f64> {
        folds.stations[ruling]
            .iter()
            .copied()
            .filter(|&f| f > 0.0 && f < 1.0)
            .collect()
    };
    (0..fan.len()).filter(|&w| fan[w]).all(|w| {
        let (left, right) = (inner(w), inner(w + 1));
        let scale = length(rulings, w).max(length(rulings, w + 1));
        left.len() == right.len()
            && left
                .iter()
                .zip(&right)
                .all(|(a, b)| (a - b).abs() * scale <= tolerance)
    })
}

/// Where a domain point is among the rulings.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    /// On ruling `.0`, at fraction `.1` along it.
    On(usize, f64),
    /// Inside wedge `.0` (between rulings `.0` and `.0 + 1`), at fraction `.1` across it.
    Inside(usize, f64),
}

/// A ruling's end points.
fn ends(rulings: &Rulings, ruling: usize) -> [DVec3; 2] {
    let [b, t] = rulings.pairs[ruling];
    [rulings.bottom[b], rulings.top[t]]
}

fn length(rulings: &Rulings, ruling: usize) -> f64 {
    let [b, t] = ends(rulings, ruling);
    b.distance(t)
}

/// The fraction along `ruling` at local height `v` (clamped to the ruling).
fn fraction_at_height(domain: &SurfaceDomain, [b, t]: [DVec3; 2], v: f64) -> f64 {
    let (low, high) = (domain.parameters(b).1, domain.parameters(t).1);
    ((v - low) / (high - low)).clamp(0.0, 1.0)
}

/// `u` of a surface point, unwrapped near `reference` when `u` is periodic.
fn u_near(domain: &SurfaceDomain, point: DVec3, reference: f64) -> f64 {
    let u = domain.parameters(point).0.unwrap_or(reference);
    match domain.period() {
        Some((_, period)) => {
            reference + (u - reference + period / 2.0).rem_euclid(period) - period / 2.0
        }
        None => u,
    }
}

/// `u` at the middle of each ruling, increasing along the rulings (a periodic `u` unwrapped,
/// starting within half a period above the domain's start).
fn ruling_references(rulings: &Rulings, domain: &SurfaceDomain) -> Vec<f64> {
    let start = domain
        .period()
        .map_or(0.0, |(start, period)| start + period / 2.0);
    let mut references: Vec<f64> = Vec::with_capacity(rulings.pairs.len());
    for ruling in 0..rulings.pairs.len() {
        let [b, t] = ends(rulings, ruling);
        let middle = b.lerp(t, 0.5);
        let u = match (references.last(), domain.period()) {
            (Some(&previous), Some((_, period))) => {
                let raw = u_near(domain, middle, previous);
                if raw < previous { raw + period } else { raw }
            }
            (None, _) => u_near(domain, middle, start),
            (Some(_), None) => u_near(domain, middle, 0.0),
        };
        references.push(u);
    }
    references
}

/// The point of `ruling` at local height `v` and its `u` near `reference`.
fn at_height(
    rulings: &Rulings,
    domain: &SurfaceDomain,
    ruling: usize,
    v: f64,
    reference: f64,
) -> (DVec3, f64, f64) {
    let [b, t] = ends(rulings, ruling);
    let fraction = fraction_at_height(domain, [b, t], v);
    let point = b.lerp(t, fraction);
    (point, u_near(domain, point, reference), fraction)
}

/// Where the domain point `point` is among the rulings (on one when within `snap` of it); `None`
/// when it is outside them.
fn place(
    rulings: &Rulings,
    domain: &SurfaceDomain,
    point: DVec2,
    tolerance: f64,
    snap: f64,
) -> Option<Place> {
    let references = ruling_references(rulings, domain);
    let (u, v) = (point.x, point.y);
    let samples: Vec<(DVec3, f64, f64)> = (0..rulings.pairs.len())
        .map(|k| at_height(rulings, domain, k, v, references[k]))
        .collect();
    // The domain's `u` of the point, unwrapped like the rulings'.
    let u = match domain.period() {
        Some((_, period)) if u > samples[samples.len() - 1].1 + tolerance => u - period,
        Some((_, period)) if u < samples[0].1 - tolerance => u + period,
        _ => u,
    };
    let scale = 1.0 + u.abs();
    let close = |k: usize| (samples[k].1 - u).abs() <= SAME_STATION_RATIO * scale;
    if let Some(k) = (0..samples.len()).find(|&k| close(k)) {
        return Some(Place::On(k, samples[k].2));
    }
    let wedge = (0..samples.len() - 1).find(|&k| samples[k].1 < u && u < samples[k + 1].1)?;
    let (p, q) = (samples[wedge].0, samples[wedge + 1].0);
    let (mut low, mut high) = (0.0, 1.0);
    for _ in 0..BISECTION_STEPS {
        let middle = 0.5 * (low + high);
        if u_near(domain, p.lerp(q, middle), u) < u {
            low = middle;
        } else {
            high = middle;
        }
    }
    let fraction = 0.5 * (low + high);
    let (width, snap) = (p.distance(q), snap.max(tolerance));
    if fraction * width <= snap {
        Some(Place::On(wedge, samples[wedge].2))
    } else if (1.0 - fraction) * width <= snap {
        Some(Place::On(wedge + 1, samples[wedge + 1].2))
    } else {
        Some(Place::Inside(wedge, fraction))
    }
}

/// The ruling and fraction of a domain point that lies on a ruling.
fn on_ruling(
    rulings: &Rulings,
    domain: &SurfaceDomain,
    point: DVec2,
    tolerance: f64,
    snap: f64,
) -> Option<(usize, f64)> {
    match place(rulings, domain, point, tolerance, snap)? {
        Place::On(ruling, fraction) => Some((ruling, fraction)),
        Place::Inside(..) => None,
    }
}

/// Adds the ruling through the point at `fraction` across `wedge` at local height `v`: from the
/// bottom side at that fraction (or the wedge's apex) through the point to the top side. `None`
/// when it would add a point on a welded section.
fn add_ruling(
    rulings: &mut Rulings,
    domain: &SurfaceDomain,
    wedge: usize,
    fraction: f64,
    v: f64,
    welded: [bool; 2],
) -> Option<()> {
    let ([b0, t0], [b1, t1]) = (rulings.pairs[wedge], rulings.pairs[wedge + 1]);
    let (left, right) = (ends(rulings, wedge), ends(rulings, wedge + 1));
    let point_on = |[b, t]: [DVec3; 2]| b.lerp(t, fraction_at_height(domain, [b, t], v));
    let point = point_on(left).lerp(point_on(right), fraction);
    let bottom_apex = b0 == b1;
    let top_apex = t0 == t1;
    if (welded[0] && !bottom_apex) || (welded[1] && !top_apex) {
        return None;
    }
    // The line through the point along the interpolated ruling direction: where the sections
    // are at the same height along both rulings, it joins the points at `fraction` across both
    // sides.
    let direction = (left[1] - left[0]).lerp(right[1] - right[0], fraction);
    let bottom = if bottom_apex {
        left[0]
    } else {
        line_meets_side(point, direction, [left[0], right[0]])
    };
    let top = if top_apex {
        left[1]
    } else {
        line_meets_side(point, direction, [left[1], right[1]])
    };
    let b = if bottom_apex {
        b0
    } else {
        rulings.bottom.insert(b0 + 1, bottom);
        b0 + 1
    };
    let t = if top_apex {
        t0
    } else {
        rulings.top.insert(t0 + 1, top);
        t0 + 1
    };
    for pair in &mut rulings.pairs[wedge + 1..] {
        pair[0] += usize::from(!bottom_apex);
        pair[1] += usize::from(!top_apex);
    }
    rulings.pairs.insert(wedge + 1, [b, t]);
    Some(())
}

/// The point of the segment `side` on the line through `point` along `direction` (least
/// squares, clamped to the segment).
fn line_meets_side(point: DVec3, direction: DVec3, side: [DVec3; 2]) -> DVec3 {
    let direction = direction.normalize_or_zero();
    let a = (side[0] - point).cross(direction);
    let c = (side[1] - side[0]).cross(direction);
    let t = if c.length_squared() > 0.0 {
        (-a.dot(c) / c.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    side[0].lerp(side[1], t)
}

/// The fraction along `ruling` where the domain segment `segment` crosses it; `None` when it
/// does not within the ruling.
fn crossing(
    rulings: &Rulings,
    domain: &SurfaceDomain,
    ruling: usize,
    segment: &[DVec2],
) -> Option<f64> {
    let [b, t] = ends(rulings, ruling);
    let (p, q) = (segment[0], segment[1]);
    let reference = ruling_references(rulings, domain)[ruling];
    let side = |fraction: f64| {
        let point = b.lerp(t, fraction);
        let here = DVec2::new(u_near(domain, point, reference), domain.parameters(point).1);
        (q - p).perp_dot(here - p)
    };
    let (mut low, mut high) = (0.0, 1.0);
    let low_side = side(low);
    if low_side * side(high) > 0.0 {
        return None;
    }
    for _ in 0..BISECTION_STEPS {
        let middle = 0.5 * (low + high);
        if side(middle) * low_side > 0.0 {
            low = middle;
        } else {
            high = middle;
        }
    }
    Some(0.5 * (low + high))
}
