//! The transport of footprint, in the paper's symmetric design (Hey & Purgathofer 2001,
//! §2; `docs/architecture.md`):
//!
//! ```text
//!   view pass  (passes/view_pass.rs)  -> importance map -> guides light paths (lt)
//!   light pass (passes/light_pass.rs) -> photon map     -> guides camera paths (pt)
//!   both directions, weighed by MIS                     -> the combined image
//! ```
//!
//! * [`passes`]: the view pass and the light pass, and the view pass's relative importance
//!   target;
//! * [`maps`]: the maps and guide caches a method needs, built from the passes (one
//!   footprint sampler, `footprint::guide`, reads either map);
//! * [`walk`]: the one path loop (vertex, Russian roulette, splitting, spawn) that the
//!   integrators and both passes share; [`emit`]: where light paths start;
//! * [`integrator`]: the `Integrator` trait and its registry: path tracing, light tracing,
//!   and the combined image; [`mis`]: its weights as running quantities per subpath;
//!   [`moments`]: the second-moment layers `auto` reads; [`learning`]: what a camera or
//!   light path teaches the learned `p_BSDF`;
//! * [`render`]: maps, passes over the film, threads, time budgets; [`shard`]: which passes
//!   a render draws; [`counts`] and [`skips`]: what it counted and what the scene's absent
//!   effects let it skip;
//! * [`method`]: a method (integrator x guide) resolved from names;
//! * [`auto`]: one layer up, the method chosen by a short pilot, then rendered;
//! * [`window`]: per-pixel means over windows sized by their noise (the target and `auto`).

pub mod auto;
pub mod counts;
pub mod emit;
pub mod integrator;
pub mod learning;
pub mod maps;
pub mod method;
pub mod mis;
pub mod moments;
pub mod passes;
pub mod render;
pub mod shard;
pub mod skips;
pub mod walk;
pub mod window;

pub use method::Method;
pub use render::{
    RenderOptions, RenderResult, StopRule, guidance, render, render_guided, render_prepared,
    render_with,
};
pub use shard::PassSelection;
