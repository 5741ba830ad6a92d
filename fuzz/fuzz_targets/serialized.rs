//! Fuzz target: `footprint_app::fuzz::serialized` (docs/testing.md, "Fuzzing").
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = footprint_app::fuzz::serialized(data);
});
