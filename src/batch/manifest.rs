//! The parts of a batch: read from a manifest (CSV with a header row, or JSON Lines: one object
//! per line) or given as input files, each with its own name, quantity, material, thickness and
//! options over the batch's.
//!
//! Manifest fields: `input` (required; relative paths are taken from the manifest's folder),
//! `name` (the part's folder under `OUT/parts/`; default the input's file stem), `quantity`,
//! `material`, `thickness` (mm), `units` (of a mesh), `tolerance`, `seam_allowance` (mm) and
//! `max_cuts`. An empty CSV cell gives nothing.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::units::Units;

use super::errors::BatchError;

/// Longest part name, in bytes: it names a folder.
pub const MAXIMUM_NAME_BYTES: usize = 200;

/// One line of a manifest: a part and what it says over the batch's options.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestEntry {
    /// The input file, as written.
    pub input: String,
    /// The part's name; default the input's file stem.
    #[serde(default)]
    pub name: Option<String>,
    /// How many copies to cut.
    #[serde(default)]
    pub quantity: Option<u32>,
    /// Material.
    #[serde(default)]
    pub material: Option<String>,
    /// Sheet thickness, mm.
    #[serde(default)]
    pub thickness: Option<f64>,
    /// Units of a mesh's coordinates.
    #[serde(default)]
    pub units: Option<Units>,
    /// Permissible area and shape error (a fraction).
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Seam allowance, mm.
    #[serde(default)]
    pub seam_allowance: Option<f64>,
    /// Largest number of crest-line cuts.
    #[serde(default)]
    pub max_cuts: Option<usize>,
}

/// The manifest fields, in the order the documentation gives them.
pub const MANIFEST_FIELDS: [&str; 9] = [
    "input",
    "name",
    "quantity",
    "material",
    "thickness",
    "units",
    "tolerance",
    "seam_allowance",
    "max_cuts",
];

/// A part of a batch: its name, where its input is, and its manifest line.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchPart {
    /// The part's name: its folder under `OUT/parts/`.
    pub name: String,
    /// The input file, found from the current folder.
    pub path: PathBuf,
    /// The manifest line (for input files given on the command line, just the input).
    pub entry: ManifestEntry,
}

/// The parts of a manifest file, in its order, with unique, valid names.
pub fn read_manifest(path: &Path) -> Result<Vec<BatchPart>, BatchError> {
    let text = std::fs::read_to_string(path).map_err(|source| BatchError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    parse_manifest(path, &text)
}

/// The parts of the manifest text of the file at `path` (CSV when its extension is `csv`, JSON
/// Lines otherwise; relative inputs are in its folder), in its order, with unique, valid names.
pub fn parse_manifest(path: &Path, text: &str) -> Result<Vec<BatchPart>, BatchError> {
    let is_csv = path
        .extension()
        .is_some_and(|extension| extension.eq_ignore_ascii_case("csv"));
    let entries = if is_csv {
        csv_entries(path, text)?
    } else {
        json_lines_entries(path, text)?
    };
    if entries.is_empty() {
        return Err(BatchError::Manifest {
            path: path.to_path_buf(),
            line: 1,
            reason: "the manifest lists no part".to_string(),
        });
    }
    let folder = path.parent().unwrap_or(Path::new(""));
    let parts = entries
        .into_iter()
        .map(|(line, entry)| {
            part_of(folder, entry).map_err(|reason| BatchError::Manifest {
                path: path.to_path_buf(),
                line,
                reason,
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    check_distinct_names(&parts)?;
    Ok(parts)
}

/// The parts of input files given on the command line, named by their file stems.
pub fn parts_of_inputs(inputs: &[PathBuf]) -> Result<Vec<BatchPart>, BatchError> {
    let parts = inputs
        .iter()
        .map(|input| {
            let entry = ManifestEntry {
                input: input.to_string_lossy().into_owned(),
                ..ManifestEntry::default()
            };
            part_of(Path::new(""), entry).map_err(|reason| BatchError::Input {
                path: input.clone(),
                reason,
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    check_distinct_names(&parts)?;
    Ok(parts)
}

/// The lines of a CSV manifest with their line numbers; the header names the fields.
fn csv_entries(path: &Path, text: &str) -> Result<Vec<(usize, ManifestEntry)>, BatchError> {
    let error = |line: usize, reason: String| BatchError::Manifest {
        path: path.to_path_buf(),
        line,
        reason,
    };
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let headers = reader
        .headers()
        .map_err(|source| error(1, source.to_string()))?
        .clone();
    for header in &headers {
        if !MANIFEST_FIELDS.contains(&header) {
            return Err(error(1, unknown_field(header)));
        }
    }
    if !headers.iter().any(|header| header == "input") {
        return Err(error(1, "the header has no `input` column".to_string()));
    }
    let mut entries = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|source| {
            let line = source.position().map_or(0, |position| position.line());
            error(line as usize, source.to_string())
        })?;
        let line = record.position().map_or(0, |position| position.line()) as usize;
        let fields: BTreeMap<&str, &str> = headers
            .iter()
            .zip(record.iter())
            .filter(|(_, value)| !value.is_empty())
            .collect();
        let entry = entry_of_fields(&fields).map_err(|reason| error(line, reason))?;
        entries.push((line, entry));
    }
    Ok(entries)
}

/// A manifest entry from the non-empty CSV cells of one line, by field name.
fn entry_of_fields(fields: &BTreeMap<&str, &str>) -> Result<ManifestEntry, String> {
    fn number<T: std::str::FromStr>(
        fields: &BTreeMap<&str, &str>,
        field: &str,
    ) -> Result<Option<T>, String> {
        fields
            .get(field)
            .map(|value| {
                value
                    .parse()
                    .map_err(|_| format!("`{field}` is {value:?}: give a number"))
            })
            .transpose()
    }
    let text = |field: &str| fields.get(field).map(|value| value.to_string());
    let units = fields
        .get("units")
        .map(|value| {
            <Units as clap::ValueEnum>::from_str(value, true)
                .map_err(|_| format!("`units` is {value:?}: give mm, cm, m or in"))
        })
        .transpose()?;
    Ok(ManifestEntry {
        input: text("input").ok_or("`input` is empty: every part needs its input file")?,
        name: text("name"),
        quantity: number(fields, "quantity")?,
        material: text("material"),
        thickness: number(fields, "thickness")?,
        units,
        tolerance: number(fields, "tolerance")?,
        seam_allowance: number(fields, "seam_allowance")?,
        max_cuts: number(fields, "max_cuts")?,
    })
}

/// The lines of a JSON Lines manifest with their line numbers; blank lines are skipped.
fn json_lines_entries(path: &Path, text: &str) -> Result<Vec<(usize, ManifestEntry)>, BatchError> {
    text.lines()
        .enumerate()
        .filter(|(_, line)| !line.trim().is_empty())
        .map(|(index, line)| {
            serde_json::from_str(line)
                .map(|entry| (index + 1, entry))
                .map_err(|source| BatchError::Manifest {
                    path: path.to_path_buf(),
                    line: index + 1,
                    reason: source.to_string(),
                })
        })
        .collect()
}

/// Names the fields a manifest knows, for an unknown one.
fn unknown_field(field: &str) -> String {
    format!(
        "unknown field `{field}`: the fields are {}",
        MANIFEST_FIELDS.join(", ")
    )
}

/// The part of a manifest entry, its input found from `folder`.
fn part_of(folder: &Path, entry: ManifestEntry) -> Result<BatchPart, String> {
    let input = Path::new(&entry.input);
    let path = if input.is_absolute() {
        input.to_path_buf()
    } else {
        folder.join(input)
    };
    let name = match &entry.name {
        Some(name) => name.clone(),
        None => path
            .file_stem()
            .map(|stem| stem.to_string_lossy().into_owned())
            .ok_or_else(|| format!("`{}` names no file", entry.input))?,
    };
    check_name(&name)?;
    Ok(BatchPart { name, path, entry })
}

/// Refuses a name that cannot be a folder of its own under `OUT/parts/`.
fn check_name(name: &str) -> Result<(), String> {
    let reason = if name.is_empty() {
        Some("is empty")
    } else if name.len() > MAXIMUM_NAME_BYTES {
        Some("is longer than 200 bytes")
    } else if name.starts_with('.') {
        Some("starts with a dot")
    } else if name
        .chars()
        .any(|c| c.is_control() || matches!(c, '/' | '\\' | ':'))
    {
        Some("holds a path separator, a colon or a control character")
    } else {
        None
    };
    match reason {
        Some(reason) => Err(format!(
            "part name {name:?} {reason}: it names the part's folder"
        )),
        None => Ok(()),
    }
}

/// Refuses two parts of one name: they would share a folder.
fn check_distinct_names(parts: &[BatchPart]) -> Result<(), BatchError> {
    let mut seen: BTreeMap<&str, &BatchPart> = BTreeMap::new();
    for part in parts {
        if let Some(earlier) = seen.insert(&part.name, part) {
            return Err(BatchError::DuplicateName {
                name: part.name.clone(),
                first: earlier.entry.input.clone(),
                second: part.entry.input.clone(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::batch::manifest::*;

    fn write(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
        let folder = tempfile::tempdir().expect("temporary folder");
        let path = folder.path().join(name);
        std::fs::write(&path, text).expect("manifest written");
        (folder, path)
    }

    #[test]
    fn csv_and_json_lines_give_the_same_parts() {
        let (_csv_folder, csv) = write(
            "batch.csv",
            "input,name,quantity,material,thickness,units\n\
             a/shirt.obj,shirt-s,2,cotton,,in\n\
             b/bracket.toml,,,steel,1.5,\n",
        );
        let (_json_folder, json) = write(
            "batch.jsonl",
            "{\"input\": \"a/shirt.obj\", \"name\": \"shirt-s\", \"quantity\": 2, \
             \"material\": \"cotton\", \"units\": \"in\"}\n\n\
             {\"input\": \"b/bracket.toml\", \"material\": \"steel\", \"thickness\": 1.5}\n",
        );
        let from_csv = read_manifest(&csv).expect("CSV manifest");
        let from_json = read_manifest(&json).expect("JSON Lines manifest");
        let entries = |parts: &[BatchPart]| -> Vec<(String, ManifestEntry)> {
            parts
                .iter()
                .map(|part| (part.name.clone(), part.entry.clone()))
                .collect()
        };
        assert_eq!(entries(&from_csv), entries(&from_json));
        assert_eq!(from_csv[0].name, "shirt-s");
        assert_eq!(from_csv[0].entry.units, Some(Units::Inches));
        assert_eq!(from_csv[1].name, "bracket");
        assert_eq!(from_csv[1].entry.thickness, Some(1.5));
        assert!(from_csv[1].path.ends_with("b/bracket.toml"));
        assert!(from_csv[1].path.starts_with(csv.parent().unwrap()));
    }

    #[test]
    fn bad_manifests_name_the_line_and_the_fault() {
        let cases = [
            (
                "bad.csv",
                "input,colour\nx.obj,red\n",
                "line 1: unknown field `colour`",
            ),
            (
                "bad.csv",
                "input,quantity\nx.obj,many\n",
                "line 2: `quantity` is \"many\"",
            ),
            (
                "bad.csv",
                "input\nx.obj\ny/x.obj\n",
                "two parts named \"x\"",
            ),
            (
                "bad.jsonl",
                "{\"input\": \"x.obj\"}\n{\"inptu\": 1}\n",
                "line 2: unknown field",
            ),
            (
                "bad.csv",
                "input,name\nx.obj,../up\n",
                "line 2: part name \"../up\"",
            ),
            ("bad.csv", "input\n", "lists no part"),
        ];
        for (name, text, expected) in cases {
            let (_folder, path) = write(name, text);
            let message = read_manifest(&path).expect_err(text).to_string();
            assert!(message.contains(expected), "{text:?} gave {message}");
        }
    }
}
