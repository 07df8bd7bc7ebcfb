//! Flattening end to end: exact developments, accuracy recomputed independently, rigid-motion
//! invariance, determinism and exit codes.

use crate::util::{
    flatcut, flatten_into, read_obj, read_report, recompute, sample, stderr, write_obj,
};

/// Developable meshes must unroll isometrically: errors at round-off level.
const DEVELOPABLE_ERROR: f64 = 1e-6;

#[test]
fn developable_samples_unroll_exactly_with_both_solvers() {
    for name in ["cone_frustum", "cylinder_segment"] {
        for solver in ["fast", "paper"] {
            let directory = tempfile::tempdir().expect("temporary directory");
            let output = flatten_into(
                &sample(&format!("{name}.obj")),
                directory.path(),
                &["--solver", solver],
            );
            assert_eq!(
                output.status.code(),
                Some(0),
                "{name} {solver}: {}",
                stderr(&output)
            );
            let figures = recompute(directory.path(), name);
            assert!(
                figures.area_error <= DEVELOPABLE_ERROR,
                "{name} {solver}: E_S {}",
                figures.area_error
            );
            assert!(
                figures.shape_error <= DEVELOPABLE_ERROR,
                "{name} {solver}: E_C {}",
                figures.shape_error
            );
            assert_eq!(figures.flipped, 0, "{name} {solver}");
        }
    }
}

#[test]
fn reported_errors_match_an_independent_recomputation() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let output = flatten_into(&sample("saddle.obj"), directory.path(), &[]);
    assert!(
        matches!(output.status.code(), Some(0 | 3)),
        "{}",
        stderr(&output)
    );
    let report = read_report(directory.path());
    let part = &report["parts"][0];
    let figures = recompute(directory.path(), "saddle");
    let reported = |key: &str| part[key].as_f64().expect("number");
    assert!(
        (reported("area_error") - figures.area_error).abs() < 1e-12,
        "{} vs {figures:?}",
        part
    );
    assert!(
        (reported("shape_error") - figures.shape_error).abs() < 1e-12,
        "{} vs {figures:?}",
        part
    );
    assert_eq!(part["flipped"].as_u64(), Some(figures.flipped as u64));
}

#[test]
fn hemisphere_has_no_flip_or_overlap_and_beats_arap() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let output = flatten_into(&sample("hemisphere.obj"), directory.path(), &[]);
    assert!(
        matches!(output.status.code(), Some(0 | 3)),
        "{}",
        stderr(&output)
    );
    let part = &read_report(directory.path())["parts"][0];
    assert_eq!(part["flipped"].as_u64(), Some(0));
    assert_eq!(part["overlap"].as_bool(), Some(false));
    // libigl ARAP on the same mesh: E_S 16.3 %, E_C 10.0 % (shared/bench/README.md).
    assert!(
        part["area_error"].as_f64().expect("number") < 0.163,
        "{part}"
    );
    assert!(
        part["shape_error"].as_f64().expect("number") < 0.100,
        "{part}"
    );
}

#[test]
fn rigid_motion_changes_no_figure() {
    let original = tempfile::tempdir().expect("temporary directory");
    let moved = tempfile::tempdir().expect("temporary directory");
    let (vertices, faces) = read_obj(&sample("saddle.obj"));
    let (sin, cos) = 0.7f64.sin_cos();
    let (sin2, cos2) = (-1.1f64).sin_cos();
    let transformed: Vec<[f64; 3]> = vertices
        .iter()
        .map(|&[x, y, z]| {
            let (x, y) = (cos * x - sin * y, sin * x + cos * y);
            let (y, z) = (cos2 * y - sin2 * z, sin2 * y + cos2 * z);
            [x + 1234.5, y - 678.25, z + 91.0]
        })
        .collect();
    let moved_input = moved.path().join("saddle.obj");
    write_obj(&moved_input, &transformed, &faces);
    let moved_output = moved.path().join("out");
    for (input, directory) in [
        (sample("saddle.obj"), original.path().to_path_buf()),
        (moved_input, moved_output.clone()),
    ] {
        let output = flatten_into(&input, &directory, &[]);
        assert!(
            matches!(output.status.code(), Some(0 | 3)),
            "{}",
            stderr(&output)
        );
    }
    let a = &read_report(original.path())["parts"][0];
    let b = &read_report(&moved_output)["parts"][0];
    for key in ["area_error", "shape_error", "max_strain", "energy"] {
        let (x, y) = (
            a[key].as_f64().expect("number"),
            b[key].as_f64().expect("number"),
        );
        assert!(
            (x - y).abs() <= 1e-9 * x.abs().max(1e-12),
            "{key}: {x} vs {y}"
        );
    }
}

#[test]
fn same_input_gives_byte_identical_outputs() {
    let first = tempfile::tempdir().expect("temporary directory");
    let second = tempfile::tempdir().expect("temporary directory");
    for directory in [first.path(), second.path()] {
        let output = flatten_into(&sample("hemisphere.obj"), directory, &[]);
        assert!(
            matches!(output.status.code(), Some(0 | 3)),
            "{}",
            stderr(&output)
        );
    }
    let mut names: Vec<_> = std::fs::read_dir(first.path())
        .expect("list")
        .map(|e| e.expect("entry").file_name())
        .collect();
    names.sort();
    assert!(names.len() >= 3, "{names:?}");
    for name in names {
        let a = std::fs::read(first.path().join(&name)).expect("read");
        let b = std::fs::read(second.path().join(&name)).expect("read");
        assert!(a == b, "{name:?} differs between runs");
    }
}

#[test]
fn json_flag_prints_the_report() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let output = flatten_into(&sample("cone_frustum.obj"), directory.path(), &["--json"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let printed: serde_json::Value =
        serde_json::from_slice(&output.stdout).expect("stdout is JSON");
    assert_eq!(printed, read_report(directory.path()));
    assert_eq!(printed["schema_version"].as_u64(), Some(1));
    assert_eq!(printed["parts"][0]["tolerance_met"].as_bool(), Some(true));
}

#[test]
fn over_tolerance_exits_3_and_still_writes_outputs() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let output = flatten_into(
        &sample("saddle.obj"),
        directory.path(),
        &["--tolerance", "0.0001", "--seams", "whole"],
    );
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let part = &read_report(directory.path())["parts"][0];
    assert_eq!(part["tolerance_met"].as_bool(), Some(false));
    assert!(directory.path().join("saddle.pattern.obj").exists());
}

#[test]
fn usage_errors_exit_2() {
    assert_eq!(flatcut(&[]).status.code(), Some(2));
    assert_eq!(
        flatcut(&["flatten", "x.obj"]).status.code(),
        Some(2),
        "missing -o"
    );
    assert_eq!(
        flatcut(&["flatten", "x.obj", "-o", "out", "--solver", "magic"])
            .status
            .code(),
        Some(2)
    );
}

#[test]
fn a_closed_tetrahedron_opens_to_its_exact_net() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let input = directory.path().join("tetrahedron.obj");
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
    std::fs::write(&input, text).expect("write input");
    let output_directory = directory.path().join("out");
    let output = flatten_into(&input, &output_directory, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let part = &read_report(&output_directory)["parts"][0];
    assert!(
        !part["seams"].as_array().expect("seams").is_empty(),
        "{part}"
    );
    let figures = recompute(&output_directory, "tetrahedron");
    assert!(
        figures.area_error <= DEVELOPABLE_ERROR && figures.shape_error <= DEVELOPABLE_ERROR,
        "{figures:?}"
    );
    assert_eq!(figures.flipped, 0);
}

#[test]
fn a_mesh_in_metres_gives_the_same_pattern_in_metres() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let (vertices, faces) = read_obj(&sample("cone_frustum.obj"));
    let metres: Vec<[f64; 3]> = vertices
        .iter()
        .map(|vertex| vertex.map(|coordinate| coordinate / 1000.0))
        .collect();
    let input = folder.path().join("cone_frustum.obj");
    write_obj(&input, &metres, &faces);
    let in_metres = folder.path().join("metres");
    let in_millimetres = folder.path().join("millimetres");
    let output = flatten_into(&input, &in_metres, &["--units", "m"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let output = flatten_into(&sample("cone_frustum.obj"), &in_millimetres, &[]);
    assert!(output.status.success(), "{}", stderr(&output));
    let part = &read_report(&in_metres)["parts"][0];
    assert_eq!(part["units"], "m");
    assert!(part["area_error"].as_f64().unwrap() < DEVELOPABLE_ERROR);
    let (flat_metres, _) = read_obj(&in_metres.join("cone_frustum.pattern.obj"));
    let (flat_millimetres, _) = read_obj(&in_millimetres.join("cone_frustum.pattern.obj"));
    let span = |points: &[[f64; 3]]| {
        let xs = points.iter().map(|point| point[0]);
        xs.clone().fold(f64::MIN, f64::max) - xs.fold(f64::MAX, f64::min)
    };
    let ratio = span(&flat_millimetres) / span(&flat_metres);
    assert!(
        (ratio - 1000.0).abs() < 1e-6 * 1000.0,
        "same pattern, in metres: {ratio}"
    );
    let dxf = std::fs::read_to_string(in_metres.join("cone_frustum.dxf")).expect("DXF");
    let lines: Vec<&str> = dxf.lines().map(str::trim).collect();
    let units = lines
        .iter()
        .position(|line| *line == "$INSUNITS")
        .expect("$INSUNITS in the header");
    assert_eq!(lines[units + 2], "6", "DXF units: metres");
}

/// A tube of radius 50 and height 100 sewn from two half panels: its OBJ gives each half its own
/// texture chart (`vt`), as a garment's sewing pattern does.
fn two_panel_tube_obj() -> String {
    let (around, rows) = (24usize, 4usize);
    let mut text = String::new();
    for j in 0..=rows {
        for i in 0..around {
            let angle = std::f64::consts::TAU * i as f64 / around as f64;
            let z = 100.0 * j as f64 / rows as f64;
            text += &format!("v {} {} {z}\n", 50.0 * angle.cos(), 50.0 * angle.sin());
        }
    }
    // Texture points: panel p's column c (0..=12) of row j; the panels lie side by side.
    let half = around / 2;
    let texture = |panel: usize, column: usize, row: usize| {
        1 + panel * (half + 1) * (rows + 1) + row * (half + 1) + column
    };
    for panel in 0..2 {
        for j in 0..=rows {
            for c in 0..=half {
                text += &format!(
                    "vt {} {}\n",
                    0.6 * panel as f64 + 0.04 * c as f64,
                    0.1 * j as f64
                );
            }
        }
    }
    for panel in 0..2 {
        for c in 0..half {
            for j in 0..rows {
                let i = panel * half + c;
                let vertex = |i: usize, j: usize| 1 + j * around + i % around;
                let corner = |di: usize, dj: usize| {
                    format!(
                        "{}/{}",
                        vertex(i + di, j + dj),
                        texture(panel, c + di, j + dj)
                    )
                };
                text += &format!(
                    "f {} {} {} {}\n",
                    corner(0, 0),
                    corner(1, 0),
                    corner(1, 1),
                    corner(0, 1)
                );
            }
        }
    }
    text
}

#[test]
fn seams_from_uv_cut_a_garment_into_its_sewing_pattern_pieces() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let input = folder.path().join("tube.obj");
    std::fs::write(&input, two_panel_tube_obj()).expect("write input");
    let pieces = folder.path().join("pieces");
    let output = flatten_into(&input, &pieces, &["--seams", "from-uv"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let report = read_report(&pieces);
    let parts = report["parts"].as_array().expect("parts");
    let names: Vec<&str> = parts.iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["tube-1", "tube-2"]);
    assert_eq!(
        report["options"]["seams"], "from-uv",
        "{}",
        report["options"]
    );
    for part in parts {
        assert_eq!(part["triangles"], 96, "{part}");
        assert!(
            part["seams"].as_array().expect("seams").is_empty(),
            "{part}"
        );
        let name = part["name"].as_str().unwrap();
        let figures = recompute(&pieces, name);
        assert!(figures.area_error <= DEVELOPABLE_ERROR, "{figures:?}");
        assert_eq!(figures.flipped, 0);
        // Each piece is half the tube: a polygonal half circumference by the height.
        let (mesh, faces) = read_obj(&pieces.join(format!("{name}.mesh.obj")));
        assert_eq!((mesh.len(), faces.len()), (13 * 5, 96));
    }
    // Without it, the tube is one part opened by the cut stage's seam.
    let whole = folder.path().join("whole");
    let output = flatten_into(&input, &whole, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let report = read_report(&whole);
    assert_eq!(report["parts"].as_array().expect("parts").len(), 1);
    assert!(
        report["options"].get("seams").is_none(),
        "the default is not echoed"
    );
}

#[test]
fn seams_from_uv_refuse_a_mesh_without_texture_points() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let output = flatten_into(
        &sample("cone_frustum.obj"),
        &folder.path().join("out"),
        &["--seams", "from-uv"],
    );
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    let message = stderr(&output);
    assert!(
        message.contains("--seams from-uv") && message.contains("vt"),
        "{message}"
    );
}

/// An OBJ box of these sizes, its faces facing out.
fn box_obj([x, y, z]: [f64; 3]) -> String {
    let mut text = String::new();
    for k in 0..8 {
        let corner = [k & 1, (k >> 1) & 1, (k >> 2) & 1].map(|bit| bit as f64);
        text += &format!("v {} {} {}\n", corner[0] * x, corner[1] * y, corner[2] * z);
    }
    // Each side as a quad of corner numbers (1-based), counter-clockwise seen from outside.
    for quad in [
        [1, 3, 4, 2],
        [5, 6, 8, 7],
        [1, 2, 6, 5],
        [3, 7, 8, 4],
        [1, 5, 7, 3],
        [2, 4, 8, 6],
    ] {
        text += &format!("f {} {} {} {}\n", quad[0], quad[1], quad[2], quad[3]);
    }
    text
}

#[test]
fn a_closed_thin_solid_mesh_is_flattened_with_a_warning_that_it_is_no_sheet_metal_unfold() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let said = |name: &str, sizes: [f64; 3]| {
        let input = folder.path().join(format!("{name}.obj"));
        std::fs::write(&input, box_obj(sizes)).expect("write input");
        let output = flatten_into(&input, &folder.path().join(name), &[]);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        stderr(&output)
    };
    // A 100 x 80 x 2 plate: 2 V / A = 2 * 16000 / 16720 = 1.914 mm.
    let plate = said("plate", [100.0, 80.0, 2.0]);
    assert!(
        plate.contains("the mesh is a closed thin solid, about 1.914 mm thick")
            && plate.contains("STEP file"),
        "{plate}"
    );
    let block = said("block", [60.0, 40.0, 30.0]);
    assert!(!block.contains("thin solid"), "{block}");
}

#[test]
fn repair_mends_a_zero_area_triangle_and_drops_a_repeated_one() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let input = folder.path().join("cap.obj");
    // Two unit squares side by side; vertex 7 halfway up their shared edge 2-5 belongs to the
    // left square only, and the cap 2-5-7 (zero area) fills the gap to the right square's edge
    // 2-5. The last face repeats the right square's second triangle.
    let text = "v 0 0 0\nv 10 0 0\nv 20 0 0\nv 0 10 0\nv 10 10 0\nv 20 10 0\nv 10 5 0\n\
                f 1 2 7\nf 1 7 5\nf 1 5 4\nf 2 5 7\nf 2 3 6\nf 2 6 5\nf 6 5 2\n";
    std::fs::write(&input, text).expect("write input");
    let refused = flatten_into(&input, &folder.path().join("refused"), &[]);
    assert_eq!(refused.status.code(), Some(1), "{}", stderr(&refused));
    let message = stderr(&refused);
    assert!(
        message.contains("triangle 4 has zero area") && message.contains("--repair"),
        "{message}"
    );
    let repaired_folder = folder.path().join("repaired");
    let repaired = flatten_into(&input, &repaired_folder, &["--repair"]);
    assert_eq!(repaired.status.code(), Some(0), "{}", stderr(&repaired));
    let message = stderr(&repaired);
    assert!(
        message.contains("triangle 7 repeats triangle 6: dropped (--repair) [line 14]"),
        "{message}"
    );
    assert!(
        message.contains("triangle 4 had zero area (its third vertex on its edge 2-5): that edge flipped (--repair) [line 11]"),
        "{message}"
    );
    let report = read_report(&repaired_folder);
    let parts = report["parts"].as_array().expect("parts");
    assert_eq!(parts.len(), 1);
    assert_eq!(parts[0]["triangles"], 6);
    let figures = recompute(&repaired_folder, "cap");
    assert!(figures.area_error <= DEVELOPABLE_ERROR, "{figures:?}");
    assert_eq!(figures.flipped, 0);
}

#[test]
fn repair_keeps_the_panels_a_texture_layout_continues_across_a_non_manifold_edge_together() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let input = folder.path().join("sewn_on.obj");
    // Two squares that the texture layout continues across edge 1-2 (one chart: texture
    // points 1-6), and a third square sewn onto that edge, a chart of its own (points 7-10).
    let text = "v 0 0 0\nv 0 0 10\nv 10 0 0\nv 10 0 10\nv -10 0 0\nv -10 0 10\n\
                v 0 10 0\nv 0 10 10\n\
                vt 0 0\nvt 0 1\nvt 1 0\nvt 1 1\nvt -1 0\nvt -1 1\n\
                vt 5 5\nvt 5 6\nvt 6 6\nvt 6 5\n\
                f 1/1 3/3 4/4 2/2\nf 2/2 6/6 5/5 1/1\nf 1/7 2/8 8/9 7/10\n";
    std::fs::write(&input, text).expect("write input");
    let output = folder.path().join("repaired");
    let repaired = flatten_into(&input, &output, &["--repair"]);
    assert_eq!(repaired.status.code(), Some(0), "{}", stderr(&repaired));
    let message = stderr(&repaired);
    assert!(
        message.contains(
            "edge 1-2 was shared by 3 triangles: split apart, keeping the 2 that the texture \
             layout (vt) continues across it together in pairs (--repair)"
        ),
        "{message}"
    );
    let report = read_report(&output);
    let mut triangles: Vec<u64> = report["parts"]
        .as_array()
        .expect("parts")
        .iter()
        .map(|part| part["triangles"].as_u64().expect("triangles"))
        .collect();
    triangles.sort_unstable();
    assert_eq!(
        triangles,
        vec![2, 4],
        "the sewn-on square, and the chart's two squares in one"
    );
    for part in report["parts"].as_array().expect("parts") {
        let figures = recompute(&output, part["name"].as_str().unwrap());
        assert!(figures.area_error <= DEVELOPABLE_ERROR, "{figures:?}");
        assert_eq!(figures.flipped, 0);
    }
}

/// A mesh a few units across read as millimetres (a garment exported in metres) gets a warning
/// naming `--units m`; read as metres, none.
#[test]
fn a_mesh_under_two_centimetres_across_is_warned_about_its_units() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let input = folder.path().join("panel.obj");
    std::fs::write(
        &input,
        "v 0 0 0\nv 1.2 0 0\nv 1.2 0.9 0\nv 0 0.9 0\nf 1 2 3 4\n",
    )
    .expect("write input");
    let read_as_mm = flatten_into(&input, &folder.path().join("mm"), &[]);
    assert_eq!(read_as_mm.status.code(), Some(0), "{}", stderr(&read_as_mm));
    assert!(
        stderr(&read_as_mm).contains(
            "the mesh is only 1.500 mm across (its bounding box's diagonal, read in \
             millimetres): if the file is in metres (as garment tools export) or centimetres, \
             give --units m or --units cm"
        ),
        "{}",
        stderr(&read_as_mm)
    );
    let read_as_m = flatten_into(&input, &folder.path().join("m"), &["--units", "m"]);
    assert_eq!(read_as_m.status.code(), Some(0), "{}", stderr(&read_as_m));
    assert!(
        !stderr(&read_as_m).contains("--units"),
        "{}",
        stderr(&read_as_m)
    );
}

#[test]
fn a_triangle_soup_is_refused_and_repair_welds_it_into_one_part() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let input = folder.path().join("soup.obj");
    // A 30 x 10 strip of six triangles, each with three vertices of its own (as some STL to
    // OBJ converters write them): without welding, six parts of one triangle each.
    let mut text = String::new();
    for i in 0..3 {
        let (x, y) = (10 * i, 10 * (i + 1));
        text += &format!("v {x} 0 0\nv {y} 0 0\nv {y} 10 0\nv {x} 0 0\nv {y} 10 0\nv {x} 10 0\n");
    }
    for t in 0..6 {
        text += &format!("f {} {} {}\n", 3 * t + 1, 3 * t + 2, 3 * t + 3);
    }
    std::fs::write(&input, text).expect("write input");
    let refused_folder = folder.path().join("refused");
    let refused = flatten_into(&input, &refused_folder, &[]);
    assert_eq!(refused.status.code(), Some(1), "{}", stderr(&refused));
    let message = stderr(&refused);
    assert!(
        message.contains(
            "6 of the 6 triangles (first: 1) share no edge with another though their corners \
             lie on other triangles' vertices: the file gives each triangle vertices of its own; \
             --repair welds vertices at the same point [line 19]"
        ),
        "{message}"
    );
    assert!(!refused_folder.join("report.json").exists());
    let repaired_folder = folder.path().join("repaired");
    let repaired = flatten_into(&input, &repaired_folder, &["--repair"]);
    assert_eq!(repaired.status.code(), Some(0), "{}", stderr(&repaired));
    let message = stderr(&repaired);
    // 18 corners at 8 points: 10 welds, all named (the tenth is the last named one).
    assert!(
        message.contains("vertex 18 lies on vertex 9: welded into it (--repair)")
            && !message.contains("more vertices lay on earlier vertices"),
        "{message}"
    );
    let report = read_report(&repaired_folder);
    let parts = report["parts"].as_array().expect("parts");
    assert_eq!(parts.len(), 1, "one strip");
    assert_eq!(parts[0]["triangles"], 6);
    let figures = recompute(&repaired_folder, parts[0]["name"].as_str().unwrap());
    assert!(figures.area_error <= DEVELOPABLE_ERROR, "{figures:?}");
    assert_eq!(figures.flipped, 0);
}

#[test]
fn a_mobius_strip_is_refused_and_repair_cuts_it_open_into_one_flat_strip() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let input = folder.path().join("mobius.obj");
    // 16 quads around a circle of radius 100 mm, 60 mm wide, the band turning half a turn on the
    // way round, its ends glued with that twist: every vertex on the boundary, so it is
    // developable once cut.
    let segments = 16;
    let mut text = String::new();
    for i in 0..segments {
        let angle = std::f64::consts::TAU * i as f64 / segments as f64;
        let (radial, height) = (30.0 * (angle / 2.0).cos(), 30.0 * (angle / 2.0).sin());
        for side in [-1.0, 1.0] {
            let radius = 100.0 + side * radial;
            let (x, y, z) = (radius * angle.cos(), radius * angle.sin(), side * height);
            text += &format!("v {x} {y} {z}\n");
        }
    }
    for i in 0..segments {
        let (a, b) = (2 * i + 1, 2 * i + 2);
        let (c, d) = if i + 1 == segments {
            (2, 1)
        } else {
            (a + 2, b + 2)
        };
        text += &format!("f {a} {c} {b}\nf {b} {c} {d}\n");
    }
    std::fs::write(&input, text).expect("write input");
    let refused = flatten_into(&input, &folder.path().join("refused"), &[]);
    assert_eq!(refused.status.code(), Some(1), "{}", stderr(&refused));
    let message = stderr(&refused);
    assert!(
        message.contains("the surface is not orientable")
            && message.contains("cuts a non-orientable surface open"),
        "{message}"
    );
    let repaired_folder = folder.path().join("repaired");
    let repaired = flatten_into(&input, &repaired_folder, &["--repair"]);
    assert_eq!(repaired.status.code(), Some(0), "{}", stderr(&repaired));
    assert!(
        stderr(&repaired).contains("cut open along 1 edge(s)"),
        "{}",
        stderr(&repaired)
    );
    let report = read_report(&repaired_folder);
    let parts = report["parts"].as_array().expect("parts");
    assert_eq!(parts.len(), 1, "one strip");
    assert_eq!(parts[0]["triangles"], 2 * segments);
    let figures = recompute(&repaired_folder, parts[0]["name"].as_str().unwrap());
    assert!(figures.area_error <= DEVELOPABLE_ERROR, "{figures:?}");
    assert_eq!(figures.flipped, 0);
}

#[test]
fn repair_splits_a_non_manifold_edge_that_stops_the_mesh_otherwise() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let input = folder.path().join("three_panels.obj");
    // Three squares sewn along one edge (vertices 1-2), and vertex 1 repeated as vertex 9.
    let text = "v 0 0 0\nv 0 0 10\nv 10 0 0\nv 10 0 10\nv -10 0 0\nv -10 0 10\n\
                v 0 10 0\nv 0 10 10\nv 0 0 0\n\
                f 1 3 4 2\nf 2 6 5 1\nf 9 2 8 7\n";
    std::fs::write(&input, text).expect("write input");
    let refused = flatten_into(&input, &folder.path().join("refused"), &[]);
    assert_eq!(refused.status.code(), Some(1), "{}", stderr(&refused));
    let message = stderr(&refused);
    assert!(message.contains("--repair"), "{message}");
    let repaired_folder = folder.path().join("repaired");
    let repaired = flatten_into(&input, &repaired_folder, &["--repair"]);
    assert_eq!(repaired.status.code(), Some(0), "{}", stderr(&repaired));
    let message = stderr(&repaired);
    assert!(
        message.contains("vertex 9 lies on vertex 1: welded into it (--repair) [lines 9 and 1]"),
        "{message}"
    );
    assert!(
        message.contains("edge 1-2 was shared by 3 triangles: split apart (--repair)"),
        "{message}"
    );
    let report = read_report(&repaired_folder);
    assert_eq!(report["options"]["repair"], true);
    let parts = report["parts"].as_array().expect("parts");
    assert_eq!(parts.len(), 3, "three panels");
    for part in parts {
        let figures = recompute(&repaired_folder, part["name"].as_str().unwrap());
        assert!(figures.area_error <= DEVELOPABLE_ERROR, "{figures:?}");
    }
}
