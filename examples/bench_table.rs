//! Flattens one mesh with one solver and prints one Markdown row of the performance table:
//! triangles, solver, seconds, peak memory, E_S, E_C, flipped, iterations, stop reason.
//!
//! One mesh and one solver per process, so the peak resident memory (`VmHWM` from
//! `/proc/self/status`, Linux only) belongs to that run alone; `bench/run_table.sh` loops over
//! meshes and solvers. Optionally writes `PREFIX.mesh.obj` and `PREFIX.pattern.obj` (the facet
//! model flattened and its pattern, same vertices and faces) so `../shared/bench/metrics.py` can
//! check the figures independently.
//!
//! ```text
//! cargo run --release --example bench_table -- MESH.obj [fast|paper] [PREFIX]
//! cargo run --release --example bench_table -- --header
//! ```

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, bail};
use flatcut::export::obj::{mesh_obj, pattern_obj};
use flatcut::flatten::{FlattenOptions, Solver};
use flatcut::pipeline::{RunOptions, flatten_part, load_parts};
use flatcut::progress::NoProgress;

fn main() -> anyhow::Result<()> {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    if arguments.first().map(String::as_str) == Some("--header") {
        println!(
            "| mesh | triangles | solver | seconds | peak MiB | E_S % | E_C % | flipped | iterations | stop |"
        );
        println!("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |");
        return Ok(());
    }
    let Some(mesh) = arguments.first() else {
        bail!("usage: bench_table MESH.obj [fast|paper] [PREFIX] | --header");
    };
    let solver = match arguments.get(1).map(String::as_str) {
        None | Some("fast") => Solver::Fast,
        Some("paper") => Solver::Paper,
        Some(other) => bail!("unknown solver {other:?}: fast or paper"),
    };
    let options = RunOptions {
        flatten: FlattenOptions {
            solver,
            ..FlattenOptions::default()
        },
        ..RunOptions::default()
    };
    let path = Path::new(mesh);
    let mut jobs = load_parts(path, &options)?;
    let job = jobs.pop().context("the mesh has no triangles")?;
    anyhow::ensure!(jobs.is_empty(), "the mesh has several components");
    let started = Instant::now();
    let result = flatten_part(job, &options, &NoProgress)?;
    let seconds = started.elapsed().as_secs_f64();
    let stats = &result.flattened.stats;
    if let Some(prefix) = arguments.get(2) {
        let model = &result.job.model;
        let header = "flatcut bench_table";
        let files = [
            (
                "mesh",
                mesh_obj(header, model.positions(), model.triangles()),
            ),
            (
                "pattern",
                pattern_obj(header, &result.flattened.positions, model.triangles()),
            ),
        ];
        for (kind, text) in files {
            let out = format!("{prefix}.{kind}.obj");
            std::fs::write(&out, text).with_context(|| format!("writing {out}"))?;
        }
    }
    println!(
        "| {} | {} | {:?} | {:.3} | {:.0} | {:.3} | {:.3} | {} | {} | {:?} |",
        path.file_stem().unwrap_or_default().to_string_lossy(),
        result.job.model.triangle_count(),
        solver,
        seconds,
        peak_mebibytes().unwrap_or(f64::NAN),
        100.0 * stats.accuracy.area_error,
        100.0 * stats.accuracy.shape_error,
        stats.accuracy.flipped,
        stats.iterations,
        stats.stop_reason,
    );
    eprintln!(
        "initial E_S {:.4} % E_C {:.4} % flipped {}; final energy {:.6e}",
        100.0 * stats.initial_accuracy.area_error,
        100.0 * stats.initial_accuracy.shape_error,
        stats.initial_accuracy.flipped,
        stats.energy
    );
    Ok(())
}

/// Peak resident set size of this process (`VmHWM`), in MiB.
fn peak_mebibytes() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|line| line.starts_with("VmHWM:"))?;
    let kibibytes: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kibibytes / 1024.0)
}
