//! Cut sidecar reader (seams and no-cut regions as JSON).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let _ = flatcut::ingest::parse_cut_sidecar(std::path::Path::new("fuzz.cut.json"), text, 1);
});
