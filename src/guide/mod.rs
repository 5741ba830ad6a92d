//! Guiding: choosing the next direction of a path from particles that the *other* kind of
//! path left behind (Hey & Purgathofer 2001; `docs/method.md`).
//!
//! The design is symmetric. A light pass fills a **photon map** (flux `Φ_p`) that guides
//! view paths (path tracing); a view pass fills an **importance map** (importance `W_p`,
//! per channel) that guides light paths (light tracing). Both maps are one data structure
//! ([`particle_map`]), and one sampler ([`sampler::GuidedSampler`]) serves both directions:
//! only the map it reads differs.
//!
//! * [`particle_map`]: the particles, a kd-tree and the k-nearest query (§2.1).
//! * [`Guide`] (`distribution.rs`): the extension point. A guide turns the particles
//!   gathered around a point into a distribution of directions ([`GuideDistribution`]),
//!   whose channels a [`ChannelMix`] (`channel_mix.rs`) mixes. Three are registered in
//!   [`GUIDES`] (`registry.rs`): BSDF sampling alone, the classic grid of Jensen 1995
//!   ([`grid`]) and the paper's footprints ([`footprint`]), which builds on the paper's
//!   tangent-plane grid ([`tangent_grid`]).
//! * [`cache`]: the guide cache. Distributions are prepared once per region of space and
//!   normal direction, where the other pass's paths scatter, and shared by every
//!   scattering event in the region; the paper's per-event preparation stays available.
//! * [`sampler`]: what the integrators call at a scattering point: `prepare`, `sample`,
//!   `pdf`, mixing the guide with BSDF sampling (`p_BSDF`) and falling back to the BSDF
//!   where particles cannot guide; [`guides_at`] says at which surfaces they can.
//! * [`selection`]: the probability `p_BSDF` of sampling the BSDF, learned per cached
//!   region from the render's own paths.
//! * [`table`]: a cached region's density tabulated for the combined image's MIS weights.
//!
//! Adding a guide: write `src/guide/NAME.rs` with a unit struct implementing [`Guide`] and
//! a type implementing [`GuideDistribution`], declare the module below and add the struct
//! to [`GUIDES`] in `registry.rs`. The command line, scene files, `compare` and the EXR
//! header take its name from there.

pub mod cache;
mod channel_mix;
mod distribution;
pub mod footprint;
pub mod grid;
pub mod particle_map;
mod registry;
pub mod sampler;
pub mod selection;
pub mod table;
pub mod tangent_grid;

pub use channel_mix::ChannelMix;
pub use distribution::{Guide, GuideDistribution, GuideParticle};
pub use registry::{BsdfOnly, GUIDES, find_guide, guide_names};
pub use sampler::{guides_at, guides_at_bsdf};
