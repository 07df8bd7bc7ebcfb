//! Pattern file reader (`<part>.pattern.json`, what `flatcut nest` reads), then the drawing it
//! puts on a sheet.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Ok(pattern) = flatcut::pattern::PatternFile::from_json(text) {
        let _ = pattern.sheet_drawing();
    }
});
