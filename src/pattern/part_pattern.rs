//! A flattened part's pattern: what is cut, drawn and nested. Its flat outline and holes, fold
//! and cut lines on the flat pattern, its grain line and grain direction, and the per-vertex
//! energies (Eq. 1) of the pattern (and of the pattern before cutting) that the energy map shows.
//!
//! Input: a [`PatternSource`], the flattened part's model, flat positions and identity (the cut
//! model's edges that are cuts). Output: a [`Pattern`]. Contours fitted within the chord tolerance
//! and offset by the seam allowance come from [`super::contours::part_contours`].

use glam::{DVec2, DVec3};

use super::drawing::PartDrawing;
use super::energy::VertexEnergy;
use super::fold_polylines::fold_polylines;
use crate::flatten::grain::flat_grain;
use crate::flatten::outline::Outline;
use crate::flatten::stiffness::Stiffness;
use crate::geometry::{deep_interior_point, ring_sides};
use crate::mesh::FacetModel;
use crate::units::Units;

/// A facet model with its stiffness and flat positions.
#[derive(Debug, Clone, Copy)]
pub struct FlatShape<'a> {
    /// The facet model (after seams and cuts).
    pub model: &'a FacetModel,
    /// Its stiffness factors.
    pub stiffness: &'a Stiffness,
    /// One flat position per vertex of `model`, model units.
    pub positions: &'a [DVec2],
}

/// What the pattern stage takes of a flattened part.
#[derive(Debug, Clone, Copy)]
pub struct PatternSource<'a> {
    /// Part name.
    pub name: &'a str,
    /// Units of the coordinates.
    pub units: Units,
    /// How many copies to cut.
    pub quantity: u32,
    /// Material, printed on the label.
    pub material: Option<&'a str>,
    /// Grain direction in 3D, when the part has one.
    pub grain: Option<DVec3>,
    /// The cut model and its pattern.
    pub flat: FlatShape<'a>,
    /// The part before its first crest-line cut, when one was made.
    pub uncut: Option<FlatShape<'a>>,
    /// Edges of the cut model (indices into its edge list, ascending) that are sides of a
    /// crest-line cut.
    pub cut_edges: &'a [usize],
    /// The spring constant `C` the part was flattened with.
    pub spring_constant: f64,
}

/// A part's pattern.
#[derive(Debug, Clone, PartialEq)]
pub struct Pattern {
    /// The drawing: outline, holes, fold lines, grain line, name, quantity, material.
    pub drawing: PartDrawing,
    /// The grain direction in the drawing's frame, degrees counter-clockwise from x, when the
    /// part has a grain that shows in the pattern.
    pub grain_degrees: Option<f64>,
    /// Crest-line cuts on the flat pattern: both sides of every cut edge, each a two-point
    /// polyline.
    pub cut_lines: Vec<Vec<DVec2>>,
    /// Per-vertex energies of the pattern.
    pub energy: VertexEnergy,
    /// Per-vertex energies of the pattern before crest-line cutting, when the part was cut.
    pub uncut_energy: Option<VertexEnergy>,
}

/// The pattern of a flattened part.
pub fn part_pattern(source: &PatternSource<'_>) -> Pattern {
    let FlatShape {
        model, positions, ..
    } = source.flat;
    let outline = Outline::of_pattern(model, positions);
    let flat_direction = source
        .grain
        .and_then(|direction| flat_grain(model, positions, direction));
    let fold_lines = fold_polylines(model, positions);
    let grain = flat_direction
        .map(|direction| grain_line(&outline.outer, &outline.holes, &fold_lines, direction));
    let drawing = PartDrawing {
        name: source.name.to_owned(),
        units: source.units,
        quantity: source.quantity,
        material: source.material.map(str::to_owned),
        outer: outline.outer,
        holes: outline.holes,
        fold_lines,
        grain,
        bends: Vec::new(),
    };
    let cut_lines = source
        .cut_edges
        .iter()
        .map(|&edge| {
            let [a, b] = model.edges()[edge];
            vec![positions[a as usize], positions[b as usize]]
        })
        .collect();
    let energy_of = |shape: FlatShape<'_>| {
        VertexEnergy::new(
            shape.model,
            shape.stiffness,
            shape.positions,
            source.spring_constant,
        )
    };
    Pattern {
        drawing,
        grain_degrees: flat_direction.map(|flat| flat.y.atan2(flat.x).to_degrees()),
        cut_lines,
        energy: energy_of(source.flat),
        uncut_energy: source.uncut.map(energy_of),
    }
}

/// The grain line drawn on a pattern: along the unit `direction`, on the chord through a point
/// deep inside the material ([`deep_interior_point`]) that no outline, hole or fold line crosses,
/// centred on that chord and at most [`GRAIN_CHORD_FRACTION`] of it long, and at most half as
/// long as the outer contour's extent along `direction`: on the material, clear of the lines
/// that are cut or folded.
fn grain_line(
    outer: &[DVec2],
    holes: &[Vec<DVec2>],
    fold_lines: &[Vec<DVec2>],
    direction: DVec2,
) -> [DVec2; 2] {
    let (first, last) = outer
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            let along = p.dot(direction);
            (a.min(along), b.max(along))
        });
    let deep = deep_interior_point(outer, holes);
    let rings = std::iter::once(outer)
        .chain(holes.iter().map(Vec::as_slice))
        .flat_map(ring_sides);
    let folds = fold_lines
        .iter()
        .flat_map(|line| line.windows(2).map(|pair| [pair[0], pair[1]]));
    let (mut behind, mut ahead) = (first - deep.dot(direction), last - deep.dot(direction));
    for [p, q] in rings.chain(folds) {
        if let Some(t) = line_crossing(deep, direction, p, q) {
            if t < 0.0 {
                behind = behind.max(t);
            } else {
                ahead = ahead.min(t);
            }
        }
    }
    let centre = deep + 0.5 * (behind + ahead) * direction;
    let half = (0.25 * (last - first)).min(0.5 * GRAIN_CHORD_FRACTION * (ahead - behind));
    [centre - half * direction, centre + half * direction]
}

/// The grain line takes at most this fraction of its free chord, leaving room at both ends.
const GRAIN_CHORD_FRACTION: f64 = 0.8;

/// Where the line `origin + t · direction` crosses the segment `p`–`q`: its `t`, or `None` when
/// it misses it or runs parallel to it.
fn line_crossing(origin: DVec2, direction: DVec2, p: DVec2, q: DVec2) -> Option<f64> {
    let side = q - p;
    let denominator = direction.perp_dot(side);
    if denominator.abs() <= f64::EPSILON * side.length() {
        return None;
    }
    let offset = p - origin;
    let s = offset.perp_dot(direction) / denominator;
    (0.0..=1.0)
        .contains(&s)
        .then(|| offset.perp_dot(side) / denominator)
}

#[cfg(test)]
mod tests {
    use crate::pattern::part_pattern::*;

    #[test]
    fn the_grain_line_keeps_to_the_material_between_fold_lines_and_holes() {
        let outer = vec![
            DVec2::ZERO,
            DVec2::new(100.0, 0.0),
            DVec2::new(100.0, 60.0),
            DVec2::new(0.0, 60.0),
        ];
        let fold = vec![vec![DVec2::new(40.0, 0.0), DVec2::new(40.0, 60.0)]];
        let [tail, head] = grain_line(&outer, &[], &fold, DVec2::X);
        let (low, high) = (tail.x.min(head.x), tail.x.max(head.x));
        let on_one_side = high < 40.0 || low > 40.0;
        assert!(on_one_side, "the grain line {tail} {head} crosses the fold");
        assert!(low > 0.0 && high < 100.0, "inside: {tail} {head}");
        assert!(
            (high - low - 32.0).abs() < 1e-9,
            "80 % of the 40 mm chord (half the 100 mm part does not fit): {tail} {head}"
        );
        // A hole across the middle: the line stays on one side of it.
        let hole = vec![vec![
            DVec2::new(45.0, 10.0),
            DVec2::new(55.0, 10.0),
            DVec2::new(55.0, 50.0),
            DVec2::new(45.0, 50.0),
        ]];
        let [tail, head] = grain_line(&outer, &hole, &[], DVec2::X);
        assert!(
            tail.x.max(head.x) <= 45.0
                || tail.x.min(head.x) >= 55.0
                || tail.y < 10.0
                || tail.y > 50.0
        );
    }
}
