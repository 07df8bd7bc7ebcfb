//! Named tolerances of the reading and meshing stages, each with what it bounds. Ratios are
//! relative to the length named in their documentation; plain tolerances are in the unit named.

/// A triangle whose area is below this fraction of its longest edge squared is degenerate: its
/// height is under a millionth of its length, too thin for a meaningful flat shape (the mesh check
/// refuses it).
pub const DEGENERATE_AREA_RATIO: f64 = 1e-12;

/// True when the triangle with these corners is degenerate: its area is at most
/// [`DEGENERATE_AREA_RATIO`] times its longest edge squared (or not a number).
pub fn has_zero_area([a, b, c]: [glam::DVec3; 3]) -> bool {
    let area = 0.5 * (b - a).cross(c - a).length();
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    area.is_nan() || area <= DEGENERATE_AREA_RATIO * longest
}

/// A triangle whose area is below this fraction of its longest edge squared is a rounding sliver of
/// a mesher (along a trim loop, between nearly coplanar rulings) and is dropped.
pub const SLIVER_AREA_RATIO: f64 = 1e-10;

/// Corners of STL triangles closer than this fraction of the bounding-box diagonal are welded.
pub const STL_WELD_TOLERANCE: f64 = 1e-9;

/// Vertices of a mesh closer than this fraction of its bounding-box diagonal are at the same point
/// to the triangle-soup check and to `--repair`'s weld: an unwelded export carries rounding noise
/// (a file written from single precision, or with a few decimals, or each corner recomputed).
pub const MESH_WELD_RATIO: f64 = 1e-7;

/// Vertices of different tessellated faces closer than this fraction of the part's bounding
/// diagonal are welded.
pub const WELD_TOLERANCE_RATIO: f64 = 1e-7;

/// Boundary vertices of a STEP face within this fraction of the face's domain size of a boundary
/// sample are that sample.
pub const SNAP_RATIO: f64 = 1e-9;

/// STEP faces mapped in polar coordinates about a pole: a domain coordinate of a boundary point
/// whose magnitude is below this fraction of its loop's extent is round-off of zero (a meridian
/// on an axis) and is zero.
pub const ROUND_OFF_RATIO: f64 = 1e-13;

/// A mesh vertex within this fraction of the mesh size (in the meshing domain) of a fold polyline
/// is on it.
pub const ON_POLYLINE_RATIO: f64 = 1e-7;

/// Stations along a profile or a section closer than this (fraction of the stretch) to each other
/// or to an end are one.
pub const STATION_TOLERANCE: f64 = 1e-9;

/// A parameter-domain point this close to a stiffness region's boundary, as a fraction of the
/// largest coordinate of the region (plus one), is inside it.
pub const BOUNDARY_TOLERANCE: f64 = 1e-9;

/// A profile point of a surface of revolution closer to the axis than this fraction of the mesh
/// size is on the axis (a pole).
pub const POLE_TOLERANCE_RATIO: f64 = 1e-9;

/// A chord between two rulings of a cone fan's row may be shorter than its development by at most
/// this fraction of the mesh size.
pub const FAN_TOLERANCE_RATIO: f64 = 1e-4;

/// Two edge directions of a loft's sections closer than this (radians) are parallel: both sections
/// advance together.
pub const PARALLEL_ANGLE_TOLERANCE: f64 = 1e-9;

/// Relative tolerance of a part file's geometric checks (planarity, arc end points), as a fraction
/// of the feature's size.
pub const GEOMETRY_TOLERANCE: f64 = 1e-6;

/// Part-file surface domains: a domain point closer than this (degrees, or part units) to the
/// domain's edge is on it.
pub const DOMAIN_EDGE_TOLERANCE: f64 = 1e-9;

/// Part-file surface domains: a point this close to the axis (fraction of the profile's length) is
/// a pole.
pub const DOMAIN_POLE_RATIO: f64 = 1e-9;

/// Part-file trim loops: loops closer than this fraction of the outer loop's size touch.
pub const LOOP_TOLERANCE: f64 = 1e-6;

/// Planar pieces of ruled surfaces: two consecutive section edges whose directions differ by less
/// than this (sine) are one side.
pub const COLLINEAR_TOLERANCE: f64 = 1e-9;

/// Planar pieces of ruled surfaces: relative margin on the longest side of a planar piece, so that
/// the patch mesher splits none.
pub const PLANE_SIDE_MARGIN: f64 = 1e-6;

/// Planar pieces of ruled surfaces: a patch vertex this close to a boundary corner (fraction of the
/// longest side) is that corner.
pub const PLANE_MATCH_RATIO: f64 = 1e-9;

/// Ruled surfaces: two wedge normals closer than this (sine of the angle) are parallel.
pub const COPLANAR_TOLERANCE: f64 = 1e-9;

/// STEP faces: a boundary point where the parallel's radius `|∂S/∂θ|` is below this fraction of the
/// face's size is a pole.
pub const STEP_POLE_RATIO: f64 = 1e-7;

/// Fold polylines on rulings: two points closer than this fraction of the mesh size are one point.
pub const SAME_POINT_RATIO: f64 = 1e-7;

/// STEP faces: a boundary point farther than this fraction of the face's size from its inverted
/// surface point means the inversion failed.
pub const INVERSION_TOLERANCE_RATIO: f64 = 1e-5;

/// STEP faces: a boundary point whose inversion lands farther than the inversion tolerance but is
/// a foot point (the point lies along the surface's normal) at most this fraction of the part's
/// size away is on the surface: exporters write edges off their faces within their own modelling
/// tolerance (Open CASCADE's IDF models: cylinder edges up to 3.6e-4 of the part's size off,
/// ten times the file's declared uncertainty). The mesh's boundary vertices stay on the edges, so
/// its triangles there lean by at most this much.
pub const BOUNDARY_DEVIATION_RATIO: f64 = 1e-3;

/// STEP faces: a boundary point's inversion is a foot point when the residual's cosine with each
/// surface tangent is at most this.
pub const FOOT_POINT_COSINE: f64 = 1e-3;

/// STEP faces: relative spread of a parameter along an edge below which the edge lies on an
/// iso-parameter line (a seam, a circle of a cone, a B-spline patch's side); its points then get
/// exactly the same parameter, so the loop is straight there and the mesher makes no sliver along
/// it.
pub const ISO_LINE_RATIO: f64 = 1e-7;

/// Fold polylines on a face mesh: a point whose smallest barycentric coordinate is above minus this
/// is inside a triangle.
pub const INSIDE_TOLERANCE: f64 = 1e-9;

/// Fold polylines on a face mesh: a barycentric coordinate above one minus this puts a point on
/// that corner.
pub const CORNER_TOLERANCE: f64 = 1e-9;

/// Cone fans: fold rows closer than this (fraction of the rulings) are one row.
pub const FOLD_ROW_TOLERANCE: f64 = 1e-9;

/// STEP faces: a cone whose radius changes less than this per unit of ruling length is a cylinder.
pub const CYLINDER_SLOPE: f64 = 1e-9;

/// STEP faces: relative change of a surface of revolution's parallel radius and meridian speed
/// along a parallel below which the angular parameter is the angle about its axis.
pub const REVOLUTION_TOLERANCE: f64 = 1e-9;

/// STEP faces: a polar map's `c` within this of 1 is a smooth pole (`c = 1`).
pub const SMOOTH_POLE_TOLERANCE: f64 = 1e-3;

/// Part-file sections: a polygon whose edge directions turn through a full turn within this
/// (radians) winds once.
pub const TURNING_TOLERANCE: f64 = 1e-6;

/// STEP faces: consecutive edges of a boundary loop whose ends are closer than this fraction of
/// the part's size meet (a larger gap is an open loop).
pub const LOOP_GAP_RATIO: f64 = 1e-6;

/// Fold polylines on rulings: a domain `u` within this fraction of `1 + |u|` of a ruling's is on
/// that ruling.
pub const SAME_STATION_RATIO: f64 = 1e-12;

/// STEP edges: edge pieces shorter than this fraction of the part's size are degenerate and do
/// not set the shortest piece at a vertex.
pub const DEGENERATE_PIECE_RATIO: f64 = 1e-9;

/// STEP edges: a vertex within this fraction of the mesh size of its curve's end is that end.
pub const EDGE_END_RATIO: f64 = 1e-6;
