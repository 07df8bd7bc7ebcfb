//! Batch manifest reader, as CSV and as JSON Lines.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    for name in ["fuzz/parts.csv", "fuzz/parts.jsonl"] {
        let _ = flatcut::batch::parse_manifest(std::path::Path::new(name), text);
    }
});
