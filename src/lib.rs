//! footprint: a physically based CPU renderer that guides both light paths and view paths
//! with particle maps (Hey & Purgathofer 2001, "Importance Sampling with Hemispherical
//! Particle Footprints"; the method as this project reads it, errata included, is
//! `docs/method.md`).
//!
//! This crate is the core library, a folder per concept:
//! * [`scene`]: geometry, the BVH, the camera, lights, textures, the effect analysis, and
//!   the TOML/OBJ and Mitsuba 3 XML loaders;
//! * [`bsdf`]: materials and their lobes, Fresnel terms, microfacet distributions, plastic;
//! * [`guide`]: the particle maps, the guides (BSDF, grid, footprints), the guide cache and
//!   the direction sampler both kinds of paths use;
//! * [`features`]: the effects a path loop is compiled for, `const` flags that compile an
//!   absent effect out of the path loop, the BSDF and the direction sampler;
//! * [`film`]: the film, pixel filters and image files;
//! * [`settings`]: what a scene file's `[render]`, `[maps]` and `[guide]` tables hold;
//! * [`schema`]: the settings set by name (scene file keys, flags, sweeps, headers, keys);
//! * foundations: [`keyword`] (values named by keywords), [`math`], [`sampling`] (warps and discrete distributions), [`rng`],
//!   [`heap`] (a counting allocator), [`memory`] (the maps' memory budget), [`error`], [`atomic_file`] (whole-or-nothing writes).
//!
//! The transport (passes, maps, the path loop, the integrators, `auto`) is the
//! `footprint-integrators` crate (`integrators/`); the command line is `footprint-app`
//! (`app/`).

pub mod atomic_file;
pub mod bsdf;
pub mod distribution_2d;
pub mod error;
pub mod features;
pub mod film;
pub mod guide;
pub mod heap;
pub mod keyword;
pub mod math;
pub mod memory;
pub mod rng;
pub mod sampling;
pub mod scene;
pub mod schema;
pub mod settings;

pub use error::{Error, Result};
pub use math::Rgb;
