//! The two particle passes (Hey & Purgathofer 2001, §2.1; docs/method.md, "Symmetry"):
//!
//! * the **light pass** emits photons from the lights in proportion to power (area lights
//!   uniformly in area and cosine-weighted in direction, or guided by an importance map,
//!   [`crate::emit`]; spot lights in their cone in proportion to the falloff, point lights
//!   uniformly; the directional light and the environment from the scene's bounding disk,
//!   along the light's direction or the environment's sampled one) and traces them in
//!   importance mode; each carries flux `Φ_p`;
//! * the **view pass** shoots importons from the camera through the image, uniformly in
//!   raster position, which distributes them like the camera's importance `W_e` (the first
//!   segment's weight `W_e cos θ / pdf` is exactly 1, from a pinhole or from a point sampled
//!   on a thin lens), and traces them in
//!   radiance mode; each carries importance `W_p` per channel, which starts equal in all
//!   channels and is multiplied by the colours the path passes through.
//!
//! Both are walks of [`crate::walk`] (the integrators' path loop and Russian roulette rule)
//! with a visitor that stores a particle at every hit on a diffuse or soft glossy surface
//! (where the guides use them, [`guides_at`]), never on mirrors, glass or strongly glossy
//! surfaces. Each path starts with weight `1/N` of the whole (`N` = paths shot), so a map's
//! weights sum to the power (or importance) arriving at stored surfaces. Directions come
//! from the pass's sampler: the BSDF's own sampling unless a map of the other pass guides
//! it.
//!
//! Besides its particles, a pass reports where its paths asked for a direction at a
//! guiding surface (its particles' places, and for the light pass the points where paths
//! left area lights): the seeds of the other map's guide cache.
//!
//! Parallel with rayon; paths are traced in fixed chunks with per-path random streams and
//! concatenated in chunk order, so a map is reproducible from its seed. Past its share of
//! the memory budget a pass keeps an even sample of its particles ([`thinning`]).

mod light_pass;
mod pass;
mod storing;
pub mod target;
pub mod thinning;
mod view_pass;

pub use light_pass::{grow_light_pass, light_pass};
pub use pass::{PassOutput, PassSettings, PassStats};
pub use storing::CHUNK_PATHS;
pub use target::ImportanceTarget;
pub use view_pass::{SEED_PASS_SHARE, seed_paths, view_pass, view_pass_seeding};
