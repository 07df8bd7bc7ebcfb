//! The placement search: what goes where, using a
//! [`CollisionEngine`](super::collision::CollisionEngine) for every feasibility test.
//!
//! 1. **Constructive bottom-left placement.** Copies are taken in a sequence (initially by
//!    decreasing area). Each copy goes to the first sheet where it fits (always the one roll), at
//!    the position that minimises its right edge, then its bottom edge. Per allowed orientation:
//!    [`SAMPLES_PER_ORIENTATION`](placement::SAMPLES_PER_ORIENTATION) seeded uniform samples (shared among the orientations of
//!    a copy with more than [`SAMPLED_ORIENTATIONS`](placement::SAMPLED_ORIENTATIONS)) left of the current front (right of the
//!    front everything fits, so the front itself, at the bottom and at the top, is the fallback);
//!    the [`COMPACTED_CANDIDATES`](placement::COMPACTED_CANDIDATES) fitting samples with the lowest right edge are slid left and down
//!    (steps, then bisection) until they touch.
//! 2. **Local search over the sequence.** Each round draws [`NEIGHBOURS_PER_ROUND`](moves::NEIGHBOURS_PER_ROUND) moves (swap two
//!    copies of different items, or move one copy earlier) from a seeded splitmix64 generator,
//!    re-places every copy from the first changed position (the prefix is kept), and evaluates the
//!    neighbours in parallel (rayon), each with its own seed.
//!    * On a **roll**, the search works by *strip shrinking*: whenever a layout holds every copy,
//!      it becomes the best and the roll is cut [`SHRINK_FRACTION`](local_search::SHRINK_FRACTION) shorter than it; copies that
//!      no longer fit are left out, and the search minimises the area left out (ties accepted)
//!      until a sequence fits everything again.
//!    * On **sheets**, the search minimises (sheets used, length used on the last sheet) with
//!      threshold accepting: a neighbour up to [`ACCEPTANCE_THRESHOLD`](local_search::ACCEPTANCE_THRESHOLD) longer is accepted at the
//!      start, falling linearly to zero.
//!
//! 3. **Search through overlap on a roll (`separator`, `compression`).** The sequence search gets
//!    [`SEQUENCE_SEARCH_SHARE`](local_search::SEQUENCE_SEARCH_SHARE) of the budget; the rest cuts
//!    the best layout's strip shorter at a random split (the parts right of it move left, into
//!    overlap) and separates them by guided local search on the pole-based overlap measure of the
//!    collision engine: each colliding part moves to the sampled, then coordinate-descent-refined,
//!    position of least weighted overlap, the weights of pairs that keep colliding grow and the
//!    others decay, and each round runs two seeded workers in parallel and keeps the better. In
//!    exploration a separated layout is cut again and a failed one is pooled, disrupted and
//!    separated again at the same length; compression then cuts the best by ever smaller steps.
//!    The result is returned only if the independent check accepts it.
//! 4. **Search through overlap on sheets (`sheets`).** The sequence search gets
//!    [`SHEETS_SEQUENCE_SEARCH_SHARE`](local_search::SHEETS_SEQUENCE_SEARCH_SHARE) of the budget;
//!    the rest separates the last sheet's parts into the earlier sheets, one at a time (dropping
//!    the last sheet when it empties), trades its widest part for a narrower one when that is
//!    what holds its length, then compresses the last sheet like a strip. Also checked
//!    independently before it is returned.
//!
//! Determinism: the work is counted in collision queries and the search stops after
//! `work_limit` of them (default `time_limit × NOMINAL_QUERIES_PER_SECOND`), so the result depends
//! only on the items, the options and the seed, not on the machine or the thread count. The
//! wall-clock `time_limit` is also enforced between rounds; when it stops the search first (a slow
//! or busy machine) the layout says so with
//! [`StopReason::TimeLimit`](crate::nest::StopReason::TimeLimit) and may differ between runs.
//!
//! Files: `problem` (validated input and oriented shapes, checked by `validation`), `placement`
//! (bottom-left, with `compaction`), `moves`, `objective`, `local_search` (the loop and its
//! budget), `separator`, `compression` and `sheets` (search through overlap), `holes` (parts in holes), `measure` (the
//! public layout), `solution` and `random`.

mod compaction;
mod compression;
mod holes;
mod local_search;
mod measure;
mod moves;
mod objective;
mod placement;
mod problem;
mod random;
mod separator;
mod sheets;
mod solution;
mod validation;

pub(crate) use problem::Problem;
