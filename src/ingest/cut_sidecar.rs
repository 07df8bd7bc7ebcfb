//! The cut sidecar of a mesh file: user seams and no-cut regions for a part given as a plain
//! mesh, which has no place for them. For `part.obj` (or `part.stl`) it is `part.cut.json` in the
//! same folder, in the mesh's coordinates:
//!
//! ```json
//! {
//!   "seams": [[[0, -100, 0], [0, -75, 50], [0, -50, 100]]],
//!   "no_cut_regions": [{"center": [0, 0, 100], "radius": 20}]
//! }
//! ```
//!
//! Both keys are optional; unknown keys are an error (a misspelt key would otherwise be ignored).
//! A sidecar applies to a mesh file with a single part: with several, which part a seam belongs
//! to would be a guess.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::errors::IngestError;

/// A cut sidecar as written: user seams and no-cut regions, in the mesh's coordinates (the
/// pipeline hands them to the cut stage).
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, rename = "CutConstraints")]
pub struct CutSidecar {
    /// User seams: 3D polylines in model units.
    #[serde(default)]
    pub seams: Vec<Vec<[f64; 3]>>,
    /// Balls of the part where nothing may be cut.
    #[serde(default)]
    pub no_cut_regions: Vec<SidecarRegion>,
}

/// A ball of the part where nothing may be cut, as written in a sidecar.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, rename = "NoCutRegion")]
pub struct SidecarRegion {
    /// Centre, model units.
    pub center: [f64; 3],
    /// Radius, model units.
    pub radius: f64,
}

/// The sidecar's path for a mesh file: the extension replaced by `cut.json`.
pub fn cut_sidecar_path(mesh: &Path) -> PathBuf {
    mesh.with_extension("cut.json")
}

/// Reads the sidecar of `mesh` if there is one. `parts` is the number of parts the mesh holds.
pub fn read_cut_sidecar(mesh: &Path, parts: usize) -> Result<Option<CutSidecar>, IngestError> {
    let path = cut_sidecar_path(mesh);
    let text = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(source) => return Err(IngestError::Read { path, source }),
    };
    parse_cut_sidecar(&path, &text, parts).map(Some)
}

/// Parses the text of the sidecar at `path` (named in errors) of a mesh of `parts` parts.
pub fn parse_cut_sidecar(path: &Path, text: &str, parts: usize) -> Result<CutSidecar, IngestError> {
    let refused = |message: String| IngestError::Sidecar {
        path: path.to_path_buf(),
        message,
    };
    let constraints: CutSidecar =
        serde_json::from_str(text).map_err(|error| refused(error.to_string()))?;
    if parts > 1 {
        return Err(refused(format!(
            "the mesh holds {parts} parts; seams and no-cut regions need a mesh file per part"
        )));
    }
    Ok(constraints)
}

#[cfg(test)]
mod tests {
    use crate::ingest::cut_sidecar::*;

    #[test]
    fn a_missing_sidecar_is_no_constraint() {
        let mesh = Path::new("/nonexistent/folder/part.obj");
        assert!(matches!(read_cut_sidecar(mesh, 1), Ok(None)));
    }

    #[test]
    fn a_sidecar_is_read_and_checked() {
        let folder = tempfile::tempdir().expect("temporary folder");
        let mesh = folder.path().join("part.obj");
        let sidecar = cut_sidecar_path(&mesh);
        std::fs::write(
            &sidecar,
            r#"{"seams": [[[0, 0, 0], [1, 0, 0]]], "no_cut_regions": [{"center": [0, 0, 1], "radius": 2}]}"#,
        )
        .expect("write");
        let constraints = read_cut_sidecar(&mesh, 1).expect("valid").expect("present");
        assert_eq!(
            constraints.seams,
            vec![vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]]
        );
        assert_eq!(constraints.no_cut_regions[0].radius, 2.0);
        assert!(matches!(
            read_cut_sidecar(&mesh, 2),
            Err(IngestError::Sidecar { .. })
        ));
        std::fs::write(&sidecar, r#"{"seems": []}"#).expect("write");
        assert!(matches!(
            read_cut_sidecar(&mesh, 1),
            Err(IngestError::Sidecar { .. })
        ));
    }
}
