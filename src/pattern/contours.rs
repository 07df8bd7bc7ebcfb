//! A part's cut, sew and fold contours, fitted and ready to draw: the one place where the chord
//! tolerance and the seam allowance are applied, so the DXF files and the previews show the same
//! geometry and the nester can ask for the outline that will actually be cut.
//!
//! Input: a [`PartDrawing`] and [`PatternOptions`] (lengths in mm, converted to the drawing's
//! units).
//! Output: [`PartContours`], outer contours counter-clockwise and holes clockwise.

use super::bulge::BulgeVertex;
use super::contour::{fit_closed, fit_open, signed_area};
use super::drawing::PartDrawing;
use super::errors::PatternError;
use super::options::PatternOptions;
use super::seam_allowance::offset_away_from_material;
use glam::DVec2;

/// The fitted contours of one part, in its drawing units.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PartContours {
    /// The outer cut contour (closed, counter-clockwise); with a seam allowance, the offset one.
    pub outer: Vec<BulgeVertex>,
    /// Inner cut contours (closed, clockwise); with a seam allowance, the offset ones.
    pub holes: Vec<Vec<BulgeVertex>>,
    /// Sew lines (closed): the nominal outer contour and holes when a seam allowance is given,
    /// otherwise empty.
    pub sew_lines: Vec<Vec<BulgeVertex>>,
    /// Fold or bend lines (open; the last vertex's bulge is 0).
    pub fold_lines: Vec<Vec<BulgeVertex>>,
}

/// Fits every contour of `drawing` within the options' chord tolerance and applies the seam
/// allowance, if any.
pub fn part_contours(
    drawing: &PartDrawing,
    options: &PatternOptions,
) -> Result<PartContours, PatternError> {
    options.validate()?;
    if let Some(grain) = drawing.grain {
        check_finite(drawing, &grain, "grain line")?;
    }
    let unit = drawing.units.millimetres();
    let tolerance = options.chord_tolerance / unit;
    let outer = fit_ring(
        drawing,
        &drawing.outer,
        "outer contour",
        tolerance,
        Winding::CounterClockwise,
    )?;
    let holes = drawing
        .holes
        .iter()
        .enumerate()
        .map(|(index, hole)| {
            fit_ring(
                drawing,
                hole,
                &format!("hole {}", index + 1),
                tolerance,
                Winding::Clockwise,
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    let fold_lines = drawing
        .fold_lines
        .iter()
        .enumerate()
        .map(|(index, line)| {
            fit_line(
                drawing,
                line,
                &format!("fold line {}", index + 1),
                tolerance,
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    let nominal = PartContours {
        outer,
        holes,
        sew_lines: Vec::new(),
        fold_lines,
    };
    match options.seam_allowance {
        Some(allowance) => with_seam_allowance(drawing, nominal, allowance, tolerance),
        None => Ok(nominal),
    }
}

/// Turning direction of a closed contour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Winding {
    CounterClockwise,
    Clockwise,
}

/// One closed contour, checked, fitted and turned the requested way.
fn fit_ring(
    drawing: &PartDrawing,
    ring: &[DVec2],
    contour: &str,
    tolerance: f64,
    winding: Winding,
) -> Result<Vec<BulgeVertex>, PatternError> {
    check_finite(drawing, ring, contour)?;
    let degenerate = || PatternError::DegenerateContour {
        part: drawing.name.clone(),
        contour: contour.to_owned(),
    };
    let fitted = fit_closed(ring, tolerance).ok_or_else(degenerate)?;
    let counter_clockwise = signed_area(ring) > 0.0;
    Ok(
        if counter_clockwise == (winding == Winding::CounterClockwise) {
            fitted
        } else {
            reverse_closed(&fitted)
        },
    )
}

/// One open polyline, checked and fitted.
fn fit_line(
    drawing: &PartDrawing,
    line: &[DVec2],
    contour: &str,
    tolerance: f64,
) -> Result<Vec<BulgeVertex>, PatternError> {
    check_finite(drawing, line, contour)?;
    fit_open(line, tolerance).ok_or_else(|| PatternError::DegenerateContour {
        part: drawing.name.clone(),
        contour: contour.to_owned(),
    })
}

/// An error naming the contour when a coordinate is NaN or infinite.
fn check_finite(
    drawing: &PartDrawing,
    points: &[DVec2],
    contour: &str,
) -> Result<(), PatternError> {
    if points.iter().all(|point| point.is_finite()) {
        return Ok(());
    }
    Err(PatternError::NonFiniteCoordinate {
        part: drawing.name.clone(),
        contour: contour.to_owned(),
    })
}

/// The same closed contour run the other way: each segment keeps its arc, with the bulge negated.
pub(crate) fn reverse_closed(vertices: &[BulgeVertex]) -> Vec<BulgeVertex> {
    let count = vertices.len();
    (0..count)
        .map(|index| {
            let vertex = vertices[count - 1 - index];
            let segment_bulge = vertices[(2 * count - 2 - index) % count].bulge;
            BulgeVertex {
                point: vertex.point,
                bulge: -segment_bulge,
            }
        })
        .collect()
}

/// The cut contours moved out by the allowance (mm) and fitted within `tolerance` (drawing
/// units), the nominal ones kept as sew lines.
fn with_seam_allowance(
    drawing: &PartDrawing,
    nominal: PartContours,
    allowance: f64,
    tolerance: f64,
) -> Result<PartContours, PatternError> {
    let distance = allowance / drawing.units.millimetres();
    let mut outer_offsets = offset_away_from_material(&nominal.outer, distance, tolerance);
    if outer_offsets.len() != 1 {
        return Err(PatternError::SeamOffsetFailed {
            part: drawing.name.clone(),
            pieces: outer_offsets.len(),
        });
    }
    let outer = outer_offsets.remove(0);
    let mut holes = Vec::with_capacity(nominal.holes.len());
    for (index, hole) in nominal.holes.iter().enumerate() {
        let offsets = offset_away_from_material(hole, distance, tolerance);
        if offsets.is_empty() {
            return Err(PatternError::SeamAllowanceClosesHole {
                part: drawing.name.clone(),
                hole: index + 1,
                allowance,
            });
        }
        holes.extend(offsets);
    }
    let sew_lines = std::iter::once(nominal.outer)
        .chain(nominal.holes)
        .collect();
    Ok(PartContours {
        outer,
        holes,
        sew_lines,
        fold_lines: nominal.fold_lines,
    })
}

#[cfg(test)]
mod tests {
    use crate::pattern::contours::*;

    #[test]
    fn reversing_keeps_each_arc_on_its_segment() {
        let vertices = [
            BulgeVertex {
                point: DVec2::ZERO,
                bulge: 0.0,
            },
            BulgeVertex {
                point: DVec2::X,
                bulge: 0.5,
            },
            BulgeVertex {
                point: DVec2::Y,
                bulge: 0.0,
            },
        ];
        let reversed = reverse_closed(&vertices);
        // Original segments: 0->X straight, X->Y bulge 0.5, Y->0 straight.
        assert_eq!(
            reversed[0],
            BulgeVertex {
                point: DVec2::Y,
                bulge: -0.5
            }
        );
        assert_eq!(
            reversed[1],
            BulgeVertex {
                point: DVec2::X,
                bulge: 0.0
            }
        );
        assert_eq!(
            reversed[2],
            BulgeVertex {
                point: DVec2::ZERO,
                bulge: 0.0
            }
        );
        assert_eq!(reverse_closed(&reversed), vertices.to_vec());
    }

    #[test]
    fn seam_allowance_on_a_disc_keeps_true_arcs() {
        let disc: Vec<DVec2> = (0..720)
            .map(|step| 50.0 * DVec2::from_angle(step as f64 * std::f64::consts::TAU / 720.0))
            .collect();
        let drawing = PartDrawing {
            name: "disc".into(),
            outer: disc,
            ..Default::default()
        };
        let options = PatternOptions {
            seam_allowance: Some(12.0),
            ..Default::default()
        };
        let contours = part_contours(&drawing, &options).expect("valid part");
        assert_eq!(contours.sew_lines.len(), 1);
        assert_eq!(contours.outer.len(), 2, "{:?}", contours.outer);
        for point in crate::pattern::bulge::sample_closed(&contours.outer, 0.5) {
            assert!((point.length() - 62.0).abs() < 1e-6, "{point}");
        }
    }

    #[test]
    fn seam_allowance_leaves_no_micro_segments() {
        // Fitted, the dense ellipse is a chain of nearly tangent arcs; the raw offset joins them
        // with arcs a few micrometres long.
        let ellipse: Vec<DVec2> = (0..2000)
            .map(|step| {
                let angle = step as f64 * std::f64::consts::TAU / 2000.0;
                DVec2::new(200.0 * angle.cos(), 90.0 * angle.sin())
            })
            .collect();
        let drawing = PartDrawing {
            name: "panel".into(),
            outer: ellipse,
            ..Default::default()
        };
        let options = PatternOptions {
            seam_allowance: Some(10.0),
            ..Default::default()
        };
        let outer = part_contours(&drawing, &options).expect("valid part").outer;
        let minimum =
            options.chord_tolerance * crate::pattern::contour::MIN_SEGMENT_LENGTH_IN_TOLERANCES;
        for (index, vertex) in outer.iter().enumerate() {
            let next = outer[(index + 1) % outer.len()];
            let length =
                crate::pattern::bulge::segment_length(vertex.point, next.point, vertex.bulge);
            assert!(length >= minimum, "segment {index} is {length} mm long");
        }
    }

    #[test]
    fn seam_allowance_that_fills_a_hole_is_an_error() {
        let square = vec![
            DVec2::ZERO,
            DVec2::new(100.0, 0.0),
            DVec2::new(100.0, 100.0),
            DVec2::new(0.0, 100.0),
        ];
        let hole: Vec<DVec2> = square
            .iter()
            .map(|point| *point * 0.05 + DVec2::splat(50.0))
            .collect();
        let drawing = PartDrawing {
            name: "panel".into(),
            outer: square,
            holes: vec![hole],
            ..Default::default()
        };
        let options = PatternOptions {
            seam_allowance: Some(10.0),
            ..Default::default()
        };
        let error = part_contours(&drawing, &options).expect_err("the hole closes");
        assert!(
            matches!(error, PatternError::SeamAllowanceClosesHole { hole: 1, .. }),
            "{error}"
        );
    }

    #[test]
    fn fitting_turns_outer_counter_clockwise_and_holes_clockwise() {
        let clockwise_square = vec![
            DVec2::ZERO,
            DVec2::new(0.0, 10.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(10.0, 0.0),
        ];
        let mut hole: Vec<DVec2> = clockwise_square
            .iter()
            .map(|point| *point * 0.2 + DVec2::splat(4.0))
            .collect();
        hole.reverse();
        let drawing = PartDrawing {
            name: "plate".into(),
            outer: clockwise_square,
            holes: vec![hole],
            ..Default::default()
        };
        let contours = part_contours(&drawing, &PatternOptions::default()).expect("valid part");
        let area = |vertices: &[BulgeVertex]| {
            signed_area(
                &vertices
                    .iter()
                    .map(|vertex| vertex.point)
                    .collect::<Vec<_>>(),
            )
        };
        assert!(area(&contours.outer) > 0.0);
        assert!(area(&contours.holes[0]) < 0.0);
    }
}
