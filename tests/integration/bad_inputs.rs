//! Bad inputs: exit code 1, a message naming the file and the defect, no panic, no output.

use std::path::Path;

use crate::util::{flatcut, stderr};

/// Writes `content` to `name` in a fresh directory, flattens it, and checks the refusal.
fn refuses(name: &str, content: &[u8], expected: &str) {
    refuses_with(name, content, &[], expected);
}

/// As [`refuses`], with `options` on the command line.
fn refuses_with(name: &str, content: &[u8], options: &[&str], expected: &str) {
    let directory = tempfile::tempdir().expect("temporary directory");
    let input = directory.path().join(name);
    std::fs::write(&input, content).expect("write input");
    let output_directory = directory.path().join("out");
    let mut arguments = vec!["flatten", path(&input), "-o", path(&output_directory)];
    arguments.extend_from_slice(options);
    let output = flatcut(&arguments);
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

/// OBJ text of a torus (radii 3 and 1) on an 8 x 4 grid, without its first `missing` quads.
fn holed_torus(missing: usize) -> String {
    let (around, across) = (8, 4);
    let mut text = String::new();
    for i in 0..around {
        for j in 0..across {
            let (u, v) = (
                i as f64 * std::f64::consts::TAU / around as f64,
                j as f64 * std::f64::consts::TAU / across as f64,
            );
            let radius = 3.0 + v.cos();
            text.push_str(&format!(
                "v {} {} {}\n",
                radius * u.cos(),
                radius * u.sin(),
                v.sin()
            ));
        }
    }
    let index = |i: usize, j: usize| (i % around) * across + (j % across) + 1;
    for i in 0..around {
        for j in 0..across {
            if i * across + j < missing {
                continue;
            }
            let (a, b, c, d) = (
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            );
            text.push_str(&format!("f {a} {b} {c}\nf {a} {c} {d}\n"));
        }
    }
    text
}

/// Automatic seams do not cut handles: kept whole, such a surface is refused; by default it is
/// cut into pieces instead.
#[test]
fn surface_with_a_handle_and_a_boundary() {
    let text = holed_torus(1);
    refuses_with(
        "handle.obj",
        text.as_bytes(),
        &["--seams", "whole"],
        "handle",
    );
    let directory = tempfile::tempdir().expect("temporary directory");
    let input = directory.path().join("handle.obj");
    std::fs::write(&input, &text).expect("write input");
    let output = crate::util::flatten_into(&input, &directory.path().join("out"), &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let report = crate::util::read_report(&directory.path().join("out"));
    let warnings = report["parts"][0]["warnings"].to_string();
    assert!(
        warnings.contains("it has genus 1, which automatic seams do not open"),
        "{warnings}"
    );
}

#[test]
fn truncated_ascii_stl() {
    let facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
    let whole = format!("solid t\n{facet}{facet}endsolid t\n");
    let cut_inside_a_facet = &whole[..whole.rfind("vertex 0 1 0").expect("last corner")];
    refuses("cut.stl", cut_inside_a_facet.as_bytes(), "truncated");
    let cut_between_facets = &whole[..whole.rfind("endsolid").expect("end")];
    refuses("short.stl", cut_between_facets.as_bytes(), "truncated");
}

/// Absurd nesting options are refused before the search starts (a 1e12 mm sheet hung it, a
/// rotation step of 1e-9 degrees aborted on memory).
#[test]
fn absurd_stock_and_rotation_step() {
    let input = crate::util::sample("cone_frustum.obj");
    let directory = tempfile::tempdir().expect("temporary directory");
    let output_directory = directory.path().join("out");
    for (options, expected) in [
        (["--sheet", "1e12x1000"], "sheet width is 1000000000000"),
        (["--roll", "1e12"], "roll width is 1000000000000"),
        (
            ["--rotations", "step:1e-9"],
            "rotation step 0.000000001 degrees",
        ),
    ] {
        let mut arguments = vec!["run", path(&input), "-o", path(&output_directory)];
        arguments.extend(options);
        if options[0] == "--rotations" {
            arguments.extend(["--sheet", "1500x1000"]);
        }
        let output = flatcut(&arguments);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{options:?}: {message}");
        assert!(message.contains(expected), "{options:?}: {message}");
    }
}

/// A chord tolerance far below the part's size is refused (1e-12 mm refined without end).
#[test]
fn absurd_chord() {
    let input = crate::util::sample("cone_frustum.toml");
    let directory = tempfile::tempdir().expect("temporary directory");
    let mesh = directory.path().join("mesh.obj");
    let output = flatcut(&[
        "tessellate",
        path(&input),
        "-o",
        path(&mesh),
        "--chord",
        "1e-12",
    ]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("cone_frustum.toml") && message.contains("the chord at least"),
        "{message}"
    );
    assert!(!mesh.exists());
}

/// Two parts of one name: the second's files would overwrite the first's.
#[test]
fn two_parts_of_one_name() {
    let (mesh, part) = (
        crate::util::sample("cone_frustum.obj"),
        crate::util::sample("cone_frustum.toml"),
    );
    let directory = tempfile::tempdir().expect("temporary directory");
    let output_directory = directory.path().join("out");
    let output = flatcut(&[
        "flatten",
        path(&mesh),
        path(&part),
        "-o",
        path(&output_directory),
    ]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("cone_frustum.toml: part 'cone_frustum' has the name of a part from"),
        "{message}"
    );
    assert!(!output_directory.exists());
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
    let message = stderr(&output);
    assert!(
        message.contains("/nonexistent/part.obj: cannot read"),
        "{message}"
    );
    assert_eq!(
        message.matches("No such file").count(),
        1,
        "the reason is given once: {message}"
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

/// A 1e300 coordinate is named too large, not a zero-area triangle.
#[test]
fn too_large_coordinate() {
    refuses(
        "huge.obj",
        b"v 0 0 0\nv 1e300 0 0\nv 0 1e300 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n",
        "coordinate too large (1e300",
    );
}

/// A mesh size too small for the part: the figures of the message are rounded.
#[test]
fn too_small_mesh_size_prints_rounded_figures() {
    let input = crate::util::sample("cone_frustum.toml");
    let directory = tempfile::tempdir().expect("temporary directory");
    let output_directory = directory.path().join("out");
    let output = flatcut(&[
        "flatten",
        path(&input),
        "-o",
        path(&output_directory),
        "--mesh-size",
        "0.01",
    ]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("the mesh size 0.01 and chord"),
        "{message}"
    );
    let longest_number = message
        .split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0);
    assert!(longest_number <= 8, "rounded figures: {message}");
}

#[test]
fn every_bad_input_is_reported_with_vertices_numbered_as_in_the_file() {
    let folder = tempfile::tempdir().expect("temporary directory");
    // Edge 1-2 (OBJ numbering) is shared by three triangles in both files.
    let fan = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 1 2 4\nf 2 1 5\n";
    let first = folder.path().join("first.obj");
    let second = folder.path().join("second.obj");
    std::fs::write(&first, fan).unwrap();
    std::fs::write(&second, fan).unwrap();
    let good = crate::util::sample("saddle.obj");
    let output = flatcut(&[
        "flatten",
        path(&first),
        path(&good),
        path(&second),
        "-o",
        path(&folder.path().join("out")),
    ]);
    let said = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{said}");
    assert!(said.contains("2 inputs cannot be used"), "{said}");
    for file in [&first, &second] {
        assert!(
            said.contains(path(file)),
            "{} named: {said}",
            file.display()
        );
    }
    assert!(
        said.contains(
            "edge 1-2 is shared by 3 triangles (non-manifold; at most 2 allowed) [lines 1 and 2]"
        ),
        "1-based, with the file's lines: {said}"
    );
    assert!(!folder.path().join("out").exists(), "nothing written");
}

#[test]
fn a_degenerate_triangle_is_named_with_its_line() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let text = "# a quad and a sliver\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n\
                f 1 2 3 4\n\nf 2 5 2\nf 2 3 5\n";
    let input = folder.path().join("sliver.obj");
    std::fs::write(&input, text.replace("f 2 5 2", "f 1 2 5")).unwrap();
    let said = refused_flatten(&input, folder.path());
    assert!(
        said.contains("triangle 3 has zero area") && said.contains("[line 9]"),
        "the fanned quad's two triangles come first; the sliver is on line 9: {said}"
    );
}

/// A file larger than flatcut reads is refused by its size, before a byte is read (a sparse
/// file: nothing is written to disk).
#[test]
fn a_file_too_large_is_refused_before_it_is_read() {
    let folder = tempfile::tempdir().expect("temporary directory");
    let input = folder.path().join("huge.obj");
    std::fs::File::create(&input)
        .and_then(|file| file.set_len(3 << 30))
        .expect("a sparse file");
    let said = refused_flatten(&input, folder.path());
    assert!(
        said.contains("the file is 3.0 GiB, above the 2 GiB flatcut reads"),
        "{said}"
    );
}

/// `flatcut flatten INPUT -o FOLDER/out`, which must be refused (exit 1): its standard error.
fn refused_flatten(input: &std::path::Path, folder: &std::path::Path) -> String {
    let output = flatcut(&["flatten", path(input), "-o", path(&folder.join("out"))]);
    let said = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{said}");
    said
}
