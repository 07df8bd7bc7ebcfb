//! SIGINT and SIGTERM during a run: the run's staging folder is removed and the process ends with
//! exit code 130, leaving the output folder with the previous run. A signal that comes while the
//! run replaces the folder's files (a few renames) lets it finish, so the folder holds the new
//! run. Before a staging folder exists nothing has been written and the signal ends the process
//! the same way.

use std::sync::{Mutex, Once, PoisonError};

use flatcut::pipeline::InterruptHandle;

/// Exit code of a run ended by a signal (128 + SIGINT, as shells report Ctrl-C).
const EXIT_INTERRUPTED: i32 = 130;

/// The staging folder of the run in progress.
static CURRENT: Mutex<Option<InterruptHandle>> = Mutex::new(None);

/// The handler is installed once, for the first run.
static INSTALLED: Once = Once::new();

/// Abandons `handle`'s staging folder on SIGINT or SIGTERM from now on.
pub fn watch(handle: InterruptHandle) {
    *CURRENT.lock().unwrap_or_else(PoisonError::into_inner) = Some(handle);
    INSTALLED.call_once(|| {
        // Without a handler (the platform refused it) a signal ends the process as before; the
        // next run removes the staging folder left behind.
        let _ = ctrlc::set_handler(on_signal);
    });
}

/// Removes the staging folder and ends the process, unless the run is replacing its files.
fn on_signal() {
    let handle = CURRENT
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .clone();
    if handle.is_none_or(|handle| handle.abandon()) {
        std::process::exit(EXIT_INTERRUPTED);
    }
}
