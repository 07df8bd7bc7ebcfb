//! Command-line interface: one module per subcommand, each with its clap arguments and a `run`
//! function that converts them into library options in one place and calls the library.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod flatten;
mod nest;
mod progress_bar;
mod run;
mod tessellate;

/// Exit code when every part finished within tolerance.
const EXIT_SUCCESS: u8 = 0;
/// Exit code for bad input or a runtime failure.
const EXIT_FAILURE: u8 = 1;
/// Exit code when the run finished but a part is over tolerance (outputs are still written).
const EXIT_OVER_TOLERANCE: u8 = 3;

/// flatcut: flat cut patterns from 3D surfaces (spring-mass energy model, Wang et al. 2002).
#[derive(Debug, Parser)]
#[command(name = "flatcut", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// The whole pipeline: flatten every part and write its files and the report.
    Run(run::RunArgs),
    /// Flatten parts and write their patterns, no nesting.
    Flatten(flatten::FlattenArgs),
    /// Nest parts or a benchmark instance (ESICUP JSON) on sheets or a roll; writes OUT/nest.json.
    Nest(nest::NestArgs),
    /// Write the facet model of a part file or STEP file as OBJ.
    Tessellate(tessellate::TessellateArgs),
}

/// How a successful command ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Everything within tolerance.
    Success,
    /// Finished, outputs written, but at least one part is over tolerance.
    OverTolerance,
}

/// Parses the command line, runs the command and returns its exit code. Usage errors exit with 2
/// through clap.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let progress = progress_bar::TerminalProgress::new();
    let result: anyhow::Result<Outcome> = match cli.command {
        Command::Run(args) => run::run(args, &progress),
        Command::Flatten(args) => flatten::run(args, None, &progress),
        Command::Nest(args) => nest::run(args, &progress),
        Command::Tessellate(args) => tessellate::run(args),
    };
    match result {
        Ok(Outcome::Success) => ExitCode::from(EXIT_SUCCESS),
        Ok(Outcome::OverTolerance) => ExitCode::from(EXIT_OVER_TOLERANCE),
        Err(error) => {
            eprintln!("flatcut: error: {}", error_message(&error));
            ExitCode::from(EXIT_FAILURE)
        }
    }
}

/// The error and its causes, joined by `: `, leaving out a cause whose text the message already
/// holds (library errors print their reason and also report it as their source).
fn error_message(error: &anyhow::Error) -> String {
    let mut message = error.to_string();
    for cause in error.chain().skip(1) {
        let text = cause.to_string();
        if !message.contains(&text) {
            message.push_str(": ");
            message.push_str(&text);
        }
    }
    message
}
