//! The command line: the subcommands and their dispatch.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use super::batch::{self, BatchArgs};
use super::flatten::{self, FlattenArgs};
use super::nest::{self, NestArgs};
use super::outcome::{Outcome, exit_code};
use super::progress_bar::TerminalProgress;
use super::run::{self, RunArgs};
use super::tessellate::{self, TessellateArgs};

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
    Run(RunArgs),
    /// Flatten parts and write their patterns, no nesting.
    Flatten(FlattenArgs),
    /// Nest the pattern files of runs (by material and thickness) or benchmark instances (ESICUP
    /// JSON) on sheets or a roll; writes the sheets and OUT/nest.json.
    Nest(NestArgs),
    /// Write the facet model of a part file or STEP file as OBJ.
    Tessellate(TessellateArgs),
    /// Flatten many parts (input files or a manifest), each into OUT/parts/<name>/, in
    /// parallel, resumable and shardable; writes OUT/batch.json.
    Batch(BatchArgs),
    /// One part of a batch, its task as JSON on standard input (run by `batch`).
    #[command(name = flatcut::batch::WORKER_SUBCOMMAND, hide = true)]
    BatchPart,
}

/// Parses the command line, runs the command and returns its exit code. Usage errors exit with 2
/// through clap.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let progress = TerminalProgress::new();
    // The command runs on a thread of rayon's pool: the solvers' parallel loops, called on
    // thousands of small pieces, then start where they are called instead of handing each loop
    // to the pool from outside and sleeping until it is done (that hand-over was 40 % of a
    // 20k-triangle scan cut into pieces).
    let result: anyhow::Result<Outcome> = rayon::scope(|_| match cli.command {
        Command::Run(args) => run::run(args, &progress),
        Command::Flatten(args) => flatten::run(args, &progress),
        Command::Nest(args) => nest::run(args, &progress),
        Command::Tessellate(args) => tessellate::run(args),
        Command::Batch(args) => batch::run(args),
        Command::BatchPart => batch::run_worker(),
    });
    exit_code(result)
}
