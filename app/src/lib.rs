//! The `footprint` application: everything around the transport that a user runs. The
//! transport itself (passes, maps, the path loop, the integrators, `auto`) is the
//! `footprint-integrators` crate; the scene, BSDFs, maps and samplers are the core
//! `footprint` crate.
//!
//! * [`compare`]: equal-time comparisons, error against time, parameter sweeps, the report;
//! * [`merge`]: the image of one run from its shards' images;
//! * [`maps_file`]: saved maps (the passes' particles), versioned and checksummed;
//! * [`map_picture`]: pictures of the maps (a density estimate per pixel, log scale, legend);
//! * [`scene_hash`]: the scene's content hash (references, saved maps, shards).

pub mod compare;
pub mod map_picture;
pub mod maps_file;
pub mod merge;
pub mod scene_hash;
