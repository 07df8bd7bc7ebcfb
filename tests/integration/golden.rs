//! Golden reports of the bundled samples: the figures scripts read, compared within a stated
//! tolerance. Regenerate with `FLATCUT_BLESS=1 cargo test golden` after an intended change, and
//! say why in the commit.

use std::path::Path;

use serde_json::Value;

use crate::util::stderr;

/// Relative tolerance on numbers (absolute below 1e-12): solver changes that move a figure by
/// more than this must be deliberate.
const GOLDEN_RELATIVE_TOLERANCE: f64 = 1e-6;

fn compare(expected: &Value, actual: &Value, at: &str) {
    match (expected, actual) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().expect("number"), y.as_f64().expect("number"));
            let scale = x.abs().max(y.abs()).max(1e-12 / GOLDEN_RELATIVE_TOLERANCE);
            assert!(
                (x - y).abs() <= GOLDEN_RELATIVE_TOLERANCE * scale,
                "{at}: expected {x}, got {y}"
            );
        }
        (Value::Object(x), Value::Object(y)) => {
            let keys = |m: &serde_json::Map<String, Value>| m.keys().cloned().collect::<Vec<_>>();
            assert_eq!(keys(x), keys(y), "{at}: keys differ");
            for (key, value) in x {
                compare(value, &y[key], &format!("{at}.{key}"));
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}: lengths differ");
            for (i, (a, b)) in x.iter().zip(y).enumerate() {
                compare(a, b, &format!("{at}[{i}]"));
            }
        }
        _ => assert_eq!(expected, actual, "{at}"),
    }
}

fn check_golden(sample: &str) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let directory = tempfile::tempdir().expect("temporary directory");
    let input = format!("samples/{sample}");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_flatcut"))
        .current_dir(root)
        .args([
            "flatten",
            &input,
            "-o",
            directory.path().to_str().expect("utf-8"),
            "--no-timings",
        ])
        .output()
        .expect("flatcut runs");
    assert!(
        matches!(output.status.code(), Some(0 | 3)),
        "{sample}: {}",
        stderr(&output)
    );
    let actual: Value = serde_json::from_str(
        &std::fs::read_to_string(directory.path().join("report.json")).expect("report"),
    )
    .expect("json");
    let golden = root
        .join("samples/golden")
        .join(format!("{sample}.report.json"));
    if std::env::var_os("FLATCUT_BLESS").is_some() {
        std::fs::create_dir_all(golden.parent().expect("parent")).expect("golden directory");
        std::fs::copy(directory.path().join("report.json"), &golden).expect("bless");
        return;
    }
    let expected: Value = serde_json::from_str(
        &std::fs::read_to_string(&golden)
            .unwrap_or_else(|e| panic!("{}: {e} (bless with FLATCUT_BLESS=1)", golden.display())),
    )
    .expect("golden json");
    compare(&expected["parts"], &actual["parts"], sample);
    compare(&expected["options"], &actual["options"], sample);
}

/// One golden test per bundled sample part.
macro_rules! golden {
    ($($test:ident: $file:literal,)*) => {
        $(
            #[test]
            fn $test() {
                check_golden($file);
            }
        )*
    };
}

golden! {
    golden_cone_frustum_mesh: "cone_frustum.obj",
    golden_cylinder_segment_mesh: "cylinder_segment.obj",
    golden_hemisphere_mesh: "hemisphere.obj",
    golden_saddle_mesh: "saddle.obj",
    golden_cone_ring_mesh: "cone_ring.obj",
    golden_cone_frustum_part: "cone_frustum.toml",
    golden_cylinder_panel_part: "cylinder_panel.toml",
    golden_square_to_round_part: "square_to_round.toml",
    golden_round_to_round_eccentric_part: "round_to_round_eccentric.toml",
    golden_rectangle_offset_transition_part: "rectangle_offset_transition.toml",
    golden_elbow_two_piece_part: "elbow_two_piece.toml",
    golden_dome_part: "dome.toml",
    golden_fender_part: "fender.toml",
    golden_hypar_part: "hypar.toml",
    golden_garment_panel_part: "garment_panel.toml",
    golden_bracket_fold_part: "bracket_fold.toml",
    golden_cone_hopper_folds_part: "cone_hopper_folds.toml",
    golden_cone_frustum_half_step: "cone_frustum_half.step",
    golden_bspline_patch_step: "bspline_patch.step",
    golden_loose_hypar_metres_step: "loose_hypar_metres.step",
    golden_cone_frustum_freecad_step: "cone_frustum_freecad.step",
    golden_bspline_loft_freecad_step: "bspline_loft_freecad.step",
}
