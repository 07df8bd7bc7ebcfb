//! Where a part's label goes: a text box inside the part's material, clear of every line drawn
//! on it (the outline and holes that are cut, fold and bend lines, the grain arrow), turned
//! along the part when it does not fit level, and made smaller only when it fits nowhere at its
//! full height. The same rule places the label on a part's own drawing and on a nested sheet,
//! where the part may be turned.

use glam::DVec2;

use super::drawing::PartDrawing;
use crate::geometry::{
    bounding_box, crosses_ray, distance_to_box, distance_to_segment, inside,
    long_side_of_smallest_rectangle, refined_grid_search, ring_sides,
};

/// Grid points per side of the search for the label's centre, in each refinement.
const LABEL_GRID: usize = 12;

/// Refinements of the search around the best centre found.
const LABEL_REFINEMENTS: usize = 4;

/// The label box's clearance to the nearest line, as a fraction of its own half extents.
const LABEL_MARGIN: f64 = 0.2;

/// How much larger than the label's box (margin included) the room around it must be for the
/// label's place to be chosen by its distance to the lines alone.
const LABEL_ROOM: f64 = 2.0;

/// Centres where the label's box grows at least this fraction of the most it grows anywhere
/// are all good enough: the one farthest from the lines is taken.
const LABEL_TIE: f64 = 0.9;

/// Angles this close beyond ±90° count as ±90° when a text is turned upright (radians, 1°): a
/// text within a degree of straight down is turned to read upwards.
const UPRIGHT_SLACK: f64 = 0.017_453_292_519_943_295;

/// A label as placed: the centre of its text box, its direction and its text height, in
/// drawing units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LabelPlacement {
    /// Centre of the text box.
    pub centre: DVec2,
    /// Direction of the text's baseline, radians from +x, in (−90°, 90°] so it reads upright.
    pub angle: f64,
    /// Text height.
    pub height: f64,
    /// Whether the box is clear of every line at that height (false when no place on the part
    /// holds it even at `smallest` height: the label is then at its best place, at that height).
    pub clear: bool,
}

impl LabelPlacement {
    /// The baseline's start of a text `width` long (the insertion point of left-aligned text).
    pub fn insertion_point(&self, width: f64) -> DVec2 {
        let along = DVec2::from_angle(self.angle);
        self.centre - along * (0.5 * width) - along.perp() * (0.5 * self.height)
    }
}

impl PartDrawing {
    /// The placement of a label of `characters` characters, each `character_width` times the
    /// height wide, at most `largest` and at least `smallest` high: level if it fits there,
    /// else along the part's long side or across it, whichever holds the larger text (level
    /// first among equals), centred where it is farthest from every line in its own box's
    /// measure. `None` when the outer contour has fewer than three points.
    pub fn label_placement(
        &self,
        characters: usize,
        character_width: f64,
        (smallest, largest): (f64, f64),
    ) -> Option<LabelPlacement> {
        if self.outer.len() < 3 {
            return None;
        }
        let segments = Lines::new(self.drawn_segments());
        let aspect = (characters.max(1) as f64 * character_width).max(f64::MIN_POSITIVE);
        // The box of the largest text with its margin: a growth of 1 fits it exactly.
        let boxed = (1.0 + LABEL_MARGIN) * largest;
        let mut best: Option<(f64, DVec2, f64)> = None;
        for angle in self.label_angles() {
            let (centre, fit) = self.best_centre(&segments, angle, aspect * boxed, boxed);
            // A box larger than the largest text gains nothing: the first angle that holds the
            // largest text (or the largest fraction of it) wins.
            let score = fit.min(1.0);
            if best.is_none_or(|(known, _, _)| score > known + 1e-9) {
                best = Some((score, centre, angle));
            }
        }
        let (score, centre, angle) = best?;
        let height = largest * score;
        Some(LabelPlacement {
            centre,
            angle,
            height: height.max(smallest),
            clear: height >= smallest,
        })
    }

    /// The centre of a level label of this part's text, each character `character_width` times
    /// the height wide.
    pub(super) fn level_label_centre(&self, character_width: f64) -> DVec2 {
        let aspect = (self.label().chars().count().max(1) as f64 * character_width).max(1.0);
        self.best_centre(&Lines::new(self.drawn_segments()), 0.0, aspect, 1.0)
            .0
    }

    /// Every line drawn on the part, as segments: outline, holes, fold lines, bend lines with
    /// their zones' edges, grain.
    fn drawn_segments(&self) -> Vec<[DVec2; 2]> {
        let mut segments = Vec::new();
        for ring in std::iter::once(&self.outer).chain(&self.holes) {
            segments.extend(ring_sides(ring));
        }
        for line in &self.fold_lines {
            segments.extend(line.windows(2).map(|pair| [pair[0], pair[1]]));
        }
        for bend in &self.bends {
            segments.push(bend.line);
            segments.extend(bend.zone_edges());
        }
        if let Some(([tail, head], [left, tip, right])) = self.grain_arrow() {
            segments.extend([[tail, head], [left, tip], [tip, right]]);
        }
        segments
    }

    /// The directions tried, in order of preference: level, along the part's long side, across
    /// it (upright, without repeats).
    fn label_angles(&self) -> Vec<f64> {
        let mut angles = vec![0.0];
        if let Some(long) = long_side_of_smallest_rectangle(&self.outer) {
            for direction in [long, long.perp()] {
                // Upright: in (−90°, 90°], a direction a hair off straight down read upwards.
                let mut angle = direction.to_angle();
                if angle < -std::f64::consts::FRAC_PI_2 + UPRIGHT_SLACK {
                    angle += std::f64::consts::PI;
                } else if angle > std::f64::consts::FRAC_PI_2 + UPRIGHT_SLACK {
                    angle -= std::f64::consts::PI;
                }
                if angles
                    .iter()
                    .all(|known: &f64| (known - angle).abs() > 1e-6)
                {
                    angles.push(angle);
                }
            }
        }
        angles
    }

    /// The centre for a box of `width` × `height` turned by `angle`, and how much the box can
    /// grow there (scaled by it, it touches a line; 0 outside the material). Among the centres
    /// where the box grows [`LABEL_ROOM`] times, or [`LABEL_TIE`] of the most it grows anywhere,
    /// the one farthest from every line wins, so the label sits in the part's most open region.
    fn best_centre(&self, lines: &Lines, angle: f64, width: f64, height: f64) -> (DVec2, f64) {
        let along = DVec2::from_angle(angle);
        let half = DVec2::new(0.5 * width, 0.5 * height);
        // A point at distance d from the centre is at least d / |half| away in the box's measure.
        let diagonal = half.length();
        let hole_boxes: Vec<(DVec2, DVec2)> = self.holes.iter().map(|h| bounding_box(h)).collect();
        let outer = Lines::ring(&self.outer);
        let measure = |point: DVec2| -> Option<(f64, f64)> {
            let in_hole = self
                .holes
                .iter()
                .zip(&hole_boxes)
                .any(|(hole, &(low, high))| {
                    point.cmpge(low).all() && point.cmple(high).all() && inside(point, hole)
                });
            (outer.encloses(point) && !in_hole).then(|| {
                let frame = |p: DVec2| {
                    let d = p - point;
                    DVec2::new(d.dot(along) / half.x, d.dot(along.perp()) / half.y)
                };
                // Nearest runs first, so that the far ones are skipped (the minima do not
                // depend on the order).
                let mut runs: Vec<(f64, &Chunk)> = (lines.chunks.iter())
                    .map(|chunk| (distance_to_box(point, chunk.low, chunk.high), chunk))
                    .collect();
                runs.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
                let (mut growth, mut clearance) = (f64::INFINITY, f64::INFINITY);
                for (near, chunk) in runs {
                    if near >= clearance && near / diagonal >= growth {
                        break;
                    }
                    for &[p, q] in &chunk.segments {
                        growth = growth.min(chebyshev_distance_to_segment(frame(p), frame(q)));
                        clearance = clearance.min(distance_to_segment(point, p, q));
                    }
                }
                (growth, clearance)
            })
        };
        // First the most the box can grow anywhere, then, among the centres where it grows
        // nearly as much (capped at the room wanted), the one farthest from every line.
        let (_, (most, _)) = self.grid_search(&measure, |(growth, _)| (growth, 0.0));
        // (Never less than full size where full size fits.)
        let enough = LABEL_ROOM.min((LABEL_TIE * most).max(most.min(1.0)));
        let (centre, (growth, _)) = self.grid_search(&measure, |(growth, clearance)| {
            (growth.min(enough), clearance)
        });
        (centre, growth)
    }

    /// The point of the part's bounding box of highest `rank` of its `measure` (`None` outside
    /// the material), by [`refined_grid_search`]; the box's centre, measured nil, when no point
    /// is in the material.
    fn grid_search(
        &self,
        measure: &impl Fn(DVec2) -> Option<(f64, f64)>,
        rank: impl Fn((f64, f64)) -> (f64, f64),
    ) -> (DVec2, (f64, f64)) {
        let (low, high) = bounding_box(&self.outer);
        refined_grid_search(
            (low, high),
            LABEL_GRID,
            LABEL_REFINEMENTS,
            |point, best: Option<((f64, f64), (f64, f64))>| {
                let found = measure(point)?;
                let ranked = rank(found);
                best.is_none_or(|(_, known)| ranked > known)
                    .then_some((found, ranked))
            },
        )
        .map_or((0.5 * (low + high), (0.0, 0.0)), |(point, (found, _))| {
            (point, found)
        })
    }
}

/// The drawn lines in runs of consecutive segments, each with its bounding box, so that a
/// search can skip the runs farther than the nearest line found.
struct Lines {
    chunks: Vec<Chunk>,
}

struct Chunk {
    low: DVec2,
    high: DVec2,
    segments: Vec<[DVec2; 2]>,
}

/// Segments per run of [`Lines`].
const CHUNK_SEGMENTS: usize = 32;

impl Lines {
    /// The closed ring's sides.
    fn ring(ring: &[DVec2]) -> Self {
        Self::new(ring_sides(ring).collect())
    }

    /// Whether `point` is inside the ring these lines are the sides of ([`Self::ring`]), as
    /// [`inside`] decides it: the crossings of a ray towards +x counted only in the runs whose
    /// height spans the point's (a side wholly above or wholly at or below it crosses nothing).
    fn encloses(&self, point: DVec2) -> bool {
        let crossings: usize = (self.chunks.iter())
            .filter(|chunk| chunk.low.y <= point.y && point.y < chunk.high.y)
            .map(|chunk| {
                (chunk.segments.iter())
                    .filter(|&&[p, q]| crosses_ray(point, p, q))
                    .count()
            })
            .sum();
        crossings % 2 == 1
    }

    fn new(segments: Vec<[DVec2; 2]>) -> Self {
        let chunks = segments
            .chunks(CHUNK_SEGMENTS)
            .map(|run| {
                let points: Vec<DVec2> = run.iter().flatten().copied().collect();
                let (low, high) = bounding_box(&points);
                Chunk {
                    low,
                    high,
                    segments: run.to_vec(),
                }
            })
            .collect();
        Self { chunks }
    }
}

/// The distance from the origin to the segment `p`–`q` in the maximum norm: the half side of
/// the largest axis-aligned square centred on the origin that the segment does not enter.
fn chebyshev_distance_to_segment(p: DVec2, q: DVec2) -> f64 {
    let d = q - p;
    let norm = |t: f64| {
        let point = p + d * t;
        point.x.abs().max(point.y.abs())
    };
    // The norm along the segment is convex and piecewise linear: its minimum is at an end, where
    // a coordinate is zero, or where the two coordinates are equal in size.
    let breaks = [
        -p.x / d.x,
        -p.y / d.y,
        (p.y - p.x) / (d.x - d.y),
        -(p.x + p.y) / (d.x + d.y),
    ];
    breaks
        .into_iter()
        .filter(|t| t.is_finite())
        .map(|t| t.clamp(0.0, 1.0))
        .chain([0.0, 1.0])
        .map(norm)
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use crate::pattern::label::*;

    fn rectangle(width: f64, height: f64) -> PartDrawing {
        PartDrawing {
            name: "part".into(),
            quantity: 1,
            outer: vec![
                DVec2::ZERO,
                DVec2::new(width, 0.0),
                DVec2::new(width, height),
                DVec2::new(0.0, height),
            ],
            ..PartDrawing::default()
        }
    }

    /// Whether the text box of `placement` for `characters` lies inside the drawing, off every
    /// drawn segment (checked on a fine grid of its points).
    fn box_is_clear(drawing: &PartDrawing, placement: &LabelPlacement, characters: usize) -> bool {
        let along = DVec2::from_angle(placement.angle);
        let (width, height) = (characters as f64 * 0.6 * placement.height, placement.height);
        let segments = drawing.drawn_segments();
        (0..=40).all(|i| {
            (0..=10).all(|j| {
                let point = placement.centre
                    + along * width * (i as f64 / 40.0 - 0.5)
                    + along.perp() * height * (j as f64 / 10.0 - 0.5);
                inside(point, &drawing.outer)
                    && segments
                        .iter()
                        .all(|&[p, q]| crate::geometry::distance_to_segment(point, p, q) > 1e-9)
            })
        })
    }

    #[test]
    fn the_maximum_norm_distance_to_a_segment() {
        let distance = chebyshev_distance_to_segment;
        assert_eq!(distance(DVec2::new(2.0, -5.0), DVec2::new(2.0, 5.0)), 2.0);
        assert_eq!(distance(DVec2::new(-5.0, 3.0), DVec2::new(5.0, 3.0)), 3.0);
        // The diagonal x + y = 4 comes nearest at (2, 2).
        assert_eq!(distance(DVec2::new(4.0, 0.0), DVec2::new(0.0, 4.0)), 2.0);
        assert_eq!(distance(DVec2::new(3.0, 3.0), DVec2::new(4.0, 5.0)), 3.0);
    }

    #[test]
    fn a_ring_encloses_the_points_inside_finds_in_it() {
        // A star of 150 points (several runs of sides), probed on a grid that hits its vertices'
        // heights exactly.
        let star: Vec<DVec2> = (0..150)
            .map(|k| {
                let angle = k as f64 * std::f64::consts::TAU / 150.0;
                DVec2::from_angle(angle) * if k % 2 == 0 { 10.0 } else { 4.0 }
            })
            .collect();
        let ring = Lines::ring(&star);
        let mut enclosed = 0;
        for i in -60..=60 {
            for j in -60..=60 {
                let point = DVec2::new(i as f64, j as f64) / 5.0;
                assert_eq!(ring.encloses(point), inside(point, &star), "{point}");
                enclosed += usize::from(inside(point, &star));
            }
        }
        assert!(enclosed > 1000, "{enclosed}");
    }

    #[test]
    fn a_wide_part_has_its_label_level_and_full_size() {
        let drawing = rectangle(200.0, 50.0);
        let placement = drawing
            .label_placement(8, 0.6, (2.0, 10.0))
            .expect("placed");
        assert_eq!(placement.angle, 0.0);
        assert_eq!(placement.height, 10.0);
        assert!(placement.clear && box_is_clear(&drawing, &placement, 8));
    }

    #[test]
    fn a_tall_narrow_part_has_its_label_along_it() {
        let drawing = rectangle(20.0, 300.0);
        let placement = drawing
            .label_placement(12, 0.6, (2.0, 10.0))
            .expect("placed");
        assert!(
            (placement.angle.abs() - std::f64::consts::FRAC_PI_2).abs() < 1e-9,
            "{placement:?}"
        );
        assert_eq!(placement.height, 10.0);
        assert!(box_is_clear(&drawing, &placement, 12), "{placement:?}");
    }

    #[test]
    fn a_part_nested_at_an_angle_has_its_label_along_it_and_clear() {
        let turn = DVec2::from_angle(37f64.to_radians());
        let mut drawing = rectangle(30.0, 260.0);
        drawing.fold_lines = vec![vec![DVec2::new(0.0, 130.0), DVec2::new(30.0, 130.0)]];
        for ring in [&mut drawing.outer] {
            for p in ring.iter_mut() {
                *p = turn.rotate(*p) + DVec2::new(500.0, 20.0);
            }
        }
        for p in drawing.fold_lines[0].iter_mut() {
            *p = turn.rotate(*p) + DVec2::new(500.0, 20.0);
        }
        let placement = drawing
            .label_placement(14, 0.6, (2.0, 10.0))
            .expect("placed");
        let along_part = turn.rotate(DVec2::Y);
        assert!(
            DVec2::from_angle(placement.angle).dot(along_part).abs() > 1.0 - 1e-9,
            "{placement:?}"
        );
        assert_eq!(placement.height, 10.0);
        assert!(box_is_clear(&drawing, &placement, 14), "{placement:?}");
    }

    #[test]
    fn the_label_keeps_off_fold_lines_and_shrinks_only_when_it_must() {
        let mut drawing = rectangle(100.0, 60.0);
        drawing.fold_lines = vec![vec![DVec2::new(50.0, 0.0), DVec2::new(50.0, 60.0)]];
        let placement = drawing
            .label_placement(6, 0.6, (2.0, 10.0))
            .expect("placed");
        assert!(box_is_clear(&drawing, &placement, 6), "{placement:?}");
        assert_eq!(placement.height, 10.0, "a 50 mm flange holds a 36 mm label");
        let small = rectangle(12.0, 12.0);
        let placement = small.label_placement(10, 0.6, (2.0, 10.0)).expect("placed");
        assert!(placement.height < 2.0 + 1e-12 && placement.height >= 2.0);
        assert!(!placement.clear, "{placement:?}");
    }
}
