//! The output folder is safe: inputs are never overwritten, options and the folder are checked
//! before any work, a folder always holds one complete run, and a rejected part is marked.

use std::path::Path;

use crate::util::{flatcut, sample, stderr};

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

#[test]
fn an_input_in_the_output_folder_under_an_output_name_is_refused_and_kept() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let folder = directory.path().join("ow");
    std::fs::create_dir(&folder).expect("folder");
    let input = folder.join("cone_frustum.mesh.obj");
    std::fs::copy(sample("cone_frustum.obj"), &input).expect("copied");
    let before = std::fs::read(&input).expect("readable");
    let part = sample("cone_frustum.toml");
    let output = flatcut(&["run", path(&input), path(&part), "-o", path(&folder)]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(message.contains("cone_frustum.mesh.obj"), "{message}");
    assert!(message.contains("output folder"), "{message}");
    assert_eq!(std::fs::read(&input).expect("still there"), before);
    assert_eq!(std::fs::read_dir(&folder).expect("listable").count(), 1);
}

/// Options that can be checked before any work are refused with exit 1, naming the option, and
/// nothing is written (no output folder is created).
#[test]
fn absurd_options_and_an_unwritable_folder_are_refused_before_any_work() {
    let input = sample("cone_frustum.obj");
    let directory = tempfile::tempdir().expect("temporary directory");
    let output_directory = directory.path().join("out");
    let cases: [(&[&str], &str); 7] = [
        (&["--sheet", "0x0"], "--sheet 0x0: the sheet width is 0 mm"),
        (
            &["--sheet", "infxinf"],
            "--sheet infxinf: the sheet width is inf",
        ),
        (&["--sheet", "100x-1"], "the sheet height is -1 mm"),
        (&["--roll", "1e300"], "--roll 1e300"),
        (&["--sheet", "100x100", "--gap=-5"], "--gap -5"),
        (
            &["--tolerance", "1"],
            "--tolerance 1: give a fraction above 0 and at most 0.5",
        ),
        (&["--dxf-chord", "0"], "--dxf-chord 0.01"),
    ];
    for (options, expected) in cases {
        let mut arguments = vec!["run", path(&input), "-o", path(&output_directory)];
        arguments.extend(options);
        let output = flatcut(&arguments);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{options:?}: {message}");
        assert!(message.contains(expected), "{options:?}: {message}");
        assert!(!output_directory.exists(), "{options:?}: nothing written");
    }
    let file = directory.path().join("file");
    std::fs::write(&file, "").expect("written");
    let under_a_file = file.join("out");
    let output = flatcut(&["run", path(&input), "-o", path(&under_a_file)]);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{message}");
    assert!(
        message.contains("cannot create or write the output directory"),
        "{message}"
    );
    assert!(
        !message.contains("E_S"),
        "refused before flattening: {message}"
    );
}

/// Files in a folder after `flatcut flatten INPUTS... -o DIR`, sorted, relative.
fn files(directory: &Path) -> Vec<String> {
    let mut names = Vec::new();
    let mut folders = vec![directory.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(folder).expect("listable") {
            let entry = entry.expect("an entry");
            if entry.file_type().expect("a type").is_dir() {
                folders.push(entry.path());
            } else {
                let relative = entry
                    .path()
                    .strip_prefix(directory)
                    .expect("inside")
                    .to_owned();
                names.push(relative.to_string_lossy().into_owned());
            }
        }
    }
    names.sort();
    names
}

/// A second run into a folder removes the files of the first that it did not write, keeps the
/// user's files, and leaves no staging folder; the manifest lists what it wrote.
#[test]
fn a_second_run_replaces_the_first_as_one_set() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let folder = directory.path().join("out");
    let (frustum, ring) = (sample("cone_frustum.obj"), sample("cone_ring.obj"));
    let first = flatcut(&["flatten", path(&frustum), path(&ring), "-o", path(&folder)]);
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
    std::fs::write(folder.join("notes.txt"), "mine").expect("written");
    std::fs::write(folder.join(".flatcut-staging-1"), "").expect("a file, not a staging folder");
    std::fs::create_dir(folder.join(".flatcut-staging-2")).expect("left by a killed run");
    let second = flatcut(&["flatten", path(&ring), "-o", path(&folder)]);
    assert_eq!(second.status.code(), Some(0), "{}", stderr(&second));
    let expected = [
        ".flatcut-manifest.json",
        ".flatcut-staging-1",
        "cone_ring.dxf",
        "cone_ring.energy.png",
        "cone_ring.mesh.obj",
        "cone_ring.pattern.json",
        "cone_ring.pattern.obj",
        "notes.txt",
        "report.json",
    ];
    assert_eq!(files(&folder), expected);
    let manifest = std::fs::read_to_string(folder.join(".flatcut-manifest.json")).expect("read");
    let manifest: serde_json::Value = serde_json::from_str(&manifest).expect("JSON");
    assert_eq!(manifest["files"].as_array().expect("a list").len(), 6);
}

/// A pipe whose reading end is closed: writing to it fails with a broken pipe.
fn closed_pipe() -> std::io::PipeWriter {
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    writer
}

/// stdout or stderr closed (piped into `head`): the run finishes quietly with its exit code and
/// writes every file, never a panic (exit 101).
#[test]
fn a_closed_stdout_or_stderr_is_a_quiet_exit() {
    let input = sample("cone_frustum.obj");
    let directory = tempfile::tempdir().expect("temporary directory");
    let binary = env!("CARGO_BIN_EXE_flatcut");
    for (index, (close_stdout, close_stderr)) in [(true, false), (false, true), (true, true)]
        .into_iter()
        .enumerate()
    {
        let folder = directory.path().join(format!("out-{index}"));
        let mut command = std::process::Command::new(binary);
        command.args(["flatten", path(&input), "-o", path(&folder), "--json"]);
        if close_stdout {
            command.stdout(closed_pipe());
        }
        if close_stderr {
            command.stderr(closed_pipe());
        } else {
            command.stderr(std::process::Stdio::piped());
        }
        let output = command.output().expect("flatcut runs");
        let message = stderr(&output);
        assert!(!message.contains("panicked"), "{message}");
        assert_eq!(output.status.code(), Some(0), "{index}: {message}");
        assert!(
            folder.join("report.json").exists(),
            "{index}: the report is written"
        );
    }
}

/// A part over tolerance is marked: its cut file is `<part>.REJECTED.dxf` (no `<part>.dxf`), the
/// summary line and the report say why, and the run exits with 3.
#[test]
fn a_rejected_part_is_marked_and_says_why() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let folder = directory.path();
    let output = crate::util::flatten_into(
        &sample("saddle.obj"),
        folder,
        &["--tolerance", "0.0001", "--seams", "whole"],
    );
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(3), "{message}");
    assert!(folder.join("saddle.REJECTED.dxf").exists());
    assert!(!folder.join("saddle.dxf").exists());
    assert!(message.contains("REJECTED: E_"), "{message}");
    assert!(message.contains("over the tolerance 0.01 %"), "{message}");
    let report = crate::util::read_report(folder);
    let reasons = report["parts"][0]["rejected"].as_array().expect("reasons");
    assert!(!reasons.is_empty());
    // An accepted part has no `rejected` entry and a normal cut file.
    let accepted = directory.path().join("accepted");
    let output = crate::util::flatten_into(&sample("cone_frustum.obj"), &accepted, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(accepted.join("cone_frustum.dxf").exists());
    assert!(
        crate::util::read_report(&accepted)["parts"][0]
            .get("rejected")
            .is_none()
    );
}

/// A flat 100 mm plate of 10 mm squares with the middle square left out: a 10 mm hole.
fn plate_with_hole(path: &Path) {
    let vertices: Vec<[f64; 3]> = (0..11)
        .flat_map(|j| (0..11).map(move |i| [f64::from(i) * 10.0, f64::from(j) * 10.0, 0.0]))
        .collect();
    let faces: Vec<[usize; 3]> = (0..10)
        .flat_map(|j| (0..10).map(move |i| (i, j)))
        .filter(|&cell| cell != (5, 5))
        .flat_map(|(i, j)| {
            let a = j * 11 + i;
            [[a, a + 1, a + 12], [a, a + 12, a + 11]]
        })
        .collect();
    crate::util::write_obj(path, &vertices, &faces);
}

/// A part whose cut contour cannot be drawn (here a seam allowance that closes its hole) is
/// rejected with the reason and gets no cut file; the run's other parts are written as usual
/// and the run exits with 3, not stopped whole.
#[test]
fn a_part_that_cannot_be_drawn_is_rejected_and_the_others_written() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let plate = directory.path().join("plate.obj");
    plate_with_hole(&plate);
    let folder = directory.path().join("out");
    let cone = sample("cone_frustum.obj");
    let arguments = ["run", path(&plate), path(&cone), "-o", path(&folder)];
    let output = flatcut(&[&arguments[..], &["--seam-allowance", "10", "--no-timings"]].concat());
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(3), "{message}");
    assert!(message.contains("closes hole 1"), "{message}");
    assert!(
        !message.contains("not nested"),
        "nothing is nested: {message}"
    );
    assert!(!folder.join("plate.dxf").exists());
    assert!(!folder.join("plate.REJECTED.dxf").exists());
    assert!(folder.join("plate.pattern.json").exists());
    assert!(folder.join("cone_frustum.dxf").exists());
    let report = crate::util::read_report(&folder);
    let reasons = report["parts"][0]["rejected"].as_array().expect("reasons");
    assert!(
        (reasons.iter()).any(|reason| reason
            .as_str()
            .is_some_and(|text| text.starts_with("its cut contour cannot be drawn"))),
        "{reasons:?}"
    );
    assert!(report["parts"][1].get("rejected").is_none());
}

/// A part that runs past its `--time-limit` ends there: rejected with the reason, its files
/// written, exit 3.
#[test]
fn a_part_past_its_time_limit_is_rejected_with_the_reason() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let folder = directory.path();
    let output = crate::util::flatten_into(
        &sample("hemisphere.obj"),
        folder,
        &["--time-limit", "0.001"],
    );
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(3), "{message}");
    assert!(message.contains("the time limit was reached"), "{message}");
    assert!(folder.join("hemisphere.REJECTED.dxf").exists());
    let report = crate::util::read_report(folder);
    assert_eq!(report["options"]["part_time_limit_seconds"], 0.001);
    assert_eq!(report["parts"][0]["cut_stop"], "time_limit");
}

#[test]
fn a_rejected_part_is_marked_on_the_sheet_too() {
    let directory = tempfile::tempdir().expect("temporary directory");
    let folder = directory.path();
    let saddle = sample("saddle.obj");
    let cone = sample("cone_frustum.obj");
    let output = flatcut(&[
        "run",
        saddle.to_str().unwrap(),
        cone.to_str().unwrap(),
        "-o",
        folder.to_str().unwrap(),
        "--tolerance",
        "0.0001",
        "--seams",
        "whole",
        "--sheet",
        "1000x1000",
        "--work",
        "2000",
        "--no-timings",
    ]);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let sheet = std::fs::read_to_string(folder.join("sheets/sheet-001.dxf")).expect("sheet DXF");
    assert!(
        sheet.contains("saddle REJECTED x1"),
        "the rejected saddle's label says so"
    );
    assert!(
        !sheet.contains("cone_frustum REJECTED"),
        "only the rejected part is marked"
    );
}
