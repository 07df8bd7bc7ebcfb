//! Export: the only stage that writes files. Every file is written to a temporary name in its
//! directory and renamed, so a failure never leaves a half-written file under a final name.

pub mod atomic;
pub mod obj;
pub mod report;

pub use atomic::write_atomically;
