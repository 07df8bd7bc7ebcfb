//! The fan-in: parts flattened in separate runs (as `flatcut batch` runs them), their pattern
//! files nested together by `flatcut nest` without flattening again. One group gives the sheets
//! a single `flatcut run` of the same parts gives, byte for byte; parts of different materials
//! or thicknesses go to separate stock; bad pattern inputs are refused with a message.

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

use crate::util::{flatcut, read_report, sample, stderr};

/// Three quick parts of no material, in file-name order (the order `OUT/parts/*` gives).
const PARTS: [&str; 3] = ["cone_frustum.obj", "cone_ring.obj", "cylinder_panel.toml"];

/// The nesting options both the run and the fan-in get: a work budget, so the layout depends on
/// nothing but the inputs, the options and the seed.
const NESTING: [&str; 6] = ["--sheet", "500x450", "--work", "20000", "--seed", "3"];

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// The part's name: its file stem.
fn stem(part: &str) -> &str {
    part.split('.').next().expect("a stem")
}

/// `flatcut run PARTS... -o directory --no-timings extra...`, which must succeed.
fn run(parts: &[&str], directory: &Path, extra: &[&str]) {
    let inputs: Vec<PathBuf> = parts.iter().map(|part| sample(part)).collect();
    let mut arguments = vec!["run"];
    arguments.extend(inputs.iter().map(|input| path(input)));
    arguments.extend(["-o", path(directory), "--no-timings"]);
    arguments.extend_from_slice(extra);
    let output = flatcut(&arguments);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
}

/// `flatcut nest inputs... -o directory extra...`.
fn nest(inputs: &[&Path], directory: &Path, extra: &[&str]) -> Output {
    let mut arguments = vec!["nest"];
    arguments.extend(inputs.iter().map(|input| path(input)));
    arguments.extend(["-o", path(directory)]);
    arguments.extend_from_slice(extra);
    flatcut(&arguments)
}

/// `nest.json` of a fan-in.
fn read_nest(directory: &Path) -> Value {
    let text = std::fs::read_to_string(directory.join("nest.json")).expect("nest.json written");
    serde_json::from_str(&text).expect("nest.json is JSON")
}

/// Each part in a run of its own, no stock (as a batch runs them): `parts/<name>/`.
fn run_separately(parts: &[&str], root: &Path) -> Vec<PathBuf> {
    parts
        .iter()
        .map(|part| {
            let folder = root.join("parts").join(stem(part));
            run(&[part], &folder, &[]);
            folder
        })
        .collect()
}

#[test]
fn a_fan_in_nest_of_separate_runs_equals_one_run_with_stock() {
    let root = tempfile::tempdir().expect("temporary directory");
    let together = root.path().join("run");
    run(&PARTS, &together, &NESTING);
    let folders = run_separately(&PARTS, root.path());
    let fan_in = root.path().join("nest");
    let inputs: Vec<&Path> = folders.iter().map(PathBuf::as_path).collect();
    let output = nest(&inputs, &fan_in, &NESTING);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));

    for (part, folder) in PARTS.iter().zip(&folders) {
        let name = format!("{}.pattern.json", stem(part));
        let alone = std::fs::read(folder.join(&name)).expect("pattern file written");
        let nested = std::fs::read(together.join(&name)).expect("pattern file written");
        assert!(alone == nested, "{name}: a run with stock writes the same");
    }
    let report = read_report(&together);
    assert_eq!(report["options"]["nesting"]["work_limit"], 20000);
    let sheets = report["sheets"].as_array().expect("sheets");
    assert!(sheets.len() >= 2, "the parts fill more than one sheet");
    let nested = read_nest(&fan_in);
    let groups = nested["groups"].as_array().expect("groups");
    assert_eq!(groups.len(), 1, "one material and thickness: one group");
    assert_eq!(groups[0]["folder"], "sheets");
    assert_eq!(groups[0]["sheets"], report["sheets"], "the same placements");
    for sheet in sheets {
        let dxf = sheet["file"].as_str().expect("a file name");
        let png = dxf.replace(".dxf", ".png");
        for file in [dxf, png.as_str()] {
            let from_run = std::fs::read(together.join(file)).expect("run's sheet");
            let from_fan_in = std::fs::read(fan_in.join(file)).expect("fan-in's sheet");
            assert!(from_run == from_fan_in, "{file} differs");
        }
    }
}

/// Rewrites the pattern file `from` as `to` with `change` applied to its JSON.
fn edited(from: &Path, to: &Path, change: impl FnOnce(&mut Value)) {
    let text = std::fs::read_to_string(from).expect("pattern file");
    let mut value: Value = serde_json::from_str(&text).expect("JSON");
    change(&mut value);
    std::fs::create_dir_all(to.parent().expect("a parent")).expect("a folder");
    std::fs::write(to, serde_json::to_string_pretty(&value).expect("JSON")).expect("written");
}

#[test]
fn parts_of_different_materials_or_thicknesses_go_to_separate_stock() {
    let root = tempfile::tempdir().expect("temporary directory");
    let patterns = root.path().join("patterns");
    // Galvanised steel 0.8 mm, no material, wool.
    run(
        &[
            "cone_frustum.toml",
            "cylinder_panel.toml",
            "garment_panel.toml",
        ],
        &patterns,
        &[],
    );
    let thicker = root.path().join("more/cone_thick.pattern.json");
    edited(
        &patterns.join("cone_frustum.pattern.json"),
        &thicker,
        |value| {
            value["drawing"]["name"] = "cone_thick".into();
            value["thickness_mm"] = 1.5.into();
        },
    );
    let fan_in = root.path().join("nest");
    let output = nest(
        &[&patterns, &thicker],
        &fan_in,
        &["--roll", "900", "--work", "5000"],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let nested = read_nest(&fan_in);
    let groups: Vec<(String, Vec<String>)> = nested["groups"]
        .as_array()
        .expect("groups")
        .iter()
        .map(|group| {
            let names = group["parts"]
                .as_array()
                .expect("parts")
                .iter()
                .map(|part| part["name"].as_str().expect("a name").to_string())
                .collect();
            (
                group["folder"].as_str().expect("a folder").to_string(),
                names,
            )
        })
        .collect();
    let expected = [
        ("sheets/galvanised_steel-0.8mm", "cone_frustum"),
        ("sheets/no-material", "cylinder_panel"),
        ("sheets/wool", "garment_panel"),
        ("sheets/galvanised_steel-1.5mm", "cone_thick"),
    ]
    .map(|(folder, name)| (folder.to_string(), vec![name.to_string()]));
    assert_eq!(groups, expected);
    for (folder, _) in &groups {
        for file in ["sheet-001.dxf", "sheet-001.png"] {
            assert!(fan_in.join(folder).join(file).is_file(), "{folder}/{file}");
        }
    }
    assert!(!fan_in.join("sheets/sheet-001.dxf").exists());
}

/// `flatcut nest inputs... --sheet 500x500` into a fresh folder: exit 1 with `expected` (and
/// every one of `named`) in the message, no panic, nothing written.
fn refused(inputs: &[&Path], extra: &[&str], expected: &str, named: &[&Path]) {
    let root = tempfile::tempdir().expect("temporary directory");
    let out = root.path().join("out");
    let output = nest(inputs, &out, extra);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{expected}: {message}");
    assert!(message.contains(expected), "'{expected}' in: {message}");
    for input in named {
        assert!(message.contains(path(input)), "names {input:?}: {message}");
    }
    assert!(!message.contains("panicked"), "{message}");
    assert!(!out.exists(), "nothing written: {message}");
}

#[test]
fn bad_pattern_inputs_are_refused_with_a_clear_message() {
    let root = tempfile::tempdir().expect("temporary directory");
    let folder = root.path().join("cone");
    run(&["cone_frustum.obj"], &folder, &[]);
    let good = folder.join("cone_frustum.pattern.json");
    let sheet = ["--sheet", "500x500"];

    let corrupt = root.path().join("bad/corrupt.pattern.json");
    std::fs::create_dir_all(corrupt.parent().expect("a parent")).expect("a folder");
    let text = std::fs::read_to_string(&good).expect("pattern file");
    std::fs::write(&corrupt, &text[..text.len() / 2]).expect("written");
    refused(&[&corrupt], &sheet, "not a valid pattern file", &[&corrupt]);

    let newer = root.path().join("bad/newer.pattern.json");
    edited(&good, &newer, |value| value["version"] = 2.into());
    refused(&[&newer], &sheet, "format version 2", &[&newer]);

    let other = root.path().join("bad/other.pattern.json");
    edited(&good, &other, |value| value["format"] = "esicup".into());
    refused(&[&other], &sheet, "not a flatcut pattern file", &[&other]);

    refused(&[&good], &[], "give --sheet WxH or --roll W", &[]);

    let instance = sample("nesting/fu.json");
    refused(
        &[&good, &instance],
        &sheet,
        "one kind at a time",
        &[&good, &instance],
    );

    let twin = root.path().join("twin/cone_frustum.pattern.json");
    edited(&good, &twin, |_| {});
    refused(&[&good, &twin], &sheet, "has the name of", &[&good, &twin]);

    let empty = root.path().join("empty");
    std::fs::create_dir_all(&empty).expect("a folder");
    refused(&[&empty], &sheet, "no `*.pattern.json`", &[&empty]);

    let coarser = root.path().join("coarser/coarse.pattern.json");
    edited(&good, &coarser, |value| {
        value["drawing"]["name"] = "coarse".into();
        value["options"]["chord_tolerance"] = 0.1.into();
    });
    refused(
        &[&good, &coarser],
        &sheet,
        "other pattern options",
        &[&coarser],
    );

    let into_itself = nest(&[&folder], &folder, &sheet);
    let message = stderr(&into_itself);
    assert_eq!(into_itself.status.code(), Some(1), "{message}");
    assert!(message.contains("in the output folder"), "{message}");
    assert!(good.is_file(), "the run's pattern file is kept");
}

#[test]
fn rejected_parts_are_nested_only_when_asked() {
    let root = tempfile::tempdir().expect("temporary directory");
    let folder = root.path().join("cone");
    run(&["cone_frustum.obj"], &folder, &[]);
    let rejected = root.path().join("rejected/bad_cone.pattern.json");
    edited(
        &folder.join("cone_frustum.pattern.json"),
        &rejected,
        |value| {
            value["drawing"]["name"] = "bad_cone".into();
            value["rejected"] = true.into();
        },
    );
    let inputs: [&Path; 2] = [&folder, &rejected];
    refused(&inputs, &["--sheet", "500x500"], "'bad_cone'", &[&rejected]);
    let out = root.path().join("out");
    let output = nest(&inputs, &out, &["--sheet", "500x500", "--include-rejected"]);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let parts = &read_nest(&out)["groups"][0]["parts"];
    assert_eq!(parts[0]["rejected"], false);
    assert_eq!(parts[1]["rejected"], true);
}
