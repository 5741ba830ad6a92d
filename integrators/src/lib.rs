//! Integrators of footprint and the driver that runs them over the film.
//!
//! * [`integrator`]: the `Integrator` trait and its registry: path tracing, light tracing,
//!   and the combined image;
//! * [`auto`]: the method chosen by a short pilot;
//! * [`walk`]: the one path loop (vertex, Russian roulette, spawn) that the integrators and
//!   both particle passes share;
//! * [`emit`]: where light paths start (light choice, guided emission at area lights);
//! * [`mis`]: the combined image's weights, kept as running quantities per subpath;
//! * [`passes`]: the light pass (photon map) and the view pass (importance map);
//! * [`maps`]: building the maps and guide caches a method needs;
//! * [`map_picture`]: pictures of the maps (a density estimate per pixel, log scale, legend);
//! * [`maps_file`]: saved maps (the passes' particles), versioned and checksummed;
//! * [`merge`]: the image of one run from its shards' images;
//! * [`method`]: a method (integrator x guide), resolved from names in one place;
//! * [`render`]: passes, threads, time budgets, progress, and the run summary;
//! * [`scene_hash`]: the scene's content hash (references, saved maps, shards);
//! * [`shard`]: which passes a render draws (shard `i` of `N`);
//! * [`skips`]: what a scene's absent effects let a render skip, and the counters;
//! * [`compare`]: equal-time comparisons, error against time, parameter sweeps.

pub mod auto;
pub mod compare;
pub mod emit;
pub mod integrator;
pub mod map_picture;
pub mod maps;
pub mod maps_file;
pub mod merge;
pub mod method;
pub mod mis;
pub mod moments;
pub mod passes;
pub mod render;
pub mod scene_hash;
pub mod shard;
pub mod skips;
pub mod target;
pub mod walk;
pub mod window;

pub use method::Method;
pub use render::{
    RenderOptions, RenderResult, StopRule, guidance, render, render_guided, render_prepared,
    render_with,
};
pub use shard::PassSelection;
