//! Printing that never panics: a closed stdout or stderr (a script piping into `head`, a closed
//! terminal) makes the lines go nowhere instead of panicking with exit 101 as `print!` and
//! `eprintln!` do; the command still finishes its work and returns its exit code.

use std::fmt::Arguments;
use std::io::Write;

/// Writes a line to stderr; a write error (a closed pipe) is ignored.
pub fn stderr_line(line: Arguments<'_>) {
    let mut stderr = std::io::stderr().lock();
    // Nowhere left to report a failed report: the exit code still says how the run ended.
    let _ = stderr
        .write_fmt(line)
        .and_then(|()| stderr.write_all(b"\n"));
}

/// Writes `text` to stdout and flushes it; a write error (a closed pipe) is ignored.
pub fn stdout_text(text: &str) {
    let mut stdout = std::io::stdout().lock();
    let _ = stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush());
}

/// `eprintln!` that ignores a closed stderr.
macro_rules! say {
    ($($argument:tt)*) => {
        $crate::cli::console::stderr_line(format_args!($($argument)*))
    };
}

pub(crate) use say;
