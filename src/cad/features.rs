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

/// Which face of the sheet a part's surfaces are at a bend: the fold's edge is then that face's
/// virtual sharp (where its two flanges' planes meet).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SheetSide {
    /// The inner face of the bend (setback `R · tan(θ/2)`).
    Inside,
    /// The mid-surface of the sheet (setback `(R + t/2) · tan(θ/2)`). The default.
    #[default]
    Mid,
    /// The outer face of the bend (setback `(R + t) · tan(θ/2)`).
    Outside,
}

impl SheetSide {
    /// The side's distance from the inner face, as a fraction of the thickness (0, 1/2, 1).
    pub fn depth(self) -> f64 {
        match self {
            Self::Inside => 0.0,
            Self::Mid => 0.5,
            Self::Outside => 1.0,
        }
    }
}

/// A fold of a part file made with a bend radius: a bend of the sheet, unfolded with an
/// allowance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoldBend {
    /// Inner bend radius (part units).
    pub inner_radius: f64,
    /// Which face of the sheet the part's surfaces are.
    pub side: SheetSide,
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
