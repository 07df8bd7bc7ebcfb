//! `flatcut run --sheet`: parts nested on sheets, sheet files written, byte-identical reruns, and
//! every DXF the run writes checked by ezdxf (a real external reader) when it is installed.

use std::path::Path;

use crate::util::{assert_ezdxf_accepts, flatcut, read_obj, read_report, sample, stderr};

fn run_on_sheets(directory: &Path) {
    let output = flatcut(&[
        "run",
        sample("cone_frustum.toml").to_str().expect("utf-8"),
        sample("garment_panel.toml").to_str().expect("utf-8"),
        "-o",
        directory.to_str().expect("utf-8"),
        "--sheet",
        "1200x800",
        "--gap",
        "3",
        // The deterministic budget of `--time 1`, with a clock cap no loaded machine reaches:
        // with `--time 1` alone the clock could end the search first, and the reruns differ.
        "--work",
        "1000000",
        "--time",
        "600",
        "--no-timings",
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}

#[test]
fn parts_are_nested_on_sheets_and_reruns_are_identical() {
    let first = tempfile::tempdir().expect("temporary directory");
    let second = tempfile::tempdir().expect("temporary directory");
    run_on_sheets(first.path());
    run_on_sheets(second.path());
    let report = read_report(first.path());
    let sheets = report["sheets"].as_array().expect("sheets");
    assert!(!sheets.is_empty());
    let placed: usize = sheets
        .iter()
        .map(|s| s["parts"].as_array().expect("parts").len())
        .sum();
    assert_eq!(placed, 3, "cone frustum x2 and garment panel x1: {report}");
    for name in [
        "report.json",
        "sheets/sheet-001.dxf",
        "cone_frustum.dxf",
        "garment_panel.dxf",
    ] {
        let a = std::fs::read(first.path().join(name)).expect("read");
        let b = std::fs::read(second.path().join(name)).expect("read");
        assert!(a == b, "{name} differs between runs");
    }
    assert!(first.path().join("sheets/sheet-001.png").exists());
    check_every_dxf_with_ezdxf(first.path());
}

/// Checks the sheet and part DXFs of `directory` with ezdxf ([`assert_ezdxf_accepts`]).
fn check_every_dxf_with_ezdxf(directory: &Path) {
    let mut files = vec![directory.join("sheets/sheet-001.dxf")];
    files.extend(["cone_frustum.dxf", "garment_panel.dxf"].map(|name| directory.join(name)));
    for file in files {
        assert_ezdxf_accepts(&file, &[]);
    }
}

/// Nests the cylinder panel (radius 150 mm, 120°, height 200 mm: a 314 × 200 mm rectangle once
/// unrolled, whose 200 mm side follows the axis) with `grain` and any multiple of 30° allowed,
/// and returns the extents along x and y of its pattern.obj turned (and mirrored) as reported.
fn nested_cylinder_panel_extents(grain: &str) -> (f64, f64) {
    let directory = tempfile::tempdir().expect("temporary directory");
    let sample_text = std::fs::read_to_string(sample("cylinder_panel.toml")).expect("sample");
    let part = directory.path().join("cylinder_panel.toml");
    let text = sample_text.replace("grain = [0.0, 0.0, 1.0]", &format!("grain = {grain}"));
    std::fs::write(&part, text).expect("part file written");
    let output_directory = directory.path().join("out");
    let output = flatcut(&[
        "run",
        part.to_str().expect("utf-8"),
        "-o",
        output_directory.to_str().expect("utf-8"),
        "--sheet",
        "1000x1000",
        "--rotations",
        "step:30",
        "--time",
        "1",
        "--no-timings",
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let report = read_report(&output_directory);
    let placement = &report["sheets"][0]["parts"][0];
    let rotation = placement["rotation"]
        .as_f64()
        .expect("rotation")
        .to_radians();
    let (vertices, _) = read_obj(&output_directory.join("cylinder_panel.pattern.obj"));
    let turned: Vec<(f64, f64)> = vertices
        .iter()
        .map(|v| {
            let x = if placement["mirrored"] == true {
                -v[0]
            } else {
                v[0]
            };
            (
                x * rotation.cos() - v[1] * rotation.sin(),
                x * rotation.sin() + v[1] * rotation.cos(),
            )
        })
        .collect();
    let extent = |coordinate: fn(&(f64, f64)) -> f64| {
        let values = turned.iter().map(coordinate);
        values.clone().fold(f64::NEG_INFINITY, f64::max) - values.fold(f64::INFINITY, f64::min)
    };
    (extent(|p| p.0), extent(|p| p.1))
}

/// The grain, mapped from 3D onto the pattern, ends up along the sheet's x axis: along the axis,
/// the 200 mm side lies along x (what the shortest layout wants anyway); around the
/// circumference, the 314 mm side must lie along x although the layout gets longer.
#[test]
fn a_part_with_grain_is_nested_with_the_grain_along_x() {
    let circumference = 100.0 * std::f64::consts::PI;
    let (along_x, along_y) = nested_cylinder_panel_extents("[0.0, 0.0, 1.0]");
    assert!(
        (along_x - 200.0).abs() < 1.0,
        "axis grain: x extent {along_x}"
    );
    assert!(
        (along_y - circumference).abs() < 1.0,
        "axis grain: y extent {along_y}"
    );
    let (along_x, along_y) = nested_cylinder_panel_extents("[1.0, 0.0, 0.0]");
    assert!(
        (along_x - circumference).abs() < 1.0,
        "circumferential grain: x extent {along_x}"
    );
    assert!(
        (along_y - 200.0).abs() < 1.0,
        "circumferential grain: y extent {along_y}"
    );
}

/// A part a fraction of a millimetre round (a scan's piece in the wrong units), whose cut outline
/// is drawn as two arcs, still gets a nesting polygon with an area: it was refused, "the outline
/// has fewer than 3 points", and the whole run with it.
#[test]
fn a_sub_millimetre_part_is_nested() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let input = directory.path().join("tiny_disc.obj");
    let segments = 48;
    let mut vertices = vec![[0.0, 0.0, 0.0]];
    vertices.extend((0..segments).map(|k| {
        let angle = std::f64::consts::TAU * k as f64 / segments as f64;
        [0.1 * angle.cos(), 0.1 * angle.sin(), 0.0]
    }));
    let faces: Vec<[usize; 3]> = (0..segments)
        .map(|k| [0, 1 + k, 1 + (k + 1) % segments])
        .collect();
    crate::util::write_obj(&input, &vertices, &faces);
    let out = directory.path().join("out");
    let output = flatcut(&[
        "run",
        input.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
        "--roll",
        "100",
        "--work",
        "2000",
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let report = read_report(&out);
    assert_eq!(report["sheets"].as_array().map(Vec::len), Some(1));
}
