//! A part's features: its fold lines (with their stiffness) and its regions of raised stiffness.
//! The sheet-metal and fold stages read bends from these, the flattener their stiffness.

use glam::{DVec2, DVec3};

/// Default stiffness factor of the springs near a fold line: the edges near it are this many
/// times stiffer than the rest, so the fold keeps its length when flattened.
pub const DEFAULT_FOLD_STIFFNESS: f64 = 10.0;

/// A fold line of a part.
#[derive(Debug, Clone, PartialEq)]
pub enum FoldLineGeometry {
    /// A polyline in a patch's parameter domain.
    OnSurface {
        /// Surface index.
        surface: usize,
        /// Parameter-domain points.
        points: Vec<DVec2>,
    },
    /// The edge shared by two surfaces.
    Between {
        /// The two surfaces.
        surfaces: [usize; 2],
    },
}

/// A fold line's stiffness settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoldStiffness {
    /// Factor of the springs near the line.
    pub factor: f64,
    /// Width of the band (part units), if given; default twice the mesh size.
    pub width: Option<f64>,
}

/// Where a stiffness region is.
#[derive(Debug, Clone, PartialEq)]
pub enum RegionShape {
    /// A 3D box.
    Box {
        /// Lower corner.
        min: DVec3,
        /// Upper corner.
        max: DVec3,
    },
    /// A polygon in a surface's parameter domain.
    Parameter {
        /// The surface.
        surface: usize,
        /// The polygon.
        polygon: Vec<DVec2>,
    },
}

/// A region of raised stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct StiffnessRegion {
    /// The factor.
    pub factor: f64,
    /// Where.
    pub shape: RegionShape,
}
