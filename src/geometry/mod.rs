//! Geometry shared by every stage.

mod minimum;
mod plane;
mod segment;
pub mod tolerance;
pub mod weld;

pub use minimum::golden_section_minimum;
pub use plane::{
    barycentric, bounding_box, convex_hull, crosses_ray, deep_interior_point, distance_to_box,
    inside, long_side_of_smallest_rectangle, refined_grid_search, ring_sides, signed_area,
};
pub use segment::{
    distance_to_segment, distance_to_segment_3d, polyline_prefix, segment_fraction,
    segments_intersect, segments_within,
};
