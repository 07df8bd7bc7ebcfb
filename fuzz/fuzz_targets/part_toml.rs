//! Part file reader (TOML surfaces, fold lines, regions): never a panic, a hang or an unbounded
//! allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = flatcut::ingest::read_part_text(std::path::Path::new("fuzz.toml"), data);
});
