//! ESICUP nesting instance reader (JSON, as in jagua-rs and sparrow).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let _ = flatcut::nest::instance::parse_instance(text);
});
