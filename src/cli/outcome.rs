//! How a command ended, as an exit code: 0 success, 1 bad input or failure, 3 a part rejected
//! (2, bad usage, is clap's). Errors are printed with their causes.

use super::console::say;
use std::process::ExitCode;

/// Exit code when every part finished within tolerance.
const EXIT_SUCCESS: u8 = 0;
/// Exit code for bad input or a runtime failure.
const EXIT_FAILURE: u8 = 1;
/// Exit code when the run finished but a part is rejected: over tolerance, flipped triangles or
/// overlap (outputs are still written, its cut file as `<part>.REJECTED.dxf`).
const EXIT_OVER_TOLERANCE: u8 = 3;

/// How a successful command ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Everything within tolerance.
    Success,
    /// Finished, outputs written, but at least one part is rejected.
    OverTolerance,
    /// Finished with this exit code, the reason already printed (a batch: its worst part's
    /// code, or 130 when stopped by a signal).
    Exit(u8),
}

/// The exit code of a command's result; an error is printed to stderr first.
pub fn exit_code(result: anyhow::Result<Outcome>) -> ExitCode {
    match result {
        Ok(Outcome::Success) => ExitCode::from(EXIT_SUCCESS),
        Ok(Outcome::OverTolerance) => ExitCode::from(EXIT_OVER_TOLERANCE),
        Ok(Outcome::Exit(code)) => ExitCode::from(code),
        Err(error) => {
            say!("flatcut: error: {}", error_message(&error));
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
