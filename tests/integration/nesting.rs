//! `flatcut run --sheet`: parts nested on sheets, sheet files written, byte-identical reruns, and
//! every DXF the run writes checked by ezdxf (a real external reader) when it is installed.

use std::path::Path;
use std::process::Command;

use crate::util::{flatcut, read_report, sample, stderr};

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
        "--time",
        "1",
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

/// Runs `tests/dxf_check.py` on every DXF below `directory`; under CI ezdxf must be installed.
fn check_every_dxf_with_ezdxf(directory: &Path) {
    let available = Command::new("python3")
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
    let mut files = vec![directory.join("sheets/sheet-001.dxf")];
    files.extend(["cone_frustum.dxf", "garment_panel.dxf"].map(|name| directory.join(name)));
    for file in files {
        let output = Command::new("python3")
            .arg(&script)
            .arg(&file)
            .arg("--no-fixes")
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
}
