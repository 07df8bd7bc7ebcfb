//! Sheet metal with formed regions (issue 17, scope item 3): faces that are not developable
//! (spheres, surfaces of revolution, B-splines) on one skin of a thin solid. A region inside
//! one flange is drawn as its projection onto that flange, the rest unfolding exactly; one that
//! runs into a bend sends the chosen skin (never the closed solid) to the energy flattening.
//! Either way the warning names the faces.

use std::f64::consts::FRAC_PI_2;

use crate::sheet_metal::{Entity, FLAT_TOLERANCE_MM, flatten_sheet, number};
use crate::util::sample;

/// The L both samples are made from: legs 50 and 30, R 2, t 2, 40 wide.
const LEGS: f64 = 80.0;
const WIDTH: f64 = 40.0;
const RADIUS: f64 = 2.0;
const THICKNESS: f64 = 2.0;

/// The DXF's one outer contour.
fn only_outline(entities: &[Entity]) -> &Entity {
    let [outline] = entities
        .iter()
        .filter(|e| e.layer == "CUT_OUTER")
        .collect::<Vec<_>>()[..]
    else {
        panic!("one outline");
    };
    outline
}

/// The part's warnings, joined.
fn warnings(part: &serde_json::Value) -> String {
    let list = part["warnings"].as_array().expect("warnings");
    list.iter()
        .map(|w| w.as_str().expect("a warning"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The area enclosed by a closed polyline's vertices (shoelace).
fn polygon_area(points: &[[f64; 2]]) -> f64 {
    let twice: f64 = (0..points.len())
        .map(|i| {
            let [x0, y0] = points[i];
            let [x1, y1] = points[(i + 1) % points.len()];
            x0 * y1 - x1 * y0
        })
        .sum();
    twice.abs() / 2.0
}

#[test]
fn a_dimple_in_a_flange_is_drawn_as_its_projection_and_the_rest_unfolds_exactly() {
    let allowance = FRAC_PI_2 * (RADIUS + 0.44 * THICKNESS);
    // From the base face (#782, the inner side of the 50 mm leg: the dimple's inner side is on
    // its skin) and from the 30 mm leg's outer side (#547: the dimple's outer side, its flange
    // reached through the bend).
    for (base_face, direction, dimple) in [
        (None, "up", "ADVANCED_FACE #884 on SPHERICAL_SURFACE"),
        (
            Some("547"),
            "down",
            "ADVANCED_FACE #697 on SPHERICAL_SURFACE",
        ),
    ] {
        let extra: Vec<&str> = base_face.map_or(vec![], |id| vec!["--base-face", id]);
        let (part, entities) = flatten_sheet(&sample("sheet_dimple_freecad.step"), &extra);
        let sheet = &part["sheet_metal"];
        let size = [number(&sheet["flat_width"]), number(&sheet["flat_height"])];
        let expected = [LEGS + allowance, WIDTH];
        for (found, wanted) in size.iter().zip(expected) {
            assert!((found - wanted).abs() <= FLAT_TOLERANCE_MM, "{size:?}");
        }
        // The dimple adds no area: its blank is the flange under it.
        let area = number(&sheet["flat_area"]);
        assert!((area - expected[0] * expected[1]).abs() < 1e-6, "{area}");
        let bends = sheet["bends"].as_array().expect("bends");
        assert_eq!(bends.len(), 1);
        assert_eq!(bends[0]["direction"], direction);
        assert_eq!(part["flipped"], 0);
        assert_eq!(part["overlap"], false);
        let said = warnings(&part);
        for words in [
            dimple,
            "SURFACE_OF_REVOLUTION",
            "is not developable: drawn as its projection onto its flange (ADVANCED_FACE #",
        ] {
            assert!(said.contains(words), "{said}");
        }
        // Not a hole: the outline only.
        assert!(entities.iter().all(|e| e.layer != "CUT_INNER"));
    }
}

#[test]
fn a_formed_face_running_into_a_bend_sends_the_skin_alone_to_the_energy_flattening() {
    // The 30 mm flange's two sides are B-spline surfaces: the region runs into the bend, so it
    // has no one flange to be projected onto; the chosen skin (the L's outer side, radius 4 in
    // the bend) is flattened as a surface: its own developed area, not twice a sheet's.
    let (part, entities) = flatten_sheet(&sample("sheet_spline_flange_freecad.step"), &[]);
    assert!(part.get("sheet_metal").is_none(), "{part}");
    let said = warnings(&part);
    for words in [
        "formed region ADVANCED_FACE #214 on B_SPLINE_SURFACE_WITH_KNOTS",
        "is not developable and it runs into a bend: the skin of ADVANCED_FACE #17 on PLANE",
        "flattened as a surface, its bends without bend allowance",
    ] {
        assert!(said.contains(words), "{said}");
    }
    assert_eq!(part["flipped"], 0);
    assert_eq!(part["overlap"], false);
    let outline = only_outline(&entities);
    let skin = WIDTH * (LEGS + FRAC_PI_2 * (RADIUS + THICKNESS));
    let area = polygon_area(&outline.points);
    assert!((area - skin).abs() < 0.001 * skin, "{area} against {skin}");
}

#[test]
fn a_dimple_cut_by_the_sheets_edge_is_not_projected_and_its_skin_is_flattened_as_a_surface() {
    // The same dimple 8 mm from the 50 mm leg's edge, cut by it: the region reaches a wall, so
    // its projection would not be its flat extent; the skin alone goes to the energy model.
    let (part, entities) = flatten_sheet(&sample("sheet_edge_dimple_freecad.step"), &[]);
    assert!(part.get("sheet_metal").is_none(), "{part}");
    let said = warnings(&part);
    for words in [
        "SPHERICAL_SURFACE",
        "is not developable and it reaches an edge of the sheet (a wall",
        "flattened as a surface, its bends without bend allowance",
    ] {
        assert!(said.contains(words), "{said}");
    }
    assert_eq!(part["flipped"], 0);
    assert_eq!(part["overlap"], false);
    // One skin: about the L's area (the dimple's own material added), never two skins'.
    let outline = only_outline(&entities);
    let area = polygon_area(&outline.points);
    let inner_skin = WIDTH * (LEGS + FRAC_PI_2 * RADIUS);
    assert!(
        area > inner_skin && area < 1.01 * WIDTH * (LEGS + FRAC_PI_2 * (RADIUS + THICKNESS)),
        "{area}"
    );
}
