//! Command-line interface: argument conversion and printing only. One module per subcommand,
//! each with its clap arguments and a `run` function that converts them into library options in
//! one place and calls the library; [`main`] parses and dispatches, and maps the outcome to an
//! exit code.

mod batch;
mod command;
mod console;
mod flatten;
mod interrupt;
mod job;
mod nest;
mod outcome;
mod parse;
mod progress_bar;
mod run;
mod tessellate;

pub use command::main;
