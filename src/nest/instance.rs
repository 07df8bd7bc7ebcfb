//! Reader of ESICUP strip-packing instances in the JSON forms of jagua-rs and sparrow:
//!
//! ```json
//! {"name": "shirts", "strip_height": 40.0,
//!  "items": [{"id": 0, "demand": 8, "allowed_orientations": [0.0, 180.0],
//!             "shape": {"type": "simple_polygon", "data": [[0.0, 0.0], [7.0, 1.0], ...]}}]}
//! ```
//!
//! `strip_height` is the roll width (extent along y). An item's rotations are given either by
//! `allowed_orientations` (jagua-rs 0.7 and the published instances: a list of degrees, `[]`
//! meaning `[0]`, missing meaning any rotation, [`Rotations::Free`]) or by jagua-rs's newer
//! `orientation` object: `{"rotation": {"mode": "discrete", "angles": [0, 180]} | {"mode":
//! "stepped", "step": 90} | {"mode": "continuous"}, "reflection_axes": [90]}`. A reflection axis
//! at `a` degrees through the item's origin, then a rotation `r`, is the mirror x → −x then the
//! rotation `r + 2a + 180`: the item's [`NestItem::mirror`] rotations. An item with both forms,
//! an unknown mode or an unknown orientation field is refused, never read as free rotation.
//! Shapes are `simple_polygon` (`data`: the ring) or `polygon` (`data`: `{"outer": ring,
//! "inner": [rings]}`). A repeated closing point is dropped. jagua-rs's first, capitalised form
//! (`{"Name", "Items": [{"Demand", "AllowedOrientations", "Shape": {"Type": "SimplePolygon",
//! "Data"}}], "Strip": {"Height"}}`), which older copies of the instances (swim) still carry, is
//! read too, its items numbered in file order. The serde types stay in this file; the rest of the
//! crate sees [`NestItem`]s.

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
    orientation: Option<ExternalOrientation>,
    shape: ExternalShape,
}

/// jagua-rs's `orientation` object: the rotations, and the axes the item may be reflected about.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ExternalOrientation {
    rotation: ExternalRotation,
    #[serde(default)]
    reflection_axes: Vec<f64>,
}

#[derive(Deserialize)]
#[serde(tag = "mode", rename_all = "snake_case", deny_unknown_fields)]
enum ExternalRotation {
    Discrete { angles: Vec<f64> },
    Stepped { step: f64 },
    Continuous {},
}

/// An instance in jagua-rs's first, capitalised form.
#[derive(Deserialize)]
#[serde(rename_all = "PascalCase")]
struct LegacyInstance {
    name: String,
    items: Vec<LegacyItem>,
    strip: LegacyStrip,
}

#[derive(Deserialize)]
#[serde(rename_all = "PascalCase")]
struct LegacyStrip {
    height: f64,
}

#[derive(Deserialize)]
#[serde(rename_all = "PascalCase")]
struct LegacyItem {
    demand: u32,
    allowed_orientations: Option<Vec<f64>>,
    shape: LegacyShape,
}

#[derive(Deserialize)]
#[serde(tag = "Type", content = "Data")]
enum LegacyShape {
    SimplePolygon(Vec<[f64; 2]>),
}

impl From<LegacyInstance> for ExternalInstance {
    fn from(legacy: LegacyInstance) -> Self {
        let items = legacy
            .items
            .into_iter()
            .zip(0..)
            .map(|(item, id)| {
                let LegacyShape::SimplePolygon(ring) = item.shape;
                ExternalItem {
                    id,
                    demand: item.demand,
                    allowed_orientations: item.allowed_orientations,
                    orientation: None,
                    shape: ExternalShape::SimplePolygon(ring),
                }
            })
            .collect();
        ExternalInstance {
            name: legacy.name,
            items,
            strip_height: legacy.strip.height,
        }
    }
}

/// Most angles an `orientation` may list or a step may expand to (jagua-rs's limit).
const MAX_ORIENTATION_ANGLES: usize = 65_536;

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
    let external = serde_json::from_str::<ExternalInstance>(text).or_else(|error| {
        serde_json::from_str::<LegacyInstance>(text)
            .map(ExternalInstance::from)
            .map_err(|legacy_error| {
                format!(
                    "not an ESICUP instance: {error} (nor in jagua-rs's older capitalised form: \
                     {legacy_error})"
                )
            })
    })?;
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
            let name = format!("{}/{}", external.name, item.id);
            let (rotations, mirror) = item_rotations(item.allowed_orientations, item.orientation)
                .map_err(|reason| format!("item {}: {reason}", item.id))?;
            let (outer, holes) = match item.shape {
                ExternalShape::SimplePolygon(ring) => (ring_points(&ring), Vec::new()),
                ExternalShape::Polygon { outer, inner } => (
                    ring_points(&outer),
                    inner.iter().map(|ring| ring_points(ring)).collect(),
                ),
            };
            Ok(NestItem {
                name,
                outer,
                holes,
                quantity: item.demand,
                rotations,
                mirror,
                grain_degrees: None,
            })
        })
        .collect::<Result<_, String>>()?;
    Ok(Instance {
        name: external.name,
        items,
        strip_height: external.strip_height,
    })
}

/// An item's rotations, and those of its mirrored copies (`None`: not mirrored), from either
/// form of the instance file.
fn item_rotations(
    allowed_orientations: Option<Vec<f64>>,
    orientation: Option<ExternalOrientation>,
) -> Result<(Rotations, Option<Rotations>), String> {
    match (allowed_orientations, orientation) {
        (Some(_), Some(_)) => {
            Err("give either `allowed_orientations` or `orientation`, not both".to_string())
        }
        (None, None) => Ok((Rotations::Free, None)),
        (Some(angles), None) if angles.is_empty() => Ok((Rotations::Fixed(vec![0.0]), None)),
        (Some(angles), None) => Ok((Rotations::Fixed(angles), None)),
        (None, Some(orientation)) => {
            let rotations = match orientation.rotation {
                ExternalRotation::Discrete { angles } => discrete(angles)?,
                ExternalRotation::Stepped { step } => stepped(step)?,
                ExternalRotation::Continuous {} => Rotations::Free,
            };
            let mirror = reflected(&rotations, &orientation.reflection_axes)?;
            Ok((rotations, mirror))
        }
    }
}

/// A `discrete` rotation: a finite, nonempty list of at most [`MAX_ORIENTATION_ANGLES`].
fn discrete(angles: Vec<f64>) -> Result<Rotations, String> {
    if angles.is_empty() || angles.len() > MAX_ORIENTATION_ANGLES {
        return Err(format!(
            "a discrete rotation lists {} angles: give 1 to {MAX_ORIENTATION_ANGLES}",
            angles.len()
        ));
    }
    if let Some(angle) = angles.iter().find(|angle| !angle.is_finite()) {
        return Err(format!("the rotation angle {angle} is not a finite number"));
    }
    Ok(Rotations::Fixed(angles))
}

/// A `stepped` rotation: its step must divide 360° (as jagua-rs requires: 90 and 0.1 do, 7 does
/// not) into at most [`MAX_ORIENTATION_ANGLES`] rotations.
fn stepped(step: f64) -> Result<Rotations, String> {
    let count = (360.0 / step).round();
    let divides = step > 0.0
        && step <= 360.0
        && (count * step - 360.0).abs() <= 360.0 * f64::from(f32::EPSILON);
    if !divides || count > MAX_ORIENTATION_ANGLES as f64 {
        return Err(format!(
            "the rotation step {step}° does not divide 360° into at most \
             {MAX_ORIENTATION_ANGLES} rotations"
        ));
    }
    Ok(Rotations::Step(360.0 / count))
}

/// The rotations of the copies mirrored (x → −x) before their rotation, for reflections about
/// `axes` (degrees, through the item's origin) before `rotations`: a reflection about the axis at
/// `a` equals the mirror x → −x followed by a turn of `2a + 180`. `None` without axes.
fn reflected(rotations: &Rotations, axes: &[f64]) -> Result<Option<Rotations>, String> {
    if axes.len() > MAX_ORIENTATION_ANGLES {
        return Err(format!(
            "{} reflection axes: give at most {MAX_ORIENTATION_ANGLES}",
            axes.len()
        ));
    }
    if let Some(axis) = axes.iter().find(|axis| !axis.is_finite()) {
        return Err(format!("the reflection axis {axis} is not a finite number"));
    }
    let turned: Vec<Rotations> = axes
        .iter()
        .map(|axis| rotations.turned_by(2.0 * axis + 180.0))
        .collect();
    Ok(Rotations::union(&turned))
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

    /// An instance whose items take jagua-rs's `orientation` object.
    fn oriented(orientation: &str) -> Result<Instance, String> {
        parse_instance(&format!(
            r#"{{"name": "o", "strip_height": 10, "items": [{{"id": 0, "demand": 1,
                "orientation": {orientation},
                "shape": {{"type": "simple_polygon", "data": [[2,3],[8,3],[8,5],[5,5],[5,9],[2,9]]}}}}]}}"#
        ))
    }

    #[test]
    fn reads_jagua_orientation_objects() {
        let item = |orientation| oriented(orientation).expect("valid").items.remove(0);
        let discrete = item(r#"{"rotation": {"mode": "discrete", "angles": [15, 195]}}"#);
        assert_eq!(discrete.rotations, Rotations::Fixed(vec![15.0, 195.0]));
        assert_eq!(discrete.mirror, None);
        let stepped = item(r#"{"rotation": {"mode": "stepped", "step": 90}}"#);
        assert_eq!(
            stepped.rotations.angles(),
            Some(vec![0.0, 90.0, 180.0, 270.0])
        );
        let continuous = item(r#"{"rotation": {"mode": "continuous"}, "reflection_axes": [0]}"#);
        assert_eq!(continuous.rotations, Rotations::Free);
        assert_eq!(continuous.mirror, Some(Rotations::Free));
        assert!(continuous.turns_freely());
        // jagua-rs's example: fixed at 0°, reflected about the y axis. The mirrored copy is the
        // mirror x → −x unturned; about the x axis it is that mirror turned by 180°.
        let y_axis =
            item(r#"{"rotation": {"mode": "discrete", "angles": [0]}, "reflection_axes": [90]}"#);
        assert_eq!(y_axis.poses(), Some(vec![(0.0, false), (0.0, true)]));
        let x_axis =
            item(r#"{"rotation": {"mode": "discrete", "angles": [0]}, "reflection_axes": [0]}"#);
        assert_eq!(x_axis.poses(), Some(vec![(0.0, false), (180.0, true)]));
        assert!(!x_axis.allows(0.0, true) && x_axis.allows(180.0, true));
        // A step whose multiples hold the reflection's turn stays a step.
        let stepped_mirror =
            item(r#"{"rotation": {"mode": "stepped", "step": 90}, "reflection_axes": [45]}"#);
        assert_eq!(stepped_mirror.mirror, Some(Rotations::Step(90.0)));
        // Both axes are alternatives, not successive reflections: no unmirrored 180° turn.
        let both = item(
            r#"{"rotation": {"mode": "discrete", "angles": [0]}, "reflection_axes": [0, 90]}"#,
        );
        assert_eq!(
            both.mirror.as_ref().and_then(Rotations::angles),
            Some(vec![0.0, 180.0])
        );
        assert!(!both.allows(180.0, false));
    }

    #[test]
    fn refuses_orientations_it_cannot_read_rather_than_freeing_them() {
        for (orientation, expected) in [
            (r#"{"rotation": {"mode": "spiral"}}"#, "unknown variant"),
            (
                r#"{"rotation": {"mode": "discrete", "angles": []}}"#,
                "1 to 65536",
            ),
            (
                r#"{"rotation": {"mode": "stepped", "step": 7}}"#,
                "does not divide 360",
            ),
            (
                r#"{"rotation": {"mode": "stepped", "step": 0}}"#,
                "does not divide 360",
            ),
            (
                r#"{"rotation": {"mode": "continuous", "step": 5}}"#,
                "unknown field",
            ),
            (
                r#"{"rotation": {"mode": "continuous"}, "mirror": true}"#,
                "unknown field",
            ),
            (r#"{"reflection_axes": [0]}"#, "missing field `rotation`"),
        ] {
            let error = oriented(orientation).expect_err(orientation);
            assert!(error.contains(expected), "{orientation}: {error}");
        }
        let both = parse_instance(
            r#"{"name": "b", "strip_height": 10, "items": [{"id": 3, "demand": 1,
                "allowed_orientations": [0], "orientation": {"rotation": {"mode": "continuous"}},
                "shape": {"type": "simple_polygon", "data": [[0,0],[1,0],[0,1]]}}]}"#,
        )
        .expect_err("both forms");
        assert!(
            both.contains("item 3") && both.contains("not both"),
            "{both}"
        );
    }

    #[test]
    fn an_empty_orientation_list_means_unturned() {
        let text = r#"{"name": "e", "strip_height": 10, "items": [{"id": 0, "demand": 1,
            "allowed_orientations": [], "shape": {"type": "simple_polygon", "data": [[0,0],[1,0],[0,1]]}}]}"#;
        let instance = parse_instance(text).expect("valid");
        assert_eq!(instance.items[0].rotations, Rotations::Fixed(vec![0.0]));
    }

    #[test]
    fn reads_the_older_capitalised_form_numbering_items_in_file_order() {
        let text = r#"{"Name": "old", "Strip": {"Height": 12.0}, "Items": [
            {"Demand": 3, "DemandMax": 3, "AllowedOrientations": [0.0, 180.0],
             "Shape": {"Type": "SimplePolygon", "Data": [[0,0],[5,0],[5,2],[0,2]]}},
            {"Demand": 1, "Shape": {"Type": "SimplePolygon", "Data": [[0,0],[3,0],[0,4]]}}]}"#;
        let instance = parse_instance(text).expect("valid instance");
        assert_eq!(instance.name, "old");
        assert_eq!(instance.strip_height, 12.0);
        let names: Vec<&str> = instance
            .items
            .iter()
            .map(|item| item.name.as_str())
            .collect();
        assert_eq!(names, ["old/0", "old/1"]);
        assert_eq!(instance.items[0].quantity, 3);
        assert_eq!(
            instance.items[0].rotations,
            Rotations::Fixed(vec![0.0, 180.0])
        );
        assert_eq!(instance.items[1].rotations, Rotations::Free);
        assert!((instance.items[1].area() - 6.0).abs() < 1e-12);
        let broken = parse_instance(r#"{"Name": "old", "Items": []}"#).expect_err("no strip");
        assert!(broken.contains("Strip"), "{broken}");
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
