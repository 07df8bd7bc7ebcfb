//! Options of nesting and their defaults.

use std::time::Duration;

use serde::Serialize;

use super::stock::Stock;

/// Default gap between parts and to the stock edge, in mm. Zero: the CAM adds the kerf.
pub const DEFAULT_GAP: f64 = 0.0;
/// Default search budget (see [`NestOptions::time_limit`]).
pub const DEFAULT_TIME_LIMIT: Duration = Duration::from_secs(60);
/// Default seed of the search.
pub const DEFAULT_SEED: u64 = 0;
/// Default roll width when none is given, mm.
pub const DEFAULT_ROLL_WIDTH: f64 = 1000.0;

/// Options of [`nest`](crate::nest::nest). [`Default`] is the only source of defaults.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NestOptions {
    /// Sheets or roll. Default: a roll 1000 mm wide ([`DEFAULT_ROLL_WIDTH`]).
    pub stock: Stock,
    /// Minimum distance between two parts and between a part and the stock edge, mm.
    /// Default [`DEFAULT_GAP`].
    pub gap: f64,
    /// Search budget. The search counts its work in collision queries and stops after
    /// `time_limit × NOMINAL_QUERIES_PER_SECOND` of them (a deterministic budget), or when this much
    /// wall-clock time has passed, whichever comes first. Default [`DEFAULT_TIME_LIMIT`].
    pub time_limit: Duration,
    /// Seed of the search's random choices. Default [`DEFAULT_SEED`].
    pub seed: u64,
    /// Work budget in collision queries, replacing `time_limit × NOMINAL_QUERIES_PER_SECOND`
    /// (the wall-clock `time_limit` still applies). Default `None`.
    pub work_limit: Option<u64>,
    /// Place small parts inside the holes of larger ones (before the search, see
    /// `search::holes`). Default `false`: a part with holes is placed as a solid.
    pub in_holes: bool,
}

impl Default for NestOptions {
    fn default() -> Self {
        Self {
            stock: Stock::Roll {
                width: DEFAULT_ROLL_WIDTH,
            },
            gap: DEFAULT_GAP,
            time_limit: DEFAULT_TIME_LIMIT,
            seed: DEFAULT_SEED,
            work_limit: None,
            in_holes: false,
        }
    }
}
