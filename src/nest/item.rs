//! One pattern to nest: its rings, quantity, allowed rotations, mirroring and grain, and the
//! poses a copy may take.

use glam::DVec2;
use serde::Serialize;

use super::rotations::{ANGLE_TOLERANCE_DEGREES, Rotations, angle_distance};
use crate::geometry::signed_area;

/// One pattern to place, `quantity` times.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NestItem {
    /// Name shown in errors and reports.
    pub name: String,
    /// Outer boundary in mm: a closed ring without a repeated last point, either orientation.
    pub outer: Vec<DVec2>,
    /// Inner boundaries (cut-outs). Kept for the report and the area; the part is placed whole by
    /// its outer ring.
    pub holes: Vec<Vec<DVec2>>,
    /// How many copies to place.
    pub quantity: u32,
    /// Allowed rotations.
    pub rotations: Rotations,
    /// The rotations a mirrored copy may take (mirrored x → −x, turned over, before its
    /// rotation); `None` when a copy is never mirrored. The same as `rotations` for `--mirror`;
    /// an instance's reflection axes can give others.
    pub mirror: Option<Rotations>,
    /// Grain direction of the material in the item's own coordinates, degrees counter-clockwise
    /// from its x axis. When set, `rotations` is ignored: a copy is only placed with its grain
    /// along the stock's x axis (the roll length, the sheet width), pointing either way, so at
    /// the two rotations that do so (and, if it may be mirrored, the two that do so for the
    /// mirrored part).
    pub grain_degrees: Option<f64>,
}

impl NestItem {
    /// The distinct (rotation in degrees in [0, 360), mirrored) poses a copy may take: with a
    /// grain, the rotations that lay the grain along x; without, every allowed rotation, and, when
    /// it may be mirrored, every allowed rotation of the mirrored part. `None` for invalid
    /// rotations or a non-finite grain.
    pub fn poses(&self) -> Option<Vec<(f64, bool)>> {
        let mut poses = Vec::new();
        for (mirrored, rotations) in self.rotation_sets() {
            let angles = match self.grain_degrees {
                Some(grain) => {
                    let along_x = -grain_after_mirror(grain, mirrored);
                    Rotations::Fixed(vec![along_x, along_x + 180.0]).angles()?
                }
                None => rotations.angles()?,
            };
            poses.extend(angles.into_iter().map(|angle| (angle, mirrored)));
        }
        Some(poses)
    }

    /// Whether every pose of a copy may be turned to any angle: free rotation, mirrored or not,
    /// and no grain.
    pub fn turns_freely(&self) -> bool {
        self.grain_degrees.is_none()
            && self
                .rotation_sets()
                .all(|(_, rotations)| *rotations == Rotations::Free)
    }

    /// The rotations of the copy as it is (`false`) and, when it may be mirrored, of the mirrored
    /// copy (`true`).
    fn rotation_sets(&self) -> impl Iterator<Item = (bool, &Rotations)> {
        std::iter::once((false, &self.rotations))
            .chain(self.mirror.as_ref().map(|mirror| (true, mirror)))
    }

    /// Whether a copy may be placed at `rotation_degrees`, mirrored or not (see
    /// [`NestItem::poses`]), within [`ANGLE_TOLERANCE_DEGREES`].
    pub fn allows(&self, rotation_degrees: f64, mirrored: bool) -> bool {
        let Some((_, rotations)) = self
            .rotation_sets()
            .find(|&(pose_mirrored, _)| pose_mirrored == mirrored)
        else {
            return false;
        };
        match self.grain_degrees {
            Some(grain) => {
                let along_x = grain_after_mirror(grain, mirrored) + rotation_degrees;
                angle_distance(along_x, 0.0) < ANGLE_TOLERANCE_DEGREES
                    || angle_distance(along_x, 180.0) < ANGLE_TOLERANCE_DEGREES
            }
            None => rotations.allows(rotation_degrees),
        }
    }

    /// Net area in mm²: outer ring minus holes.
    pub fn area(&self) -> f64 {
        let holes: f64 = self.holes.iter().map(|hole| signed_area(hole).abs()).sum();
        signed_area(&self.outer).abs() - holes
    }
}

/// The direction (degrees) of a grain at `grain` degrees after the part is mirrored (x → −x), or
/// `grain` itself when it is not.
fn grain_after_mirror(grain: f64, mirrored: bool) -> f64 {
    if mirrored { 180.0 - grain } else { grain }
}
