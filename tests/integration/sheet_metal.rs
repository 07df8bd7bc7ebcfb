//! Sheet-metal STEP solids (issue 17): FreeCAD-made L, U and Z sections and the FreeCAD
//! SheetMetal README case, and a SolidWorks plate, unfolded through the real binary. The flat
//! size must be the sum of the flat legs and the bend allowances θ · (R + K · t) within
//! 0.001 mm, holes circles of their diameter, bend lines LINEs on the bend layers only, and
//! every DXF clean for ezdxf.

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

use crate::util::{assert_ezdxf_accepts, flatten_into, read_report, sample, stderr};

/// The flat size must match the analytic one this closely, mm.
pub(crate) const FLAT_TOLERANCE_MM: f64 = 1e-3;

/// One entity of an ASCII DXF: its type, layer, points (codes 10/20), end point (11/21),
/// bulges (42), text (1), text height (40).
#[derive(Debug, Default)]
pub(crate) struct Entity {
    pub(crate) kind: String,
    pub(crate) layer: String,
    pub(crate) points: Vec<[f64; 2]>,
    pub(crate) end: Option<[f64; 2]>,
    pub(crate) bulges: Vec<f64>,
    pub(crate) text: String,
    pub(crate) height: f64,
}

/// The entities of an ASCII DXF's ENTITIES section, read with a parser of our own.
pub(crate) fn dxf_entities(path: &Path) -> Vec<Entity> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    let start = lines
        .windows(2)
        .position(|pair| pair == ["2", "ENTITIES"])
        .expect("an ENTITIES section");
    let mut entities: Vec<Entity> = Vec::new();
    for pair in lines[start + 2..].chunks(2) {
        let [code, value] = [pair[0], pair.get(1).copied().unwrap_or("")];
        if code == "0" {
            if value == "ENDSEC" {
                break;
            }
            entities.push(Entity {
                kind: value.to_owned(),
                ..Default::default()
            });
            continue;
        }
        let Some(entity) = entities.last_mut() else {
            continue;
        };
        let number = || value.parse::<f64>().expect("a number");
        match code {
            "8" => entity.layer = value.to_owned(),
            "1" => entity.text = value.to_owned(),
            "10" => {
                entity.points.push([number(), 0.0]);
                if entity.kind == "LWPOLYLINE" && entity.bulges.len() + 1 < entity.points.len() {
                    entity.bulges.push(0.0);
                }
            }
            "20" => entity.points.last_mut().expect("x before y")[1] = number(),
            "11" => entity.end = Some([number(), 0.0]),
            "21" => entity.end.as_mut().expect("x before y")[1] = number(),
            "42" => entity.bulges.push(number()),
            "40" => entity.height = number(),
            _ => {}
        }
    }
    for entity in &mut entities {
        entity.bulges.resize(entity.points.len(), 0.0);
    }
    entities
}

/// The radius of a closed polyline of two arcs (a circle), or `None` when it is not one.
pub(crate) fn circle_radius(entity: &Entity) -> Option<f64> {
    let ([a, b], [first, second]) = (entity.points.as_slice(), entity.bulges.as_slice()) else {
        return None;
    };
    if *first == 0.0 || *second == 0.0 {
        return None;
    }
    let chord = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    let radius = |bulge: f64| chord * (1.0 + bulge * bulge) / (4.0 * bulge.abs());
    let (one, other) = (radius(*first), radius(*second));
    ((one - other).abs() < 1e-9 * one).then_some(one)
}

/// Flattens a sample at `k_factor` and returns its report part and its DXF's entities.
fn unfold(name: &str, k_factor: f64) -> (serde_json::Value, Vec<Entity>) {
    flatten_sheet(&sample(name), &["--k-factor", &k_factor.to_string()])
}

/// Flattens `input` with `extra` arguments, expecting success: its report part and its DXF's
/// entities (the DXF checked by [`check_with_ezdxf`]).
pub(crate) fn flatten_sheet(input: &Path, extra: &[&str]) -> (serde_json::Value, Vec<Entity>) {
    let directory = tempfile::tempdir().expect("a temporary directory");
    let output = flatten_into(input, directory.path(), extra);
    assert!(output.status.success(), "{input:?}: {}", stderr(&output));
    let part = read_report(directory.path())["parts"][0].clone();
    let name = part["name"].as_str().expect("a name").to_owned();
    let dxf = directory.path().join(format!("{name}.dxf"));
    check_with_ezdxf(&dxf);
    (part, dxf_entities(&dxf))
}

/// Checks `file` with ezdxf ([`assert_ezdxf_accepts`]): its audit, the bend layers defined, no
/// SPLINE or open polyline on a cut layer.
pub(crate) fn check_with_ezdxf(file: &Path) {
    assert_ezdxf_accepts(file, &["--layer", "BEND_UP", "--layer", "BEND_DOWN"]);
}

pub(crate) fn number(value: &serde_json::Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("a number: {value}"))
}

/// Asserts the flat extents, the bends (90°, `radius`), one LINE per bend on the layer of its
/// direction and a note per bend; returns the directions, in the report's order.
fn assert_unfold(
    part: &serde_json::Value,
    entities: &[Entity],
    expected: [f64; 2],
    radius: f64,
) -> Vec<String> {
    let sheet = &part["sheet_metal"];
    let size = [number(&sheet["flat_width"]), number(&sheet["flat_height"])];
    for (found, wanted) in size.iter().zip(expected) {
        assert!(
            (found - wanted).abs() <= FLAT_TOLERANCE_MM,
            "{}: flat {size:?}, expected {expected:?}",
            part["name"]
        );
    }
    let bends = sheet["bends"].as_array().expect("bends");
    let directions: Vec<String> = bends
        .iter()
        .map(|b| b["direction"].as_str().expect("a direction").to_owned())
        .collect();
    for bend in bends {
        assert!((number(&bend["angle"]) - 90.0).abs() < 1e-9, "{bend}");
        assert!(
            (number(&bend["inner_radius"]) - radius).abs() < 1e-9,
            "{bend}"
        );
        assert!((number(&bend["length"]) - expected[1]).abs() < FLAT_TOLERANCE_MM);
    }
    for direction in ["up", "down"] {
        let layer = format!("BEND_{}", direction.to_uppercase());
        let on_layer: Vec<&Entity> = entities.iter().filter(|e| e.layer == layer).collect();
        let wanted = directions.iter().filter(|d| *d == direction).count();
        assert_eq!(on_layer.len(), wanted, "{layer}");
        assert!(on_layer.iter().all(|e| e.kind == "LINE"), "{layer}");
    }
    let notes = entities
        .iter()
        .filter(|e| e.layer == "MARKS" && e.text.contains("90%%d R"))
        .count();
    assert_eq!(notes, directions.len());
    assert_eq!(part["stop_reason"], "exact_unfold");
    assert_eq!(part["tolerance_met"], true);
    directions
}

/// The centre of a closed polyline of two arcs: from the first arc's chord and bulge `β`, the
/// centre is `c (1 − β²) / (4β)` to the left of the chord's middle.
pub(crate) fn circle_centre(entity: &Entity) -> [f64; 2] {
    let ([a, b], [bulge, _]) = (entity.points.as_slice(), entity.bulges.as_slice()) else {
        panic!("a circle of two arcs");
    };
    let chord = [b[0] - a[0], b[1] - a[1]];
    let length = chord[0].hypot(chord[1]);
    let offset = length * (1.0 - bulge * bulge) / (4.0 * bulge);
    let left = [-chord[1] / length, chord[0] / length];
    [0, 1].map(|i| (a[i] + b[i]) / 2.0 + left[i] * offset)
}

/// The x of each bend line (the lines run along y, across the flat's width).
pub(crate) fn bend_line_positions(entities: &[Entity]) -> Vec<f64> {
    let mut positions: Vec<f64> = entities
        .iter()
        .filter(|e| e.layer == "BEND_UP" || e.layer == "BEND_DOWN")
        .map(|e| {
            let end = e.end.expect("a LINE's end");
            assert!(
                (e.points[0][0] - end[0]).abs() < 1e-9,
                "bend lines run along y"
            );
            end[0]
        })
        .collect();
    positions.sort_by(f64::total_cmp);
    positions
}

#[test]
fn an_l_section_unfolds_to_its_legs_plus_the_allowance_with_its_hole_a_circle() {
    let (k, t, r) = (0.44, 2.0, 2.0);
    let allowance = FRAC_PI_2 * (r + k * t);
    let (part, entities) = unfold("sheet_l_hole_freecad.step", k);
    assert_unfold(&part, &entities, [50.0 + 30.0 + allowance, 40.0], r);
    assert_eq!(part["sheet_metal"]["thickness"], 2.0);
    assert_eq!(part["sheet_metal"]["k_factor"], 0.44);
    let width = 80.0 + allowance;
    let [line] = bend_line_positions(&entities)[..] else {
        panic!("one bend line");
    };
    // The bend's centre line: half the allowance past the 50 mm or the 30 mm leg.
    let from_edge = line.min(width - line);
    assert!(
        (from_edge - (30.0 + allowance / 2.0)).abs() < FLAT_TOLERANCE_MM,
        "{line}"
    );
    let holes: Vec<&Entity> = entities.iter().filter(|e| e.layer == "CUT_INNER").collect();
    let [hole] = holes[..] else {
        panic!("one hole");
    };
    let radius = circle_radius(hole).expect("the hole is a circle of two arcs");
    assert!(
        (radius - 5.0).abs() < FLAT_TOLERANCE_MM,
        "hole radius {radius}"
    );
    // Its centre: 25 mm from the 50 mm leg's end, in the middle of the 40 mm width.
    let centre = circle_centre(hole);
    let along = centre[0].min(width - centre[0]);
    assert!(
        (along - 25.0).abs() < FLAT_TOLERANCE_MM && (centre[1] - 20.0).abs() < FLAT_TOLERANCE_MM,
        "hole centre {centre:?}"
    );
}

#[test]
fn a_u_section_at_another_k_factor_takes_two_allowances() {
    let (k, t, r) = (0.3, 1.5, 3.0);
    let allowance = FRAC_PI_2 * (r + k * t);
    let (part, entities) = unfold("sheet_u_freecad.step", k);
    let directions = assert_unfold(&part, &entities, [140.0 + 2.0 * allowance, 30.0], r);
    assert_eq!(directions[0], directions[1], "a U bends twice the same way");
    let lines = bend_line_positions(&entities);
    let expected = [40.0 + allowance / 2.0, 100.0 + 1.5 * allowance];
    for (found, wanted) in lines.iter().zip(expected) {
        assert!((found - wanted).abs() < FLAT_TOLERANCE_MM, "{lines:?}");
    }
}

#[test]
fn a_z_section_bends_one_way_then_the_other() {
    let (k, t, r) = (0.44, 2.0, 2.0);
    let allowance = FRAC_PI_2 * (r + k * t);
    let (part, entities) = unfold("sheet_z_freecad.step", k);
    let mut directions = assert_unfold(&part, &entities, [100.0 + 2.0 * allowance, 25.0], r);
    directions.sort();
    assert_eq!(directions, ["down", "up"]);
}

/// The FreeCAD SheetMetal README's test case: t 2, K 0.38 (ANSI), inner radius 1.64, 90°, leg
/// (flat part) 48.12 mm, so flange 51.76 mm outside (48.12 + R + t); the README's output, "end
/// to mold-line distance 50 mm", is the flat distance from the end to the bend's centre line,
/// leg + BA / 2 = 48.12 + 1.885 = 50.005 (50 to the README's two decimals of the inputs).
#[test]
fn the_freecad_sheetmetal_readme_case_puts_the_bend_line_50_mm_from_each_end() {
    let (k, t, r, leg) = (0.38, 2.0, 1.64, 48.12);
    let allowance = FRAC_PI_2 * (r + k * t);
    assert!((leg + r + t - 51.76).abs() < 1e-12);
    let (part, entities) = unfold("sheet_readme_case_freecad.step", k);
    let width = 2.0 * leg + allowance;
    assert_unfold(&part, &entities, [width, 30.0], r);
    let [line] = bend_line_positions(&entities)[..] else {
        panic!("one bend line");
    };
    for from_end in [line, width - line] {
        assert!((from_end - (leg + allowance / 2.0)).abs() < FLAT_TOLERANCE_MM);
        assert!((from_end - 50.0).abs() < 0.01, "{from_end}");
    }
}

/// A real SolidWorks plate (3/16 in thick, no bend, four 0.26 in holes and one of 6 in): the
/// flat is the plate itself, exactly, its holes circles.
#[test]
fn a_solidworks_plate_comes_out_as_itself_with_its_holes_as_circles() {
    let (part, entities) = unfold("base_interface_solidworks.step", 0.44);
    let sheet = &part["sheet_metal"];
    assert!((number(&sheet["thickness"]) - 0.1875 * 25.4).abs() < 1e-9);
    assert_eq!(sheet["bends"].as_array().map(Vec::len), Some(0));
    assert!(number(&part["area_error"]) < 1e-12 && number(&part["shape_error"]) < 1e-12);
    assert_eq!(part["flipped"], 0);
    let mut diameters: Vec<f64> = entities
        .iter()
        .filter(|e| e.layer == "CUT_INNER")
        .map(|e| 2.0 * circle_radius(e).expect("every hole a circle"))
        .collect();
    diameters.sort_by(f64::total_cmp);
    let expected = [0.26, 0.26, 0.26, 0.26, 6.0].map(|inches| inches * 25.4);
    assert_eq!(diameters.len(), expected.len());
    for (found, wanted) in diameters.iter().zip(expected) {
        assert!((found - wanted).abs() < FLAT_TOLERANCE_MM, "{diameters:?}");
    }
    // The plate is flat already: its outline has the area the report gives (the skin's own).
    assert!(number(&sheet["flat_area"]) > 0.25 * PI * 152.4 * 152.4);
}
