//! The `footprint` application: everything around the transport that a user runs. The
//! transport itself (passes, maps, the path loop, the integrators, `auto`) is the
//! `footprint-integrators` crate; the scene, BSDFs, maps and samplers are the core
//! `footprint` crate.
//!
//! * [`cli`]: the command line (clap), the global flags and the exit codes;
//! * [`commands`]: one file a command (`render`, `maps`, `compare`, `merge`, `metrics`,
//!   `export`, `bench`): its flags and what it runs;
//! * [`args`]: flags several commands share, the settings flags from the schema;
//! * [`exr_header`]: what a rendered EXR records;
//! * [`bench`]: the speed measurements of `footprint bench`; [`ray_bench`]: its rays per
//!   second by kind on each ray tracer (`--rays`);
//! * [`compare`]: equal-time comparisons, error against time, parameter sweeps, the report;
//! * [`merge`]: the image of one run from its shards' images;
//! * [`maps_file`]: saved maps (the passes' particles), versioned and checksummed;
//! * [`map_picture`]: pictures of the maps (a density estimate per pixel, log scale, legend);
//! * [`scene_hash`]: the scene's content hash (references, saved maps, shards);
//! * [`fuzz`]: the readers' fuzz harnesses (`fuzz/`, `tests/fuzz_corpus.rs`).

pub mod args;
pub mod bench;
pub mod cli;
pub mod commands;
pub mod compare;
pub mod exr_header;
pub mod fuzz;
pub mod map_picture;
pub mod maps_file;
pub mod merge;
pub mod ray_bench;
pub mod scene_hash;
