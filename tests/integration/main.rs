//! flatcut's integration tests: one binary, run against the real `flatcut` executable.

mod architecture;
mod bad_inputs;
mod batch;
mod benchmark_nest;
mod energy_png;
mod fan_in;
mod flatten;
mod golden;
mod nesting;
mod outputs;
mod pieces;
mod sheet_metal;
mod sheet_metal_bends;
mod sheet_metal_cone;
mod sheet_metal_formed;
mod smooth_cuts;
mod util;
