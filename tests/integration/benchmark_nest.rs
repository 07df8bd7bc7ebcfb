//! `flatcut nest` on a benchmark instance writes what `flatcut run` writes for its sheets: a DXF
//! (read and audited by ezdxf, one closed outer cut contour per part) and a PNG per sheet, and a
//! density in `nest.json` equal to an independent recomputation from the instance file.

use std::path::Path;

use serde_json::Value;

use crate::util::{assert_ezdxf_accepts, flatcut, sample, stderr};

/// Shoelace area of a ring given as `[[x, y], ...]` (absolute).
fn ring_area(points: &[Value]) -> f64 {
    let point = |value: &Value| {
        let pair = value.as_array().expect("a point");
        (pair[0].as_f64().expect("x"), pair[1].as_f64().expect("y"))
    };
    let twice: f64 = (0..points.len())
        .map(|i| {
            let (a, b) = (point(&points[i]), point(&points[(i + 1) % points.len()]));
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    twice.abs() / 2.0
}

/// Net area of every copy of the instance's items, read from its file (simple polygons).
fn instance_area(instance: &Path) -> f64 {
    let text = std::fs::read_to_string(instance).expect("instance file");
    let value: Value = serde_json::from_str(&text).expect("instance JSON");
    (value["items"].as_array().expect("items").iter())
        .map(|item| {
            let shape = &item["shape"];
            assert_eq!(shape["type"], "simple_polygon", "{item}");
            let demand = item["demand"].as_f64().expect("demand");
            demand * ring_area(shape["data"].as_array().expect("outline"))
        })
        .sum()
}

/// Runs `flatcut nest INSTANCE -o DIR EXTRA... --work 300000 --time 600 --seed 0` and returns
/// its `nest.json`.
fn nest_instance(instance: &Path, directory: &Path, extra: &[&str]) -> Value {
    let mut arguments = vec![
        "nest",
        instance.to_str().expect("utf-8"),
        "-o",
        directory.to_str().expect("utf-8"),
        "--work",
        "300000",
        "--time",
        "600",
        "--seed",
        "0",
    ];
    arguments.extend_from_slice(extra);
    let output = flatcut(&arguments);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(stderr(&output).contains("density"), "{}", stderr(&output));
    let text = std::fs::read_to_string(directory.join("nest.json")).expect("nest.json written");
    serde_json::from_str(&text).expect("nest.json is JSON")
}

/// Every sheet of `report` has its DXF (ezdxf reads it; one outer cut contour per part) and its
/// PNG, under the names `sheet_files` lists.
fn check_sheet_files(directory: &Path, report: &Value) {
    let sheets = report["sheets"].as_array().expect("sheets");
    let files = report["sheet_files"].as_array().expect("sheet_files");
    assert_eq!(files.len(), sheets.len());
    for (index, (sheet, file)) in sheets.iter().zip(files).enumerate() {
        let expected = format!("sheets/sheet-{:03}.dxf", index + 1);
        assert_eq!(file.as_str(), Some(expected.as_str()));
        let dxf = directory.join(&expected);
        let parts = sheet["placements"].as_array().expect("placements").len();
        assert!(parts > 0);
        let count = format!("CUT_OUTER:LWPOLYLINE:{parts}");
        assert_ezdxf_accepts(&dxf, &["--count", &count]);
        let png = std::fs::read(dxf.with_extension("png")).expect("sheet PNG written");
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "{}", expected);
    }
}

#[test]
fn a_benchmark_on_a_roll_writes_its_sheet_files_and_a_recomputable_density() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let instance = sample("nesting/fu.json");
    let report = nest_instance(&instance, directory.path(), &[]);
    check_sheet_files(directory.path(), &report);
    let height = report["options"]["stock"]["roll"]["width"]
        .as_f64()
        .expect("a roll's width");
    let used = height * report["used_length"].as_f64().expect("used_length");
    let density = report["density"].as_f64().expect("density");
    let recomputed = instance_area(&instance) / used;
    assert!(
        (density - recomputed).abs() < 1e-9,
        "{density} vs {recomputed}"
    );
    assert!(density > 0.6 && density < 1.0, "{density}");
}

#[test]
fn a_benchmark_on_sheets_writes_every_sheet_and_a_recomputable_density() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let instance = sample("nesting/fu.json");
    let report = nest_instance(&instance, directory.path(), &["--sheet", "20x38.0038"]);
    check_sheet_files(directory.path(), &report);
    let sheets = report["sheets"].as_array().expect("sheets").len();
    assert!(sheets >= 2, "1083 mm² of parts on 760 mm² sheets");
    let density = report["density"].as_f64().expect("density");
    let recomputed = instance_area(&instance) / (sheets as f64 * 20.0 * 38.0038);
    assert!(
        (density - recomputed).abs() < 1e-9,
        "{density} vs {recomputed}"
    );
}
