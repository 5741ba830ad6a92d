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
//! * [`method`]: a method (integrator x guide), resolved from names in one place;
//! * [`render`]: passes, threads, time budgets, progress, and the run summary;
//! * [`shard`]: which passes a render draws (shard `i` of `N`);
//! * [`counts`]: counters of a render's paths (guided events, fallbacks, hits, escapes);
//! * [`skips`]: what a scene's absent effects let a render skip, and the counters.

pub mod auto;
pub mod counts;
pub mod emit;
pub mod integrator;
pub mod maps;
pub mod method;
pub mod mis;
pub mod moments;
pub mod passes;
pub mod render;
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
