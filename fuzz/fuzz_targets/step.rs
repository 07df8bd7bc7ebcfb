//! STEP reader (exchange structure, entities, B-rep): never a panic, a hang or an unbounded
//! allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = flatcut::ingest::read_step(std::path::Path::new("fuzz.step"), data);
});
