//! The whole run in the library: every input loaded and checked before anything is flattened,
//! every part flattened, cut and made a pattern, and the patterns nested on the stock (when there
//! is one) and checked independently. Nothing is written here (see [`super::outputs`]).

use crate::error::Error;
use crate::flatten::Solver;
use crate::nest::parts::items_from_patterns;
use crate::nest::verify::verify;
use crate::nest::{NestItem, NestLayout, Stock, nest};
use crate::pattern::{PatternFile, part_contours};
use crate::progress::Progress;

use super::config::{NestingConfig, RunConfig};
use super::flatten_part::flatten_job;
use super::load::{PartJob, load_parts};
use super::part_result::PartResult;

/// Above this many triangles the paper's solver is reported to be slow (its phase one is
/// quadratic: about 10 s at 5,000 triangles on a 2-core machine).
pub const PAPER_SOLVER_ADVISED_TRIANGLES: usize = 5_000;

/// What a run made.
#[derive(Debug, Clone)]
pub struct RunOutput {
    /// Every part, flattened, cut and made a pattern, in input order.
    pub parts: Vec<PartResult>,
    /// Every part's pattern file (`patterns[i]` is part `i`'s): what the run nests and writes
    /// as `<part>.pattern.json`.
    pub patterns: Vec<PatternFile>,
    /// The nested layout, when the run had stock.
    pub nesting: Option<NestedLayout>,
    /// The parts on the stock, in the layout's item order (`nestable_parts`); none without
    /// stock.
    pub nested_parts: Vec<usize>,
}

/// The patterns nested on the stock, checked independently.
#[derive(Debug, Clone)]
pub struct NestedLayout {
    /// The nesting items, one per pattern nested, in mm.
    pub items: Vec<NestItem>,
    /// Where every copy of every item went.
    pub layout: NestLayout,
}

/// Runs the whole pipeline: checks the options ([`RunConfig::validate`]), loads every input
/// ([`load_all`]), flattens and cuts every part into its pattern, and nests the patterns when
/// `config` has stock ([`run_loaded`]).
pub fn run(config: &RunConfig, progress: &dyn Progress) -> Result<RunOutput, Error> {
    let jobs = load_all(config, progress)?;
    run_loaded(jobs, config, progress)
}

/// Checks the options ([`RunConfig::validate`]) and loads every input (refusing two parts of one
/// name; every input that cannot be used is reported, not only the first), reporting their repairs as warnings through `progress`: everything a run can find
/// wrong before its long work.
pub fn load_all(config: &RunConfig, progress: &dyn Progress) -> Result<Vec<PartJob>, Error> {
    config.validate()?;
    let mut jobs = Vec::new();
    let mut errors = Vec::new();
    for (index, input) in config.inputs.iter().enumerate() {
        progress.start(
            &format!(
                "reading {}/{} {}",
                index + 1,
                config.inputs.len(),
                input.display()
            ),
            0,
        );
        let loaded = load_parts(input, &config.options);
        progress.finish();
        match loaded {
            Ok(parts) => jobs.extend(parts),
            Err(error) => errors.push(error),
        }
    }
    if errors.len() > 1 {
        return Err(Error::Inputs { errors });
    }
    if let Some(error) = errors.pop() {
        return Err(error);
    }
    check_distinct_names(&jobs)?;
    // The parts of one file share its warnings: each is said once.
    let mut said = std::collections::BTreeSet::new();
    for job in &jobs {
        for warning in &job.warnings {
            let line = format!("{}: {warning}", job.source.display());
            if said.insert(line.clone()) {
                progress.warn(&line);
            }
        }
        let triangles = job.model.triangle_count();
        if config.options.flatten.solver == Solver::Paper
            && triangles > PAPER_SOLVER_ADVISED_TRIANGLES
        {
            progress.warn(&format!(
                "{}: {triangles} triangles: the paper's solver is quadratic and will be slow; \
                 the default solver minimises the same energy",
                job.name
            ));
        }
    }
    Ok(jobs)
}

/// Flattens and cuts every loaded part into its pattern, and nests the patterns when `config`
/// has stock, rejecting a layout the independent check ([`verify`]) finds a defect in.
pub fn run_loaded(
    jobs: Vec<PartJob>,
    config: &RunConfig,
    progress: &dyn Progress,
) -> Result<RunOutput, Error> {
    let count = jobs.len();
    let parts = jobs
        .into_iter()
        .enumerate()
        .map(|(index, job)| {
            let part_progress = PartProgress {
                inner: progress,
                prefix: format!("part {}/{count} {}", index + 1, job.name),
            };
            flatten_job(job, &config.options, &part_progress)
        })
        .collect::<Result<Vec<Vec<PartResult>>, _>>()?
        .into_iter()
        .flatten()
        .collect::<Vec<PartResult>>();
    let tolerance = config.options.flatten.tolerance;
    let patterns: Vec<PatternFile> = parts
        .iter()
        .map(|part| part.pattern_file(&config.pattern, tolerance))
        .collect();
    let (nested_parts, nesting) = match config.stock {
        Some(stock) => {
            let nested_parts = nestable_parts(&patterns, progress);
            let nested = nested_parts.iter().map(|&part| &patterns[part]);
            let layout = nest_checked(nested, stock, &config.nesting, progress)?;
            (nested_parts, Some(layout))
        }
        None => (Vec::new(), None),
    };
    Ok(RunOutput {
        parts,
        patterns,
        nesting,
        nested_parts,
    })
}

/// The parts that go on the stock: every part but a rejected one whose outline cannot be drawn
/// (a hole collapsed to nothing, seen on a real garment panel), which has no cut file either
/// and is named in a warning. A rejected part that can be drawn goes on the sheets marked
/// [`crate::pattern::REJECTED_MARK`].
pub fn nestable_parts(patterns: &[PatternFile], progress: &dyn Progress) -> Vec<usize> {
    let mut nestable = Vec::with_capacity(patterns.len());
    for (part, pattern) in patterns.iter().enumerate() {
        if !pattern.rejected || part_contours(&pattern.drawing, &pattern.options).is_ok() {
            nestable.push(part);
        } else {
            progress.warn(&format!(
                "{}: not nested, its outline cannot be drawn (the part is rejected)",
                pattern.drawing.name
            ));
        }
    }
    nestable
}

/// Nests `patterns` on `stock` ([`items_from_patterns`], [`nest`]) and checks the layout
/// independently ([`verify`]): a layout with a defect is an error, never a result.
pub fn nest_checked<'a>(
    patterns: impl IntoIterator<Item = &'a PatternFile>,
    stock: Stock,
    nesting: &NestingConfig,
    progress: &dyn Progress,
) -> Result<NestedLayout, Error> {
    let items = items_from_patterns(patterns, &nesting.rotations, nesting.mirror)?;
    let layout = nest(&items, &nesting.nest_options(stock), progress)?;
    let violations = verify(&items, &layout);
    if !violations.is_empty() {
        return Err(Error::LayoutRejected { violations });
    }
    Ok(NestedLayout { items, layout })
}

/// Refuses two parts of the same name: the second's files would overwrite the first's.
fn check_distinct_names(jobs: &[PartJob]) -> Result<(), Error> {
    for (index, job) in jobs.iter().enumerate() {
        if let Some(earlier) = jobs[..index].iter().find(|other| other.name == job.name) {
            return Err(Error::DuplicateName {
                path: job.source.clone(),
                name: job.name.clone(),
                earlier: earlier.source.clone(),
            });
        }
    }
    Ok(())
}

/// Progress of one part among several: its stages named `part I/N NAME: STAGE`.
struct PartProgress<'a> {
    inner: &'a dyn Progress,
    prefix: String,
}

impl Progress for PartProgress<'_> {
    fn start(&self, stage: &str, total: u64) {
        self.inner
            .start(&format!("{}: {stage}", self.prefix), total);
    }

    fn advance(&self, done: u64) {
        self.inner.advance(done);
    }

    fn finish(&self) {
        self.inner.finish();
    }

    fn warn(&self, message: &str) {
        self.inner.warn(message);
    }

    fn status(&self, status: &str) {
        self.inner.status(status);
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Mutex;

    use glam::DVec2;

    use crate::pattern::{PartDrawing, PatternOptions};
    use crate::pipeline::run::*;
    use crate::units::Units;

    /// Records warnings.
    #[derive(Default)]
    struct Warnings(Mutex<Vec<String>>);

    impl Progress for Warnings {
        fn start(&self, _stage: &str, _total: u64) {}
        fn advance(&self, _done: u64) {}
        fn finish(&self) {}
        fn warn(&self, message: &str) {
            self.0.lock().unwrap().push(message.to_owned());
        }
    }

    /// A 100 x 50 plate named `name` with the given holes.
    fn plate(name: &str, holes: Vec<Vec<DVec2>>, rejected: bool) -> PatternFile {
        let corners = [(0.0, 0.0), (100.0, 0.0), (100.0, 50.0), (0.0, 50.0)];
        PatternFile {
            drawing: PartDrawing {
                name: name.into(),
                units: Units::Millimetres,
                quantity: 1,
                material: None,
                outer: corners.iter().map(|&(x, y)| DVec2::new(x, y)).collect(),
                holes,
                fold_lines: Vec::new(),
                grain: None,
                bends: Vec::new(),
            },
            grain_degrees: None,
            thickness_mm: None,
            options: PatternOptions::default(),
            rejected,
        }
    }

    #[test]
    fn a_rejected_part_whose_outline_cannot_be_drawn_is_left_off_the_sheets() {
        let collapsed = vec![vec![DVec2::new(20.0, 20.0); 3]];
        let broken = plate("broken", collapsed.clone(), true);
        assert!(part_contours(&broken.drawing, &broken.options).is_err());
        let patterns = [
            plate("good", Vec::new(), false),
            broken,
            plate("over tolerance", Vec::new(), true),
            plate("broken but accepted", collapsed, false),
        ];
        let warnings = Warnings::default();
        assert_eq!(nestable_parts(&patterns, &warnings), [0, 2, 3]);
        assert_eq!(
            warnings.0.into_inner().unwrap(),
            ["broken: not nested, its outline cannot be drawn (the part is rejected)"]
        );
    }
}
