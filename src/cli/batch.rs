//! `flatcut batch (INPUT... | --manifest FILE) -o OUT [--jobs N] [--shard I/N] [--kill-after S]`:
//! every part into `OUT/parts/<name>/`, each in a worker process (the hidden subcommand
//! `batch-part`), with `OUT/batch.json` summing them up. SIGINT and SIGTERM stop the workers
//! (each leaves its folder as it was) and end the batch with exit code 130; a rerun finishes
//! what is left.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use anyhow::{Context, bail};
use clap::Args;

use flatcut::batch::{
    BatchConfig, BatchEvent, BatchSource, PartStatus, Scheduling, Shard, default_kill_after,
    read_task, run_batch, run_part_task,
};
use flatcut::pipeline::MAXIMUM_PART_TIME_LIMIT;

use super::console::{say, stdout_text};
use super::flatten::PartArgs;
use super::outcome::Outcome;

/// Arguments of `flatcut batch`.
#[derive(Debug, Args)]
pub struct BatchArgs {
    /// Input parts, one part folder each, named by their file stems (or give --manifest).
    #[arg(required_unless_present = "manifest", conflicts_with = "manifest")]
    inputs: Vec<PathBuf>,
    /// The parts as a manifest: CSV with a header row, or JSON Lines (.jsonl), with the fields
    /// input, name, quantity, material, thickness, units, tolerance, seam_allowance, max_cuts.
    #[arg(long, value_name = "FILE")]
    manifest: Option<PathBuf>,
    /// Output folder: parts/<name>/ for each part and batch.json.
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// Parts run at once (default: the number of cores).
    #[arg(long, value_name = "N")]
    jobs: Option<usize>,
    /// Run only shard I of N: the parts at positions I, I+N, I+2N, ... of the manifest.
    #[arg(long, value_name = "I/N")]
    shard: Option<Shard>,
    /// Seconds after which a part's worker is killed, whatever it is doing; the part is then
    /// `timed_out`. Default: the part's --time-limit plus a minute. (--time-limit ends the
    /// flattening itself, with the part rejected and its files written.)
    #[arg(long, value_name = "S")]
    kill_after: Option<f64>,
    #[command(flatten)]
    part: PartArgs,
    /// Print batch.json to stdout too.
    #[arg(long)]
    json: bool,
}

impl BatchArgs {
    /// The batch, converted in one place.
    fn config(&self) -> anyhow::Result<BatchConfig> {
        let source = match &self.manifest {
            Some(manifest) => BatchSource::Manifest(manifest.clone()),
            None => BatchSource::Inputs(self.inputs.clone()),
        };
        let base = self.part.config()?;
        let time_limit = match self.kill_after {
            Some(seconds) if !(seconds > 0.0 && seconds <= MAXIMUM_PART_TIME_LIMIT) => {
                bail!(
                    "--kill-after {seconds}: give a number of seconds above 0 and at most {MAXIMUM_PART_TIME_LIMIT}"
                )
            }
            Some(seconds) => Duration::from_secs_f64(seconds),
            None => default_kill_after(&base.options),
        };
        let jobs = match self.jobs {
            Some(0) => bail!("--jobs 0: give at least 1"),
            Some(jobs) => jobs,
            None => std::thread::available_parallelism().map_or(1, |cores| cores.get()),
        };
        let program = std::env::current_exe().context("cannot find the flatcut program")?;
        Ok(BatchConfig {
            source,
            output: self.output.clone(),
            base,
            shard: self.shard.unwrap_or_default(),
            scheduling: Scheduling {
                program,
                jobs,
                time_limit: Some(time_limit),
            },
        })
    }
}

/// Raised by SIGINT or SIGTERM: the workers are stopped and no more start.
static STOP: AtomicBool = AtomicBool::new(false);

/// Exit code of a batch ended by a signal.
const EXIT_INTERRUPTED: u8 = 130;

/// Runs a batch.
pub fn run(args: BatchArgs) -> anyhow::Result<Outcome> {
    let config = args.config()?;
    // Without a handler a signal ends the batch at once; its workers get SIGTERM with it.
    let _ = ctrlc::set_handler(|| STOP.store(true, Ordering::SeqCst));
    let finished = AtomicUsize::new(0);
    let on_event = |event: BatchEvent<'_>| {
        if let BatchEvent::Finished {
            task,
            record,
            skipped,
            seconds,
            total,
        } = event
        {
            let count = finished.fetch_add(1, Ordering::SeqCst) + 1;
            let how = if skipped {
                "done before, skipped".to_string()
            } else {
                format!("{seconds:.1} s")
            };
            let status = record.status.name();
            let reason = record
                .reason
                .as_ref()
                .map(|reason| format!(": {reason}"))
                .unwrap_or_default();
            say!(
                "flatcut batch: [{count}/{total}] {}: {status} ({how}){reason}",
                task.name
            );
        }
    };
    let outcome = run_batch(&config, &STOP, &on_event)?;
    let counts: Vec<String> = outcome
        .summary
        .counts
        .iter()
        .map(|(status, count)| format!("{count} {status}"))
        .collect();
    say!(
        "flatcut batch: {} part(s): {}; summary {}",
        outcome.summary.parts.len(),
        counts.join(", "),
        config.output.join(flatcut::batch::SUMMARY_FILE).display()
    );
    if args.json {
        let mut text = serde_json::to_string_pretty(&outcome.summary)?;
        text.push('\n');
        stdout_text(&text);
    }
    if STOP.load(Ordering::SeqCst) {
        return Ok(Outcome::Exit(EXIT_INTERRUPTED));
    }
    Ok(Outcome::Exit(outcome.exit_code()))
}

/// Runs one part of a batch: the task comes as JSON on standard input (see `flatcut batch`).
pub fn run_worker() -> anyhow::Result<Outcome> {
    let task = read_task(std::io::stdin().lock())?;
    let record = run_part_task(&task, &super::interrupt::watch)?;
    Ok(match record.status {
        PartStatus::Ok => Outcome::Success,
        status => Outcome::Exit(status.exit_code()),
    })
}
