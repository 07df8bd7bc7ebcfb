//! OBJ reader, then mesh validation, plain and after the `--repair` and `--seams from-uv` steps in
//! the order the pipeline runs them: never a panic, a hang or an unbounded allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(soup) = flatcut::ingest::parse_obj(data) {
        let _ = flatcut::mesh::validate(&soup);
        let (welded, _) = flatcut::mesh::weld_duplicates(&soup);
        let charts = flatcut::mesh::split_at_texture_seams(&welded).unwrap_or(welded);
        let (split, _) = flatcut::mesh::split_non_manifold(&charts);
        let _ = flatcut::mesh::validate(&split);
    }
});
