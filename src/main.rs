//! The `flatcut` command: parse the arguments, convert them to library options, run, and map the
//! outcome to an exit code (0 success, 1 bad input or failure, 2 bad usage, 3 over tolerance).

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
