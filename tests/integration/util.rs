//! Helpers shared by the integration tests: running the binary, reading its outputs with a
//! parser of our own (independent of the library), and recomputing the paper's measures.

use std::path::{Path, PathBuf};
use std::process::Output;

/// Path of a bundled sample.
pub fn sample(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("samples")
        .join(name)
}

/// Runs `flatcut` with the arguments.
pub fn flatcut(arguments: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_flatcut"))
        .args(arguments)
        .output()
        .expect("flatcut runs")
}

/// Runs `flatcut flatten INPUT -o DIR --no-timings EXTRA...` and returns the output.
pub fn flatten_into(input: &Path, directory: &Path, extra: &[&str]) -> Output {
    let mut arguments = vec![
        "flatten",
        input.to_str().expect("utf-8 path"),
        "-o",
        directory.to_str().expect("utf-8 path"),
    ];
    arguments.push("--no-timings");
    arguments.extend_from_slice(extra);
    flatcut(&arguments)
}

/// Runs `tests/dxf_check.py FILE --no-fixes EXTRA...` (ezdxf reads the file and audits it; see
/// the script for what `EXTRA` can ask) and asserts it passes. Skipped when ezdxf is not
/// installed, except under CI, which needs it (`pip install -r requirements-test.txt`).
pub fn assert_ezdxf_accepts(file: &Path, extra: &[&str]) {
    let available = std::process::Command::new("python3")
        .args(["-c", "import ezdxf"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !available {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI needs ezdxf: pip install -r requirements-test.txt"
        );
        eprintln!("SKIPPED: ezdxf is not installed (pip install -r requirements-test.txt)");
        return;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/dxf_check.py");
    let output = std::process::Command::new("python3")
        .arg(&script)
        .arg(file)
        .arg("--no-fixes")
        .args(extra)
        .output()
        .expect("python3 runs");
    assert!(
        output.status.success(),
        "{}: {}{}",
        file.display(),
        String::from_utf8_lossy(&output.stdout),
        stderr(&output)
    );
}

/// The standard error of a run, as text.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Vertices and triangles of an OBJ file (only `v` and triangular `f` lines).
pub fn read_obj(path: &Path) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.first() {
            Some(&"v") => {
                vertices.push([1, 2, 3].map(|i| words[i].parse::<f64>().expect("number")))
            }
            Some(&"f") => {
                faces.push([1, 2, 3].map(|i| words[i].parse::<usize>().expect("index") - 1))
            }
            _ => {}
        }
    }
    (vertices, faces)
}

/// The report of a run.
pub fn read_report(directory: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(directory.join("report.json")).expect("report.json written");
    serde_json::from_str(&text).expect("report.json is JSON")
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Area of the 3D triangle `a b c`.
pub fn area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let cross = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    0.5 * (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt()
}

/// Independently recomputed figures of a mesh and its pattern.
#[derive(Debug)]
pub struct Recomputed {
    /// E_S, Eq. 4.
    pub area_error: f64,
    /// E_C, Eq. 6, each undirected edge once.
    pub shape_error: f64,
    /// Flat triangles with non-positive signed area.
    pub flipped: usize,
}

/// Recomputes E_S, E_C and flips from `<part>.mesh.obj` and `<part>.pattern.obj`.
pub fn recompute(directory: &Path, part: &str) -> Recomputed {
    let (mesh, faces) = read_obj(&directory.join(format!("{part}.mesh.obj")));
    let (pattern, pattern_faces) = read_obj(&directory.join(format!("{part}.pattern.obj")));
    assert_eq!(faces, pattern_faces, "mesh and pattern share their faces");
    assert_eq!(
        mesh.len(),
        pattern.len(),
        "mesh and pattern share their vertices"
    );
    assert!(
        pattern.iter().all(|p| p[2] == 0.0),
        "the pattern lies in z = 0"
    );
    let (mut area_difference, mut area_total, mut flipped) = (0.0, 0.0, 0);
    let mut edges = std::collections::BTreeSet::new();
    for &[a, b, c] in &faces {
        let original = area(mesh[a], mesh[b], mesh[c]);
        let [p, q, r] = [pattern[a], pattern[b], pattern[c]];
        let signed = 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
        if signed <= 0.0 {
            flipped += 1;
        }
        area_difference += (original - signed.abs()).abs();
        area_total += original;
        for (x, y) in [(a, b), (b, c), (c, a)] {
            edges.insert((x.min(y), x.max(y)));
        }
    }
    let (mut length_difference, mut length_total) = (0.0, 0.0);
    for (a, b) in edges {
        let original = distance(mesh[a], mesh[b]);
        length_difference += (original - distance(pattern[a], pattern[b])).abs();
        length_total += original;
    }
    Recomputed {
        area_error: area_difference / area_total,
        shape_error: length_difference / length_total,
        flipped,
    }
}

/// Writes an OBJ file from vertices and 0-based triangles.
pub fn write_obj(path: &Path, vertices: &[[f64; 3]], faces: &[[usize; 3]]) {
    let mut text = String::new();
    for v in vertices {
        text.push_str(&format!("v {} {} {}\n", v[0], v[1], v[2]));
    }
    for f in faces {
        text.push_str(&format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1));
    }
    std::fs::write(path, text).expect("write test OBJ");
}
