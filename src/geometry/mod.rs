//! Geometry shared by every stage.

mod plane;
mod segment;
pub mod tolerance;
pub mod weld;

pub use plane::{
    bounding_box, convex_hull, deep_interior_point, inside, long_side_of_smallest_rectangle,
    signed_area,
};
pub use segment::{distance_to_segment, distance_to_segment_3d};
