//! Sheet metal, issue 17 continued: FreeCAD-made hat, hem, box with four flanges and corner
//! reliefs and holes across a flange (flat = Σ flanges + Σ BA within 0.001 mm); bend rules
//! (a bend table of K, BA or BD interpolated, DIN 6935) against hand-computed allowances;
//! `--base-face`; `--bend-zones`; the label kept off the bend lines; part files whose folds
//! have a bend radius; a multi-body file, each solid unfolded on its own.

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

use crate::sheet_metal::{
    Entity, FLAT_TOLERANCE_MM, bend_line_positions, circle_centre, circle_radius, flatten_sheet,
    number,
};
use crate::util::{flatten_into, read_report, sample, stderr};

/// The default K-factor.
const K: f64 = 0.44;

/// Flattens `input` with `extra` arguments, expecting a refusal: its stderr.
fn refused(input: &Path, extra: &[&str]) -> String {
    let directory = tempfile::tempdir().expect("a temporary directory");
    let output = flatten_into(input, directory.path(), extra);
    assert!(
        !output.status.success(),
        "{input:?} {extra:?} was not refused"
    );
    stderr(&output)
}

/// The flat extents of a report part.
fn flat_size(part: &serde_json::Value) -> [f64; 2] {
    let sheet = &part["sheet_metal"];
    [number(&sheet["flat_width"]), number(&sheet["flat_height"])]
}

/// Asserts the flat extents within [`FLAT_TOLERANCE_MM`].
fn assert_size(part: &serde_json::Value, expected: [f64; 2]) {
    let size = flat_size(part);
    for (found, wanted) in size.iter().zip(expected) {
        assert!(
            (found - wanted).abs() <= FLAT_TOLERANCE_MM,
            "{}: flat {size:?}, expected {expected:?}",
            part["name"]
        );
    }
}

/// The bends' directions, sorted.
fn directions(part: &serde_json::Value) -> Vec<String> {
    let mut directions: Vec<String> = part["sheet_metal"]["bends"]
        .as_array()
        .expect("bends")
        .iter()
        .map(|bend| bend["direction"].as_str().expect("a direction").to_owned())
        .collect();
    directions.sort();
    directions
}

/// The allowance of a 90° bend at inner radius `r`, thickness `t`, K-factor `k`.
fn quarter(r: f64, t: f64, k: f64) -> f64 {
    FRAC_PI_2 * (r + k * t)
}

#[test]
fn a_hat_section_takes_four_allowances_two_up_two_down() {
    let allowance = quarter(2.0, 2.0, K);
    let (part, entities) = flatten_sheet(&sample("sheet_hat_freecad.step"), &[]);
    assert_size(&part, [140.0 + 4.0 * allowance, 30.0]);
    assert_eq!(directions(&part), ["down", "down", "up", "up"]);
    let lines = bend_line_positions(&entities);
    let expected = [
        20.0 + allowance / 2.0,
        50.0 + 1.5 * allowance,
        90.0 + 2.5 * allowance,
        120.0 + 3.5 * allowance,
    ];
    for (found, wanted) in lines.iter().zip(expected) {
        assert!((found - wanted).abs() < FLAT_TOLERANCE_MM, "{lines:?}");
    }
}

#[test]
fn a_hem_folded_back_by_180_degrees_takes_half_a_turn_of_neutral_fibre() {
    let (r, t) = (1.0, 1.0);
    let (part, _) = flatten_sheet(&sample("sheet_hem_freecad.step"), &[]);
    assert_size(&part, [60.0 + PI * (r + K * t), 30.0]);
    let bend = &part["sheet_metal"]["bends"][0];
    assert!((number(&bend["angle"]) - 180.0).abs() < 1e-9, "{bend}");
}

#[test]
fn holes_across_a_flange_stay_circles_where_the_flange_unrolls() {
    let allowance = quarter(2.0, 2.0, K);
    let width = 100.0 + allowance;
    let (part, entities) = flatten_sheet(&sample("sheet_flange_holes_freecad.step"), &[]);
    assert_size(&part, [width, 50.0]);
    let holes: Vec<&Entity> = entities.iter().filter(|e| e.layer == "CUT_INNER").collect();
    assert_eq!(holes.len(), 3);
    let mut across = Vec::new();
    for hole in holes {
        let radius = circle_radius(hole).expect("a circle of two arcs");
        assert!((radius - 3.0).abs() < FLAT_TOLERANCE_MM, "{radius}");
        let [x, y] = circle_centre(hole);
        // 15 mm up the 40 mm flange: 25 mm from its end.
        assert!((x.min(width - x) - 25.0).abs() < FLAT_TOLERANCE_MM, "{x}");
        across.push(y);
    }
    across.sort_by(f64::total_cmp);
    for (found, wanted) in across.iter().zip([10.0, 25.0, 40.0]) {
        assert!((found - wanted).abs() < FLAT_TOLERANCE_MM, "{across:?}");
    }
}

#[test]
fn a_box_with_four_flanges_and_corner_reliefs_unfolds_to_a_cross() {
    let allowance = quarter(2.0, 2.0, K);
    let (part, entities) = flatten_sheet(&sample("sheet_box_freecad.step"), &[]);
    assert_size(&part, [100.0 + 2.0 * allowance, 80.0 + 2.0 * allowance]);
    assert_eq!(directions(&part).len(), 4);
    // The cross: the base, four flanges with their bend zones, the base's hole.
    let arms = 2.0 * (20.0 + allowance) * (40.0 + 60.0);
    let area = 60.0 * 40.0 + arms - PI * 25.0;
    let found = number(&part["sheet_metal"]["flat_area"]);
    assert!((found - area).abs() < 0.05, "{found} against {area}");
    let [hole] = entities
        .iter()
        .filter(|e| e.layer == "CUT_INNER")
        .collect::<Vec<_>>()[..]
    else {
        panic!("one hole");
    };
    assert!((circle_radius(hole).expect("a circle") - 5.0).abs() < FLAT_TOLERANCE_MM);
}

#[test]
fn a_box_whose_base_meets_its_other_skin_only_through_its_bends_unfolds_from_either_skin() {
    // No hole and open corner reliefs: no wall joins the base's two sides, so the thickness is
    // found across the bends and the base's opposite face through the bends' outer skins.
    let allowance = quarter(2.0, 2.0, K);
    let arm = 20.0 + allowance;
    let area = 60.0 * 40.0 + 2.0 * arm * (40.0 + 60.0);
    // #485 is the base's outer side (x = 24, the largest planar face, the first of two equal),
    // #1085 its inner side (x = 22).
    for (base_face, direction) in [(None, "down"), (Some("1085"), "up")] {
        let extra: Vec<&str> = base_face.map_or(vec![], |id| vec!["--base-face", id]);
        let (part, entities) = flatten_sheet(&sample("sheet_box_plain_freecad.step"), &extra);
        let sheet = &part["sheet_metal"];
        assert_eq!(number(&sheet["thickness"]), 2.0);
        assert_size(&part, [60.0 + 2.0 * arm, 40.0 + 2.0 * arm]);
        let found = number(&sheet["flat_area"]);
        assert!((found - area).abs() < 1e-6, "{found} against {area}");
        assert_eq!(directions(&part), [direction; 4]);
        let mut lengths: Vec<f64> = sheet["bends"]
            .as_array()
            .expect("bends")
            .iter()
            .map(|bend| number(&bend["length"]))
            .collect();
        lengths.sort_by(f64::total_cmp);
        for (found, wanted) in lengths.iter().zip([40.0, 40.0, 60.0, 60.0]) {
            assert!((found - wanted).abs() < FLAT_TOLERANCE_MM, "{lengths:?}");
        }
        assert!(entities.iter().all(|e| e.layer != "CUT_INNER"));
        assert!(part["warnings"].as_array().expect("warnings").is_empty());
    }
}

/// The L of `sheet_l_hole_freecad.step` (legs 50 and 30, R 2, t 2, 40 wide) with a bend of
/// allowance `allowance`: its flat size.
fn l_size(allowance: f64) -> [f64; 2] {
    [80.0 + allowance, 40.0]
}

/// Writes a bend table and returns its directory (kept alive by the caller) and path.
fn table(text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let directory = tempfile::tempdir().expect("a temporary directory");
    let path = directory.path().join("bends.csv");
    std::fs::write(&path, text).expect("table written");
    (directory, path)
}

#[test]
fn a_k_table_is_interpolated_between_radii_and_angles_for_the_parts_material() {
    // R 2 and 90° lie midway between the rows' radii 1, 3 and angles 60, 120: the four steel
    // rows' mean, 0.375; the aluminium rows must not count.
    let (_keep, path) = table(
        "material,thickness,inner_radius,angle,k\n\
         steel,2,1,60,0.30\nsteel,2,1,120,0.34\nsteel,2,3,60,0.40\nsteel,2,3,120,0.46\n\
         alu,2,1,60,0.5\nalu,2,1,120,0.5\nalu,2,3,60,0.5\nalu,2,3,120,0.5\n",
    );
    let file = path.to_str().expect("utf-8");
    let arguments = ["--bend-table", file, "--material", "Steel"];
    let (part, _) = flatten_sheet(&sample("sheet_l_hole_freecad.step"), &arguments);
    let k = (0.30 + 0.34 + 0.40 + 0.46) / 4.0;
    assert_size(&part, l_size(quarter(2.0, 2.0, k)));
    let rule = &part["sheet_metal"]["bends"][0]["rule"];
    assert_eq!(rule["kind"], "table");
    assert_eq!(rule["quantity"], "k");
    assert!((number(&rule["value"]) - k).abs() < 1e-12, "{rule}");
    assert_eq!(rule["lines"], serde_json::json!([2, 3, 4, 5]));
    assert_eq!(part["sheet_metal"].get("k_factor"), None);
    let error = refused(
        &sample("sheet_l_hole_freecad.step"),
        &["--bend-table", file],
    );
    assert!(error.contains("give --material"), "{error}");
}

#[test]
fn allowance_and_deduction_tables_give_the_allowance_at_a_grid_point() {
    let (_keep, path) = table("thickness,inner_radius,angle,ba\n2,2,90,4.2\n");
    let arguments = ["--bend-table", path.to_str().expect("utf-8")];
    let (part, _) = flatten_sheet(&sample("sheet_l_hole_freecad.step"), &arguments);
    assert_size(&part, l_size(4.2));
    // BD 3.9 at R 2, t 2, 90°: BA = 2 · OSSB − BD = 2 · (2 + 2) · tan 45° − 3.9 = 4.1.
    let (_keep, path) = table("thickness,inner_radius,angle,bd\n2,2,90,3.9\n");
    let arguments = ["--bend-table", path.to_str().expect("utf-8")];
    let (part, _) = flatten_sheet(&sample("sheet_l_hole_freecad.step"), &arguments);
    assert_size(&part, l_size(4.1));
}

#[test]
fn a_bend_outside_the_table_or_a_malformed_table_is_refused_naming_file_and_line() {
    let (_keep, path) = table("thickness,inner_radius,angle,k\n2,3,90,0.4\n2,5,90,0.45\n");
    let file = path.to_str().expect("utf-8");
    let error = refused(
        &sample("sheet_l_hole_freecad.step"),
        &["--bend-table", file],
    );
    assert!(
        error.contains(file)
            && error.contains("inner radius 2.0000 mm is outside the table's 3 to 5 mm"),
        "{error}"
    );
    let (_keep, path) = table("thickness,inner_radius,angle,k\n2,2,90,0.4\n2,2,abc,0.4\n");
    let file = path.to_str().expect("utf-8");
    let error = refused(
        &sample("sheet_l_hole_freecad.step"),
        &["--bend-table", file],
    );
    assert!(
        error.contains(&format!("{file} line 3: `angle` is \"abc\"")),
        "{error}"
    );
}

#[test]
fn din_6935_gives_its_correction_factor_and_compensation() {
    // R/t = 1: k = 0.65 + 0.5 · log10(1) = 0.65; BA = π/2 · (2 + 0.65 · 2 / 2) = 4.1626;
    // β = 90°: v = BA − 2 · (R + t) = BA − 8.
    let (part, _) = flatten_sheet(
        &sample("sheet_l_hole_freecad.step"),
        &["--bend-rule", "din6935"],
    );
    let allowance = FRAC_PI_2 * (2.0 + 0.65);
    assert_size(&part, l_size(allowance));
    let rule = &part["sheet_metal"]["bends"][0]["rule"];
    assert_eq!(rule["kind"], "din6935");
    assert!((number(&rule["k"]) - 0.65).abs() < 1e-12, "{rule}");
    assert!(
        (number(&rule["compensation"]) - (allowance - 8.0)).abs() < 1e-9,
        "{rule}"
    );
    assert_eq!(part["sheet_metal"]["bend_rule"], "DIN 6935");
}

/// The `ADVANCED_FACE`s of a STEP file with whether each lies on a `PLANE`.
fn faces(step: &Path) -> Vec<(u64, bool)> {
    let text = std::fs::read_to_string(step).expect("the STEP file");
    let entity = |line: &str| -> Option<(u64, String)> {
        let (id, body) = line.trim().strip_prefix('#')?.split_once('=')?;
        Some((id.trim().parse().ok()?, body.trim().to_owned()))
    };
    let entities: Vec<(u64, String)> = text.lines().filter_map(entity).collect();
    let kind = |id: u64| {
        entities
            .iter()
            .find(|(other, _)| *other == id)
            .map(|(_, body)| body.clone())
            .unwrap_or_default()
    };
    entities
        .iter()
        .filter(|(_, body)| body.starts_with("ADVANCED_FACE"))
        .map(|(id, body)| {
            let surface = body
                .rsplit_once("),#")
                .and_then(|(_, rest)| rest.split(',').next())
                .and_then(|id| id.parse().ok())
                .expect("the face's surface");
            (*id, kind(surface).starts_with("PLANE"))
        })
        .collect()
}

#[test]
fn any_flange_face_can_be_the_base_face_and_the_others_are_refused() {
    let step = sample("sheet_l_hole_freecad.step");
    let size = l_size(quarter(2.0, 2.0, K));
    let mut accepted = Vec::new();
    for (id, planar) in faces(&step) {
        let id = id.to_string();
        let directory = tempfile::tempdir().expect("a temporary directory");
        let output = flatten_into(&step, directory.path(), &["--base-face", &id]);
        if output.status.success() {
            let part = read_report(directory.path())["parts"][0].clone();
            assert_size(&part, size);
            let base = part["sheet_metal"]["base_face"]
                .as_str()
                .expect("base face");
            assert!(base.starts_with(&format!("ADVANCED_FACE #{id} ")), "{base}");
            accepted.push(directions(&part)[0].clone());
        } else if planar {
            assert!(stderr(&output).contains("is a wall"), "{}", stderr(&output));
        } else {
            assert!(
                stderr(&output).contains("is not planar"),
                "{}",
                stderr(&output)
            );
        }
    }
    // Two flanges, two skins each; seen from the other skin the bend folds the other way.
    accepted.sort();
    assert_eq!(accepted, ["down", "down", "up", "up"]);
    let error = refused(&step, &["--base-face", "999999"]);
    assert!(error.contains("no ADVANCED_FACE #999999"), "{error}");
}

/// The report's parts of `input` flattened with `extra` arguments, expecting success.
fn report_parts(input: &Path, extra: &[&str]) -> Vec<serde_json::Value> {
    let directory = tempfile::tempdir().expect("a temporary directory");
    let output = flatten_into(input, directory.path(), extra);
    assert!(output.status.success(), "{input:?}: {}", stderr(&output));
    read_report(directory.path())["parts"]
        .as_array()
        .expect("parts")
        .clone()
}

#[test]
fn each_solid_of_a_multi_body_file_unfolds_on_its_own() {
    let step = sample("sheet_two_bodies_freecad.step");
    let parts = report_parts(&step, &[]);
    let names: Vec<&str> = parts
        .iter()
        .map(|part| part["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "sheet_two_bodies_freecad-1",
            "sheet_two_bodies_freecad-2",
            "sheet_two_bodies_freecad-3"
        ]
    );
    // The U and the L unfold as they do from files of their own; the L's size is also known.
    let alone = |name: &str| report_parts(&sample(name), &[])[0].clone();
    assert_size(&parts[0], flat_size(&alone("sheet_u_freecad.step")));
    assert_eq!(directions(&parts[0]).len(), 2);
    assert_size(&parts[1], l_size(quarter(2.0, 2.0, K)));
    assert_size(&parts[1], flat_size(&alone("sheet_l_hole_freecad.step")));
    // The cube is a block: flattened as a surface, saying why it is not unfolded.
    assert!(parts[2]["sheet_metal"].is_null(), "{}", parts[2]);
    let warnings = parts[2]["warnings"].to_string();
    assert!(
        warnings.contains("not unfolded as sheet metal"),
        "{warnings}"
    );

    // A base face applies to the solid holding it; the others unfold from their largest face.
    let (l_face, _) = (faces(&step).into_iter())
        .filter(|&(_, planar)| planar)
        .find(|&(id, _)| {
            let id = id.to_string();
            let directory = tempfile::tempdir().expect("a temporary directory");
            let output = flatten_into(&step, directory.path(), &["--base-face", &id]);
            output.status.success()
                && (read_report(directory.path())["parts"][1]["sheet_metal"]["base_face"].as_str())
                    .is_some_and(|base| base.starts_with(&format!("ADVANCED_FACE #{id} ")))
        })
        .expect("a face of the L that can be its base face");
    let parts = report_parts(&step, &["--base-face", &l_face.to_string()]);
    assert_size(&parts[0], flat_size(&alone("sheet_u_freecad.step")));
    assert_size(&parts[1], l_size(quarter(2.0, 2.0, K)));
    let error = refused(&step, &["--base-face", "999999"]);
    assert!(
        error.contains("no solid of the file has an ADVANCED_FACE #999999"),
        "{error}"
    );
}

#[test]
fn bend_zones_are_drawn_half_the_allowance_either_side_of_the_bend_line() {
    let allowance = quarter(2.0, 2.0, K);
    let (_, entities) = flatten_sheet(&sample("sheet_l_hole_freecad.step"), &["--bend-zones"]);
    let [line] = bend_line_positions(&entities)[..] else {
        panic!("one bend line");
    };
    let mut zones: Vec<f64> = entities
        .iter()
        .filter(|e| e.layer == "BEND_ZONE")
        .map(|e| {
            assert_eq!(e.kind, "LINE");
            e.points[0][0]
        })
        .collect();
    zones.sort_by(f64::total_cmp);
    assert_eq!(zones.len(), 2);
    assert!(
        (zones[0] - (line - allowance / 2.0)).abs() < 1e-9,
        "{zones:?}"
    );
    assert!(
        (zones[1] - (line + allowance / 2.0)).abs() < 1e-9,
        "{zones:?}"
    );
    let (_, plain) = flatten_sheet(&sample("sheet_l_hole_freecad.step"), &[]);
    assert!(plain.iter().all(|e| e.layer != "BEND_ZONE"));
}

/// Asserts that the part's label (TEXT on MARKS holding its name, `0.6 · height` per character)
/// stays clear of every bend line (bend lines run along y).
fn assert_label_clear_of_bends(entities: &[Entity], name: &str) {
    let label = entities
        .iter()
        .find(|e| e.layer == "MARKS" && e.text.starts_with(name))
        .expect("a label");
    let [x, _] = label.points[0];
    let width = label.text.chars().count() as f64 * label.height * 0.6;
    for line in bend_line_positions(entities) {
        assert!(
            line < x || line > x + width,
            "{name}: label [{x}, {}] across the bend line at {line}",
            x + width
        );
    }
}

#[test]
fn the_label_sits_inside_a_flange_never_across_a_bend_line() {
    for name in [
        "sheet_l_hole_freecad",
        "sheet_hat_freecad",
        "sheet_u_freecad",
    ] {
        let (_, entities) = flatten_sheet(&sample(&format!("{name}.step")), &[]);
        assert_label_clear_of_bends(&entities, name);
    }
}

/// The bracket part file with `side` (when given) set on its bent fold.
fn bracket(side: Option<&str>, directory: &Path) -> std::path::PathBuf {
    let text = std::fs::read_to_string(sample("bracket_fold.toml")).expect("the sample");
    let text = match side {
        Some(side) => text.replace(
            "bend_radius = 2.0",
            &format!("bend_radius = 2.0\nside = \"{side}\""),
        ),
        None => text,
    };
    let path = directory.join("bracket_fold.toml");
    std::fs::write(&path, text).expect("written");
    path
}

#[test]
fn a_part_files_bent_fold_takes_the_allowance_against_the_setback_of_its_side() {
    // Flanges 80 and 60 to the fold's sharp, R 2, t 2, 90°: flat = 140 − 2 · SB + BA, with
    // SB = (R + s) tan 45° for the side modelled (s = 0, t/2, t).
    let allowance = quarter(2.0, 2.0, K);
    let directory = tempfile::tempdir().expect("a temporary directory");
    for (side, depth) in [(None, 1.0), (Some("inside"), 0.0), (Some("outside"), 2.0)] {
        let (part, entities) = flatten_sheet(&bracket(side, directory.path()), &[]);
        let setback = 2.0 + depth;
        let width = 140.0 - 2.0 * setback + allowance;
        assert_size(&part, [width, 100.0]);
        let [line] = bend_line_positions(&entities)[..] else {
            panic!("one bend line");
        };
        // The bend line: half the allowance past the 60 mm flange's flat part.
        let from_end = line.min(width - line);
        assert!(
            (from_end - (60.0 - setback + allowance / 2.0)).abs() < FLAT_TOLERANCE_MM,
            "{side:?}: {line}"
        );
        assert!(entities.iter().any(|e| e.layer == "BEND_DOWN"));
        assert!(entities.iter().all(|e| e.layer != "FOLD"));
        assert_label_clear_of_bends(&entities, "bracket_fold");
    }
    let (part, _) = flatten_sheet(
        &bracket(None, directory.path()),
        &["--bend-rule", "din6935"],
    );
    assert_size(&part, [140.0 - 6.0 + FRAC_PI_2 * (2.0 + 0.65), 100.0]);
}

#[test]
fn a_bend_radius_off_a_polygon_edge_or_without_thickness_is_refused() {
    let directory = tempfile::tempdir().expect("a temporary directory");
    let text = std::fs::read_to_string(sample("bracket_fold.toml")).expect("the sample");
    let cases = [
        (
            text.replace("thickness = 2.0\n", ""),
            "a bend needs the part's `thickness`",
        ),
        (
            text.replace(
                "between = [0, 1]",
                "surface = 0\npoints = [[0.0, 10.0], [100.0, 10.0]]",
            ),
            "give 'between = [a, b]'",
        ),
    ];
    for (text, expected) in cases {
        let path = directory.path().join("bent.toml");
        std::fs::write(&path, text).expect("written");
        let error = refused(&path, &[]);
        assert!(
            error.contains(expected) && error.contains("fold_line[0]"),
            "{error}"
        );
    }
}

/// A part file of three rectangular polygons, 30 wide, joined by two folds of bend radius 2 (mid
/// surface, t 2): the first flange in z = 0 up to x = 40, a web in x = 40 up to z = `height`,
/// the last flange from the web's top towards `+x` (a Z) or, for a U, back towards `−x`.
fn three_flanges(directory: &Path, name: &str, last_towards_plus_x: bool) -> std::path::PathBuf {
    let end = if last_towards_plus_x { 80 } else { 0 };
    let text = format!(
        "name = \"{name}\"\nthickness = 2.0\n\n\
         [[surface]]\nkind = \"polygon\"\npoints = [[0, 0, 0], [40, 0, 0], [40, 30, 0], [0, 30, 0]]\n\n\
         [[surface]]\nkind = \"polygon\"\npoints = [[40, 0, 0], [40, 0, 30], [40, 30, 30], [40, 30, 0]]\n\n\
         [[surface]]\nkind = \"polygon\"\npoints = [[40, 0, 30], [{end}, 0, 30], [{end}, 30, 30], [40, 30, 30]]\n\n\
         [[fold_line]]\nbetween = [0, 1]\nbend_radius = 2.0\n\n\
         [[fold_line]]\nbetween = [1, 2]\nbend_radius = 2.0\n"
    );
    let path = directory.join(format!("{name}.toml"));
    std::fs::write(&path, text).expect("written");
    path
}

#[test]
fn part_file_z_and_u_bend_both_ways_and_the_same_way() {
    // Flanges 40, 30, 40 to the sharps, SB = (2 + 1) tan 45° = 3: 110 − 4 · 3 + 2 BA.
    let allowance = quarter(2.0, 2.0, K);
    let directory = tempfile::tempdir().expect("a temporary directory");
    let (z, _) = flatten_sheet(&three_flanges(directory.path(), "zpart", true), &[]);
    assert_size(&z, [110.0 - 12.0 + 2.0 * allowance, 30.0]);
    assert_eq!(directions(&z), ["down", "up"]);
    let (u, _) = flatten_sheet(&three_flanges(directory.path(), "upart", false), &[]);
    assert_size(&u, [110.0 - 12.0 + 2.0 * allowance, 30.0]);
    let mut both = directions(&u);
    both.dedup();
    assert_eq!(both.len(), 1, "a U bends twice the same way");
}
