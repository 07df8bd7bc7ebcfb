//! The part file's external (serde) types: exactly what a TOML part file may say, converted once
//! into geometry by [`super::build`]. Every table denies unknown fields, so a misspelt field is an
//! error with its line and column. Lengths are in the part's `units`, angles in degrees.
//! The format is documented field by field in `docs/part-format.md`.

use serde::Deserialize;
use toml::Spanned;

use crate::units::Units;

/// A whole part file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PartSpec {
    /// Part name; default the file stem.
    pub name: Option<String>,
    /// Units of every length in the file; default millimetres.
    #[serde(default)]
    pub units: Units,
    /// Copies to cut; default 1.
    #[serde(default = "one")]
    pub quantity: u32,
    /// Material, carried to the outputs.
    pub material: Option<String>,
    /// Sheet thickness, carried to the outputs.
    pub thickness: Option<Spanned<f64>>,
    /// Grain direction as a 3D vector on the part.
    pub grain: Option<[f64; 3]>,
    /// Whether surfaces sharing an edge are welded into one part (`weld`, the default) or each
    /// surface is a part of its own (`separate`).
    #[serde(default)]
    pub join: Join,
    /// The surfaces, at least one.
    #[serde(default, rename = "surface")]
    pub surfaces: Vec<Spanned<SurfaceSpec>>,
    /// Fold lines.
    #[serde(default, rename = "fold_line")]
    pub fold_lines: Vec<Spanned<FoldLineSpec>>,
    /// Regions of raised stiffness.
    #[serde(default, rename = "stiffness_region")]
    pub stiffness_regions: Vec<Spanned<RegionSpec>>,
}

fn one() -> u32 {
    1
}

/// How the surfaces of a part are joined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Join {
    /// Surfaces sharing an edge become one part.
    #[default]
    Weld,
    /// Each surface is a part of its own (the pieces of an elbow).
    Separate,
}

/// A placement: the local frame a surface of revolution or a cone is built in.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlacementSpec {
    /// Origin of the local frame; default `[0, 0, 0]`.
    #[serde(default)]
    pub origin: [f64; 3],
    /// Local z axis (the axis of revolution); default `[0, 0, 1]`.
    #[serde(default = "z_axis")]
    pub axis: [f64; 3],
    /// Local x axis (angle 0), made perpendicular to `axis`; default `[1, 0, 0]` (or `[0, 1, 0]`
    /// when the axis is along x).
    pub reference: Option<[f64; 3]>,
}

impl Default for PlacementSpec {
    fn default() -> Self {
        Self {
            origin: [0.0; 3],
            axis: z_axis(),
            reference: None,
        }
    }
}

fn z_axis() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}

fn full_turn() -> [f64; 2] {
    [0.0, 360.0]
}

/// One surface, selected by its `kind`.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SurfaceSpec {
    /// A planar polygon with optional holes.
    Polygon(PolygonSpec),
    /// A cylinder segment, optionally with mitred (tilted) ends.
    Cylinder(CylinderSpec),
    /// A cone frustum, optionally eccentric (oblique).
    Cone(ConeSpec),
    /// A surface of revolution from a profile of lines and arcs.
    Revolution(RevolutionSpec),
    /// A B-spline or NURBS patch from a control grid.
    Bspline(BsplineSpec),
    /// A ruled loft between two convex sections in parallel planes.
    Loft(LoftSpec),
    /// An extrusion (sweep along a line) of an open or closed profile.
    Extrusion(ExtrusionSpec),
}

/// A planar polygon.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolygonSpec {
    /// Outer boundary, 3D points on one plane, at least three.
    pub points: Vec<[f64; 3]>,
    /// Holes, each a loop of 3D points on the same plane.
    #[serde(default)]
    pub holes: Vec<Vec<[f64; 3]>>,
}

/// A cylinder segment around the placement's axis.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CylinderSpec {
    /// Radius (> 0).
    pub radius: f64,
    /// Height of the top end's centre on the axis (> 0).
    pub height: f64,
    /// Angular range in degrees, default `[0, 360]` (a full turn is opened along a seam at the
    /// start angle).
    #[serde(default = "full_turn")]
    pub angles: [f64; 2],
    /// Tilt of the bottom end plane about the local y axis, degrees (a mitre); default 0.
    #[serde(default)]
    pub bottom_cut: f64,
    /// Tilt of the top end plane about the local y axis, degrees (a mitre); default 0.
    #[serde(default)]
    pub top_cut: f64,
    /// Local frame; default the world frame.
    #[serde(default)]
    pub placement: PlacementSpec,
}

/// A cone frustum between two parallel circles.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConeSpec {
    /// Radius at the bottom (z = 0), > 0.
    pub bottom_radius: f64,
    /// Radius at the top (z = height), > 0.
    pub top_radius: f64,
    /// Distance between the two circle planes (> 0).
    pub height: f64,
    /// Offset of the top centre in the local x, y (an oblique, eccentric frustum); default `[0, 0]`.
    #[serde(default)]
    pub top_offset: [f64; 2],
    /// Angular range in degrees, default `[0, 360]`.
    #[serde(default = "full_turn")]
    pub angles: [f64; 2],
    /// Local frame; default the world frame.
    #[serde(default)]
    pub placement: PlacementSpec,
}

/// A surface of revolution.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RevolutionSpec {
    /// First profile point `[radius, z]` in the local frame.
    pub start: [f64; 2],
    /// Profile segments, each a line or an arc to its end point.
    pub profile: Vec<ProfileSegmentSpec>,
    /// Angular range in degrees, default `[0, 360]`.
    #[serde(default = "full_turn")]
    pub angles: [f64; 2],
    /// Local frame; default the world frame.
    #[serde(default)]
    pub placement: PlacementSpec,
}

/// One profile segment: a line to `to`, or a circular arc to `to` around `center`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileSegmentSpec {
    /// End point `[radius, z]` (or `[x, y]` for an extrusion profile).
    pub to: [f64; 2],
    /// Centre of an arc; the arc turns the short way unless `clockwise` says otherwise.
    pub center: Option<[f64; 2]>,
    /// For an arc: true to turn clockwise, false counter-clockwise; default the shorter way.
    pub clockwise: Option<bool>,
}

/// A B-spline or NURBS patch.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BsplineSpec {
    /// Degrees in u and v (each ≥ 1).
    pub degree: [usize; 2],
    /// Control grid: rows along u, each row a list of points along v; all rows the same length.
    pub control_points: Vec<Vec<[f64; 3]>>,
    /// Knot vector in u; default clamped uniform on [0, 1].
    pub knots_u: Option<Vec<f64>>,
    /// Knot vector in v; default clamped uniform on [0, 1].
    pub knots_v: Option<Vec<f64>>,
    /// Weights, one per control point (a NURBS patch); default all 1.
    pub weights: Option<Vec<Vec<f64>>>,
    /// Trim loops in the parameter domain.
    pub trim: Option<TrimSpec>,
}

/// Trim loops in a patch's parameter domain `(u, v)`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrimSpec {
    /// Outer boundary (a cut-off corner, for instance); default the whole domain rectangle.
    pub outer: Option<Vec<[f64; 2]>>,
    /// Holes.
    #[serde(default)]
    pub holes: Vec<Vec<[f64; 2]>>,
}

/// A ruled loft between two convex sections in parallel planes.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoftSpec {
    /// Bottom section.
    pub bottom: SectionSpec,
    /// Top section.
    pub top: SectionSpec,
    /// Direction (degrees, in the local x-y plane) of the tangent at which the closed loft is
    /// opened along a ruling; default 0.
    #[serde(default)]
    pub seam: f64,
    /// Local frame; default the world frame.
    #[serde(default)]
    pub placement: PlacementSpec,
}

/// A convex closed section in a plane `z = const` of the local frame.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// `circle`, `rectangle` or `polygon`.
    pub shape: SectionShape,
    /// Height of the section's plane.
    #[serde(default)]
    pub z: f64,
    /// Centre in the local x, y; default `[0, 0]`.
    #[serde(default)]
    pub center: [f64; 2],
    /// Circle diameter.
    pub diameter: Option<f64>,
    /// Rectangle width (along x).
    pub width: Option<f64>,
    /// Rectangle depth (along y).
    pub depth: Option<f64>,
    /// Convex polygon corners `[x, y]`, counter-clockwise, relative to `center`.
    pub points: Option<Vec<[f64; 2]>>,
}

/// The shape of a loft section.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SectionShape {
    /// A circle of `diameter`.
    Circle,
    /// A rectangle of `width` × `depth`.
    Rectangle,
    /// A convex polygon of `points`.
    Polygon,
}

/// An extrusion of a profile along a straight direction.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtrusionSpec {
    /// First profile point `[x, y]` in the local x-y plane.
    pub start: [f64; 2],
    /// Profile segments (lines and arcs).
    pub profile: Vec<ProfileSegmentSpec>,
    /// Extrusion vector in the local frame (need not be along z: an oblique sweep).
    pub direction: [f64; 3],
    /// Local frame; default the world frame.
    #[serde(default)]
    pub placement: PlacementSpec,
}

/// A fold line: a polyline in one surface's parameter domain, or the edge two surfaces share.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FoldLineSpec {
    /// The surface (0-based, in file order) whose parameter domain `points` are in.
    pub surface: Option<usize>,
    /// Polyline in that surface's parameter domain (polygon: plane coordinates; patch: `(u, v)`).
    pub points: Option<Vec<[f64; 2]>>,
    /// The two surfaces whose shared edge is the fold line.
    pub between: Option<[usize; 2]>,
    /// Stiffness factor of the springs within `width`; default 10.
    pub factor: Option<f64>,
    /// Width of the band of raised stiffness (part units); default twice the mesh size.
    pub width: Option<f64>,
    /// Inner bend radius (part units): the fold is a bend of the sheet, unfolded with an
    /// allowance (needs `between` two polygons and the part's `thickness`).
    pub bend_radius: Option<f64>,
    /// Which face of the sheet the surfaces are at this bend; default `mid`.
    pub side: Option<SheetSideSpec>,
}

/// Which face of the sheet a part's surfaces are at a bend.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SheetSideSpec {
    /// The inner face of the bend.
    Inside,
    /// The mid-surface.
    Mid,
    /// The outer face of the bend.
    Outside,
}

/// A region of raised stiffness: a 3D box, or a polygon in one surface's parameter domain.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    /// Stiffness factor (> 0).
    pub factor: f64,
    /// Lower corner of a 3D box.
    pub box_min: Option<[f64; 3]>,
    /// Upper corner of a 3D box.
    pub box_max: Option<[f64; 3]>,
    /// Surface whose parameter domain `polygon` is in.
    pub surface: Option<usize>,
    /// Polygon in the parameter domain.
    pub polygon: Option<Vec<[f64; 2]>>,
    /// Box in the parameter domain: `[u_min, v_min, u_max, v_max]`.
    pub parameter_box: Option<[f64; 4]>,
}
