//! Progress reporting from long stages, decoupled from any terminal: the library reports through
//! the [`Progress`] trait (progress and warnings) and the binary decides how (a bar on a terminal,
//! nothing otherwise; warnings on stderr).

/// Receives progress from a long stage. Implementations must be cheap: stages call
/// [`Progress::advance`] often.
pub trait Progress: Sync {
    /// A new stage starts, with `total` units of work (0 if unknown).
    fn start(&self, stage: &str, total: u64);
    /// `done` units of the current stage are complete (absolute, not a delta).
    fn advance(&self, done: u64);
    /// The current stage is over.
    fn finish(&self);
    /// Something the user should know that does not stop the run (a repair made to an input, a
    /// slow option), as one line without a prefix. Ignored by default.
    fn warn(&self, _message: &str) {}
    /// A short status of the current stage that replaces the previous one (the nesting's best
    /// density so far), shown beside the stage's name. Ignored by default.
    fn status(&self, _status: &str) {}
}

/// Progress that goes nowhere: for tests, scripts and library users who do not care.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn start(&self, _stage: &str, _total: u64) {}
    fn advance(&self, _done: u64) {}
    fn finish(&self) {}
}

/// When a long computation must stop: a part's time limit as an instant, checked by the solvers
/// between iterations and by the cut loop between steps. A stage that stops there says so
/// ([`crate::flatten::StopReason::TimeLimit`], [`crate::cut::CutStop::TimeLimit`]) and returns
/// what it has. The default has no limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Deadline(Option<std::time::Instant>);

impl Deadline {
    /// No limit.
    pub const NONE: Self = Self(None);

    /// `limit` from now.
    pub fn after(limit: std::time::Duration) -> Self {
        Self(std::time::Instant::now().checked_add(limit))
    }

    /// Whether the limit has passed.
    pub fn passed(&self) -> bool {
        self.0
            .is_some_and(|instant| std::time::Instant::now() >= instant)
    }
}
