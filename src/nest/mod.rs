//! Nesting: place flat patterns, each in its quantity, on rectangular sheets or on a roll.
//!
//! Inputs are [`NestItem`]s (closed outlines in mm, optional holes, quantity, allowed rotations,
//! mirroring) and [`NestOptions`] (stock, gap, time limit, seed). The output is a [`NestLayout`]:
//! per sheet the [`Placement`] of every copy, and the utilisation.
//!
//! * **Sheets** (`Stock::Sheets`): as few sheets as possible, then the least used length of the
//!   last sheet. Sheets are filled from their left edge along x; the used length is measured along x.
//! * **Roll** (`Stock::Roll`): a strip whose *width* is its extent along y; the used length along x
//!   is minimised (the ESICUP strip-packing problem, where `strip_height` is the roll width).
//!
//! Collisions are detected by jagua-rs 1.1.0 behind our own trait (`CollisionEngine` in
//! `collision.rs`); the search (`search/`) is ours: a bottom-left constructive placement followed
//! by a seeded local search over the placement order and, on a roll, a compression that lets
//! parts overlap and separates them by minimising a weighted overlap measure. Every result can be checked by [`verify::verify`], an
//! independent exact f64 check that shares no code with the collision engine.
//!
//! Parts with holes are placed by their outer ring: nothing is placed inside a hole.

mod collision;
mod entry;
mod errors;
pub mod instance;
mod item;
mod layout;
mod options;
pub mod parts;
mod rotations;
mod search;
mod stock;
pub mod verify;

pub use entry::nest;
pub use errors::NestError;
pub use item::NestItem;
pub use layout::{NestLayout, Placement, SheetLayout, StopReason};
pub use options::{DEFAULT_GAP, DEFAULT_ROLL_WIDTH, DEFAULT_SEED, DEFAULT_TIME_LIMIT, NestOptions};
pub use rotations::{
    ANGLE_TOLERANCE_DEGREES, FREE_ROTATION_SAMPLES, MINIMUM_ROTATION_STEP_DEGREES, Rotations,
};
pub use stock::{MAXIMUM_STOCK_MM, Stock};
