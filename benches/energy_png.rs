//! Criterion benchmark of the energy report picture: rendering (PNG encoding included) the
//! flattened patterns of a hemisphere and a fender-like patch of about 100k triangles each, with
//! their per-vertex energies, at the default width. The goal: 100k triangles in under a
//! second. `cargo bench --bench energy_png`.

use criterion::{Criterion, criterion_group, criterion_main};
use flatcut::export::energy_png::{EnergyMap, EnergyPngOptions, PatternFigures, render_energy_png};
use flatcut::flatten::{FlattenOptions, PAPER_SPRING_CONSTANT, SpringSystem, Stiffness, flatten};
use flatcut::pattern::{NEGLIGIBLE_STRAIN, negligible_vertex_energy};
use flatcut::progress::NoProgress;

mod meshes;
use meshes::{fender, hemisphere};

/// Grid cells per side: 2 x 224² = 100,352 triangles.
const CELLS: usize = 224;

fn bench_energy_png(criterion: &mut Criterion) {
    let mut group = criterion.benchmark_group("energy_png");
    group.sample_size(10);
    for (name, model) in [("hemisphere", hemisphere(CELLS)), ("fender", fender(CELLS))] {
        let stiffness = Stiffness::uniform(&model);
        let options = FlattenOptions::default();
        let flattened = flatten(&model, &stiffness, &options, &NoProgress).expect("flattens");
        let springs = SpringSystem::new(&model, stiffness.factors(), PAPER_SPRING_CONSTANT);
        let energies = springs.vertex_energies(&flattened.positions);
        let accuracy = flattened.stats.accuracy;
        let map = EnergyMap {
            name: name.to_string(),
            energy_units: "mm²".to_string(),
            length_units: "mm".to_string(),
            positions: &flattened.positions,
            triangles: model.triangles(),
            vertex_energies: &energies,
            boundary_loops: model.boundary_loops(),
            cut_polylines: Vec::new(),
            fold_polylines: Vec::new(),
            figures: PatternFigures {
                area_error: accuracy.area_error,
                shape_error: accuracy.shape_error,
                max_strain: accuracy.max_strain,
                cuts: 0,
            },
            negligible_energy: negligible_vertex_energy(&springs, NEGLIGIBLE_STRAIN),
        };
        let png_options = EnergyPngOptions::default();
        group.bench_function(format!("{name}_100k"), |bencher| {
            bencher.iter(|| render_energy_png(&map, None, &png_options).expect("renders"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_energy_png);
criterion_main!(benches);
