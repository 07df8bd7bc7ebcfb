//! Reading a part file: its text parsed, every surface and feature built and checked, into the
//! CAD model's [`PartModel`].

use std::ops::Range;
use std::path::Path;

use glam::DVec3;

use super::build::build_surface;
use super::errors::{PartError, SpecDefect};
use super::features::{build_fold_bend, build_fold_line, build_region};
use super::locate::{field_line, find_key, line_of, syntax_error, table_end};
use super::spec::{Join, PartSpec};
use crate::cad::{CadPart, PartAttributes, PartModel};

/// Parses and builds a part file's text; `path` names it in errors.
pub fn parse_part(path: &Path, text: &str) -> Result<PartModel, PartError> {
    let spec: PartSpec = toml::from_str(text).map_err(|error| syntax_error(path, text, &error))?;
    let located = |span: Range<usize>, defect: SpecDefect, prefix: String| PartError {
        path: path.to_path_buf(),
        line: Some(field_line(text, span, &defect.field)),
        field: if defect.field.is_empty() {
            prefix
        } else {
            format!("{prefix}.{}", defect.field)
        },
        message: defect.message,
    };
    if spec.surfaces.is_empty() {
        return Err(PartError {
            path: path.to_path_buf(),
            line: None,
            field: "surface".into(),
            message: "the part has no surface; add a [[surface]] table".into(),
        });
    }
    let mut surfaces = Vec::with_capacity(spec.surfaces.len());
    for (index, surface) in spec.surfaces.iter().enumerate() {
        let built = build_surface(surface.get_ref())
            .map_err(|d| located(surface.span(), d, format!("surface[{index}]")))?;
        surfaces.push(built);
    }
    let mut fold_lines = Vec::new();
    let mut fold_stiffness = Vec::new();
    let mut fold_bends = Vec::new();
    let thickness = spec.thickness.as_ref().map(|t| *t.get_ref());
    for (index, fold) in spec.fold_lines.iter().enumerate() {
        let at = |d| located(fold.span(), d, format!("fold_line[{index}]"));
        let (geometry, stiffness) = build_fold_line(fold.get_ref(), &surfaces).map_err(at)?;
        fold_bends.push(build_fold_bend(fold.get_ref(), &surfaces, thickness).map_err(at)?);
        fold_lines.push(geometry);
        fold_stiffness.push(stiffness);
    }
    let regions = spec
        .stiffness_regions
        .iter()
        .enumerate()
        .map(|(index, region)| {
            build_region(region.get_ref(), &surfaces)
                .map_err(|d| located(region.span(), d, format!("stiffness_region[{index}]")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    check_header(path, text, &spec)?;
    Ok(PartModel {
        name: spec.name.clone().unwrap_or_else(|| file_stem(path)),
        units: spec.units,
        quantity: spec.quantity,
        attributes: PartAttributes {
            material: spec.material.clone(),
            thickness: spec.thickness.as_ref().map(|t| *t.get_ref()),
            grain: spec.grain.map(DVec3::from_array),
        },
        cad: CadPart {
            surfaces,
            fold_lines,
            weld: spec.join == Join::Weld,
        },
        fold_stiffness,
        fold_bends,
        regions,
    })
}

fn check_header(path: &Path, text: &str, spec: &PartSpec) -> Result<(), PartError> {
    let error = |field: &str, message: String, span: Option<Range<usize>>| PartError {
        path: path.to_path_buf(),
        line: span.map(|s| line_of(text, s.start)),
        field: field.into(),
        message,
    };
    // Top-level keys precede the first table.
    let header = &text[..table_end(text, 0)];
    let key_span = |key: &str| find_key(header, key).map(|at| at..at + key.len());
    if spec.quantity == 0 {
        return Err(error(
            "quantity",
            "must be at least 1".into(),
            key_span("quantity"),
        ));
    }
    if let Some(name) = &spec.name
        && let Some(defect) = name_defect(name)
    {
        return Err(error("name", defect, key_span("name")));
    }
    if let Some(thickness) = &spec.thickness {
        let value = *thickness.get_ref();
        if !(value.is_finite() && value > 0.0) {
            return Err(error(
                "thickness",
                format!("must be a positive length, got {value}"),
                Some(thickness.span()),
            ));
        }
    }
    if let Some(grain) = spec.grain
        && DVec3::from_array(grain).try_normalize().is_none()
    {
        return Err(error(
            "grain",
            format!("must be a non-zero finite direction, got {grain:?}"),
            key_span("grain"),
        ));
    }
    Ok(())
}

/// The longest part name: output files add up to 16 bytes (`.energy.png`, `-NNN`) to it, and file
/// names are limited to 255 bytes.
const MAXIMUM_NAME_BYTES: usize = 200;

/// Why a part name cannot name output files, if it cannot.
fn name_defect(name: &str) -> Option<String> {
    if name.trim().is_empty() || name == "." || name == ".." {
        Some("must name the part's output files: give a non-empty name".into())
    } else if name.contains(['/', '\\']) || name.chars().any(char::is_control) {
        Some(format!(
            "must not hold a path separator or a control character (it names the output files), got {name:?}"
        ))
    } else if name.len() > MAXIMUM_NAME_BYTES {
        Some(format!(
            "is {} bytes long; output file names allow at most {MAXIMUM_NAME_BYTES}",
            name.len()
        ))
    } else {
        None
    }
}

/// Reads and builds a part file.
pub fn read_part_text(path: &Path, bytes: &[u8]) -> Result<PartModel, PartError> {
    let text = std::str::from_utf8(bytes).map_err(|e| PartError {
        path: path.to_path_buf(),
        line: None,
        field: String::new(),
        message: format!("not UTF-8 text: {e}"),
    })?;
    parse_part(path, text)
}

fn file_stem(path: &Path) -> String {
    path.file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("part")
        .to_string()
}

/// True when the text looks like a part file (for files without the `.toml` extension).
pub fn looks_like_part(bytes: &[u8]) -> bool {
    std::str::from_utf8(bytes).is_ok_and(|text| text.lines().any(|l| l.trim() == "[[surface]]"))
}

#[cfg(test)]
mod tests {
    use crate::ingest::part::reader::*;

    fn error_of(text: &str) -> PartError {
        match parse_part(Path::new("bad.toml"), text) {
            Ok(_) => panic!("accepted a bad part file"),
            Err(error) => error,
        }
    }

    const CONE: &str = "name = \"c\"\n\n[[surface]]\nkind = \"cone\"\nbottom_radius = 100.0\ntop_radius = 50.0\nheight = 80.0\n";

    #[test]
    fn a_good_cone_builds() {
        let part = parse_part(Path::new("cone.toml"), CONE).expect("valid");
        assert_eq!(part.cad.surfaces.len(), 1);
        assert_eq!(part.name, "c");
    }

    #[test]
    fn a_zero_radius_names_the_line_and_field() {
        let error = error_of(&CONE.replace("top_radius = 50.0", "top_radius = 0.0"));
        assert_eq!(error.line, Some(6));
        assert_eq!(error.field, "surface[0].top_radius");
    }

    #[test]
    fn a_misspelt_field_names_its_line() {
        let error = error_of(&CONE.replace("height", "hieght"));
        assert_eq!(error.line, Some(7), "{error}");
        assert!(error.to_string().contains("hieght"), "{error}");
    }

    #[test]
    fn a_unit_typo_names_the_field() {
        let error = error_of(&format!("units = \"milimetres\"\n{CONE}"));
        assert_eq!(error.line, Some(1));
        assert_eq!(error.field, "units");
    }

    #[test]
    fn an_unknown_surface_kind_is_an_error() {
        let error = error_of(&CONE.replace("\"cone\"", "\"torus\""));
        assert!(error.to_string().contains("torus"), "{error}");
        assert!(error.line.is_some());
    }

    #[test]
    fn a_non_rectangular_grid_is_an_error() {
        let text = "[[surface]]\nkind = \"bspline\"\ndegree = [1, 1]\ncontrol_points = [[[0,0,0],[1,0,0]],[[0,1,0]]]\n";
        let error = error_of(text);
        assert_eq!(error.field, "surface[0].control_points");
        assert_eq!(error.line, Some(4));
    }

    #[test]
    fn a_degenerate_grid_is_an_error() {
        let text = "[[surface]]\nkind = \"bspline\"\ndegree = [1, 1]\ncontrol_points = [[[0,0,0],[1,0,0]],[[0,0,0],[1,0,0]]]\n";
        assert!(error_of(text).message.contains("degenerate"));
    }

    #[test]
    fn a_wrong_type_inside_a_surface_names_the_field() {
        let error = error_of(&CONE.replace("height = 80.0", "height = \"80 mm\""));
        assert_eq!(error.line, Some(7), "{error}");
        assert_eq!(error.field, "surface[0].height", "{error}");
        let grid = "[[surface]]\nkind = \"bspline\"\ndegree = [1, -1]\ncontrol_points = [\n  [[0,0,0],[1,0,0]],\n  [[0,1,0],[1,1,0]],\n]\n";
        let error = error_of(grid);
        assert_eq!(
            (error.line, error.field.as_str()),
            (Some(3), "surface[0].degree")
        );
        let error = error_of(
            &grid
                .replace("[1, -1]", "[1, 1]")
                .replace("1,1,0]", "1,1,\"x\"]"),
        );
        assert_eq!(
            (error.line, error.field.as_str()),
            (Some(6), "surface[0].control_points")
        );
    }

    #[test]
    fn header_defects_name_their_line() {
        let error = error_of(&format!("quantity = 0\n{CONE}"));
        assert_eq!((error.line, error.field.as_str()), (Some(1), "quantity"));
        let error = error_of(&format!("grain = [inf, 0, 0]\n{CONE}"));
        assert_eq!((error.line, error.field.as_str()), (Some(1), "grain"));
        for name in ["", "..", "left/bracket", "a\\u0000b"] {
            let error = error_of(&CONE.replace("name = \"c\"", &format!("name = \"{name}\"")));
            assert_eq!(
                (error.line, error.field.as_str()),
                (Some(1), "name"),
                "{name}"
            );
        }
    }

    #[test]
    fn impossible_profiles_are_errors() {
        let revolution = |profile: &str| {
            format!(
                "[[surface]]\nkind = \"revolution\"\nstart = [50.0, 0.0]\nprofile = {profile}\n"
            )
        };
        for (profile, field, expected) in [
            (
                "[{ to = [50.0, 100.0], center = [50.0, 50.0] }]",
                "surface[0].profile[0].clockwise",
                "half circle",
            ),
            (
                "[{ to = [80.0, 100.0] }, { to = [80.0, 0.0] }, { to = [50.0, 100.0] }]",
                "surface[0].profile",
                "segments 0 and 2",
            ),
            (
                "[{ to = [50.0, 100.0] }, { to = [50.0, 20.0] }]",
                "surface[0].profile",
                "crosses itself",
            ),
            (
                "[{ to = [-10.0, 100.0] }]",
                "surface[0].profile[0]",
                "crosses the axis",
            ),
            (
                "[{ to = [0.0, 50.0] }, { to = [50.0, 100.0] }]",
                "surface[0].profile[0]",
                "meets the axis",
            ),
            (
                "[{ to = [50.0, 100.0], center = [0.0, 50.0], clockwise = true }]",
                "surface[0].profile[0]",
                "crosses the axis",
            ),
        ] {
            let error = error_of(&revolution(profile));
            assert_eq!(error.field, field, "{profile}: {error}");
            assert!(error.message.contains(expected), "{profile}: {error}");
        }
        let pole_to_pole = "[{ to = [0.0, -50.0], center = [0.0, 0.0], clockwise = true }]";
        let sphere = revolution(pole_to_pole).replace("[50.0, 0.0]", "[0.0, 50.0]");
        parse_part(Path::new("sphere.toml"), &sphere).expect("a sphere from pole to pole");
    }

    #[test]
    fn folds_along_an_edge_or_seam_and_touching_holes_are_errors() {
        let cylinder = "[[surface]]\nkind = \"cylinder\"\nradius = 50.0\nheight = 100.0\n";
        for points in [
            "[[0.0, 0.0], [0.0, 100.0]]",
            "[[360.0, 10.0], [360.0, 90.0]]",
            "[[0.0, 0.0], [360.0, 0.0]]",
            "[[90.0, 10.0], [90.0, 90.0], [90.0, 50.0]]",
        ] {
            let text = format!("{cylinder}[[fold_line]]\nsurface = 0\npoints = {points}\n");
            assert_eq!(error_of(&text).field, "fold_line[0].points", "{points}");
        }
        let ok = format!(
            "{cylinder}[[fold_line]]\nsurface = 0\npoints = [[0.0, 50.0], [360.0, 50.0]]\n"
        );
        parse_part(Path::new("ring.toml"), &ok).expect("a fold around the cylinder");
        let plate = "[[surface]]\nkind = \"polygon\"\npoints = [[0, 0, 0], [100, 0, 0], [100, 100, 0], [0, 100, 0]]\n";
        for holes in [
            "[[[0, 0, 0], [30, 20, 0], [20, 30, 0]]]",
            "[[[10, 10, 0], [50, 10, 0], [50, 50, 0]], [[50, 10, 0], [90, 10, 0], [90, 50, 0]]]",
        ] {
            let error = error_of(&format!("{plate}holes = {holes}\n"));
            assert!(error.message.contains("touch"), "{holes}: {error}");
        }
    }

    use proptest::strategy::Strategy as _;

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
        /// Any value in any numeric field of a cone with a fold line: no panic, and a refusal
        /// names the line and the field.
        #[test]
        fn numeric_fields_never_panic_and_errors_name_the_field(
            field in 0usize..8,
            value in proptest::prop_oneof![
                proptest::num::f64::ANY.prop_map(|v| format!("{v:?}").replace("NaN", "nan")),
                proptest::strategy::Just("-0.0".to_string()),
                proptest::strategy::Just("\"x\"".to_string()),
            ],
        ) {
            let mut numbers = ["100.0", "50.0", "80.0", "10.0", "0.0", "360.0", "90.0", "5.0"]
                .map(str::to_string);
            numbers[field] = value;
            let [bottom, top, height, offset, start, end, angle, factor] = numbers;
            let text = format!(
                "[[surface]]\nkind = \"cone\"\nbottom_radius = {bottom}\ntop_radius = {top}\nheight = {height}\ntop_offset = [{offset}, 0.0]\nangles = [{start}, {end}]\n\n[[fold_line]]\nsurface = 0\npoints = [[{angle}, 0.0], [{angle}, 80.0]]\nfactor = {factor}\n"
            );
            if let Err(error) = parse_part(Path::new("fuzz.toml"), &text) {
                proptest::prop_assert!(error.line.is_some(), "{}", error);
                proptest::prop_assert!(!error.field.is_empty(), "{}", error);
            }
        }
    }

    #[test]
    fn a_self_intersecting_trim_is_an_error() {
        let text = "[[surface]]\nkind = \"bspline\"\ndegree = [1, 1]\ncontrol_points = [[[0,0,0],[0,1,0]],[[1,0,0],[1,1,0]]]\ntrim = { holes = [[[0.2,0.2],[0.8,0.8],[0.8,0.2],[0.2,0.8]]] }\n";
        let error = error_of(text);
        assert_eq!(error.field, "surface[0].trim.holes[0]");
        assert_eq!(error.line, Some(5));
        assert!(error.to_string().contains("intersects itself"), "{error}");
    }
}
