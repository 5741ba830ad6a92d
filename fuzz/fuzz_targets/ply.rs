//! Fuzz target: `footprint_app::fuzz::ply` (docs/testing.md, "Fuzzing").
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = footprint_app::fuzz::ply(data);
});
