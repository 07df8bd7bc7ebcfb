//! Named tolerances of the reading and meshing stages, each with what it bounds. Ratios are
//! relative to the length named in their documentation; plain tolerances are in the unit named.

/// A triangle whose area is below this fraction of its longest edge squared is degenerate: its
/// height is under a millionth of its length, too thin for a meaningful flat shape (the mesh
/// check refuses it).
pub const DEGENERATE_AREA_RATIO: f64 = 1e-12;

/// A triangle whose area is below this fraction of its longest edge squared is a rounding sliver
/// of a mesher (along a trim loop, between nearly coplanar rulings) and is dropped.
pub const SLIVER_AREA_RATIO: f64 = 1e-10;

/// Corners of STL triangles closer than this fraction of the bounding-box diagonal are welded.
pub const STL_WELD_TOLERANCE: f64 = 1e-9;

/// Vertices of different tessellated faces closer than this fraction of the part's bounding
/// diagonal are welded.
pub const WELD_TOLERANCE_RATIO: f64 = 1e-7;

/// Boundary vertices of a STEP face within this fraction of the face's domain size of a
/// boundary sample are that sample.
pub const SNAP_RATIO: f64 = 1e-9;

/// A mesh vertex within this fraction of the mesh size (in the meshing domain) of a fold
/// polyline is on it.
pub const ON_POLYLINE_RATIO: f64 = 1e-7;

/// Stations along a profile or a section closer than this (fraction of the stretch) to each
/// other or to an end are one.
pub const STATION_TOLERANCE: f64 = 1e-9;

/// A parameter-domain point this close to a stiffness region's boundary, as a fraction of the
/// largest coordinate of the region (plus one), is inside it.
pub const BOUNDARY_TOLERANCE: f64 = 1e-9;

/// A profile point of a surface of revolution closer to the axis than this fraction of the mesh
/// size is on the axis (a pole).
pub const POLE_TOLERANCE_RATIO: f64 = 1e-9;

/// A chord between two rulings of a cone fan's row may be shorter than its development by at
/// most this fraction of the mesh size.
pub const FAN_TOLERANCE_RATIO: f64 = 1e-4;

/// Two edge directions of a loft's sections closer than this (radians) are parallel: both
/// sections advance together.
pub const PARALLEL_ANGLE_TOLERANCE: f64 = 1e-9;

/// Relative tolerance of a part file's geometric checks (planarity, arc end points), as a
/// fraction of the feature's size.
pub const GEOMETRY_TOLERANCE: f64 = 1e-6;
