//! CAD surfaces in, end to end through the library: part files and STEP files tessellated,
//! flattened and measured against their analytic developments and areas.

use std::f64::consts::{PI, TAU};
use std::path::{Path, PathBuf};

use glam::DVec2;

use flatcut::flatten::fold_lines::fold_line_lengths;
use flatcut::pipeline::{PartJob, PartResult, RunOptions, flatten_part, load_parts};
use flatcut::progress::NoProgress;

/// Tessellated areas must be within this fraction of the analytic area.
const AREA_TOLERANCE: f64 = 1e-3;
/// Developable parts must flatten with E_S and E_C below this.
const DEVELOPABLE_TOLERANCE: f64 = 1e-5;
/// The flat outline must match the analytic development within this (mm).
const OUTLINE_TOLERANCE: f64 = 0.05;

fn sample(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("samples")
        .join(name)
}

fn flatten_sample(name: &str) -> Vec<PartResult> {
    let options = RunOptions::default();
    load_parts(&sample(name), &options)
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .into_iter()
        .map(|job| flatten_part(job, &options, &NoProgress).expect("flattens"))
        .collect()
}

fn assert_isometric(result: &PartResult) {
    let accuracy = result.flattened.stats.accuracy;
    assert!(
        accuracy.area_error <= DEVELOPABLE_TOLERANCE
            && accuracy.shape_error <= DEVELOPABLE_TOLERANCE,
        "{}: E_S {} E_C {}",
        result.job.name,
        accuracy.area_error,
        accuracy.shape_error
    );
}

fn assert_area(result: &PartResult, analytic: f64) {
    let area = result.job.model.area();
    assert!(
        (area - analytic).abs() / analytic <= AREA_TOLERANCE,
        "{}: area {area} vs analytic {analytic}",
        result.job.name
    );
}

/// The circle through three points.
fn circle_centre(a: DVec2, b: DVec2, c: DVec2) -> DVec2 {
    let d = 2.0 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
    let (a2, b2, c2) = (a.length_squared(), b.length_squared(), c.length_squared());
    DVec2::new(
        (a2 * (b.y - c.y) + b2 * (c.y - a.y) + c2 * (a.y - b.y)) / d,
        (a2 * (c.x - b.x) + b2 * (a.x - c.x) + c2 * (b.x - a.x)) / d,
    )
}

#[test]
fn cone_frustum_develops_into_its_annular_sector() {
    let results = flatten_sample("cone_frustum.toml");
    let result = &results[0];
    assert_isometric(result);
    let (bottom, top, height) = (100.0_f64, 50.0_f64, 80.0_f64);
    let slant = ((bottom - top).powi(2) + height * height).sqrt();
    assert_area(result, PI * (bottom + top) * slant);
    // The flat images of the bottom rim (z = 0) and the top rim (z = height).
    let model = &result.job.model;
    let flat = &result.flattened.positions;
    let rim = |z: f64| -> Vec<DVec2> {
        (0..model.vertex_count())
            .filter(|&v| (model.positions()[v].z - z).abs() < 1e-9)
            .map(|v| flat[v])
            .collect()
    };
    let (outer, inner) = (rim(0.0), rim(height));
    let centre = circle_centre(outer[0], outer[outer.len() / 3], outer[2 * outer.len() / 3]);
    let sine = (bottom - top) / slant;
    for (points, radius) in [(&outer, bottom / sine), (&inner, top / sine)] {
        for p in points.iter() {
            assert!(
                (p.distance(centre) - radius).abs() <= OUTLINE_TOLERANCE,
                "a rim point is {} from the apex, the development says {radius}",
                p.distance(centre)
            );
        }
    }
    // The sector angle 2π sin(a), from the seam's two copies of the bottom rim's start. Pinned
    // at one seam end, the other seam end is off the development by the whole angular deficit of
    // the inscribed rim polygon times the development radius; compared after the best rotation
    // about the apex, each end is off by half of it.
    let angles: Vec<f64> = outer.iter().map(|p| (*p - centre).to_angle()).collect();
    let spread = sector_angle(&angles);
    let pinned_error = (spread - TAU * sine).abs() * bottom / sine;
    assert!(
        pinned_error <= OUTLINE_TOLERANCE,
        "with one seam end pinned the other is {pinned_error} mm off the development"
    );
    assert!(0.5 * pinned_error <= OUTLINE_TOLERANCE);
    // Independently, from the flat points themselves: rotate the pattern about the apex so that
    // the rim point at one seam end lies on its analytic position, and measure how far the rim
    // point at the other seam end is from its own.
    let mut order: Vec<usize> = (0..outer.len()).collect();
    order.sort_by(|&a, &b| angles[a].total_cmp(&angles[b]));
    let gap_before = |k: usize| {
        (angles[order[k]] - angles[order[(k + order.len() - 1) % order.len()]]).rem_euclid(TAU)
    };
    let first = (0..order.len())
        .max_by(|&a, &b| gap_before(a).total_cmp(&gap_before(b)))
        .expect("rim points");
    let (start, end) = (
        outer[order[first]] - centre,
        outer[order[(first + order.len() - 1) % order.len()]] - centre,
    );
    let pinned = DVec2::from_angle(start.to_angle()).rotate(DVec2::new(bottom / sine, 0.0));
    let analytic_end = DVec2::from_angle(TAU * sine).rotate(pinned);
    let pinned_end = DVec2::from_angle(start.angle_to(pinned)).rotate(end);
    assert!(
        pinned_end.distance(analytic_end) <= OUTLINE_TOLERANCE,
        "pinned at one seam end, the other is {} mm off the development",
        pinned_end.distance(analytic_end)
    );
}

/// The angle a set of directions spans (they cover less than a full turn).
fn sector_angle(angles: &[f64]) -> f64 {
    let mut sorted = angles.to_vec();
    sorted.sort_by(f64::total_cmp);
    let largest_gap = sorted
        .windows(2)
        .map(|w| w[1] - w[0])
        .chain(std::iter::once(sorted[0] + TAU - sorted[sorted.len() - 1]))
        .fold(0.0, f64::max);
    TAU - largest_gap
}

#[test]
fn cylinder_panel_is_isometric_with_its_area() {
    let results = flatten_sample("cylinder_panel.toml");
    assert_isometric(&results[0]);
    assert_area(&results[0], 150.0 * TAU / 3.0 * 200.0);
}

#[test]
fn a_grain_direction_turns_the_pattern_and_is_drawn_along_it() {
    // The panel's grain runs along the cylinder's axis: the pattern is its development, a
    // 200 mm (axis, now x) by 150 · 2π/3 mm (arc, now y) rectangle with the grain line along x.
    let result = &flatten_sample("cylinder_panel.toml")[0];
    let flat = &result.flattened.positions;
    let size = flat.iter().fold(DVec2::ZERO, |size, &p| size.max(p));
    assert!(flat.iter().all(|p| p.min_element() >= 0.0));
    assert!((size.x - 200.0).abs() < 1e-6, "{size}");
    // The arc side is the development of the inscribed polygon: short by its chords' sag.
    assert!((size.y - 100.0 * PI).abs() < OUTLINE_TOLERANCE, "{size}");
    let drawing = &result.pattern.drawing;
    let [tail, head] = drawing.grain.expect("a grain line");
    assert!(
        (head.y - tail.y).abs() < 1e-9 && head.x > tail.x,
        "{tail} {head}"
    );
    assert!((head.x - tail.x - 100.0).abs() < 1e-6, "{tail} {head}");
    assert_eq!(drawing.material, None);
}

#[test]
fn a_part_without_grain_lies_along_its_smallest_bounding_rectangle() {
    // The garment panel is a square-ish sheet: its pattern comes out axis-aligned, not turned.
    let result = &flatten_sample("garment_panel.toml")[0];
    let flat = &result.flattened.positions;
    let size = flat.iter().fold(DVec2::ZERO, |size, &p| size.max(p));
    let area = result.job.model.area();
    assert!(size.x * size.y < 1.02 * area, "{size} around {area}");
    assert_eq!(result.pattern.drawing.material.as_deref(), Some("wool"));
}

/// Area of the exact square-to-round: four plane triangles and four oblique quarter cones
/// (each integrated finely).
fn square_to_round_area(half_side: f64, radius: f64, height: f64) -> f64 {
    let triangle = 2.0 * half_side * ((half_side - radius).powi(2) + height * height).sqrt() / 2.0;
    let steps = 100_000;
    let corner = glam::DVec3::new(half_side, -half_side, 0.0);
    let point = |t: f64| {
        let angle = -PI / 2.0 + t * PI / 2.0;
        glam::DVec3::new(radius * angle.cos(), radius * angle.sin(), height)
    };
    let cone: f64 = (0..steps)
        .map(|k| {
            let (a, b) = (
                point(k as f64 / steps as f64),
                point((k + 1) as f64 / steps as f64),
            );
            0.5 * (a - corner).cross(b - corner).length()
        })
        .sum();
    4.0 * (triangle + cone)
}

#[test]
fn square_to_round_is_isometric_with_its_area() {
    let results = flatten_sample("square_to_round.toml");
    assert_isometric(&results[0]);
    // The cone fans are graded towards the square's corners, and so are the square's sides in
    // the plane triangles next to them (gaps growing by 1.2 from the fan's first ruling gap):
    // the worst angle is 25.0° at the default size.
    let worst = results[0]
        .job
        .tessellation
        .expect("a part file has tessellation figures")
        .minimum_angle;
    assert!(worst >= 20.0, "worst angle {worst}");
    assert_area(&results[0], square_to_round_area(100.0, 60.0, 150.0));
}

#[test]
fn both_elbow_pieces_are_isometric() {
    let results = flatten_sample("elbow_two_piece.toml");
    assert_eq!(results.len(), 2);
    for result in &results {
        assert_isometric(result);
        // A cylinder cut at 45° at its top: the mean height stays 100.
        assert_area(result, TAU * 50.0 * 100.0);
    }
}

#[test]
fn eccentric_round_to_round_and_offset_rectangles_are_isometric() {
    for name in [
        "round_to_round_eccentric.toml",
        "rectangle_offset_transition.toml",
    ] {
        let results = flatten_sample(name);
        assert_isometric(&results[0]);
    }
}

#[test]
fn dome_has_the_area_of_its_spherical_cap() {
    let options = RunOptions::default();
    let jobs = load_parts(&sample("dome.toml"), &options).expect("loads");
    let (radius, cap_height) = (120.0, 60.0);
    let area = jobs[0].model.area();
    let analytic = TAU * radius * cap_height;
    assert!(
        (area - analytic).abs() / analytic <= AREA_TOLERANCE,
        "{area} vs {analytic}"
    );
}

#[test]
fn a_stiff_fold_line_keeps_its_length_better_than_a_uniform_one() {
    let stiff = &flatten_sample("garment_panel.toml")[0];
    let uniform = &flatten_sample("garment_panel_uniform.toml")[0];
    let error = |result: &PartResult| {
        fold_line_lengths(&result.job.model, &result.flattened.positions, 1)[0].error
    };
    // The target is 0.05 % with factor 10. At the converged energy minimum the sample's
    // 12 mm band gives 0.055 % (a 24 mm band 0.048 %, factor 100 0.0095 %): missed and reported.
    assert!(error(stiff) <= 6e-4, "fold error {}", error(stiff));
    assert!(
        error(stiff) < error(uniform),
        "{} vs {}",
        error(stiff),
        error(uniform)
    );
}

#[test]
fn step_samples_ingest_tessellate_and_flatten() {
    for name in [
        "cone_frustum_half.step",
        "bspline_patch.step",
        "cone_frustum_freecad.step",
        "bspline_loft_freecad.step",
    ] {
        let results = flatten_sample(name);
        assert!(!results.is_empty(), "{name}");
        for result in &results {
            let accuracy = result.flattened.stats.accuracy;
            assert!(
                accuracy.area_error < 0.01 && accuracy.shape_error < 0.01,
                "{name}: {accuracy:?}"
            );
        }
    }
}

#[test]
fn step_units_are_converted_to_millimetres() {
    let jobs =
        load_parts(&sample("cone_frustum_half.step"), &RunOptions::default()).expect("loads");
    // The file is in inches: a 4 in bottom radius is 101.6 mm.
    let largest = jobs[0]
        .model
        .positions()
        .iter()
        .map(|p| p.truncate().length())
        .fold(0.0, f64::max);
    assert!((largest - 101.6).abs() < 0.5, "{largest}");
}

/// Loads STEP text written to a temporary file.
fn load_step_text(text: &str) -> Vec<flatcut::pipeline::PartJob> {
    let directory = tempfile::tempdir().expect("temporary directory");
    let path = directory.path().join("part.step");
    std::fs::write(&path, text).expect("writes");
    load_parts(&path, &RunOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// Loads STEP bytes written to a temporary file named `name`.
fn load_step_bytes(name: &str, bytes: &[u8]) -> Vec<flatcut::pipeline::PartJob> {
    let directory = tempfile::tempdir().expect("temporary directory");
    let path = directory.path().join(name);
    std::fs::write(&path, bytes).expect("writes");
    load_parts(&path, &RunOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn step_files_in_iso_8859_1_or_utf_8_and_opening_with_a_comment_read_as_the_plain_file() {
    let plain = std::fs::read_to_string(sample("cone_frustum_freecad.step")).expect("sample");
    let reference = load_step_text(&plain);
    let named = |name: &str| {
        plain
            .replacen("'Open CASCADE STEP translator 7.6 1'", name, 1)
            .replacen("'FreeCAD Model'", "'Modèle ☃'", 1)
    };
    assert_ne!(
        named("'x'"),
        plain,
        "the sample's names are where the test expects"
    );
    let mut latin = b"/* written by hand, with a comment before the keyword */\r\n".to_vec();
    latin.extend(named("'Pi\0ce'").bytes());
    let marker = latin.iter().position(|&b| b == 0).expect("marker");
    latin[marker] = 0xE8; // è in ISO 8859-1
    assert!(
        std::str::from_utf8(&latin).is_err(),
        "not UTF-8: raw ISO 8859-1 bytes"
    );
    for (name, bytes) in [
        ("latin.step", latin),
        ("utf8.dat", named("'Pièce développée'").into_bytes()),
    ] {
        let jobs = load_step_bytes(name, &bytes);
        assert_eq!(jobs.len(), reference.len(), "{name}");
        for (job, expected) in jobs.iter().zip(&reference) {
            assert_eq!(job.model.positions(), expected.model.positions(), "{name}");
            assert_eq!(job.model.triangles(), expected.model.triangles(), "{name}");
        }
    }
}

#[test]
fn cone_angles_in_degrees_and_the_units_of_the_solids_own_context_are_honoured() {
    let inch = std::fs::read_to_string(sample("cone_frustum_half.step")).expect("sample");
    let area = |text: &str| load_step_text(text)[0].model.area();
    let reference = area(&inch);
    // CATIA V4 writes cone semi-angles in degrees when its context's angle unit is the degree.
    let degrees = inch
        .replace(
            "#56 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );",
            "#56 = ( CONVERSION_BASED_UNIT('DEGREE',#59) NAMED_UNIT(#52) PLANE_ANGLE_UNIT() );\n\
             #59 = PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.0174532925),#61);\n\
             #61 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );",
        )
        .replace("4.,0.558599315343562);", "4.,32.0053832080835);");
    assert_ne!(degrees, inch);
    let in_degrees = area(&degrees);
    assert!(
        (in_degrees - reference).abs() <= 1e-6 * reference,
        "{in_degrees} vs {reference}"
    );
    // Autodesk Inventor writes an inch context beside the millimetre context of its solids.
    let millimetres = inch
        .replace(
            "GLOBAL_UNIT_ASSIGNED_CONTEXT((#51,#56,#57))",
            "GLOBAL_UNIT_ASSIGNED_CONTEXT((#54,#56,#57))",
        )
        .replace(
            "#50 = ",
            "#70 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#51,#56,#57)) \
             REPRESENTATION_CONTEXT('inch','3D') );\n#71 = SHAPE_REPRESENTATION('',(#4),#70);\n#50 = ",
        );
    let in_millimetres = area(&millimetres);
    let expected = reference / (25.4 * 25.4);
    assert!(
        (in_millimetres - expected).abs() <= 1e-6 * expected,
        "{in_millimetres} vs {expected}"
    );
}

#[test]
fn unsupported_step_content_is_named() {
    let error = load_parts(
        &sample("unsupported_offset_surface.step"),
        &RunOptions::default(),
    )
    .expect_err("an offset surface cannot be read");
    assert!(
        error
            .to_string()
            .contains("ADVANCED_FACE #46 on OFFSET_SURFACE (#5)"),
        "{error}"
    );
}

/// Writes the STEP `text` to a temporary file, flattens it with the CLI, checks that it exits 1 and returns its stderr.
fn step_text_error(text: &str) -> String {
    let output = flatten_text_as("part.step", text);
    let message = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(1), "{message}");
    message
}

/// Writes `text` to a file called `name` in a temporary directory and flattens it with the CLI.
fn flatten_text_as(name: &str, text: &str) -> std::process::Output {
    let directory = tempfile::tempdir().expect("temporary directory");
    let path = directory.path().join(name);
    std::fs::write(&path, text).expect("writes");
    flatcut(&[
        "flatten",
        path.to_str().expect("utf-8"),
        "-o",
        directory.path().join("out").to_str().expect("utf-8"),
    ])
}

/// Flattens the part file `text` with the CLI and checks that it exits 1 with `expected` (the
/// file, line and field) on stderr.
fn assert_part_text_exits_1_naming(text: &str, expected: &str) {
    let output = flatten_text_as("part.toml", text);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(expected), "{stderr}");
}

#[test]
fn a_face_on_an_unsupported_surface_and_a_file_without_surfaces_exit_1_naming_why() {
    let cone = std::fs::read_to_string(sample("cone_frustum_half.step")).expect("sample");
    let trimmed = cone.replace(
        "#5 = CONICAL_SURFACE(",
        "#5 = RECTANGULAR_TRIMMED_SURFACE('',#6,0.,6.28,0.,4.,.T.,.T.);\n#6 = CONICAL_SURFACE(",
    );
    assert_ne!(trimmed, cone);
    let message = step_text_error(&trimmed);
    assert!(
        message.contains("ADVANCED_FACE #46 on RECTANGULAR_TRIMMED_SURFACE (#5)"),
        "{message}"
    );
    // Named before truck-stepio is called, which would print a lookup failure of its own.
    assert!(!message.contains("Lookup failed"), "{message}");
    let points_only = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('points'),'2;1');\n\
        FILE_NAME('p.step','2026-11-22T00:00:00',(''),(''),'','','');\n\
        FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n\
        #1 = CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n";
    let message = step_text_error(points_only);
    assert!(
        message.contains("no shell, face or B-spline surface"),
        "{message}"
    );
}

#[test]
fn a_trimmed_edge_curve_is_read_as_its_basis_and_an_unreadable_one_is_named() {
    let cone = std::fs::read_to_string(sample("cone_frustum_half.step")).expect("sample");
    let with_curve = |curve: &str| {
        cone.replace(
            "#32 = LINE('',#12,#31);",
            &format!("#32 = {curve};\n#38 = LINE('',#12,#31);"),
        )
    };
    let reference = load_step_text(&cone)[0].model.area();
    let trimmed = load_step_text(&with_curve(
        "TRIMMED_CURVE('',#38,(#12),(#15),.T.,.CARTESIAN.)",
    ))[0]
        .model
        .area();
    assert!((trimmed - reference).abs() <= 1e-9 * reference, "{trimmed}");
    let message = step_text_error(&with_curve("OFFSET_CURVE_3D('',#38,1.,.F.,#30)"));
    assert!(
        message.contains("ADVANCED_FACE #46 on CONICAL_SURFACE (#5): edge EDGE_CURVE #33 on OFFSET_CURVE_3D (#32)"),
        "{message}"
    );
    // Named before truck-stepio is called, which would print a lookup failure of its own.
    assert!(!message.contains("Lookup failed"), "{message}");
}

/// A SolidWorks 2018 export (`samples/base_interface_solidworks.step`, from trimesh, MIT): a
/// 3/16 in plate with holes and slots, in inches through an inch context. Open CASCADE (FreeCAD
/// 0.20, `Part.read(path).Area`) integrates 541917.241 mm². Its long plate edges meet the short
/// pieces of small holes' edges at shared vertices: before edges were graded there, the side
/// faces had 4.1° slivers at those corners. (The whole solid's tessellation: the pipeline
/// unfolds this plate as sheet metal, its part is one skin, see `tests/integration/sheet_metal.rs`.)
#[test]
fn a_solidworks_plate_keeps_its_area_units_and_graded_corners() {
    use flatcut::ingest::{Input, read_input};
    use flatcut::pipeline::tessellate_step;
    let path = sample("base_interface_solidworks.step");
    let Ok(Input::Step(brep)) = read_input(&path, Default::default()) else {
        panic!("read as STEP");
    };
    let tessellation = tessellate_step(&path, &brep, &Default::default()).expect("tessellates");
    let validated = flatcut::mesh::validate(tessellation.soup()).expect("a valid mesh");
    assert_eq!(validated.components.len(), 1, "one closed solid");
    let model = &validated.components[0];
    let area = model.area();
    let reference = 541917.241;
    assert!(
        (area - reference).abs() / reference <= AREA_TOLERANCE,
        "area {area} vs {reference}"
    );
    let largest = model
        .positions()
        .iter()
        .map(|p| p.x.abs())
        .fold(0.0, f64::max);
    assert!((largest - 11.7994561 * 25.4).abs() < 0.01, "{largest}");
    let angle = tessellation.figures.minimum_angle;
    assert!(angle >= 7.0, "worst angle {angle}");
}

/// A sphere of radius 50 split into two half-sphere lunes, each bounded by two meridians from
/// pole to pole (the layout CATIA V4 writes): not meshed yet, so an error naming the face.
const SPHERE_LUNES: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('lunes'),'2;1');\n\
    FILE_NAME('lunes.step','2026-11-22T00:00:00',(''),(''),'','','');\n\
    FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n\
    #1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=DIRECTION('',(0.,0.,1.));\n#3=DIRECTION('',(1.,0.,0.));\n\
    #4=AXIS2_PLACEMENT_3D('',#1,#2,#3);\n#5=SPHERICAL_SURFACE('',#4,50.);\n\
    #6=CARTESIAN_POINT('',(0.,0.,50.));\n#7=VERTEX_POINT('',#6);\n\
    #8=CARTESIAN_POINT('',(0.,0.,-50.));\n#9=VERTEX_POINT('',#8);\n\
    #10=DIRECTION('',(0.,1.,0.));\n#11=AXIS2_PLACEMENT_3D('',#1,#10,#2);\n#12=CIRCLE('',#11,50.);\n\
    #13=DIRECTION('',(0.,-1.,0.));\n#14=AXIS2_PLACEMENT_3D('',#1,#13,#2);\n#15=CIRCLE('',#14,50.);\n\
    #16=EDGE_CURVE('',#7,#9,#12,.T.);\n#17=EDGE_CURVE('',#7,#9,#15,.T.);\n\
    #18=ORIENTED_EDGE('',*,*,#16,.T.);\n#19=ORIENTED_EDGE('',*,*,#17,.F.);\n\
    #20=EDGE_LOOP('',(#18,#19));\n#21=FACE_OUTER_BOUND('',#20,.T.);\n#22=ADVANCED_FACE('',(#21),#5,.T.);\n\
    #23=ORIENTED_EDGE('',*,*,#17,.T.);\n#24=ORIENTED_EDGE('',*,*,#16,.F.);\n\
    #25=EDGE_LOOP('',(#23,#24));\n#26=FACE_OUTER_BOUND('',#25,.T.);\n#27=ADVANCED_FACE('',(#26),#5,.T.);\n\
    #28=CLOSED_SHELL('',(#22,#27));\n#29=MANIFOLD_SOLID_BREP('',#28);\n\
    #30=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n\
    #31=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#30))REPRESENTATION_CONTEXT('',''));\n\
    #32=ADVANCED_BREP_SHAPE_REPRESENTATION('',(#29),#31);\nENDSEC;\nEND-ISO-10303-21;\n";

#[test]
fn a_sphere_split_into_lunes_is_an_error_naming_the_face() {
    let message = step_text_error(SPHERE_LUNES);
    assert!(
        message.contains("shell #28, ADVANCED_FACE #22 on SPHERICAL_SURFACE (#5)")
            && message.contains("both poles"),
        "{message}"
    );
}

/// Smallest triangle angle STEP faces must keep where their domains allow it, degrees.
const STEP_MINIMUM_ANGLE: f64 = 20.0;

/// STEP samples FreeCAD 0.20 (Open CASCADE) wrote, with the areas Open CASCADE integrates for
/// them (printed by `samples/step-sources/freecad_samples.py`), mm².
const FREECAD_SAMPLES: [(&str, f64); 4] = [
    ("cone_frustum_freecad.step", 44456.588728),
    ("bspline_loft_freecad.step", 32767.552169),
    ("box_fillet_pocket_inch.step", 34952.113572),
    // 2 × 156 + 160 × 60 for the L, 784 + 56√2 − 112 for the gusset: its triangular faces came
    // out with zero-area slivers along their sides before they were flipped or peeled off.
    ("gusset_bracket_freecad.step", 10663.195959),
];

#[test]
fn freecad_step_faces_keep_their_area_and_angles() {
    for (name, reference) in FREECAD_SAMPLES {
        let jobs = load_parts(&sample(name), &RunOptions::default()).expect("loads");
        assert_eq!(jobs.len(), 1, "{name}: one connected part");
        let job = &jobs[0];
        let area = job.model.area();
        assert!(
            (area - reference).abs() / reference <= AREA_TOLERANCE,
            "{name}: area {area} vs {reference}"
        );
        let angle = job.tessellation.expect("figures").minimum_angle;
        assert!(angle >= STEP_MINIMUM_ANGLE, "{name}: worst angle {angle}");
    }
}

/// FreeCAD STEP samples on surfaces of revolution, with Open CASCADE's areas (mm²) and the worst
/// angle each must reach: a hemisphere and a full sphere and spheroid (their poles meshed in the
/// polar map), a quarter torus and a revolved B-spline profile (in Mercator coordinates) and a
/// cone through its apex (its seam graded toward the apex) all reach 20°.
const REVOLUTION_SAMPLES: [(&str, f64, f64); 6] = [
    ("hemisphere_freecad.step", 40212.385966, STEP_MINIMUM_ANGLE),
    (
        "torus_quarter_freecad.step",
        24674.011003,
        STEP_MINIMUM_ANGLE,
    ),
    ("cone_apex_freecad.step", 33291.904316, STEP_MINIMUM_ANGLE),
    (
        "vase_revolved_freecad.step",
        74115.845005,
        STEP_MINIMUM_ANGLE,
    ),
    ("sphere_freecad.step", 31415.926536, STEP_MINIMUM_ANGLE),
    ("spheroid_freecad.step", 11136.124110, STEP_MINIMUM_ANGLE),
];

#[test]
fn step_faces_on_surfaces_of_revolution_keep_their_area() {
    for (name, reference, minimum_angle) in REVOLUTION_SAMPLES {
        let jobs = load_parts(&sample(name), &RunOptions::default()).expect("loads");
        assert_eq!(jobs.len(), 1, "{name}: one connected part");
        let area = jobs[0].model.area();
        assert!(
            (area - reference).abs() / reference <= AREA_TOLERANCE,
            "{name}: area {area} vs {reference}"
        );
        let angle = jobs[0].tessellation.expect("figures").minimum_angle;
        assert!(angle >= minimum_angle, "{name}: worst angle {angle}");
    }
}

#[test]
fn a_hemisphere_is_one_disk_through_its_pole() {
    let jobs =
        load_parts(&sample("hemisphere_freecad.step"), &RunOptions::default()).expect("loads");
    let model = &jobs[0].model;
    // The seam through the pole is meshed across: one boundary loop, the equator.
    assert_eq!(model.boundary_loops().len(), 1);
    // The mesh covers the pole (within the chord: the default is 0.024 mm here).
    let top = model.positions().iter().map(|p| p.z).fold(0.0, f64::max);
    assert!(
        (top - 80.0).abs() < 0.03,
        "the mesh stops short of the pole: {top}"
    );
}

#[test]
fn a_full_sphere_bounded_by_a_vertex_loop_is_one_closed_surface() {
    // FreeCAD writes a whole sphere as one face bounded by a VERTEX_LOOP only (no edge).
    let jobs = load_parts(&sample("sphere_freecad.step"), &RunOptions::default()).expect("loads");
    assert_eq!(jobs.len(), 1);
    let model = &jobs[0].model;
    assert!(
        model.boundary_loops().is_empty(),
        "the two caps weld into a closed surface"
    );
    // Every vertex is on the sphere (radius 50 mm about the origin).
    let worst = model
        .positions()
        .iter()
        .map(|p| (p.length() - 50.0).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-9, "a vertex is {worst} mm off the sphere");
    // Both poles are covered (within the chord, 0.01 mm here).
    let (low, high) = model
        .positions()
        .iter()
        .fold((0.0_f64, 0.0_f64), |(l, h), p| (l.min(p.z), h.max(p.z)));
    assert!(low < -49.99 && high > 49.99, "z from {low} to {high}");
}

#[test]
fn a_closed_cone_side_face_becomes_a_ring_and_flattens_to_its_area() {
    let jobs =
        load_parts(&sample("cone_frustum_freecad.step"), &RunOptions::default()).expect("loads");
    let model = &jobs[0].model;
    // The seam edge is welded: the side face is a ring with its two rims as boundaries.
    assert_eq!(model.boundary_loops().len(), 2);
    let (bottom, top, height) = (100.0_f64, 50.0_f64, 80.0_f64);
    let slant = ((bottom - top).powi(2) + height * height).sqrt();
    let analytic = PI * (bottom + top) * slant;
    let results = flatten_sample("cone_frustum_freecad.step");
    let result = &results[0];
    assert_eq!(
        result.seams.len(),
        1,
        "the automatic seam opens the ring once"
    );
    assert_area(result, analytic);
    let accuracy = result.flattened.stats.accuracy;
    assert!(
        accuracy.area_error < 1e-3 && accuracy.shape_error < 1e-3,
        "{accuracy:?}"
    );
}

#[test]
fn a_solid_in_inches_is_a_closed_surface_in_millimetres() {
    let jobs = load_parts(
        &sample("box_fillet_pocket_inch.step"),
        &RunOptions::default(),
    )
    .expect("loads");
    let model = &jobs[0].model;
    assert!(
        model.is_closed(),
        "the solid's faces weld into a closed surface"
    );
    let (low, high) = model.positions().iter().fold(
        (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY),
        |(low, high), &p| (low.min(p), high.max(p)),
    );
    // A 4 x 3 x 2 in box.
    let extent = high - low;
    for (measured, inches) in [(extent.x, 4.0), (extent.y, 3.0), (extent.z, 2.0)] {
        assert!((measured - 25.4 * inches).abs() < 1e-6, "{extent}");
    }
}

#[test]
fn the_mesh_size_applies_to_step_faces() {
    let mean_edge = |mesh_size: f64| {
        let mut options = RunOptions::default();
        options.tessellate.mesh_size = Some(mesh_size);
        options.tessellate.chord = Some(0.5);
        let jobs = load_parts(&sample("cone_frustum_freecad.step"), &options).expect("loads");
        let model = &jobs[0].model;
        let total: f64 = model
            .edges()
            .iter()
            .map(|e| model.positions()[e[0] as usize].distance(model.positions()[e[1] as usize]))
            .sum();
        total / model.edges().len() as f64
    };
    for mesh_size in [5.0, 10.0] {
        let mean = mean_edge(mesh_size);
        assert!(
            mean > 0.6 * mesh_size && mean < 1.2 * mesh_size,
            "mesh size {mesh_size}: mean edge {mean}"
        );
    }
}

#[test]
fn bad_part_files_name_the_file_line_and_field() {
    let bad = sample("bad");
    let mut checked = 0;
    let mut entries: Vec<PathBuf> = std::fs::read_dir(&bad)
        .expect("samples/bad exists")
        .map(|e| e.expect("entry").path())
        .collect();
    entries.sort();
    for path in entries {
        let error = load_parts(&path, &RunOptions::default()).expect_err("bad file rejected");
        let text = error.to_string();
        let file = path.file_name().and_then(|f| f.to_str()).expect("name");
        assert!(text.contains(file), "{text}");
        assert!(text.contains("field '"), "{text}");
        assert!(text.contains(".toml:"), "{text}");
        checked += 1;
    }
    assert!(checked >= 6);
}

/// Regenerates the STEP samples written with truck-stepio's writer:
/// `cargo test --test cad -- --ignored regenerate_step_samples`.
#[test]
#[ignore = "regenerates samples/bspline_patch.step"]
fn regenerate_step_samples() {
    use truck_modeling::*;
    let curve = |points: [[f64; 3]; 4]| {
        let points = points.map(|p| Point3::new(p[0], p[1], p[2])).to_vec();
        BSplineCurve::new(KnotVec::bezier_knot(3), points)
    };
    let near = curve([
        [0.0, 0.0, 0.0],
        [60.0, 0.0, 30.0],
        [140.0, 0.0, 30.0],
        [200.0, 0.0, 0.0],
    ]);
    let far = curve([
        [0.0, 150.0, 20.0],
        [60.0, 150.0, -10.0],
        [140.0, 150.0, 50.0],
        [200.0, 150.0, 10.0],
    ]);
    let edge = |c: BSplineCurve<Point3>| {
        let (front, back) = (c.front(), c.back());
        Edge::new(
            &builder::vertex(front),
            &builder::vertex(back),
            Curve::BSplineCurve(c),
        )
    };
    let face = builder::homotopy(&edge(near), &edge(far));
    let shell: Shell = vec![face].into();
    let compressed = shell.compress();
    let text = truck_stepio::out::CompleteStepDisplay::new(
        truck_stepio::out::StepModel::from(&compressed),
        truck_stepio::out::StepHeaderDescriptor {
            file_name: "bspline_patch.step".to_owned(),
            organization_system: "flatcut sample generator (truck-stepio writer)".to_owned(),
            ..Default::default()
        },
    )
    .to_string();
    std::fs::write(sample("bspline_patch.step"), text).expect("writes");
}

#[test]
fn a_loose_step_surface_in_metres_is_meshed_in_millimetres() {
    let jobs =
        load_parts(&sample("loose_hypar_metres.step"), &RunOptions::default()).expect("loads");
    let largest = jobs[0]
        .model
        .positions()
        .iter()
        .map(|p| p.x)
        .fold(0.0, f64::max);
    assert!((largest - 200.0).abs() < 1e-6, "{largest}");
}

#[test]
fn fold_lines_and_regions_raise_the_stiffness_of_their_edges() {
    // The bracket without its bend radius: a stiff fold line, flattened by the energy model (with
    // the radius it is a bend, unfolded exactly, and stiffness does not apply).
    let text = std::fs::read_to_string(sample("bracket_fold.toml")).expect("the sample");
    assert!(text.contains("bend_radius = 2.0\n"));
    let directory = tempfile::tempdir().expect("a temporary directory");
    let path = directory.path().join("bracket_fold.toml");
    std::fs::write(&path, text.replace("bend_radius = 2.0\n", "")).expect("written");
    let jobs = load_parts(&path, &RunOptions::default()).expect("loads");
    let job = &jobs[0];
    let factors = job.stiffness.factors();
    let fold_edges = job
        .model
        .edge_fold_lines()
        .iter()
        .filter(|&&l| l == 0)
        .count();
    assert!(fold_edges > 0, "the shared edge is tagged");
    for factor in [10.0, 4.0, 3.0] {
        assert!(
            factors.iter().any(|&f| (f - factor).abs() < 1e-12),
            "some edge has factor {factor}"
        );
    }
    assert_eq!(job.attributes.thickness, Some(2.0));
}

fn flatcut(arguments: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_flatcut"))
        .args(arguments)
        .output()
        .expect("flatcut runs")
}

#[test]
fn the_cli_tessellates_a_part_and_rejects_bad_input_with_exit_1() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let mesh = directory.path().join("cone.obj");
    let cone = sample("cone_frustum.toml");
    let output = flatcut(&[
        "tessellate",
        cone.to_str().expect("utf-8"),
        "-o",
        mesh.to_str().expect("utf-8"),
        "--mesh-size",
        "20",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        std::fs::read_to_string(&mesh)
            .expect("written")
            .contains("\nf ")
    );
    let out = directory.path().join("out");
    for (input, expected) in [
        (
            "bad/zero_radius.toml",
            "zero_radius.toml:3: field 'surface[0].radius'",
        ),
        ("unsupported_offset_surface.step", "OFFSET_SURFACE"),
    ] {
        let path = sample(input);
        let output = flatcut(&[
            "flatten",
            path.to_str().expect("utf-8"),
            "-o",
            out.to_str().expect("utf-8"),
        ]);
        assert_eq!(output.status.code(), Some(1));
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(message.contains(expected), "{message}");
    }
}

/// Writes a part file in a temporary directory and loads its first part through the library
/// (tessellated, stiffness set).
fn load_part_text(text: &str, options: &RunOptions) -> PartJob {
    let directory = tempfile::tempdir().expect("temporary directory");
    let path = directory.path().join("part.toml");
    std::fs::write(&path, text).expect("writes");
    load_parts(&path, options)
        .unwrap_or_else(|e| panic!("{e}"))
        .remove(0)
}

/// Writes a part file in a temporary directory and flattens it through the library.
fn flatten_part_text(text: &str) -> PartResult {
    let options = RunOptions::default();
    flatten_part(load_part_text(text, &options), &options, &NoProgress).expect("flattens")
}

/// Checks a fold line on a part: its 3D length against the analytic length of the curve within
/// `allowed_3d`, its flat length against its 3D length within `allowed_error` (relative), and
/// the tessellation's worst angle. On a ruled developable surface the fold is carried along the
/// rulings and the mesh stays exactly developable: the developable target 1e-5 holds.
fn assert_fold(
    result: &PartResult,
    line: usize,
    analytic: f64,
    allowed_3d: f64,
    allowed_error: f64,
) {
    let lengths = fold_line_lengths(
        &result.job.model,
        &result.flattened.positions,
        result.job.fold_line_count,
    );
    let fold = lengths[line];
    assert!(
        (fold.length_3d - analytic).abs() <= allowed_3d,
        "fold {line}: 3D length {} vs analytic {analytic} (allowed {allowed_3d})",
        fold.length_3d
    );
    assert!(
        fold.error <= allowed_error,
        "fold {line}: flat length {} vs 3D {}: error {}",
        fold.length_flat,
        fold.length_3d,
        fold.error
    );
    let tessellation = result.job.tessellation.as_ref().expect("from surfaces");
    assert!(
        tessellation.minimum_angle >= MINIMUM_FOLD_MESH_ANGLE,
        "worst angle {}",
        tessellation.minimum_angle
    );
}

/// The worst triangle angle of a mesh around fold polylines (measured 22.2° to 42.7° on the
/// parts below, docs/tessellation.md).
const MINIMUM_FOLD_MESH_ANGLE: f64 = 20.0;

fn chord_of(result: &PartResult) -> f64 {
    result
        .job
        .tessellation
        .as_ref()
        .expect("from surfaces")
        .chord
}

#[test]
fn a_fold_along_a_cylinder_generator_keeps_its_length() {
    let result = flatten_part_text(
        "[[surface]]\nkind = \"cylinder\"\nradius = 150.0\nheight = 200.0\nangles = [0.0, 120.0]\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[61.3, 0.0], [61.3, 200.0]]\n",
    );
    // A generator is straight: its mesh polyline lies in the facets, within the chord.
    assert_fold(&result, 0, 200.0, chord_of(&result), DEVELOPABLE_TOLERANCE);
    assert_isometric(&result);
    assert_area(&result, 150.0 * 120f64.to_radians() * 200.0);
}

#[test]
fn cone_folds_along_a_generator_and_a_circle_of_latitude_keep_their_lengths() {
    let result = flatten_part_text(
        "[[surface]]\nkind = \"cone\"\nbottom_radius = 100.0\ntop_radius = 50.0\nheight = 80.0\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[90.0, 0.0], [90.0, 80.0]]\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[0.0, 40.0], [360.0, 40.0]]\n",
    );
    let chord = chord_of(&result);
    let slant = (80f64 * 80.0 + 50.0 * 50.0).sqrt();
    // The generator is a ruling of the mesh: its length is the slant height.
    assert_fold(&result, 0, slant, 1e-9, DEVELOPABLE_TOLERANCE);
    // The circle of latitude (radius 75) lies within the chord inside the surface: its length
    // is short by at most 2π times the chord.
    assert_fold(&result, 1, TAU * 75.0, TAU * chord, DEVELOPABLE_TOLERANCE);
    assert_isometric(&result);
    assert_area(&result, PI * 150.0 * slant);
}

#[test]
fn folds_on_an_oblique_cone_an_extrusion_a_loft_and_a_dome_are_carried_onto_the_mesh() {
    let oblique = flatten_part_text(
        "[[surface]]\nkind = \"cone\"\nbottom_radius = 100.0\ntop_radius = 50.0\nheight = 80.0\n\
         top_offset = [20.0, 10.0]\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[30.0, 0.0], [30.0, 80.0]]\n",
    );
    // The ruling at angle a joins (100 cos a, 100 sin a, 0) and (20 + 50 cos a, 10 + 50 sin a, 80).
    let a = 30f64.to_radians();
    let ruling = glam::DVec3::new(20.0 - 50.0 * a.cos(), 10.0 - 50.0 * a.sin(), 80.0).length();
    assert_fold(
        &oblique,
        0,
        ruling,
        chord_of(&oblique),
        DEVELOPABLE_TOLERANCE,
    );
    assert_isometric(&oblique);
    let extrusion = flatten_part_text(
        "[[surface]]\nkind = \"extrusion\"\nstart = [0.0, 0.0]\n\
         profile = [{ to = [100.0, 0.0] }, { to = [150.0, 50.0], center = [100.0, 50.0] }]\n\
         direction = [0.0, 0.0, 120.0]\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[0.0, 60.0], [178.53981633974483, 60.0]]\n",
    );
    // Along the profile at half height: 100 + a quarter circle of radius 50.
    assert_fold(
        &extrusion,
        0,
        100.0 + 25.0 * PI,
        2.0 * chord_of(&extrusion),
        DEVELOPABLE_TOLERANCE,
    );
    assert_isometric(&extrusion);
    let loft = flatten_part_text(
        "[[surface]]\nkind = \"loft\"\n\
         bottom = { shape = \"rectangle\", width = 200.0, depth = 200.0 }\n\
         top = { shape = \"circle\", diameter = 120.0, z = 150.0 }\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[0.0, 75.0], [360.0, 75.0]]\n",
    );
    // Halfway up, the section is the mean of the square and the circle (a Minkowski sum): its
    // perimeter is the mean of theirs.
    let perimeter = (800.0 + TAU * 60.0) / 2.0;
    let lengths = fold_line_lengths(&loft.job.model, &loft.flattened.positions, 1);
    assert!(
        (lengths[0].length_3d - perimeter).abs() <= TAU * chord_of(&loft)
            && lengths[0].error <= DEVELOPABLE_TOLERANCE,
        "{:?} vs {perimeter}",
        lengths[0]
    );
    // The section crosses the corner fans at half their rulings: a row of each fan follows it.
    assert_isometric(&loft);
    let dome = flatten_part_text(
        "[[surface]]\nkind = \"revolution\"\nstart = [0.0, 120.0]\n\
         profile = [{ to = [103.92304845413264, 60.0], center = [0.0, 0.0] }]\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[0.0, 60.0], [360.0, 60.0]]\n",
    );
    // 60 mm along the meridian from the pole: the parallel at 0.5 rad from the axis.
    let parallel = TAU * 120.0 * 0.5f64.sin();
    let tessellation = dome.job.tessellation.as_ref().expect("from surfaces");
    let lengths = fold_line_lengths(&dome.job.model, &dome.flattened.positions, 1);
    assert!(
        (lengths[0].length_3d - parallel).abs() <= TAU * tessellation.chord
            && tessellation.minimum_angle >= 20.0,
        "{:?} vs {parallel}, worst angle {}",
        lengths[0],
        tessellation.minimum_angle
    );
}

#[test]
fn a_fold_polyline_off_its_surface_or_through_a_trim_hole_exits_1_naming_it() {
    let cases = [
        (
            "[[surface]]\nkind = \"cylinder\"\nradius = 50.0\nheight = 100.0\n\n\
             [[fold_line]]\nsurface = 0\npoints = [[0.0, 0.0], [90.0, 120.0]]\n",
            "part.toml:8: field 'fold_line[0].points'",
        ),
        (
            "[[surface]]\nkind = \"bspline\"\ndegree = [1, 1]\n\
             control_points = [[[0, 0, 0], [0, 100, 0]], [[100, 0, 0], [100, 100, 10]]]\n\
             trim = { holes = [[[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6]]] }\n\n\
             [[fold_line]]\nsurface = 0\npoints = [[0.0, 0.5], [1.0, 0.5]]\n",
            "part.toml:9: field 'fold_line[0].points'",
        ),
    ];
    for (text, expected) in cases {
        assert_part_text_exits_1_naming(text, expected);
    }
}

#[test]
fn crossing_fold_polylines_on_a_polygon_share_their_crossing() {
    let result = flatten_part_text(
        "[[surface]]\nkind = \"polygon\"\n\
         points = [[0, 0, 0], [200, 0, 0], [200, 200, 0], [0, 200, 0]]\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[0.0, 0.0], [200.0, 200.0]]\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[0.0, 200.0], [200.0, 0.0]]\n",
    );
    let diagonal = 200.0 * 2f64.sqrt();
    assert_fold(&result, 0, diagonal, 1e-9, 1e-9);
    assert_fold(&result, 1, diagonal, 1e-9, 1e-9);
}

/// The stiffness factor the region tests give their region (no other edge has it).
const REGION_FACTOR: f64 = 7.0;

/// An angle in degrees, `[0, 360)`, of the local vector `(x, y)`.
fn degrees(x: f64, y: f64) -> f64 {
    y.atan2(x).to_degrees().rem_euclid(360.0)
}

/// Whether `value` lies in `[low, high]`, within round-off.
fn within(value: f64, low: f64, high: f64) -> bool {
    value >= low - 1e-9 && value <= high + 1e-9
}

/// Whether the angle `u` (degrees) lies on the arc from `from` counter-clockwise to `to`.
fn on_arc(u: f64, from: f64, to: f64) -> bool {
    within(
        (u - from).rem_euclid(360.0),
        0.0,
        (to - from).rem_euclid(360.0),
    ) || within((u - from).rem_euclid(360.0), 360.0, 360.0)
}

/// Loads a part whose one stiffness region has [`REGION_FACTOR`] and checks that exactly the
/// edges whose two ends satisfy `in_region` (computed from the analytic domain coordinates of
/// the positions) got it. Returns how many did.
fn assert_region_selects(text: &str, in_region: impl Fn(glam::DVec3) -> bool) -> usize {
    let job = load_part_text(text, &RunOptions::default());
    let positions = job.model.positions();
    let mut selected = 0;
    for (edge, &factor) in job.model.edges().iter().zip(job.stiffness.factors()) {
        let expected = edge.iter().all(|&v| in_region(positions[v as usize]));
        let got = (factor - REGION_FACTOR).abs() < 1e-12;
        assert_eq!(
            got, expected,
            "edge {:?} - {:?}",
            positions[edge[0] as usize], positions[edge[1] as usize]
        );
        selected += usize::from(got);
    }
    assert!(
        selected > 0 && selected < job.model.edges().len(),
        "{selected} edges selected"
    );
    selected
}

#[test]
fn parameter_regions_select_the_springs_inside_them_on_every_kind() {
    // A full-turn cylinder, the box across the seam (u_max < u_min) and the same region as a
    // polygon from -19.5 degrees: the same springs.
    let cylinder = "[[surface]]\nkind = \"cylinder\"\nradius = 100.0\nheight = 200.0\n\n\
                    [[stiffness_region]]\nfactor = 7.0\nsurface = 0\n";
    let in_cylinder =
        |p: glam::DVec3| on_arc(degrees(p.x, p.y), 340.5, 15.7) && within(p.z, 20.3, 130.1);
    let through_seam = assert_region_selects(
        &format!("{cylinder}parameter_box = [340.5, 20.3, 15.7, 130.1]\n"),
        in_cylinder,
    );
    let negative = assert_region_selects(
        &format!(
            "{cylinder}polygon = [[-19.5, 20.3], [15.7, 20.3], [15.7, 130.1], [-19.5, 130.1]]\n"
        ),
        in_cylinder,
    );
    assert_eq!(through_seam, negative);
    // An oblique cone: the angle about the axis through the two centres.
    assert_region_selects(
        "[[surface]]\nkind = \"cone\"\nbottom_radius = 100.0\ntop_radius = 50.0\nheight = 80.0\n\
         top_offset = [20.0, 10.0]\n\n\
         [[stiffness_region]]\nfactor = 7.0\nsurface = 0\nparameter_box = [100.2, 10.5, 200.9, 61.1]\n",
        |p| {
            let t = p.z / 80.0;
            on_arc(degrees(p.x - 20.0 * t, p.y - 10.0 * t), 100.2, 200.9) && within(p.z, 10.5, 61.1)
        },
    );
    // A dome (a revolution through a pole): the angle and the arc length from the pole. The
    // region reaches the pole, so the pole is in it.
    assert_region_selects(
        "[[surface]]\nkind = \"revolution\"\nstart = [0.0, 120.0]\n\
         profile = [{ to = [103.92304845413264, 60.0], center = [0.0, 0.0] }]\n\n\
         [[stiffness_region]]\nfactor = 7.0\nsurface = 0\nparameter_box = [-30.5, 0.0, 45.2, 60.7]\n",
        |p| {
            let radius = p.x.hypot(p.y);
            let arc = 120.0 * radius.atan2(p.z);
            within(arc, 0.0, 60.7) && (radius < 1e-9 || on_arc(degrees(p.x, p.y), -30.5, 45.2))
        },
    );
    // An extrusion of a line and a quarter circle: the arc length along the profile.
    assert_region_selects(
        "[[surface]]\nkind = \"extrusion\"\nstart = [0.0, 0.0]\n\
         profile = [{ to = [100.0, 0.0] }, { to = [150.0, 50.0], center = [100.0, 50.0] }]\n\
         direction = [0.0, 0.0, 120.0]\n\n\
         [[stiffness_region]]\nfactor = 7.0\nsurface = 0\nparameter_box = [60.3, 10.2, 140.7, 50.9]\n",
        |p| {
            let along = if p.x <= 100.0 + 1e-9 && p.y.abs() < 1e-9 {
                p.x
            } else {
                100.0 + 50.0 * (p.x - 100.0).atan2(50.0 - p.y)
            };
            within(along, 60.3, 140.7) && within(p.z, 10.2, 50.9)
        },
    );
    // An eccentric round-to-round loft: the angle about the axis through the centres, from the
    // seam ruling (tangent direction 0: the circles' points at -90 degrees).
    assert_region_selects(
        "[[surface]]\nkind = \"loft\"\n\
         bottom = { shape = \"circle\", diameter = 200.0 }\n\
         top = { shape = \"circle\", diameter = 120.0, center = [20.0, 0.0], z = 100.0 }\n\n\
         [[stiffness_region]]\nfactor = 7.0\nsurface = 0\n\
         polygon = [[-20.5, 10.3], [30.2, 10.3], [30.2, 90.7], [-20.5, 90.7]]\n",
        |p| {
            let u = degrees(p.x - 20.0 * p.z / 100.0, p.y) + 90.0;
            on_arc(u, -20.5, 30.2) && within(p.z, 10.3, 90.7)
        },
    );
    // A polygon with a hole the region covers: plane coordinates.
    assert_region_selects(
        "[[surface]]\nkind = \"polygon\"\npoints = [[0, 0, 0], [200, 0, 0], [200, 100, 0], [0, 100, 0]]\n\
         holes = [[[80, 30, 0], [120, 30, 0], [120, 70, 0], [80, 70, 0]]]\n\n\
         [[stiffness_region]]\nfactor = 7.0\nsurface = 0\n\
         polygon = [[50.5, 10.5], [150.5, 10.5], [150.5, 90.5], [50.5, 90.5]]\n",
        |p| within(p.x, 50.5, 150.5) && within(p.y, 10.5, 90.5),
    );
    // A bilinear B-spline patch (x = 200 u, y = 200 v) and a triangle.
    let triangle = [
        DVec2::new(0.1, 0.1),
        DVec2::new(0.9, 0.2),
        DVec2::new(0.4, 0.8),
    ];
    assert_region_selects(
        "[[surface]]\nkind = \"bspline\"\ndegree = [1, 1]\n\
         control_points = [[[0, 0, 40], [0, 200, -40]], [[200, 0, -40], [200, 200, 40]]]\n\n\
         [[stiffness_region]]\nfactor = 7.0\nsurface = 0\n\
         polygon = [[0.1, 0.1], [0.9, 0.2], [0.4, 0.8]]\n",
        |p| {
            let uv = DVec2::new(p.x, p.y) / 200.0;
            (0..3).all(|k| {
                let (a, b) = (triangle[k], triangle[(k + 1) % 3]);
                (b - a).perp_dot(uv - a) >= -1e-12
            })
        },
    );
    // Two welded squares: a region covering the second one takes the edges of the edge they
    // share too (its vertices are on both surfaces).
    assert_region_selects(
        "[[surface]]\nkind = \"polygon\"\npoints = [[0, 0, 0], [100, 0, 0], [100, 100, 0], [0, 100, 0]]\n\n\
         [[surface]]\nkind = \"polygon\"\npoints = [[100, 0, 0], [200, 0, 0], [200, 100, 0], [100, 100, 0]]\n\n\
         [[stiffness_region]]\nfactor = 7.0\nsurface = 1\nparameter_box = [-1.0, -1.0, 101.0, 101.0]\n",
        |p| p.x >= 100.0 - 1e-9,
    );
}

#[test]
fn a_parameter_region_off_its_surface_or_a_reversed_box_exits_1_naming_it() {
    let cylinder = "[[surface]]\nkind = \"cylinder\"\nradius = 50.0\nheight = 100.0\nangles = [0.0, 120.0]\n\n\
                    [[stiffness_region]]\nfactor = 5.0\nsurface = 0\n";
    let cases = [
        (
            format!("{cylinder}parameter_box = [200.0, 10.0, 300.0, 50.0]\n"),
            "part.toml:10: field 'stiffness_region[0].parameter_box': the region (u (angle) from 200 to 300, v (height) from 10 to 50) lies off its surface, whose domain is u (angle) from 0 to 120,",
        ),
        (
            format!("{cylinder}polygon = [[0.0, 120.0], [90.0, 120.0], [90.0, 150.0]]\n"),
            "part.toml:10: field 'stiffness_region[0].polygon'",
        ),
        (
            format!("{cylinder}parameter_box = [10.0, 50.0, 90.0, 20.0]\n"),
            "part.toml:10: field 'stiffness_region[0].parameter_box': v_max (20) must exceed",
        ),
    ];
    for (text, expected) in cases {
        assert_part_text_exits_1_naming(&text, expected);
    }
}

/// Mean |strain| (flat length over 3D length, minus one) of the edges whose two ends satisfy
/// `in_region`.
fn mean_strain_where(result: &PartResult, in_region: impl Fn(glam::DVec3) -> bool) -> f64 {
    let model = &result.job.model;
    let (positions, flat) = (model.positions(), &result.flattened.positions);
    let strains: Vec<f64> = model
        .edges()
        .iter()
        .filter(|edge| edge.iter().all(|&v| in_region(positions[v as usize])))
        .map(|&[a, b]| {
            let length = positions[a as usize].distance(positions[b as usize]);
            (flat[a as usize].distance(flat[b as usize]) / length - 1.0).abs()
        })
        .collect();
    assert!(!strains.is_empty(), "no edge in the region");
    strains.iter().sum::<f64>() / strains.len() as f64
}

#[test]
fn a_region_keeps_a_cone_exact_and_lowers_a_domes_strain_where_it_is() {
    let cone = flatten_part_text(
        "[[surface]]\nkind = \"cone\"\nbottom_radius = 100.0\ntop_radius = 50.0\nheight = 80.0\n\n\
         [[stiffness_region]]\nfactor = 10.0\nsurface = 0\nparameter_box = [300.0, 20.0, 60.0, 60.0]\n",
    );
    assert_isometric(&cone);
    assert!(cone.job.stiffness.factors().contains(&10.0));
    // The dome uncut (the same mesh and seam both ways), with and without a stiff sector ring.
    let dome = "[[surface]]\nkind = \"revolution\"\nstart = [0.0, 120.0]\n\
                profile = [{ to = [103.92304845413264, 60.0], center = [0.0, 0.0] }]\n";
    let region = "\n[[stiffness_region]]\nfactor = 10.0\nsurface = 0\n\
                  parameter_box = [20.0, 60.0, 160.0, 120.0]\n";
    let in_region = |p: glam::DVec3| {
        let arc = 120.0 * p.x.hypot(p.y).atan2(p.z);
        within(arc, 60.0, 120.0) && on_arc(degrees(p.x, p.y), 20.0, 160.0)
    };
    let mut options = RunOptions::default();
    options.cut.max_cuts = Some(0);
    let strain = |text: &str| {
        let job = load_part_text(text, &options);
        let result = flatten_part(job, &options, &NoProgress).expect("flattens");
        mean_strain_where(&result, in_region)
    };
    let (uniform, stiff) = (strain(dome), strain(&format!("{dome}{region}")));
    eprintln!("dome, mean |strain| in the region: uniform {uniform:.6}, factor 10 {stiff:.6}");
    // Measured: 0.0131 uniform, 0.0078 with the region (40 % less).
    assert!(stiff < 0.7 * uniform, "uniform {uniform}, stiff {stiff}");
}

/// Edges used by one triangle only, as pairs of positions.
fn boundary_edges(result: &PartResult) -> Vec<[glam::DVec3; 2]> {
    let model = &result.job.model;
    let mut count = std::collections::HashMap::new();
    for t in model.triangles() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    count
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|((a, b), _)| [a, b].map(|v| model.positions()[v as usize]))
        .collect()
}

#[test]
fn folds_on_cylinders_welded_along_a_circle_keep_the_weld() {
    // Two cylinder panels, one on top of the other, welded along the circle at z = 100. A
    // generator fold on the lower one needs a ruling, so a point on the welded circle: it is
    // inserted by re-triangulation instead, and the circle keeps its points. A circle of latitude
    // on the upper one ends on its end rulings and needs no new ruling: it is carried along the
    // rulings.
    let result = flatten_part_text(
        "[[surface]]\nkind = \"cylinder\"\nradius = 150.0\nheight = 100.0\nangles = [0.0, 90.0]\n\n\
         [[surface]]\nkind = \"cylinder\"\nradius = 150.0\nheight = 100.0\nangles = [0.0, 90.0]\n\
         placement = { origin = [0.0, 0.0, 100.0] }\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[36.2, 0.0], [36.2, 60.0]]\n\n\
         [[fold_line]]\nsurface = 1\npoints = [[0.0, 50.0], [90.0, 50.0]]\n",
    );
    // No boundary edge inside the shared circle (z = 100, away from its two ends).
    let inner = boundary_edges(&result).into_iter().filter(|edge| {
        edge.iter()
            .all(|p| (p.z - 100.0).abs() < 1e-6 && p.x > 1e-6 && p.y > 1e-6)
    });
    assert_eq!(inner.count(), 0, "the weld along the circle is broken");
    assert_fold(&result, 0, 60.0, chord_of(&result), 1e-4);
    let quarter = 150.0 * PI / 2.0;
    assert_fold(
        &result,
        1,
        quarter,
        2.0 * chord_of(&result),
        DEVELOPABLE_TOLERANCE,
    );
}

#[test]
fn folds_inside_the_wedges_of_a_loft_keep_it_exactly_developable() {
    // A loft's rulings are fixed by its sections: a fold vertex between two of them gets a ruling
    // inside their planar wedge, and a fold crossing the rulings gets a point on each.
    let result = flatten_part_text(
        "[[surface]]\nkind = \"loft\"\nbottom = { shape = \"circle\", diameter = 160.0 }\n\
         top = { shape = \"circle\", diameter = 100.0, center = [30.0, 0.0], z = 120.0 }\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[47.3, 0.0], [47.3, 120.0]]\n\n\
         [[fold_line]]\nsurface = 0\npoints = [[0.0, 50.0], [360.0, 50.0]]\n",
    );
    assert_isometric(&result);
    let lengths = fold_line_lengths(&result.job.model, &result.flattened.positions, 2);
    assert!(
        lengths.iter().all(|l| l.error <= DEVELOPABLE_TOLERANCE),
        "{lengths:?}"
    );
    // At z = 50 the section is the circle of radius 80 + (50 - 80) 50 / 120 about the centre
    // moved 30 · 50 / 120 (the loft of two circles is a cone): 2π · 67.5 within the chord.
    let circle = TAU * (80.0 - 30.0 * 50.0 / 120.0);
    assert!(
        (lengths[1].length_3d - circle).abs() <= TAU * chord_of(&result),
        "{} vs {circle}",
        lengths[1].length_3d
    );
}

/// A STEP file is read into a B-rep whose faces keep their surfaces' exact parameters, their
/// STEP entities and their adjacency (`cad::BrepShell`), before any tessellation.
#[test]
fn step_faces_keep_their_exact_surfaces_and_adjacency() {
    use flatcut::cad::SurfaceGeometry;
    use flatcut::ingest::{Input, read_input};
    let read = |name: &str| match read_input(&sample(name), Default::default()) {
        Ok(Input::Step(brep)) => brep,
        _ => panic!("{name}: not read as STEP"),
    };
    // Bottom radius 100 mm, top radius 50 mm, height 80 mm, about the z axis.
    let frustum = read("cone_frustum_freecad.step");
    let shell = &frustum.shells[0];
    let cone = (0..shell.shell.faces.len())
        .find_map(|face| match shell.surface_geometry(face) {
            SurfaceGeometry::Cone {
                origin,
                axis,
                radius,
                half_angle,
            } => Some((origin, axis, radius, half_angle)),
            _ => None,
        })
        .expect("a conical face");
    let (origin, axis, radius, half_angle) = cone;
    assert!((axis.z.abs() - 1.0).abs() < 1e-9, "axis {axis}");
    let radius_at = |z: f64| radius + (z - origin.z) / axis.z * half_angle.tan();
    assert!((radius_at(0.0) - 100.0).abs() < 1e-6, "{}", radius_at(0.0));
    assert!((radius_at(80.0) - 50.0).abs() < 1e-6, "{}", radius_at(80.0));
    assert!(shell.describe_face(0).contains("CONICAL_SURFACE"));
    // A solid cone: its side and its base share the base circle.
    let solid = read("cone_apex_freecad.step");
    let shell = &solid.shells[0];
    let kinds: Vec<SurfaceGeometry> = (0..shell.shell.faces.len())
        .map(|face| shell.surface_geometry(face))
        .collect();
    assert!(
        kinds
            .iter()
            .any(|k| matches!(k, SurfaceGeometry::Plane { normal, .. } if normal.z.abs() > 0.999))
    );
    assert!(
        shell
            .adjacent_faces()
            .iter()
            .any(|&(faces, _)| faces == [0, 1]),
        "{:?}",
        shell.adjacent_faces()
    );
}

/// Thin-solid recognition on the B-rep: the FreeCAD L section is a 2 mm sheet whose chosen skin
/// is one side (a flange, its bend and the other flange), the gusset bracket (two plates and a
/// gusset, sharp corners) is planes only but no sheet, and a solid cone is not made of planes
/// and cylinders.
#[test]
fn thin_solids_are_recognised_on_the_brep() {
    use flatcut::ingest::{Input, read_input};
    use flatcut::pipeline::tessellate_step;
    use flatcut::sheet::{NotASheet, SheetSurface, recognise_shell};
    let recognised = |name: &str| {
        let Ok(Input::Step(brep)) = read_input(&sample(name), Default::default()) else {
            panic!("{name}: not read as STEP");
        };
        let tessellation =
            tessellate_step(&sample(name), &brep, &Default::default()).expect("tessellated");
        recognise_shell(&brep.shells[0], tessellation.soup(), None)
    };
    let solid = recognised("sheet_l_hole_freecad.step").expect("the L is a sheet");
    assert!((solid.thickness - 2.0).abs() < 1e-9);
    assert_eq!(solid.skin.len(), 3, "flange, bend, flange");
    let cylinders = solid
        .skin
        .iter()
        .filter(|&&face| matches!(solid.surfaces[face], SheetSurface::Cylinder { .. }))
        .count();
    assert_eq!(cylinders, 1);
    match recognised("gusset_bracket_freecad.step") {
        Err(NotASheet::NoConstantThickness(reason)) => {
            assert!(reason.contains("neither on a skin nor a wall"), "{reason}")
        }
        other => panic!("the gusset bracket is no sheet: {other:?}"),
    }
    assert!(matches!(
        recognised("cone_apex_freecad.step"),
        Err(NotASheet::OtherSurfaces(_))
    ));
}
