//! Criterion benchmarks of `flatten` on generated meshes of about 1k and 20k triangles: a
//! hemisphere (radius 100 mm, strongly non-developable) and a fender-like bicubic patch
//! (about 600 x 400 mm, gently curved both ways). The meshes are built here, in Rust, so the
//! benchmarks need nothing else. `cargo bench --bench flatten`.
//!
//! Groups: the whole `flatten` with the fast solver (both sizes) and the paper's (1k only: its
//! phase one is quadratic), and the fast solver's reusable `solve` alone from a fixed initial
//! pattern (what the flatten → cut → re-flatten loop repeats).

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use flatcut::flatten::{
    FastOptions, FastSolver, FlattenOptions, InitRelease, PAPER_SPRING_CONSTANT, Solver,
    SpringSystem, Stiffness, flatten, init_flatten,
};
use flatcut::progress::NoProgress;

mod meshes;
use meshes::{fender, hemisphere};

/// Grid cells per side for about 1k and 20k triangles (2 triangles per cell).
const SIZES: [(&str, usize); 2] = [("1k", 22), ("20k", 100)];

fn options(solver: Solver) -> FlattenOptions {
    FlattenOptions {
        solver,
        ..FlattenOptions::default()
    }
}

fn bench_flatten(criterion: &mut Criterion) {
    let mut group = criterion.benchmark_group("flatten");
    group.sample_size(10);
    for (label, cells) in SIZES {
        for (name, model) in [("hemisphere", hemisphere(cells)), ("fender", fender(cells))] {
            let stiffness = Stiffness::uniform(&model);
            let id = format!("{name}_{label}");
            let mut solvers = vec![Solver::Fast];
            if model.triangle_count() < 5_000 {
                solvers.push(Solver::Paper);
            }
            for solver in solvers {
                let parameter = BenchmarkId::new(format!("{solver:?}").to_lowercase(), &id);
                group.bench_with_input(parameter, &model, |bencher, model| {
                    bencher.iter(|| {
                        flatten(model, &stiffness, &options(solver), &NoProgress).expect("flattens")
                    })
                });
            }
        }
    }
    group.finish();
}

fn bench_fast_solve(criterion: &mut Criterion) {
    let mut group = criterion.benchmark_group("fast_solve");
    group.sample_size(10);
    for (label, cells) in SIZES {
        for (name, model) in [("hemisphere", hemisphere(cells)), ("fender", fender(cells))] {
            let stiffness = Stiffness::uniform(&model);
            let springs = SpringSystem::new(&model, stiffness.factors(), PAPER_SPRING_CONSTANT);
            let release = InitRelease::Neighbourhood { sweeps: 1 };
            let start = init_flatten(&model, &springs, release, &NoProgress);
            let solver =
                FastSolver::new(&model, &springs, FastOptions::default()).expect("factors");
            group.bench_function(format!("{name}_{label}"), |bencher| {
                bencher.iter(|| {
                    let mut positions = start.clone();
                    black_box(solver.solve(&mut positions))
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench_flatten, bench_fast_solve);
criterion_main!(benches);
