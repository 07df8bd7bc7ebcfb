//! Bad inputs: exit code 1, a message naming the file and the defect, no panic, no output.

use std::path::Path;

use crate::util::{flatcut, stderr};

/// Writes `content` to `name` in a fresh directory, flattens it, and checks the refusal.
fn refuses(name: &str, content: &[u8], expected: &str) {
    let directory = tempfile::tempdir().expect("temporary directory");
    let input = directory.path().join(name);
    std::fs::write(&input, content).expect("write input");
    let output_directory = directory.path().join("out");
    let output = flatcut(&["flatten", path(&input), "-o", path(&output_directory)]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{name}: {message}");
    assert!(
        message.contains(name),
        "{name}: the message names the file: {message}"
    );
    assert!(
        message.to_lowercase().contains(expected),
        "{name}: expected '{expected}' in: {message}"
    );
    assert!(!message.contains("panicked"), "{name}: {message}");
    assert!(!output_directory.exists(), "{name}: no output is written");
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

const TRIANGLE_PAIR: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn empty_file() {
    refuses("empty.obj", b"", "no triangles");
}

#[test]
fn binary_garbage() {
    let garbage: Vec<u8> = (0..1000u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    refuses("garbage.stl", &garbage, "not an ascii stl");
    refuses("garbage.obj", &garbage, "not utf-8");
}

#[test]
fn nan_coordinates() {
    refuses(
        "nan.obj",
        format!("{TRIANGLE_PAIR}v nan 0 0\nf 1 2 3\nf 1 3 5\n").as_bytes(),
        "nan",
    );
}

#[test]
fn face_index_out_of_range() {
    refuses(
        "range.obj",
        format!("{TRIANGLE_PAIR}f 1 2 9\n").as_bytes(),
        "out of range",
    );
}

#[test]
fn non_manifold_edge() {
    let text = format!("{TRIANGLE_PAIR}v 0 -1 1\nf 1 2 3\nf 1 3 4\nf 3 1 5\n");
    refuses("fin.obj", text.as_bytes(), "non-manifold");
}

#[test]
fn zero_area_triangle() {
    let text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 2 3 4\nf 1 3 2\n";
    refuses("sliver.obj", text.as_bytes(), "zero area");
}

#[test]
fn closed_surface() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
    refuses("tetrahedron.obj", text.as_bytes(), "closed");
}

#[test]
fn missing_file() {
    let output = flatcut(&[
        "flatten",
        "/nonexistent/part.obj",
        "-o",
        "/tmp/flatcut-never-written",
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr(&output).contains("/nonexistent/part.obj: cannot read"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn unknown_kind() {
    refuses(
        "notes.txt",
        b"hello, this is not a mesh\n",
        "unknown input kind",
    );
}
