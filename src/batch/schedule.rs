//! Running a batch's parts, each in a worker process of its own (a crash, a runaway part or a
//! time limit then costs one part, never the batch), at most `jobs` at a time. A part whose
//! record is final and matches its fingerprint is skipped. A worker gets its task as JSON on
//! standard input and ends with the parent: on Linux it receives SIGTERM when the batch dies.

use std::io::{Read, Write};
use std::path::PathBuf;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::thread;
use std::time::{Duration, Instant};

use super::errors::BatchError;
use super::record::{Fingerprint, PartRecord, PartStatus};
use super::task::PartTask;
use crate::pipeline::RunOptions;

/// The subcommand of the `flatcut` binary that runs one part of a batch, its task as JSON on
/// standard input.
pub const WORKER_SUBCOMMAND: &str = "batch-part";

/// How often a running worker is looked at (for its end, the time limit and a stop).
const POLL_INTERVAL: Duration = Duration::from_millis(20);

/// How long a worker asked to stop (SIGTERM) has to remove its staging folder before it is
/// killed.
const STOP_GRACE: Duration = Duration::from_secs(5);

/// The most of a failed worker's standard error kept as the reason, in bytes (its end).
const STDERR_TAIL_BYTES: usize = 2000;

/// Time a part's worker gets beyond its own time limit before it is killed by default: enough
/// to write the part's files after the limit ended its flattening.
pub const KILL_GRACE: Duration = Duration::from_secs(60);

/// The default hard limit of a part's worker: its time limit
/// ([`RunOptions::time_limit_seconds`]) plus [`KILL_GRACE`].
pub fn default_kill_after(options: &RunOptions) -> Duration {
    Duration::from_secs_f64(options.time_limit_seconds) + KILL_GRACE
}

/// How a batch's parts are run.
#[derive(Debug, Clone, PartialEq)]
pub struct Scheduling {
    /// The worker program (the `flatcut` binary); it is run as `PROGRAM batch-part`.
    pub program: PathBuf,
    /// Parts running at once.
    pub jobs: usize,
    /// Longest a part's worker may run before it is killed (the part is then `timed_out`);
    /// `None` for no limit. The part's own time limit, which ends its flattening with the part
    /// rejected, is [`RunOptions::time_limit_seconds`].
    pub time_limit: Option<Duration>,
}

/// What the scheduler reports as it goes.
#[derive(Debug, Clone, Copy)]
pub enum BatchEvent<'a> {
    /// A part's worker started.
    Started {
        /// The part.
        task: &'a PartTask,
        /// Parts this batch runs.
        total: usize,
    },
    /// A part ended (or was skipped: its record was complete).
    Finished {
        /// The part.
        task: &'a PartTask,
        /// Its record.
        record: &'a PartRecord,
        /// Whether it was skipped.
        skipped: bool,
        /// Seconds it ran.
        seconds: f64,
        /// Parts this batch runs.
        total: usize,
    },
}

/// Runs `tasks` (with their `fingerprints`) in worker processes, `scheduling.jobs` at a time,
/// skipping complete ones, and returns each task's record: `None` for a part not run because
/// `stop` was raised (its worker was asked to stop, or never started).
pub fn run_tasks(
    tasks: &[PartTask],
    fingerprints: &[Fingerprint],
    scheduling: &Scheduling,
    stop: &AtomicBool,
    on_event: &(dyn Fn(BatchEvent<'_>) + Sync),
) -> Result<Vec<Option<PartRecord>>, BatchError> {
    let next = AtomicUsize::new(0);
    let jobs = scheduling.jobs.clamp(1, tasks.len().max(1));
    let threads_per_worker = worker_threads(jobs);
    let results: Vec<Result<Vec<(usize, PartRecord)>, BatchError>> = thread::scope(|scope| {
        let handles: Vec<_> = (0..jobs)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        if stop.load(Ordering::SeqCst) {
                            break;
                        }
                        let index = next.fetch_add(1, Ordering::SeqCst);
                        let (Some(task), Some(fingerprint)) =
                            (tasks.get(index), fingerprints.get(index))
                        else {
                            break;
                        };
                        let runner = WorkerRun {
                            task,
                            fingerprint,
                            total: tasks.len(),
                            scheduling,
                            threads: threads_per_worker,
                            stop,
                        };
                        if let Some(record) = runner.run(on_event)? {
                            done.push((index, record));
                        }
                    }
                    Ok(done)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|handle| handle.join().expect("a scheduler thread does not panic"))
            .collect()
    });
    let mut records = vec![None; tasks.len()];
    for result in results {
        for (index, record) in result? {
            records[index] = Some(record);
        }
    }
    Ok(records)
}

/// Threads each worker's own parallel loops get: the cores shared among the workers.
fn worker_threads(jobs: usize) -> usize {
    let cores = thread::available_parallelism().map_or(1, |cores| cores.get());
    (cores / jobs).max(1)
}

/// One part through its worker.
struct WorkerRun<'a> {
    task: &'a PartTask,
    fingerprint: &'a Fingerprint,
    total: usize,
    scheduling: &'a Scheduling,
    threads: usize,
    stop: &'a AtomicBool,
}

/// How a worker process ended.
enum WorkerEnd {
    /// It exited (with or without a record).
    Exited(ExitStatus),
    /// It ran past the time limit and was stopped.
    TimedOut,
    /// The batch was stopped.
    Stopped,
}

impl WorkerRun<'_> {
    /// Skips the part when complete, else runs its worker and returns its record (`None` when
    /// the batch was stopped first).
    fn run(
        &self,
        on_event: &(dyn Fn(BatchEvent<'_>) + Sync),
    ) -> Result<Option<PartRecord>, BatchError> {
        let task = self.task;
        if let Some(record) = task.completed_record(self.fingerprint) {
            on_event(BatchEvent::Finished {
                task,
                record: &record,
                skipped: true,
                seconds: 0.0,
                total: self.total,
            });
            return Ok(Some(record));
        }
        on_event(BatchEvent::Started {
            task,
            total: self.total,
        });
        let started = Instant::now();
        let mut child = self.spawn()?;
        let stderr = child.stderr.take().map(|mut pipe| {
            thread::spawn(move || {
                let mut bytes = Vec::new();
                let _ = pipe.read_to_end(&mut bytes);
                bytes
            })
        });
        let end = self.wait(&mut child, started);
        let stderr = stderr
            .and_then(|reader| reader.join().ok())
            .unwrap_or_default();
        let Some(record) = self.record_of(end, &stderr)? else {
            return Ok(None);
        };
        on_event(BatchEvent::Finished {
            task,
            record: &record,
            skipped: false,
            seconds: started.elapsed().as_secs_f64(),
            total: self.total,
        });
        Ok(Some(record))
    }

    /// Starts the worker with the task on its standard input.
    fn spawn(&self) -> Result<Child, BatchError> {
        let program = &self.scheduling.program;
        let worker_error = |source| BatchError::Worker {
            program: program.clone(),
            source,
        };
        let mut command = Command::new(program);
        command
            .arg(WORKER_SUBCOMMAND)
            .env("RAYON_NUM_THREADS", self.threads.to_string())
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(Stdio::piped());
        end_with_parent(&mut command);
        let mut child = command.spawn().map_err(worker_error)?;
        let task = serde_json::to_vec(self.task).expect("a task serialises");
        if let Some(mut stdin) = child.stdin.take() {
            // A worker that died at once shows in its exit status, not here.
            let _ = stdin.write_all(&task);
        }
        Ok(child)
    }

    /// Waits for the worker, stopping it at the time limit or when the batch stops.
    fn wait(&self, child: &mut Child, started: Instant) -> WorkerEnd {
        loop {
            if let Ok(Some(status)) = child.try_wait() {
                return WorkerEnd::Exited(status);
            }
            let late = self
                .scheduling
                .time_limit
                .is_some_and(|limit| started.elapsed() > limit);
            let stopped = self.stop.load(Ordering::SeqCst);
            if late || stopped {
                stop_worker(child);
                return if late {
                    WorkerEnd::TimedOut
                } else {
                    WorkerEnd::Stopped
                };
            }
            thread::sleep(POLL_INTERVAL);
        }
    }

    /// The part's record after its worker ended: the one it wrote, or one the batch writes for
    /// a worker that timed out or ended without one; `None` when the batch was stopped.
    fn record_of(&self, end: WorkerEnd, stderr: &[u8]) -> Result<Option<PartRecord>, BatchError> {
        let task = self.task;
        let written =
            PartRecord::read(&task.folder).filter(|record| &record.fingerprint == self.fingerprint);
        // A Ctrl-C reaches the workers too: one may end before the batch sees its stop.
        let stopped = self.stop.load(Ordering::SeqCst);
        let (status, reason) = match (end, written) {
            (WorkerEnd::Exited(_), Some(record)) => return Ok(Some(record)),
            (WorkerEnd::Stopped, _) => return Ok(None),
            (WorkerEnd::Exited(_), None) if stopped => return Ok(None),
            (WorkerEnd::TimedOut, _) => (
                PartStatus::TimedOut,
                format!(
                    "stopped at the time limit of {} s",
                    self.scheduling
                        .time_limit
                        .map_or(0.0, |limit| limit.as_secs_f64())
                ),
            ),
            (WorkerEnd::Exited(status), None) => (
                PartStatus::Failed,
                format!(
                    "the worker ended ({status}) without a result{}",
                    stderr_tail(stderr)
                ),
            ),
        };
        std::fs::create_dir_all(&task.folder).map_err(|source| BatchError::Write {
            path: task.folder.clone(),
            source,
        })?;
        let record = task.record_without_outputs(self.fingerprint.clone(), status, reason);
        record.write(&task.folder)?;
        Ok(Some(record))
    }
}

/// The end of a worker's standard error, as `: TEXT`, or nothing when it wrote none.
fn stderr_tail(stderr: &[u8]) -> String {
    let text = String::from_utf8_lossy(&stderr[stderr.len().saturating_sub(STDERR_TAIL_BYTES)..]);
    let text = text.trim();
    if text.is_empty() {
        String::new()
    } else {
        format!(": {text}")
    }
}

/// Asks the worker to stop (SIGTERM: it removes its staging folder), and kills it when it has
/// not ended after [`STOP_GRACE`].
fn stop_worker(child: &mut Child) {
    terminate(child);
    let asked = Instant::now();
    while asked.elapsed() < STOP_GRACE {
        if let Ok(Some(_)) = child.try_wait() {
            return;
        }
        thread::sleep(POLL_INTERVAL);
    }
    let _ = child.kill();
    let _ = child.wait();
}

/// Sends SIGTERM to the worker.
#[cfg(unix)]
fn terminate(child: &Child) {
    if let Ok(pid) = libc::pid_t::try_from(child.id()) {
        // SAFETY: kill(2) with a child's pid and a valid signal has no memory effects.
        unsafe {
            libc::kill(pid, libc::SIGTERM);
        }
    }
}

/// Without signals the worker is killed outright.
#[cfg(not(unix))]
fn terminate(child: &mut Child) {
    let _ = child.kill();
}

/// Has the worker receive SIGTERM when the batch process dies (Linux), so that a killed batch
/// leaves no workers behind.
#[cfg(target_os = "linux")]
fn end_with_parent(command: &mut Command) {
    use std::os::unix::process::CommandExt;
    let batch = libc::pid_t::try_from(std::process::id()).unwrap_or(0);
    // SAFETY: prctl(PR_SET_PDEATHSIG) and getppid are async-signal-safe and touch no memory of
    // the parent.
    unsafe {
        command.pre_exec(move || {
            if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM) == -1 {
                return Err(std::io::Error::last_os_error());
            }
            // The batch died between the fork and the prctl: no signal will come, so stop here.
            if libc::getppid() != batch {
                return Err(std::io::Error::other(
                    "the batch ended before its worker started",
                ));
            }
            Ok(())
        });
    }
}

/// Elsewhere a worker outlives a killed batch and finishes its part.
#[cfg(not(target_os = "linux"))]
fn end_with_parent(_command: &mut Command) {}
