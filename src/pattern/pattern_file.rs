//! A part's pattern file, `<part>.pattern.json`: exactly what nesting and the sheet drawings need
//! of a flattened part, so the patterns of parts flattened in separate runs (or on separate
//! machines) can be nested together later without flattening again. Written by every run beside
//! the part's DXF; `flatcut nest` reads it. See `docs/formats.md`.
//!
//! Values in, text out: [`PatternFile::to_json`] gives the bytes (deterministic, every f64 in the
//! shortest form that reads back to the same value) and [`PatternFile::from_json`] reads them
//! back bit for bit (serde_json's `float_roundtrip` parser), refusing another format or version.

use serde::{Deserialize, Serialize};

use super::drawing::PartDrawing;
use super::options::PatternOptions;

/// The ending of a pattern file's name: `<part>.pattern.json`.
pub const PATTERN_FILE_ENDING: &str = ".pattern.json";

/// The `format` key of every pattern file.
pub const PATTERN_FILE_FORMAT: &str = "flatcut-pattern";

/// The version of the pattern file format this flatcut writes and reads; raised when a key
/// changes meaning.
pub const PATTERN_FILE_VERSION: u32 = 1;

/// What a pattern file holds: the part's drawing and what shapes its nested contour.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PatternFile {
    /// The part's flat pattern as drawn: name, units, quantity, material, outer contour, holes,
    /// fold lines, grain line.
    pub drawing: PartDrawing,
    /// The grain direction in the drawing's frame, degrees counter-clockwise from x, when the
    /// part has a grain (the nester keeps it along the stock's x axis).
    pub grain_degrees: Option<f64>,
    /// The part's sheet thickness in mm, when it has one: parts of different thicknesses are
    /// nested on separate stock.
    pub thickness_mm: Option<f64>,
    /// The chord tolerance and seam allowance the part's cut contours are made with.
    pub options: PatternOptions,
    /// Whether the part was rejected (over tolerance, flipped triangles or overlap): its cut file
    /// is `<part>.REJECTED.dxf`, and `flatcut nest` refuses it unless asked to include it.
    pub rejected: bool,
}

/// What follows the name of a rejected part on the sheets it is nested on.
pub const REJECTED_MARK: &str = "REJECTED";

impl PatternFile {
    /// The drawing as it goes on a nested sheet: a rejected part's name followed by
    /// [`REJECTED_MARK`], so that its label on the sheet's DXF and preview says so.
    pub fn sheet_drawing(&self) -> PartDrawing {
        let mut drawing = self.drawing.clone();
        if self.rejected {
            drawing.name = format!("{} {REJECTED_MARK}", drawing.name);
        }
        drawing
    }
}

/// A pattern file as written: the format's name and version first.
#[derive(Serialize)]
struct Written<'a> {
    format: &'static str,
    version: u32,
    #[serde(flatten)]
    pattern: &'a PatternFile,
}

/// Why a pattern file's text could not be read.
#[derive(Debug, thiserror::Error)]
pub enum PatternFileError {
    /// The text is not JSON, or a key is missing or of the wrong kind.
    #[error("not a valid pattern file: {0}")]
    Json(#[source] serde_json::Error),
    /// The `format` key is missing or names another format.
    #[error(
        "not a flatcut pattern file: its \"format\" is {found}, expected \"{PATTERN_FILE_FORMAT}\""
    )]
    NotAPatternFile {
        /// The `format` value found, as JSON (`null` when missing).
        found: String,
    },
    /// The file is of another version of the format.
    #[error(
        "pattern file format version {found}: this flatcut reads version {PATTERN_FILE_VERSION}; \
         flatten the part again with this flatcut"
    )]
    UnsupportedVersion {
        /// The `version` value found, as JSON (`null` when missing).
        found: String,
    },
}

impl PatternFile {
    /// The file's text: pretty JSON with a final newline, `format` and `version` first.
    pub fn to_json(&self) -> Result<String, serde_json::Error> {
        let written = Written {
            format: PATTERN_FILE_FORMAT,
            version: PATTERN_FILE_VERSION,
            pattern: self,
        };
        Ok(serde_json::to_string_pretty(&written)? + "\n")
    }

    /// Reads a pattern file's text, refusing another format or another version of this one.
    pub fn from_json(text: &str) -> Result<Self, PatternFileError> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(PatternFileError::Json)?;
        let key = |name: &str| value.get(name).cloned().unwrap_or_default();
        let format = key("format");
        if format.as_str() != Some(PATTERN_FILE_FORMAT) {
            return Err(PatternFileError::NotAPatternFile {
                found: format.to_string(),
            });
        }
        let version = key("version");
        if version.as_u64() != Some(u64::from(PATTERN_FILE_VERSION)) {
            return Err(PatternFileError::UnsupportedVersion {
                found: version.to_string(),
            });
        }
        // Read again from the text, not the value: errors then name the line and column.
        serde_json::from_str(text).map_err(PatternFileError::Json)
    }
}

#[cfg(test)]
mod tests {
    use crate::pattern::pattern_file::*;
    use crate::sheet::{BendDirection, BendLine};
    use crate::units::Units;
    use glam::DVec2;
    use proptest::prelude::*;

    fn square(values: [f64; 4]) -> PatternFile {
        let [a, b, c, d] = values;
        PatternFile {
            drawing: PartDrawing {
                name: "plate".into(),
                units: Units::Inches,
                quantity: 3,
                material: Some("steel".into()),
                outer: vec![DVec2::new(a, b), DVec2::new(c, b), DVec2::new(c, d)],
                holes: vec![vec![DVec2::new(d, c), DVec2::new(b, a), DVec2::new(a, d)]],
                fold_lines: vec![vec![DVec2::new(a, c), DVec2::new(b, d)]],
                grain: Some([DVec2::new(a, a), DVec2::new(d, d)]),
                bends: vec![BendLine {
                    line: [DVec2::new(a, d), DVec2::new(c, b)],
                    direction: BendDirection::Down,
                    angle_degrees: c,
                    inner_radius: b,
                    allowance: d,
                    rule: Some(crate::sheet::AllowanceRule::Din6935 {
                        k: a,
                        compensation: b,
                    }),
                    conical: None,
                }],
            },
            grain_degrees: Some(c),
            thickness_mm: Some(b),
            options: PatternOptions {
                chord_tolerance: 0.01,
                seam_allowance: Some(a.abs().max(1.0)),
                bend_zones: true,
            },
            rejected: true,
        }
    }

    #[test]
    fn awkward_floats_read_back_to_the_same_bits() {
        let awkward = [
            -0.0,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            0.1 + 0.2,
            1.0 / 3.0,
            // The largest subnormal, and 2^53 + 2.
            f64::from_bits(0x000F_FFFF_FFFF_FFFF),
            f64::from_bits(0x4340_0000_0000_0001),
            123456.78901234567,
            -1.7976931348623157e308,
            // Read back one unit in the last place off without serde_json's float_roundtrip.
            f64::from_bits(7_298_876_732_068_443_691),
        ];
        for window in awkward.windows(4) {
            let file = square([window[0], window[1], window[2], window[3]]);
            let text = file.to_json().expect("written");
            let read = PatternFile::from_json(&text).expect("read");
            assert_eq!(read.to_json().expect("written"), text, "same bytes again");
            let bits = |file: &PatternFile| {
                let mut bits: Vec<u64> = file
                    .drawing
                    .outer
                    .iter()
                    .flat_map(|p| [p.x.to_bits(), p.y.to_bits()])
                    .collect();
                bits.extend(file.grain_degrees.map(f64::to_bits));
                bits.extend(file.thickness_mm.map(f64::to_bits));
                bits
            };
            assert_eq!(bits(&read), bits(&file));
            assert_eq!(read, file);
        }
    }

    proptest! {
        #[test]
        fn any_finite_f64_reads_back_to_the_same_bits(bits in proptest::array::uniform4(any::<u64>())) {
            let values = bits.map(|bits| {
                let value = f64::from_bits(bits);
                if value.is_finite() { value } else { 1.0 }
            });
            let file = square(values);
            let read = PatternFile::from_json(&file.to_json().expect("written")).expect("read");
            for (written, read) in file.drawing.outer.iter().zip(&read.drawing.outer) {
                prop_assert_eq!(written.x.to_bits(), read.x.to_bits());
                prop_assert_eq!(written.y.to_bits(), read.y.to_bits());
            }
            prop_assert_eq!(read.grain_degrees.map(f64::to_bits), file.grain_degrees.map(f64::to_bits));
        }
    }

    #[test]
    fn another_format_or_version_is_refused() {
        let text = square([0.0, 1.0, 2.0, 3.0]).to_json().expect("written");
        let newer = text.replacen("\"version\": 1", "\"version\": 2", 1);
        assert!(matches!(
            PatternFile::from_json(&newer),
            Err(PatternFileError::UnsupportedVersion { found }) if found == "2"
        ));
        let other = text.replacen(PATTERN_FILE_FORMAT, "esicup", 1);
        assert!(matches!(
            PatternFile::from_json(&other),
            Err(PatternFileError::NotAPatternFile { .. })
        ));
        assert!(matches!(
            PatternFile::from_json(&text[..text.len() / 2]),
            Err(PatternFileError::Json(_))
        ));
        assert!(text.starts_with("{\n  \"format\": \"flatcut-pattern\",\n  \"version\": 1,"));
    }
}
