//! `flatcut batch`: every part into its own folder with a summary, resumed after an
//! interruption, split into shards whose union is the unsharded batch byte for byte, parts
//! stopped at the time limit, and the GNU parallel recipe of `docs/cluster.md`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::util::{flatcut, sample, stderr};

/// Every file under `root`, by path relative to it, with its bytes.
fn tree(root: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut folders = vec![root.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).expect("folder readable") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                folders.push(path);
            } else {
                let bytes = std::fs::read(&path).expect("file readable");
                files.insert(
                    path.strip_prefix(root).expect("inside").to_path_buf(),
                    bytes,
                );
            }
        }
    }
    files
}

/// Asserts two output folders hold the same files with the same bytes.
fn assert_same_tree(expected: &Path, actual: &Path) {
    let (expected, actual) = (tree(expected), tree(actual));
    let names = |files: &BTreeMap<PathBuf, Vec<u8>>| files.keys().cloned().collect::<Vec<_>>();
    assert_eq!(names(&expected), names(&actual), "the same files");
    for (path, bytes) in &expected {
        assert!(actual[path] == *bytes, "{} differs", path.display());
    }
}

/// Runs `flatcut batch ARGUMENTS... -o OUTPUT`.
fn batch(arguments: &[&str], output: &Path) -> Output {
    let mut all = vec!["batch"];
    all.extend_from_slice(arguments);
    all.extend_from_slice(&["-o", output.to_str().expect("utf-8 path")]);
    flatcut(&all)
}

/// The summary of a batch.
fn summary(output: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(output.join("batch.json")).expect("batch.json written");
    serde_json::from_str(&text).expect("batch.json is JSON")
}

/// The statuses of the summary's parts, in order, as `name: status`.
fn statuses(summary: &serde_json::Value) -> Vec<String> {
    summary["parts"]
        .as_array()
        .expect("parts")
        .iter()
        .map(|part| {
            format!(
                "{}: {}",
                part["name"].as_str().unwrap(),
                part["status"].as_str().unwrap()
            )
        })
        .collect()
}

/// A manifest of four quick parts, with quantities and materials, in `folder`.
fn write_manifest(folder: &Path) -> PathBuf {
    let samples = sample("");
    let samples = samples.to_str().expect("utf-8 path");
    let manifest = folder.join("parts.csv");
    let text = format!(
        "input,name,quantity,material,thickness\n\
         {samples}/cone_frustum.toml,cone,3,steel,1.5\n\
         {samples}/cylinder_segment.obj,,2,steel,1.5\n\
         {samples}/cone_frustum.obj,cone-mesh,1,aluminium,2\n\
         {samples}/cylinder_panel.toml,panel,,,\n"
    );
    std::fs::write(&manifest, text).expect("manifest written");
    manifest
}

#[test]
fn a_batch_writes_every_part_into_its_folder_and_sums_them_up() {
    let folder = tempfile::tempdir().expect("temporary folder");
    let output = folder.path().join("out");
    let inputs = [
        sample("cone_frustum.toml"),
        sample("saddle.obj"),
        sample("bad/degenerate_grid.toml"),
    ];
    let inputs: Vec<&str> = inputs.iter().map(|path| path.to_str().unwrap()).collect();
    let result = batch(&inputs, &output);
    assert_eq!(
        result.status.code(),
        Some(1),
        "a refused part: exit 1\n{}",
        stderr(&result)
    );
    let summary = summary(&output);
    assert_eq!(
        statuses(&summary),
        ["cone_frustum: ok", "saddle: ok", "degenerate_grid: refused"]
    );
    assert_eq!(summary["counts"]["ok"], 2);
    let refused = &summary["parts"][2];
    assert!(
        refused["reason"].as_str().unwrap().contains("degenerate"),
        "{refused}"
    );
    for name in ["cone_frustum", "saddle"] {
        let part = output.join("parts").join(name);
        for file in [
            format!("{name}.dxf"),
            "report.json".to_string(),
            "batch-part.json".to_string(),
        ] {
            assert!(part.join(&file).is_file(), "{name}/{file} written");
        }
    }
    let refused_folder = output.join("parts/degenerate_grid");
    assert!(
        !refused_folder.join("report.json").exists(),
        "nothing written for a refused part"
    );
    let ok = batch(&inputs[..2], &output);
    assert_eq!(ok.status.code(), Some(0), "{}", stderr(&ok));
}

#[test]
fn a_rerun_redoes_only_what_is_missing_and_ends_byte_identical() {
    let folder = tempfile::tempdir().expect("temporary folder");
    let manifest = write_manifest(folder.path());
    let manifest = manifest.to_str().unwrap();
    let whole = folder.path().join("whole");
    let first = batch(&["--manifest", manifest, "--jobs", "2"], &whole);
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));

    let resumed = folder.path().join("resumed");
    assert!(batch(&["--manifest", manifest], &resumed).status.success());
    // As a killed batch leaves it: one part's outputs half replaced, another never run.
    std::fs::remove_file(resumed.join("parts/cone/cone.dxf")).expect("a file removed");
    std::fs::remove_dir_all(resumed.join("parts/panel")).expect("a part folder removed");
    let rerun = batch(&["--manifest", manifest], &resumed);
    let said = stderr(&rerun);
    assert!(rerun.status.success(), "{said}");
    assert!(
        said.contains("cylinder_segment: ok (done before, skipped)"),
        "{said}"
    );
    assert!(
        said.contains("cone-mesh: ok (done before, skipped)"),
        "{said}"
    );
    assert!(!said.contains("cone: ok (done before"), "{said}");
    assert!(!said.contains("panel: ok (done before"), "{said}");
    assert_same_tree(&whole, &resumed);

    // The manifest's quantity and material reach the part's report and its label.
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(whole.join("parts/cone/report.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(report["parts"][0]["quantity"], 3);
    let dxf = std::fs::read_to_string(whole.join("parts/cone/cone.dxf")).unwrap();
    assert!(dxf.contains("x3 steel"), "label with quantity and material");
}

#[test]
fn shards_together_are_the_unsharded_batch_byte_for_byte() {
    let folder = tempfile::tempdir().expect("temporary folder");
    let manifest = write_manifest(folder.path());
    let manifest = manifest.to_str().unwrap();
    let whole = folder.path().join("whole");
    assert!(batch(&["--manifest", manifest], &whole).status.success());
    let sharded = folder.path().join("sharded");
    for shard in ["2/3", "1/3"] {
        let result = batch(&["--manifest", manifest, "--shard", shard], &sharded);
        assert!(result.status.success(), "{}", stderr(&result));
    }
    let partial = statuses(&summary(&sharded));
    assert_eq!(partial[2], "cone-mesh: pending", "shard 3/3 still to run");
    let last = batch(&["--manifest", manifest, "--shard", "3/3"], &sharded);
    assert!(last.status.success(), "{}", stderr(&last));
    assert_same_tree(&whole, &sharded);
}

#[test]
fn a_part_past_the_time_limit_is_timed_out_and_run_again_by_the_next_batch() {
    let folder = tempfile::tempdir().expect("temporary folder");
    let output = folder.path().join("out");
    let input = sample("saddle.obj");
    let input = input.to_str().unwrap();
    let late = batch(&[input, "--kill-after", "0.001"], &output);
    assert_eq!(late.status.code(), Some(1), "{}", stderr(&late));
    assert_eq!(statuses(&summary(&output)), ["saddle: timed_out"]);
    let part = output.join("parts/saddle");
    let left: Vec<String> = std::fs::read_dir(&part)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name != "batch-part.json" && name != ".flatcut-batch.lock")
        .collect();
    assert!(
        left.is_empty(),
        "a stopped part leaves nothing behind: {left:?}"
    );
    let again = batch(&[input], &output);
    assert!(again.status.success(), "{}", stderr(&again));
    assert_eq!(statuses(&summary(&output)), ["saddle: ok"]);
}

#[test]
fn bad_batches_are_refused_with_the_reason() {
    let folder = tempfile::tempdir().expect("temporary folder");
    let output = folder.path().join("out");
    let manifest = folder.path().join("parts.csv");
    std::fs::write(&manifest, "input,colour\nx.obj,red\n").unwrap();
    let cases: [(Vec<String>, &str); 4] = [
        (
            vec!["--manifest".into(), manifest.to_string_lossy().into()],
            "line 1: unknown field `colour`",
        ),
        (
            vec![
                sample("saddle.obj").to_string_lossy().into(),
                "--jobs".into(),
                "0".into(),
            ],
            "--jobs 0",
        ),
        (
            vec![
                sample("saddle.obj").to_string_lossy().into(),
                sample("saddle.obj").to_string_lossy().into(),
            ],
            "two parts named \"saddle\"",
        ),
        (
            vec![
                sample("saddle.obj").to_string_lossy().into(),
                "--quantity".into(),
                "0".into(),
            ],
            "--quantity 0",
        ),
    ];
    for (arguments, expected) in cases {
        let arguments: Vec<&str> = arguments.iter().map(String::as_str).collect();
        let result = batch(&arguments, &output);
        let said = stderr(&result);
        assert_eq!(result.status.code(), Some(1), "{arguments:?}: {said}");
        assert!(said.contains(expected), "{arguments:?}: {said}");
        assert!(!said.contains("panicked"), "{said}");
    }
    let shard = batch(
        &[sample("saddle.obj").to_str().unwrap(), "--shard", "4/3"],
        &output,
    );
    assert_eq!(shard.status.code(), Some(2), "a bad shard is a usage error");
}

/// Whether GNU parallel is installed (`.ci/run` installs it; CI fails without it).
fn gnu_parallel_present() -> bool {
    let present = Command::new("parallel")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        present || std::env::var_os("CI").is_none(),
        "GNU parallel is missing: .ci/run installs it"
    );
    present
}

#[test]
fn the_gnu_parallel_recipe_gives_the_unsharded_batch() {
    if !gnu_parallel_present() {
        eprintln!("GNU parallel not installed: the recipe is not run here");
        return;
    }
    let folder = tempfile::tempdir().expect("temporary folder");
    let manifest = write_manifest(folder.path());
    let whole = folder.path().join("whole");
    assert!(
        batch(&["--manifest", manifest.to_str().unwrap()], &whole)
            .status
            .success()
    );
    let sharded = folder.path().join("sharded");
    // docs/cluster.md: one worker per shard, all writing into one output folder.
    let result = Command::new("parallel")
        .args(["--will-cite", "--halt", "now,fail=1", "-j", "3"])
        .arg(env!("CARGO_BIN_EXE_flatcut"))
        .args(["batch", "--manifest"])
        .arg(&manifest)
        .arg("-o")
        .arg(&sharded)
        .args(["--jobs", "1", "--shard", "{}/3", ":::", "1", "2", "3"])
        .output()
        .expect("parallel runs");
    assert!(result.status.success(), "{}", stderr(&result));
    assert_same_tree(&whole, &sharded);
}

#[test]
fn the_fan_in_nest_of_a_batch_is_the_run_of_its_parts() {
    let folder = tempfile::tempdir().expect("temporary folder");
    let parts = [sample("cone_frustum.obj"), sample("cylinder_segment.obj")];
    let parts: Vec<&str> = parts.iter().map(|path| path.to_str().unwrap()).collect();
    let refused = sample("bad/degenerate_grid.toml");
    let output = folder.path().join("batch");
    let mut inputs = parts.clone();
    inputs.push(refused.to_str().unwrap());
    assert_eq!(
        batch(&inputs, &output).status.code(),
        Some(1),
        "a refused part"
    );

    let nesting = ["--sheet", "600x400", "--work", "20000", "--seed", "3"];
    let folders: Vec<String> = ["cone_frustum", "cylinder_segment", "degenerate_grid"]
        .iter()
        .map(|name| {
            output
                .join("parts")
                .join(name)
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    let nested = folder.path().join("nested");
    let mut arguments: Vec<&str> = vec!["nest"];
    arguments.extend(folders.iter().map(String::as_str));
    arguments.extend_from_slice(&nesting);
    arguments.extend_from_slice(&["-o", nested.to_str().unwrap()]);
    let fan_in = flatcut(&arguments);
    let said = stderr(&fan_in);
    assert!(fan_in.status.success(), "{said}");
    assert!(
        said.contains("degenerate_grid: no `*.pattern.json`"),
        "the refused part is skipped: {said}"
    );

    let run = folder.path().join("run");
    let mut arguments: Vec<&str> = vec!["run"];
    arguments.extend_from_slice(&parts);
    arguments.extend_from_slice(&nesting);
    arguments.extend_from_slice(&["-o", run.to_str().unwrap(), "--no-timings"]);
    let whole = flatcut(&arguments);
    assert!(whole.status.success(), "{}", stderr(&whole));
    assert_same_tree(&run.join("sheets"), &nested.join("sheets"));
}
