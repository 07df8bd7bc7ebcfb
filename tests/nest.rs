//! Integration tests of the nesting stage: a standard ESICUP benchmark instance, with a short
//! budget, must pass the independent check and reach a sane density; and a whole nested run,
//! from part files to sheets, runs from the library without the command line.

use std::path::PathBuf;
use std::time::Duration;

use flatcut::nest::instance::read_instance;
use flatcut::nest::verify::verify;
use flatcut::nest::{NestOptions, Stock, nest};
use flatcut::pipeline::{NestingConfig, RunConfig, run, write_outputs};
use flatcut::progress::NoProgress;

/// The instance from the repository's samples, or from the shared directory beside the repository.
fn instance_path(name: &str) -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let sample = root.join("samples/nesting").join(name);
    if sample.exists() {
        sample
    } else {
        root.join("../shared/nesting").join(name)
    }
}

#[test]
fn fu_is_nested_without_overlap_at_a_sane_density() {
    let instance = read_instance(&instance_path("fu.json")).expect("fu.json reads");
    let options = NestOptions {
        stock: Stock::Roll {
            width: instance.strip_height,
        },
        time_limit: Duration::from_secs(3),
        work_limit: Some(1_000_000),
        ..NestOptions::default()
    };
    let layout = nest(&instance.items, &options, &NoProgress).expect("fu nests");
    let violations = verify(&instance.items, &layout);
    assert!(violations.is_empty(), "{violations:?}");
    let placed: usize = layout
        .sheets
        .iter()
        .map(|sheet| sheet.placements.len())
        .sum();
    assert_eq!(placed, 12);
    assert!(layout.utilisation > 0.70, "density {}", layout.utilisation);
}

/// `pipeline::run` with a sheet: every part flattened within tolerance, every copy placed once,
/// the layout clean under the independent check, and the output folder written by the library.
#[test]
fn a_nested_run_from_the_library_places_every_part() {
    let samples = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("samples");
    let config = RunConfig {
        inputs: vec![
            samples.join("cone_frustum.toml"),
            samples.join("cylinder_panel.toml"),
        ],
        stock: Some(Stock::Sheets {
            width: 600.0,
            height: 400.0,
        }),
        nesting: NestingConfig {
            time_limit: Duration::ZERO,
            ..NestingConfig::default()
        },
        timings: false,
        ..RunConfig::default()
    };
    let output = run(&config, &NoProgress).expect("the run succeeds");
    assert_eq!(output.parts.len(), 2);
    let tolerance = config.options.flatten.tolerance;
    for part in &output.parts {
        let accuracy = part.flattened.stats.accuracy;
        assert!(
            accuracy.within(tolerance),
            "{}: E_S {}, E_C {}, overlap {}",
            part.job.name,
            accuracy.area_error,
            accuracy.shape_error,
            accuracy.overlap
        );
        assert!(part.pattern.drawing.outer.len() >= 3, "{}", part.job.name);
    }
    let nested = output.nesting.as_ref().expect("a layout on the sheet");
    assert_eq!(nested.items.len(), output.parts.len());
    let violations = verify(&nested.items, &nested.layout);
    assert!(violations.is_empty(), "{violations:?}");
    for (index, (item, part)) in nested.items.iter().zip(&output.parts).enumerate() {
        assert_eq!(item.quantity, part.job.quantity);
        let mut copies: Vec<u32> = nested
            .layout
            .sheets
            .iter()
            .flat_map(|sheet| &sheet.placements)
            .filter(|placement| placement.item == index)
            .map(|placement| placement.copy)
            .collect();
        copies.sort_unstable();
        assert_eq!(
            copies,
            (0..item.quantity).collect::<Vec<_>>(),
            "{}",
            item.name
        );
    }
    let directory = tempfile::tempdir().expect("temporary directory");
    let report =
        write_outputs(&output, &config, directory.path(), &NoProgress).expect("outputs written");
    assert_eq!(report.sheets.len(), nested.layout.sheets.len());
    assert!(report.parts.iter().all(|part| part.tolerance_met));
    for part in &output.parts {
        assert!(
            directory
                .path()
                .join(format!("{}.dxf", part.job.name))
                .exists()
        );
    }
    assert!(directory.path().join("sheets/sheet-001.dxf").exists());
    assert!(directory.path().join("report.json").exists());
}
