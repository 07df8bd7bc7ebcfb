//! Progress on stderr: an indicatif bar when stderr is a terminal, nothing otherwise; warnings on
//! stderr always.

use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressStyle};

use super::console::say;
use flatcut::progress::Progress;

/// How often a spinner (a stage of unknown length: reading, tessellating) turns.
const SPINNER_TICK: Duration = Duration::from_millis(120);

/// A progress bar on stderr, silent when stderr is not a terminal (scripts, CI, pipes).
pub struct TerminalProgress {
    /// The bar and the name of its stage.
    bar: Mutex<Option<(ProgressBar, String)>>,
    enabled: bool,
}

impl TerminalProgress {
    /// A reporter that draws only if stderr is a terminal.
    pub fn new() -> Self {
        Self {
            bar: Mutex::new(None),
            enabled: std::io::stderr().is_terminal(),
        }
    }
}

impl Progress for TerminalProgress {
    fn start(&self, stage: &str, total: u64) {
        if !self.enabled {
            return;
        }
        let bar = if total > 0 {
            ProgressBar::new(total)
        } else {
            ProgressBar::new_spinner()
        };
        let template = if total > 0 {
            "{msg} [{bar:30}] {pos}/{len} {elapsed_precise}, about {eta} left"
        } else {
            "{msg} {spinner} {elapsed_precise}"
        };
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(stage.to_string());
        if total == 0 {
            bar.enable_steady_tick(SPINNER_TICK);
        }
        let mut slot = self
            .bar
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        *slot = Some((bar, stage.to_string()));
    }

    fn advance(&self, done: u64) {
        if let Some(bar) = self
            .bar
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .as_ref()
        {
            bar.0.set_position(done);
        }
    }

    fn finish(&self) {
        if let Some(bar) = self
            .bar
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .take()
        {
            bar.0.finish_and_clear();
        }
    }

    /// Prints `flatcut: warning: MESSAGE` on stderr, above the bar if one is drawn.
    fn warn(&self, message: &str) {
        let line = format!("flatcut: warning: {message}");
        match self
            .bar
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .as_ref()
        {
            Some(bar) => bar.0.suspend(|| say!("{line}")),
            None => say!("{line}"),
        }
    }

    /// Shows `STAGE (STATUS)` as the bar's message.
    fn status(&self, status: &str) {
        if let Some((bar, stage)) = self
            .bar
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .as_ref()
        {
            bar.set_message(format!("{stage} ({status})"));
        }
    }
}
