//! Placement of local coordinates in a part: a right-handed orthonormal frame.

use glam::DVec3;

/// A right-handed orthonormal frame: where local coordinates live in the part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Origin.
    pub origin: DVec3,
    /// Local x axis (unit).
    pub x: DVec3,
    /// Local y axis (unit).
    pub y: DVec3,
    /// Local z axis (unit).
    pub z: DVec3,
}

impl Frame {
    /// The world frame.
    pub const WORLD: Frame = Frame {
        origin: DVec3::ZERO,
        x: DVec3::X,
        y: DVec3::Y,
        z: DVec3::Z,
    };

    /// A frame from an origin, a z axis and a reference for x (made perpendicular to z). `None`
    /// when the axis is zero or the reference is parallel to it.
    pub fn new(origin: DVec3, axis: DVec3, reference: DVec3) -> Option<Frame> {
        let z = axis.try_normalize()?;
        let x = (reference - z * reference.dot(z)).try_normalize()?;
        Some(Frame {
            origin,
            x,
            y: z.cross(x),
            z,
        })
    }

    /// The world position of local coordinates.
    pub fn point(&self, local: DVec3) -> DVec3 {
        self.origin + self.x * local.x + self.y * local.y + self.z * local.z
    }

    /// The world direction of a local vector.
    pub fn vector(&self, local: DVec3) -> DVec3 {
        self.x * local.x + self.y * local.y + self.z * local.z
    }
}
