//! `--seams pieces` (issue 13): a part cut into pieces by plane sections, each flattened within
//! tolerance. Checked from the written files alone: every piece's `E_S`, `E_C` and flips
//! recomputed by [`crate::util::recompute`], and the pieces' meshes together the input surface
//! (a section moves a vertex onto it only where the area of the vertex's faces changes by at most
//! [`MAX_FAN_AREA_CHANGE`], so each section changes the area by at most that fraction; the
//! pieces together are asserted within one such fraction of the input).

use std::f64::consts::TAU;
use std::path::Path;

use flatcut::mesh::MAX_FAN_AREA_CHANGE;

use crate::util::{
    area, flatten_into, read_obj, read_report, recompute, sample, stderr, write_obj,
};

/// A torus of radii 100 and 40, `around` × `across` quads, two triangles each: a closed surface
/// with a handle.
fn torus(around: usize, across: usize) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let (major, minor) = (100.0, 40.0);
    let mut vertices = Vec::new();
    for i in 0..around {
        let u = TAU * i as f64 / around as f64;
        for j in 0..across {
            let v = TAU * j as f64 / across as f64;
            let r = major + minor * v.cos();
            vertices.push([r * u.cos(), r * u.sin(), minor * v.sin()]);
        }
    }
    let at = |i: usize, j: usize| (i % around) * across + j % across;
    let mut faces = Vec::new();
    for i in 0..around {
        for j in 0..across {
            faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            faces.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    (vertices, faces)
}

/// Total area of an OBJ file's triangles.
fn surface_area(path: &Path) -> f64 {
    let (vertices, faces) = read_obj(path);
    faces
        .iter()
        .map(|&[a, b, c]| area(vertices[a], vertices[b], vertices[c]))
        .sum()
}

/// Flattens `input` with `options` into pieces and checks every piece; returns the pieces'
/// names.
fn assert_pieces_within_tolerance(input: &Path, directory: &Path, options: &[&str]) -> Vec<String> {
    let output = flatten_into(input, directory, options);
    assert!(output.status.success(), "{}", stderr(&output));
    let report = read_report(directory);
    let parts = report["parts"].as_array().expect("parts");
    let names: Vec<String> = parts
        .iter()
        .map(|part| part["name"].as_str().expect("name").to_owned())
        .collect();
    let mut pieces_area = 0.0;
    for (part, name) in parts.iter().zip(&names) {
        let figures = recompute(directory, name);
        assert_eq!(figures.flipped, 0, "{name}");
        assert!(figures.area_error <= 0.01, "{name}: {figures:?}");
        assert!(figures.shape_error <= 0.01, "{name}: {figures:?}");
        assert_eq!(part["tolerance_met"], true, "{name}");
        assert_eq!(part["cuts"].as_array().map(Vec::len), Some(0), "{name}");
        let sections = part["seams"].as_array().expect("seams");
        assert!(
            sections.iter().any(|seam| seam["kind"] == "section"),
            "{name}: every piece is bounded by a section"
        );
        assert!(directory.join(format!("{name}.dxf")).is_file(), "{name}");
        pieces_area += surface_area(&directory.join(format!("{name}.mesh.obj")));
    }
    let input_area = surface_area(input);
    assert!(
        (pieces_area - input_area).abs() <= MAX_FAN_AREA_CHANGE * input_area,
        "the pieces make up the surface: {pieces_area} against {input_area}"
    );
    names
}

/// A closed torus stays over tolerance whole: `--seams whole` rejects it after its crest-line
/// cuts, the default cuts it into pieces instead, and each piece says why.
#[test]
fn a_torus_over_tolerance_whole_comes_out_in_pieces_each_within_tolerance() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let input = directory.path().join("torus.obj");
    let (vertices, faces) = torus(48, 20);
    write_obj(&input, &vertices, &faces);
    let whole = flatten_into(
        &input,
        &directory.path().join("whole"),
        &["--seams", "whole"],
    );
    assert_eq!(whole.status.code(), Some(3), "{}", stderr(&whole));
    assert!(
        stderr(&whole).contains("--seams auto cuts"),
        "{}",
        stderr(&whole)
    );
    let pieces = directory.path().join("pieces");
    let names = assert_pieces_within_tolerance(&input, &pieces, &[]);
    assert!(names.len() >= 4, "{names:?}");
    assert_eq!(names[0], "torus-p1");
    let report = read_report(&pieces);
    let warnings = report["parts"][0]["warnings"].to_string();
    assert!(
        warnings.contains(&format!(
            "cut into {} pieces (--seams auto): whole, closed, it does not lie flat",
            names.len()
        )),
        "{warnings}"
    );
}

#[test]
fn the_hemisphere_comes_out_in_pieces_each_within_tolerance_with_the_same_files_each_run() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let input = sample("hemisphere.obj");
    let first = directory.path().join("first");
    let names = assert_pieces_within_tolerance(&input, &first, &["--seams", "pieces"]);
    assert!(names.len() >= 2, "{names:?}");
    let second = directory.path().join("second");
    let output = flatten_into(&input, &second, &["--seams", "pieces"]);
    assert!(output.status.success(), "{}", stderr(&output));
    for name in &names {
        for file in [format!("{name}.dxf"), format!("{name}.pattern.json")] {
            assert_eq!(
                std::fs::read(first.join(&file)).expect("first"),
                std::fs::read(second.join(&file)).expect("second"),
                "{file} is the same each run"
            );
        }
    }
    assert_eq!(
        std::fs::read(first.join("report.json")).expect("first"),
        std::fs::read(second.join("report.json")).expect("second"),
    );
}
