//! Part files: a part described as CAD surfaces in TOML (`docs/part-format.md`), read into the
//! tessellator's [`CadPart`] with the part's name, units, quantity, attributes, fold-line
//! stiffness and stiffness regions. Every defect names the file, the line and the field.

pub mod build;
mod errors;
pub mod features;
pub mod loops;
pub mod spec;

use std::ops::Range;
use std::path::Path;

use glam::DVec3;

pub use errors::{PartError, SpecDefect};
pub use features::{FoldStiffness, RegionShape, StiffnessRegion};
use spec::{Join, PartSpec};

use crate::tessellate::CadPart;
use crate::units::Units;

/// Attributes of a part carried to the outputs (DXF labels, nesting).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PartAttributes {
    /// Material name.
    pub material: Option<String>,
    /// Sheet thickness (part units).
    pub thickness: Option<f64>,
    /// Grain direction on the part.
    pub grain: Option<DVec3>,
}

/// A part file, read and built.
#[derive(Debug, Clone)]
pub struct PartInput {
    /// Part name.
    pub name: String,
    /// Units of every length.
    pub units: Units,
    /// Copies to cut.
    pub quantity: u32,
    /// Material, thickness, grain.
    pub attributes: PartAttributes,
    /// The geometry.
    pub cad: CadPart,
    /// Stiffness of each fold line, in the order of `cad.fold_lines`.
    pub fold_stiffness: Vec<FoldStiffness>,
    /// Regions of raised stiffness.
    pub regions: Vec<StiffnessRegion>,
}

/// Parses and builds a part file's text; `path` names it in errors.
pub fn parse_part(path: &Path, text: &str) -> Result<PartInput, PartError> {
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
        let built = build::build_surface(surface.get_ref())
            .map_err(|d| located(surface.span(), d, format!("surface[{index}]")))?;
        surfaces.push(built);
    }
    let mut fold_lines = Vec::new();
    let mut fold_stiffness = Vec::new();
    for (index, fold) in spec.fold_lines.iter().enumerate() {
        let (geometry, stiffness) = features::build_fold_line(fold.get_ref(), &surfaces)
            .map_err(|d| located(fold.span(), d, format!("fold_line[{index}]")))?;
        fold_lines.push(geometry);
        fold_stiffness.push(stiffness);
    }
    let regions = spec
        .stiffness_regions
        .iter()
        .enumerate()
        .map(|(index, region)| {
            features::build_region(region.get_ref(), &surfaces)
                .map_err(|d| located(region.span(), d, format!("stiffness_region[{index}]")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    check_header(path, text, &spec)?;
    Ok(PartInput {
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
    if spec.quantity == 0 {
        return Err(error("quantity", "must be at least 1".into(), None));
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
        && (DVec3::from_array(grain).length().is_nan() || DVec3::from_array(grain).length() <= 0.0)
    {
        return Err(error("grain", "must be a non-zero direction".into(), None));
    }
    Ok(())
}

/// Reads and builds a part file.
pub fn read_part_text(path: &Path, bytes: &[u8]) -> Result<PartInput, PartError> {
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

/// 1-based line of byte `offset`.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// The key assigned on the line holding byte `offset`, if the line is `key = value`.
fn key_on_line(text: &str, offset: usize) -> Option<String> {
    let start = text[..offset.min(text.len())]
        .rfind('\n')
        .map_or(0, |i| i + 1);
    let line = text[start..].lines().next()?;
    let (key, _) = line.split_once('=')?;
    let key = key.trim();
    (!key.is_empty() && !key.starts_with('[')).then(|| key.to_string())
}

fn syntax_error(path: &Path, text: &str, error: &toml::de::Error) -> PartError {
    let message = error.message().trim().to_string();
    let start = error.span().map_or(0, |s| s.start.min(text.len()));
    // Errors inside a surface table (buffered to read its `kind`) carry the table's span, not
    // the field's: the first name the message quotes locates the field within the table.
    let quoted = message.split('`').nth(1).unwrap_or_default();
    let (line, field) = if let Some(found) = (!quoted.is_empty())
        .then(|| find_key(&text[start..], quoted))
        .flatten()
    {
        (line_of(text, start + found), quoted.to_string())
    } else if let Some(found) = (!quoted.is_empty())
        .then(|| text[start..].find(&format!("\"{quoted}\"")))
        .flatten()
    {
        let offset = start + found;
        (
            line_of(text, offset),
            key_on_line(text, offset).unwrap_or_default(),
        )
    } else {
        let field = key_on_line(text, start).unwrap_or_else(|| {
            if message.starts_with("missing field") {
                quoted.to_string()
            } else {
                String::new()
            }
        });
        (line_of(text, start), field)
    };
    PartError {
        path: path.to_path_buf(),
        line: error.span().map(|_| line),
        field,
        message,
    }
}

/// The line of `field` (its last named component, then its first) inside the table at `span`;
/// the table's first line when neither is written there.
fn field_line(text: &str, span: Range<usize>, field: &str) -> usize {
    let names: Vec<&str> = field
        .split('.')
        .map(|part| part.split('[').next().unwrap_or(part))
        .filter(|name| !name.is_empty())
        .collect();
    let start = span.start.min(text.len());
    let table = &text[start..table_end(text, start).max(span.end.min(text.len()))];
    for name in names.iter().rev().chain(names.first()) {
        if let Some(position) = find_key(table, name) {
            return line_of(text, start + position);
        }
    }
    line_of(text, start)
}

/// The end of the table whose header or body starts at `start`: the next line that opens a
/// table (`[`), or the end of the text.
fn table_end(text: &str, start: usize) -> usize {
    let mut offset = start;
    for (index, line) in text[start..].split_inclusive('\n').enumerate() {
        if index > 0 && line.trim_start().starts_with('[') {
            return offset;
        }
        offset += line.len();
    }
    text.len()
}

/// Byte position of `name` used as a key (`name =`) in `table`.
fn find_key(table: &str, name: &str) -> Option<usize> {
    let mut search_from = 0;
    while let Some(found) = table[search_from..].find(name) {
        let position = search_from + found;
        let before = table[..position].chars().next_back();
        let after = table[position + name.len()..].trim_start();
        let starts_word = before.is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
        if starts_word && after.starts_with('=') {
            return Some(position);
        }
        search_from = position + name.len();
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn a_self_intersecting_trim_is_an_error() {
        let text = "[[surface]]\nkind = \"bspline\"\ndegree = [1, 1]\ncontrol_points = [[[0,0,0],[0,1,0]],[[1,0,0],[1,1,0]]]\ntrim = { holes = [[[0.2,0.2],[0.8,0.8],[0.8,0.2],[0.2,0.8]]] }\n";
        let error = error_of(text);
        assert_eq!(error.field, "surface[0].trim.holes[0]");
        assert_eq!(error.line, Some(5));
    }
}
