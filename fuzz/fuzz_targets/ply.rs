//! PLY reader (ASCII and binary), then mesh validation: never a panic, a hang or an unbounded allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(soup) = flatcut::ingest::parse_ply(data) {
        let _ = flatcut::mesh::validate(&soup);
    }
});
