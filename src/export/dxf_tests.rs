//! Tests of the DXF writer: files read back with the dxf crate.

use super::*;
use crate::export::drawing::PlacedPart;
use crate::pattern::{
    BulgeArc, DEFAULT_CHORD_TOLERANCE, PatternError, PatternOptions, distance_to_line_segment,
    sample_closed,
};
use std::f64::consts::TAU;

/// An annular sector (a cone frustum's development), counter-clockwise, 400 points per arc.
fn cone_development(inner: f64, outer: f64, angle: f64) -> Vec<DVec2> {
    let arc = |radius: f64, reversed: bool| {
        (0..400).map(move |step| {
            let fraction = step as f64 / 399.0;
            let angle = angle * if reversed { 1.0 - fraction } else { fraction };
            radius * DVec2::new(angle.cos(), angle.sin())
        })
    };
    arc(outer, false).chain(arc(inner, true)).collect()
}

/// A circle of `count` points.
fn circle(center: DVec2, radius: f64, count: usize) -> Vec<DVec2> {
    (0..count)
        .map(|step| center + radius * DVec2::from_angle(TAU * step as f64 / count as f64))
        .collect()
}

fn cone_part() -> PartDrawing {
    PartDrawing {
        name: "cone".into(),
        quantity: 2,
        material: Some("steel 1.5".into()),
        outer: cone_development(120.0, 300.0, 2.0),
        holes: vec![circle(DVec2::new(200.0, 100.0), 10.0, 360)],
        // A radial line across the sector, from the inner to the outer arc.
        fold_lines: vec![vec![
            120.0 * DVec2::from_angle(1.2),
            300.0 * DVec2::from_angle(1.2),
        ]],
        grain: Some([DVec2::new(140.0, 60.0), DVec2::new(200.0, 60.0)]),
        ..Default::default()
    }
}

fn read_back(bytes: &[u8]) -> Drawing {
    Drawing::load(&mut &bytes[..]).expect("the dxf crate reads its own output")
}

/// Bulge vertices of the polylines on a layer, in file order (LWPOLYLINE or POLYLINE).
fn polylines_on(document: &Drawing, layer: &str) -> Vec<Vec<BulgeVertex>> {
    document
        .entities()
        .filter(|entity| entity.common.layer == layer)
        .filter_map(|entity| match &entity.specific {
            EntityType::LwPolyline(polyline) => Some(
                polyline
                    .vertices
                    .iter()
                    .map(|vertex| BulgeVertex {
                        point: DVec2::new(vertex.x, vertex.y),
                        bulge: vertex.bulge,
                    })
                    .collect(),
            ),
            EntityType::Polyline(polyline) => Some(
                polyline
                    .vertices()
                    .map(|vertex| BulgeVertex {
                        point: DVec2::new(vertex.location.x, vertex.location.y),
                        bulge: vertex.bulge,
                    })
                    .collect(),
            ),
            _ => None,
        })
        .collect()
}

#[test]
fn cone_development_is_written_with_true_arcs_within_tolerance() {
    let (inner, outer, angle): (f64, f64, f64) = (120.0, 300.0, 2.0);
    let bytes = write_part_dxf(&cone_part(), &DxfOptions::default()).expect("writes");
    let outlines = polylines_on(&read_back(&bytes), layers::CUT_OUTER);
    assert_eq!(outlines.len(), 1);
    let outline = &outlines[0];
    assert!(outline.len() < 20, "{} vertices", outline.len());
    let edge = DVec2::new(angle.cos(), angle.sin());
    let deviation = sample_closed(outline, 0.05)
        .into_iter()
        .map(|point| {
            let circles = (point.length() - inner)
                .abs()
                .min((point.length() - outer).abs());
            let lines = distance_to_line_segment(point, DVec2::X * inner, DVec2::X * outer)
                .min(distance_to_line_segment(point, edge * inner, edge * outer));
            circles.min(lines)
        })
        .fold(0.0, f64::max);
    assert!(
        deviation <= DEFAULT_CHORD_TOLERANCE,
        "deviation {deviation} mm"
    );
}

#[test]
fn circular_hole_is_two_arcs_on_the_inner_layer() {
    let bytes = write_part_dxf(&cone_part(), &DxfOptions::default()).expect("writes");
    let holes = polylines_on(&read_back(&bytes), layers::CUT_INNER);
    assert_eq!(holes.len(), 1);
    assert_eq!(holes[0].len(), 2);
    for (index, vertex) in holes[0].iter().enumerate() {
        let next = holes[0][(index + 1) % 2];
        let arc = BulgeArc::from_segment(vertex.point, next.point, vertex.bulge).expect("an arc");
        assert!((arc.radius - 10.0).abs() < 1e-6);
        assert!(arc.center.distance(DVec2::new(200.0, 100.0)) < 1e-6);
    }
}

#[test]
fn square_stays_four_vertices() {
    let square = vec![
        DVec2::ZERO,
        DVec2::new(50.0, 0.0),
        DVec2::new(50.0, 50.0),
        DVec2::new(0.0, 50.0),
    ];
    let part = PartDrawing {
        name: "square".into(),
        quantity: 1,
        outer: square,
        ..Default::default()
    };
    let bytes = write_part_dxf(&part, &DxfOptions::default()).expect("writes");
    let outlines = polylines_on(&read_back(&bytes), layers::CUT_OUTER);
    assert_eq!(outlines[0].len(), 4);
}

#[test]
fn same_input_gives_identical_bytes() {
    let first = write_part_dxf(&cone_part(), &DxfOptions::default()).expect("writes");
    std::thread::sleep(std::time::Duration::from_millis(1100));
    let second = write_part_dxf(&cone_part(), &DxfOptions::default()).expect("writes");
    assert!(first == second, "two writes differ");
    let r12 = DxfOptions {
        version: DxfVersion::R12,
        ..Default::default()
    };
    assert!(
        write_part_dxf(&cone_part(), &r12).expect("writes")
            == write_part_dxf(&cone_part(), &r12).expect("writes")
    );
}

#[test]
fn r2000_states_units_and_version() {
    let text =
        String::from_utf8(write_part_dxf(&cone_part(), &DxfOptions::default()).expect("writes"))
            .expect("ASCII");
    let normalised: String = text.lines().map(str::trim).collect::<Vec<_>>().join("\n");
    assert!(normalised.contains("$ACADVER\n1\nAC1015"));
    assert!(normalised.contains("$INSUNITS\n70\n4"));
    assert!(normalised.contains("$MEASUREMENT\n70\n1"));
    assert!(normalised.contains("LWPOLYLINE"));
    assert!(!normalised.contains("\n0\nSPLINE\n") && !normalised.contains("\n0\nELLIPSE\n"));
}

#[test]
fn extents_hold_the_outer_arc() {
    let document =
        read_back(&write_part_dxf(&cone_part(), &DxfOptions::default()).expect("writes"));
    let (low, high) = (
        document.header.minimum_drawing_extents,
        document.header.maximum_drawing_extents,
    );
    // The outer arc of radius 300 runs from 0 to 2 radians: it passes the top of its circle.
    assert!((high.y - 300.0).abs() < 1e-9 && (high.x - 300.0).abs() < 1e-9);
    assert!((low.x - 300.0 * 2.0f64.cos()).abs() < 1e-9 && low.y.abs() < 1e-9);
}

#[test]
fn inches_state_inch_units() {
    let part = PartDrawing {
        units: Units::Inches,
        ..cone_part()
    };
    let document = read_back(&write_part_dxf(&part, &DxfOptions::default()).expect("writes"));
    assert_eq!(document.header.default_drawing_units, DxfUnits::Inches);
    assert_eq!(document.header.drawing_units, DrawingUnits::English);
}

#[test]
fn r12_has_no_lightweight_polylines() {
    let options = DxfOptions {
        version: DxfVersion::R12,
        ..Default::default()
    };
    let bytes = write_part_dxf(&cone_part(), &options).expect("writes");
    let text = String::from_utf8(bytes.clone()).expect("ASCII");
    assert!(!text.contains("LWPOLYLINE"));
    assert!(text.contains("AC1009"));
    let document = read_back(&bytes);
    assert_eq!(polylines_on(&document, layers::CUT_OUTER)[0].len(), 4);
    assert_eq!(polylines_on(&document, layers::CUT_INNER)[0].len(), 2);
}

#[test]
fn every_layer_is_defined_and_entities_sit_on_them() {
    let document =
        read_back(&write_part_dxf(&cone_part(), &DxfOptions::default()).expect("writes"));
    for (name, _, line_type) in layers::ALL {
        let layer = document
            .layers()
            .find(|layer| layer.name == name)
            .expect("layer defined");
        assert_eq!(layer.line_type_name, line_type);
    }
    assert!(
        document
            .line_types()
            .any(|line_type| line_type.name == layers::DASHED)
    );
    let on = |layer: &str| {
        document
            .entities()
            .filter(|entity| entity.common.layer == layer)
            .count()
    };
    assert_eq!(
        (
            on(layers::CUT_OUTER),
            on(layers::CUT_INNER),
            on(layers::FOLD),
            on(layers::MARKS)
        ),
        (1, 1, 1, 3)
    );
    let label = document
        .entities()
        .find_map(|entity| match &entity.specific {
            EntityType::Text(text) => Some(text.value.clone()),
            _ => None,
        });
    assert_eq!(label.as_deref(), Some("cone x2 steel 1.5"));
}

#[test]
fn label_shows_names_literally() {
    let part = PartDrawing {
        name: "sleeve\nleft ^5".into(),
        material: Some("cotton 100 %%c".into()),
        ..cone_part()
    };
    let document = read_back(&write_part_dxf(&part, &DxfOptions::default()).expect("writes"));
    let label = document
        .entities()
        .find_map(|entity| match &entity.specific {
            EntityType::Text(text) => Some(text.value.clone()),
            _ => None,
        });
    assert_eq!(
        label.as_deref(),
        Some("sleeve left ^ 5 x2 cotton 100 %%%%%%c")
    );
}

#[test]
fn the_label_sits_on_the_material_and_is_sized_from_the_true_extents() {
    // A half annulus of radii 200 and 300: its bounding-box centre (0, 150) lies in the hollow;
    // the label must not. Its outline is 4 collinear vertices and 2 arcs, so the label's size
    // must come from the arcs' extents (600 x 300 mm: the 10 mm cap), not from the vertices.
    let part = PartDrawing {
        outer: cone_development(200.0, 300.0, std::f64::consts::PI),
        holes: Vec::new(),
        fold_lines: Vec::new(),
        grain: None,
        ..cone_part()
    };
    let document = read_back(&write_part_dxf(&part, &DxfOptions::default()).expect("writes"));
    let text = document
        .entities()
        .find_map(|entity| match &entity.specific {
            EntityType::Text(text) => Some(text.clone()),
            _ => None,
        })
        .expect("a label");
    assert!(
        (text.text_height - 10.0).abs() < 1e-9,
        "{}",
        text.text_height
    );
    let width = text.value.chars().count() as f64 * text.text_height * LABEL_CHARACTER_WIDTH;
    let along = DVec2::from_angle(text.rotation.to_radians());
    let centre = DVec2::new(text.location.x, text.location.y)
        + 0.5 * (along * width + along.perp() * text.text_height);
    let radius = centre.length();
    assert!(
        (220.0..280.0).contains(&radius),
        "label centre {centre} at radius {radius}"
    );
    assert!(centre.y > 0.0, "{centre}");
}

#[test]
fn seam_allowance_cuts_outside_and_keeps_the_sew_line() {
    let square = vec![
        DVec2::ZERO,
        DVec2::new(100.0, 0.0),
        DVec2::new(100.0, 60.0),
        DVec2::new(0.0, 60.0),
    ];
    let part = PartDrawing {
        name: "panel".into(),
        quantity: 1,
        outer: square,
        ..Default::default()
    };
    let options = DxfOptions {
        pattern: PatternOptions {
            seam_allowance: Some(10.0),
            ..Default::default()
        },
        ..Default::default()
    };
    let document = read_back(&write_part_dxf(&part, &options).expect("writes"));
    let cut = &polylines_on(&document, layers::CUT_OUTER)[0];
    let sew = &polylines_on(&document, layers::SEW)[0];
    assert_eq!(sew.len(), 4);
    let cut_points = sample_closed(cut, 0.1);
    let (low, high) = cut_points.iter().fold(
        (DVec2::INFINITY, DVec2::NEG_INFINITY),
        |(low, high), point| (low.min(*point), high.max(*point)),
    );
    assert!(
        low.distance(DVec2::splat(-10.0)) < 1e-6 && high.distance(DVec2::new(110.0, 70.0)) < 1e-6
    );
}

#[test]
fn sheet_has_its_outline_and_every_part() {
    let shifted = |offset: DVec2| {
        let mut part = cone_part();
        part.outer
            .iter_mut()
            .chain(part.holes.iter_mut().flatten())
            .for_each(|point| *point += offset);
        part.fold_lines
            .iter_mut()
            .flatten()
            .for_each(|point| *point += offset);
        PlacedPart { drawing: part }
    };
    let sheet = SheetDrawing {
        index: 1,
        width: 1000.0,
        height: 500.0,
        parts: vec![
            shifted(DVec2::new(350.0, 10.0)),
            shifted(DVec2::new(700.0, 10.0)),
        ],
        ..Default::default()
    };
    let document = read_back(&write_sheet_dxf(&sheet, &DxfOptions::default()).expect("writes"));
    assert_eq!(polylines_on(&document, layers::SHEET).len(), 1);
    assert_eq!(polylines_on(&document, layers::CUT_OUTER).len(), 2);
    assert_eq!(polylines_on(&document, layers::CUT_INNER).len(), 2);
}

#[test]
fn bad_input_is_an_error_that_names_the_part() {
    let mut part = cone_part();
    part.holes.push(vec![DVec2::ZERO, DVec2::NAN, DVec2::X]);
    let error = write_part_dxf(&part, &DxfOptions::default()).expect_err("NaN refused");
    assert!(error.to_string().contains("cone") && error.to_string().contains("hole 2"));
    let no_grain = PartDrawing {
        grain: Some([DVec2::ZERO, DVec2::INFINITY]),
        ..cone_part()
    };
    let error = write_part_dxf(&no_grain, &DxfOptions::default()).expect_err("infinity refused");
    assert!(error.to_string().contains("grain line"));
    let options = DxfOptions {
        pattern: PatternOptions {
            chord_tolerance: 0.0,
            ..Default::default()
        },
        ..Default::default()
    };
    assert!(matches!(
        write_part_dxf(&cone_part(), &options),
        Err(ExportError::Pattern(
            PatternError::InvalidChordTolerance { .. }
        ))
    ));
    let sheet = SheetDrawing {
        width: -1.0,
        height: 10.0,
        ..Default::default()
    };
    assert!(matches!(
        write_sheet_dxf(&sheet, &DxfOptions::default()),
        Err(ExportError::InvalidSheetSize { .. })
    ));
}
