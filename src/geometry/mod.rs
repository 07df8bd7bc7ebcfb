//! Geometry shared by every stage.

mod plane;
pub mod tolerance;
pub mod weld;

pub use plane::{
    convex_hull, deep_interior_point, distance_to_segment, inside, long_side_of_smallest_rectangle,
    signed_area,
};
