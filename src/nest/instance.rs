//! Reader of ESICUP strip-packing instances in the JSON form of jagua-rs 0.7 and sparrow:
//!
//! ```json
//! {"name": "shirts", "strip_height": 40.0,
//!  "items": [{"id": 0, "demand": 8, "allowed_orientations": [0.0, 180.0],
//!             "shape": {"type": "simple_polygon", "data": [[0.0, 0.0], [7.0, 1.0], ...]}}]}
//! ```
//!
//! `strip_height` is the roll width (extent along y). A missing `allowed_orientations` means any
//! rotation ([`Rotations::Free`]). Shapes are `simple_polygon` (`data`: the ring) or `polygon`
//! (`data`: `{"outer": ring, "inner": [rings]}`). A repeated closing point is dropped. The serde
//! types stay in this file; the rest of the crate sees [`NestItem`]s.

use std::path::Path;

use glam::DVec2;
use serde::Deserialize;

use super::errors::NestError;
use super::item::NestItem;
use super::rotations::Rotations;

/// A benchmark instance: its items and the strip (roll) width.
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    /// The instance's name.
    pub name: String,
    /// The items, named `<instance>/<id>`.
    pub items: Vec<NestItem>,
    /// The strip height of the benchmark: the roll width, mm.
    pub strip_height: f64,
}

#[derive(Deserialize)]
struct ExternalInstance {
    name: String,
    items: Vec<ExternalItem>,
    strip_height: f64,
}

#[derive(Deserialize)]
struct ExternalItem {
    id: u64,
    demand: u32,
    allowed_orientations: Option<Vec<f64>>,
    shape: ExternalShape,
}

#[derive(Deserialize)]
#[serde(tag = "type", content = "data", rename_all = "snake_case")]
enum ExternalShape {
    SimplePolygon(Vec<[f64; 2]>),
    Polygon {
        outer: Vec<[f64; 2]>,
        inner: Vec<Vec<[f64; 2]>>,
    },
}

/// Reads an instance file. Errors name the file and, for bad JSON, the field, line and column.
pub fn read_instance(path: &Path) -> Result<Instance, NestError> {
    let text = std::fs::read_to_string(path).map_err(|error| NestError::Instance {
        path: path.display().to_string(),
        reason: error.to_string(),
    })?;
    parse_instance(&text).map_err(|reason| NestError::Instance {
        path: path.display().to_string(),
        reason,
    })
}

/// Parses instance JSON text; the error is a message for the user.
pub fn parse_instance(text: &str) -> Result<Instance, String> {
    let external: ExternalInstance =
        serde_json::from_str(text).map_err(|error| format!("not an ESICUP instance: {error}"))?;
    if !external.strip_height.is_finite() || external.strip_height <= 0.0 {
        return Err(format!(
            "strip_height is {}: it must be positive",
            external.strip_height
        ));
    }
    let items = external
        .items
        .into_iter()
        .map(|item| {
            let (outer, holes) = match item.shape {
                ExternalShape::SimplePolygon(ring) => (ring_points(&ring), Vec::new()),
                ExternalShape::Polygon { outer, inner } => (
                    ring_points(&outer),
                    inner.iter().map(|ring| ring_points(ring)).collect(),
                ),
            };
            NestItem {
                name: format!("{}/{}", external.name, item.id),
                outer,
                holes,
                quantity: item.demand,
                rotations: item
                    .allowed_orientations
                    .map_or(Rotations::Free, Rotations::Fixed),
                mirror_allowed: false,
                grain_degrees: None,
            }
        })
        .collect();
    Ok(Instance {
        name: external.name,
        items,
        strip_height: external.strip_height,
    })
}

/// A last point closer than this to the first (relative to the ring's extent) closes the ring.
const CLOSING_TOLERANCE_RELATIVE: f64 = 1e-12;

/// The ring as points, without a closing point that repeats the first.
fn ring_points(ring: &[[f64; 2]]) -> Vec<DVec2> {
    let mut points: Vec<DVec2> = ring.iter().map(|&point| DVec2::from(point)).collect();
    let extent = points.iter().fold(0.0_f64, |extent, point| {
        extent.max(point.abs().max_element())
    });
    if let (Some(first), Some(last)) = (points.first(), points.last())
        && points.len() > 1
        && first.distance(*last) <= CLOSING_TOLERANCE_RELATIVE * extent
    {
        points.pop();
    }
    points
}

#[cfg(test)]
mod tests {
    use crate::nest::instance::*;

    #[test]
    fn reads_items_demands_and_orientations() {
        let text = r#"{"name": "tiny", "strip_height": 10.0, "items": [
            {"id": 0, "demand": 2, "allowed_orientations": [0.0, 180.0],
             "shape": {"type": "simple_polygon", "data": [[0,0],[4,0],[4,3],[0,3],[0,0]]}},
            {"id": 1, "demand": 1,
             "shape": {"type": "polygon", "data": {"outer": [[0,0],[6,0],[6,6],[0,6]],
                                                   "inner": [[[2,2],[4,2],[4,4],[2,4]]]}}}]}"#;
        let instance = parse_instance(text).expect("valid instance");
        assert_eq!(instance.strip_height, 10.0);
        assert_eq!(instance.items.len(), 2);
        assert_eq!(instance.items[0].outer.len(), 4, "closing point dropped");
        assert_eq!(
            instance.items[0].rotations,
            Rotations::Fixed(vec![0.0, 180.0])
        );
        assert_eq!(instance.items[1].rotations, Rotations::Free);
        assert!((instance.items[1].area() - 32.0).abs() < 1e-12);
    }

    #[test]
    fn bad_input_names_the_problem() {
        let missing = parse_instance(r#"{"name": "x", "items": []}"#).expect_err("no strip_height");
        assert!(missing.contains("strip_height"), "{missing}");
        let negative = parse_instance(r#"{"name": "x", "items": [], "strip_height": -1}"#)
            .expect_err("negative");
        assert!(negative.contains("strip_height"), "{negative}");
        let error =
            read_instance(Path::new("/nonexistent/instance.json")).expect_err("missing file");
        assert!(error.to_string().contains("/nonexistent/instance.json"));
    }
}
