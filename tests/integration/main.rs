//! flatcut's integration tests: one binary, run against the real `flatcut` executable.

mod bad_inputs;
mod flatten;
mod golden;
mod util;
