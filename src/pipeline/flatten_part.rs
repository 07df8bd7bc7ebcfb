//! Flattening one loaded part: seams, crest-line cuts and re-flattening until it is within
//! tolerance, then the pattern turned to its grain.

use crate::cut::cut_and_flatten;
use crate::error::Error;
use crate::flatten::orient::orient;
use crate::progress::Progress;

use super::load::{PartJob, PartResult, RunOptions};

/// Flattens one part, with seams and crest-line cuts until it is within tolerance or the cut
/// budget is spent.
pub fn flatten_part(
    mut job: PartJob,
    options: &RunOptions,
    progress: &dyn Progress,
) -> Result<PartResult, Error> {
    let started = std::time::Instant::now();
    let mut result = cut_and_flatten(
        &job.model,
        &job.stiffness,
        &job.constraints,
        &options.flatten,
        &options.cut,
        progress,
    )
    .map_err(|reason| Error::Cut {
        path: job.source.clone(),
        part: job.name.clone(),
        reason,
    })?;
    let grain = job.attributes.grain;
    orient(&result.model, &mut result.flattened, grain);
    if let Some(uncut) = &mut result.uncut {
        orient(&uncut.model, &mut uncut.flattened, grain);
    }
    // The part's time is the whole of it: seams, every cut tried and every flattening.
    result.flattened.stats.seconds = started.elapsed().as_secs_f64();
    job.model = result.model;
    job.stiffness = result.stiffness;
    Ok(PartResult {
        job,
        flattened: result.flattened,
        seams: result.seams,
        cuts: result.cuts,
        cut_stop: result.stop,
        uncut: result.uncut,
    })
}
