//! Integration test of the nesting stage on a standard ESICUP benchmark instance, with a short
//! budget: the layout must pass the independent check and reach a sane density.

use std::path::PathBuf;
use std::time::Duration;

use flatcut::nest::instance::read_instance;
use flatcut::nest::verify::verify;
use flatcut::nest::{NestOptions, Stock, nest};
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
